//! The point-contact fit on a small dataset made by ehlmap itself (`tests/data/smoke-point`,
//! from `tests/data/smoke-point.toml`: M in {1, 3, 10, 30, 100, 300} x L in {0, 5, 10} x
//! D in {0.25, 0.5, 1}, 129^2 points, 54 cases of which 19 have an error estimate above 2 % and
//! 23 a domain-truncation bias above 2 % (rigid-like, M <= 10) and are left out), and a mixed
//! line and point input: each contact is fitted on its own; a contact
//! with too few cases is reported as skipped while the other is still fitted.

use ehlmap::fit::dataset::load_fit_input;
use ehlmap::fit::report::{fit_report, FitInput};
use std::path::PathBuf;
use std::process::Command;

fn dir(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

fn param(q: &ehlmap::fit::report::QuantityFit, name: &str) -> f64 {
    q.params.iter().find(|p| p.name == name).unwrap().value
}

#[test]
fn point_fit_beats_nvm_and_checks_its_asymptotes() {
    let input = load_fit_input(&[dir("smoke-point")]).unwrap();
    assert_eq!(input.point.len(), 12);
    assert_eq!(input.excluded.len(), 42);
    let biased = input.excluded.iter().filter(|e| e.contains("domain bias"));
    assert_eq!(biased.count(), 23);
    assert!(input.line.is_empty());
    let r = fit_report(&input, true).unwrap().point;
    let h_c = r.h_c.as_ref().unwrap();
    let nvm = r.published[0].overall.as_ref().unwrap();
    assert_eq!(r.published[0].name, "NVM 1994");
    assert_eq!(r.published[1].against, "H_pm");
    assert_eq!(
        r.published[2].skipped.as_deref(),
        Some("skipped: dataset has no G")
    );
    println!(
        "fit H_c max {:+.3} rms {:.3}; NVM max {:+.3} rms {:.3}",
        h_c.overall.max, h_c.overall.rms, nvm.max, nvm.rms
    );
    // Measured: fit max 2.2 %, RMS 1.1 %; NVM 1994 max 6.2 %, RMS 3.3 % on the same 12 cases
    // (with the domain-biased rigid-like rows in, NVM was 72.6 % off: the solver, not NVM).
    assert!(h_c.overall.max.abs() < 0.03, "{}", h_c.overall.max);
    assert!(h_c.overall.max.abs() < nvm.max.abs());
    assert!(h_c.overall.rms < 0.5 * nvm.rms);
    // Physical: the rigid-isoviscous constant (PHYSICS.md 5 asks the project to settle it:
    // NVM 41.3, truncated-domain numerics 23) near the solver's domain-extrapolated rigid value
    // 34 (M = 1, D = 1, rigid: 32.1 and 33.0 with 4x and 8x the inlet and side extents on 513^2,
    // extrapolated as 1/extent; src/problem/point_domain.rs), although only cases with M >= 10
    // are fitted; the piezoviscous L exponent near the theoretical 2/3.
    let c_ri = param(h_c, "ln_c_RI").exp();
    assert!((c_ri / 34.0 - 1.0).abs() < 0.15, "c_RI {c_ri}");
    let beta = param(h_c, "beta_RP");
    assert!((beta - 2.0 / 3.0).abs() < 0.1, "beta_RP {beta}");
    assert!(param(h_c, "alpha_EI") < 0.0);
    assert!(h_c.params.iter().all(|p| p.sigma.is_finite()));
    // Four asymptote rows. The rigid limit solve (129^2, default domain) is biased low by the
    // truncated domain (24.6 against the extrapolated 34): ratio about 0.7, and said so.
    assert_eq!(
        r.asymptotes.len(),
        12,
        "four asymptotes for each of three films"
    );
    let names: Vec<_> = r
        .asymptotes
        .iter()
        .filter(|a| a.quantity == "H_c")
        .map(|a| a.asymptote.as_str())
        .collect();
    assert_eq!(
        names,
        [
            "rigid-isoviscous",
            "elastic-isoviscous",
            "rigid-piezoviscous",
            "elastic-piezoviscous"
        ]
    );
    let ri = r.asymptotes[0].ratio.unwrap();
    assert!(ri > 0.6 && ri < 0.8, "RI ratio {ri}");
    assert!(
        r.asymptotes[0].note.contains("biased low"),
        "{}",
        r.asymptotes[0].note
    );
}

#[test]
fn mixed_input_fits_each_contact_and_skips_a_thin_one() {
    let mut input = load_fit_input(&[dir("smoke-line"), dir("smoke-point")]).unwrap();
    assert_eq!((input.line.len(), input.point.len()), (32, 12));
    let r = fit_report(&input, false).unwrap();
    assert!(r.line.h_c.is_some() && r.point.h_c.is_some());
    // 7 free point parameters (12 asymptote parameters less the 5 held at NVM's) + 5 spare.
    input.point.truncate(6);
    let r = fit_report(&input, false).unwrap();
    assert!(r.line.h_c.is_some());
    assert_eq!(
        r.point.skipped.as_deref(),
        Some("skipped: 6 cases, need at least 12")
    );
    input.line.clear();
    let e = fit_report(&input, false).unwrap_err();
    assert!(
        e.contains("too few") && e.contains("need at least 12"),
        "{e}"
    );
    assert!(fit_report(&FitInput::default(), false)
        .unwrap_err()
        .contains("no converged cases"));
}

#[test]
fn fit_command_on_a_mixed_dataset_writes_both_sections() {
    let out = std::env::temp_dir().join(format!("ehlmap-fit-point-{}", std::process::id()));
    let run = Command::new(env!("CARGO_BIN_EXE_ehlmap"))
        .args(["fit", dir("smoke-line").to_str().unwrap()])
        .arg(dir("smoke-point"))
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
    assert_eq!(v["point"]["converged_cases"], 12);
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
