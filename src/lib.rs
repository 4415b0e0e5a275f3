//! ehlmap: steady isothermal elastohydrodynamic lubrication (EHL) by full multigrid.
//!
//! The module tree follows the data flow: parameters and lubricant models ([`params`],
//! [`lubricant`]) -> the discretised problem ([`problem`]) -> solvers ([`solver`]) -> what a solve
//! reports ([`solution`]); [`select`] picks the cheapest adequate model ([`slender`]: a line contact for slender ellipses) -> storage ([`io`]); [`formulas`] holds the published film formulas the
//! results are compared with.

// Stencil and kernel loops index several arrays by node number; iterator chains would hide that.
#![allow(clippy::needless_range_loop)]

pub mod accuracy;
pub mod bench;
pub mod case;
pub mod cli;
pub mod fit;
pub mod formulas;
pub mod hertz;
pub mod io;
pub mod lubricant;
pub mod oils;
pub mod params;
pub mod pictures;
pub mod problem;
pub mod regimes;
pub mod select;
pub mod slender;
pub mod solution;
pub mod solver;
pub mod sweep;
