//! Model selection (`ehlmap::strategy::select`): each simplification is checked against the full model,
//! solved independently on two fine grids and Richardson-extrapolated (order 2), and the
//! reported error estimate must bound the true error.

mod common;

use common::point_reference;
use ehlmap::model::case::{LineCase, PointCase};
use ehlmap::solve::line::{solve_line, LineSolveParams};
use ehlmap::solve::point::PointSolveParams;
use ehlmap::solve::solution::{ModelUsed, Outputs};
use ehlmap::solve::Status;
use ehlmap::strategy::select::{solve_line_selected, solve_point_selected, Selection};

const TARGET: f64 = 0.01;

/// Full-model H_c and H_min on `grid` and its half grid, Richardson order 2.
fn line_reference(c: &LineCase, grid: usize) -> (f64, f64) {
    let solve = |g: usize| {
        let mut p = LineSolveParams::default();
        p.mg.grid = g;
        let o = solve_line(c, &p).outputs;
        assert_eq!(
            o.status,
            Status::Converged,
            "reference M={} L={}: {}",
            c.m,
            c.l,
            o.reason
        );
        (o.h_c, o.h_min)
    };
    let (a, b) = (solve((grid - 1) / 2 + 1), solve(grid));
    (b.0 + (b.0 - a.0) / 3.0, b.1 + (b.1 - a.1) / 3.0)
}

/// The selected answer is within the target of the reference, and its estimate bounds the error.
fn check(label: &str, got: (f64, f64), est: f64, reference: (f64, f64)) {
    let err = ((got.0 / reference.0 - 1.0).abs()).max((got.1 / reference.1 - 1.0).abs());
    println!("{label}: error {err:.2e}, estimate {est:.2e}");
    assert!(err < TARGET, "{label}: error {err} above the target");
    assert!(err <= est, "{label}: error {err} above the estimate {est}");
}

#[test]
fn line_simplifications_match_the_full_model() {
    // (M, L, the model the selection must pick)
    let cases = [
        (0.05, 1.0, ModelUsed::ClosedForm),
        (0.1, 0.0, ModelUsed::ClosedForm),
        (100.0, 0.001, ModelUsed::Isoviscous),
    ];
    for (m, l, want) in cases {
        let c = LineCase::new(m, l).unwrap();
        let (s, sel) = solve_line_selected(&c, &LineSolveParams::default(), TARGET, 4097);
        let o = &s.outputs;
        assert_eq!(sel.model, want, "M={m} L={l}: {}", o.reason);
        assert_eq!(o.model_used, want.as_str());
        assert_eq!(o.status, Status::Converged, "{}", o.reason);
        let est = o.error_estimate.expect("an estimate");
        check(
            &format!("line M={m} L={l} {want}"),
            (o.h_c, o.h_min),
            est,
            line_reference(&c, 2049),
        );
    }
}

#[test]
fn the_check_grid_rejects_what_the_screen_gets_wrong() {
    // Moes' blend puts the piezoviscous effect at M = 0.05, L = 5 near 1.5e-4 (closed form would
    // pass the screen); the solver measures about 4e-3 on the check grid, above half the target,
    // so the full model is solved.
    let c = LineCase::new(0.05, 5.0).unwrap();
    let (s, sel) = solve_line_selected(&c, &LineSolveParams::default(), TARGET, 4097);
    assert!(sel.piezo_effect < 1e-3, "{sel:?}");
    assert_eq!(sel.model, ModelUsed::Full, "{}", s.outputs.reason);
    assert!(sel.measured.unwrap() > 0.5 * TARGET, "{sel:?}");
    // A typical EHL case needs everything and pays for no check.
    let c = LineCase::new(20.0, 10.0).unwrap();
    let (s, sel) = solve_line_selected(&c, &LineSolveParams::default(), TARGET, 4097);
    assert_eq!(sel.model, ModelUsed::Full);
    assert!(sel.measured.is_none() && s.outputs.model_used == "full");
    // The closed form where even the full check fails (M = 0.01): Martin's film exactly.
    let c = LineCase::new(0.01, 0.0).unwrap();
    let (s, sel) = solve_line_selected(&c, &LineSolveParams::default(), TARGET, 4097);
    assert_eq!(sel.model, ModelUsed::ClosedForm, "{}", s.outputs.reason);
    assert!((s.outputs.h_c * 0.01 / 2.4475 - 1.0).abs() < 1e-12);
    assert!(s.outputs.level.is_none() && s.outputs.error_estimate.unwrap() < TARGET);
}

/// The selected answer of a point case at the 1 % target (grids up to `max_grid`), which must
/// come from model `want` and have converged.
fn selected_point(c: &PointCase, max_grid: usize, want: ModelUsed) -> (Outputs, Selection) {
    let (s, sel) = solve_point_selected(c, &PointSolveParams::default(), TARGET, max_grid);
    let o = s.outputs;
    assert_eq!(sel.model, want, "{}", o.reason);
    assert_eq!(o.status, Status::Converged, "{}", o.reason);
    (o, sel)
}

#[test]
fn point_isoviscous_selection_matches_the_full_model() {
    let c = PointCase::new(100.0, 0.001, 1.0).unwrap();
    // (1 % needs 513^2 here: 257^2 estimates 1.5 %, and 33^2 does not resolve the film.)
    let (o, _) = selected_point(&c, 513, ModelUsed::Isoviscous);
    assert!(o.level.is_some());
    check(
        "point M=100 L=0.001 D=1",
        (o.h_c, o.h_min),
        o.error_estimate.unwrap(),
        // (the reference finer than the answer's 513^2)
        point_reference(&c, 1025).0,
    );
}

#[test]
fn a_simplified_answer_meets_the_target_with_its_neglected_effect() {
    // Point M = 7.56, L = 30, D = 0.046 (issue 22's point box): the rigid model is kept, its
    // measured neglected effect (3.4e-3) plus the domain-truncation estimate (4.5e-3) leave
    // 2.1e-3 of the 1 % target to the grid, so the rigid solve must refine past 257^2 (whose
    // 3.5e-3 would have reported 1.14 % against the 1 % target).
    let c = PointCase::new(7.56346075264, 30.0, 0.0464158883361).unwrap();
    let (o, sel) = selected_point(&c, 1025, ModelUsed::Rigid);
    let neglected = sel.measured.expect("measured on the check grid");
    assert!(
        neglected > 0.2 * TARGET && neglected < 0.5 * TARGET,
        "{sel:?}"
    );
    let est = o.error_estimate.unwrap();
    // The target is met by the answer as reported (the neglected effect included).
    assert_eq!(o.accuracy_met, Some(true), "{}", o.reason);
    assert!(
        est <= TARGET,
        "estimate {est} above the target: {}",
        o.reason
    );
    assert!(
        est >= neglected,
        "estimate {est} without the neglected effect"
    );
    check(
        "point M=7.56 L=30 D=0.046 rigid",
        (o.h_c, o.h_min),
        est,
        point_reference(&c, 513).0,
    );
}
