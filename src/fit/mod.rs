//! Fitting Moes/NVM-style film-thickness formulas to sweep results, and checking them.
//!
//! [`model`] (line, Moes 1992 form) and [`point_model`] (point, NVM 1994 form, [`approach`] its
//! elastic-isoviscous approach factor) define the
//! blended-asymptote formulas ([`blend`]: either), [`lsq`] fits either in log space by Levenberg-Marquardt with
//! parameter uncertainties, [`correction`] is the interior correction that vanishes in every
//! asymptotic limit and [`heldout`] chooses its size by cross-validation ([`support`]: where its data are, beyond which a point correction fades), [`kriging`] is the residual's Gaussian-process
//! posterior mean offered on top of it, [`side`] is the
//! side-lobe factor of the point minimum film, [`corner`] the corner of the central film where it meets the
//! film at the pressure maximum, [`stats`] turns formula-vs-data errors into tables (overall and per
//! region of the (M, L) plane, and the M range that meets a target), [`dataset`] reads the
//! sweep rows a fit uses, [`fitted`] holds what a fit returns and [`error`] why a fit failed.

pub mod approach;
pub mod blend;
pub mod corner;
pub mod correction;
pub mod dataset;
pub mod error;
pub mod fitted;
pub mod heldout;
pub mod kriging;
pub mod lsq;
pub mod model;
pub mod point_model;
pub mod side;
pub mod stats;
pub mod support;
