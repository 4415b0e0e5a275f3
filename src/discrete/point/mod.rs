//! Point contacts of any ellipticity: domain rule, the 2D 1/r kernel, and the discrete operator.

pub mod domain;
pub mod kernel;
pub mod operator;
