//! Accuracy targets: the reported error estimate must be honest, i.e. the true error against a
//! much finer solve (Richardson over 4097 and 8193 points) is below the estimate.

use ehlmap::model::case::LineCase;
use ehlmap::solve::line::{solve_line, LineSolveParams};
use ehlmap::solve::Status;
use ehlmap::strategy::accuracy::richardson2;
use ehlmap::strategy::accuracy::solve_line_to_accuracy;

fn reference(case: &LineCase) -> (f64, f64) {
    let run = |g: usize| {
        let mut p = LineSolveParams::default();
        p.mg.grid = g;
        solve_line(case, &p).outputs
    };
    let (a, b) = (run(4097), run(8193));
    assert!(
        a.status == Status::Converged && b.status == Status::Converged,
        "reference solves"
    );
    (
        richardson2(a.h_c, b.h_c).extrapolated,
        richardson2(a.h_min, b.h_min).extrapolated,
    )
}

#[test]
fn error_estimates_are_honest_on_a_validation_set() {
    let mut honest = 0;
    let mut total = 0;
    for (m, l) in [
        (2.0, 0.0),
        (5.0, 5.0),
        (20.0, 10.0),
        (100.0, 0.0),
        (300.0, 10.0),
        (1000.0, 10.0),
    ] {
        let case = LineCase::new(m, l).unwrap();
        let (hc, hm) = reference(&case);
        for target in [0.01, 0.003] {
            let o =
                solve_line_to_accuracy(&case, &LineSolveParams::default(), target, 4097).outputs;
            assert_eq!(o.status, Status::Converged, "M={m} L={l}: {}", o.reason);
            let est = o.error_estimate.expect("an estimate");
            let truth = (o.h_c / hc - 1.0).abs().max((o.h_min / hm - 1.0).abs());
            println!(
                "M={m} L={l} target {target}: grid {} estimate {est:.2e} true {truth:.2e} met {:?}",
                o.grid, o.accuracy_met
            );
            total += 1;
            honest += usize::from(truth <= est);
            if o.accuracy_met == Some(true) {
                assert!(est <= target);
            }
        }
    }
    // The issue asks for at least 95 % honest estimates: with 12 cases that is all of them.
    assert_eq!(honest, total, "{honest}/{total} honest");
}

/// Point contacts: the same check, against Richardson over 129^2 and 257^2 nodes.
#[test]
fn point_error_estimates_are_honest_on_a_validation_set() {
    use ehlmap::model::case::PointCase;
    use ehlmap::solve::point::{solve_point, PointSolveParams};
    use ehlmap::strategy::accuracy::solve_point_to_accuracy;
    let run = |c: &PointCase, g: usize| {
        let mut p = PointSolveParams::default();
        p.mg.grid = g;
        let o = solve_point(c, &p).outputs;
        assert_eq!(o.status, Status::Converged, "reference: {}", o.reason);
        o
    };
    let (mut honest, mut total) = (0, 0);
    for (m, l, d) in [
        (5.0, 5.0, 1.0),
        (10.0, 0.0, 1.0),
        (20.0, 10.0, 0.5),
        (30.0, 5.0, 0.25),
        (50.0, 10.0, 1.0),
    ] {
        let case = PointCase::new(m, l, d).unwrap();
        let (a, b) = (run(&case, 129), run(&case, 257));
        let hc = richardson2(a.h_c, b.h_c).extrapolated;
        let hm = richardson2(a.h_min, b.h_min).extrapolated;
        let o = solve_point_to_accuracy(&case, &PointSolveParams::default(), 0.02, 129).outputs;
        assert_eq!(
            o.status,
            Status::Converged,
            "M={m} L={l} D={d}: {}",
            o.reason
        );
        let est = o.error_estimate.expect("an estimate");
        let truth = (o.h_c / hc - 1.0).abs().max((o.h_min / hm - 1.0).abs());
        println!(
            "point M={m} L={l} D={d}: grid {} estimate {est:.2e} true {truth:.2e} met {:?}",
            o.grid, o.accuracy_met
        );
        total += 1;
        honest += usize::from(truth <= est);
    }
    // At least 95 %: with 5 cases, all of them.
    assert_eq!(honest, total, "{honest}/{total} honest");
}

/// The accuracy ladder seeds each grid's FMG ascent with the previous grid's converged solve
/// (`Seed`): on the same grid the seeded solve agrees with the cold one within their algebraic
/// error estimates, for less work; a seed that matches no level (another case's domain) is
/// ignored, bit for bit. (The point case asked for less than 0.8 times the cold work units
/// before the finest level's residual bound: the seeded solve then stopped after 17.1 work
/// units claiming an algebraic error of 7.2e-5 with H_min 1.1e-4 off the tight answer; with
/// the bound it stops after 25.3 against the cold 26.2, claiming 2.8e-4 with 1.8e-5 off.)
#[test]
fn a_seeded_solve_agrees_with_the_cold_one_for_less_work() {
    use ehlmap::model::case::PointCase;
    use ehlmap::solve::line::solve_line_seeded;
    use ehlmap::solve::multilevel::Seed;
    use ehlmap::solve::point::{solve_point, solve_point_seeded, PointSolveParams};
    let case = PointCase::new(100.0, 10.0, 1.0).unwrap();
    let params = |g: usize, keep: bool| {
        let mut p = PointSolveParams::default();
        p.mg.grid = g;
        p.keep_fields = keep;
        p
    };
    let coarse = solve_point(&case, &params(129, true));
    let seed = Seed::of(&coarse).expect("a converged solve with fields");
    let cold = solve_point(&case, &params(257, false)).outputs;
    let warm = solve_point_seeded(&case, &params(257, false), Some(&seed)).outputs;
    assert_eq!(warm.status, Status::Converged, "{}", warm.reason);
    let alg = cold.algebraic_error.unwrap() + warm.algebraic_error.unwrap();
    for (a, b) in [(cold.h_c, warm.h_c), (cold.h_min, warm.h_min)] {
        assert!((a / b - 1.0).abs() <= alg, "{a} {b} (algebraic {alg:.1e})");
    }
    assert!(
        warm.work_units < cold.work_units,
        "seeded {} WU, cold {} WU",
        warm.work_units,
        cold.work_units
    );
    // Another case has another domain: no level matches, the solve is the cold one.
    let other = PointCase::new(50.0, 10.0, 1.0).unwrap();
    let a = solve_point(&other, &params(129, false)).outputs;
    let b = solve_point_seeded(&other, &params(129, false), Some(&seed)).outputs;
    assert_eq!(
        (a.h_c, a.h_min, a.work_units),
        (b.h_c, b.h_min, b.work_units)
    );
    // The line twin.
    let line = LineCase::new(1000.0, 20.0).unwrap();
    let lp = |g: usize, keep: bool| {
        let mut p = LineSolveParams::default();
        p.mg.grid = g;
        p.keep_fields = keep;
        p
    };
    let seed = Seed::of(&solve_line(&line, &lp(4097, true))).expect("a line seed");
    let cold = solve_line(&line, &lp(8193, false)).outputs;
    let warm = solve_line_seeded(&line, &lp(8193, false), Some(&seed)).outputs;
    let alg = cold.algebraic_error.unwrap() + warm.algebraic_error.unwrap();
    for (a, b) in [(cold.h_c, warm.h_c), (cold.h_min, warm.h_min)] {
        assert!(
            (a / b - 1.0).abs() <= alg,
            "line: {a} {b} (algebraic {alg:.1e})"
        );
    }
    assert!(
        warm.work_units < cold.work_units,
        "{} {}",
        warm.work_units,
        cold.work_units
    );
}

/// A cold fast solve of `case` on grid `g` with the library's default solver settings:
/// [H_c, H_min], asserted converged.
fn cold_films(case: &ehlmap::model::case::Case, g: usize) -> [f64; 2] {
    use ehlmap::model::case::Case;
    use ehlmap::solve::point::{solve_point, PointSolveParams};
    let o = match case {
        Case::Line(c) => {
            let mut p = LineSolveParams::default();
            p.mg.grid = g;
            solve_line(c, &p).outputs
        }
        Case::Point(c) => {
            let mut p = PointSolveParams::default();
            p.mg.grid = g;
            solve_point(c, &p).outputs
        }
    };
    assert_eq!(
        o.status,
        Status::Converged,
        "reference on {g}: {}",
        o.reason
    );
    [o.h_c, o.h_min]
}

/// The grid-converged limit of film `q` from three grids refined by 2 (`a` coarsest),
/// extrapolated at their observed order clamped to [1, 3] (second order where the differences
/// do not shrink), with that order.
fn three_grid_limit(a: [f64; 2], b: [f64; 2], c: [f64; 2], q: usize) -> (f64, f64) {
    let ratio = (a[q] - b[q]) / (b[q] - c[q]);
    let order = if ratio > 1.0 {
        ratio.log2().clamp(1.0, 3.0)
    } else {
        2.0
    };
    (c[q] + (c[q] - b[q]) / (2f64.powf(order) - 1.0), order)
}

/// Check an answer's films against the limit of `refs` (three grids): the true error below
/// `bound` and below the answer's own error bar.
fn check_against_limit(
    name: &str,
    o: &ehlmap::solve::solution::Outputs,
    refs: [[f64; 2]; 3],
    bound: f64,
) {
    for (q, (film, h, err)) in [("H_c", o.h_c, o.h_c_err), ("H_min", o.h_min, o.h_min_err)]
        .into_iter()
        .enumerate()
    {
        let (limit, order) = three_grid_limit(refs[0], refs[1], refs[2], q);
        let truth = (h / limit - 1.0).abs();
        let err = err.expect("an error bar");
        println!(
            "{name} {film} on {}: {h:.6}, limit {limit:.6} (order {order:.2}), true error \
             {truth:.2e}, estimate {err:.2e}",
            o.grid
        );
        assert!(truth < bound, "{name} {film}: true error {truth}");
        assert!(
            truth <= err,
            "{name} {film}: true {truth} above the estimate {err}"
        );
    }
}

/// Issue 23's cases: with the library defaults (1 % target, the ladder capped at 16385 line
/// points and 1025^2 point nodes) each answer is within 1 % of its grid-converged film, and its
/// error bars bound the error. Reference: cold solves on the answer's grid g, on (g + 1)/2 and
/// on 2 g - 1, extrapolated at their observed order (clamped to [1, 3]; two grids' second order
/// where the differences do not shrink).
#[test]
fn issue_23_default_answers_are_within_one_percent_of_the_limit() {
    use ehlmap::model::case::{Case, PointCase};
    use ehlmap::strategy::solve_case::{solve, SolveParams};
    let point = |m: f64, l: f64, d: f64| Case::Point(PointCase::new(m, l, d).unwrap());
    let line = |m: f64, l: f64| Case::Line(LineCase::new(m, l).unwrap());
    for (name, case) in [
        ("point (20, 10, 1)", point(20.0, 10.0, 1.0)),
        ("point (100, 10, 1)", point(100.0, 10.0, 1.0)),
        ("point (200, 10, 1)", point(200.0, 10.0, 1.0)),
        ("point (10, 0, 1)", point(10.0, 0.0, 1.0)),
        ("point (1000, 0, 1)", point(1000.0, 0.0, 1.0)),
        ("point (100, 10, 0.25)", point(100.0, 10.0, 0.25)),
        ("point (500, 10, 0.5)", point(500.0, 10.0, 0.5)),
        ("line (1000, 20)", line(1000.0, 20.0)),
        ("line (300, 0)", line(300.0, 0.0)),
        ("line (10, 20)", line(10.0, 20.0)),
    ] {
        let o = solve(&case, &SolveParams::default()).outputs;
        assert_eq!(o.status, Status::Converged, "{name}: {}", o.reason);
        let g = o.grid;
        let refs = [g.div_ceil(2), g, 2 * g - 1].map(|r| cold_films(&case, r));
        check_against_limit(name, &o, refs, 0.01);
    }
}

/// Issue 22's half-percent targets: `accuracy = 0.005` meets its target with an error estimate
/// at line M = 1000, L = 20 and circular M = 1000, L = 0 (whose point ladder goes on to 2049^2
/// for targets below 1 %), and each answer is within 0.5 % of the limit of cold solves on its
/// grid and the two coarser ones, inside its error bars.
#[test]
fn issue_22_half_percent_targets_are_met_with_an_estimate() {
    use ehlmap::model::case::{Case, PointCase};
    use ehlmap::strategy::solve_case::{solve, SolveParams};
    for (name, case) in [
        (
            "line (1000, 20)",
            Case::Line(LineCase::new(1000.0, 20.0).unwrap()),
        ),
        (
            "point (1000, 0, 1)",
            Case::Point(PointCase::new(1000.0, 0.0, 1.0).unwrap()),
        ),
    ] {
        let params = SolveParams {
            accuracy: Some(0.005),
            ..SolveParams::default()
        };
        let o = solve(&case, &params).outputs;
        assert_eq!(o.status, Status::Converged, "{name}: {}", o.reason);
        assert_eq!(o.accuracy_met, Some(true), "{name}: {}", o.reason);
        let e = o.error_estimate.expect("an error estimate");
        assert!(e <= 0.005, "{name}: estimate {e}");
        let g = o.grid;
        let refs = [g.div_ceil(4), g.div_ceil(2), g].map(|r| cold_films(&case, r));
        check_against_limit(name, &o, refs, 0.005);
    }
}

/// The film at the pressure maximum and the maximum itself carry Richardson estimates too
/// (`H_c_pmax_err`, `P_max_err`; reported, not targeted). Where the maximum is a smooth peak
/// H_c_pmax_err bounds H_c_pmax's true error (against Richardson over tight solves on 4097 and
/// 8193 points). Where it is a Barus spike whose height the grid sets (line M = 3.1, L = 20:
/// P_max 2.56, 3.00, 4.14, 5.97, 9.23 on 513 ... 8193 points, the spike on the main maximum so
/// that no second maximum is found), P_max_err flags it above 2 %, the limit beyond which the
/// fit leaves H_pm out (`ehlmap::fit::dataset::peak_is_unresolved`), while H_c and H_min meet
/// the target.
#[test]
fn pressure_maximum_estimates_bound_the_smooth_peak_and_flag_the_spike() {
    for (m, l) in [(5.0, 2.0), (100.0, 0.0), (30.0, 5.0)] {
        let case = LineCase::new(m, l).unwrap();
        let run = |g: usize| {
            let mut p = LineSolveParams::default();
            p.mg.grid = g;
            solve_line(&case, &p).outputs
        };
        let (a, b) = (run(4097), run(8193));
        let limit = richardson2(a.h_c_pmax, b.h_c_pmax).extrapolated;
        let o = solve_line_to_accuracy(&case, &LineSolveParams::default(), 0.005, 4097).outputs;
        assert_eq!(o.accuracy_met, Some(true), "M={m} L={l}: {}", o.reason);
        let truth = (o.h_c_pmax / limit - 1.0).abs();
        let (e_pm, e_p) = (o.h_c_pmax_err.unwrap(), o.p_max_err.unwrap());
        println!(
            "M={m} L={l} on {}: H_c_pmax {:.6} limit {limit:.6}: true {truth:.2e}, estimate \
             {e_pm:.2e}; P_max {:.4} (P_max_err {e_p:.2e})",
            o.grid, o.h_c_pmax, o.p_max
        );
        assert!(truth <= e_pm, "M={m} L={l}: {truth} above {e_pm}");
        assert!(e_p < 0.02, "M={m} L={l}: a smooth peak: {e_p}");
        // error_estimate is H_c's and H_min's alone.
        assert_eq!(
            o.error_estimate,
            Some(o.h_c_err.unwrap().max(o.h_min_err.unwrap()))
        );
    }
    let spike = LineCase::new(3.107233, 20.0).unwrap();
    let o = solve_line_to_accuracy(&spike, &LineSolveParams::default(), 0.005, 4097).outputs;
    println!(
        "spike M=3.107 L=20 on {}: P_max {:.4} (P_max_err {:?}), H_c_err {:?}",
        o.grid, o.p_max, o.p_max_err, o.h_c_err
    );
    assert_eq!(o.accuracy_met, Some(true), "{}", o.reason);
    assert!(o.spike.is_none(), "no second maximum is found");
    assert!(o.p_max_err.unwrap() > 0.02, "{:?}", o.p_max_err);
}
