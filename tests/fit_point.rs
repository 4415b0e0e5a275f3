//! The point-contact fit on a dataset made by ehlmap itself (`tests/data/point-257`, from
//! `tests/data/point-257.toml`: the nightly point sweep's axes from M = 7.2 up at 257^2 points,
//! 96 cases of which 28 have an error estimate above 2 % (M >= 139) and 22 a domain-truncation
//! error above 2 % (rigid-like, M <= 19) and are left out), and a mixed line and point input:
//! each contact is fitted on its own; a contact with too few cases is reported as skipped while
//! the other is still fitted.

use ehlmap::fit::dataset::load_fit_input;
use ehlmap::fit::point_model::ri_d_factor;
use ehlmap::limits::rigid_d_factor::ri_shape;
use ehlmap::limits::rigid_point::{RigidPointSolves, C_RI_CENTRE, C_RI_PMAX};
use ehlmap::limits::rigid_rp::PI_CIRCULAR;
use ehlmap::report::{fit_report, Film, FitInput};
use std::path::PathBuf;
use std::process::Command;

fn dir(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

fn param(q: &ehlmap::report::QuantityFit, name: &str) -> (f64, f64) {
    let p = q.params.iter().find(|p| p.name == name).unwrap();
    (p.value, p.sigma)
}

#[test]
fn point_fit_beats_nvm_and_checks_its_asymptotes() {
    let input = load_fit_input(&[dir("point-257")]).unwrap();
    // 45 rows left out (22 for domain truncation, 23 with both error estimates above 2 %), 5
    // used for one film only (the other's estimate above 2 %).
    assert_eq!(input.point.len(), 51);
    assert_eq!(input.excluded.len(), 45, "{:?}", input.excluded);
    assert_eq!(input.one_film.len(), 5, "{:?}", input.one_film);
    let truncated = input
        .excluded
        .iter()
        .filter(|e| e.contains("domain truncation"));
    assert_eq!(truncated.count(), 22);
    assert!(input.line.is_empty());
    let r = fit_report(&input, true).unwrap().point;
    let h_c = r.h_c.as_ref().unwrap();
    let nvm = r.published[0].overall.as_ref().unwrap();
    assert_eq!(r.published[0].name, "NVM 1994");
    assert_eq!(r.published[1].against, "H_pm");
    let nvm_pm = r.published[1].overall.as_ref().unwrap();
    assert_eq!(
        r.published[2].skipped.as_deref(),
        Some("skipped: dataset has no G")
    );
    println!(
        "fit H_c max {:+.3} rms {:.3}; NVM max {:+.3} rms {:.3}",
        h_c.overall.max, h_c.overall.rms, nvm.max, nvm.rms
    );
    // Measured: fit max 1.40 %, RMS 0.5 %, with H_RI and H_RP held at the solver's limits and the
    // elastic exponents at theory's, and the interior correction (48 cases with H_c's error
    // estimate within 2 %; 1.01 % when H_RP and the exponents were free); NVM 1994 max 7.90 %,
    // RMS 2.72 % on the same 48 cases. The target is 2 %. (From the all-case blend alone, without
    // the folds' blends as starts of the final fit, 2.05 %.)
    assert!(h_c.overall.max.abs() < 0.02, "{}", h_c.overall.max);
    assert!(h_c.overall.max.abs() < 0.5 * nvm.max.abs());
    assert!(h_c.overall.rms < 0.5 * nvm.rms);
    // H_min: these rows (schema before 7) have no centre-line minimum, so H_min is fitted
    // directly, and NVM's form follows the side-lobe minimum poorly at high L. Measured 3.68 %
    // (held out 9.3 %) with the elastic exponents at theory's (3.00 % when they were free; 7.1 %
    // from the all-case blend alone). Current data carry H_min_cl and take the centre-line route
    // (tests/fit_side.rs).
    let h_min = r.h_min.as_ref().unwrap();
    assert!(h_min.overall.max.abs() < 0.04, "{:?}", h_min.overall);
    // The film at the pressure maximum: 1.91 % with the correction (the blend alone 3.04 %)
    // against NVM's 5.85 %.
    let h_pm = r.h_pm.as_ref().unwrap();
    assert!(h_pm.overall.max.abs() < nvm_pm.max.abs());
    // Physical: the rigid-isoviscous constant (PHYSICS.md 5 asks the project to settle it:
    // NVM 41.3, truncated-domain numerics 23) is held at the solver's own, its rigid solves
    // extrapolated to an unbounded domain (35.5; checked against fresh solves below). Fitted
    // freely on these rows (M >= 7) it came out 40.2 with a sigma of ln c_RI of 0.19. The
    // rigid-piezoviscous law is held at the solver's limit (b = 35.5 pi(1), L^(2/3)) and the
    // elastic exponents at theory's (-2/15; -1/12 and 3/4).
    assert_eq!(param(h_c, "ln_c_RI"), (35.5f64.ln(), 0.0));
    assert_eq!(
        param(r.h_pm.as_ref().unwrap(), "ln_c_RI"),
        (45f64.ln(), 0.0)
    );
    let b = param(h_c, "ln_b_RP");
    assert!((b.0 - (35.5 * PI_CIRCULAR).ln()).abs() < 1e-12 && b.1 == 0.0);
    for (name, v) in [
        ("beta_RP", 2.0 / 3.0),
        ("e_RP", 0.0),
        ("alpha_EI", -2.0 / 15.0),
        ("gamma_EP", -1.0 / 12.0),
        ("delta_EP", 0.75),
    ] {
        let (x, sigma) = param(h_c, name);
        assert!((x - v).abs() < 1e-15 && sigma == 0.0, "{name} {x} {sigma}");
    }
    assert!(h_c.params.iter().all(|p| p.sigma.is_finite()));
    // Four asymptote rows per film, and the D factor's rigid-isoviscous and rigid-piezoviscous
    // rows (the data go down to D = 0.1).
    assert_eq!(
        r.asymptotes.len(),
        18,
        "four asymptotes and two D factors for each of three films"
    );
    let check = |film: &str, name: &str| {
        r.asymptotes
            .iter()
            .find(|a| a.quantity == film && a.asymptote == name)
            .unwrap_or_else(|| panic!("{film} {name} missing"))
    };
    // The rigid rows: fresh rigid solves on the default domain enlarged 1, 2, 4 times (257^2,
    // 513^2, 1025^2: the same spacing) rise toward the held constant (H_c 24.8, 29.4, 32.2 of
    // 35.5), and their extrapolation to an unbounded domain is that constant within 1 %
    // (a reference independent of the extrapolation's inputs: scales 2, 4, 8 gave 35.50).
    for (film, c) in [("H_c", 35.5), ("H_pm", 45.0)] {
        let ri = check(film, "rigid-isoviscous");
        assert_eq!(ri.trend_over, "domain scale");
        let t: Vec<f64> = ri.trend.iter().map(|p| p.1).collect();
        assert!(
            t.len() == 3 && t[0] < 0.75 && t[0] < t[1] && t[1] < t[2] && t[2] < 0.95,
            "{film} {t:?}"
        );
        let ratio = ri.ratio.unwrap();
        assert!((ratio - 1.0).abs() < 0.01, "{film} {ratio}");
        assert!((ri.fitted - c).abs() < 1e-9, "{film} {}", ri.fitted);
    }
    // The D factor of H_RI (src/limits/rigid_d_factor.rs): far-field rigid solves at the data's
    // smallest D (0.1) and a tenth of it, beyond the data, within 0.5 % of the held law
    // (measured 0.9998 and 1.0006 for H_c; 0.9998 and 1.0005 for H_pm). The solves lie 2.0 %
    // (H_c) and 4.8 % (H_pm) below NVM's factor at D = 0.1, 4.3 % and 7.5 % at D = 0.01.
    // So is the D factor of H_RP (src/limits/rigid_rp.rs), from the same solves.
    for film in ["H_c", "H_pm", "H_min"] {
        for asymptote in ["rigid-isoviscous", "rigid-piezoviscous"] {
            let row = r
                .asymptotes
                .iter()
                .find(|a| a.quantity == film && a.trend_over == "D" && a.asymptote == asymptote)
                .unwrap_or_else(|| panic!("{film}: no {asymptote} D-factor row"));
            assert_eq!(row.d, Some(0.01));
            assert_eq!(row.trend.len(), 2, "{:?}", row.trend);
            assert_eq!(row.trend[0].0, 0.1);
            for (d, ratio) in &row.trend {
                assert!(
                    (ratio - 1.0).abs() < 5e-3,
                    "{film} {asymptote} D = {d}: {ratio}"
                );
            }
        }
    }
    let check = |name: &str| check("H_c", name);
    // The rigid-piezoviscous law is the limit: the row at D = 1 (rigid solves on domains enlarged
    // 1, 2, 4 times, extrapolated) within 0.5 % of the law held from far-field solves, although
    // the elastic films at the largest L lie well above it (limit 0.7098 L^(2/3) = 5.23 at L = 20,
    // D = 1; the data H_c 7.29 and 7.09 at M = 52 and 139, +36-40 %): the interior correction
    // carries the excess.
    let rp = check("rigid-piezoviscous");
    assert_eq!((rp.l, rp.d), (20.0, Some(1.0)));
    let limit = rp.solver.unwrap();
    assert!((limit / 5.23 - 1.0).abs() < 0.01, "RP limit {limit}");
    let above: Vec<f64> = input
        .point
        .iter()
        .filter(|p| p.l == 20.0 && p.d == Some(1.0))
        .map(|p| p.h_c / limit)
        .collect();
    assert!(
        above.len() >= 2 && above.iter().all(|&x| x > 1.3),
        "{above:?}"
    );
    let ratio = rp.ratio.unwrap();
    assert!((ratio - 1.0).abs() < 5e-3, "RP ratio {ratio}");
    // These 257^2 data stop at M = 139 (L = 0, its H_c only, and L = 20) for D = 1, short of the
    // elastic limits: the solver / law ratio is below 1 over the data's M range. (Measured with
    // the elastic exponents at theory's: EI 0.875, 0.853, 0.857 at M = 13.9, 43.9, 139, EP 0.783,
    // 0.858, 0.911. With the exponents free this test also asked the EI ratio to rise over the
    // range, last above first, measured 0.921, 0.916, 0.940; with theory's exponent the law is
    // steeper than these pre-asymptotic data and the EI trend dips: that part is now asked of EP
    // only.) (The 513^2 nightly point sweep reaches M = 1000: EI ratio 1.000 there.)
    for (name, n) in [("elastic-isoviscous", 3), ("elastic-piezoviscous", 3)] {
        let t = &check(name).trend;
        println!("{name} trend {t:?}");
        assert_eq!(t.len(), n, "{name} trend {t:?}");
        assert!(
            t.iter().all(|p| p.1 > 0.75 && p.1 < 1.01),
            "{name} trend {t:?}"
        );
    }
    let ep = &check("elastic-piezoviscous").trend;
    assert!(ep[0].1 < ep[2].1, "{ep:?}");
    // A decade beyond the data (src/limits/beyond.rs): the elastic-isoviscous case at ten times
    // the data's largest L = 0 M at D = 1 (M = 138.9 here) on 513^2, 1025^2 and 2049^2, each
    // film extrapolated to zero spacing. Measured (2026-12-07): H_c 0.83435, 0.83986, 0.84118 ->
    // 0.84159 +- 0.00042 (order 2.06), 0.943 of the EI limit 2.3422 M^(-2/15) (0.939 at M = 1000
    // and 0.952 at 3162 on the same grids: the slow approach); the formula of these 257^2 data is
    // 2.8 % (H_c), 2.5 % (H_pm) and 44 % (H_min, whose side-lobe factor stops at the data's M)
    // thicker there: issue 24's 0.5 % needs the 0.5 % data (docs/validation.md).
    let m_top = input
        .point
        .iter()
        .filter(|p| p.l == 0.0 && p.d == Some(1.0))
        .fold(0.0, |m: f64, p| m.max(p.m));
    let limit = 2.3422 * (10.0 * m_top).powf(-2.0 / 15.0);
    let models = [(&r.h_c, "H_c"), (&r.h_pm, "H_pm"), (&r.h_min, "H_min")];
    for (q, film) in models {
        let row = r
            .asymptotes
            .iter()
            .find(|a| a.quantity == film && a.asymptote == "elastic-isoviscous")
            .unwrap();
        let b = row.decade.as_ref().expect("a decade-beyond check");
        assert_eq!((b.m, b.d), (10.0 * m_top, 1.0));
        assert_eq!(b.grids, [513, 1025, 2049]);
        let f: Vec<f64> = b.films.iter().map(|f| f.expect("converged")).collect();
        assert!(f[0] < f[1] && f[1] < f[2], "{film} {f:?}");
        let (v, bar) = (b.solver.unwrap(), b.error_bar.unwrap());
        assert!(v > f[2] && bar < 3e-3 * v, "{film} {v} +- {bar}");
        if film != "H_min" {
            let p = b.order.expect("an observed order");
            assert!((1.8..2.4).contains(&p), "{film} order {p}");
            assert!((0.93..0.96).contains(&(v / limit)), "{film} {}", v / limit);
        }
        let h = q.as_ref().unwrap().model.eval(b.m, 0.0, b.d);
        assert_eq!(b.formula, Some(h));
        assert_eq!(b.ratio, Some(v / h));
    }
    // Only the elastic-isoviscous rows carry it.
    assert_eq!(
        r.asymptotes.iter().filter(|a| a.decade.is_some()).count(),
        3
    );
}

#[test]
fn mixed_input_fits_each_contact_and_skips_a_thin_one() {
    let mut input = load_fit_input(&[dir("smoke-line"), dir("point-257")]).unwrap();
    assert_eq!((input.line.len(), input.point.len()), (32, 51));
    let r = fit_report(&input, false).unwrap();
    assert!(r.line.h_c.is_some() && r.point.h_c.is_some());
    // 5 free point parameters (10 asymptote parameters, H_RI held, less the 5 held at NVM's in
    // stage 1) + 5 spare.
    input.point.truncate(6);
    let r = fit_report(&input, false).unwrap();
    assert!(r.line.h_c.is_some());
    assert_eq!(
        r.point.skipped.as_deref(),
        Some("skipped: 6 cases, need at least 10")
    );
    input.line.clear();
    let e = fit_report(&input, false).unwrap_err().to_string();
    assert!(
        e.contains("too few") && e.contains("need at least 10"),
        "{e}"
    );
    assert!(fit_report(&FitInput::default(), false)
        .unwrap_err()
        .to_string()
        .contains("no converged cases"));
}

#[test]
fn fit_command_on_a_mixed_dataset_writes_both_sections() {
    let out = std::env::temp_dir().join(format!("ehlmap-fit-point-{}", std::process::id()));
    let run = Command::new(env!("CARGO_BIN_EXE_ehlmap"))
        .args(["fit", dir("smoke-line").to_str().unwrap()])
        .arg(dir("point-257"))
        .args(["--no-limit-solves", "--json", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    assert_eq!(v["line"]["converged_cases"], 32);
    assert_eq!(v["point"]["converged_cases"], 51);
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.contains("## line contact") && md.contains("## point contact"));
    assert!(md.contains("NVM 1994") && md.contains("Moes 1992"));
    for f in [
        "point_regime_map.png",
        "point_hc_vs_m.svg",
        "regime_map.png",
    ] {
        assert!(
            out.join(f)
                .metadata()
                .map(|m| m.len() > 100)
                .unwrap_or(false),
            "{f}"
        );
    }
    std::fs::remove_dir_all(&out).ok();
}

#[test]
fn rigid_constant_follows_the_solver_d_factor_at_d_one_half() {
    // The point fit holds H_RI = c_RI f_RI(D) M^-2 with the solver's own D factor (fitted to
    // far-field solves; src/limits/rigid_d_factor.rs): the truncated domains enlarged 1, 2, 4
    // times and extrapolated (the report's check) agree with it. Measured ratios (solver /
    // c_RI f_RI(D)) at D = 0.5: 0.9950 (H_c) and 0.9962 (H_pm); against NVM's D factor
    // 0.9988 and 0.9848.
    let d = 0.5;
    let r = RigidPointSolves::run(d).expect("a valid D");
    assert!(r.converged(), "rigid solves converge");
    let films = r.films(Film::Centre);
    assert!(films[0] < films[1] && films[1] < films[2], "{films:?}");
    let f = |film| ri_d_factor(ri_shape(film), d);
    let ratio = r.extrapolated(Film::Centre) / (C_RI_CENTRE * f(Film::Centre));
    assert!((ratio - 1.0).abs() < 0.01, "H_c {ratio}");
    let ratio = r.extrapolated(Film::PressureMax) / (C_RI_PMAX * f(Film::PressureMax));
    assert!((ratio - 1.0).abs() < 0.01, "H_pm {ratio}");
    // H_min is the centre film for a rigid contact.
    let h_min = r.films(Film::Minimum);
    assert!(h_min
        .iter()
        .zip(films)
        .all(|(a, b)| (a / b - 1.0).abs() < 1e-12));
}
