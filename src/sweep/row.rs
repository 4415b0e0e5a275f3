//! One case to one row: solve a planned case (line or point; with the spec's accuracy target,
//! through the model selection of `crate::strategy::select`), add the half-grid error estimate when the
//! spec asks for it, and copy every output into a [`CaseRow`]. Non-finite outputs become nulls
//! with `valid = false`; a panicking solve becomes a row with status `panic`.

use crate::discrete::point::domain::PointDomainParams;
use crate::model::case::{Case as ModelCase, ParamError};
use crate::model::lubricant::{Density, Viscosity};
use crate::solve::solution::ModelUsed;
use crate::solve::solution::{Outputs, Solution};
use crate::solve::Status;
use crate::store::results::{finite, CaseRow, RowStatus};
use crate::strategy::formula::FormulaRef;
use crate::strategy::solve_case::{estimate_fixed, solve, SolveParams};
use crate::strategy::warm::warm_start_line;
use crate::sweep::plan::Case;

/// The input columns of a case; outputs empty, status "not-run".
pub fn input_row(case: &Case, sweep: &str) -> CaseRow {
    let n = &case.numerics;
    let (z, ph_v) = match case.models.viscosity {
        Viscosity::Barus => (None, None),
        Viscosity::Roelands { z, ph_pa } => (Some(z), Some(ph_pa)),
    };
    let ph_d = match case.models.density {
        Density::Incompressible => None,
        Density::DowsonHigginson { ph_pa } => Some(ph_pa),
    };
    let rough = case.models.roughness.filter(|r| r.is_rough());
    CaseRow {
        case_id: case.id_hex(),
        sweep: sweep.to_string(),
        contact: case.contact,
        m: case.m,
        l: case.l,
        d: case.d,
        // Exact Hertz ellipse ratio of D (point contacts), known before any solve.
        k: case.point_case().ok().map(|p| p.ellipse().k),
        elasticity: case.models.elasticity,
        viscosity: case.models.viscosity.name().to_string(),
        density: case.models.density.name().to_string(),
        z,
        eta0: case.eta0,
        ph: ph_v.or(ph_d),
        sigma: rough.map(|r| r.sigma),
        gamma: rough.map(|r| r.gamma),
        slide_roll: rough.map(|r| r.slide_roll),
        grid_requested: n.grid as i64,
        cycle: n.cycle,
        converge: n.converge,
        max_cycles: n.max_cycles as i64,
        fallback: n.fallback,
        tol_load: n.tol_load,
        tol_h: n.tol_h,
        half_grid_estimate: n.error_estimate,
        accuracy: n.accuracy,
        far_field: n.far_field,
        ..CaseRow::default()
    }
}

/// The solve parameters of a planned case on the fixed `grid` (its numerics over the defaults;
/// no accuracy target, no estimate).
pub fn solve_params(case: &Case, grid: usize) -> SolveParams {
    let n = &case.numerics;
    SolveParams {
        grid: Some(grid),
        cycle: n.cycle,
        converge: n.converge,
        max_cycles: Some(n.max_cycles),
        tol_load: Some(n.tol_load),
        tol_h: Some(n.tol_h),
        fallback: n.fallback,
        accuracy: None,
        estimate: false,
        point_domain: PointDomainParams {
            far_field: n.far_field,
            ..PointDomainParams::default()
        },
        ..SolveParams::default()
    }
}

/// Solve one case (line or point, [`solve`]) and turn it into a row. With an accuracy target
/// the ladder refines the grid up to the spec's `grid`; without one the case is solved on
/// `grid` and, with `error_estimate`, on its half grid ([`estimate_fixed`], after a warm start
/// where one ran): `H_c_err`, `H_min_err` hold relative error estimates (Richardson with the
/// conservative order of the accuracy targets plus both solves' algebraic errors, the estimate
/// `ehlmap solve` reports); `work_units`, `wall_s` are the cost of every solve. All the solves
/// of the case together take at most `time_limit` seconds ([`SolveParams::time_limit`]).
pub fn solve_case(case: &Case, sweep: &str, time_limit: Option<f64>) -> CaseRow {
    solve_case_with(
        case,
        sweep,
        CaseOptions {
            time_limit,
            formula: None,
        },
    )
}

/// How each case of a run is solved besides its spec: run options, not dataset settings.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CaseOptions {
    /// Seconds all the solves of a case may take ([`SolveParams::time_limit`]).
    pub time_limit: Option<f64>,
    /// A fitted formula that answers cases with an accuracy target where it may
    /// ([`SolveParams::formula`]).
    pub formula: Option<FormulaRef>,
}

/// [`solve_case`] with the run's [`CaseOptions`].
pub fn solve_case_with(case: &Case, sweep: &str, opts: CaseOptions) -> CaseRow {
    let c = match case.case() {
        Ok(c) => c,
        Err(e) => return invalid_row(case, sweep, e),
    };
    let n = &case.numerics;
    let params = SolveParams {
        grid: n.accuracy.is_none().then_some(n.grid),
        accuracy: n.accuracy,
        max_grid: Some(n.grid),
        formula: opts.formula,
        ..solve_params(case, n.grid)
    }
    .time_limit(opts.time_limit);
    let mut s = solve(&c, &params);
    // D and k are inputs (k from the exact Hertz ellipse, set by input_row); a solver that
    // reports them must agree.
    debug_assert!(s.outputs.d.is_none_or(|d| Some(d) == c.d()));
    let warm = warm_start(case, &c, &params, &mut s);
    if n.accuracy.is_none() && n.error_estimate {
        estimate_fixed(&c, &params, &mut s);
    }
    let mut row = build_row(case, sweep, &s.outputs, s.attempt);
    row.warm_start = warm;
    if opts.formula.is_some() && n.accuracy.is_none() {
        row.reason
            .push_str("; formula not used: the spec names a grid and no accuracy target");
    }
    row
}

/// A line case whose cold solve failed (no accuracy target, fallback on) is continued in M
/// ([`warm_start_line`]); returns the case id of the neighbour it started from when that
/// converged, and counts the chain's cost either way.
fn warm_start(
    case: &Case,
    c: &ModelCase,
    params: &SolveParams,
    s: &mut Solution,
) -> Option<String> {
    let ModelCase::Line(lc) = c else {
        return None;
    };
    if !params.fallback || params.accuracy.is_some() || s.info.status == Status::Converged {
        return None;
    }
    let mut spent = (0.0, 0.0);
    let (wu, wall) = (s.outputs.work_units, s.outputs.wall_s);
    let mut warm = None;
    if let Some(w) = warm_start_line(lc, &params.line_params(), &mut spent) {
        *s = w;
        warm = Some(case.with_m(case.m / 2.0).id_hex());
    }
    s.outputs.work_units = wu + spent.0;
    s.outputs.wall_s = wall + spent.1;
    warm
}

/// A row for a case that is not a valid case.
fn invalid_row(case: &Case, sweep: &str, e: ParamError) -> CaseRow {
    let mut row = input_row(case, sweep);
    row.status = RowStatus::Invalid;
    row.reason = e.to_string();
    row.valid = false;
    row
}

/// Copy a solve's outputs into `row` (non-finite values become null and clear `valid`).
fn fill_outputs(row: &mut CaseRow, o: &Outputs, attempt: usize, valid: &mut bool) {
    row.model_used = o.model_used;
    row.level = o.level.map(|l| l as i64);
    // A closed-form answer has no grid, pressure maximum or traction, a slender-line one no
    // point film constant or traction, a formula answer none of these and no film position or
    // load error: null, not invalid.
    let partial = matches!(
        o.model_used,
        ModelUsed::ClosedForm | ModelUsed::SlenderLine | ModelUsed::Formula
    );
    // A formula gives no film position or load error either; every solve does.
    let formula = o.model_used == ModelUsed::Formula;
    // NaN is null (not invalid) for a value the model may lack.
    let may_lack = |lacks: bool, v: f64, valid: &mut bool| {
        if lacks && v.is_nan() {
            None
        } else {
            finite(v, valid)
        }
    };
    let opt = |v: f64, valid: &mut bool| may_lack(partial, v, valid);
    let solved = |v: f64, valid: &mut bool| may_lack(formula, v, valid);
    row.grid = (o.grid > 0).then_some(o.grid as i64);
    row.levels = (o.levels > 0).then_some(o.levels as i64);
    row.h_c = finite(o.h_c, valid);
    row.h_c_pmax = finite(o.h_c_pmax, valid);
    row.h_min = finite(o.h_min, valid);
    row.x_min = solved(o.x_min, valid);
    row.y_min = o.y_min.and_then(|y| solved(y, valid));
    if let Some(cl) = &o.centre_line {
        row.h_min_cl = finite(cl.h_min, valid);
        row.x_min_cl = solved(cl.x_min, valid);
        row.h_min_cl_err = cl.h_min_err.and_then(|e| finite(e, valid));
    }
    row.p_max = opt(o.p_max, valid);
    if let Some(sp) = o.spike {
        row.spike_x = finite(sp.x, valid);
        row.spike_p = finite(sp.p, valid);
    }
    row.h0 = opt(o.h0, valid);
    row.f = opt(o.f, valid);
    row.load_error = solved(o.load_error, valid);
    row.status = o.status.into();
    row.reason = o.reason.clone();
    row.attempt = Some(attempt as i64);
}

/// The row of a finished solve: its outputs, the error columns, the cost of every solve,
/// `error_estimate` and `valid`.
fn build_row(case: &Case, sweep: &str, o: &Outputs, attempt: usize) -> CaseRow {
    let mut row = input_row(case, sweep);
    let mut valid = true;
    fill_outputs(&mut row, o, attempt, &mut valid);
    // A film <= 0 is no answer: the row stays, flagged.
    valid &= o.status != Status::UnderResolved;
    row.h_c_err = o.h_c_err.and_then(|e| finite(e, &mut valid));
    row.h_min_err = o.h_min_err.and_then(|e| finite(e, &mut valid));
    row.h_c_pmax_err = o.h_c_pmax_err.and_then(|e| finite(e, &mut valid));
    row.p_max_err = o.p_max_err.and_then(|e| finite(e, &mut valid));
    row.work_units = finite(o.work_units, &mut valid);
    row.wall_s = finite(o.wall_s, &mut valid);
    row.algebraic_error = o.algebraic_error.and_then(|a| finite(a, &mut valid));
    row.error_estimate = o.error_estimate.and_then(|e| finite(e, &mut valid));
    if let Some(x) = &o.mixed {
        row.lambda_min = finite(x.lambda_min, &mut valid);
        row.lambda_c = finite(x.lambda_c, &mut valid);
        row.asperity_load_fraction = finite(x.asperity_load_fraction, &mut valid);
        row.p_asperity_max = finite(x.p_asperity_max, &mut valid);
        row.h_c_smooth = x.h_c_smooth.and_then(|v| finite(v, &mut valid));
        row.h_min_smooth = x.h_min_smooth.and_then(|v| finite(v, &mut valid));
        row.mixed_iterations = Some(x.mixed_iterations as i64);
    }
    row.valid = valid;
    row
}

pub(crate) fn solve_guarded(case: &Case, sweep: &str, opts: CaseOptions) -> CaseRow {
    let solve = || solve_case_with(case, sweep, opts);
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(solve)) {
        Ok(r) => r,
        Err(p) => {
            let msg = p
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| p.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".to_string());
            let mut row = input_row(case, sweep);
            row.status = RowStatus::Panic;
            row.reason = format!("the solver panicked: {msg}");
            row.valid = false;
            row
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn point_cases_become_point_rows() {
        let text = "contact = \"point\"\n[axes]\nM = [10]\nL = [0]\nD = [0.5, 1]\n\
                    [numerics]\ngrid = 33\nerror_estimate = true\n";
        let spec = crate::sweep::spec::parse("p.toml", text, "p").unwrap();
        let cases = crate::sweep::plan::plan(&spec).unwrap();
        for c in &cases {
            let row = solve_case(c, "p", None);
            assert_eq!(row.contact, "point");
            assert_eq!(row.d, c.d);
            let k = row.k.unwrap();
            if c.d == Some(1.0) {
                assert_eq!(k, 1.0);
            } else {
                assert!(k > 1.0, "k = {k}");
            }
            assert_eq!(row.grid_requested, 33);
            assert!(row.grid.is_some() && row.attempt.is_some());
            // Whatever the solver returns, no non-finite value survives, and a dropped one
            // clears `valid`.
            let all = [row.h_c, row.h_min, row.x_min, row.y_min, row.p_max, row.h0];
            assert!(all.iter().flatten().all(|v| v.is_finite()));
            if all.iter().any(|v| v.is_none()) {
                assert!(!row.valid);
            }
            assert_eq!(row.status, "converged", "{}", row.reason);
            assert!(row.valid && row.y_min.is_some());
            assert!(row.h_c_err.is_some() && row.h_min_err.is_some());
        }
        // Line rows keep D, k and Y_min null.
        let line = crate::sweep::spec::parse(
            "l.toml",
            "contact = \"line\"\n[axes]\nM = [20]\nL = [0]\n[numerics]\ngrid = 129\n",
            "l",
        )
        .unwrap();
        let row = solve_case(&crate::sweep::plan::plan(&line).unwrap()[0], "l", None);
        assert_eq!((row.d, row.k, row.y_min), (None, None, None));
        assert_eq!(row.status, "converged");
    }
}
