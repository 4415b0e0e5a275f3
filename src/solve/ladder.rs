//! The ladders shared by the line and point solves. Fallback ([`run_ladder`]): run the attempts in order until one
//! converges; keep the converged one, or the failed one with the lowest final residual. The
//! reason names the attempt kept, the cost (work units, wall time) covers all attempts made, and a
//! converged solve whose H_min <= 0 carries a warning (the grid does not resolve the film).
//! Grids ([`refine_to_accuracy`]): solve on grids refined by 2 until a Richardson estimate of the
//! relative error of H_c and H_min meets a target.

use crate::solve::solution::Outputs;
use crate::solve::{SolveInfo, Status};
use crate::strategy::accuracy::relative_error;

/// A solve result the ladder can rank and annotate.
pub trait Attempt {
    fn parts(&mut self) -> (&mut SolveInfo, &mut Outputs);
    fn info(&self) -> &SolveInfo;
    fn set_attempt(&mut self, k: usize);
    fn attempt(&self) -> usize;
}

fn final_residual(info: &SolveInfo) -> f64 {
    info.history
        .last()
        .map_or(f64::INFINITY, |r| r.residual)
        .abs()
}

/// Run `run(k)` for k = 0..names.len() (stopping at the first converged one) and annotate.
pub fn run_ladder<S: Attempt>(names: &[&str], mut run: impl FnMut(usize) -> S) -> S {
    let total = names.len();
    let mut best: Option<S> = None;
    let (mut spent_wu, mut spent_s) = (0.0, 0.0);
    for k in 0..total {
        let mut s = run(k);
        s.set_attempt(k + 1);
        spent_wu += s.info().work_units;
        spent_s += s.info().wall_s;
        let ok = s.info().status == Status::Converged;
        if ok
            || best
                .as_ref()
                .is_none_or(|b| final_residual(s.info()) < final_residual(b.info()))
        {
            best = Some(s);
        }
        if ok {
            break;
        }
    }
    let mut s = best.expect("at least one attempt");
    let attempt = s.attempt();
    let (info, out) = s.parts();
    if total > 1 && (attempt > 1 || info.status != Status::Converged) {
        let note = format!(
            " (attempt {attempt} of {total}; {} used)",
            names[attempt - 1]
        );
        info.reason.push_str(&note);
        out.reason.push_str(&note);
    }
    if info.status == Status::Converged && (out.h_min.is_nan() || out.h_min <= 0.0) {
        let note = "; warning: H_min <= 0, the grid does not resolve the film (refine --grid)";
        info.reason.push_str(note);
        out.reason.push_str(note);
    }
    info.work_units = spent_wu;
    info.wall_s = spent_s;
    out.work_units = spent_wu;
    out.wall_s = spent_s;
    s
}

/// Cycles a grid of the accuracy ladder below the finest allowed one may take: a grid that has
/// not converged by then does not resolve the case (full multigrid converges in about 5-15), and
/// the ladder moves on instead of spending the full cycle budget on it.
pub const COARSE_LADDER_CYCLES: usize = 20;

/// Solve on `start`, 2 start - 1, ... points (up to `max_grid`) until the error estimate between
/// the last two grids is below `target`. The estimate is Richardson's with order p,
/// |Q_h - Q_2h| / ((2^p - 1) |Q_h|), max over H_c and H_min, from two consecutive converged
/// grids. `solve(grid, last)` is told whether `grid` is the finest allowed: callers run their
/// fallback ladder there only, so a coarse grid that does not resolve the case costs one attempt
/// and the ladder moves on to a finer grid instead of stopping. Returns the finest solution with
/// `error_estimate` and `accuracy_met` set; the cost of all grids is counted.
pub fn refine_to_accuracy<S: Attempt>(
    start: usize,
    max_grid: usize,
    target: f64,
    order: f64,
    mut solve: impl FnMut(usize, bool) -> S,
) -> S {
    let mut grid = start;
    let mut prev: Option<S> = None;
    let (mut wu, mut wall) = (0.0, 0.0);
    let mut failed_grids = vec![];
    loop {
        let last = 2 * (grid - 1) + 1 > max_grid;
        let mut s = solve(grid, last);
        let (si, so) = s.parts();
        wu += si.work_units;
        wall += si.wall_s;
        let converged = si.status == Status::Converged;
        let est = prev.as_mut().filter(|_| converged).map(|c| {
            let (_, co) = c.parts();
            relative_error(co.h_c, so.h_c, order).max(relative_error(co.h_min, so.h_min, order))
        });
        if est.is_some_and(|e| e <= target) || last {
            so.error_estimate = est;
            so.accuracy_met = Some(est.is_some_and(|e| e <= target));
            let mut note = match est {
                Some(e) if e <= target => {
                    format!("; accuracy {e:.1e} <= target {target:.1e} on {} points", so.grid)
                }
                Some(e) => format!(
                    "; accuracy target {target:.1e} NOT met: estimate {e:.1e} at the finest allowed grid ({} points)",
                    so.grid
                ),
                None => format!(
                    "; accuracy target {target:.1e} NOT met: no error estimate (no two consecutive grids converged)"
                ),
            };
            if !failed_grids.is_empty() {
                note.push_str(&format!(
                    " (not converged on the coarser grids {failed_grids:?}, fallback not tried there)"
                ));
            }
            so.reason.push_str(&note);
            si.reason.push_str(&note);
            so.work_units = wu;
            so.wall_s = wall;
            si.work_units = wu;
            si.wall_s = wall;
            return s;
        }
        let g = so.grid;
        if converged {
            prev = Some(s);
        } else {
            failed_grids.push(g);
            prev = None;
        }
        grid = 2 * (g - 1) + 1;
    }
}
