//! The line fit on `tests/data/fit-line` (the output of `sweeps/fit-line.toml`, committed: 598
//! line cases, M 0.1 ... 3000 (46, log) x 13 L in 0 ... 20, each refined to a 0.25 % error
//! estimate): the lattice correction against issue 24's held-out targets (1 % for every line film),
//! with the 5-fold held-out procedure of `ehlmap::fit::heldout`.
//!
//! * H_min meets the target: held-out max below 0.5 %, RMS below 0.1 %, with the half-spacing
//!   lattice (W = 0.375) chosen (measured 2026-12-03: 0.26 % / 0.04 %; with W = 0.75 only it
//!   was 0.65 % / 0.11 %).
//! * H_pm meets it too, on the rows whose pressure maximum is grid-converged: held-out max below
//!   0.5 %, RMS below 0.1 %, half-spacing lattice (0.25 % / 0.04 %; before 0.85 % / 0.12 %). Rows whose maximum is the outlet spike or whose P_max estimate
//!   (`P_max_err`) exceeds 2 % are not fitted (Barus spikes at L >= 8 that grow with the grid;
//!   the film under them is where the grid puts them).
//! * H_c meets it through its corner law (`ehlmap::fit::corner`): the film at X = 0 rises ever
//!   faster with M until it meets the film at the pressure maximum (M about 1.8 at L = 20) and
//!   follows it from there, a corner no smooth correction follows (the smooth lattice alone:
//!   held-out max 4.08 %, RMS 0.36 %). With the corner law: held-out max below 1 %, RMS below
//!   0.15 % (measured 2026-12-06: 0.74 % / 0.084 %, at M = 1.97, L = 4, just past the corner).
//!   Between the data, on the committed corner band `tests/data/fit-line-corner` (153 cases,
//!   never fitted), the corner law halves the smooth law's RMS error and cuts the cases above
//!   1 % at least threefold (0.57 % and 7 against 1.25 % and 44); its largest error there stays
//!   below 5 % (4.39 %, just past the corner, which the data's M spacing leaves unplaced).
//! * For every line film the lattice is chosen and beats the blend alone by more than a factor
//!   of 2 in held-out RMS.
//!
//! And the point fit on `tests/data/fit-point` (the nightly point sweep and its midpoints in M,
//! `sweeps/nightly-point.toml` and `nightly-point-mid.toml` on 513^2, 420 cases, committed), whose
//! lattice terms also come times ln D and (ln D)^2: H_c and H_pm choose the lattice, held out within 6 % max
//! and 1.5 % RMS (the nested terms: 18.7 % and 7.8 % max), which is not issue 24's 1 %, and
//! below 0.5 (H_c) and 0.7 (H_pm) times the blend alone's held-out RMS; H_min keeps the nested
//! terms. Point fits are offered the level-0 lattice only. The point H_c keeps its corner law
//! (bumps also times ln D and (ln D)^2): held-out RMS below 0.85 times the smooth law's, max
//! below 5 % (measured 2026-12-06: 0.67 % and 4.05 % against 0.85 % and 4.22 %).

use ehlmap::fit::dataset::{load_fit_input, peak_is_unresolved, spike_is_the_maximum};
use ehlmap::report::{fit_report, QuantityFit};
use std::path::PathBuf;

/// The line fit of `tests/data/fit-line`, checked on `tests/data/fit-line-corner` (the output
/// of `sweeps/fit-line-corner.toml`: 153 cases around the H_c corner, M 1.1 ... 2.8 a factor
/// 1.06 apart x L 4 ... 20, 0.25 %, never fitted).
fn fitted() -> ehlmap::report::ContactReport {
    let data = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let input = load_fit_input(&[data.join("fit-line")]).unwrap();
    assert_eq!(input.line.len(), 598, "{:?}", input.excluded);
    let check = load_fit_input(&[data.join("fit-line-corner")]).unwrap();
    assert_eq!(check.line.len(), 153, "{:?}", check.excluded);
    fit_report(&input.with_check(check).unwrap(), false)
        .unwrap()
        .line
}

/// The lattice level of the candidate kept (0 for nested terms).
fn level(q: &QuantityFit) -> u8 {
    q.heldout.as_ref().expect("held-out errors").chosen.level
}

/// Held-out max and RMS of the formula kept, the blend alone's RMS, and the ridge kept.
fn held_out(q: &QuantityFit) -> (f64, f64, f64, f64) {
    let h = q.heldout.as_ref().expect("held-out errors");
    let blend = h
        .joint
        .iter()
        .find(|s| s.terms == 0)
        .expect("the blend alone");
    (h.chosen.max.abs(), h.chosen.rms, blend.rms, h.chosen.ridge)
}

/// Prints the film's held-out errors, asserts that the lattice is chosen at less than half the
/// blend alone's held-out RMS, and returns the held-out max and RMS.
fn lattice_beats_the_blend(q: &QuantityFit) -> (f64, f64) {
    lattice_beats_the_blend_by(q, 0.5)
}

/// [`lattice_beats_the_blend`] with the RMS ratio `factor`.
fn lattice_beats_the_blend_by(q: &QuantityFit, factor: f64) -> (f64, f64) {
    let (max, rms, blend_rms, ridge) = held_out(q);
    eprintln!(
        "{}: held-out max {:.2} %, RMS {:.3} % (blend alone RMS {:.2} %), ridge {ridge:e}",
        q.quantity,
        100.0 * max,
        100.0 * rms,
        100.0 * blend_rms
    );
    assert!(ridge > 0.0, "{}: the lattice is chosen", q.quantity);
    assert!(
        rms < factor * blend_rms,
        "{}: {rms} vs {blend_rms}",
        q.quantity
    );
    (max, rms)
}

#[test]
fn the_line_fit_meets_the_held_out_targets_for_every_film() {
    let r = fitted();
    let (h_c, h_pm, h_min) = (
        r.h_c.as_ref().unwrap(),
        r.h_pm.as_ref().unwrap(),
        r.h_min.as_ref().unwrap(),
    );
    for q in [h_c, h_pm, h_min] {
        lattice_beats_the_blend(q);
    }
    let (max, rms, ..) = held_out(h_min);
    assert!(max < 0.005 && rms < 0.001, "H_min: {max} {rms}");
    let (max, rms, ..) = held_out(h_pm);
    assert!(max < 0.005 && rms < 0.001, "H_pm: {max} {rms}");
    for q in [h_c, h_pm, h_min] {
        assert_eq!(
            level(q),
            1,
            "{}: the half-spacing lattice is chosen",
            q.quantity
        );
        let c = &q.model.correction;
        assert!(c.terms.iter().all(|t| t.level == 1), "{}", q.quantity);
    }
    // H_pm is fitted exactly where the pressure maximum is a converged quantity (and its own
    // estimate is within 2 %); the unresolved peaks are more than the detected spikes.
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/fit-line");
    let rows = ehlmap::store::results::read_dataset(&dir).unwrap();
    let resolved = |r: &&ehlmap::store::results::CaseRow| {
        !spike_is_the_maximum(r)
            && !peak_is_unresolved(r)
            && r.h_c_pmax_err.is_some_and(|e| e <= 0.02)
    };
    let unresolved_only = rows
        .iter()
        .filter(|r| peak_is_unresolved(r) && !spike_is_the_maximum(r))
        .count();
    eprintln!(
        "H_pm fitted on {} of {} rows ({unresolved_only} left out for P_max_err alone)",
        h_pm.heldout.as_ref().unwrap().cases.len(),
        rows.len()
    );
    assert_eq!(
        h_pm.heldout.as_ref().unwrap().cases.len(),
        rows.iter().filter(resolved).count()
    );
    assert!(unresolved_only >= 20, "{unresolved_only}");
    // H_c through its corner: kept over the smooth law, within issue 24's 1 % held out.
    let corner = h_c.corner.as_ref().expect("the corner law is kept for H_c");
    assert!(h_c.model.corner.is_some());
    let (max, rms, ..) = held_out(h_c);
    eprintln!(
        "H_c with its corner: held-out max {:.2} %, RMS {:.3} %, ridges {:?}, {} of {} cases follow H_pm",
        100.0 * max,
        100.0 * rms,
        corner.ridges,
        corner.follows[0],
        corner.follows[1]
    );
    assert!(max < 0.01 && rms < 0.0015, "H_c: {max} {rms}");
    // Both sides of the corner are populated, and the corner sits where the data put it: at
    // L = 20, H_c follows H_pm from M = 1.97 on and not below M = 1.56.
    assert!(corner.follows[0] > 300 && corner.follows[1] - corner.follows[0] > 150);
    let law = h_c.model.corner.as_ref().unwrap();
    let h = |m: f64| law.h(h_c.model.blend.asymptotes(m, 20.0, 1.0), 1.0);
    assert!(h(1.56) > 0.02, "{}", h(1.56));
    assert!(h(1.97) <= 0.0, "{}", h(1.97));
    // Between the data, on the corner band: the corner law against the smooth law (the same
    // fit without its corner). Measured 2026-12-06: max 4.39 %, RMS 0.57 %, 7 of 153 cases above
    // 1 %, against 4.91 %, 1.25 %, 44 (the corner's place between the data's M = 1.56 and 1.97 is
    // the law's extrapolation: docs/known-limits.md).
    let stats = |e: &[f64]| {
        let rms = (e.iter().map(|v| v * v).sum::<f64>() / e.len() as f64).sqrt();
        let max = e.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        (max, rms, e.iter().filter(|v| v.abs() > 0.01).count())
    };
    let with: Vec<f64> = h_c.check.iter().map(|c| c.error).collect();
    assert_eq!(with.len(), 153);
    let mut smooth = h_c.model.clone();
    smooth.corner = None;
    let without: Vec<f64> = h_c
        .check
        .iter()
        .map(|c| smooth.eval(c.m, c.l, 1.0) / c.h.unwrap() - 1.0)
        .collect();
    let ((max, rms, above), (max0, rms0, above0)) = (stats(&with), stats(&without));
    eprintln!(
        "corner band: with the corner law max {:.2} %, RMS {:.2} %, {above} above 1 %; smooth law \
         {:.2} %, {:.2} %, {above0}",
        100.0 * max,
        100.0 * rms,
        100.0 * max0,
        100.0 * rms0
    );
    assert!(rms < 0.008 && rms < 0.6 * rms0, "{rms} {rms0}");
    assert!(above <= 12 && 3 * above <= above0, "{above} {above0}");
    assert!(max < 0.05, "{max}");
}

#[test]
fn the_point_lattice_cuts_the_held_out_errors_of_h_c_and_h_pm() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/fit-point");
    let input = load_fit_input(&[dir]).unwrap();
    assert_eq!(input.point.len() + input.excluded.len(), 420);
    let r = fit_report(&input, false).unwrap().point;
    // Measured 2026-11-29: H_c held out 5.09 % max, 1.17 % RMS (blend alone 3.76 %); H_pm 4.60 %,
    // 1.00 % (blend alone 1.54 %: the solver's rigid D factor made the blend better, so the
    // lattice's H_pm ratio is 0.65, no longer below the half it was asserted at before).
    for (q, factor) in [
        (r.h_c.as_ref().unwrap(), 0.5),
        (r.h_pm.as_ref().unwrap(), 0.7),
    ] {
        let (max, rms) = lattice_beats_the_blend_by(q, factor);
        assert!(max < 0.06 && rms < 0.015, "{}: {max} {rms}", q.quantity);
        assert_eq!(level(q), 0, "{}", q.quantity);
    }
    // The kriging residual on the smooth laws of H_pm and H_min (through the centre line): kept,
    // and lowering the held-out RMS and max by at least a sixth (measured 2026-12-06: H_pm 5.04
    // % / 0.82 % -> 3.45 % / 0.56 %; H_min, fitted directly on these data, 5.13 % / 0.84 % ->
    // 2.98 % / 0.54 %).
    for q in [r.h_pm.as_ref().unwrap(), r.h_min.as_ref().unwrap()] {
        let k = q.kriging.as_ref().expect("a kriging residual is kept");
        eprintln!(
            "{} with kriging: held-out max {:.2} %, RMS {:.3} %; without {:.2} %, {:.3} %",
            q.quantity,
            100.0 * k.max,
            100.0 * k.rms,
            100.0 * k.without_max,
            100.0 * k.without_rms
        );
        assert!(q.model.kriging.is_some());
        assert!(k.rms < 0.83 * k.without_rms && k.max < 0.83 * k.without_max);
        assert!(k.max < 0.04 && k.rms < 0.007, "{}: {k:?}", q.quantity);
    }
    // H_c through its corner: kept, its bumps times ln D and (ln D)^2, and its held-out RMS
    // below 0.85 times the smooth law's (measured 2026-12-06: max 4.05 %, RMS 0.67 % against
    // the smooth law's 4.22 %, 0.85 %, whose bumps are also times (ln D)^2; 4.37 %, 1.25 % with
    // ln D alone; 237 of 410 cases follow H_pm).
    let h_c = r.h_c.as_ref().unwrap();
    let corner = h_c
        .corner
        .as_ref()
        .expect("the corner law is kept for the point H_c");
    assert!(h_c.model.corner.is_some());
    assert_eq!(corner.ln_d_powers, 2);
    // The corner law carries a kriging residual too (measured 2026-12-06: 4.05 % / 0.672 % ->
    // 4.04 % / 0.563 % held out).
    let k = h_c.kriging.as_ref().expect("kriging on the corner law");
    assert!(
        h_c.model.kriging.is_some() && k.rms < 0.9 * k.without_rms,
        "{k:?}"
    );
    let h = h_c.heldout.as_ref().unwrap();
    let smooth = h
        .joint
        .iter()
        .find(|s| s.candidate == h.chosen.candidate)
        .expect("the smooth law's candidate");
    eprintln!(
        "point H_c with its corner: held-out max {:.2} %, RMS {:.3} %; smooth law {:.2} %, {:.3} %; \
         {} of {} cases follow H_pm",
        100.0 * h.chosen.max.abs(),
        100.0 * h.chosen.rms,
        100.0 * smooth.max.abs(),
        100.0 * smooth.rms,
        corner.follows[0],
        corner.follows[1]
    );
    assert!(
        h.chosen.rms < 0.85 * smooth.rms,
        "{} {}",
        h.chosen.rms,
        smooth.rms
    );
    assert!(h.chosen.max.abs() < 0.05, "{}", h.chosen.max);
}
