//! Warm starts (`ehlmap::strategy::warm`): a line solve started on the finest level from a solved
//! neighbour's pressure converges to the same solution as the cold FMG solve, whatever the
//! guess's film level; neighbour cases get their own ids.

use ehlmap::model::case::LineCase;
use ehlmap::solve::line::{solve_line, solve_line_from, warm_guess, LineSolveParams};
use ehlmap::solve::params::Converge;
use ehlmap::solve::Status;

fn params(grid: usize) -> LineSolveParams {
    let mut p = LineSolveParams::default();
    p.mg.grid = grid;
    // Warm and cold starts reach the same discrete solution when both converge tightly.
    p.mg.converge = Converge::Tight;
    p.keep_fields = true;
    p
}

#[test]
fn warm_start_from_lower_m_reaches_the_cold_solution() {
    for (m, l) in [(100.0, 10.0), (1000.0, 20.0), (20.0, 2.0)] {
        let p = params(1025);
        let case = LineCase::new(m, l).unwrap();
        let cold = solve_line(&case, &p);
        assert_eq!(cold.info.status, Status::Converged, "{}", cold.info.reason);
        let nb = LineCase::new(m / 2.0, l).unwrap();
        let from = solve_line(&nb, &p);
        assert_eq!(from.info.status, Status::Converged);
        let mut guess = warm_guess(&case, &nb, &from).expect("a guess");
        let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
        // The guess is the neighbour's pressure at a film level of its own, not this case's.
        assert!(
            (guess.centre_film * 8.0 * m / std::f64::consts::PI / cold.outputs.h_c - 1.0).abs()
                < 0.1
        );
        for scale in [1.0, 1.3, 0.8] {
            let mut g = guess.clone();
            g.centre_film *= scale;
            let warm = solve_line_from(&case, &p, Some(&g));
            assert_eq!(warm.info.status, Status::Converged, "{}", warm.info.reason);
            // No coarser level to estimate from: never a NaN in the reason.
            assert!(!warm.info.reason.contains("NaN"), "{}", warm.info.reason);
            assert!(
                rel(warm.outputs.h_c, cold.outputs.h_c) < 1e-5,
                "M {m} L {l} x{scale}"
            );
            assert!(
                rel(warm.outputs.h_min, cold.outputs.h_min) < 1e-4,
                "M {m} L {l} x{scale}"
            );
            // Started from the guess, not the FMG ascent: a different cost.
            assert!(warm.info.work_units != cold.info.work_units);
        }
        // The default stopping rule from a guess: no coarser level to estimate the
        // discretisation error from, so the cycles run to the tolerance and say so (the reason
        // once printed "a tenth of the discretisation error NaN").
        let mut fast = p;
        fast.mg.converge = Converge::Fast;
        let warm = solve_line_from(&case, &fast, Some(&guess));
        assert_eq!(warm.info.status, Status::Converged, "{}", warm.info.reason);
        assert!(
            warm.info.reason.contains("no coarser level") && !warm.info.reason.contains("NaN"),
            "{}",
            warm.info.reason
        );
        assert!(rel(warm.outputs.h_c, cold.outputs.h_c) < 1e-4);
        guess.p.clear();
        guess.x.clear();
        // An empty guess (zero pressure) still ends converged or with a status, never a panic.
        let _ = solve_line_from(&case, &p, Some(&guess)).info.status;
    }
}

/// The sweep's row for a case that fails cold: the warm-start chain runs (its cost is counted),
/// and when it does not converge either the cold result stands with `warm_start` null. A case
/// that converges cold is not warm-started and costs one solve.
#[test]
fn sweep_rows_count_the_warm_start_chain() {
    use ehlmap::sweep::{
        plan::plan,
        row::{solve_case, solve_params},
        spec::parse,
    };
    let spec = |cycles: usize| {
        let text = format!(
            "contact = \"line\"\n[axes]\nM = [20]\nL = [5]\n[numerics]\ngrid = 257\nmax_cycles = {cycles}\n"
        );
        plan(&parse("w.toml", &text, "w").unwrap())
            .unwrap()
            .remove(0)
    };
    let cold = |c: &ehlmap::sweep::plan::Case| {
        solve_line(&c.line_case().unwrap(), &solve_params(c, 257).line_params())
    };
    let failing = spec(1);
    let c = cold(&failing);
    assert_ne!(
        c.info.status,
        Status::Converged,
        "one cycle should not converge"
    );
    let row = solve_case(&failing, "w", None);
    assert_eq!(row.status, c.info.status.as_str());
    assert_eq!(row.warm_start, None);
    // The cost is the cold ladder's plus the whole chain's (recomputed here: deterministic).
    let mut spent = (0.0, 0.0);
    let p = solve_params(&failing, 257).line_params();
    assert!(
        ehlmap::strategy::warm::warm_start_line(&failing.line_case().unwrap(), &p, &mut spent)
            .is_none()
    );
    assert!(spent.0 > 0.5 * c.info.work_units, "{spent:?}");
    let expect = c.info.work_units + spent.0;
    let got = row.work_units.unwrap();
    assert!((got - expect).abs() < 1e-9 * expect, "{got} {expect}");
    assert_eq!(row.h_c, Some(c.outputs.h_c));

    let fine = spec(60);
    let c = cold(&fine);
    let row = solve_case(&fine, "w", None);
    assert_eq!(row.status, "converged");
    assert_eq!(row.warm_start, None);
    assert_eq!(row.work_units, Some(c.info.work_units));
    assert_eq!(row.h_c, Some(c.outputs.h_c));
}
