//! The discretised problem: for each contact its domain and grids ([`line::domain`],
//! [`point::domain`]), the deformation kernel and its FFT product, and the discrete Reynolds
//! operator with the film equation. What the two contacts share is written once: the lubricant's
//! coefficients ([`physics`]), the Reynolds stencil along a grid direction and its derivatives
//! ([`stencil`]), row-by-row work on the rayon pool ([`rows`]), and, for the tests, random fields
//! and product checks (`testing`).

pub mod grid;
pub mod level;
pub mod line;
pub mod physics;
pub mod point;
pub mod roughness;
pub mod rows;
pub mod stencil;
#[cfg(test)]
pub(crate) mod testing;
