//! The discretised problem: for each contact its domain and grids ([`line::domain`],
//! [`point::domain`]), the deformation kernel and its FFT product, and the discrete Reynolds
//! operator with the film equation.

pub mod grid;
pub mod line;
pub mod point;
