//! The point coarse grids' frozen band along the cavitation boundary (alpha_bar >= 5; a first
//! attempt freezes it from L = 25 on) and the fallback ladder's unfrozen rung: where the band leaves an error that the cycles hardly
//! reduce (thin piezoviscous films), the same cycles without the band converge, within their
//! algebraic error estimate of the iteration's converged answer.

use ehlmap::model::case::PointCase;
use ehlmap::solve::point::{solve_point, PointSolveParams};
use ehlmap::solve::Status;

fn params(grid: usize, fallback: bool) -> PointSolveParams {
    let mut p = PointSolveParams::default();
    p.mg.grid = grid;
    p.fallback = fallback;
    p
}

#[test]
fn a_thin_piezoviscous_film_that_the_band_loses_converges_without_it() {
    // M = 5720, L = 30, D = 0.215 on 513^2 (alpha_bar = L sqrt(M / 2 pi) = 905; from L = 25 on
    // the first attempt freezes the band): with the band the finest cycles run out of their
    // 40-cycle budget (measured 2026-11-28: 164.3 work units); the ladder's second rung, the
    // same cycles without the band, converges (32.7 work units). Deliberately tied to today's
    // first attempt failing here: if it learns to converge, move the test to another case.
    let case = PointCase::new(5720.0, 30.0, 0.215).unwrap();
    let first = solve_point(&case, &params(513, false)).outputs;
    assert_ne!(first.status, Status::Converged, "{}", first.reason);

    let laddered = solve_point(&case, &params(513, true));
    let o = &laddered.outputs;
    assert_eq!(o.status, Status::Converged, "{}", o.reason);
    assert_eq!(laddered.attempt, 2, "{}", o.reason);
    assert!(o.reason.contains("no frozen band"), "{}", o.reason);
    assert!(o.load_error.abs() < 1e-4, "load error {}", o.load_error);

    // The converged answer of the same iteration, run on for its whole cycle budget with the
    // algebraic error cap at 1e-5, is within the fast answer's algebraic error estimate
    // (measured 2026-12-01: H_c 8.94036 against 8.94611, 6.4e-4, H_min 1.4e-3, estimate
    // 2.3e-3).
    let mut on = params(513, false);
    on.mg.max_algebraic = 1e-5;
    on.mg.freeze_band = Some(false);
    let r = solve_point(&case, &on).outputs;
    let alg = o.algebraic_error.expect("an algebraic error estimate");
    for (a, b) in [(o.h_c, r.h_c), (o.h_min, r.h_min)] {
        let d = (a / b - 1.0).abs();
        eprintln!("fast {a} run on {b}: {d:.1e}, estimate {alg:.1e}");
        assert!(
            d <= alg && d < 1e-2,
            "{a} vs {b}: {d:.1e} (estimate {alg:.1e})"
        );
    }
}

#[test]
fn below_alpha_bar_five_the_ladder_has_no_unfrozen_rung() {
    // M = 20, L = 0.5 (alpha_bar = L sqrt(M / 2 pi) = 0.89): no band to unfreeze, so the rung
    // would repeat the first attempt; the ladder skips it and keeps its seven rungs.
    let case = PointCase::new(20.0, 0.5, 1.0).unwrap();
    let mut p = params(33, true);
    // One cycle: every rung fails, so the reason names the ladder's length.
    p.mg.max_cycles = 1;
    p.mg.fmg_cycles = 1;
    let s = solve_point(&case, &p);
    assert_ne!(s.outputs.status, Status::Converged, "{}", s.outputs.reason);
    assert!(s.outputs.reason.contains("of 7;"), "{}", s.outputs.reason);
    // With a band (L = 10: alpha_bar = 17.8) the ladder has eight rungs.
    let case = PointCase::new(20.0, 10.0, 1.0).unwrap();
    let s = solve_point(&case, &p);
    assert_ne!(s.outputs.status, Status::Converged, "{}", s.outputs.reason);
    assert!(s.outputs.reason.contains("of 8;"), "{}", s.outputs.reason);
}
