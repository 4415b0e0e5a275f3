//! The fit report on a small dataset made by ehlmap itself (`tests/data/smoke-line`: the smoke
//! sweep, 36 line cases on 2049 points, committed): the fitted formula beats Moes 1992 on the
//! same cases, its exponents are physical, and bad datasets give clear errors.

use ehlmap::fit::dataset::load_fit_input;
use ehlmap::fit::report::{fit_report, FitInput};
use std::path::PathBuf;
use std::process::Command;

fn data() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/smoke-line")
}

#[test]
fn fitted_formula_beats_moes_on_the_committed_dataset() {
    let input = load_fit_input(&[data()]).unwrap();
    assert_eq!(input.points.len(), 36);
    assert_eq!(input.failed, 0);
    let r = fit_report(&input, false).unwrap();
    let moes = r.moes_1992.as_ref().unwrap();
    println!(
        "fit H_c max {:+.3}, H_min max {:+.3}, Moes max {:+.3}",
        r.h_c.overall.max, r.h_min.overall.max, moes.max
    );
    // Measured: fit 2.4 % (H_c), 1.3 % (H_min); Moes 1992 8.0 % on these cases.
    assert!(r.h_c.overall.max.abs() < 0.03, "{:?}", r.h_c.overall);
    assert!(r.h_min.overall.max.abs() < 0.03, "{:?}", r.h_min.overall);
    assert!(r.h_c.overall.max.abs() < moes.max.abs());
    assert!(r.h_c.overall.rms < moes.rms);
    // Elastic-isoviscous exponent near Moes' -1/5 and piezoviscous exponent of L near 3/4.
    let p = |name: &str| r.h_c.params.iter().find(|p| p.name == name).unwrap().value;
    assert!((p("alpha_EI") + 0.2).abs() < 0.06, "{}", p("alpha_EI"));
    assert!((p("delta_EP") - 0.75).abs() < 0.1, "{}", p("delta_EP"));
    assert!(r.h_c.params.iter().all(|p| p.sigma.is_finite()));
}

#[test]
fn empty_or_tiny_datasets_are_clear_errors() {
    let e = fit_report(&FitInput::default(), false).unwrap_err();
    assert!(e.contains("no converged cases"), "{e}");
    let mut input = load_fit_input(&[data()]).unwrap();
    input.points.truncate(5);
    let e = fit_report(&input, false).unwrap_err();
    assert!(e.contains("too few"), "{e}");
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
    assert_eq!(v["converged_cases"], 36);
    for f in [
        "regime_map.png",
        "report.md",
        "fit.json",
        "parity.png",
        "parity.svg",
        "hc_vs_m.png",
        "error_map.svg",
    ] {
        assert!(
            out.join(f)
                .metadata()
                .map(|m| m.len() > 100)
                .unwrap_or(false),
            "{f} missing"
        );
    }
    let bad = Command::new(env!("CARGO_BIN_EXE_ehlmap"))
        .args(["fit", "/nonexistent/dataset"])
        .output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(2));
    std::fs::remove_dir_all(&out).ok();
}
