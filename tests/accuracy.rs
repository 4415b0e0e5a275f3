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
