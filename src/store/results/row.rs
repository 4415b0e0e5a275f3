//! One row of a sweep dataset: [`CaseRow`], a case's inputs and every output of its solve, with
//! typed names ([`Contact`], [`Elasticity`], [`CycleType`], [`ModelUsed`], [`RowStatus`]) where
//! the file holds strings; [`finite`] and [`larger_error`] fill its float columns.
//!
//! Invariant of a row built by the sweep: no optional float holds a non-finite value unless
//! `valid` is false (the writer nulls such values and clears `valid` anyway).

use crate::model::case::{Contact, Elasticity, ParamError};
use crate::solve::params::{Converge, CycleType};
use crate::solve::solution::ModelUsed;
use crate::solve::Status;
use std::fmt;
use std::str::FromStr;

/// How the solve of a row ended: one of the solver's [`Status`]es, or a row-only outcome (the
/// case was not run, was not a valid case, or its solver panicked). Stored by [`Self::as_str`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum RowStatus {
    /// The solve converged (`converged`).
    Converged,
    /// The solve diverged (`diverged`).
    Diverged,
    /// The solve stopped improving (`stalled`).
    Stalled,
    /// The solve ran out of cycles (`max-iterations`).
    MaxIterations,
    /// The solve converged to a film <= 0: the grid does not resolve the case
    /// (`under-resolved`).
    UnderResolved,
    /// Not solved yet: a row of inputs only (`not-run`).
    #[default]
    NotRun,
    /// The parameters are not a valid case; outputs null (`invalid`).
    Invalid,
    /// The solver panicked; outputs null (`panic`).
    Panic,
}

impl RowStatus {
    /// Every status, the solver's first.
    pub const ALL: [RowStatus; 8] = [
        RowStatus::Converged,
        RowStatus::Diverged,
        RowStatus::Stalled,
        RowStatus::MaxIterations,
        RowStatus::UnderResolved,
        RowStatus::NotRun,
        RowStatus::Invalid,
        RowStatus::Panic,
    ];

    /// The name stored in the `status` column.
    pub fn as_str(&self) -> &'static str {
        match self {
            RowStatus::Converged => "converged",
            RowStatus::Diverged => "diverged",
            RowStatus::Stalled => "stalled",
            RowStatus::MaxIterations => "max-iterations",
            RowStatus::UnderResolved => "under-resolved",
            RowStatus::NotRun => "not-run",
            RowStatus::Invalid => "invalid",
            RowStatus::Panic => "panic",
        }
    }
}

impl From<Status> for RowStatus {
    fn from(s: Status) -> Self {
        match s {
            Status::Converged => RowStatus::Converged,
            Status::Diverged => RowStatus::Diverged,
            Status::Stalled => RowStatus::Stalled,
            Status::MaxIterations => RowStatus::MaxIterations,
            Status::UnderResolved => RowStatus::UnderResolved,
        }
    }
}

impl fmt::Display for RowStatus {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl FromStr for RowStatus {
    type Err = ParamError;
    fn from_str(s: &str) -> Result<Self, ParamError> {
        RowStatus::ALL
            .into_iter()
            .find(|r| r.as_str() == s)
            .ok_or_else(|| ParamError::Unknown {
                what: "status",
                name: s.to_string(),
                expected: "converged, diverged, stalled, max-iterations, not-run, invalid or panic",
            })
    }
}

impl PartialEq<&str> for RowStatus {
    fn eq(&self, other: &&str) -> bool {
        self.as_str() == *other
    }
}

impl PartialEq<Status> for RowStatus {
    fn eq(&self, other: &Status) -> bool {
        *self == RowStatus::from(*other)
    }
}

/// One case of a sweep: its inputs and every output of its solve.
///
/// Optional floats are null when they do not apply (`D`, `k`, `Y_min` for line contacts,
/// `spike_*` when there is no spike, `*_err` without an error estimate) or when the solver
/// produced a non-finite value (then `valid` is false). The file's column of each field is listed
/// in [`crate::store::results::columns::COLUMNS`].
#[derive(Clone, Debug, PartialEq)]
pub struct CaseRow {
    /// 16 hex digits: FNV-1a hash of the canonical case string (see `sweep::plan`).
    pub case_id: String,
    /// Name of the sweep (the spec's `name`).
    pub sweep: String,
    /// Line or point contact.
    pub contact: Contact,
    /// Moes load parameter (column `M`).
    pub m: f64,
    /// Moes lubricant parameter (column `L`).
    pub l: f64,
    /// Ellipticity Rx/Ry of a point contact (column `D`; null for line contacts).
    pub d: Option<f64>,
    /// Hertz ellipse ratio a/b of D (point contacts; null for line contacts).
    pub k: Option<f64>,
    /// Elastic or rigid surfaces.
    pub elasticity: Elasticity,
    /// Viscosity model name (`barus`, `roelands`).
    pub viscosity: String,
    /// Density model name (`incompressible`, `dowson-higginson`).
    pub density: String,
    /// Roelands pressure-viscosity index (derived from `eta0` when the spec gives eta0).
    pub z: Option<f64>,
    /// Ambient viscosity, Pa s, when the spec gave it.
    pub eta0: Option<f64>,
    /// Hertzian pressure, Pa (Roelands and Dowson-Higginson).
    pub ph: Option<f64>,
    /// Composite RMS roughness in Moes film units (null: smooth surfaces).
    pub sigma: Option<f64>,
    /// Roughness orientation gamma (null: smooth).
    pub gamma: Option<f64>,
    /// Slide-to-roll ratio (u1 - u2)/u_m of the rough case (null: smooth).
    pub slide_roll: Option<f64>,
    /// Finest-grid points asked for in the spec (point: per direction).
    pub grid_requested: i64,
    /// V or W cycles (stored `v`, `w`).
    pub cycle: CycleType,
    /// Cycles allowed on the finest level.
    pub max_cycles: i64,
    /// Retries with conservative smoothers allowed.
    pub fallback: bool,
    /// Load-balance tolerance.
    pub tol_load: f64,
    /// Film-change tolerance.
    pub tol_h: f64,
    /// The stopping rule of the multigrid (stored `fast`, `tight`).
    pub converge: Converge,
    /// The spec asked for a half-grid twin solve and its Richardson error columns.
    pub half_grid_estimate: bool,
    /// The spec's target relative accuracy of H_c and H_min, when it gave one.
    pub accuracy: Option<f64>,
    /// Point contacts: the asymptotic far field on the domain's boundary (false: P = 0 there;
    /// always false for line contacts and in files written before schema 5).
    pub far_field: bool,
    /// The model that answered the case (see `crate::strategy::select`).
    pub model_used: ModelUsed,
    /// Refinement level of the finest grid: log2 of its intervals over the first grid of the
    /// accuracy ladder (256 line intervals, 32 point intervals per direction); null without a
    /// grid (a closed-form answer).
    pub level: Option<i64>,
    /// Estimated relative error of H_c and H_min (the larger): the discretisation estimate
    /// plus, for a simplified model, the estimated effect of what it neglects.
    pub error_estimate: Option<f64>,
    /// Estimated relative algebraic error of H_c and H_min (the larger) left on the finest grid
    /// when its cycles stopped (fast convergence); part of `error_estimate`.
    pub algebraic_error: Option<f64>,
    /// Case id of the neighbour this case was warm-started from, when it was.
    pub warm_start: Option<String>,
    /// Finest-grid points actually used (point: per direction).
    pub grid: Option<i64>,
    /// Multigrid levels.
    pub levels: Option<i64>,
    /// Film at X = 0 (point: X = Y = 0), column `H_c`.
    pub h_c: Option<f64>,
    /// Film at the pressure maximum, column `H_c_pmax`.
    pub h_c_pmax: Option<f64>,
    /// Minimum film, column `H_min`.
    pub h_min: Option<f64>,
    /// x/b of the minimum film, column `X_min`.
    pub x_min: Option<f64>,
    /// y/b of the minimum film (point contacts), column `Y_min`.
    pub y_min: Option<f64>,
    /// The minimum film on the centre line Y = 0 (point contacts), column `H_min_cl` (schema 7).
    pub h_min_cl: Option<f64>,
    /// x/b of the centre line's minimum film, column `X_min_cl` (schema 7).
    pub x_min_cl: Option<f64>,
    /// Maximum pressure p/p_h, column `P_max`.
    pub p_max: Option<f64>,
    /// x/b of the outlet pressure spike, column `spike_X`.
    pub spike_x: Option<f64>,
    /// Height p/p_h of the outlet pressure spike, column `spike_P`.
    pub spike_p: Option<f64>,
    /// Film constant, column `H0`.
    pub h0: Option<f64>,
    /// Rolling traction F_r/w times R/b.
    pub f: Option<f64>,
    /// Relative load-balance error on the finest grid.
    pub load_error: Option<f64>,
    /// Relative error estimate of H_c, column `H_c_err`.
    pub h_c_err: Option<f64>,
    /// Relative error estimate of H_min, column `H_min_err`.
    pub h_min_err: Option<f64>,
    /// Relative error estimate of H_c_pmax, column `H_c_pmax_err` (schema 6; not part of
    /// `error_estimate`).
    pub h_c_pmax_err: Option<f64>,
    /// Relative error estimate of P_max, column `P_max_err` (schema 6).
    pub p_max_err: Option<f64>,
    /// Relative error estimate of `H_min_cl`, column `H_min_cl_err` (schema 7; not part of
    /// `error_estimate`).
    pub h_min_cl_err: Option<f64>,
    /// The film parameter H_min/sigma, column `Lambda`.
    pub lambda_min: Option<f64>,
    /// H_c/sigma, column `Lambda_c`.
    pub lambda_c: Option<f64>,
    /// The share of the load the asperities carry.
    pub asperity_load_fraction: Option<f64>,
    /// The largest asperity pressure p_a/p_h, column `P_asperity_max`.
    pub p_asperity_max: Option<f64>,
    /// H_c of the same case with smooth surfaces, column `H_c_smooth`.
    pub h_c_smooth: Option<f64>,
    /// H_min of the same case with smooth surfaces, column `H_min_smooth`.
    pub h_min_smooth: Option<f64>,
    /// Re-solves of the asperity load's fixed point.
    pub mixed_iterations: Option<i64>,
    /// How the solve ended.
    pub status: RowStatus,
    /// Why, and which fallback attempt was kept.
    pub reason: String,
    /// 1-based solver attempt that produced the row.
    pub attempt: Option<i64>,
    /// Relaxation work in finest-grid sweeps, all solves of the row included.
    pub work_units: Option<f64>,
    /// Wall time of the solve(s), s.
    pub wall_s: Option<f64>,
    /// False when an output was non-finite and written as null, or the solve failed to run.
    pub valid: bool,
}

impl Default for CaseRow {
    /// An empty row: a line contact of the default models and numerics with empty names, zero
    /// numbers, null options, status `not-run`, model `full`, `valid`. The reader starts every
    /// row from it, so a column that an older file lacks keeps this value.
    fn default() -> Self {
        CaseRow {
            case_id: String::new(),
            sweep: String::new(),
            contact: Contact::Line,
            m: 0.0,
            l: 0.0,
            d: None,
            k: None,
            elasticity: Elasticity::default(),
            viscosity: String::new(),
            density: String::new(),
            z: None,
            eta0: None,
            ph: None,
            grid_requested: 0,
            cycle: CycleType::default(),
            max_cycles: 0,
            fallback: false,
            tol_load: 0.0,
            tol_h: 0.0,
            converge: Converge::default(),
            half_grid_estimate: false,
            accuracy: None,
            far_field: false,
            model_used: ModelUsed::default(),
            level: None,
            error_estimate: None,
            algebraic_error: None,
            warm_start: None,
            grid: None,
            levels: None,
            h_c: None,
            h_c_pmax: None,
            h_min: None,
            x_min: None,
            y_min: None,
            h_min_cl: None,
            x_min_cl: None,
            p_max: None,
            spike_x: None,
            spike_p: None,
            h0: None,
            f: None,
            load_error: None,
            h_c_err: None,
            h_min_err: None,
            h_c_pmax_err: None,
            p_max_err: None,
            h_min_cl_err: None,
            sigma: None,
            gamma: None,
            slide_roll: None,
            lambda_min: None,
            lambda_c: None,
            asperity_load_fraction: None,
            p_asperity_max: None,
            h_c_smooth: None,
            h_min_smooth: None,
            mixed_iterations: None,
            status: RowStatus::default(),
            reason: String::new(),
            attempt: None,
            work_units: None,
            wall_s: None,
            valid: true,
        }
    }
}

/// The `error_estimate` column from the two error columns: the larger, or the one given.
pub fn larger_error(h_c_err: Option<f64>, h_min_err: Option<f64>) -> Option<f64> {
    match (h_c_err, h_min_err) {
        (Some(a), Some(b)) => Some(a.max(b)),
        (a, b) => a.or(b),
    }
}

/// `Some(v)` for a finite `v`, else `None`; clears `valid` when a value had to be dropped.
pub fn finite(v: f64, valid: &mut bool) -> Option<f64> {
    if v.is_finite() {
        Some(v)
    } else {
        *valid = false;
        None
    }
}

/// A full converged line row with case id `id` (for the tests of the store).
#[cfg(test)]
pub(crate) fn sample(id: &str) -> CaseRow {
    CaseRow {
        case_id: id.into(),
        sweep: "t".into(),
        contact: Contact::Line,
        m: 20.0,
        l: 10.0,
        d: None,
        k: None,
        elasticity: Elasticity::Elastic,
        viscosity: "barus".into(),
        density: "incompressible".into(),
        z: None,
        eta0: None,
        ph: None,
        grid_requested: 257,
        cycle: CycleType::V,
        max_cycles: 60,
        fallback: true,
        tol_load: 1e-7,
        tol_h: 1e-6,
        converge: Converge::Fast,
        half_grid_estimate: false,
        accuracy: Some(0.005),
        far_field: false,
        model_used: ModelUsed::Full,
        level: Some(0),
        error_estimate: Some(2e-3),
        algebraic_error: Some(1e-5),
        warm_start: Some("00000000000000cc".into()),
        grid: Some(257),
        levels: Some(4),
        h_c: Some(5.2),
        h_c_pmax: Some(4.9),
        h_min: Some(3.9),
        x_min: Some(0.9),
        y_min: None,
        h_min_cl: Some(4.1),
        x_min_cl: Some(0.85),
        p_max: Some(1.1),
        spike_x: Some(0.8),
        spike_p: Some(0.7),
        h0: Some(-1.0),
        f: Some(1e-3),
        load_error: Some(1e-8),
        h_c_err: None,
        h_min_err: None,
        h_c_pmax_err: Some(2e-3),
        p_max_err: Some(4e-2),
        h_min_cl_err: Some(3e-3),
        sigma: Some(0.5),
        gamma: Some(1.0),
        slide_roll: Some(0.2),
        lambda_min: Some(7.8),
        lambda_c: Some(10.4),
        asperity_load_fraction: Some(1e-3),
        p_asperity_max: Some(2e-3),
        h_c_smooth: Some(5.1),
        h_min_smooth: Some(3.8),
        mixed_iterations: Some(4),
        status: RowStatus::Converged,
        reason: "ok".into(),
        attempt: Some(1),
        work_units: Some(50.0),
        wall_s: Some(0.01),
        valid: true,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statuses_round_trip_by_name() {
        for s in RowStatus::ALL {
            assert_eq!(s.as_str().parse::<RowStatus>(), Ok(s));
            assert_eq!(s, s.as_str());
            assert_eq!(s.to_string(), s.as_str());
        }
        for s in [
            Status::Converged,
            Status::Diverged,
            Status::Stalled,
            Status::MaxIterations,
        ] {
            assert_eq!(RowStatus::from(s), s.as_str());
            assert_eq!(RowStatus::from(s), s);
        }
        assert_ne!(RowStatus::Panic, Status::Converged);
        let e = "done".parse::<RowStatus>().unwrap_err().to_string();
        assert!(e.contains("\"done\"") && e.contains("converged"), "{e}");
    }
}
