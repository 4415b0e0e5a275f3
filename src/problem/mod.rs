//! The discretised problem: domain and grids, deformation kernels, and the discrete operators.

pub mod domain;
pub mod kernel1d;
pub mod kernel2d;
pub mod line;
pub mod point;
pub mod point_domain;
