//! The fit report on a small dataset made by ehlmap itself (`tests/data/smoke-line`: the smoke
//! sweep, 36 line cases on 2049 points, committed): the fitted formula beats Moes 1992 on the
//! same cases, its exponents are physical, and bad datasets give clear errors. Rows whose
//! Richardson error estimate exceeds 2 % (the four M = 1000 cases of this dataset, 2.7 to 3.9 %)
//! are left out and listed; the fit uses the other 32.

use ehlmap::fit::dataset::load_fit_input;
use ehlmap::fit::stats::{err_stats, target_range};
use ehlmap::report::markdown::to_markdown;
use ehlmap::report::{fit_report, Film, FitInput, FitPoint};
use std::path::PathBuf;
use std::process::Command;

fn data() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/smoke-line")
}

#[test]
fn fitted_formula_beats_moes_on_the_committed_dataset() {
    let input = load_fit_input(&[data()]).unwrap();
    assert_eq!(input.line.len(), 32);
    assert_eq!(input.excluded.len(), 4, "{:?}", input.excluded);
    assert!(input.excluded.iter().all(|e| e.contains("M = 1000.0000")));
    assert_eq!(input.failed_line, 0);
    assert!(input.point.is_empty());
    let r = fit_report(&input, false).unwrap();
    let r = r.line;
    assert!(r.skipped.is_none());
    let moes = r.published[0].overall.as_ref().unwrap();
    assert_eq!(r.published[0].name, "Moes 1992");
    assert_eq!(r.published[0].against, "H_c");
    let moes_pm = r.published[1].overall.as_ref().unwrap();
    assert_eq!(
        (
            r.published[1].name.as_str(),
            r.published[1].against.as_str()
        ),
        ("Moes 1992", "H_pm")
    );
    // Dowson-Toyoda needs G, which the dataset does not carry.
    assert_eq!(
        r.published[2].skipped.as_deref(),
        Some("skipped: dataset has no G")
    );
    let (h_c, h_min) = (r.h_c.as_ref().unwrap(), r.h_min.as_ref().unwrap());
    println!(
        "fit H_c max {:+.3}, H_min max {:+.3}, Moes max {:+.3}",
        h_c.overall.max, h_min.overall.max, moes.max
    );
    // Measured on the 32 cases: fit 2.4 % (H_c), 1.3 % (H_min); Moes 1992 5.9 % (8.0 % with
    // the four excluded M = 1000 rows).
    assert!(h_c.overall.max.abs() < 0.03, "{:?}", h_c.overall);
    assert!(h_min.overall.max.abs() < 0.03, "{:?}", h_min.overall);
    assert!(h_c.overall.max.abs() < moes.max.abs());
    assert!(h_c.overall.rms < moes.rms);
    // Elastic-isoviscous exponent near Moes' -1/5 and piezoviscous exponent of L near 3/4.
    let p = |name: &str| h_c.params.iter().find(|p| p.name == name).unwrap().value;
    assert!((p("alpha_EI") + 0.2).abs() < 0.06, "{}", p("alpha_EI"));
    assert!((p("delta_EP") - 0.75).abs() < 0.1, "{}", p("delta_EP"));
    assert!(h_c.params.iter().all(|p| p.sigma.is_finite()));
    // The film at the pressure maximum (Moes' central film, H_RI = 3/M): measured 1.60 % max
    // against Moes' 5.86 % on the same film.
    let h_pm = r.h_pm.as_ref().unwrap();
    assert_eq!(h_pm.quantity, "H_pm");
    assert!(h_pm.overall.max.abs() < 0.02, "{:?}", h_pm.overall);
    assert!(h_pm.overall.max.abs() < 0.5 * moes_pm.max.abs());
    assert!(h_pm.overall.rms < 0.5 * moes_pm.rms);
}

/// The line limit solves (rigid M = 1; elastic at the largest M, L = 0 and L = 10; 4097 points)
/// against the fitted asymptotes of each film. Independent references: Martin's exact rigid
/// films, 2.4475/M at X = 0 and 3/M at the pressure maximum.
#[test]
fn line_asymptotes_agree_with_the_limit_solves() {
    let input = load_fit_input(&[data()]).unwrap();
    let full = fit_report(&input, true).unwrap();
    let md = to_markdown(&full);
    let r = full.line;
    let check = |film: &str, name: &str| {
        r.asymptotes
            .iter()
            .find(|a| a.quantity == film && a.asymptote == name)
            .unwrap_or_else(|| panic!("{film} {name} missing"))
    };
    assert_eq!(
        r.asymptotes.len(),
        15,
        "four asymptotes and the EP limit for each of three films"
    );
    let ri_c = check("H_c", "rigid-isoviscous");
    assert!((ri_c.solver.unwrap() - 2.4475).abs() < 0.005);
    let ri_pm = check("H_pm", "rigid-isoviscous");
    assert!((ri_pm.solver.unwrap() - 3.0).abs() < 0.006);
    // Line limit solves are refined to a 0.2 % estimate (the rigid one stops on 2049 points).
    assert!(ri_pm.grid.is_some_and(|g| g >= 1025), "{:?}", ri_pm.grid);
    // The EI law is held at the solver's own limit (2.488 M^-1/5, 1.984 for H_min, from solves
    // beyond the nightly data): its ratio falls toward 1 over the data (H_pm 1.0184, 1.0073,
    // 1.0014 at M = 50, 158, 500) and is within 0.5 % at the data's largest M.
    for film in ["H_c", "H_pm", "H_min"] {
        let ei = check(film, "elastic-isoviscous");
        let r = ei.ratio.unwrap();
        assert!((r - 1.0).abs() < 0.005, "{film} EI ratio {r}");
        assert!(
            ei.trend.windows(2).all(|w| w[1].1 < w[0].1),
            "{:?}",
            ei.trend
        );
    }
    for (name, tol) in [("elastic-isoviscous", 0.03), ("elastic-piezoviscous", 0.06)] {
        let t = &check("H_pm", name).trend;
        assert_eq!(t.len(), 3, "{name} trend {t:?}");
        assert!(
            t.iter().all(|(_, r)| (r - 1.0).abs() < tol),
            "{name} trend {t:?}"
        );
    }
    // The RP law is held at the rigid limit B_RP_CENTRAL L^(2/3) (times 3/2.4475 for H_pm): the
    // check's own rigid solve (alpha q_max = 1 at L = 10) agrees with that constant.
    for film in ["H_c", "H_pm", "H_min"] {
        let rp = check(film, "rigid-piezoviscous").ratio.unwrap();
        assert!((rp - 1.0).abs() < 0.005, "{film} RP ratio {rp}");
    }
    // The EP law is held at the solver's limit (D_EP_CENTRAL M^(-1/8) L^(3/4), from solves at
    // M = 1e4 and L up to 80). At the data's corner (M = 500, L = 10) the EI law still adds to
    // the film, so the solver lies above the limit (measured H_pm 1.0540); beyond the data, at
    // twice the largest L, that share falls (like L^-3/4) and the ratio moves toward 1 (1.0170).
    // (When d was fitted this test asked the L = 20 ratio to be within 1 % of 1, measured
    // 0.9994: the fitted law passed between the data's corner and the limit.)
    let ep = check("H_pm", "elastic-piezoviscous");
    let (l2, beyond) = ep.beyond.expect("EP solve at twice the largest L");
    let beyond = beyond.expect("converged");
    assert_eq!(l2, 20.0);
    let at_corner = ep.ratio.unwrap();
    assert!(
        beyond > 1.0 && beyond < 1.025 && beyond - 1.0 < 0.4 * (at_corner - 1.0),
        "beyond {beyond}, at the corner {at_corner}"
    );
    assert!(check("H_pm", "elastic-isoviscous").beyond.is_none());
    // The EP limit itself, re-derived from fresh solves at M = 1e4, L = 20, 40, 80 on 65537
    // points (src/limits/line_ep.rs): the held constant within 0.5 % (measured 1.0001 for H_c
    // and H_pm, 0.9999 for H_min), the ratio at each L falling toward 1 (H_c 1.0190, 1.0088,
    // 1.0041).
    for film in ["H_c", "H_pm", "H_min"] {
        let row = r
            .asymptotes
            .iter()
            .find(|a| a.quantity == film && a.trend_over == "L")
            .unwrap_or_else(|| panic!("{film}: no EP limit row"));
        assert_eq!(
            (row.asymptote.as_str(), row.m),
            ("elastic-piezoviscous", 1e4)
        );
        let ratio = row.ratio.expect("the three limit solves converged");
        assert!((ratio - 1.0).abs() < 5e-3, "{film} EP limit {ratio}");
        let t: Vec<f64> = row.trend.iter().map(|p| p.1).collect();
        assert!(
            t.len() == 3 && t.windows(2).all(|w| w[1] < w[0]) && t[2] > 1.0,
            "{film} {t:?}"
        );
    }
    // The summary counts the checks within 1 %.
    assert!(
        md.contains(
            "- H_pm: max error 0.00 % (target 2 %: met); held-out max 1.93 %, RMS 0.54 % (10 \
             correction terms and a kriging residual (Matern 5/2, scales 2 / 0.5 in a / c, \
             nugget 1e-5; without it held out 2.35 % / 0.78 %)); Moes 1992 5.86 % (fit better); \
             asymptotes within 1 % of the limit solves: 4 of 5 (rigid-isoviscous, \
             elastic-isoviscous, rigid-piezoviscous, elastic-piezoviscous)."
        ),
        "{md}"
    );
}

#[test]
fn empty_or_tiny_datasets_are_clear_errors() {
    let e = fit_report(&FitInput::default(), false)
        .unwrap_err()
        .to_string();
    assert!(e.contains("no converged cases"), "{e}");
    let mut input = load_fit_input(&[data()]).unwrap();
    input.line.truncate(5);
    let e = fit_report(&input, false).unwrap_err().to_string();
    assert!(e.contains("too few"), "{e}");
    assert!(e.contains("line skipped: 5 cases, need at least 10"), "{e}");
    // A dataset whose rows mostly lack the film at the pressure maximum (older datasets): H_c
    // and H_min are fitted, H_pm is not, and the report says why.
    let mut input = load_fit_input(&[data()]).unwrap();
    for p in input.line.iter_mut().skip(5) {
        p.h_pm = None;
    }
    let r = fit_report(&input, false).unwrap().line;
    assert!(r.h_c.is_some() && r.h_min.is_some() && r.h_pm.is_none());
    assert_eq!(
        r.skipped_films,
        ["H_pm: 5 of 32 cases carry it, need at least 10"]
    );
    assert_eq!(
        r.published.len(),
        3,
        "Moes on H_c and on the 5 H_pm cases, D-T"
    );
    assert!(load_fit_input(&[PathBuf::from("/nonexistent/dataset")]).is_err());
}

#[test]
fn fit_command_writes_report_json_and_charts() {
    let out = std::env::temp_dir().join(format!("ehlmap-fit-{}", std::process::id()));
    let run = Command::new(env!("CARGO_BIN_EXE_ehlmap"))
        .args([
            "fit",
            data().to_str().unwrap(),
            "--no-limit-solves",
            "--json",
            "--out",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    assert_eq!(v["line"]["converged_cases"], 32);
    assert!(v["point"]["skipped"]
        .as_str()
        .unwrap()
        .starts_with("skipped: 0 cases"));
    for f in [
        "regime_map.png",
        "report.md",
        "fit.json",
        "parity.png",
        "parity.svg",
        "hc_vs_m.png",
        "error_map.svg",
        "validity_map.png",
        "validity_map.svg",
    ] {
        assert!(
            out.join(f)
                .metadata()
                .map(|m| m.len() > 100)
                .unwrap_or(false),
            "{f} missing"
        );
    }
    // The summary states each film's target and held-out errors: with the interior correction
    // H_c and H_pm meet 2 % on this dataset (the blend alone: 2.37 % and 1.60 %). H_pm is fitted
    // on 27 of the 32 rows (not where the pressure maximum is the outlet spike). With H_RP held at
    // the solver's rigid limit and H_EP's exponents at theory (2026-11-27) the held-out maxima
    // were H_c 2.74 %, H_pm 1.62 %, H_min 0.94 % (free RP law and EP exponents: 2.26, 2.94 and
    // 1.14 % with the spike rows' exclusion; 2.26, 1.01, 1.14 % before it); with H_EP's constant
    // held at the solver's limit too (2026-12-06) 2.62 %, 2.35 % and 0.98 %; with the kriging
    // residual (2026-12-06, 18:55 UTC) 2.07 %, 1.93 % and 0.71 % (in sample below 0.005 %).
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        md.contains(
            "- H_pm: max error 0.00 % (target 2 %: met); held-out max 1.93 %, RMS 0.54 % (10 \
             correction terms and a kriging residual (Matern 5/2, scales 2 / 0.5 in a / c, \
             nugget 1e-5; without it held out 2.35 % / 0.78 %)); Moes 1992 5.86 % (fit better)."
        ),
        "{md}"
    );
    assert!(md.contains("- H_c: max error 0.00 % (target 2 %: met); held-out max 2.07 %"));
    // Every formula on the same cases in one table: the fit in sample and held out, the published.
    assert!(
        md.contains(
            "| ehlmap fit, held out | 2.07 % / 0.73 % | 1.93 % / 0.54 % | 0.71 % / 0.21 % |\n\
             | Moes 1992 | 5.86 % / 2.75 % | 5.86 % / 2.53 % | - |\n\
             | Dowson-Toyoda 1979 (skipped: dataset has no G) | - | - | - |"
        ),
        "{md}"
    );
    // formula.py is written beside the report.
    let py = std::fs::read_to_string(out.join("formula.py")).unwrap();
    assert!(py.contains("def H(M, L, D=None, film=\"H_c\"):") && py.contains("LINE = {"));
    let bad = Command::new(env!("CARGO_BIN_EXE_ehlmap"))
        .args(["fit", "/nonexistent/dataset"])
        .output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(2));
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn a_film_with_a_large_error_estimate_is_left_out_of_its_fit_only() {
    let p = FitPoint {
        m: 372.76,
        l: 0.0,
        d: Some(1.0),
        h_c: 0.98,
        h_min: 0.59,
        g: None,
        h_pm: Some(0.97),
        grid: Some(513),
        h_c_err: Some(0.012),
        h_min_err: Some(0.035),
        h_pm_err: None,
        h_min_cl: None,
        h_min_cl_err: None,
    };
    assert_eq!(p.film(Film::Centre), Some(0.98));
    assert_eq!(p.film(Film::Minimum), None);
    // H_pm without an estimate of its own (files before schema 6): it needs both.
    assert_eq!(p.film(Film::PressureMax), None);
    assert_eq!(p.estimate(Film::PressureMax), Some(0.035));
    // With its own estimate, that one decides, whatever H_c's and H_min's.
    let own = |e: f64| FitPoint {
        h_pm_err: Some(e),
        ..p
    };
    assert_eq!(own(0.01).film(Film::PressureMax), Some(0.97));
    assert_eq!(own(0.01).estimate(Film::PressureMax), Some(0.01));
    assert_eq!(own(0.03).film(Film::PressureMax), None);
    let q = FitPoint {
        h_min_err: Some(0.02),
        ..p
    };
    assert_eq!(q.film(Film::Minimum), Some(0.59));
    assert_eq!(q.film(Film::PressureMax), Some(0.97));
    // No estimate (a dataset solved without one): every film is used.
    let r = FitPoint {
        h_c_err: None,
        h_min_err: None,
        ..p
    };
    assert!(Film::ALL.iter().all(|f| r.film(*f).is_some()));
}

/// The report states where a film's fit meets the 2 % target. On the committed smoke data every
/// line film meets it over the whole M range (the blend alone did not: H_c 2.37 % at M = 5). On
/// the committed point data H_pm with its kriging residual meets it everywhere; without it H_pm
/// does not (2.98 % max): the range it gives is checked against that formula itself, every
/// case inside within 2 % and the report saying "not met".
#[test]
fn the_report_gives_the_m_range_where_each_fit_meets_its_target() {
    let input = load_fit_input(&[data()]).unwrap();
    let report = fit_report(&input, false).unwrap();
    let r = &report.line;
    for q in [&r.h_c, &r.h_pm, &r.h_min] {
        let q = q.as_ref().unwrap();
        let range = q.within_target.as_ref().unwrap();
        assert_eq!(
            (range.m_lo, range.m_hi, range.n, range.of),
            // H_pm is not fitted at the 5 rows whose pressure maximum is the outlet spike.
            (
                2.0,
                500.0,
                if q.quantity == "H_pm" { 27 } else { 32 },
                if q.quantity == "H_pm" { 27 } else { 32 }
            ),
            "{}",
            q.quantity
        );
    }
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/point-257");
    let input = load_fit_input(&[dir]).unwrap();
    let mut report = fit_report(&input, false).unwrap();
    // With its kriging residual the point H_pm all but interpolates the data, and meets the
    // target everywhere; the law beneath it (blend times correction) does not, and the report of
    // that law gives the range.
    let q = report.point.h_pm.as_mut().unwrap();
    assert!(q.model.kriging.is_some(), "kriging kept on the point H_pm");
    let range = q.within_target.as_ref().unwrap();
    assert!(
        q.overall.max.abs() < 0.02 && range.n == range.of,
        "{:?}",
        q.overall
    );
    q.model.kriging = None;
    let tuples: Vec<(f64, f64, f64, f64)> = input
        .point
        .iter()
        .filter_map(|p| {
            let h = p.film(Film::PressureMax)?;
            Some((p.m, p.l, q.model.eval(p.m, p.l, p.d.unwrap()), h))
        })
        .collect();
    q.overall = err_stats(&tuples).unwrap();
    q.within_target = target_range(&tuples, 0.02);
    let h_pm = report.point.h_pm.as_ref().unwrap();
    assert!(h_pm.overall.max.abs() > 0.02, "{:?}", h_pm.overall);
    let err = |p: &FitPoint| {
        h_pm.model.eval(p.m, p.l, p.d.unwrap()) / p.film(Film::PressureMax).unwrap() - 1.0
    };
    // Measured: M in [138.9, 1000], 19 of 43 cases.
    assert!(h_pm.within_target.is_some());
    if let Some(range) = &h_pm.within_target {
        let inside: Vec<_> = input
            .point
            .iter()
            .filter(|p| {
                p.m >= range.m_lo && p.m <= range.m_hi && p.film(Film::PressureMax).is_some()
            })
            .collect();
        assert_eq!(inside.len(), range.n);
        assert!(inside.iter().all(|p| err(p).abs() <= 0.02));
    }
    let md = to_markdown(&report);
    assert!(
        md.contains(&format!(
            "- H_pm: max error {:.2} % (target 2 %: not met)",
            100.0 * h_pm.overall.max.abs()
        )),
        "{md}"
    );
}

/// Issue 24's "a decade beyond the data" for the held line elastic-isoviscous law: the committed
/// line data reach M = 3000; at M = 3e4, L = 0 (131073 points: 65537 leaves a 1 % estimate, and
/// 262145 diverges) the solver's H_c and H_min agree with the held laws A_EI_CENTRAL M^(-1/5) and
/// A_EI_MIN M^(-1/5) within 0.5 % (measured 2026-12-06: 0.9993 and 0.9998, estimate 0.26 %; about
/// 12 s). The rigid limits do not depend on M, and the elastic-piezoviscous limit is solved at
/// M = 1e4, L = 20-80 by every report with L > 0 data (`line_asymptotes_agree_with_the_limit_solves`).
#[test]
fn the_held_line_elastic_law_holds_a_decade_beyond_the_data() {
    use ehlmap::model::case::{Elasticity, LineCase, Models};
    use ehlmap::report::{A_EI_CENTRAL, A_EI_MIN};
    use ehlmap::solve::line::LineSolveParams;
    use ehlmap::solve::Status;
    use ehlmap::strategy::accuracy::solve_line_to_accuracy;
    let m = 3e4;
    let models = Models {
        elasticity: Elasticity::Elastic,
        ..Models::default()
    };
    let case = LineCase::with_models(m, 0.0, models).unwrap();
    let o = solve_line_to_accuracy(&case, &LineSolveParams::default(), 0.003, 131073).outputs;
    let estimate = o.error_estimate.expect("an error estimate");
    let ratios = [
        o.h_c * m.powf(0.2) / A_EI_CENTRAL,
        o.h_min * m.powf(0.2) / A_EI_MIN,
    ];
    eprintln!(
        "M = 3e4, L = 0 on {} points: H_c, H_min over the held EI laws {ratios:?}, estimate {estimate:e}",
        o.grid
    );
    assert_eq!(o.status, Status::Converged, "{}", o.reason);
    assert!(estimate <= 0.005, "{estimate}");
    for r in ratios {
        assert!((r - 1.0).abs() <= 0.005, "{ratios:?}");
    }
}

/// The held-out folds are fitted in parallel (rayon), each on its own and collected in fold
/// order, so the whole report (every coefficient, every held-out error) is the same on one
/// thread as on two: checked on the committed line smoke data and the 51 point cases of
/// `tests/data/point-257`.
#[test]
fn the_fit_is_the_same_at_any_thread_count() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let input = load_fit_input(&[dir.join("smoke-line"), dir.join("point-257")]).unwrap();
    let on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let r = pool.install(|| fit_report(&input, false).unwrap());
        serde_json::to_string(&r).unwrap()
    };
    let (one, two) = (on(1), on(2));
    assert!(
        one.contains("\"heldout\""),
        "the folds were cross-validated"
    );
    assert_eq!(one, two);
}
