//! Fitting a Moes-style film-thickness formula to sweep results, and checking it.
//!
//! [`model`] defines the blended-asymptote formula, [`lsq`] fits it in log space by
//! Levenberg-Marquardt with parameter uncertainties, [`stats`] turns formula-vs-data errors into
//! tables (overall and per region of the (M, L) plane).

pub mod charts;
pub mod cli;
pub mod dataset;
pub mod lsq;
pub mod model;
pub mod report;
pub mod stats;
