//! Speed benchmark of the line-contact solver (`cargo bench`): median wall time over repeats, the
//! work units, and the scaling of time with the number of grid points.
//!
//! Target (issue 2): M = 20, L = 10 on 4097 points converged (load error < 1e-6, H_c within 0.1 %
//! of the fully converged value) in under 50 ms on one core.

use ehlmap::model::case::LineCase;
use ehlmap::solve::line::{solve_line, LineSolveParams};
use std::time::Instant;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.partial_cmp(b).expect("finite times"));
    v[v.len() / 2]
}

fn bench(
    case: &LineCase,
    grid: usize,
    tol_load: f64,
    tol_h: f64,
    repeats: usize,
) -> (f64, f64, f64, String) {
    let mut p = LineSolveParams::default();
    p.mg.grid = grid;
    p.mg.tol_load = tol_load;
    p.mg.tol_h = tol_h;
    let mut times = vec![];
    let mut last = None;
    for _ in 0..repeats {
        let t = Instant::now();
        let s = solve_line(case, &p);
        times.push(t.elapsed().as_secs_f64());
        last = Some(s);
    }
    let s = last.expect("at least one repeat");
    (
        median(times),
        s.outputs.work_units,
        s.outputs.h_c,
        s.outputs.status.to_string(),
    )
}

fn main() {
    // `cargo bench` passes --bench; ignore arguments.
    let case = LineCase::new(20.0, 10.0).expect("valid case");
    let reference = {
        let mut p = LineSolveParams::default();
        p.mg.grid = 4097;
        p.mg.tol_load = 1e-10;
        p.mg.tol_h = 1e-10;
        solve_line(&case, &p).outputs.h_c
    };
    println!("line M=20 L=10, one thread; fully converged H_c on 4097 points = {reference:.6}");
    println!(
        "{:>7} {:>9} {:>11} {:>9} {:>10} {:>12}",
        "grid", "tol_load", "median_ms", "WU", "H_c", "dev_vs_full"
    );
    for (grid, tl, th) in [(4097, 1e-6, 1e-4), (4097, 1e-7, 1e-6)] {
        let (t, wu, hc, st) = bench(&case, grid, tl, th, 7);
        println!(
            "{grid:>7} {tl:>9.0e} {:>11.2} {wu:>9.1} {hc:>10.6} {:>11.2e}  {st}",
            1e3 * t,
            (hc / reference - 1.0).abs()
        );
    }
    println!("\nscaling (tol_load 1e-6):");
    let mut prev: Option<(usize, f64)> = None;
    for grid in [513, 1025, 2049, 4097, 8193, 16385] {
        let (t, wu, hc, st) = bench(&case, grid, 1e-6, 1e-4, 3);
        let slope = prev.map_or(String::new(), |(g0, t0)| {
            format!(
                "slope {:.2}",
                (t / t0).ln() / ((grid - 1) as f64 / (g0 - 1) as f64).ln()
            )
        });
        println!(
            "{grid:>7} {:>11.2} ms {wu:>7.1} WU  H_c {hc:.6}  {st}  {slope}",
            1e3 * t
        );
        prev = Some((grid, t));
    }
}
