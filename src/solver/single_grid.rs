//! Baseline: the multigrid smoother alone on the finest grid (no coarse-grid correction).
//!
//! Sweeps of the line relaxation at fixed H0; every `sweeps_per_check` sweeps the load error is
//! checked, and once it has settled (changed by less than a tenth of itself since the last check)
//! H0 takes a safeguarded secant step ([`LoadBalance`]). Converged when the load error and the
//! change of H_c over a check fall below the multigrid tolerances. Expected to be slow: smooth
//! error components decay like 1 - O(h^2) per sweep, which is what the comparison shows.

use crate::solver::load_balance::LoadBalance;
use crate::solver::multigrid::LineMultigrid;
use crate::solver::{CycleRecord, SolveInfo, Status};
use std::time::Instant;

/// Run single-grid relaxation on a one-level [`LineMultigrid`] (built with
/// `coarse_intervals` equal to the finest interval count). `max_sweeps` bounds the work.
pub fn solve_relax(
    mg: &mut LineMultigrid,
    max_sweeps: usize,
    sweeps_per_check: usize,
) -> SolveInfo {
    let start = Instant::now();
    mg.initialise();
    let l = mg.levels.len() - 1;
    let mut lb = LoadBalance::new(-std::f64::consts::FRAC_PI_2 / mg.domain.h_estimate);
    let mut history: Vec<CycleRecord> = vec![];
    let mut prev: Option<CycleRecord> = None;
    let (tol_load, tol_h) = (mg.params.tol_load, mg.params.tol_h);
    let mut sweeps = 0;
    let mut status = Status::MaxIterations;
    let mut reason = format!("no convergence in {max_sweeps} sweeps");
    while sweeps < max_sweeps {
        for _ in 0..sweeps_per_check {
            mg.relax_level(l);
        }
        sweeps += sweeps_per_check;
        let rec = mg.record(l);
        history.push(rec);
        if !(rec.residual.is_finite() && rec.h_c.is_finite()) || rec.load_error.abs() > 10.0 {
            status = Status::Diverged;
            reason = format!("non-finite or exploding state after {sweeps} sweeps");
            break;
        }
        let settled = prev.is_some_and(|p| {
            (rec.load_error - p.load_error).abs() <= 0.1 * rec.load_error.abs() + 0.25 * tol_load
        });
        let dh = prev.map_or(f64::INFINITY, |p| {
            (rec.h_c - p.h_c).abs() / rec.h_c.abs().max(1e-300)
        });
        if rec.load_error.abs() < tol_load && dh < tol_h {
            status = Status::Converged;
            reason = format!(
                "load error {:.1e} and H_c change {dh:.1e} after {sweeps} sweeps",
                rec.load_error
            );
            break;
        }
        if settled {
            let lv = &mut mg.levels[l];
            let ic = mg.domain.centre_index(lv.len() - 1);
            let max_step =
                0.3 * lv.film[ic].abs().max(1e-3 * mg.domain.h_estimate) + 0.1 * mg.h0.abs();
            mg.h0 = lb.next(mg.h0, rec.load_error * lv.g, max_step);
            lv.update_film(&mg.phys, mg.h0);
            prev = None;
        } else {
            prev = Some(rec);
        }
    }
    let fine = mg.levels.last().expect("levels");
    SolveInfo {
        status,
        reason,
        history,
        work_units: mg.work_units,
        wall_s: start.elapsed().as_secs_f64(),
        grid: fine.len(),
        levels: 1,
    }
}
