//! Point contacts of any ellipticity: domain rule, the 2D 1/r kernel, the far field and the
//! discrete operator, and bands of a level's rows borrowed in place (strips, for the smoother and
//! its parallel rows).

pub mod domain;
pub mod far_field;
pub mod kernel;
pub mod operator;
pub mod strip;
