//! What a line solve reports (PHYSICS.md section 7), in Moes units unless named otherwise.
//!
//! * `H_c`: film at X = 0. `H_c_pmax`: film at the global pressure maximum (dP/dX = 0 there, so
//!   for an incompressible lubricant it is the flux thickness, exactly 3/M in the rigid-isoviscous
//!   limit). `H_min`, `X_min`: the minimum film and where it is (parabolic refinement between
//!   nodes). `P_max`: the maximum pressure (P = p/p_h).
//! * `spike`: the most downstream local pressure maximum above 5 % of P_max when there are two
//!   or more (position X and height P), else none.
//! * `H0`: the film constant (Moes units). `f`: rolling traction F_r/w with
//!   F_r = integral (h/2) dp/dx dx, reported as f R/b = integral (H/2) P' dX / integral P dX
//!   (Hertzian units); multiply by b/R = sqrt(8 W'/pi) for the dimensional coefficient, which
//!   (M, L) alone do not fix.
//! * `load_error`: (h sum P - pi/2)/(pi/2) on the finest grid.

use crate::model::error::ParamError;
use crate::solve::{SolveInfo, Status};
use serde::{Deserialize, Serialize};

/// The model that answered a case, cheapest first ([`crate::strategy::select`] picks it).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ModelUsed {
    /// A film formula fitted to solver data, where its held-out error map allows
    /// ([`crate::strategy::formula`]).
    Formula,
    /// Martin's closed form (rigid isoviscous line contact).
    ClosedForm,
    /// A rigid isoviscous solve.
    RigidIsoviscous,
    /// A rigid (piezoviscous) solve.
    Rigid,
    /// An elastic isoviscous solve.
    Isoviscous,
    /// A slender ellipse answered by the equivalent line contact.
    SlenderLine,
    #[default]
    /// The full model.
    Full,
}

impl ModelUsed {
    /// Every model, cheapest first.
    pub const ALL: [ModelUsed; 7] = [
        ModelUsed::Formula,
        ModelUsed::ClosedForm,
        ModelUsed::RigidIsoviscous,
        ModelUsed::Rigid,
        ModelUsed::Isoviscous,
        ModelUsed::SlenderLine,
        ModelUsed::Full,
    ];

    /// The name stored in JSON and Parquet.
    pub fn as_str(&self) -> &'static str {
        match self {
            ModelUsed::Formula => "formula",
            ModelUsed::ClosedForm => "closed-form",
            ModelUsed::RigidIsoviscous => "rigid-isoviscous",
            ModelUsed::Rigid => "rigid",
            ModelUsed::Isoviscous => "isoviscous",
            ModelUsed::SlenderLine => "slender-line",
            ModelUsed::Full => "full",
        }
    }
}

impl std::fmt::Display for ModelUsed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl std::str::FromStr for ModelUsed {
    type Err = ParamError;
    fn from_str(s: &str) -> Result<Self, ParamError> {
        ModelUsed::ALL
            .into_iter()
            .find(|m| m.as_str() == s)
            .ok_or_else(|| ParamError::Unknown {
                what: "model",
                name: s.to_string(),
                expected: "formula, closed-form, rigid-isoviscous, rigid, isoviscous, slender-line or full",
            })
    }
}

impl PartialEq<&str> for ModelUsed {
    fn eq(&self, other: &&str) -> bool {
        self.as_str() == *other
    }
}

/// A secondary pressure maximum near the outlet.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Spike {
    /// Where the spike is (X, Hertzian units).
    pub x: f64,
    /// Its height P = p/p_h.
    pub p: f64,
}

/// The outputs of one solve (line or point), with the JSON field names of the CLI.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Outputs {
    #[serde(rename = "H_c")]
    /// The film at X = 0 (Y = 0), Moes units.
    pub h_c: f64,
    #[serde(rename = "H_c_pmax")]
    /// The film at the global pressure maximum, Moes units.
    pub h_c_pmax: f64,
    #[serde(rename = "H_min")]
    /// The minimum film, Moes units.
    pub h_min: f64,
    #[serde(rename = "X_min")]
    /// Where the minimum film is along the rolling direction (X = x/b).
    pub x_min: f64,
    /// Point contacts: where the minimum film is across the rolling direction (Y = y/b).
    #[serde(rename = "Y_min", skip_serializing_if = "Option::is_none", default)]
    pub y_min: Option<f64>,
    /// Point contacts: the minimum film on the centre line Y = 0 (absent for line contacts).
    #[serde(flatten, default)]
    pub centre_line: Option<CentreLine>,
    /// Point contacts: the ellipticity parameter D = Rx/Ry.
    #[serde(rename = "D", skip_serializing_if = "Option::is_none", default)]
    pub d: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none", default)]
    /// Point contacts: the Hertz ratio k = a/b.
    pub k: Option<f64>,
    #[serde(rename = "P_max")]
    /// The maximum pressure P = p/p_h.
    pub p_max: f64,
    /// The outlet pressure spike, when there is one.
    pub spike: Option<Spike>,
    #[serde(rename = "H0")]
    /// The film constant H0, Moes units.
    pub h0: f64,
    /// The rolling traction coefficient f R/b (module docs).
    pub f: f64,
    /// The relative load error on the finest grid.
    pub load_error: f64,
    /// How the solve ended.
    pub status: Status,
    /// Why, in words.
    pub reason: String,
    /// Points of the finest grid (per direction for point contacts; 0 for a closed form).
    pub grid: usize,
    /// Levels of the multigrid hierarchy.
    pub levels: usize,
    /// Refinement level of the finest grid: log2 of its intervals over those of the smallest
    /// grid a solve accepts (32 line intervals, 16 point intervals per direction), so 257 / 1025
    /// / 4097 line points are levels 3 / 5 / 7 and 33^2 / 65^2 / 129^2 point nodes 1 / 2 / 3;
    /// none for a closed-form answer.
    pub level: Option<usize>,
    /// The model that answered: full unless a simpler one was selected.
    #[serde(default)]
    pub model_used: ModelUsed,
    /// Relaxation sweeps in finest-grid equivalents, all attempts and grids included.
    pub work_units: f64,
    /// Wall time (s), all attempts and grids included.
    pub wall_s: f64,
    /// The estimated relative algebraic error of H_c and H_min (the larger) left on the finest
    /// grid when the cycles stopped (fast convergence; none under tight convergence, where it
    /// is far below the tolerances, and for a closed form).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub algebraic_error: Option<f64>,
    /// The estimated relative error of H_c: the discretisation error by Richardson between
    /// this grid and the one with half the intervals, plus the algebraic errors both solves
    /// left, plus what a simplified model neglects or the point domain's truncation; none when
    /// there is no estimate (`--no-estimate`, or a coarser solve did not converge).
    #[serde(rename = "H_c_err", default)]
    pub h_c_err: Option<f64>,
    /// The same for H_c_pmax, the film at the pressure maximum. Reported, not targeted: the
    /// accuracy ladder refines until H_c and H_min meet the target, and `error_estimate` leaves
    /// this one out; where the pressure maximum is the outlet spike (high L) the maximum and
    /// its film move with the grid and the estimate can be far above the others.
    #[serde(rename = "H_c_pmax_err", default)]
    pub h_c_pmax_err: Option<f64>,
    /// The same Richardson estimate for P_max (discretisation and algebraic parts only).
    /// Reported, not targeted. Large where the pressure maximum is a spike whose height is set
    /// by the grid (Barus viscosity at high L): the position of the maximum, and so H_c_pmax,
    /// is then the grid's, not the physics'.
    #[serde(rename = "P_max_err", default)]
    pub p_max_err: Option<f64>,
    /// The same for H_min.
    #[serde(rename = "H_min_err", default)]
    pub h_min_err: Option<f64>,
    /// The larger of `H_c_err` and `H_min_err`.
    #[serde(default)]
    pub error_estimate: Option<f64>,
    /// With an accuracy target: whether the estimate met it (none on a fixed grid).
    #[serde(default)]
    pub accuracy_met: Option<bool>,
    /// Rough surfaces: the mixed-lubrication outputs (absent for smooth ones).
    #[serde(flatten, default)]
    pub mixed: Option<MixedOutputs>,
}

/// Relative error estimates of the three films and of P_max of a solve (see
/// [`Outputs::h_c_err`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrorEstimates {
    /// Of H_c.
    pub h_c: f64,
    /// Of H_c_pmax (may be NaN where the film at the pressure maximum has no estimate).
    pub h_c_pmax: f64,
    /// Of H_min.
    pub h_min: f64,
    /// Of P_max (may be NaN).
    pub p_max: f64,
    /// Of the centre line's minimum film of a point contact (NaN where there is none).
    pub h_min_cl: f64,
}

impl Outputs {
    /// The outputs of an answer without a solve (closed form, fitted formula): the films
    /// [H_c, H_c_pmax, H_min], the model and the reason; converged, no grid and no cost,
    /// algebraic error 0, error estimates 0 (met); everything else NaN or none, for the caller to
    /// set where its answer gives it.
    pub fn without_solve(model_used: ModelUsed, films: [f64; 3], reason: String) -> Outputs {
        let [h_c, h_c_pmax, h_min] = films;
        Outputs {
            h_c,
            h_c_pmax,
            h_min,
            x_min: f64::NAN,
            y_min: None,
            centre_line: None,
            d: None,
            k: None,
            p_max: f64::NAN,
            spike: None,
            h0: f64::NAN,
            f: f64::NAN,
            load_error: f64::NAN,
            status: Status::Converged,
            reason,
            grid: 0,
            levels: 0,
            level: None,
            model_used,
            work_units: 0.0,
            wall_s: 0.0,
            algebraic_error: Some(0.0),
            h_c_err: Some(0.0),
            h_c_pmax_err: Some(0.0),
            p_max_err: None,
            h_min_err: Some(0.0),
            error_estimate: Some(0.0),
            accuracy_met: Some(true),
            mixed: None,
        }
    }

    /// Set the relative error estimates of the films and P_max; `error_estimate` is the larger
    /// of H_c's and H_min's. A non-finite H_c_pmax or P_max estimate is stored as none.
    pub fn set_errors(&mut self, e: ErrorEstimates) {
        self.h_c_err = Some(e.h_c);
        self.h_c_pmax_err = Some(e.h_c_pmax).filter(|v| v.is_finite());
        self.p_max_err = Some(e.p_max).filter(|v| v.is_finite());
        self.h_min_err = Some(e.h_min);
        self.error_estimate = Some(e.h_c.max(e.h_min));
        if let Some(cl) = &mut self.centre_line {
            cl.h_min_err = Some(e.h_min_cl).filter(|v| v.is_finite());
        }
    }

    /// Add `e` to every error estimate there is (a neglected effect, a truncation estimate).
    pub fn widen_errors(&mut self, e: f64) {
        for x in [
            &mut self.h_c_err,
            &mut self.h_c_pmax_err,
            &mut self.h_min_err,
            &mut self.error_estimate,
        ] {
            *x = x.map(|v| v + e);
        }
        if let Some(cl) = &mut self.centre_line {
            cl.h_min_err = cl.h_min_err.map(|v| v + e);
        }
    }
}

/// `v +- e` with `e = v rel` to two significant figures and `v` to the same decimal; `v` to six
/// decimals and "(no error estimate)" without `rel`.
pub fn with_error(v: f64, rel: Option<f64>) -> String {
    let e = rel
        .map(|r| (v * r).abs())
        .filter(|e| e.is_finite() && *e > 0.0);
    match e {
        Some(e) => {
            let decimals = (1 - e.log10().floor() as i32).clamp(0, 12) as usize;
            format!("{v:.decimals$} +- {e:.decimals$}")
        }
        None if rel == Some(0.0) => format!("{v:.6} (exact)"),
        None => format!("{v:.6} (no error estimate)"),
    }
}

/// log2((grid - 1) / base), rounded: the refinement level of a grid over `base` intervals.
pub fn grid_level(grid: usize, base: usize) -> usize {
    ((grid.saturating_sub(1) as f64 / base as f64).log2().round()).max(0.0) as usize
}

/// Pressure and film along X on the finest grid (X, P in Hertzian units, H in Moes units).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Profile {
    /// Node coordinates X (Hertzian units).
    pub x: Vec<f64>,
    /// The pressure P at the nodes.
    pub p: Vec<f64>,
    /// The film H at the nodes, Moes units.
    pub h: Vec<f64>,
    /// Rough surfaces: the asperity pressure p_a/p_h at the nodes.
    pub p_asperity: Option<Vec<f64>>,
}

/// A point contact's minimum film on the centre line Y = 0 (the exit constriction there), with
/// where it is and its error estimate. It is H_min where the minimum lies on the centre line;
/// where the side lobes are thinner (circular contacts from M of about 15) it is the second
/// branch of the minimum film.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CentreLine {
    /// The minimum film on Y = 0, Moes units (parabola-refined, as H_min).
    #[serde(rename = "H_min_cl")]
    pub h_min: f64,
    /// Where it is along the rolling direction (X = x/b).
    #[serde(rename = "X_min_cl")]
    pub x_min: f64,
    /// Its relative error estimate, as `H_min_err` (none without an estimate).
    #[serde(rename = "H_min_cl_err", default)]
    pub h_min_err: Option<f64>,
}

/// What a solve with rough surfaces reports besides the films (Moes units; module docs of
/// [`crate::solve::mixed`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MixedOutputs {
    /// Composite RMS roughness, Moes film units.
    pub sigma: f64,
    /// Roughness orientation gamma.
    pub gamma: f64,
    /// Slide-to-roll ratio (u1 - u2)/u_m.
    pub slide_roll: f64,
    /// The film parameter H_min/sigma.
    #[serde(rename = "Lambda")]
    pub lambda_min: f64,
    /// H_c/sigma.
    #[serde(rename = "Lambda_c")]
    pub lambda_c: f64,
    /// The share of the load the asperities carry.
    pub asperity_load_fraction: f64,
    /// The largest asperity pressure p_a/p_h.
    #[serde(rename = "P_asperity_max")]
    pub p_asperity_max: f64,
    /// Re-solves of the asperity load's fixed point (0: no asperity contact).
    pub mixed_iterations: usize,
    /// The same case with smooth surfaces: H_c (filled by the case-level solve).
    #[serde(rename = "H_c_smooth", default)]
    pub h_c_smooth: Option<f64>,
    /// The same case with smooth surfaces: H_min.
    #[serde(rename = "H_min_smooth", default)]
    pub h_min_smooth: Option<f64>,
}

/// Vertex of the parabola through (-1, a), (0, b), (1, c): offset in [-1, 1] and value.
pub(crate) fn parabola_vertex(a: f64, b: f64, c: f64) -> (f64, f64) {
    let den = a - 2.0 * b + c;
    if den.abs() < 1e-300 {
        return (0.0, b);
    }
    let t = (0.5 * (a - c) / den).clamp(-1.0, 1.0);
    (t, b - 0.25 * (a - c) * t)
}

/// Linear interpolation of `v` at fractional node position `i + t` (t in [-1, 1]).
fn interp(v: &[f64], i: usize, t: f64) -> f64 {
    if t >= 0.0 {
        v[i] + t * (v[(i + 1).min(v.len() - 1)] - v[i])
    } else {
        v[i] + t * (v[i] - v[i.saturating_sub(1)])
    }
}

/// Extract the outputs from a finished finest level.
/// `x`, `p`, `film` are the finest-grid arrays in Hertzian units; `h_scale` = H_Moes/H_Venner.
pub fn line_outputs(
    x: &[f64],
    p: &[f64],
    film: &[f64],
    h0: f64,
    h_scale: f64,
    i_centre: usize,
    info: &SolveInfo,
) -> Outputs {
    let n = x.len();
    let h = x[1] - x[0];
    let mut imax = 0;
    for i in 0..n {
        if p[i] > p[imax] {
            imax = i;
        }
    }
    let (t, p_max) = if imax > 0 && imax + 1 < n {
        parabola_vertex(p[imax - 1], p[imax], p[imax + 1])
    } else {
        (0.0, p[imax])
    };
    let h_c_pmax = interp(film, imax, t) * h_scale;
    let mut imin = 1;
    for i in 1..n - 1 {
        if film[i] < film[imin] {
            imin = i;
        }
    }
    let (tm, hm) = parabola_vertex(film[imin - 1], film[imin], film[imin + 1]);
    let maxima: Vec<usize> = (1..n - 1)
        .filter(|&i| p[i] > p[i - 1] && p[i] >= p[i + 1] && p[i] > 0.05 * p_max)
        .collect();
    let spike = if maxima.len() >= 2 {
        let i = *maxima.last().expect("two or more maxima");
        let (ts, ps) = parabola_vertex(p[i - 1], p[i], p[i + 1]);
        Some(Spike {
            x: x[i] + ts * h,
            p: ps,
        })
    } else {
        None
    };
    let load: f64 = h * p.iter().sum::<f64>();
    let mut traction = 0.0;
    for i in 0..n - 1 {
        traction += 0.25 * (film[i] + film[i + 1]) * (p[i + 1] - p[i]);
    }
    let target = std::f64::consts::FRAC_PI_2;
    Outputs {
        h_c: film[i_centre] * h_scale,
        h_c_pmax,
        h_min: hm * h_scale,
        x_min: x[imin] + tm * h,
        y_min: None,
        centre_line: None,
        d: None,
        k: None,
        p_max,
        spike,
        h0: h0 * h_scale,
        f: traction / load,
        load_error: (load - target) / target,
        status: info.status,
        reason: info.reason.clone(),
        grid: info.grid,
        levels: info.levels,
        level: Some(grid_level(info.grid, 32)),
        model_used: ModelUsed::Full,
        work_units: info.work_units,
        wall_s: info.wall_s,
        algebraic_error: info.algebraic_error,
        h_c_err: None,
        h_c_pmax_err: None,
        p_max_err: None,
        h_min_err: None,
        error_estimate: None,
        accuracy_met: None,
        mixed: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_carry_two_significant_figures_of_their_error() {
        assert_eq!(with_error(4.4846, Some(9.2e-3)), "4.485 +- 0.041");
        assert_eq!(with_error(0.87039, Some(0.14)), "0.87 +- 0.12");
        assert_eq!(with_error(123.4, Some(0.5)), "123 +- 62");
        assert_eq!(with_error(2.4475, Some(0.0)), "2.447500 (exact)");
        assert_eq!(with_error(1.5, None), "1.500000 (no error estimate)");
    }

    #[test]
    fn model_names_round_trip_and_unknown_names_are_errors() {
        for m in ModelUsed::ALL {
            assert_eq!(m.as_str().parse::<ModelUsed>(), Ok(m));
            let json = serde_json::to_string(&m).unwrap();
            assert_eq!(json, format!("\"{}\"", m.as_str()));
        }
        let e = "Full".parse::<ModelUsed>().unwrap_err().to_string();
        assert!(
            e.contains("unknown model \"Full\"") && e.contains("slender-line"),
            "{e}"
        );
    }

    #[test]
    fn parabola_vertex_is_exact_for_parabolas() {
        // y = 2 - 3 (t - 0.3)^2 sampled at -1, 0, 1.
        let y = |t: f64| 2.0 - 3.0 * (t - 0.3) * (t - 0.3);
        let (t, v) = parabola_vertex(y(-1.0), y(0.0), y(1.0));
        assert!((t - 0.3).abs() < 1e-12 && (v - 2.0).abs() < 1e-12);
    }
}

/// The finest-grid fields: node coordinates and, row-major with X fastest (node (i, j) at
/// j * x.len() + i), P (Hertzian units) and H (Moes units).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct PointFields {
    /// Node coordinates X along the rolling direction.
    pub x: Vec<f64>,
    /// Node coordinates Y across it.
    pub y: Vec<f64>,
    /// The pressure P, row-major with X fastest.
    pub p: Vec<f64>,
    /// The film H (Moes units), row-major with X fastest.
    pub h: Vec<f64>,
    /// Rough surfaces: the asperity pressure p_a/p_h, row-major with X fastest.
    pub p_asperity: Option<Vec<f64>>,
}

impl Solution {
    /// An answer without a solve ([`Outputs::without_solve`]): its info repeats the outputs'
    /// status, reason, cost and algebraic error, with `discretisation_error`; no history.
    pub fn without_solve(outputs: Outputs, discretisation_error: Option<f64>) -> Solution {
        let info = SolveInfo {
            status: outputs.status,
            reason: outputs.reason.clone(),
            history: vec![],
            work_units: outputs.work_units,
            wall_s: outputs.wall_s,
            grid: outputs.grid,
            levels: outputs.levels,
            algebraic_error: outputs.algebraic_error,
            discretisation_error,
            phases: Default::default(),
        };
        Solution {
            outputs,
            info,
            profile: None,
            attempt: 1,
            fields: None,
        }
    }
}

/// Everything a solve returns, line or point contact.
#[derive(Clone, Debug)]
pub struct Solution {
    /// The films, pressures, status and cost.
    pub outputs: Outputs,
    /// The status, reason, cycle history and cost.
    pub info: SolveInfo,
    /// Which attempt of the fallback ladder (1-based) produced the result.
    pub attempt: usize,
    /// Line contacts, when asked for: the P(X), H(X) profile on the finest grid.
    pub profile: Option<Profile>,
    /// Point contacts, when asked for: the P(X, Y), H(X, Y) fields on the finest grid.
    pub fields: Option<PointFields>,
}
