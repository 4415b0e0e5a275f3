//! The `ehlmap solve` command line: JSON field names, exit codes on bad input, and the Parquet
//! profile read back with the arrow-rs reader.

mod common;
use common::ehlmap;

#[test]
fn json_has_exactly_the_documented_fields() {
    let out = ehlmap(&[
        "solve",
        "--contact",
        "line",
        "--M",
        "20",
        "--L",
        "10",
        "--grid",
        "1025",
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("one JSON object");
    let mut keys: Vec<&str> = v.as_object().unwrap().keys().map(|s| s.as_str()).collect();
    keys.sort();
    let mut want = vec![
        "H_c",
        "H_c_pmax",
        "H_min",
        "X_min",
        "P_max",
        "spike",
        "H0",
        "f",
        "load_error",
        "status",
        "reason",
        "grid",
        "levels",
        "level",
        "model_used",
        "work_units",
        "wall_s",
        "algebraic_error",
        "H_c_err",
        "H_c_pmax_err",
        "P_max_err",
        "H_min_err",
        "error_estimate",
        "accuracy_met",
    ];
    want.sort();
    assert_eq!(keys, want);
    // A fixed grid: no target, but the half-grid estimate (1025 points are 0.19 % below the
    // grid limit 5.27566, Richardson over tight solves on 8193 and 16385 points).
    assert!(v["accuracy_met"].is_null());
    let (e_c, e_m) = (
        v["H_c_err"].as_f64().unwrap(),
        v["H_min_err"].as_f64().unwrap(),
    );
    assert!(
        e_c > 1e-5 && e_c < 5e-3 && e_m > 1e-5 && e_m < 5e-3,
        "{e_c} {e_m}"
    );
    assert_eq!(v["error_estimate"].as_f64().unwrap(), e_c.max(e_m));
    assert_eq!(v["model_used"], "full");
    assert_eq!(v["level"], 5, "1025 points are 2^5 x 32 intervals");
    assert_eq!(v["status"], "converged");
    assert_eq!(v["grid"], 1025);
    let hc = v["H_c"].as_f64().unwrap();
    assert!((hc / 5.2655 - 1.0).abs() < 1e-3, "H_c {hc}");
}

/// The default solve meets the default 1 % target, says so, and prints its error bars.
#[test]
fn the_default_solve_meets_one_percent_with_error_bars() {
    let out = ehlmap(&["solve", "--M", "20", "--L", "10", "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("one JSON object");
    assert_eq!(v["status"], "converged", "{}", v["reason"]);
    assert_eq!(v["accuracy_met"], true, "{}", v["reason"]);
    let e = v["error_estimate"].as_f64().unwrap();
    assert!(e <= 0.01, "{e}");
    // Against the grid-converged H_c (Richardson over tight solves on 8193 and 16385 points,
    // 5.275501 and 5.275621): within the estimate.
    let hc = v["H_c"].as_f64().unwrap();
    let reference = 5.27566;
    assert!(
        (hc / reference - 1.0).abs() <= v["H_c_err"].as_f64().unwrap(),
        "H_c {hc}"
    );
    let text = ehlmap(&["solve", "--M", "20", "--L", "10"]);
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(text.contains("H_c            5.2"), "{text}");
    assert!(text.contains(" +- "), "{text}");
    assert!(text.contains("accuracy       target met"), "{text}");
    // A point contact is a circular one by default.
    let out = ehlmap(&[
        "solve",
        "--contact",
        "point",
        "--M",
        "20",
        "--L",
        "10",
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("one JSON object");
    assert_eq!(
        (v["D"].as_f64(), v["accuracy_met"].as_bool()),
        (Some(1.0), Some(true))
    );
}

#[test]
fn bad_input_exits_with_code_2_naming_the_value() {
    for (args, needle) in [
        (vec!["solve", "--M", "0", "--L", "1"], "M = 0"),
        (vec!["solve", "--M", "-3", "--L", "1"], "M = -3"),
        (vec!["solve", "--M", "NaN"], "M = NaN"),
        (vec!["solve", "--M", "20", "--L", "-1"], "L = -1"),
        (vec!["solve", "--M", "20", "--grid", "9"], "--grid 9"),
        (
            vec!["solve", "--M", "20", "--viscosity", "roelands"],
            "--ph",
        ),
        (vec!["solve", "--M", "20", "--viscosity", "foo"], "foo"),
        (
            vec!["solve", "--M", "20", "--density", "dowson-higginson"],
            "--ph",
        ),
        (
            vec![
                "solve",
                "--M",
                "20",
                "--viscosity",
                "roelands",
                "--ph",
                "1e9",
                "--eta0",
                "-1",
            ],
            "eta0 = -1",
        ),
    ] {
        let out = ehlmap(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}

#[test]
fn models_run_from_the_command_line() {
    let out = ehlmap(&[
        "solve",
        "--M",
        "50",
        "--L",
        "8",
        "--grid",
        "1025",
        "--viscosity",
        "roelands",
        "--eta0",
        "0.05",
        "--ph",
        "1.2e9",
        "--density",
        "dowson-higginson",
        "--json",
    ]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["status"], "converged", "{}", v["reason"]);
    // Roelands thins the lubricant at high pressure relative to Barus, and compressibility
    // lowers the film: the film is below the Barus, incompressible one.
    let barus = ehlmap(&["solve", "--M", "50", "--L", "8", "--grid", "1025", "--json"]);
    let b: serde_json::Value = serde_json::from_slice(&barus.stdout).unwrap();
    assert!(v["H_c"].as_f64().unwrap() < b["H_c"].as_f64().unwrap());
}

#[test]
fn profile_parquet_reads_back() {
    use arrow_array::Float64Array;
    use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
    let dir = std::env::temp_dir().join(format!("ehlmap-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("profile.parquet");
    let out = ehlmap(&[
        "solve",
        "--M",
        "20",
        "--L",
        "10",
        "--grid",
        "513",
        "--profile",
        path.to_str().unwrap(),
        "--json",
    ]);
    assert!(out.status.success());
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let load_error = json["load_error"].as_f64().unwrap();
    let file = std::fs::File::open(&path).unwrap();
    let builder = ParquetRecordBatchReaderBuilder::try_new(file).unwrap();
    let kv = builder
        .metadata()
        .file_metadata()
        .key_value_metadata()
        .unwrap()
        .clone();
    assert!(kv
        .iter()
        .any(|k| k.key == "M" && k.value.as_deref() == Some("20")));
    let mut rows = 0;
    let mut load = 0.0;
    let mut xs = vec![];
    for batch in builder.build().unwrap() {
        let b = batch.unwrap();
        let x = b
            .column_by_name("X")
            .unwrap()
            .as_any()
            .downcast_ref::<Float64Array>()
            .unwrap();
        let p = b
            .column_by_name("P")
            .unwrap()
            .as_any()
            .downcast_ref::<Float64Array>()
            .unwrap();
        rows += b.num_rows();
        xs.extend(x.values().iter().copied());
        load += p.values().iter().sum::<f64>();
        assert!(p.values().iter().all(|&v| v >= 0.0));
    }
    assert_eq!(rows, 513);
    let h = xs[1] - xs[0];
    // The profile carries the load the solve reports (the default stopping rule leaves a load
    // error well below its algebraic error estimate, 4e-6 here).
    let profile_error = load * h / std::f64::consts::FRAC_PI_2 - 1.0;
    assert!(
        (profile_error - load_error).abs() < 1e-9,
        "{profile_error} vs {load_error}"
    );
    assert!(load_error.abs() < 1e-5, "{load_error}");
    std::fs::remove_dir_all(&dir).ok();
}
