//! ehlmap: steady isothermal elastohydrodynamic lubrication (EHL) of line contacts and of point
//! contacts of any ellipticity, by full multigrid, in Moes' parameters (M, L) and D = Rx/Ry.
//!
//! One [`solve()`] takes a [`Case`] (a [`LineCase`] or a [`PointCase`]) and [`SolveParams`] and
//! returns a [`Solution`]: the films and pressures in [`Outputs`], with a [`Status`], a reason
//! (numerical failure is a result, never a panic) and the error estimates of H_c and H_min. By
//! default the grid is refined until they meet 1 %; a fixed `grid` is estimated against its half
//! grid.
//!
//! ```
//! use ehlmap::{solve, Case, LineCase, SolveParams, Status};
//!
//! let case = Case::Line(LineCase::new(20.0, 10.0).expect("valid M, L"));
//! let s = solve(&case, &SolveParams::default());
//! assert_eq!(s.outputs.status, Status::Converged);
//! assert_eq!(s.outputs.accuracy_met, Some(true));
//! // Moes 1992 gives H_c = 5.10 for M = 20, L = 10; the grid-converged solver 5.2757.
//! let err = s.outputs.h_c_err.expect("an estimate");
//! assert!(err <= 0.01 && (s.outputs.h_c / 5.2757 - 1.0).abs() <= err);
//! ```
//!
//! The modules follow the data flow, each importing only from those before it:
//! [`model`] (the case, lubricant, Hertz, published formulas, SI case files) ->
//! [`discrete`] (domains, kernels, discrete operators) -> [`mod@solve`] (multigrid, fallback
//! ladder, Newton; line and point twins behind one interface) -> [`strategy`] (accuracy targets,
//! model selection, warm starts, the one [`solve()`]) -> [`cases`] (dimensional cases) ->
//! [`store`] (Parquet) and [`sweep`] (spec, plan, executor) -> [`limits`] (the asymptote limit
//! solves) -> [`fit`] (fitted film formulas) -> [`report`] (report.md, fit.json) -> [`render`]
//! (charts and pictures) -> [`mod@bench`] (speed and stability). The command line is the binary's
//! own `cli` module.

// Stencil and kernel loops index several arrays by node number; iterator chains would hide that.
#![allow(clippy::needless_range_loop)]
#![warn(missing_docs)]

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

pub use model::case::{Case, Contact, Elasticity, LineCase, Models, ParamError, PointCase};
pub use model::lubricant::{Density, Viscosity};
pub use solve::params::CycleType;
pub use solve::params::Method;
pub use solve::solution::{ModelUsed, Outputs, Solution};
pub use solve::{CycleEvent, CycleRecord, Observer, SolveInfo, Status};
pub use strategy::solve_case::{solve, SolveParams};

/// The README's Rust snippets compile and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
