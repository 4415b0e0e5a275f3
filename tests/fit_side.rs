//! The point H_min formula through the centre line's minimum and the side-lobe factor
//! (`ehlmap::fit::side`), on `tests/data/fit-point-05`: the output of `sweeps/fit-point.toml`
//! (420 point cases, M 1 ... 1000 x 7 L x 4 D, each refined to a 0.5 % error estimate, with the
//! schema-7 columns `H_min_cl`, `H_min_cl_err`), committed.
//!
//! * The H_min law is the centre-line law times exp(-max(0, g)); its held-out errors are those of
//!   H_min, every case predicted by both parts fitted without its fold (measured 2026-12-06:
//!   4.33 % max, 0.92 % RMS with the lattice ridge 1e-1 chosen; 4.88 % / 1.01 % when the
//!   largest ridge offered was 1e-2; the NVM-form law fitted to H_min directly was 16.8 % / 3.54 % on
//!   the same rows, docs/validation.md), which is still above issue 24's 2 %.
//! * The factor alone is held out to 0.30 % RMS, 1.41 % max in ln F.
//! * The formula never puts H_min above the centre line's minimum, and equals it up to the
//!   largest M below every side lobe of the data (M_0 = 7.2), so in the rigid corner.

use ehlmap::fit::dataset::{load_fit_input, FitInput};
use ehlmap::report::fit_report;
use ehlmap::solve::film::Film;
use std::path::PathBuf;

fn input() -> FitInput {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/fit-point-05");
    let input = load_fit_input(&[dir]).unwrap();
    assert_eq!(input.point.len(), 420, "{:?}", input.excluded);
    input
}

#[test]
fn the_point_minimum_film_is_the_centre_line_law_times_the_side_lobe_factor() {
    let input = input();
    let with_cl = input
        .point
        .iter()
        .filter(|p| p.centre_line_min().is_some())
        .count();
    assert_eq!(with_cl, 420);
    let lobes = input
        .point
        .iter()
        .filter(|p| p.centre_line_min().unwrap() > 1.01 * p.h_min)
        .count();
    assert!(
        lobes > 100,
        "{lobes} cases with a side lobe 1 % below the centre line"
    );
    let r = fit_report(&input, false).unwrap().point;
    let q = r.h_min.as_ref().expect("H_min fitted");
    let side = q.model.side.as_ref().expect("a side-lobe factor");
    let choice = q.side.as_ref().expect("its held-out choice");
    // The factor alone, held out (ln F against ln(H_min / H_min,cl)).
    assert!(
        choice.rms < 0.004 && choice.max.abs() < 0.02,
        "{:?} {} {}",
        choice.chosen,
        choice.rms,
        choice.max
    );
    // H_min held out: every case, composed of both parts' fold fits.
    let h = q.heldout.as_ref().expect("held-out errors");
    assert_eq!(h.cases.len(), 420);
    assert!(
        h.chosen.max.abs() < 0.05 && h.chosen.rms < 0.011,
        "{} {}",
        h.chosen.max,
        h.chosen.rms
    );
    // Each held-out error is of H_min: its data film is the case's H_min.
    for c in &h.cases {
        let p = input
            .point
            .iter()
            .find(|p| p.m == c.m && p.l == c.l && p.d == Some(c.d))
            .unwrap();
        assert!((c.h.unwrap() / p.h_min - 1.0).abs() < 1e-12);
    }
    // In sample the formula meets 3 % at every case (measured 2.66 %: the ridge chosen by
    // held-out error, 1e-1, gives up some of the in-sample fit; 2.40 % with 1e-2).
    assert!(q.overall.max.abs() < 0.03, "{:?}", q.overall);
    // The factor never lifts the film and is 1 up to M_0 = 7.2 at every (L, D) (the data's side
    // lobes start at M = 11.8).
    let [m0, m1] = side.ramp.expect("a ramp").map(f64::exp);
    assert!(
        (m0 - 7.197).abs() < 1e-3 && (m1 - 11.788).abs() < 1e-3,
        "{m0} {m1}"
    );
    for p in &input.point {
        let f = side.factor(p.m, p.l, p.d.unwrap());
        assert!(f <= 1.0);
        if p.m < 7.2 {
            assert_eq!(f, 1.0, "{p:?}");
        }
    }
    assert_eq!(side.factor(1e-3, 10.0, 1.0), 1.0, "the rigid corner");
    // The centre-line law alone is not the H_min law where the side lobes are: at M = 1000,
    // L = 5, D = 1 the data's H_min is 0.37 times H_min,cl.
    let p = input
        .point
        .iter()
        .find(|p| p.m == 1000.0 && p.l == 5.0 && p.d == Some(1.0))
        .unwrap();
    let e = q.model.eval(p.m, p.l, 1.0) / p.film(Film::Minimum).unwrap() - 1.0;
    assert!(e.abs() < 0.03, "{e}");
    assert!(p.h_min / p.centre_line_min().unwrap() < 0.4);
}

#[test]
fn without_the_centre_line_column_h_min_is_fitted_directly() {
    let mut input = input();
    for p in &mut input.point {
        p.h_min_cl = None;
    }
    input.point.truncate(60);
    let r = fit_report(&input, false).unwrap().point;
    let q = r.h_min.as_ref().expect("H_min fitted");
    assert!(q.model.side.is_none() && q.side.is_none());
}
