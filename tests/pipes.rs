//! Every command that prints, with stdout a pipe whose reader closes early: closed before the
//! command starts (every write fails with EPIPE), or after reading one line of an output larger
//! than the pipe's buffer. The command stops quietly with exit code 0 (docs/cli.md, exit codes),
//! never a panic; what it writes to files is written all the same. A closed stderr is ignored.
//! Solves are tiny (33 to 257 points) so that the file runs in seconds.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

/// The exit code of a command whose stdout was closed by its reader (docs/cli.md).
const CLOSED: i32 = 0;

fn ehlmap(args: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_ehlmap"));
    c.args(args).stdin(Stdio::null());
    for v in [
        "SLURM_ARRAY_TASK_ID",
        "SLURM_ARRAY_TASK_COUNT",
        "SLURM_CPUS_PER_TASK",
        "EHLMAP_MAX_MEMORY",
    ] {
        c.env_remove(v);
    }
    c
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("ehlmap-pipes-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn data(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
        .display()
        .to_string()
}

/// No panic, no abort, the documented code.
fn quiet(what: &str, o: &Output) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!err.contains("panicked"), "{what}: {err}");
    assert_eq!(o.status.code(), Some(CLOSED), "{what}: {err}");
    assert!(!err.contains("Broken pipe"), "{what}: {err}");
}

/// Run with stdout a pipe whose read end is closed before the command starts.
fn closed_before(args: &[&str]) -> Output {
    let (r, w) = std::io::pipe().unwrap();
    drop(r);
    let o = ehlmap(args)
        .stdout(Stdio::from(w))
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    quiet(&format!("{args:?}, stdout closed before"), &o);
    o
}

/// Run with stdout piped, read one line (`want_line`: there must be one), then close it.
fn closed_after_one_line(args: &[&str], want_line: bool) -> Output {
    let mut child = ehlmap(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut line = String::new();
    {
        let mut r = BufReader::new(child.stdout.take().unwrap());
        r.read_line(&mut line).unwrap();
    } // the reader, and with it the pipe's read end, is dropped here
    if want_line {
        assert!(!line.is_empty(), "{args:?}: no output");
    }
    let o = child.wait_with_output().unwrap();
    quiet(&format!("{args:?}, stdout closed after one line"), &o);
    o
}

/// Both ways of closing.
fn both(args: &[&str]) {
    closed_before(args);
    closed_after_one_line(args, true);
}

#[test]
fn solve_summary_and_json() {
    both(&["solve", "--M", "20", "--L", "5", "--grid", "65"]);
    both(&["solve", "--M", "20", "--grid", "65", "--json"]);
    both(&[
        "solve",
        "--contact",
        "point",
        "--D",
        "1",
        "--M",
        "20",
        "--grid",
        "33",
    ]);
    both(&[
        "solve",
        "--M",
        "20",
        "--accuracy",
        "0.05",
        "--max-grid",
        "513",
    ]);
    // A failed solve prints its status: the same.
    both(&["solve", "--M", "1e-300", "--grid", "65"]);
}

#[test]
fn solve_still_writes_its_files() {
    let dir = scratch("solve-files");
    let profile = dir.join("p.parquet");
    let plots = dir.join("plots");
    closed_before(&[
        "solve",
        "--M",
        "20",
        "--grid",
        "65",
        "--profile",
        profile.to_str().unwrap(),
        "--plot",
        plots.to_str().unwrap(),
    ]);
    assert!(profile.is_file());
    assert!(plots.join("line-M20-L0-profile.png").is_file());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn case_report_json_and_no_solve() {
    let dir = scratch("case");
    let file = dir.join("c.toml");
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("sweeps/cases/example-7-1.toml"),
    )
    .unwrap()
    .replace("u2 = 1.08\n", "u2 = 1.08\ngrid = 129\n");
    assert!(
        text.contains("grid = 129"),
        "the example's speeds moved: {text}"
    );
    std::fs::write(&file, text).unwrap();
    let f = file.to_str().unwrap();
    both(&["case", f]);
    both(&["case", f, "--json"]);
    both(&["case", f, "--no-solve"]);
    // the issue's own command, on the example's own grid
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("sweeps/cases/example-7-1.toml");
    closed_before(&["case", example.to_str().unwrap(), "--no-solve"]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn sweep_dry_run_larger_than_the_pipe() {
    let dir = scratch("dry-run");
    // 10 000 cases: about 600 kB of plan, far more than a pipe holds, so the command is still
    // writing when the reader goes.
    let spec = dir.join("big.toml");
    std::fs::write(
        &spec,
        "name = \"big\"\ncontact = \"line\"\n[axes]\nM = { from = 1, to = 1000, count = 100, scale = \"log\" }\n\
         L = { from = 0, to = 10, count = 100 }\n[numerics]\ngrid = 65\n",
    )
    .unwrap();
    let out = dir.join("out");
    let args = [
        "sweep",
        spec.to_str().unwrap(),
        "--dry-run",
        "--out",
        out.to_str().unwrap(),
    ];
    closed_before(&args);
    let o = closed_after_one_line(&args, true);
    assert!(
        o.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    // the command
    let nightly = Path::new(env!("CARGO_MANIFEST_DIR")).join("sweeps/nightly-line.toml");
    both(&[
        "sweep",
        nightly.to_str().unwrap(),
        "--dry-run",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!out.exists(), "a dry run writes nothing");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn sweep_with_fit_stores_its_rows_and_report() {
    let dir = scratch("sweep-fit");
    let spec = dir.join("sf.toml");
    std::fs::write(
        &spec,
        "name = \"sf\"\ncontact = \"line\"\n[axes]\nM = [5, 10, 20, 50, 100, 200]\nL = [0, 2, 5]\n\
         [numerics]\ngrid = 257\n",
    )
    .unwrap();
    closed_before(&[
        "sweep",
        spec.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
        "--progress",
        "none",
        "--fit",
    ]);
    assert!(dir.join("sf/part-1of1-0001.parquet").is_file());
    assert!(dir.join("sf-report/report.md").is_file());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn fit_report_and_json() {
    let dir = scratch("fit");
    let out = dir.join("report");
    let (ds, o) = (data("smoke-line"), out.to_str().unwrap().to_string());
    both(&["fit", &ds, "--out", &o, "--no-limit-solves"]);
    both(&["fit", &ds, "--out", &o, "--json", "--no-limit-solves"]);
    closed_before(&["fit", &ds, "--out", &o, "--json"]);
    assert!(out.join("report.md").is_file() && out.join("fit.json").is_file());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bench_selection_stability_and_chart() {
    let dir = scratch("bench");
    let spec = dir.join("sel.toml");
    std::fs::write(
        &spec,
        "name = \"sel\"\ncontact = \"line\"\n[axes]\nM = [10, 20]\nL = [0]\n[numerics]\ngrid = 129\n",
    )
    .unwrap();
    let d = |s: &str| dir.join(s).to_str().unwrap().to_string();
    both(&[
        "bench",
        "--selection",
        spec.to_str().unwrap(),
        "--out",
        &d("bench"),
    ]);
    assert!(dir.join("bench/selection.md").is_file());
    closed_before(&["stability", "--quick", "--grid", "33", "--out", &d("st")]);
    assert!(dir.join("st/stability.md").is_file());
    both(&["chart", "regimes", "--out", &d("charts")]);
    both(&["chart", "regimes", "--D", "0.5", "--out", &d("charts")]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn help_and_version() {
    both(&["--help"]);
    both(&["--version"]);
    both(&["solve", "--help"]);
    both(&["sweep", "--help"]);
}

#[test]
fn a_closed_stderr_is_ignored() {
    // --trace writes every cycle to stderr; a sweep writes its log lines there.
    let run = |args: &[&str]| {
        let (r, w) = std::io::pipe().unwrap();
        drop(r);
        let o = ehlmap(args)
            .stdout(Stdio::piped())
            .stderr(Stdio::from(w))
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(0), "{args:?}");
        o
    };
    let o = run(&["solve", "--M", "20", "--grid", "65", "--trace", "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("the JSON all the same");
    assert_eq!(v["grid"], 65);
    let dir = scratch("stderr");
    let spec = dir.join("t.toml");
    std::fs::write(
        &spec,
        "name = \"t\"\ncontact = \"line\"\n[axes]\nM = [10, 20, 30]\nL = [0]\n[numerics]\ngrid = 65\n",
    )
    .unwrap();
    for progress in ["log", "bar", "auto"] {
        let out = dir.join(progress);
        run(&[
            "sweep",
            spec.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--progress",
            progress,
        ]);
        assert!(out.join("t/part-1of1-0001.parquet").is_file());
    }
    // an error message on a closed stderr: the exit code still says it
    let (r, w) = std::io::pipe().unwrap();
    drop(r);
    let o = ehlmap(&["solve", "--M", "-1"])
        .stderr(Stdio::from(w))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    std::fs::remove_dir_all(&dir).ok();
}

/// The speed ladder takes minutes (`ehlmap bench --quick`): run with `--ignored`.
#[test]
#[ignore]
fn bench_speed_ladder() {
    let dir = scratch("bench-ladder");
    closed_before(&[
        "bench",
        "--quick",
        "--repeats",
        "1",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(dir.join("bench.md").is_file());
    std::fs::remove_dir_all(&dir).ok();
}
