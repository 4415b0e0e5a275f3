//! The time split of a multigrid solve (`SolveInfo::phases`, issue 21's per-work-unit cost): the
//! phases do not overlap (their sum is within the solve's wall time), every phase a solve runs
//! is charged, a rigid solve runs no deformation product, the split covers the solve's own work
//! units, and timing never changes a result (two solves give the same bits).

use ehlmap::model::case::{Elasticity, LineCase, Models, PointCase};
use ehlmap::solve::line::{solve_line, LineSolveParams};
use ehlmap::solve::phases::PhaseTimes;
use ehlmap::solve::point::{solve_point, PointSolveParams};
use ehlmap::solve::solution::Solution;
use ehlmap::solve::Status;

fn rigid() -> Models {
    Models {
        elasticity: Elasticity::Rigid,
        ..Default::default()
    }
}

/// The checks every converged solve's split meets; `elastic`: deformation products ran.
fn check(t: &PhaseTimes, wall_s: f64, work_units: f64, elastic: bool, what: &str) {
    for (name, v) in [
        ("relaxation", t.relaxation),
        ("residual", t.residual),
        ("transfers", t.transfers),
        ("coarsest", t.coarsest),
    ] {
        assert!(v > 0.0 && v.is_finite(), "{what}: {name} {v} ({t:?})");
    }
    if elastic {
        assert!(t.deformation > 0.0, "{what}: no deformation time ({t:?})");
    } else {
        assert_eq!(
            t.deformation, 0.0,
            "{what}: a rigid solve ran a deformation product"
        );
    }
    // No phase is counted twice: the measured phases fit in the solve's wall time, which fits in
    // the info's (the info adds the solution's post-processing).
    assert!(t.measured() <= t.total * (1.0 + 1e-12), "{what}: {t:?}");
    assert!(
        t.total > 0.0 && t.total <= wall_s * (1.0 + 1e-12),
        "{what}: {t:?} wall {wall_s}"
    );
    // The phases cover the solve: what they leave (set-up, the stopping rule) is a small part.
    assert!(t.other() < 0.25 * t.total, "{what}: {t:?}");
    assert_eq!(
        t.work_units, work_units,
        "{what}: the split's own work units"
    );
    let per = t.per_work_unit();
    assert!((per.total * t.work_units - t.total).abs() <= 1e-12 * t.total);
}

/// Solve twice: the first solve's split passes [`check`], and both give the same bits.
fn check_twice(solve: impl Fn() -> Solution, elastic: bool, what: &str) {
    let a = solve();
    assert_eq!(
        a.info.status,
        Status::Converged,
        "{what}: {}",
        a.info.reason
    );
    check(
        &a.info.phases,
        a.info.wall_s,
        a.info.work_units,
        elastic,
        what,
    );
    let b = solve();
    assert_eq!(a.outputs.h_c.to_bits(), b.outputs.h_c.to_bits(), "{what}");
    assert_eq!(
        a.outputs.h_min.to_bits(),
        b.outputs.h_min.to_bits(),
        "{what}"
    );
    assert_eq!(a.info.work_units, b.info.work_units, "{what}");
}

#[test]
fn point_solves_split_their_time_without_overlap() {
    // Elastic piezoviscous, and rigid isoviscous (the rigid regime's own case).
    for (m, l, models, elastic) in [
        (20.0, 10.0, Models::default(), true),
        (1.0, 0.0, rigid(), false),
    ] {
        let case = PointCase::with_models(m, l, 1.0, models).expect("valid case");
        let mut p = PointSolveParams::default();
        p.mg.grid = 65;
        let what = format!("point 65^2 elastic {elastic}");
        check_twice(|| solve_point(&case, &p), elastic, &what);
    }
}

#[test]
fn line_solves_split_their_time_without_overlap() {
    for (case, elastic) in [
        (LineCase::new(20.0, 10.0).expect("valid case"), true),
        (
            LineCase::with_models(1.0, 0.0, rigid()).expect("valid case"),
            false,
        ),
    ] {
        let mut p = LineSolveParams::default();
        p.mg.grid = 1025;
        let what = format!("line 1025 elastic {elastic}");
        check_twice(|| solve_line(&case, &p), elastic, &what);
    }
}
