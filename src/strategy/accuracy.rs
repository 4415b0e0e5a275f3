//! Accuracy targets: discretisation error estimates by Richardson extrapolation over grids
//! refined by 2, and the grid ladder that refines a line or point solve until the estimate of
//! H_c and H_min meets a target ([`refine_to_accuracy`], [`solve_line_to_accuracy`],
//! [`solve_point_to_accuracy`]).
//!
//! For a quantity converging as Q_h = Q + C h^p, three grids (h, h/2, h/4) give the observed order
//! p = log2((Q_h - Q_{h/2})/(Q_{h/2} - Q_{h/4})) and the extrapolated value
//! Q* = Q_{h/4} + (Q_{h/4} - Q_{h/2})/(2^p - 1); two grids assume p = 2.

use crate::discrete::point::domain::PointDomain;
use crate::model::case::{LineCase, PointCase};
use crate::solve::ladder::Attempt;
use crate::solve::line::{solve_line_seeded, LineSolveParams};
use crate::solve::multilevel::Seed;
use crate::solve::params::ContactParams;
use crate::solve::point::{solve_point_seeded, PointSolveParams};
use crate::solve::solution::{ErrorEstimates, Outputs, Solution};
use crate::solve::Status;
use serde::{Deserialize, Serialize};

/// Result of a Richardson extrapolation.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Richardson {
    /// Observed order (the assumed one for two grids).
    pub order: f64,
    /// Extrapolated value.
    pub extrapolated: f64,
    /// Estimated relative error of the finest value, |Q_fine - Q*| / |Q*|.
    pub error_estimate: f64,
}

/// Richardson from the values on grids h, h/2, h/4 (coarse to fine).
pub fn richardson3(coarse: f64, mid: f64, fine: f64) -> Richardson {
    let ratio = (coarse - mid) / (mid - fine);
    let order = if ratio.is_finite() && ratio > 1.0 {
        ratio.log2()
    } else {
        f64::NAN
    };
    let p = if order.is_finite() { order } else { 2.0 };
    let extrapolated = fine + (fine - mid) / (2f64.powf(p) - 1.0);
    Richardson {
        order,
        extrapolated,
        error_estimate: ((fine - extrapolated) / extrapolated).abs(),
    }
}

/// Richardson's estimate of the relative error of the fine value from grids h (`coarse`) and
/// h/2 (`fine`) for a quantity converging at `order`: |Q_h/2 - Q_h| / ((2^p - 1) |Q_h/2|).
pub fn relative_error(coarse: f64, fine: f64, order: f64) -> f64 {
    let factor = 1.0 / (2f64.powf(order) - 1.0);
    factor * ((fine - coarse) / fine).abs()
}

/// Richardson from two grids h, h/2 assuming second order.
pub fn richardson2(coarse: f64, fine: f64) -> Richardson {
    let extrapolated = fine + (fine - coarse) / 3.0;
    Richardson {
        order: 2.0,
        extrapolated,
        error_estimate: ((fine - extrapolated) / extrapolated).abs(),
    }
}

/// Cycles a grid of the accuracy ladder below the finest allowed one may take: a grid that has
/// not converged by then does not resolve the case (full multigrid converges in about 5-15), and
/// the ladder moves on instead of spending the full cycle budget on it.
pub const COARSE_LADDER_CYCLES: usize = 20;

/// Solve on `start`, 2 start - 1, ... points (up to `max_grid`) until the error estimate between
/// the last two grids is below `target`. The estimate is Richardson's with order p,
/// |Q_h - Q_2h| / ((2^p - 1) |Q_h|), max over H_c and H_min, from two consecutive converged
/// grids, plus the algebraic error estimates of both solves. `solve(grid, full)` is told whether
/// to spend the full effort on `grid` (the fallback ladder and the whole cycle budget): the
/// finest allowed grid gets it, a coarser one does not, so a coarse grid that does not resolve
/// the case costs one attempt and the ladder moves on. Where a grid converges after the grid
/// below it failed, that grid is solved again with the full effort, so that an estimate is not
/// lost to a coarse grid's cheap attempt. Returns the finest solution with `error_estimate` and
/// `accuracy_met` set, or, when the finest allowed grid does not converge even with its
/// fallback ladder, the finest converged solution that has an estimate (target not met, the
/// reason naming the grids that failed); the cost of all grids is counted. Once `deadline` has
/// passed, the grid just solved is the last (the reason says so).
pub fn refine_to_accuracy<S: Attempt>(
    start: usize,
    max_grid: usize,
    target: f64,
    order: f64,
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
    let mut count = |s: &mut S| {
        let (si, _) = s.parts();
        wu += si.work_units;
        wall += si.wall_s;
    };
    loop {
        let finest = 2 * (grid - 1) + 1 > max_grid;
        let mut s = solve(grid, finest);
        count(&mut s);
        // The time limit makes this grid the last one.
        let timed_out = !finest && crate::solve::deadline::past(deadline);
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
            .and_then(|c| half_grid_errors(c, so, order));
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
                     last {}: {})",
                    bo.error_estimate.unwrap_or(f64::NAN),
                    bo.grid,
                    failed_grids.iter().chain([&so.grid]).collect::<Vec<_>>(),
                    if timed_out {
                        "stopped by the time limit"
                    } else {
                        "with its fallback ladder"
                    },
                    so.status
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
                    " (not converged on the coarser grids {failed_grids:?} at the first attempt)"
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

/// The grid below `grid` in the ladder (half the intervals).
pub fn coarser_grid(grid: usize) -> usize {
    (grid - 1) / 2 + 1
}

/// The relative error estimates of H_c, H_c_pmax, H_min and P_max of `fine` from `coarse`, the
/// solve on its half grid: Richardson at `order` ([`relative_error`]) plus the algebraic errors
/// both solves left (they contaminate the difference as well as the fine answer). None unless
/// both converged and the estimates of H_c and H_min are finite (the others may be NaN).
pub fn half_grid_errors(coarse: &Outputs, fine: &Outputs, order: f64) -> Option<ErrorEstimates> {
    if coarse.status != Status::Converged || fine.status != Status::Converged {
        return None;
    }
    let algebraic = fine.algebraic_error.unwrap_or(0.0) + coarse.algebraic_error.unwrap_or(0.0);
    let of = |q: fn(&Outputs) -> f64| relative_error(q(coarse), q(fine), order) + algebraic;
    let e = ErrorEstimates {
        h_c: of(|o| o.h_c),
        h_c_pmax: of(|o| o.h_c_pmax),
        h_min: of(|o| o.h_min),
        p_max: of(|o| o.p_max),
    };
    (e.h_c.is_finite() && e.h_min.is_finite()).then_some(e)
}

/// Add the half-grid error estimate to a solve on a fixed grid: solve again on the grid with
/// half the intervals (`solve_half(grid)`, counted in the cost) and set `H_c_err`, `H_min_err`
/// and `error_estimate` ([`half_grid_errors`] at `order`). A grid below `2 min_grid - 1`, a
/// solve that did not converge or a half-grid solve that did not leaves the estimates empty
/// and says why in the reason.
pub fn add_half_grid_estimate(
    s: &mut Solution,
    min_grid: usize,
    order: f64,
    solve_half: impl FnOnce(usize) -> Solution,
) {
    let grid = s.outputs.grid;
    let note = if s.outputs.status != Status::Converged {
        "; no error estimate: the solve did not converge".to_string()
    } else if grid < 2 * min_grid - 1 {
        format!("; no error estimate: the half grid of {grid} points is below {min_grid}")
    } else {
        let half = solve_half(coarser_grid(grid));
        for (w, t) in [
            (&mut s.outputs.work_units, &mut s.outputs.wall_s),
            (&mut s.info.work_units, &mut s.info.wall_s),
        ] {
            *w += half.outputs.work_units;
            *t += half.outputs.wall_s;
        }
        match half_grid_errors(&half.outputs, &s.outputs, order) {
            Some(e) => {
                s.outputs.set_errors(e);
                return;
            }
            None => format!(
                "; no error estimate: the half-grid solve ({} points) ended {}",
                half.outputs.grid, half.outputs.status
            ),
        }
    };
    s.outputs.reason.push_str(&note);
    s.info.reason.push_str(&note);
}

/// The point domain's truncation estimate of a case under `params` (rigid-like cases; see
/// `PointDomain::truncation_error`), to add to its error estimates.
pub fn point_truncation(case: &PointCase, params: &PointSolveParams) -> f64 {
    PointDomain::of_case(case, &params.mg.domain).truncation_error()
}

/// The fraction of the accuracy target each solve of the ladder may leave as algebraic error
/// ([`crate::solve::params::MgParams::max_algebraic`]).
pub const LADDER_ALGEBRAIC_FRACTION: f64 = 0.1;

/// The convergence order assumed by the accuracy-target error estimate.
pub const ESTIMATE_ORDER: f64 = 1.5;

/// Solve to a target relative accuracy of H_c and H_min: solve on 257, 513, ... points (up to
/// `max_grid`) until the error estimate between the last two grids is below `target`. The
/// estimate is Richardson's with a conservative order p = 1.5, |Q_h - Q_2h| / ((2^p - 1) |Q_h|),
/// max over H_c and H_min: H_c converges at order 2 but H_min at about 1.7, and the p = 2
/// estimate was below the true error in half of the validation cases (tests/accuracy.rs).
/// Returns the finest solution with `error_estimate` and `accuracy_met` set; the cost of all
/// grids is counted.
pub fn solve_line_to_accuracy(
    case: &LineCase,
    params: &LineSolveParams,
    target: f64,
    max_grid: usize,
) -> Solution {
    refine(257, ESTIMATE_ORDER, params, target, max_grid, |p, seed| {
        solve_line_seeded(case, p, seed)
    })
}

/// The convergence order assumed by the point solve's accuracy-target estimate (H_c converges at
/// order 2 on the circular reference case; H_min more slowly, as for the line contact).
pub const POINT_ESTIMATE_ORDER: f64 = 1.5;

/// Solve to a target relative accuracy of H_c and H_min on 33, 65, 129, ... points per direction
/// (up to `max_grid`); see [`refine_to_accuracy`]. The domain-truncation estimate t
/// (`PointDomain::truncation_error`, rigid-like cases) is added to `error_estimate`: the grid
/// refinement stops when the discretisation estimate meets target - t (the target itself when
/// t alone breaks it, which is then reported as not met).
pub fn solve_point_to_accuracy(
    case: &PointCase,
    params: &PointSolveParams,
    target: f64,
    max_grid: usize,
) -> Solution {
    let t = point_truncation(case, params);
    let grid_target = if t > 0.0 && t < target {
        target - t
    } else {
        target
    };
    let mut s = refine(
        33,
        POINT_ESTIMATE_ORDER,
        params,
        grid_target,
        max_grid,
        |p, seed| solve_point_seeded(case, p, seed),
    );
    if grid_target < target {
        let note = format!(
            " (the grid's share of the target {target:.1e}, less the domain-truncation \
             estimate {t:.1e})"
        );
        s.outputs.reason.push_str(&note);
        s.info.reason.push_str(&note);
    }
    let o = &mut s.outputs;
    if let Some(e) = o.error_estimate {
        o.widen_errors(t);
        if o.accuracy_met == Some(true) && e + t > target {
            o.accuracy_met = Some(false);
            let note = format!(
                "; accuracy target {target:.1e} NOT met with the domain-truncation estimate \
                 {t:.1e} added"
            );
            o.reason.push_str(&note);
            s.info.reason.push_str(&note);
        }
    }
    s
}

/// [`refine_to_accuracy`] of a contact's solve from `start` points: the fallback ladder only on
/// the finest allowed grid, and at most [`COARSE_LADDER_CYCLES`] cycles below it. The finest grid
/// converged so far seeds the FMG ascent of the next one ([`Seed`]: the ascent starts from that
/// converged solution instead of from the coarsest level, and it is the first coarser level of
/// the stopping rule's discretisation estimate). The fields or profile the ladder keeps for this
/// are dropped from the answer unless `params.keep_fields`.
fn refine<D: Copy>(
    start: usize,
    order: f64,
    params: &ContactParams<D>,
    target: f64,
    max_grid: usize,
    solve: impl Fn(&ContactParams<D>, Option<&Seed>) -> Solution,
) -> Solution {
    let mut seed: Option<Seed> = None;
    let mut s = refine_to_accuracy(
        start,
        max_grid,
        target,
        order,
        params.mg.deadline,
        |grid, last| {
            let mut p = *params;
            p.mg.grid = grid;
            p.fallback = params.fallback && last;
            p.keep_fields = true;
            if !last {
                p.mg.max_cycles = p.mg.max_cycles.min(COARSE_LADDER_CYCLES);
            }
            // Two solves' algebraic errors enter the estimate: each may use a small part of the
            // target only.
            p.mg.max_algebraic = p.mg.max_algebraic.min(LADDER_ALGEBRAIC_FRACTION * target);
            let s = solve(&p, seed.as_ref());
            if let Some(new) = Seed::of(&s) {
                if seed.as_ref().is_none_or(|old| new.p.len() > old.p.len()) {
                    seed = Some(new);
                }
            }
            s
        },
    );
    if !params.keep_fields {
        s.fields = None;
        s.profile = None;
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn outputs(status: Status, h_c: f64, h_min: f64) -> Outputs {
        Outputs {
            h_c,
            h_c_pmax: h_c,
            h_min,
            x_min: 0.9,
            y_min: None,
            d: None,
            k: None,
            p_max: 1.0,
            spike: None,
            h0: 0.0,
            f: 0.0,
            load_error: 0.0,
            status,
            reason: String::new(),
            grid: 129,
            levels: 4,
            level: Some(3),
            model_used: crate::solve::solution::ModelUsed::Full,
            work_units: 1.0,
            wall_s: 0.0,
            algebraic_error: None,
            h_c_err: None,
            h_c_pmax_err: None,
            p_max_err: None,
            h_min_err: None,
            error_estimate: None,
            accuracy_met: None,
            mixed: None,
        }
    }

    #[test]
    fn half_grid_errors_need_two_converged_solves() {
        let mut fine = outputs(Status::Converged, 5.0, 4.0);
        let mut coarse = outputs(Status::Converged, 5.1, 3.9);
        (fine.h_c_pmax, coarse.h_c_pmax) = (4.5, 4.2);
        (fine.p_max, coarse.p_max) = (2.0, 1.5);
        let factor = 1.0 / (2f64.powf(ESTIMATE_ORDER) - 1.0);
        let e = half_grid_errors(&coarse, &fine, ESTIMATE_ORDER).unwrap();
        assert!((e.h_c - factor * 0.1 / 5.0).abs() < 1e-14);
        assert!((e.h_c_pmax - factor * 0.3 / 4.5).abs() < 1e-14);
        assert!((e.h_min - factor * 0.1 / 4.0).abs() < 1e-14);
        assert!((e.p_max - factor * 0.5 / 2.0).abs() < 1e-14);
        // Both solves' algebraic errors add to every estimate.
        fine.algebraic_error = Some(1e-4);
        coarse.algebraic_error = Some(2e-4);
        let e2 = half_grid_errors(&coarse, &fine, ESTIMATE_ORDER).unwrap();
        for (a, b) in [
            (e2.h_c, e.h_c),
            (e2.h_c_pmax, e.h_c_pmax),
            (e2.h_min, e.h_min),
        ] {
            assert!((a - b - 3e-4).abs() < 1e-14);
        }
        // The estimate goes to the outputs; error_estimate leaves H_c_pmax's out.
        fine.set_errors(e2);
        assert_eq!(fine.h_c_pmax_err, Some(e2.h_c_pmax));
        assert_eq!(fine.p_max_err, Some(e2.p_max));
        assert_eq!(fine.error_estimate, Some(e2.h_c.max(e2.h_min)));
        // A film at the pressure maximum without a value has no estimate; the others stand.
        coarse.h_c_pmax = f64::NAN;
        let e3 = half_grid_errors(&coarse, &fine, ESTIMATE_ORDER).unwrap();
        assert!(e3.h_c_pmax.is_nan() && e3.h_c == e2.h_c);
        fine.set_errors(e3);
        assert_eq!(fine.h_c_pmax_err, None);
        let failed = outputs(Status::Diverged, 5.1, 3.9);
        assert_eq!(half_grid_errors(&failed, &fine, ESTIMATE_ORDER), None);
        let nan = outputs(Status::Converged, f64::NAN, 3.9);
        assert_eq!(half_grid_errors(&nan, &fine, ESTIMATE_ORDER), None);
        assert_eq!(coarser_grid(129), 65);
    }

    /// A converged solve on `grid` with films `h` (or a failed one), 1 work unit.
    fn fake(grid: usize, h: f64, status: Status) -> Solution {
        let mut o = outputs(status, h, h);
        o.grid = grid;
        Solution {
            info: crate::solve::SolveInfo {
                status,
                reason: String::new(),
                history: vec![],
                work_units: 1.0,
                wall_s: 0.0,
                grid,
                levels: 4,
                algebraic_error: None,
                discretisation_error: None,
            },
            outputs: o,
            attempt: 1,
            profile: None,
            fields: None,
        }
    }

    #[test]
    fn the_ladder_stops_at_the_target_and_falls_back_to_the_finest_converged_grid() {
        // H converges like 1 - 1/grid: 257 -> 513 changes H by about 1.9e-3.
        let h = |g: usize| 1.0 - 1.0 / g as f64;
        let ladder = |target: f64, fail_from: usize| {
            let mut asked = vec![];
            let s = refine_to_accuracy(257, 1025, target, 2.0, None, |g, full| {
                asked.push((g, full));
                let status = if g >= fail_from {
                    Status::Diverged
                } else {
                    Status::Converged
                };
                fake(g, h(g), status)
            });
            (s, asked)
        };
        // Met on 513: (h(513) - h(257)) / (3 h(513)) = 6.5e-4.
        let (s, asked) = ladder(1e-3, usize::MAX);
        assert_eq!(asked, vec![(257, false), (513, false)]);
        assert_eq!((s.outputs.grid, s.outputs.accuracy_met), (513, Some(true)));
        let e = (h(513) - h(257)) / (3.0 * h(513));
        assert!((s.outputs.error_estimate.unwrap() - e).abs() < 1e-15);
        // Not met on 513, and 1025 (the finest allowed, with its fallback) fails: the 513
        // answer with its estimate, the cost of all three solves, the failure named.
        let (s, asked) = ladder(1e-4, 1025);
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
        // 513 fails its cheap attempt and 1025 converges: 513 is solved again with its
        // fallback ladder, and the estimate comes from the pair.
        let mut asked = vec![];
        let s = refine_to_accuracy(257, 1025, 1e-4, 2.0, None, |g, full| {
            asked.push((g, full));
            let status = if g == 513 && !full {
                Status::Diverged
            } else {
                Status::Converged
            };
            fake(g, h(g), status)
        });
        assert_eq!(
            asked,
            vec![(257, false), (513, false), (1025, true), (513, true)]
        );
        let e = (h(1025) - h(513)) / (3.0 * h(1025));
        assert!((s.outputs.error_estimate.unwrap() - e).abs() < 1e-15);
        assert_eq!(s.outputs.accuracy_met, Some(false));
    }

    #[test]
    fn a_passed_deadline_makes_the_grid_just_solved_the_last() {
        let h = |g: usize| 1.0 - 1.0 / g as f64;
        let past = Some(std::time::Instant::now());
        // The target needs 1025; the deadline stops the ladder after 257, which has no estimate.
        let mut asked = vec![];
        let s = refine_to_accuracy(257, 1025, 1e-5, 2.0, past, |g, full| {
            asked.push((g, full));
            fake(g, h(g), Status::Converged)
        });
        assert_eq!(asked, vec![(257, false)]);
        assert_eq!((s.outputs.grid, s.outputs.accuracy_met), (257, Some(false)));
        assert!(
            s.outputs.reason.contains("time limit"),
            "{}",
            s.outputs.reason
        );
        // A deadline far away changes nothing.
        let later = Some(std::time::Instant::now() + std::time::Duration::from_secs(3600));
        let mut asked = vec![];
        refine_to_accuracy(257, 1025, 1e-5, 2.0, later, |g, full| {
            asked.push((g, full));
            fake(g, h(g), Status::Converged)
        });
        assert_eq!(asked, vec![(257, false), (513, false), (1025, true)]);
    }

    #[test]
    fn recovers_order_and_limit() {
        let q = |h: f64| 5.0 + 0.7 * h * h + 0.01 * h * h * h;
        let r = richardson3(q(0.1), q(0.05), q(0.025));
        assert!((r.order - 2.0).abs() < 0.02, "{r:?}");
        assert!((r.extrapolated - 5.0).abs() < 1e-6);
        let r2 = richardson2(q(0.05), q(0.025));
        assert!((r2.extrapolated - 5.0).abs() < 1e-5);
    }
}
