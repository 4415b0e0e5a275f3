//! The discretised problem: for each contact its domain and grids ([`line::domain`],
//! [`point::domain`]), the deformation kernel and its FFT product, and the discrete Reynolds
//! operator with the film equation. The tests of both contacts share random fields and product
//! checks (`testing`).

pub mod line;
pub mod point;
#[cfg(test)]
pub(crate) mod testing;
