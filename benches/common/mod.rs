//! Timing helpers shared by the benchmarks: the median wall time over repeats and the verdict
//! word of a target.

use ehlmap::solve::solution::Outputs;
use std::time::Instant;

/// The median of `v` (the upper one for an even count).
pub fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.partial_cmp(b).expect("finite times"));
    v[v.len() / 2]
}

/// Median wall time of `repeats` runs of `run`, and the last run's outputs.
pub fn time(repeats: usize, run: impl Fn() -> Outputs) -> (f64, Outputs) {
    let mut times = vec![];
    let mut last = None;
    for _ in 0..repeats {
        let t = Instant::now();
        let o = run();
        times.push(t.elapsed().as_secs_f64());
        last = Some(o);
    }
    (median(times), last.expect("at least one repeat"))
}

/// `met` or `NOT met`.
pub fn verdict(ok: bool) -> &'static str {
    if ok {
        "met"
    } else {
        "NOT met"
    }
}
