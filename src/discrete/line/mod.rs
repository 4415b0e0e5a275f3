//! Line contacts: domain rule, the 1D log kernel, and the discrete operator.

pub mod domain;
pub mod kernel;
pub mod operator;
