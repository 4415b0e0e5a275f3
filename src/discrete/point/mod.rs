//! Point contacts of any ellipticity: domain rule, the 2D 1/r kernel, the far field and the
//! discrete operator.

pub mod domain;
pub mod far_field;
pub mod kernel;
pub mod operator;
