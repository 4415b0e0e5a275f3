//! The point elastic-isoviscous limit of `ehlmap::limits::point_ei` against the solver: the law is
//! the line's held limit (2.488 M^(-1/5)) carried over to the ellipse by the local inlet
//! analysis, so these solves are an independent check of it. Beyond the committed point data
//! (M <= 1000), at M = 3162 and L = 0, the solver's H_c over the law was 1.0140 (D = 0.1, 1025^2)
//! and 1.0006 (D = 0.25, 2049^2), falling towards 1 from 1.029 and 1.007 at M = 1000 (measured
//! 2026-12-07, docs/validation.md, "The point elastic-isoviscous limit"). Where the contact is
//! rounder the approach is slower (0.960 at M = 1e4, D = 1), so these two D are the check.
//!
//! The same solves check the H_pm formula that `ehlmap fit` derives from the committed 0.5 %
//! point data (`tests/data/fit-point-05`, 420 cases, M <= 1000): its H_EI is held at the law
//! times an approach factor fitted to the data's L = 0, M >= 100 cases, which tends to 1 as
//! M -> infinity. At M = 3162 the solver over the formula was 0.9995 (D = 0.1) and 0.9984
//! (D = 0.25) on these 1025^2 solves, 0.9997 at D = 0.25 on 2049^2 (docs/validation.md, "The
//! approach to the point elastic-isoviscous limit"); the fitted H_EI law it replaces was 2.4 %
//! and 2.1 % off there. Asserted: 0.5 %, issue 24's bound a decade beyond the data.
//! (H_c keeps a fitted law, 2.1 % off at D = 0.25: not asserted.)

use ehlmap::fit::dataset::load_fit_input;
use ehlmap::fit::fitted::Blend;
use ehlmap::limits::point_ei::{circular_over_line, ei_d_factor};
use ehlmap::model::case::{Elasticity, Models, PointCase};
use ehlmap::report::{fit_report, A_EI_CENTRAL};
use ehlmap::solve::point::PointSolveParams;
use ehlmap::solve::Status;
use ehlmap::strategy::accuracy::solve_point_to_accuracy;
use std::path::PathBuf;

/// The law's H_EI at (M, D).
fn law(m: f64, d: f64) -> f64 {
    A_EI_CENTRAL * circular_over_line() * ei_d_factor(d) * m.powf(-2.0 / 15.0)
}

#[test]
fn point_films_beyond_the_data_approach_the_limit_and_the_fitted_h_pm_formula() {
    let m = 3162.28;
    let models = Models {
        elasticity: Elasticity::Elastic,
        ..Models::default()
    };
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/fit-point-05");
    let input = load_fit_input(&[dir]).unwrap();
    let fit = fit_report(&input, false).unwrap();
    let h_pm = fit.point.h_pm.expect("point H_pm fitted").model;
    let Blend::Point(b) = &h_pm.blend else {
        panic!("a point blend")
    };
    assert!(b.ei_exact, "H_EI held at the law");
    assert!(b.x[16..22].iter().all(|c| *c != 0.0), "an approach factor");
    assert!(
        b.x[22..].iter().all(|c| *c == 0.0),
        "its third power only with anchors"
    );
    // g -> 1: far beyond the data the formula is the law (the correction and the kriging vanish
    // there too).
    for d in [0.1, 0.25, 1.0] {
        let far = h_pm.eval(1e9, 0.0, d) / law(1e9, d);
        assert!((far - 1.0).abs() < 5e-3, "M = 1e9, D = {d}: {far}");
    }
    for (d, tol) in [(0.1, 0.02), (0.25, 0.01)] {
        let case = PointCase::with_models(m, 0.0, d, models).unwrap();
        let o = solve_point_to_accuracy(&case, &PointSolveParams::default(), 0.004, 1025).outputs;
        assert_eq!(o.status, Status::Converged, "D = {d}: {}", o.reason);
        let estimate = o.error_estimate.expect("an error estimate");
        let r = o.h_c / law(m, d);
        let r_pm = o.h_c_pmax / law(m, d);
        eprintln!(
            "M = {m}, L = 0, D = {d} on {}^2: H_c / law {r:.4}, H_pm / law {r_pm:.4}, estimate {estimate:.2e}",
            o.grid
        );
        assert!(estimate <= 0.005, "D = {d}: {estimate}");
        assert!((r - 1.0).abs() <= tol, "D = {d}: {r}");
        assert!((r_pm - 1.0).abs() <= tol, "D = {d}: {r_pm}");
        let f_pm = o.h_c_pmax / h_pm.eval(m, 0.0, d);
        eprintln!("  solver / formula: H_pm {f_pm:.4}");
        assert!((f_pm - 1.0).abs() <= 0.005, "D = {d}: H_pm {f_pm}");
    }
}
