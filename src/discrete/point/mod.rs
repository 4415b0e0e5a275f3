//! Point contacts of any ellipticity: domain rule, the 2D 1/r kernel, the far field and the
//! discrete operator, and a level's rows as a level of their own (strips, for parallel rows).

pub mod domain;
pub mod far_field;
pub mod kernel;
pub mod operator;
pub mod strip;
