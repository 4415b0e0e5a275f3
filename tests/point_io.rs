//! Point contacts through the command line, sweep specs, sweeps and storage: exit codes, JSON
//! names, the fields file, D and k (exact Hertz ellipse), converged rows with error estimates,
//! and no NaN in any file.

use arrow_array::Float64Array;
use ehlmap::solve::point::PointFields;
use ehlmap::store::fields::write_fields;
use ehlmap::store::results::read_dataset;
use ehlmap::sweep::spec::{self, Contact};
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn ehlmap(args: &[&str]) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_ehlmap"));
    c.args(args);
    for v in [
        "SLURM_ARRAY_TASK_ID",
        "SLURM_ARRAY_TASK_COUNT",
        "SLURM_ARRAY_TASK_MIN",
        "SLURM_ARRAY_TASK_STEP",
        "SLURM_CPUS_PER_TASK",
    ] {
        c.env_remove(v);
    }
    c.output().expect("run ehlmap")
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("ehlmap-point-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Status strings a row may carry (the solver's statuses, plus the executor's own).
const STATUSES: [&str; 6] = [
    "converged",
    "diverged",
    "stalled",
    "max-iterations",
    "invalid",
    "panic",
];

#[test]
fn point_specs_parse_and_bad_ones_name_the_key() {
    let head = "contact = \"point\"\n[axes]\nM = [10, 100]\nL = [0, 10]\n";
    let s = spec::parse("p.toml", &format!("{head}D = [0.5, 1]\n"), "p").unwrap();
    assert_eq!(s.contacts[0].contact, Contact::Point);
    assert_eq!(s.d.as_deref(), Some(&[0.5, 1.0][..]));
    // No grid named: the default 1 % target, up to 1025^2.
    let n = &s.contacts[0].numerics;
    assert_eq!((n.grid, n.accuracy), (1025, Some(0.01)));
    let s = spec::parse(
        "p.toml",
        &format!("{head}D = {{ from = 0.05, to = 1, count = 4, scale = \"log\" }}\n"),
        "p",
    )
    .unwrap();
    assert_eq!(s.d.as_ref().map(|d| d.len()), Some(4));
    for (text, line, key, needle) in [
        (format!("{head}D = [0]\n"), 5, "axes.D", "D = 0 is invalid"),
        (
            format!("{head}D = [0.5, 1.5]\n"),
            5,
            "axes.D",
            "D = 1.5 is invalid",
        ),
        (head.to_string(), 2, "axes.D", "missing"),
        (
            "contact = \"line\"\n[axes]\nM = [10]\nL = [0]\nD = [0.5]\n".to_string(),
            5,
            "axes.D",
            "point\" only",
        ),
        (
            format!("{head}D = [1]\n[numerics]\ngrid = 4097\n"),
            7,
            "numerics.grid",
            "from 17 to 2049",
        ),
    ] {
        let e = spec::parse("p.toml", &text, "p").unwrap_err();
        assert_eq!((e.line, e.key.as_str()), (line, key), "{e}");
        assert!(e.message.contains(needle), "{e}");
    }
    // The same errors through the binary: exit 2, one line `FILE:LINE: KEY: ...`, nothing run.
    let dir = scratch("specs");
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, format!("{head}D = [1.5]\n")).unwrap();
    let out_dir = dir.join("out");
    let o = ehlmap(&[
        "sweep",
        bad.to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains(&format!("{}:5: axes.D: D = 1.5 is invalid", bad.display())),
        "{}",
        stderr(&o)
    );
    assert!(!out_dir.exists());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn committed_point_specs_are_valid() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let smoke = spec::load(&root.join("sweeps/smoke-point.toml")).unwrap();
    assert_eq!(smoke.contacts[0].contact, Contact::Point);
    assert_eq!(smoke.contacts[0].numerics.grid, 65);
    assert_eq!(ehlmap::sweep::plan::plan(&smoke).unwrap().len(), 8);
    let nightly = spec::load(&root.join("sweeps/nightly-point.toml")).unwrap();
    assert_eq!(nightly.contacts[0].numerics.grid, 513);
    assert!(nightly.contacts[0].numerics.error_estimate);
    assert_eq!(nightly.m.len(), 8);
    assert_eq!((nightly.m[0], nightly.m[7]), (1.0, 1000.0));
    assert_eq!(ehlmap::sweep::plan::plan(&nightly).unwrap().len(), 224);
    // The fit tests' dataset is the nightly sweep from M = 7.2 up.
    let data = spec::load(&root.join("tests/data/point-257.toml")).unwrap();
    assert_eq!(data.contacts[0].numerics.grid, 257);
    assert_eq!(data.m[..], nightly.m[2..]);
    assert_eq!(ehlmap::sweep::plan::plan(&data).unwrap().len(), 96);
}

#[test]
fn bad_point_input_exits_2_naming_the_value() {
    let base = ["solve", "--contact", "point", "--M", "100", "--L", "10"];
    for (extra, needle) in [
        (vec!["--D", "0"], "D = 0"),
        (vec!["--D", "1.5"], "D = 1.5"),
        (vec!["--D", "-0.2"], "D = -0.2"),
        (
            vec!["--D", "0.5", "--method", "newton"],
            "use --grid 33 or less",
        ),
        (vec!["--D", "0.5", "--grid", "9"], "--grid 9"),
        (vec!["--D", "0.5", "--grid", "4097"], "--grid 4097"),
        (vec!["--D", "0.5", "--profile", "p.parquet"], "--profile"),
        (
            vec!["--D", "0.5", "--accuracy", "1.5"],
            "--accuracy 1.5 is invalid",
        ),
        (vec!["--D", "0.5", "--viscosity", "roelands"], "--ph"),
    ] {
        let mut args: Vec<&str> = base.to_vec();
        args.extend(extra.iter().copied());
        let o = ehlmap(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(needle), "{args:?}: {}", stderr(&o));
        assert_eq!(stderr(&o).lines().count(), 1, "{args:?}");
    }
    // Without --D a point contact is circular.
    let o = ehlmap(&[
        "solve",
        "--contact",
        "point",
        "--M",
        "20",
        "--L",
        "10",
        "--grid",
        "33",
        "--json",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!((v["D"].as_f64(), v["k"].as_f64()), (Some(1.0), Some(1.0)));
    let o = ehlmap(&["solve", "--M", "20", "--D", "0.5"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--D applies to point contacts only"));
    let o = ehlmap(&["solve", "--M", "20", "--fields", "f.parquet"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--fields applies to point contacts only"));
}

/// `ehlmap solve --json` of the circular case (M, L = 10) on `grid`^2 nodes.
fn circular_json(m: &str, grid: &str) -> Output {
    ehlmap(&[
        "solve",
        "--contact",
        "point",
        "--D",
        "1",
        "--M",
        m,
        "--L",
        "10",
        "--grid",
        grid,
        "--json",
    ])
}

#[test]
fn point_json_has_the_line_fields_plus_d_k_y_min() {
    let o = circular_json("100", "33");
    // A non-converged solve is a result: exit 0, like the line solve.
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("one JSON object");
    let mut keys: Vec<&str> = v.as_object().unwrap().keys().map(|s| s.as_str()).collect();
    keys.sort();
    let mut want = vec![
        "H_c",
        "H_c_pmax",
        "H_min",
        "X_min",
        "Y_min",
        "H_min_cl",
        "X_min_cl",
        "H_min_cl_err",
        "D",
        "k",
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
    assert_eq!(
        v["level"], 1,
        "33^2 nodes are 2 x 16 intervals per direction"
    );
    assert_eq!(v["D"], 1.0);
    assert_eq!(v["k"], 1.0);
    assert!(STATUSES.contains(&v["status"].as_str().unwrap()));
    assert_eq!(v["status"], "converged", "{}", v["reason"]);
    for key in ["H_c", "H_min", "Y_min"] {
        assert!(
            v[key].as_f64().is_some_and(|x| x.is_finite()),
            "{key}: {}",
            v[key]
        );
    }
    assert!(v["H_c"].as_f64().unwrap() > 0.0);
    // The centre line's minimum film: a second branch of the minimum, never below H_min; no
    // estimate from a 17^2 half grid.
    let (h_min, h_min_cl) = (
        v["H_min"].as_f64().unwrap(),
        v["H_min_cl"].as_f64().unwrap(),
    );
    assert!(h_min_cl >= h_min && h_min > 0.0, "{h_min_cl} {h_min}");
    assert!(v["X_min_cl"].as_f64().is_some_and(|x| x > 0.0 && x < 1.5));
    assert!(v["H_min_cl_err"].is_null());
    let with_estimate = circular_json("20", "65");
    let e: serde_json::Value = serde_json::from_slice(&with_estimate.stdout).unwrap();
    let err = e["H_min_cl_err"].as_f64().expect("a half-grid estimate");
    assert!(err > 0.0 && err < 0.1, "{err}");
    let text = ehlmap(&[
        "solve",
        "--contact",
        "point",
        "--D",
        "0.25",
        "--M",
        "100",
        "--L",
        "10",
        "--grid",
        "33",
    ]);
    assert_eq!(text.status.code(), Some(0));
    let t = String::from_utf8_lossy(&text.stdout);
    assert!(
        t.starts_with("point contact  M = 100  L = 10  D = 0.25  (k = "),
        "{t}"
    );
    assert!(t.contains("H_min, Y = 0   "), "{t}");
}

#[test]
fn fields_file_round_trips() {
    let dir = scratch("fields");
    // A small fake field (the placeholder solver returns none).
    let x: Vec<f64> = (0..4).map(|i| -1.5 + i as f64).collect();
    let y: Vec<f64> = vec![-1.0, 0.0, 1.0];
    let n = x.len() * y.len();
    let p: Vec<f64> = (0..n).map(|i| i as f64 / n as f64).collect();
    let h: Vec<f64> = (0..n).map(|i| 1.0 + i as f64).collect();
    let f = PointFields {
        x: x.clone(),
        y: y.clone(),
        p: p.clone(),
        h: h.clone(),
        p_asperity: None,
    };
    let path = dir.join("fields.parquet");
    write_fields(&path, &f, &[("M", "100".into()), ("D", "0.5".into())]).unwrap();
    let builder =
        ParquetRecordBatchReaderBuilder::try_new(std::fs::File::open(&path).unwrap()).unwrap();
    let kv = builder
        .metadata()
        .file_metadata()
        .key_value_metadata()
        .unwrap()
        .clone();
    assert!(kv
        .iter()
        .any(|k| k.key == "D" && k.value.as_deref() == Some("0.5")));
    let mut rows = 0;
    let mut cols: Vec<Vec<f64>> = vec![vec![]; 4];
    for b in builder.build().unwrap() {
        let b = b.unwrap();
        rows += b.num_rows();
        assert_eq!(b.schema().fields().len(), 4);
        for (c, name) in cols.iter_mut().zip(["X", "Y", "P", "H"]) {
            let a = b.column_by_name(name).unwrap();
            let a = a.as_any().downcast_ref::<Float64Array>().unwrap();
            c.extend(a.values().iter().copied());
        }
    }
    assert_eq!(rows, n);
    for (j, &yj) in y.iter().enumerate() {
        for (i, &xi) in x.iter().enumerate() {
            let r = j * x.len() + i;
            assert_eq!(
                (cols[0][r], cols[1][r], cols[2][r], cols[3][r]),
                (xi, yj, p[r], h[r])
            );
        }
    }
    // Through the command line: one row per node of the 33 x 33 grid.
    let cli = dir.join("cli.parquet");
    let o = ehlmap(&[
        "solve",
        "--contact",
        "point",
        "--D",
        "0.5",
        "--M",
        "100",
        "--grid",
        "33",
        "--fields",
        cli.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let b = ParquetRecordBatchReaderBuilder::try_new(std::fs::File::open(&cli).unwrap()).unwrap();
    let rows = b.metadata().file_metadata().num_rows() as usize;
    assert_eq!(rows, 33 * 33);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn point_sweep_writes_one_row_per_case() {
    let dir = scratch("sweep");
    let spec = dir.join("tiny-point.toml");
    std::fs::write(
        &spec,
        "name = \"tiny-point\"\ncontact = \"point\"\n[axes]\nM = [10, 30]\nL = [0]\n\
         D = [0.25, 1]\n[numerics]\ngrid = 65\nerror_estimate = true\n",
    )
    .unwrap();
    let out_dir = dir.join("out");
    let args = [
        "sweep",
        spec.to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
        "--threads",
        "2",
        "--progress",
        "none",
    ];
    let o = ehlmap(&args);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let rows = read_dataset(&out_dir.join("tiny-point")).unwrap();
    assert_eq!(rows.len(), 4);
    let ids: std::collections::HashSet<&str> = rows.iter().map(|r| r.case_id.as_str()).collect();
    assert_eq!(ids.len(), 4);
    for r in &rows {
        assert_eq!(r.contact, "point");
        assert_eq!(r.sweep, "tiny-point");
        assert_eq!(r.grid_requested, 65);
        assert!(r.half_grid_estimate);
        let d = r.d.expect("D filled");
        let k = r.k.expect("k filled");
        if d == 1.0 {
            assert_eq!(k, 1.0);
        } else {
            assert_eq!(d, 0.25);
            // The exact Hertz ellipse of D = 0.25 (k ~ D^(-2/pi) ~ 2.4).
            assert!(k > 2.0 && k < 3.0, "k = {k}");
        }
        assert!(STATUSES.contains(&r.status.as_str()), "{}", r.status);
        assert_ne!(r.status, "panic", "{}", r.reason);
        assert_ne!(r.status, "invalid", "{}", r.reason);
        assert!(r.attempt.is_some() && r.grid.is_some());
        // No non-finite value in the file, and a nulled output clears `valid`.
        let outs = [r.h_c, r.h_c_pmax, r.h_min, r.x_min, r.y_min, r.p_max, r.h0];
        assert!(outs.iter().flatten().all(|v| v.is_finite()));
        if outs.iter().any(|v| v.is_none()) {
            assert!(!r.valid);
        }
        assert_eq!(r.status, "converged", "{}", r.reason);
        assert!(r.valid);
        assert!(outs.iter().all(|v| v.is_some()));
        assert!(r.h_c.unwrap() > 0.0 && r.h_min.unwrap() > 0.0);
        assert!(r.h_c_err.is_some() && r.h_min_err.is_some());
    }
    // A rerun solves nothing: the case ids are stored.
    let o = ehlmap(&args);
    assert_eq!(o.status.code(), Some(0));
    assert!(stderr(&o).contains("4 already stored"), "{}", stderr(&o));
    // --fit on 4 point cases on 33^2 nodes (three with error estimates above the fit's 2 %
    // cut): too few to fit, a clear error (exit 2) naming the count.
    let mut fit = args.to_vec();
    fit.push("--fit");
    let o = ehlmap(&fit);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("too few converged cases to fit")
            && stderr(&o).contains("point skipped: 1 cases, need at least 10"),
        "{}",
        stderr(&o)
    );
    std::fs::remove_dir_all(&dir).ok();
}
