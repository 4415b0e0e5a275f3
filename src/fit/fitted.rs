//! What a fit returns: each film's fitted law with its parameters and their uncertainties, and
//! its error statistics against the data.

use crate::fit::model::LineModel;
use crate::fit::point_model::PointModel;
use crate::fit::stats::{ErrStats, RegionStats, TargetRange};
use serde::{Deserialize, Serialize};

/// A fitted parameter with its one-sigma uncertainty (0: held fixed).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Param {
    pub name: String,
    pub value: f64,
    pub sigma: f64,
}

/// A fitted model of either contact.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum FittedModel {
    Line(LineModel),
    Point(PointModel),
}

impl FittedModel {
    pub fn eval(&self, m: f64, l: f64, d: f64) -> f64 {
        match self {
            FittedModel::Line(x) => x.eval(m, l),
            FittedModel::Point(x) => x.eval(m, l, d),
        }
    }
}

/// The fit of one quantity.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct QuantityFit {
    pub quantity: String,
    pub model: FittedModel,
    pub params: Vec<Param>,
    pub rms_log: f64,
    pub converged: bool,
    pub overall: ErrStats,
    pub regions: Vec<RegionStats>,
    /// Per D (point contacts).
    pub per_d: Vec<RegionStats>,
    /// The M range over which the fit meets the 2 % target ([`MAX_ERROR_TARGET`]); None when no
    /// M value of the data has all its cases within it.
    #[serde(default)]
    pub within_target: Option<TargetRange>,
}
