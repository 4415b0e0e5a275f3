//! The point-contact solve as a library call: case + parameters in, outputs + info (+ fields) out.
//!
//! Outputs use the line contact's names (PHYSICS.md section 7), evaluated on the finest grid:
//! `H_c` = H(0, 0); `H_c_pmax` the film at the pressure maximum on the centre line Y = 0; `H_min`
//! with `X_min`, `Y_min`; `P_max`; `spike` on the centre line; `H0`; `f` the rolling traction
//! integral (H/2) dP/dX over the load; `load_error` against 2 pi k/3; plus `D` and `k`.

use crate::params::PointCase;
use crate::solution::Outputs;
use crate::solver::multigrid::CycleType;
use crate::solver::{SolveInfo, Status};

/// Multigrid settings of a point solve; `Default` gives the settings the stability map supports.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointMgParams {
    /// Points per direction of the finest level (rounded up to 2^k n0 + 1).
    pub grid: usize,
    pub cycle: CycleType,
    /// Cycles allowed on the finest level after FMG.
    pub max_cycles: usize,
    pub tol_load: f64,
    pub tol_h: f64,
}

impl Default for PointMgParams {
    fn default() -> Self {
        PointMgParams {
            grid: 129,
            cycle: CycleType::V,
            max_cycles: 40,
            tol_load: 1e-6,
            tol_h: 1e-6,
        }
    }
}

/// Parameters of a point solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointSolveParams {
    pub mg: PointMgParams,
    /// Retry with conservative settings when the first attempt fails.
    pub fallback: bool,
    /// Return the P(X, Y), H(X, Y) fields.
    pub keep_fields: bool,
}

impl Default for PointSolveParams {
    fn default() -> Self {
        PointSolveParams {
            mg: PointMgParams::default(),
            fallback: true,
            keep_fields: false,
        }
    }
}

/// The finest-grid fields: node coordinates and, row-major with X fastest (node (i, j) at
/// j * x.len() + i), P (Hertzian units) and H (Moes units).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct PointFields {
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub p: Vec<f64>,
    pub h: Vec<f64>,
}

/// Everything a point solve returns.
#[derive(Clone, Debug)]
pub struct PointSolution {
    pub outputs: Outputs,
    pub info: SolveInfo,
    pub fields: Option<PointFields>,
    /// Which attempt (1-based) produced the result.
    pub attempt: usize,
}

/// Solve a point contact.
pub fn solve_point(case: &PointCase, params: &PointSolveParams) -> PointSolution {
    // PLACEHOLDER until the point multigrid lands (this commit only fixes the API).
    let el = case.ellipse();
    let info = SolveInfo {
        status: Status::Diverged,
        reason: "point solver under construction".into(),
        history: vec![],
        work_units: 0.0,
        wall_s: 0.0,
        grid: params.mg.grid,
        levels: 0,
    };
    let nan = f64::NAN;
    PointSolution {
        outputs: Outputs {
            h_c: nan,
            h_c_pmax: nan,
            h_min: nan,
            x_min: nan,
            y_min: Some(nan),
            d: Some(case.d),
            k: Some(el.k),
            p_max: nan,
            spike: None,
            h0: nan,
            f: nan,
            load_error: nan,
            status: info.status,
            reason: info.reason.clone(),
            grid: info.grid,
            levels: 0,
            work_units: 0.0,
            wall_s: 0.0,
            error_estimate: None,
            accuracy_met: None,
        },
        info,
        fields: None,
        attempt: 1,
    }
}
