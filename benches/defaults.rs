//! Default solves (`cargo bench --bench defaults`): the library's default parameters (1 % target
//! on H_c and H_min, the accuracy ladder, model selection) on the cases of issue 23, one thread,
//! median wall time over repeats, with the grid picked, the error estimates of H_c and H_min and
//! whether the target was met.
//!
//! The targets checked: each case meets 1 % by its own estimate (`accuracy_met`; issue 23 asks
//! for 1 % of the grid-converged value, which `tests/accuracy.rs` checks against finer grids);
//! circular M = 20, L = 10 in under 1 s; circular M = 1000, L = 0 in under 10 s; the
//! ball-bearing case file (`sweeps/cases/ball-bearing.toml`, M = 8729, L = 16.4, D = 0.031) in
//! under 30 s. Each line of the summary says `met` or `NOT met`.

mod common;
use common::{time, verdict};
use ehlmap::model::case::{Case, LineCase, PointCase};
use ehlmap::solve::solution::Outputs;
use ehlmap::strategy::solve_case::{solve, SolveParams};

fn report(name: &str, t: f64, o: &Outputs) -> bool {
    let e = |x: Option<f64>| x.map_or("-".to_string(), |v| format!("{v:.2e}"));
    let met = o.accuracy_met == Some(true);
    println!(
        "{name:<28} {t:>7.3} s  grid {:>5}  {:<16}  H_c {:.4} (err {})  H_min {:.4} (err {})  1 %: {}",
        o.grid,
        o.model_used.as_str(),
        o.h_c,
        e(o.h_c_err),
        o.h_min,
        e(o.h_min_err),
        verdict(met)
    );
    met
}

fn main() {
    println!("{}", common::machine());
    let params = SolveParams::default();
    let point = |m: f64, l: f64, d: f64| Case::Point(PointCase::new(m, l, d).expect("valid case"));
    let line = |m: f64, l: f64| Case::Line(LineCase::new(m, l).expect("valid case"));
    let cases = [
        ("point M=20 L=10 D=1", point(20.0, 10.0, 1.0), 5),
        ("point M=100 L=10 D=1", point(100.0, 10.0, 1.0), 3),
        ("point M=200 L=10 D=1", point(200.0, 10.0, 1.0), 3),
        ("point M=10 L=0 D=1", point(10.0, 0.0, 1.0), 3),
        ("point M=1000 L=0 D=1", point(1000.0, 0.0, 1.0), 3),
        ("point M=100 L=10 D=0.25", point(100.0, 10.0, 0.25), 3),
        ("point M=500 L=10 D=0.5", point(500.0, 10.0, 0.5), 3),
        ("line M=1000 L=20", line(1000.0, 20.0), 5),
        ("line M=300 L=0", line(300.0, 0.0), 5),
        ("line M=10 L=20", line(10.0, 20.0), 5),
    ];
    println!("default solves (1 % target), one thread, median wall time:");
    let mut met = 0;
    let mut times = vec![];
    for (name, case, repeats) in &cases {
        let (t, o) = time(*repeats, || solve(case, &params).outputs);
        met += usize::from(report(name, t, &o));
        times.push(t);
    }
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/sweeps/cases/ball-bearing.toml"
    );
    let spec = ehlmap::cases::read_case(std::path::Path::new(path)).expect("the case file");
    let (t_bb, o_bb) = time(3, || {
        // The default smooth solve (the rough one of the file's roughness is issue 25's).
        let opts = ehlmap::cases::RunOptions {
            solve: true,
            keep_fields: false,
            rough: false,
            time_limit: None,
            formula: None,
        };
        let (r, _) = ehlmap::cases::run(&spec, opts).expect("a valid case");
        r.numerical.expect("a numerical solve")
    });
    let bb_met = report("ball-bearing case file", t_bb, &o_bb);
    println!("\ntargets:");
    println!(
        "  the {} cases within 1 % by their estimate: {} of {}: {}",
        cases.len() + 1,
        met + usize::from(bb_met),
        cases.len() + 1,
        verdict(met + usize::from(bb_met) == cases.len() + 1)
    );
    println!(
        "  (issue 23 asks each answer within 1 % of its grid-converged value with an estimate that \
         bounds the error, within the grid caps: tests/accuracy.rs checks that against finer \
         grids; a case at the 1025^2 cap may keep an estimate above 1 %)"
    );
    println!(
        "  circular M=20 L=10 under 1 s: {:.3} s: {}",
        times[0],
        verdict(times[0] < 1.0)
    );
    println!(
        "  circular M=1000 L=0 under 10 s: {:.3} s: {}",
        times[4],
        verdict(times[4] < 10.0)
    );
    println!(
        "  ball-bearing case under 30 s: {t_bb:.3} s: {}",
        verdict(t_bb < 30.0)
    );
}
