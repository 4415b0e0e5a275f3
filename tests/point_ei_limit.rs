//! The point elastic-isoviscous limit of `ehlmap::limits::point_ei` against the solver: the law is
//! the line's held limit (2.488 M^(-1/5)) carried over to the ellipse by the local inlet
//! analysis, so these solves are an independent check of it. Beyond the committed point data
//! (M <= 1000), at M = 3162 and L = 0, the solver's H_c over the law was 1.0140 (D = 0.1, 1025^2)
//! and 1.0006 (D = 0.25, 2049^2), falling towards 1 from 1.029 and 1.007 at M = 1000 (measured
//! 2026-12-07, docs/validation.md, "The point elastic-isoviscous limit"). Where the contact is
//! rounder the approach is slower (0.960 at M = 1e4, D = 1), so these two D are the check.

use ehlmap::limits::point_ei::{circular_over_line, ei_d_factor};
use ehlmap::model::case::{Elasticity, Models, PointCase};
use ehlmap::report::A_EI_CENTRAL;
use ehlmap::solve::point::PointSolveParams;
use ehlmap::solve::Status;
use ehlmap::strategy::accuracy::solve_point_to_accuracy;

/// The law's H_EI at (M, D).
fn law(m: f64, d: f64) -> f64 {
    A_EI_CENTRAL * circular_over_line() * ei_d_factor(d) * m.powf(-2.0 / 15.0)
}

#[test]
fn slender_point_films_beyond_the_data_approach_the_carried_over_line_limit() {
    let m = 3162.28;
    let models = Models {
        elasticity: Elasticity::Elastic,
        ..Models::default()
    };
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
    }
}
