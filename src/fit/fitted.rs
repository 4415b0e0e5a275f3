//! What a fit returns: each film's fitted law with its parameters and their uncertainties, and
//! its error statistics against the data.

pub use crate::fit::blend::Blend;
use crate::fit::corner::{Corner, CornerChoice};
use crate::fit::correction::Correction;
use crate::fit::dataset::FitPoint;
use crate::fit::heldout::{CaseError, HeldOut};
use crate::fit::kriging::{Kriging, KrigingChoice};
use crate::fit::side::{SideChoice, SideLobe};
use crate::fit::stats::{ErrStats, RegionStats, TargetRange};
use crate::solve::film::Film;
use serde::{Deserialize, Serialize};

/// A fitted parameter with its one-sigma uncertainty (0: held fixed).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Param {
    /// The parameter's name ([`PARAM_NAMES`] or [`POINT_PARAM_NAMES`]; `ln_` marks a constant
    /// held as its logarithm).
    ///
    /// [`PARAM_NAMES`]: crate::fit::model::PARAM_NAMES
    /// [`POINT_PARAM_NAMES`]: crate::fit::point_model::POINT_PARAM_NAMES
    pub name: String,
    /// The value: fitted, or where it was held (the start, or an earlier stage's fit).
    pub value: f64,
    /// One-sigma uncertainty from the least-squares covariance (0: held in the final fit; NaN:
    /// not identified, J^T J singular).
    #[serde(deserialize_with = "crate::fit::stats::null_as_nan")]
    pub sigma: f64,
}

/// A fitted formula: the blend times its interior correction
/// ([`crate::fit::correction`]), H = H_blend exp(correction), for the point minimum film times
/// the side-lobe factor ([`crate::fit::side`]) when the data carry the centre line's minimum.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FittedModel {
    /// The blended-asymptote law (its asymptotes are the formula's).
    #[serde(flatten)]
    pub blend: Blend,
    /// The interior correction (no terms: none; fit reports before it had none).
    #[serde(default)]
    pub correction: Correction,
    /// The side-lobe factor of the point H_min law (None: the law is the corrected blend; then
    /// the blend was fitted to H_min itself).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub side: Option<SideLobe>,
    /// The H_c law through its corner ([`crate::fit::corner`]; None: the corrected blend). When
    /// present it is the formula on `blend` in place of `correction` (then the smooth H_c law's
    /// correction, kept for the report).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub corner: Option<Corner>,
    /// The kriging residual ([`crate::fit::kriging`]) on the corrected blend or, with a corner,
    /// on the corner law (None: none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kriging: Option<Kriging>,
}

impl FittedModel {
    /// The fitted film H at (M, L, D) in Moes units; a line law ignores D.
    pub fn eval(&self, m: f64, l: f64, d: f64) -> f64 {
        let b = &self.blend;
        let (blend, asym) = (b.eval(m, l, d), b.asymptotes(m, l, d));
        let h = match &self.corner {
            Some(c) => c.apply(blend, asym, d),
            None => self.correction.apply(blend, asym, d),
        };
        let h = self
            .kriging
            .as_ref()
            .map_or(h, |k| h * k.log_factor(asym, m, l, d).exp());
        self.side.as_ref().map_or(h, |s| h * s.factor(m, l, d))
    }

    /// The relative errors formula / data - 1 of `film` at the cases of `pts` that carry it,
    /// with the data's film and error estimate (a check set: cases the formula was not fitted
    /// to).
    pub fn errors_on(&self, pts: &[FitPoint], film: Film) -> Vec<CaseError> {
        pts.iter()
            .filter_map(|p| {
                let h = p.film(film)?;
                Some(CaseError {
                    m: p.m,
                    l: p.l,
                    d: p.dd(),
                    h: Some(h),
                    error: self.eval(p.m, p.l, p.dd()) / h - 1.0,
                    estimate: p.estimate(film),
                })
            })
            .collect()
    }
}

/// The fit of one quantity.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct QuantityFit {
    /// The film fitted: "H_c", "H_pm" or "H_min".
    pub quantity: String,
    /// The fitted law.
    pub model: FittedModel,
    /// Every parameter of the law's vector, in vector order, fitted or held (the line law's
    /// fixed c_RI is not among them; it is in `model`).
    pub params: Vec<Param>,
    /// RMS of the log residuals ln(H_fit) - ln(H_data) over the cases fitted.
    pub rms_log: f64,
    /// Whether Levenberg-Marquardt ended successfully.
    pub converged: bool,
    /// Relative errors fit/data - 1 over every case that carries the film.
    pub overall: ErrStats,
    /// The same errors per region of the (M, L) plane (M decades x L bands; empty regions left
    /// out).
    pub regions: Vec<RegionStats>,
    /// The same errors per ellipticity D, in increasing D (point contacts; empty for line
    /// contacts).
    pub per_d: Vec<RegionStats>,
    /// The M range over which the fit meets the 2 % target ([`MAX_ERROR_TARGET`]); None when no
    /// M value of the data has all its cases within it.
    ///
    /// [`MAX_ERROR_TARGET`]: crate::report::MAX_ERROR_TARGET
    #[serde(default)]
    pub within_target: Option<TargetRange>,
    /// Held-out (cross-validated) errors of the formula and how the correction's size was
    /// chosen (None: not enough cases, or a fold's blend fit failed).
    #[serde(default)]
    pub heldout: Option<HeldOut>,
    /// The formula's errors on the check set: cases of separate datasets (`ehlmap fit --check`,
    /// e.g. the midpoints between the data), never fitted; with the data's error estimates.
    #[serde(default)]
    pub check: Vec<CaseError>,
    /// The held-out choice of the side-lobe factor (point H_min fitted through the centre
    /// line's minimum; None otherwise).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub side: Option<SideChoice>,
    /// The held-out choice of the corner law (H_c with a corner; None otherwise).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub corner: Option<CornerChoice>,
    /// The held-out choice of the kriging residual (None: not offered, or not kept).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kriging: Option<KrigingChoice>,
}
