//! Timing helpers shared by the benchmarks: the machine they ran on, the median wall time over
//! repeats and the verdict word of a target.

use ehlmap::solve::solution::Outputs;
use std::time::Instant;

/// The machine, for the first line of a benchmark's output: the CPU model (Linux's
/// /proc/cpuinfo; "unknown CPU" elsewhere) and the threads available. Timings are only
/// comparable on one machine.
pub fn machine() -> String {
    let model = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".to_string());
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    format!("machine: {model}, {threads} threads available")
}

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
