//! `ehlmap solve --sigma`: the mixed-lubrication fields of the JSON and the summary, bad rough
//! input with exit code 2 naming it, and a sweep with a roughness axis through `ehlmap mixed`.

mod common;
use common::ehlmap;

#[test]
fn a_rough_solve_reports_lambda_the_asperity_share_and_the_smooth_film() {
    let args = [
        "solve",
        "--contact",
        "line",
        "--M",
        "100",
        "--L",
        "10",
        "--sigma",
        "4",
        "--grid",
        "1025",
    ];
    let out = ehlmap(&[&args[..], &["--json"]].concat());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("one JSON object");
    assert_eq!(v["status"], "converged");
    assert_eq!(v["sigma"], 4.0);
    assert_eq!(v["gamma"], 1.0);
    let (hc, hmin) = (v["H_c"].as_f64().unwrap(), v["H_min"].as_f64().unwrap());
    // (serde_json parses floats to within an ulp, not exactly)
    let close = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-14;
    assert!(close(v["Lambda"].as_f64().unwrap(), hmin / 4.0));
    assert!(close(v["Lambda_c"].as_f64().unwrap(), hc / 4.0));
    let share = v["asperity_load_fraction"].as_f64().unwrap();
    assert!(share > 0.0 && share < 0.01, "{share}");
    let smooth = v["H_c_smooth"].as_f64().unwrap();
    // The smooth film of this case on 1025 points (tests/cli.rs pins M = 20; here the plain
    // solve of the same command without --sigma).
    let plain = ehlmap(&[
        "solve",
        "--contact",
        "line",
        "--M",
        "100",
        "--L",
        "10",
        "--grid",
        "1025",
        "--json",
    ]);
    let p: serde_json::Value = serde_json::from_slice(&plain.stdout).unwrap();
    assert!(close(smooth, p["H_c"].as_f64().unwrap()));
    assert!(p.get("sigma").is_none() && p.get("Lambda").is_none());
    // Load balance of fluid and asperities together.
    assert!(v["load_error"].as_f64().unwrap().abs() < 1e-4);
    let text = ehlmap(&args);
    let s = String::from_utf8_lossy(&text.stdout);
    for needle in [
        "roughness      sigma 4",
        "film parameter Lambda",
        "asperities",
        "smooth film",
    ] {
        assert!(s.contains(needle), "{needle}: {s}");
    }
}

#[test]
fn bad_rough_input_exits_with_code_2_naming_the_input() {
    for (extra, needle) in [
        (vec!["--sigma", "-0.5"], "--sigma"),
        (vec!["--sigma", "1", "--gamma", "0"], "--gamma"),
        (vec!["--sigma", "1", "--gamma", "-2"], "--gamma"),
        (vec!["--gamma", "3"], "--gamma needs --sigma"),
        (vec!["--sigma", "1", "--slide-roll", "3"], "--slide-roll"),
        (vec!["--sigma", "1", "--ph-over-e", "0"], "--ph-over-e"),
        (vec!["--sigma", "1", "--method", "newton"], "--sigma"),
        (
            vec!["--sigma", "1", "--eta-beta-sigma", "0"],
            "--eta-beta-sigma",
        ),
        (
            vec!["--sigma", "1", "--sigma-over-beta", "-1"],
            "--sigma-over-beta",
        ),
        (
            vec!["--sigma-over-beta", "1e-3"],
            "--sigma-over-beta needs --sigma",
        ),
    ] {
        let args = [&["solve", "--M", "20", "--L", "5"][..], &extra[..]].concat();
        let out = ehlmap(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}

#[test]
fn a_sweep_with_a_sigma_axis_makes_the_mixed_map() {
    let dir = std::env::temp_dir().join(format!("ehlmap-mixed-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let spec = dir.join("rough.toml");
    std::fs::write(
        &spec,
        format!(
            "name = \"rough\"\ncontact = \"line\"\n[axes]\nM = [50]\nL = [5]\n\
             sigma = [0, 1, 3]\ngamma = [1, 3]\n[numerics]\ngrid = 513\nerror_estimate = false\n\
             [output]\ndir = \"{}\"\n",
            dir.display()
        ),
    )
    .unwrap();
    let out = ehlmap(&["sweep", spec.to_str().unwrap(), "--progress", "none"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let data = dir.join("rough");
    let out = ehlmap(&["mixed", data.to_str().unwrap(), "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let curves = v["curves"].as_array().unwrap();
    assert_eq!(curves.len(), 2, "gamma 1 and 3");
    for c in curves {
        let pts = c["points"].as_array().unwrap();
        assert_eq!(pts.len(), 2, "sigma 1 and 3");
        let lam: Vec<f64> = pts.iter().map(|p| p["lambda"].as_f64().unwrap()).collect();
        assert!(lam[0] > lam[1], "by decreasing Lambda: {lam:?}");
    }
    assert!(dir.join("rough-mixed").join("mixed.png").is_file());
    // A dataset that does not exist is bad input.
    let missing = ehlmap(&["mixed", dir.join("nothing").to_str().unwrap()]);
    assert_eq!(missing.status.code(), Some(2));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn denser_summits_carry_more_of_the_load() {
    let share = |extra: &[&str]| {
        let base = [
            "solve",
            "--contact",
            "line",
            "--M",
            "100",
            "--L",
            "10",
            "--sigma",
            "6",
            "--grid",
            "1025",
            "--no-estimate",
            "--json",
        ];
        let out = ehlmap(&[&base[..], extra].concat());
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(v["status"], "converged");
        v["asperity_load_fraction"].as_f64().unwrap()
    };
    let (default, dense) = (share(&[]), share(&["--eta-beta-sigma", "0.08"]));
    // K' grows with (eta_s beta sigma)^2: four times the pressure at the same film.
    assert!(dense > 1.5 * default && default > 0.0, "{default} {dense}");
}
