//! Slender elliptic contacts answered by a line contact (`ehlmap::strategy::slender`): the gap bound is
//! checked on a validation set that was not used to set it, against point solves on 129^2 and
//! 257^2 nodes extrapolated (Richardson, order 2), and the selection picks the line model only
//! inside its gate, with an answer within the target of the point reference.

mod common;

use common::point_reference;
use ehlmap::model::case::PointCase;
use ehlmap::solve::line::{solve_line, LineSolveParams};
use ehlmap::solve::point::PointSolveParams;
use ehlmap::solve::solution::ModelUsed;
use ehlmap::solve::Status;
use ehlmap::strategy::select::solve_point_selected;
use ehlmap::strategy::slender::{equivalent_line, gap_bound, point_outputs};

fn gap(got: (f64, f64), reference: (f64, f64)) -> f64 {
    (got.0 / reference.0 - 1.0)
        .abs()
        .max((got.1 / reference.1 - 1.0).abs())
}

#[test]
fn gap_bound_holds_on_the_validation_set() {
    // (M, L, D): none of these set the bound (see the table in src/slender.rs).
    let mut real = 0;
    for (m, l, d) in [(500.0, 15.0, 0.03), (250.0, 0.0, 0.07), (120.0, 10.0, 0.02)] {
        let pc = PointCase::new(m, l, d).unwrap();
        let bound = gap_bound(&pc).expect("inside the gate");
        let mut lp = LineSolveParams::default();
        lp.mg.grid = 4097;
        let line = solve_line(&equivalent_line(&pc), &lp).outputs;
        assert_eq!(line.status, Status::Converged, "{}", line.reason);
        let o = point_outputs(&pc, &line);
        let (reference, change) = point_reference(&pc, 513);
        let g = gap((o.h_c, o.h_min), reference);
        println!("M={m} L={l} D={d}: gap {g:.4}, bound {bound:.4}, point 257->513 {change:.4}");
        assert!(
            g <= bound,
            "M={m} L={l} D={d}: gap {g} above the bound {bound}"
        );
        // A real gap: larger than 0.5 % and than the reference's own 257 -> 513 change. (Its
        // sign is not fixed: with the far field the point film at M = 120, L = 10, D = 0.02
        // lies above the line's; on the truncated domain, 1.4 % low at that D, it lay below.
        // Since the far film carries the load's deformation, M = 500, L = 15, D = 0.03 agrees
        // with the line within its reference's resolution: 0.43 % against a 0.43 % change.)
        if g > 0.005 && change < g {
            real += 1;
        }
    }
    assert!(
        real >= 2,
        "the bound is tested against real gaps in {real} cases only"
    );
}

#[test]
fn selection_uses_the_line_model_only_inside_its_gate() {
    // Bound 1.95 % at (120, 10, 0.02): a 6 % target takes the line model.
    let target = 0.06;
    let pc = PointCase::new(120.0, 10.0, 0.02).unwrap();
    let (s, sel) = solve_point_selected(&pc, &PointSolveParams::default(), target, 129);
    let o = &s.outputs;
    assert_eq!(sel.model, ModelUsed::SlenderLine, "{}", o.reason);
    assert_eq!(o.model_used, "slender-line");
    assert_eq!(o.status, Status::Converged);
    assert!(
        o.reason.contains("slender-contact gap bound"),
        "{}",
        o.reason
    );
    assert_eq!((o.d, o.y_min), (Some(0.02), Some(0.0)));
    let (reference, _) = point_reference(&pc, 257);
    let err = gap((o.h_c, o.h_min), reference);
    let est = o.error_estimate.unwrap();
    println!("slender-line: error {err:.4}, estimate {est:.4}");
    assert!(err < target && err <= est, "error {err}, estimate {est}");
    // Not at 1 % (the bound is above half the target), not at D = 0.2, not at M = 10 (the
    // equivalent line case is rigid-like and the point film is 6 times the line film).
    for (m, d, t) in [(120.0, 0.02, 0.01), (1000.0, 0.2, 0.2), (10.0, 0.02, 0.2)] {
        let pc = PointCase::new(m, 10.0, d).unwrap();
        let (s, sel) = solve_point_selected(&pc, &PointSolveParams::default(), t, 65);
        assert_ne!(sel.model, ModelUsed::SlenderLine, "M={m} D={d}");
        assert_ne!(s.outputs.model_used, "slender-line");
    }
}

#[test]
fn sweep_rows_of_the_line_model_are_valid_and_say_so() {
    let (dir, _, out) = common::sweep_in_temp(
        "slender",
        "sl",
        "name = \"sl\"\ncontact = \"point\"\n[axes]\nM = [1000]\nL = [0]\nD = [0.02, 0.5]\n\
         [numerics]\ngrid = 33\naccuracy = 0.05\n",
    );
    let log = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{log}");
    assert!(log.contains("slender-line 1"), "{log}");
    let rows = ehlmap::store::results::read_dataset(&dir.join("sl")).unwrap();
    assert_eq!(rows.len(), 2);
    for r in &rows {
        if r.d == Some(0.02) {
            assert_eq!(r.status, "converged", "{}", r.reason);
            assert!(r.valid, "{}", r.reason);
            // Bound 1.3 % < half the target; H0 and f have no point meaning: null, still valid.
            assert_eq!(r.model_used, "slender-line");
            assert!(r.h0.is_none() && r.f.is_none() && r.p_max.is_some());
            assert!(
                r.h_c.unwrap() > 0.0 && r.grid.unwrap() >= 257,
                "{:?}",
                r.grid
            );
        } else {
            // M = 1000, D = 0.5 is not resolved by 33^2 (a film <= 0): said so, not valid,
            // never called converged. (65^2 gives a positive film since thin films have the
            // narrower sides and a 33^2 coarsest grid, src/discrete/point/domain.rs.)
            assert_ne!(r.model_used, "slender-line");
            assert_eq!(r.status, "under-resolved", "{}", r.reason);
            assert!(!r.valid, "{}", r.reason);
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}
