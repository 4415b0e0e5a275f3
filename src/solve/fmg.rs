//! The full-multigrid driver shared by the line and point solvers (Venner & Lubrecht's FMG with
//! the load balance as an outer secant iteration on H0).
//!
//! A solver exposes its levels through [`Fas`]: an initial guess, an exact start on the coarsest
//! level (Newton with the load equation, plus the load slope dG/dH0), the FMG interpolation, one
//! FAS cycle at fixed H0, and the convergence record of a level. [`fmg_solve`] then runs, level by
//! level from the coarsest: cycles at fixed H0 until the load error has settled (the residual fell
//! by 20 since the last H0 change and the load error moved by less than a tenth of itself), then a
//! safeguarded secant step on H0 ([`LoadBalance`]); H0 is predicted on each new level by
//! Richardson extrapolation of its last change (H0 converges at second order in h). On the finest
//! level it stops when the load error and the change of H_c per cycle are below the tolerances,
//! and reports divergence (non-finite values, residual growth by 1e4), stalling (the load error
//! stuck with H_c frozen) or the cycle limit honestly.

use crate::solve::load_balance::LoadBalance;
use crate::solve::newton::NewtonOutcome;
use crate::solve::{CycleRecord, SolveInfo, Status};
use std::time::Instant;

/// The driver's tolerances and limits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FmgControl {
    /// Cycles on each FMG level before moving to the next finer one (4x this at most).
    pub fmg_cycles: usize,
    /// Cycles allowed on the finest level.
    pub max_cycles: usize,
    /// Load tolerance on the finest level: |load error| below it converges.
    pub tol_load: f64,
    /// Relative change of H_c per cycle below which the finest level converges.
    pub tol_h: f64,
    /// Load tolerance on the coarser FMG levels.
    pub tol_load_fmg: f64,
    /// Fast convergence: the largest algebraic error the finest level may stop with.
    pub max_algebraic: f64,
    /// Fast convergence: the factor of the finest level's residual bound on the algebraic
    /// error ([`crate::solve::fmg_fast`]; 0: none).
    pub residual_bound: f64,
    /// Damping of the secant step on H0 (`None`: 1).
    pub load_factor: Option<f64>,
    /// The cycle budget of a coarser FMG level grows by this factor per level below the finest
    /// (1: 4 fmg_cycles everywhere). Point contacts use 2: a coarse cycle costs a quarter of the
    /// next finer one, and a load balance settled on the coarse levels saves fine cycles.
    pub coarse_budget_growth: usize,
    /// Stop once this instant has passed ([`crate::solve::params::MgParams::deadline`]).
    pub deadline: Option<Instant>,
}

/// The reason of a solve stopped by its deadline after cycle `k` (0-based) of level `l`, if
/// the deadline has passed.
pub(crate) fn time_limit(c: &FmgControl, l: usize, k: usize) -> Option<String> {
    crate::solve::deadline::past(c.deadline).then(|| {
        format!(
            "time limit reached at cycle {} of level {l}, not converged",
            k + 1
        )
    })
}

/// What the FMG driver needs from a multilevel solver.
pub trait Fas {
    /// The driver's controls (cycle budgets, tolerances).
    fn control(&self) -> FmgControl;
    /// Index of the finest level (0 = coarsest).
    fn top(&self) -> usize;
    /// Initial guess on the coarsest level.
    fn initialise(&mut self);
    /// Exact solve on the coarsest level with the load equation; with `with_slope`, also
    /// estimate dG/dH0 for [`Fas::load_slope`].
    fn start_coarse(&mut self, with_slope: bool) -> NewtonOutcome;
    /// Estimate of d(load)/dH0 from the coarsest level, for the first secant step.
    fn load_slope(&self) -> f64;
    /// Start level l from level l-1's solution.
    fn fmg_interpolate(&mut self, l: usize);
    /// One FAS cycle with level l as the finest, at fixed H0. With a cycle damping beta < 1
    /// ([`Fas::damp_cycles`]) the cycle's change of P and H0 is scaled by beta.
    fn cycle(&mut self, l: usize);
    /// Scale the change of every later cycle by `beta` in (0, 1] (1: undamped). A fixed point
    /// of the cycle is one of the damped cycle; an oscillation of period two (an eigenvalue of
    /// the cycle near -1) is removed by beta = 1/2.
    fn damp_cycles(&mut self, beta: f64);
    /// One relaxation sweep of level l (counted in work units).
    fn relax(&mut self, l: usize);
    /// Convergence measures of level `l` after a cycle.
    fn record(&mut self, l: usize) -> CycleRecord;
    /// The current film constant H0 (Hertzian units).
    fn h0(&self) -> f64;
    /// Set H0 and refresh level l's film.
    fn set_h0(&mut self, l: usize, h0: f64);
    /// Central film of level l (Hertzian units).
    fn centre_film(&self, l: usize) -> f64;
    /// The central film estimate of the domain rule (Hertzian units).
    fn h_estimate(&self) -> f64;
    /// Right-hand side of level l's load equation.
    fn load_target(&self, l: usize) -> f64;
    /// Who receives every cycle (None: nobody).
    fn observer(&self) -> Option<crate::solve::Observer>;
    /// Install a warm-start guess (pressure and H0 from a solved neighbour) on level `l`, the
    /// finest; true when there was one. The FMG ascent is then skipped: the coarse start only
    /// supplies the load slope, and the finest-level cycles start from the guess.
    fn install_guess(&mut self, _l: usize) -> bool {
        false
    }
    /// Install the seed ([`crate::solve::multilevel::Seed`]) on the coarser level whose nodes
    /// are its nodes, with its H0; the level's index, or None (no seed, or no level matches).
    /// The fast rule's FMG ascent then continues from that level, which also serves as the
    /// first coarser level of the discretisation estimate (the tight rule does not call it: its
    /// solves start cold).
    fn install_seed(&mut self) -> Option<usize> {
        None
    }
    /// A warm start's estimate of the finest level's relative discretisation error (from an
    /// earlier cold solve of nearly the same problem), used where there is no coarser level to
    /// estimate it from.
    fn discretisation_hint(&self) -> Option<f64> {
        None
    }
    /// Whether the next solve resumes from a finest-level state that [`Fas::install_guess`]
    /// installs (no coarse start: the load slope of the earlier solve is kept).
    fn resuming(&self) -> bool {
        false
    }
    /// Whether a coarsest-level solve with the load equation (fast convergence) has failed, so
    /// that H0 no longer moves with the cycles.
    fn coarse_load_failed(&self) -> bool {
        false
    }
    /// Forget the history of the finest level's cycle acceleration
    /// ([`crate::solve::params::MgParams::anderson`]) after a cycle that hardly contracted the
    /// residual ([`crate::solve::fmg_fast::ACCELERATION_RESTART`]).
    fn restart_acceleration(&mut self) {}
    /// Work units spent so far (relaxation sweeps in finest-grid equivalents).
    fn work_units(&self) -> f64;
    /// Where the time went so far ([`crate::solve::phases::PhaseTimes`], `total` not set).
    fn phases(&self) -> crate::solve::phases::PhaseTimes {
        Default::default()
    }
    /// Points (per direction for point contacts) of level `l`.
    fn points(&self, l: usize) -> usize;
    /// The solve's info: its status and reason, the finest level's history, the cost since
    /// `start`, the finest grid and the level count.
    fn finish(
        &self,
        start: Instant,
        status: Status,
        reason: String,
        history: Vec<CycleRecord>,
    ) -> SolveInfo {
        let wall_s = start.elapsed().as_secs_f64();
        SolveInfo {
            status,
            reason,
            history,
            work_units: self.work_units(),
            wall_s,
            grid: self.points(self.top()),
            levels: self.top() + 1,
            algebraic_error: None,
            discretisation_error: None,
            phases: crate::solve::phases::PhaseTimes {
                total: wall_s,
                work_units: self.work_units(),
                ..self.phases()
            },
        }
    }
}

/// Run full multigrid with the load balance (see the module docs).
pub fn fmg_solve<S: Fas>(s: &mut S) -> SolveInfo {
    let c = s.control();
    let start = Instant::now();
    s.initialise();
    let top = s.top();
    let coarse = s.start_coarse(top > 0);
    if top == 0 {
        return single_level(s, start, &coarse);
    }
    let mut d = Driver {
        lb: LoadBalance::new(s.load_slope()),
        history: vec![],
        status: Status::MaxIterations,
        reason: format!("no convergence in {} cycles", c.max_cycles),
        min_res: f64::INFINITY,
    };
    // H0 at the end of each level: it converges at second order in h, so the next level's
    // H0 is predicted by extrapolating the last change by 1/4 (Richardson).
    let mut h0_end = vec![s.h0()];
    let warm = s.install_guess(top);
    for l in (if warm { top } else { 1 })..=top {
        if !warm {
            start_level(s, l, &h0_end);
        }
        match run_level(s, &c, l, top, &mut d) {
            Err(reason) => return s.finish(start, Status::Diverged, reason, d.history),
            Ok(Some(reason)) => return s.finish(start, Status::MaxIterations, reason, d.history),
            Ok(None) => {}
        }
        h0_end.push(s.h0());
    }
    s.finish(start, d.status, d.reason, d.history)
}

/// A single level: the Newton solve of the coarse start is the whole solve.
pub(crate) fn single_level<S: Fas>(s: &mut S, start: Instant, coarse: &NewtonOutcome) -> SolveInfo {
    let rec = s.record(0);
    let (status, reason) = if coarse.converged {
        (
            Status::Converged,
            format!("Newton converged in {} iterations", coarse.iterations),
        )
    } else if coarse.singular {
        (Status::Diverged, "singular Newton system".to_string())
    } else {
        (
            Status::MaxIterations,
            format!(
                "Newton residual {:.2e} after {} iterations",
                coarse.residual, coarse.iterations
            ),
        )
    };
    s.finish(start, status, reason, vec![rec])
}

/// The state of the driver across the levels: the load balance on H0, the finest level's
/// cycles, the outcome so far and the smallest finest-level residual.
struct Driver {
    lb: LoadBalance,
    history: Vec<CycleRecord>,
    status: Status,
    reason: String,
    min_res: f64,
}

/// Start level `l` from level l-1: H0 predicted by Richardson extrapolation of its last change
/// (from level 3 on, `h0_end` holding H0 at the end of each level), then the FMG interpolation.
pub(crate) fn start_level<S: Fas>(s: &mut S, l: usize, h0_end: &[f64]) {
    if let [.., a, b] = h0_end[..] {
        if l >= 3 {
            s.set_h0(l, b + 0.25 * (b - a));
        }
    }
    s.fmg_interpolate(l);
}

/// The load tolerance and the cycle budget of level `l`.
fn level_budget(c: &FmgControl, l: usize, top: usize) -> (f64, usize) {
    if l == top {
        (c.tol_load, c.max_cycles)
    } else {
        (
            c.tol_load_fmg,
            4 * c.fmg_cycles * c.coarse_budget_growth.pow((top - l) as u32),
        )
    }
}

/// Cycle level `l` until its load error is below the tolerance with P settled (on the finest
/// level also H_c steady; there the outcome goes to `d`), the load error stalls on the finest
/// level, or the budget is spent; a secant step on H0 each time P has settled. `Err` holds the
/// reason of a divergence, `Ok(Some)` that of a deadline passed before convergence.
fn run_level<S: Fas>(
    s: &mut S,
    c: &FmgControl,
    l: usize,
    top: usize,
    d: &mut Driver,
) -> Result<Option<String>, String> {
    d.lb.reset();
    let final_level = l == top;
    let (tol_e, max) = level_budget(c, l, top);
    let mut settling = Settling::new();
    let mut settled_h: Option<f64> = None;
    for k in 0..max {
        let rec = cycle_once(s, l, k);
        if final_level {
            d.history.push(rec);
        }
        check_divergence(s, l, final_level, &rec, &mut d.min_res)?;
        let (settled, dh) = settling.observe(&rec, tol_e);
        if rec.load_error.abs() < tol_e
            && (settled || k + 1 == max)
            && (!final_level || dh < c.tol_h)
        {
            if final_level {
                d.status = Status::Converged;
                d.reason = format!(
                    "load error {:.1e} and H_c change {:.1e} below tolerances",
                    rec.load_error, dh
                );
            }
            break;
        }
        if let Some(why) = time_limit(c, l, k) {
            return Ok(Some(why));
        }
        if settled {
            if final_level && stalled(&rec, &mut settled_h, tol_e, d) {
                break;
            }
            secant_step(s, c, l, &mut d.lb, &rec);
            settling = Settling::new();
        } else {
            settling.prev = Some(rec);
        }
    }
    Ok(None)
}

/// Cycle `k` of level `l`: one FAS cycle and its record (sent to the observer, if any).
pub(crate) fn cycle_once<S: Fas>(s: &mut S, l: usize, k: usize) -> CycleRecord {
    s.cycle(l);
    let rec = s.record(l);
    if let Some(o) = s.observer() {
        o.notify(&crate::solve::CycleEvent {
            level: l,
            cycle: k,
            record: rec,
            h0: s.h0(),
            points: s.points(l),
            finest_points: s.points(s.top()),
        });
    }
    rec
}

/// The reason of a divergence, if the cycle diverged: a non-finite residual, film or H0 on any
/// level; on the finest level (where `min_res` tracks the smallest residual) a residual grown
/// by 1e4 or a load error above 10.
pub(crate) fn check_divergence<S: Fas>(
    s: &S,
    l: usize,
    final_level: bool,
    rec: &CycleRecord,
    min_res: &mut f64,
) -> Result<(), String> {
    if !(rec.residual.is_finite() && rec.h_c.is_finite() && s.h0().is_finite()) {
        return Err(format!("non-finite residual or film on level {l}"));
    }
    if final_level {
        *min_res = min_res.min(rec.residual);
        if rec.residual > 1e4 * min_res.max(1e-14) || rec.load_error.abs() > 10.0 {
            return Err(format!(
                "residual grew to {:.3e} (min {:.3e}), load error {:.3e}",
                rec.residual, *min_res, rec.load_error
            ));
        }
    }
    Ok(())
}

/// Whether P has settled for the current H0: the residual fell by 20 since the last H0 change
/// and the load error moved by less than a tenth of itself over the last cycle.
struct Settling {
    /// The previous cycle at this H0 (none right after an H0 change).
    prev: Option<CycleRecord>,
    /// The residual of the first cycle at this H0.
    first_res: f64,
}

impl Settling {
    fn new() -> Self {
        Settling {
            prev: None,
            first_res: f64::INFINITY,
        }
    }

    /// Take a cycle's record: whether P has settled, and the relative change of H_c over the
    /// cycle (infinite for the first cycle at this H0).
    fn observe(&mut self, rec: &CycleRecord, tol_e: f64) -> (bool, f64) {
        let prev = self.prev;
        self.first_res = self.first_res.min(if prev.is_none() {
            rec.residual
        } else {
            f64::INFINITY
        });
        let first_res = self.first_res;
        let settled = prev.is_some_and(|p| {
            (rec.load_error - p.load_error).abs() <= 0.1 * rec.load_error.abs() + 0.25 * tol_e
                && rec.residual <= 0.05 * first_res
        });
        let dh = prev.map_or(f64::INFINITY, |p| {
            // (a floor for the dry limit, where H_c is zero up to rounding)
            (rec.h_c - p.h_c).abs() / rec.h_c.abs().max(1e-6)
        });
        (settled, dh)
    }
}

/// On the finest level, with P settled: true (and the outcome Stalled in `d`) when H_c has not
/// moved since the previous settled H0 (`settled_h`) while the load error is above `tol_e`;
/// else `settled_h` becomes this H_c.
fn stalled(rec: &CycleRecord, settled_h: &mut Option<f64>, tol_e: f64, d: &mut Driver) -> bool {
    if let Some(hs) = *settled_h {
        if (rec.h_c - hs).abs() / rec.h_c.abs() < 1e-12 && rec.load_error.abs() > tol_e {
            d.status = Status::Stalled;
            d.reason = format!("load error stuck at {:.2e}", rec.load_error);
            return true;
        }
    }
    *settled_h = Some(rec.h_c);
    false
}

/// The safeguarded (and damped) secant step of the load balance on H0, after P has settled.
pub(crate) fn secant_step<S: Fas>(
    s: &mut S,
    c: &FmgControl,
    l: usize,
    lb: &mut LoadBalance,
    rec: &CycleRecord,
) {
    // H0 is a rigid approach: elastic contacts absorb much of a change of it, so the
    // step limit scales with |H0| as well as with the film.
    let max_step = 0.3 * s.centre_film(l).abs().max(1e-3 * s.h_estimate()) + 0.1 * s.h0().abs();
    let g = rec.load_error * s.load_target(l);
    let next = lb.next(s.h0(), g, max_step);
    let h0 = s.h0() + c.load_factor.unwrap_or(1.0) * (next - s.h0());
    s.set_h0(l, h0);
}
