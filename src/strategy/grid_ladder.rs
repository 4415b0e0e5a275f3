//! The grid ladder of an accuracy target: solve on grids refined by 2 until the half-grid
//! estimate of H_c and H_min (Richardson's, `crate::strategy::accuracy::half_grid_errors`)
//! meets the target ([`refine_to_accuracy`]).
//!
//! Inputs: the first and the largest grid, the target, the half-grid estimate, an optional deadline,
//! and `solve(grid, full)`, which spends either a cheap attempt (no fallback ladder, few cycles)
//! or the full effort on a grid. Output: one solve, with `error_estimate` and `accuracy_met` set
//! where two consecutive grids converged. Invariants: the cost (work units, wall time) covers
//! every solve made; an estimate always comes from two consecutive converged grids; a grid
//! converged just above or below a failed cheap attempt gets the full effort on its failed
//! neighbour before the ladder gives up the pair.

use crate::solve::deadline::past;
use crate::solve::ladder::Attempt;
use crate::solve::solution::{ErrorEstimates, Outputs};
use crate::solve::Status;

/// Cycles a grid of the accuracy ladder below the finest allowed one may take: a grid that has
/// not converged by then does not resolve the case (full multigrid converges in about 5-15), and
/// the ladder moves on instead of spending the full cycle budget on it.
pub const COARSE_LADDER_CYCLES: usize = 20;

/// Solve on `start`, 2 start - 1, ... points (up to `max_grid`) until the error estimate between
/// the last two grids is below `target`. `estimate(coarse, fine)` gives the estimates of the
/// finer of two consecutive converged grids (Richardson's with order p, that is
/// |Q_h - Q_2h| / ((2^p - 1) |Q_h|), plus the algebraic error estimates of both solves); the
/// target applies to the larger of H_c's and H_min's. `solve(grid, full)` is told whether to
/// spend the full effort on `grid` (the fallback ladder and the whole cycle budget): the finest
/// allowed grid gets it, a coarser one does not, so a coarse grid that does not resolve the case
/// costs one attempt and the ladder moves on. Where a grid converges after the grid below it
/// failed, that grid is solved again with the full effort, and where a grid fails its cheap
/// attempt just above a converged grid, it is solved again with the full effort, so that an
/// estimate is not lost to a cheap attempt (line M = 1, L = 40: 513 points converge, 1025
/// converge only with the fallback ladder, and every finer grid fails). Returns the finest
/// solution with `error_estimate` and `accuracy_met` set, or, when the finest allowed grid does
/// not converge even with its fallback ladder, the finest converged solution that has an
/// estimate (target not met, the reason naming the grids that failed); the cost of all grids is
/// counted. Once `deadline` has passed, the grid just solved is the last (the reason says so).
pub fn refine_to_accuracy<S: Attempt>(
    start: usize,
    max_grid: usize,
    target: f64,
    estimate: impl Fn(&Outputs, &Outputs) -> Option<ErrorEstimates>,
    deadline: Option<std::time::Instant>,
    mut solve: impl FnMut(usize, bool) -> S,
) -> S {
    let mut grid = start;
    // The outputs of the grid below, when it converged.
    let mut prev: Option<Outputs> = None;
    // The finest converged solve with an error estimate so far.
    let mut best: Option<S> = None;
    let (mut wu, mut wall) = (0.0, 0.0);
    let mut failed_grids = vec![];
    // The failed grids that had the full effort too.
    let mut failed_with_ladder = vec![];
    let mut count = |s: &mut S| {
        let (si, _) = s.parts();
        wu += si.work_units;
        wall += si.wall_s;
    };
    loop {
        let finest = 2 * (grid - 1) + 1 > max_grid;
        let mut s = solve(grid, finest);
        count(&mut s);
        // A cheap attempt that fails just above a converged grid gets the full effort: the pair
        // may give the estimate that the finer grids, failing too, never would.
        if !finest && prev.is_some() && s.info().status != Status::Converged && !past(deadline) {
            let mut again = solve(grid, true);
            count(&mut again);
            if again.info().status == Status::Converged {
                s = again;
            } else {
                failed_with_ladder.push(grid);
            }
        }
        // The time limit makes this grid the last one.
        let timed_out = !finest && past(deadline);
        let last = finest || timed_out;
        let converged = s.info().status == Status::Converged;
        if converged && prev.is_none() && failed_grids.last() == Some(&coarser_grid(grid)) {
            let mut again = solve(coarser_grid(grid), true);
            count(&mut again);
            if again.info().status == Status::Converged {
                failed_grids.pop();
                prev = Some(again.parts().1.clone());
            }
        }
        let (si, so) = s.parts();
        let est = prev
            .as_ref()
            .filter(|_| converged)
            .and_then(|c| estimate(c, so));
        if let Some(e) = est {
            so.set_errors(e);
        }
        let est = est.map(|e| e.h_c.max(e.h_min));
        if last && !converged {
            if let Some(mut b) = best.take() {
                // The finest grid failed even with its fallback ladder: the finest converged
                // grid's answer, with its error bar, is the better result.
                let (bi, bo) = b.parts();
                bo.accuracy_met = Some(false);
                let note = format!(
                    "; accuracy target {target:.1e} NOT met: estimate {:.1e} on {} points, the \
                     finest grid that converged (not converged on the finer grids {:?}, the \
                     last {}: {}{})",
                    bo.error_estimate.unwrap_or(f64::NAN),
                    bo.grid,
                    failed_grids.iter().chain([&so.grid]).collect::<Vec<_>>(),
                    if timed_out {
                        "stopped by the time limit"
                    } else {
                        "with its fallback ladder"
                    },
                    so.status,
                    ladder_note(&failed_with_ladder)
                );
                for (r, w, t) in [
                    (&mut bo.reason, &mut bo.work_units, &mut bo.wall_s),
                    (&mut bi.reason, &mut bi.work_units, &mut bi.wall_s),
                ] {
                    r.push_str(&note);
                    (*w, *t) = (wu, wall);
                }
                return b;
            }
        }
        if est.is_some_and(|e| e <= target) || last {
            so.accuracy_met = Some(est.is_some_and(|e| e <= target));
            let mut note = match est {
                Some(e) if e <= target => {
                    format!("; accuracy {e:.1e} <= target {target:.1e} on {} points", so.grid)
                }
                Some(e) if timed_out => format!(
                    "; accuracy target {target:.1e} NOT met: estimate {e:.1e} on {} points when \
                     the time limit was reached",
                    so.grid
                ),
                Some(e) => format!(
                    "; accuracy target {target:.1e} NOT met: estimate {e:.1e} at the finest allowed grid ({} points)",
                    so.grid
                ),
                None if timed_out => format!(
                    "; accuracy target {target:.1e} NOT met: no error estimate when the time \
                     limit was reached on {} points",
                    so.grid
                ),
                None => format!(
                    "; accuracy target {target:.1e} NOT met: no error estimate (no two consecutive grids converged)"
                ),
            };
            if !failed_grids.is_empty() {
                note.push_str(&format!(
                    " (not converged on the coarser grids {failed_grids:?} at the first attempt{})",
                    ladder_note(&failed_with_ladder)
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
            prev = Some(so.clone());
            if est.is_some() {
                best = Some(s);
            }
        } else {
            failed_grids.push(g);
            prev = None;
        }
        grid = 2 * (g - 1) + 1;
    }
}

/// "; [grids] not with the fallback ladder either" for the failed grids that had the full
/// effort below the last one, or nothing.
fn ladder_note(grids: &[usize]) -> String {
    if grids.is_empty() {
        String::new()
    } else {
        format!("; {grids:?} not with the fallback ladder either")
    }
}

/// The grid below `grid` in the ladder (half the intervals).
pub fn coarser_grid(grid: usize) -> usize {
    (grid - 1) / 2 + 1
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::solve::solution::{ModelUsed, Solution};

    /// Outputs of a solve on 129 points with the given status and films (H_c_pmax = H_c,
    /// P_max 1), 1 work unit, every estimate empty.
    pub(crate) fn outputs(status: Status, h_c: f64, h_min: f64) -> Outputs {
        Outputs {
            p_max: 1.0,
            status,
            grid: 129,
            levels: 4,
            level: Some(3),
            work_units: 1.0,
            algebraic_error: None,
            h_c_err: None,
            h_c_pmax_err: None,
            h_min_err: None,
            error_estimate: None,
            accuracy_met: None,
            ..Outputs::without_solve(ModelUsed::Full, [h_c, h_c, h_min], String::new())
        }
    }

    /// Richardson's half-grid estimate at order 2, without algebraic errors.
    fn order2(c: &Outputs, f: &Outputs) -> Option<ErrorEstimates> {
        let rel = |a: f64, b: f64| (b - a).abs() / (3.0 * b.abs());
        Some(ErrorEstimates {
            h_c: rel(c.h_c, f.h_c),
            h_c_pmax: rel(c.h_c_pmax, f.h_c_pmax),
            h_min: rel(c.h_min, f.h_min),
            p_max: rel(c.p_max, f.p_max),
            h_min_cl: f64::NAN,
        })
    }

    /// A solve on `grid` with films `h` and `status`, 1 work unit.
    fn fake(grid: usize, h: f64, status: Status) -> Solution {
        let o = Outputs {
            grid,
            ..outputs(status, h, h)
        };
        Solution::without_solve(o, None)
    }

    /// Films converging like 1 - 1/grid: 257 -> 513 changes them by about 1.9e-3.
    fn h(grid: usize) -> f64 {
        1.0 - 1.0 / grid as f64
    }

    /// The ladder from 257 points up to `max_grid` on fake solves of films [`h`] whose status is
    /// `status(grid, full)`, and the solves it asked for, in order.
    fn ladder(
        max_grid: usize,
        target: f64,
        deadline: Option<std::time::Instant>,
        status: impl Fn(usize, bool) -> Status,
    ) -> (Solution, Vec<(usize, bool)>) {
        let mut asked = vec![];
        let s = refine_to_accuracy(257, max_grid, target, order2, deadline, |g, full| {
            asked.push((g, full));
            fake(g, h(g), status(g, full))
        });
        (s, asked)
    }

    /// Converged where `ok`, diverged elsewhere.
    fn converged_if(ok: bool) -> Status {
        if ok {
            Status::Converged
        } else {
            Status::Diverged
        }
    }

    #[test]
    fn the_ladder_stops_at_the_target_and_falls_back_to_the_finest_converged_grid() {
        let failing_from = |target: f64, fail_from: usize| {
            ladder(1025, target, None, |g, _| converged_if(g < fail_from))
        };
        // Met on 513: (h(513) - h(257)) / (3 h(513)) = 6.5e-4.
        let (s, asked) = failing_from(1e-3, usize::MAX);
        assert_eq!(asked, vec![(257, false), (513, false)]);
        assert_eq!((s.outputs.grid, s.outputs.accuracy_met), (513, Some(true)));
        let e = (h(513) - h(257)) / (3.0 * h(513));
        assert!((s.outputs.error_estimate.unwrap() - e).abs() < 1e-15);
        // Not met on 513, and 1025 (the finest allowed, with its fallback) fails: the 513
        // answer with its estimate, the cost of all three solves, the failure named.
        let (s, asked) = failing_from(1e-4, 1025);
        assert_eq!(asked, vec![(257, false), (513, false), (1025, true)]);
        assert_eq!((s.outputs.grid, s.outputs.accuracy_met), (513, Some(false)));
        assert_eq!(s.outputs.status, Status::Converged);
        assert!((s.outputs.error_estimate.unwrap() - e).abs() < 1e-15);
        assert_eq!(s.outputs.work_units, 3.0);
        assert!(
            s.outputs.reason.contains("finer grids [1025]"),
            "{}",
            s.outputs.reason
        );
        // 257 (the first grid) fails its cheap attempt and 513 converges: 257 is solved again
        // with its fallback ladder, and the estimate on 513 comes from the pair.
        let (s, asked) = ladder(1025, 1e-4, None, |g, full| converged_if(g != 257 || full));
        assert_eq!(
            asked,
            vec![(257, false), (513, false), (257, true), (1025, true)]
        );
        let e = (h(1025) - h(513)) / (3.0 * h(1025));
        assert!((s.outputs.error_estimate.unwrap() - e).abs() < 1e-15);
        assert_eq!(s.outputs.accuracy_met, Some(false));
    }

    #[test]
    fn a_passed_deadline_makes_the_grid_just_solved_the_last() {
        let past = Some(std::time::Instant::now());
        // The target needs 1025; the deadline stops the ladder after 257, which has no estimate.
        let (s, asked) = ladder(1025, 1e-5, past, |_, _| Status::Converged);
        assert_eq!(asked, vec![(257, false)]);
        assert_eq!((s.outputs.grid, s.outputs.accuracy_met), (257, Some(false)));
        assert!(
            s.outputs.reason.contains("time limit"),
            "{}",
            s.outputs.reason
        );
        // A deadline far away changes nothing.
        let later = Some(std::time::Instant::now() + std::time::Duration::from_secs(3600));
        let (_, asked) = ladder(1025, 1e-5, later, |_, _| Status::Converged);
        assert_eq!(asked, vec![(257, false), (513, false), (1025, true)]);
    }

    #[test]
    fn a_cheap_failure_above_a_converged_grid_gets_the_full_effort() {
        // 513 converges only with its fallback ladder, every finer grid fails: the estimate
        // comes from 257 and 513 (6.5e-4), which meets 1e-3 without a look at 1025.
        let run = |target: f64, rescued: bool| {
            ladder(2049, target, None, |g, full| {
                converged_if(g == 257 || (g == 513 && full && rescued))
            })
        };
        let (s, asked) = run(1e-3, true);
        assert_eq!(asked, vec![(257, false), (513, false), (513, true)]);
        assert_eq!((s.outputs.grid, s.outputs.accuracy_met), (513, Some(true)));
        let e = (h(513) - h(257)) / (3.0 * h(513));
        assert!((s.outputs.error_estimate.unwrap() - e).abs() < 1e-15);
        assert_eq!(s.outputs.work_units, 3.0);
        // A tighter target goes on: 1025 fails its cheap attempt above the converged 513 and
        // gets the full effort too, in vain; 2049 (the largest) fails: the 513 answer.
        let (s, asked) = run(1e-4, true);
        assert_eq!(
            asked,
            vec![
                (257, false),
                (513, false),
                (513, true),
                (1025, false),
                (1025, true),
                (2049, true)
            ]
        );
        assert_eq!((s.outputs.grid, s.outputs.accuracy_met), (513, Some(false)));
        assert!(s
            .outputs
            .reason
            .contains("[1025] not with the fallback ladder either"));
        // Without the rescue: no estimate, and only 513 is retried (1025's grid below failed).
        let (s, asked) = run(1e-3, false);
        assert_eq!(
            asked,
            vec![
                (257, false),
                (513, false),
                (513, true),
                (1025, false),
                (2049, true)
            ]
        );
        assert_eq!(s.outputs.accuracy_met, Some(false));
        assert_eq!(s.outputs.work_units, 5.0);
    }
}
