//! Full multigrid converged to the discretisation error (the default stopping rule,
//! [`crate::solve::params::Converge::Fast`]).
//!
//! From the coarsest level's Newton solve (P and H0 with the load equation), each finer level
//! l starts from level l-1's solution (FMG interpolation, H0 predicted by Richardson
//! extrapolation of its last change) and runs FAS cycles whose coarsest-level solve includes
//! the load equation, so H0 converges with P inside the cycle (where that coarsest solve fails,
//! the coarsest level is solved at fixed H0 and the cycle is followed by a secant step of the
//! load balance on H0, as in [`crate::solve::fmg`]). After each cycle, with Q_l the
//! vector (H_c, H_min) of level l:
//! * the algebraic error of each of H_c and H_min is estimated from its change over the cycle,
//!   delta_k = |Q^k - Q^(k-1)| / |Q^k| (the first cycle compared with the interpolated start),
//!   and the convergence factor rho, the larger of delta_k / delta_(k-1) and the residual's
//!   contraction over the cycle (clamped to [0.1, 0.9], 0.5 after the first cycle), as the
//!   geometric tail 2 delta_k rho / (1 - rho) with a safety factor of 2 (rho is observed over
//!   two cycles only); on a finest level started from a coarser one (not a warm or resumed
//!   start), and where the contact has a pressure spike next to its cavitation boundary
//!   ([`crate::solve::multilevel::Contact::spiked_boundary`]: line contacts, point contacts
//!   from alpha_bar = 5 on, with or without a frozen band), not below the residual bound
//!   c 3 e_d r_k / r_0 (r_0 and r_k the residuals after the level's first and latest cycle,
//!   e_d below; c = `residual_bound`, [`RESIDUAL_BOUND`]): the FMG start carries an
//!   algebraic error of about the difference of the two grids' answers, 3 e_d, which falls
//!   with the residual once the slowest modes dominate (a slow mode at the outlet spike or the
//!   cavitation boundary can leave H_c and H_min almost unchanged for two cycles and move them
//!   later); e_a is the larger of these plus 2 |load error|, the load error, which moves H by
//!   at most twice its relative size (H ~ W^-2 in the rigid-isoviscous limit, weaker
//!   elsewhere);
//! * the discretisation error of level l is estimated by Richardson for second order from level
//!   l-1's final values, e_d = max |Q_l - Q_(l-1)| / (3 |Q_l|);
//! * the finest level stops when e_a <= max(min(e_d / 10, cap), tol_h) ([`FINEST_FRACTION`];
//!   the cap is `max_algebraic`, by default [`MAX_ALGEBRAIC_ERROR`] = 1e-2) and its residual is within [`STOP_RESIDUAL_FACTOR`] of the
//!   smallest its cycles reached and H0 was not held over the cycle (where the coarsest
//!   solve with the load equation failed, H0 moves by the secant step between cycles, and a
//!   cycle at held H0 changes the film only through P: a rigid film not at all), after at
//!   most `max_cycles` cycles (status max-iterations then); a coarser level when
//!   e_a <= max(e_d, tol_h) ([`COARSE_FRACTION`]), after at most 2 `fmg_cycles` cycles.
//!
//! Where the contact asks for it ([`crate::solve::params::MgParams::anderson`], point contacts
//! whose coarse grids freeze no band), each finest-level cycle is followed by an Anderson step
//! of depth one ([`crate::solve::anderson`]), whose history is forgotten after a cycle whose
//! residual ratio exceeds [`ACCELERATION_RESTART`]; the changes and contractions above are
//! those of the accelerated iterates.
//!
//! A level whose cycles oscillate with period two ([`Swing`]: H_c alternating while the
//! residual stalls, as where a pressure spike is under-resolved on the coarser grids) has the
//! change of each later cycle halved ([`Fas::damp_cycles`], again at each new detection, down
//! to 1/8; it holds on the finer levels), and its contraction check starts again.
//!
//! The finest level's e_a and e_d are returned in [`SolveInfo::algebraic_error`] and
//! [`SolveInfo::discretisation_error`]. Divergence (non-finite values, residual growth) is
//! reported as by [`crate::solve::fmg::fmg_solve`], and so is a level whose residual grows by
//! 100 over its smallest, has not fallen below the first cycle's after 8 cycles, or exceeds
//! [`LEVEL_RESIDUAL_GROWTH`] times the coarser levels' largest. Reference: Brandt's FMG with the
//! global constraint on the coarsest grid; Venner & Lubrecht, Multilevel Methods in Lubrication (2000),
//! ch. 4 and 7.

use crate::solve::fmg::{
    check_divergence, cycle_once, secant_step, single_level, start_level, time_limit, Fas,
};
use crate::solve::load_balance::LoadBalance;
use crate::solve::{CycleRecord, SolveInfo, Status};
use std::time::Instant;

/// The finest level stops when its algebraic error estimate is below this fraction of its
/// discretisation error estimate.
pub const FINEST_FRACTION: f64 = 0.1;

/// A coarser FMG level stops when its algebraic error estimate is below this fraction of its
/// discretisation error estimate: the next level's interpolated start needs no more (classic
/// FMG), and the finest level's cycles remove what is left.
pub const COARSE_FRACTION: f64 = 1.0;

/// The factor on the cycle damping ([`Fas::damp_cycles`]) each time the cycles of a level are
/// found oscillating ([`Swing`]), down to [`MIN_CYCLE_DAMPING`].
pub const OSCILLATION_DAMPING: f64 = 0.5;

/// The smallest cycle damping.
pub const MIN_CYCLE_DAMPING: f64 = 0.125;

/// Detects an oscillation of period two: the change of H_c alternates in sign over three
/// consecutive cycles while the residual contracts by less than 1/4 over two cycles.
#[derive(Default)]
struct Swing {
    /// Whether H_c rose over the last cycle, the residuals of the last two cycles, and how many
    /// consecutive cycles flipped the sign of the change.
    rose: Option<bool>,
    residuals: [f64; 2],
    alternations: usize,
}

impl Swing {
    /// Observe the cycle from `prev` to `rec`; true when the oscillation is established.
    fn observe(&mut self, prev: &CycleRecord, rec: &CycleRecord) -> bool {
        let rose = rec.h_c > prev.h_c;
        let slow = rec.residual > 0.25 * self.residuals[0];
        let flipped = self.rose.is_some_and(|r| r != rose);
        self.alternations = if flipped && slow {
            self.alternations + 1
        } else {
            0
        };
        self.rose = Some(rose);
        self.residuals = [self.residuals[1], rec.residual];
        if self.alternations >= 2 {
            // A new oscillation has to establish itself before the next detection.
            self.alternations = 0;
            self.rose = None;
            return true;
        }
        false
    }
}

/// The default largest algebraic error the finest level may stop with, however large its
/// discretisation error estimate ([`crate::solve::params::MgParams::max_algebraic`]): a grid so coarse that its estimate exceeds ten times this is
/// not a solution to stop at, and the cycles continue until it is met or the budget is spent.
pub const MAX_ALGEBRAIC_ERROR: f64 = 1e-2;

/// The default factor c of the finest level's residual bound on the algebraic error, c 3 e_d
/// r_k / r_0 (module docs; [`crate::solve::params::MgParams::residual_bound`]). Measured on 120
/// point cases (M 1-1000, L 0-20, D 1-0.1 on 257^2 and 513^2, each run on for 22 finest cycles
/// to find its converged answer): without the bound 25 of them stopped with a true algebraic
/// error above the estimate (up to 32 times, up to 0.79 of the discretisation estimate), with
/// c = 1 where alpha_bar >= 5 (the frozen band,
/// [`crate::solve::multilevel::Contact::frozen_band`]) 9 (up to 2.8 times, at most 0.11 of
/// the discretisation estimate), for 13 % more work units. The line contact's estimate was
/// already honest (4 of 94 cases above it, up to 3.3 times, at most 0.06 of the
/// discretisation estimate) and takes c = 0.1 (`LINE_RESIDUAL_BOUND` of the line multigrid:
/// 0 of 94 above it, 0.6 % more work units). docs/method.md, "The algebraic error estimate
/// and its residual bound".
pub const RESIDUAL_BOUND: f64 = 1.0;

/// The finest level's cycle acceleration ([`Fas::restart_acceleration`]) forgets its history
/// after a cycle whose residual ratio (latest over previous) exceeds this: its extrapolation
/// overshot, or the cycles have stopped contracting.
pub const ACCELERATION_RESTART: f64 = 0.9;

/// A level whose residual exceeds this multiple of the largest residual on the coarser levels
/// has diverged: on a converging hierarchy the finer levels' residuals are no larger.
pub const LEVEL_RESIDUAL_GROWTH: f64 = 1e3;

/// The finest level stops only while its residual is within this factor of the smallest
/// residual its cycles have reached: cycles whose residual grew (a pressure spike moving to its
/// place on the finest grid) change H_c and H_min little from one cycle to the next while they
/// are still far from the solution, so small changes there do not measure the algebraic error.
pub const STOP_RESIDUAL_FACTOR: f64 = 2.0;

/// Bracket ends of the load balance older than this many cycles are dropped.
pub const BRACKET_MEMORY: usize = 4;

/// Relative change from `a` to `b` (a floor for the dry limit, where films vanish).
fn rel(a: f64, b: f64) -> f64 {
    (b - a).abs() / b.abs().max(1e-6)
}

/// The relative changes of H_c and H_min from `a` to `b`.
fn changes(a: &CycleRecord, b: &CycleRecord) -> [f64; 2] {
    [rel(a.h_c, b.h_c), rel(a.h_min, b.h_min)]
}

/// The remaining algebraic error of one quantity after a cycle that changed it by `delta`, the
/// previous cycle by `prev`, with `res_ratio` the residual's contraction over the cycle (none
/// for the first cycle of a level): the geometric tail 2 delta rho / (1 - rho) with rho the
/// larger of the two observed contractions, clamped to [0.1, 0.9] (0.5 when none is known).
pub fn tail(delta: f64, prev: Option<f64>, res_ratio: Option<f64>) -> f64 {
    let observed = prev.filter(|p| *p > 0.0).map(|p| delta / p);
    let rho = match (observed, res_ratio) {
        (None, None) => 0.5,
        (a, b) => a.unwrap_or(0.0).max(b.unwrap_or(0.0)),
    }
    .clamp(0.1, 0.9);
    2.0 * delta * rho / (1.0 - rho)
}

/// The residual bound c 3 e_d r / r_0 on the finest level's algebraic error (module docs):
/// factor `c`, discretisation estimate `e_d`, residual `r` after the latest cycle and `r_0`
/// after the level's first (0 where r_0 is not a positive number).
pub fn residual_bound(c: f64, e_d: f64, r: f64, r_0: f64) -> f64 {
    if r_0 > 0.0 && r_0.is_finite() {
        c * 3.0 * e_d * r / r_0
    } else {
        0.0
    }
}

/// The algebraic error estimate of H_c and H_min (the larger, module docs) after a cycle that
/// changed them by `delta`, the previous cycle by `prev`, with the residual's contraction
/// `res_ratio`, the relative load error `load_error` and the finest level's residual bound
/// `bound` ([`residual_bound`]; 0 on coarser levels).
pub fn algebraic_error(
    delta: [f64; 2],
    prev: Option<[f64; 2]>,
    res_ratio: Option<f64>,
    load_error: f64,
    bound: f64,
) -> f64 {
    let t = |q: usize| tail(delta[q], prev.map(|p| p[q]), res_ratio);
    t(0).max(t(1)).max(bound) + 2.0 * load_error.abs()
}

/// The reason to give up on level `l` after cycle `k`: its residual grew by 100 over its
/// smallest on the level, or is no smaller than at the first cycle after 8 cycles. (Cycles that
/// do not contract are better spent on the fallback ladder's conservative settings.) `seen`
/// holds the level's first and smallest residuals (since `k = 0`).
fn no_contraction(
    l: usize,
    k: usize,
    rec: &CycleRecord,
    seen: &mut (f64, f64),
) -> Result<(), String> {
    if k == 0 {
        *seen = (rec.residual, rec.residual);
    }
    let (first, min_res) = (seen.0, seen.1.min(rec.residual));
    seen.1 = min_res;
    if rec.residual > 100.0 * min_res {
        return Err(format!(
            "residual grew to {:.3e} (min {min_res:.3e}) on level {l}",
            rec.residual
        ));
    }
    if k >= 8 && rec.residual >= first {
        return Err(format!(
            "no contraction on level {l}: residual {:.3e} after {} cycles (first {first:.3e})",
            rec.residual,
            k + 1
        ));
    }
    Ok(())
}

/// The reason to give up on level `l` when its `residual` exceeds [`LEVEL_RESIDUAL_GROWTH`]
/// times `coarser_max`, the largest residual of the coarser levels (0 on the first level: no
/// check).
fn residual_jump(l: usize, residual: f64, coarser_max: f64) -> Result<(), String> {
    if coarser_max > 0.0 && residual > LEVEL_RESIDUAL_GROWTH * coarser_max {
        return Err(format!(
            "residual {residual:.3e} on level {l}, more than {LEVEL_RESIDUAL_GROWTH:.0e} times \
             the coarser levels' largest ({coarser_max:.3e})"
        ));
    }
    Ok(())
}

/// Run full multigrid to the discretisation error (see the module docs).
pub fn fmg_fast_solve<S: Fas>(s: &mut S) -> SolveInfo {
    let c = s.control();
    let start = Instant::now();
    let top = s.top();
    // A resumed solve keeps its load slope and starts on the finest level: no coarse start.
    if !(top > 0 && s.resuming()) {
        s.initialise();
        let coarse = s.start_coarse(true);
        if top == 0 {
            return single_level(s, start, &coarse);
        }
    }
    // H0 moves by the load balance only where the coarsest solve with the load equation fails,
    // then once per cycle, before P has settled: old bracket ends are dropped.
    let mut lb = LoadBalance::new(s.load_slope()).with_memory(BRACKET_MEMORY);
    let mut history = vec![];
    let mut min_res = f64::INFINITY;
    // The largest residual of the coarser levels' cycles (see [`LEVEL_RESIDUAL_GROWTH`]).
    let mut coarser_max_res = 0.0f64;
    let mut level_max_res = 0.0f64;
    let warm = s.install_guess(top);
    // A seed (a converged coarser grid of the same case) replaces the ascent up to its level.
    let seeded = if warm { None } else { s.install_seed() };
    let mut h0_end = vec![s.h0()];
    let mut coarser = if warm {
        None
    } else {
        Some(s.record(seeded.unwrap_or(0)))
    };
    let (mut status, mut reason) = (
        Status::MaxIterations,
        format!("no convergence in {} cycles", c.max_cycles),
    );
    let (mut e_a, mut e_d) = (None, None);
    // The cycle damping: once the cycles oscillate, it holds on the finer levels too.
    let mut beta = 1.0;
    let first = match (warm, seeded) {
        (true, _) => top,
        (false, Some(l)) => l + 1,
        (false, None) => 1,
    };
    for l in first..=top {
        if !warm {
            start_level(s, l, &h0_end);
        }
        let final_level = l == top;
        let max = if final_level {
            c.max_cycles
        } else {
            2 * c.fmg_cycles
        };
        coarser_max_res = coarser_max_res.max(level_max_res);
        let mut last = s.record(l);
        let mut prev_delta = None;
        lb.reset();
        let mut level_seen = (f64::INFINITY, f64::INFINITY);
        // The smallest residual of the level's cycles (not reset by damping).
        let mut smallest_res = f64::INFINITY;
        let mut swing = Swing::default();
        // The cycle of the level's last damping: the contraction check starts again there.
        let mut damped_at = 0;
        for k in 0..max {
            let h0_before = s.h0();
            let rec = cycle_once(s, l, k);
            // H0 held over the cycle (its coarsest solve with the load equation failed and no
            // secant step came before it): the change of H then shows P's part only.
            let h0_held = s.coarse_load_failed() && s.h0() == h0_before;
            if final_level {
                history.push(rec);
            }
            level_max_res = level_max_res.max(rec.residual);
            smallest_res = smallest_res.min(rec.residual);
            let diverged = check_divergence(s, l, final_level, &rec, &mut min_res)
                .and_then(|()| no_contraction(l, k - damped_at, &rec, &mut level_seen))
                .and_then(|()| residual_jump(l, rec.residual, coarser_max_res));
            if let Err(why) = diverged {
                return with_errors(s.finish(start, Status::Diverged, why, history), e_a, e_d);
            }
            if swing.observe(&last, &rec) {
                beta = (beta * OSCILLATION_DAMPING).max(MIN_CYCLE_DAMPING);
                s.damp_cycles(beta);
                damped_at = k + 1;
            }
            let delta = changes(&last, &rec);
            let res_ratio = (k > 0).then(|| rec.residual / last.residual.max(1e-300));
            if final_level && res_ratio.is_some_and(|r| r > ACCELERATION_RESTART) {
                s.restart_acceleration();
            }
            let from_coarser = coarser.map(|q| {
                let d = changes(&q, &rec);
                d[0].max(d[1]) / 3.0
            });
            let disc = from_coarser.or_else(|| s.discretisation_hint().filter(|_| final_level));
            // Only a level started from a coarser one carries the start error 3 e_d (a warm
            // or resumed start carries less: no bound). `history` holds the finest level's
            // cycles: its first is the bound's reference.
            let bound = match (final_level, from_coarser, history.first()) {
                (true, Some(d), Some(r_0)) => {
                    residual_bound(c.residual_bound, d, rec.residual, r_0.residual)
                }
                _ => 0.0,
            };
            let alg = algebraic_error(delta, prev_delta, res_ratio, rec.load_error, bound);
            if final_level {
                e_a = Some(alg);
                e_d = disc;
            }
            last = rec;
            prev_delta = Some(delta);
            let fraction = if final_level {
                FINEST_FRACTION
            } else {
                COARSE_FRACTION
            };
            let cap = if final_level {
                c.max_algebraic
            } else {
                f64::INFINITY
            };
            let goal = (fraction * disc.unwrap_or(0.0)).min(cap).max(c.tol_h);
            let settled =
                !final_level || (rec.residual <= STOP_RESIDUAL_FACTOR * smallest_res && !h0_held);
            if alg <= goal && settled {
                if final_level {
                    status = Status::Converged;
                    reason = match disc {
                        Some(d) => format!(
                            "algebraic error {alg:.1e} below a tenth of the discretisation error \
                             {d:.1e} (load error {:.1e})",
                            rec.load_error
                        ),
                        // A warm start has no coarser level to estimate the discretisation
                        // error from: the cycles ran to the tolerance instead.
                        None => format!(
                            "algebraic error {alg:.1e} below the tolerance {:.1e} (load error \
                             {:.1e}; no coarser level for a discretisation estimate)",
                            c.tol_h, rec.load_error
                        ),
                    };
                }
                break;
            }
            if let Some(why) = time_limit(&c, l, k) {
                return with_errors(
                    s.finish(start, Status::MaxIterations, why, history),
                    e_a,
                    e_d,
                );
            }
            if s.coarse_load_failed() {
                // H0 did not move with the cycle: a secant step of the load balance instead.
                secant_step(s, &c, l, &mut lb, &rec);
            }
        }
        coarser = Some(last);
        h0_end.push(s.h0());
    }
    with_errors(s.finish(start, status, reason, history), e_a, e_d)
}

/// `info` with the finest level's algebraic and discretisation error estimates.
fn with_errors(info: SolveInfo, e_a: Option<f64>, e_d: Option<f64>) -> SolveInfo {
    SolveInfo {
        algebraic_error: e_a,
        discretisation_error: e_d,
        ..info
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn algebraic_error_sums_the_geometric_tail_and_the_load_error() {
        // A contraction by 1/2 per cycle: the remaining error equals the last change (twice
        // that with the safety factor).
        assert!((tail(1e-3, Some(2e-3), None) - 2e-3).abs() < 1e-15);
        // By 1/10: a ninth of it.
        assert!((tail(1e-4, Some(1e-3), None) - 2e-4 / 9.0).abs() < 1e-15);
        // The residual contracting more slowly than the quantity decides.
        assert!((tail(1e-4, Some(1e-3), Some(0.5)) - 2e-4).abs() < 1e-15);
        // No contraction observed: the factor is capped at 0.9 (9 times the change).
        assert!((tail(1e-3, Some(1e-3), None) - 18e-3).abs() < 1e-15);
        // The first cycle assumes 1/2.
        assert!((tail(1e-3, None, None) - 2e-3).abs() < 1e-15);
        // The larger of the two quantities' tails, plus twice the load error.
        let e = algebraic_error([1e-3, 1e-4], Some([2e-3, 1e-3]), None, -1e-4, 0.0);
        assert!((e - 2.2e-3).abs() < 1e-15);
        let e = algebraic_error([1e-5, 1e-4], Some([1e-3, 2e-4]), Some(0.1), 0.0, 0.0);
        assert!((e - 2e-4).abs() < 1e-15);
        // A residual bound above the tails replaces them (the load error still adds).
        let e = algebraic_error([1e-5, 1e-4], Some([1e-3, 2e-4]), Some(0.1), 1e-5, 5e-4);
        assert!((e - 5.2e-4).abs() < 1e-15);
    }

    #[test]
    fn the_residual_bound_scales_the_start_error_with_the_residual() {
        // e_d = 1e-3: the FMG start is about 3e-3 off; a residual fallen 30 times from the
        // first cycle's leaves a tenth of e_d.
        assert!((residual_bound(1.0, 1e-3, 1e-4, 3e-3) - 1e-4).abs() < 1e-18);
        assert!((residual_bound(0.1, 1e-3, 1e-4, 3e-3) - 1e-5).abs() < 1e-18);
        // No reference residual: no bound.
        assert_eq!(residual_bound(1.0, 1e-3, 1e-4, 0.0), 0.0);
        assert_eq!(residual_bound(1.0, 1e-3, 1e-4, f64::NAN), 0.0);
    }

    fn record(residual: f64, h_c: f64) -> CycleRecord {
        CycleRecord {
            residual,
            load_error: 0.0,
            h_c,
            h_min: 1.0,
            work_units: 0.0,
        }
    }

    /// Feed (residual, H_c) after each cycle; which cycles report an oscillation.
    fn swings(cycles: &[(f64, f64)]) -> Vec<usize> {
        let mut sw = Swing::default();
        let mut last = record(1.0, 1.0);
        let mut out = vec![];
        for (k, &(r, h)) in cycles.iter().enumerate() {
            let rec = record(r, h);
            if sw.observe(&last, &rec) {
                out.push(k);
            }
            last = rec;
        }
        out
    }

    #[test]
    fn oscillations_of_period_two_are_detected_and_contracting_cycles_are_not() {
        // H_c up, down, up with a stalled residual: found at the third cycle, and again only
        // after three more alternating cycles.
        let osc = [
            (1e-3, 1.01),
            (1.1e-3, 1.0),
            (0.9e-3, 1.01),
            (1e-3, 1.0),
            (1e-3, 1.01),
        ];
        assert_eq!(swings(&osc), vec![2]);
        let long: Vec<_> = (0..9)
            .map(|k| (1e-3, if k % 2 == 0 { 1.01 } else { 1.0 }))
            .collect();
        assert_eq!(swings(&long), vec![2, 5, 8]);
        // The same alternation while the residual falls by 10 per cycle: normal convergence.
        let fast: Vec<_> = (0..9)
            .map(|k| (0.1f64.powi(k), if k % 2 == 0 { 1.01 } else { 1.0 }))
            .collect();
        assert!(swings(&fast).is_empty());
        // A stalled residual with H_c moving one way: not an oscillation.
        let creep: Vec<_> = (0..9).map(|k| (1e-3, 1.0 + 1e-3 * k as f64)).collect();
        assert!(swings(&creep).is_empty());
    }
}
