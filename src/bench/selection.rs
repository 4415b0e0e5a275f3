//! The saving of "model no more than a case needs": every case of a sweep spec solved twice,
//! (a) with an accuracy target, i.e. the cheapest verified model (`crate::strategy::select`) on the
//! coarsest grid whose error estimate meets the target, and (b) with the full model on the
//! spec's finest grid, as a sweep without a target would. Both go through the sweep's own row
//! builder ([`solve_case`]); the cases run in parallel on the current rayon pool, each solve on
//! one thread, so the summed wall times compare like with like.
//!
//! Reported: total time of (a) and (b), cases per model, and the deviation of (a) from (b),
//! which the target should bound wherever (b) is itself converged to better than the target.

use crate::store::results::{CaseRow, RowStatus};
use crate::sweep::executor::solve_case;
use crate::sweep::plan::Case;
use rayon::prelude::*;
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// One case, solved both ways.
#[derive(Clone, Debug)]
pub struct Pair {
    /// (a): the row solved with the accuracy target (selected model, coarsest adequate grid).
    pub selected: CaseRow,
    /// (b): the row solved with the full model on the spec's finest grid, no target.
    pub full: CaseRow,
}

impl Pair {
    /// max(|H_c,a / H_c,b - 1|, |H_min,a / H_min,b - 1|), when both converged.
    pub fn deviation(&self) -> Option<f64> {
        let ok = |r: &CaseRow| r.status == RowStatus::Converged && r.valid;
        if !(ok(&self.selected) && ok(&self.full)) {
            return None;
        }
        let rel = |a: Option<f64>, b: Option<f64>| Some((a? / b? - 1.0).abs());
        Some(rel(self.selected.h_c, self.full.h_c)?.max(rel(self.selected.h_min, self.full.h_min)?))
    }
}

/// Solve every case with the target and with the full model on its finest grid.
pub fn run(cases: &[Case], sweep: &str, target: f64) -> Vec<Pair> {
    cases
        .par_iter()
        .map(|c| {
            let mut sel = c.clone();
            sel.numerics.accuracy = Some(target);
            sel.numerics.error_estimate = false;
            let mut full = c.clone();
            full.numerics.accuracy = None;
            full.numerics.error_estimate = false;
            Pair {
                selected: solve_case(&sel, sweep, None),
                full: solve_case(&full, sweep, None),
            }
        })
        .collect()
}

/// The Markdown summary: times, models, deviations.
pub fn summary(pairs: &[Pair], target: f64, spec: &str) -> String {
    let wall = |f: fn(&Pair) -> &CaseRow| -> f64 {
        pairs.iter().map(|p| f(p).wall_s.unwrap_or(0.0)).sum()
    };
    let (t_sel, t_full) = (wall(|p| &p.selected), wall(|p| &p.full));
    let mut models: BTreeMap<&str, usize> = BTreeMap::new();
    for p in pairs {
        *models.entry(p.selected.model_used.as_str()).or_default() += 1;
    }
    let devs: Vec<f64> = pairs.iter().filter_map(Pair::deviation).collect();
    let within = devs.iter().filter(|&&d| d <= target).count();
    let max_dev = devs.iter().cloned().fold(0.0, f64::max);
    let conv = |f: fn(&Pair) -> &CaseRow| {
        pairs
            .iter()
            .filter(|p| f(p).status == RowStatus::Converged)
            .count()
    };
    let mut md = format!("# Model selection and accuracy target {target} on `{spec}`\n\n");
    let _ = writeln!(
        md,
        "| | cases converged | summed solve time |\n|---|---|---|\n\
         | target {target}: selected model, coarsest adequate grid | {} / {} | {t_sel:.1} s |\n\
         | full model, finest grid of the spec | {} / {} | {t_full:.1} s |\n",
        conv(|p| &p.selected),
        pairs.len(),
        conv(|p| &p.full),
        pairs.len()
    );
    let _ = writeln!(
        md,
        "Saving: {:.1}x ({:.0} % of the time). Models: {}.\n",
        t_full / t_sel.max(1e-12),
        100.0 * (1.0 - t_sel / t_full.max(1e-12)),
        models
            .iter()
            .map(|(m, n)| format!("{m} {n}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let _ = writeln!(
        md,
        "Deviation of the targeted answer from the full finest-grid one (max over H_c and \
         H_min): within the target in {within} of {} cases with both converged; largest {:.2e}.",
        devs.len(),
        max_dev
    );
    md
}
