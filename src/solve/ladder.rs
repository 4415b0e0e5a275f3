//! The fallback ladder shared by the line and point solves ([`run_ladder`]): run the attempts
//! in order until one converges; keep the converged one, or the failed one with the lowest final
//! residual. The reason names the attempt kept, the cost (work units, wall time) covers all
//! attempts made, and a converged solve whose film H_c or H_min is <= 0 (or not a number) is
//! not an answer: its status becomes [`Status::UnderResolved`] (the grid does not resolve the
//! film).

use crate::solve::deadline::past;
use crate::solve::params::{FinerCoarsest, MgParams, Rung};
use crate::solve::solution::{Outputs, Solution};
use crate::solve::{SolveInfo, Status};

/// A solve result the ladder can rank and annotate.
pub trait Attempt {
    /// The solve's info and outputs, to annotate.
    fn parts(&mut self) -> (&mut SolveInfo, &mut Outputs);
    /// The solve's info (status, history, cost).
    fn info(&self) -> &SolveInfo;
    /// Record which attempt (1-based) produced this result.
    fn set_attempt(&mut self, k: usize);
    /// Which attempt (1-based) produced this result.
    fn attempt(&self) -> usize;
}

fn final_residual(info: &SolveInfo) -> f64 {
    info.history
        .last()
        .map_or(f64::INFINITY, |r| r.residual)
        .abs()
}

/// Run `run(k)` for k = 0..names.len() (stopping at the first converged one, or once
/// `deadline` has passed) and annotate.
pub fn run_ladder<S: Attempt>(
    names: &[&str],
    deadline: Option<std::time::Instant>,
    mut run: impl FnMut(usize) -> S,
) -> S {
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
        if ok || past(deadline) {
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
    if info.status == Status::Converged && !(out.h_min > 0.0 && out.h_c > 0.0) {
        let note = format!(
            "; but the film is not positive (H_c = {:.3e}, H_min = {:.3e}): the grid does not \
             resolve the case (refine it)",
            out.h_c, out.h_min
        );
        info.reason.push_str(&note);
        out.reason.push_str(&note);
        info.status = Status::UnderResolved;
        out.status = Status::UnderResolved;
    }
    info.work_units = spent_wu;
    info.wall_s = spent_s;
    out.work_units = spent_wu;
    out.wall_s = spent_s;
    s
}

/// Run the ladder `rungs` over the settings `p` (only the first rung without `fallback`):
/// `run` solves with each rung's settings; see [`run_ladder`].
pub fn run_rungs<D: Copy + PartialEq + FinerCoarsest, S: Attempt>(
    rungs: &[Rung],
    p: &MgParams<D>,
    fallback: bool,
    mut run: impl FnMut(&MgParams<D>) -> S,
) -> S {
    let rungs = if fallback { rungs } else { &rungs[..1] };
    // A rung that changes nothing over an earlier one (the tight rung of a tight solve) is
    // skipped.
    let mut settings: Vec<(Rung, MgParams<D>)> = vec![];
    for r in rungs {
        let q = r.apply(p);
        if !settings.iter().any(|(_, s)| *s == q) {
            settings.push((*r, q));
        }
    }
    let names: Vec<&str> = settings.iter().map(|(r, _)| r.name()).collect();
    run_ladder(&names, p.deadline, |k| run(&settings[k].1))
}

impl Attempt for Solution {
    fn parts(&mut self) -> (&mut SolveInfo, &mut Outputs) {
        (&mut self.info, &mut self.outputs)
    }
    fn info(&self) -> &SolveInfo {
        &self.info
    }
    fn set_attempt(&mut self, k: usize) {
        self.attempt = k;
    }
    fn attempt(&self) -> usize {
        self.attempt
    }
}
