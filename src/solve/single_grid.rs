//! Baseline: the multigrid smoother alone on the finest grid (no coarse-grid correction).
//!
//! Sweeps of the line relaxation at fixed H0; every `sweeps_per_check` sweeps the load error is
//! checked, and once it has settled (changed by less than a tenth of itself since the last check)
//! H0 takes a safeguarded secant step ([`LoadBalance`]). Converged when the load error and the
//! change of H_c over a check fall below the multigrid tolerances. Expected to be slow: smooth
//! error components decay like 1 - O(h^2) per sweep, which is what the comparison shows.

use crate::solve::fmg::Fas;
use crate::solve::load_balance::LoadBalance;
use crate::solve::{CycleRecord, SolveInfo, Status};
use std::time::Instant;

/// Run single-grid relaxation on a one-level solver (a [`crate::solve::line::multigrid::LineMultigrid`]
/// built with `coarse_intervals` equal to the finest interval count, or a
/// [`crate::solve::point::multigrid::PointMultigrid`] whose coarsest grid is the finest).
/// `max_sweeps` (and the deadline of the solver's controls) bound the work.
pub fn solve_relax<S: Fas>(mg: &mut S, max_sweeps: usize, sweeps_per_check: usize) -> SolveInfo {
    let start = Instant::now();
    mg.initialise();
    let l = mg.top();
    let mut lb = LoadBalance::new(-mg.load_target(l) / mg.h_estimate());
    let mut history: Vec<CycleRecord> = vec![];
    let mut prev: Option<CycleRecord> = None;
    let c = mg.control();
    let (tol_load, tol_h) = (c.tol_load, c.tol_h);
    let mut sweeps = 0;
    let mut status = Status::MaxIterations;
    let mut reason = format!("no convergence in {max_sweeps} sweeps");
    while sweeps < max_sweeps {
        for _ in 0..sweeps_per_check {
            mg.relax(l);
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
            (rec.h_c - p.h_c).abs() / rec.h_c.abs().max(1e-6)
        });
        if rec.load_error.abs() < tol_load && dh < tol_h {
            status = Status::Converged;
            reason = format!(
                "load error {:.1e} and H_c change {dh:.1e} after {sweeps} sweeps",
                rec.load_error
            );
            break;
        }
        if crate::solve::deadline::past(c.deadline) {
            reason = format!("time limit reached after {sweeps} sweeps, not converged");
            break;
        }
        if settled {
            let max_step =
                0.3 * mg.centre_film(l).abs().max(1e-3 * mg.h_estimate()) + 0.1 * mg.h0().abs();
            let h0 = lb.next(mg.h0(), rec.load_error * mg.load_target(l), max_step);
            mg.set_h0(l, h0);
            prev = None;
        } else {
            prev = Some(rec);
        }
    }
    mg.finish(start, status, reason, history)
}
