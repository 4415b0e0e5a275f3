//! The `ehlmap solve` command line: JSON field names, exit codes on bad input, and the Parquet
//! profile read back with the arrow-rs reader.

use std::process::Command;

fn ehlmap(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_ehlmap"))
        .args(args)
        .output()
        .expect("run ehlmap")
}

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
    ];
    want.sort();
    assert_eq!(keys, want);
    assert_eq!(v["model_used"], "full");
    assert_eq!(v["level"], 5, "1025 points are 2^5 x 32 intervals");
    assert_eq!(v["status"], "converged");
    assert_eq!(v["grid"], 1025);
    let hc = v["H_c"].as_f64().unwrap();
    assert!((hc / 5.2655 - 1.0).abs() < 1e-3, "H_c {hc}");
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
