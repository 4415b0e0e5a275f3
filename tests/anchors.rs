//! The point approach factor fitted with anchors (src/limits/anchors.rs): the solver's L = 0 films
//! half a decade of M beyond the data pin it where the data stop, and a decade beyond the data
//! the formulas of H_pm and H_c (whose elastic-isoviscous law the anchors hold too, its corner
//! law fading beyond the data) follow the solver within issue 24's 0.5 %.
//!
//! `tests/data/fit-point-05-anchors.json` holds the anchors of `tests/data/fit-point-05` as
//! `ehlmap fit tests/data/fit-point-05 --no-limit-solves --anchor-solves FILE` wrote them
//! (M = 3162.28 at D = 0.1, 0.25, 0.5, 1; 513^2, 1025^2, 2049^2, Richardson; 30-43 s each on the
//! 2-core sandbox, 2026-12-07). The check a decade beyond the data solves its reference here.

use ehlmap::fit::dataset::load_fit_input;
use ehlmap::fit::fitted::Blend;
use ehlmap::fit::point_model::APPROACH_M0;
use ehlmap::limits::anchors::{cases, AnchorFile, ANCHOR_FACTOR};
use ehlmap::limits::beyond::BeyondSolves;
use ehlmap::report::fit_report;
use ehlmap::solve::film::Film;
use std::path::PathBuf;

#[test]
fn anchors_pin_the_approach_factor_and_the_formula_follows_the_solver_a_decade_beyond() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let mut input = load_fit_input(&[root.join("fit-point-05")]).unwrap();
    let text = std::fs::read_to_string(root.join("fit-point-05-anchors.json")).unwrap();
    let file: AnchorFile = serde_json::from_str(&text).unwrap();
    // The file's cases are those of the data (what `ehlmap fit --anchors` checks).
    let data: Vec<(f64, f64, f64)> = input.point.iter().map(|p| (p.m, p.l, p.dd())).collect();
    let want = cases(&data, 100.0);
    assert_eq!(want.len(), 4);
    for (a, w) in file.anchors.iter().zip(&want) {
        assert!((a.m / w.0 - 1.0).abs() < 1e-12 && a.d == w.1, "{a:?} {w:?}");
        assert!((a.m / (ANCHOR_FACTOR * 1000.0) - 1.0).abs() < 1e-12);
    }
    input.anchors = file.anchors.clone();
    let fit = fit_report(&input, false).unwrap();
    // A decade beyond the data (M = 1e4), against the solver extrapolated to zero spacing.
    let beyond = BeyondSolves::at(1e4, 0.25);
    for (film, q) in [
        (
            Film::PressureMax,
            fit.point.h_pm.expect("point H_pm fitted"),
        ),
        (Film::Centre, fit.point.h_c.expect("point H_c fitted")),
    ] {
        let Blend::Point(b) = &q.model.blend else {
            panic!("a point blend")
        };
        assert!(b.ei_exact, "{film:?}: the EI law held");
        assert_eq!(b.approach_m0, APPROACH_M0);
        assert!(
            b.x[22..].iter().any(|c| *c != 0.0),
            "{film:?}, the third power: {:?}",
            b.x
        );
        // The formula honours the anchors (their error bars are 0.03-0.11 %).
        for a in &file.anchors {
            let h = a.film(film).expect("an anchor film");
            let r = h / q.model.eval(a.m, 0.0, a.d);
            eprintln!("{film:?}, anchor D = {}: solver / formula {r:.5}", a.d);
            assert!((r - 1.0).abs() < 3e-3, "{film:?}, D = {}: {r}", a.d);
        }
        let s = beyond.of(film);
        let solver = s.solver.expect("the three solves converge");
        let r = solver / q.model.eval(1e4, 0.0, 0.25);
        eprintln!(
            "{film:?}, M = 1e4, D = 0.25: solver {solver:.5} +- {:.5}, solver / formula {r:.5}",
            s.error_bar.unwrap()
        );
        assert!((r - 1.0).abs() < 5e-3, "{film:?}: {r}");
        // g -> 1 far beyond: the held limit.
        assert!((b.approach(1e12, 0.25) - 1.0).abs() < 1e-3);
    }
}
