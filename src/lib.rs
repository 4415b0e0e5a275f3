//! ehlmap: steady isothermal elastohydrodynamic lubrication (EHL) by full multigrid.

// Stencil and kernel loops index several arrays by node number; iterator chains would hide that.
#![allow(clippy::needless_range_loop)]

pub mod bench;
pub mod cases;
pub mod discrete;
pub mod fit;
pub mod limits;
pub mod model;
pub mod render;
pub mod report;
pub mod solve;
pub mod store;
pub mod strategy;
pub mod sweep;
