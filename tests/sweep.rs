//! `ehlmap sweep`: spec validation through the binary (exit code 2, file:line: key), identical
//! rows for 1 and 2 threads, shards whose union is the whole sweep (also from the Slurm array
//! variables), resume skipping stored ids, and a real `kill -9` of a running sweep.
//! The sweeps are tiny (257 points) so that the file runs in seconds.

use ehlmap::store::results::{is_part_name, part_files, read_dataset, read_part, CaseRow};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

mod common;
use common::SLURM_VARS;

fn ehlmap_cmd(args: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_ehlmap"));
    c.args(args);
    for v in SLURM_VARS {
        c.env_remove(v);
    }
    c
}

fn ehlmap(args: &[&str]) -> Output {
    ehlmap_cmd(args).output().expect("run ehlmap")
}

/// A fresh scratch directory for one test, removed when the test passes.
fn scratch(name: &str) -> common::Scratch {
    common::Scratch::new(&format!("sweep-{name}"))
}

fn write(dir: &Path, file: &str, text: &str) -> PathBuf {
    let p = dir.join(file);
    std::fs::write(&p, text).unwrap();
    p
}

fn ok(out: &Output) {
    assert!(
        out.status.success(),
        "exit {:?}\nstdout: {}\nstderr: {}",
        out.status.code(),
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Rows without the only column that may differ between identical solves.
fn comparable(mut rows: Vec<CaseRow>) -> Vec<CaseRow> {
    for r in &mut rows {
        r.wall_s = None;
    }
    rows
}

const SMALL: &str = r#"
name = "small"
contact = "line"
[axes]
M = [5, 20, 100]
L = { from = 0, to = 10, count = 2 }
[numerics]
grid = 257
[output]
batch = 2
"#;

#[test]
fn bad_specs_exit_2_naming_file_line_and_key() {
    let dir = scratch("bad");
    let head = "contact = \"line\"\n[axes]\n";
    let cases: Vec<(&str, String, &str)> = vec![
        // (file, text, expected "file:line: key" and message fragment)
        (
            "unknown.toml",
            format!("{head}M = [5]\nL = [0]\nQ = [1]\n"),
            ":5: axes.Q: unknown key",
        ),
        (
            "unknown_top.toml",
            format!("grdi = 3\n{head}M = [5]\nL = [0]\n"),
            ":1: grdi: unknown key",
        ),
        (
            "empty.toml",
            format!("{head}M = []\nL = [0]\n"),
            ":3: axes.M: the axis is empty",
        ),
        (
            "m_zero.toml",
            format!("{head}M = [5, 0]\nL = [0]\n"),
            ":3: axes.M: M = 0 is invalid",
        ),
        (
            "m_neg.toml",
            format!("{head}L = [0]\nM = {{ from = -1, to = 10, count = 3 }}\n"),
            ":4: axes.M: M = -1 is invalid",
        ),
        (
            "l_neg.toml",
            format!("{head}M = [5]\nL = [0, -2]\n"),
            ":4: axes.L: L = -2 is invalid",
        ),
        (
            "d_range.toml",
            "contact = \"point\"\n[axes]\nM = [5]\nL = [0]\nD = [0.5, 1.5]\n".to_string(),
            ":5: axes.D: D = 1.5 is invalid",
        ),
        (
            "point_no_d.toml",
            "contact = \"point\"\n[axes]\nM = [5]\nL = [0]\n".to_string(),
            ":2: axes.D: missing: contact = \"point\" needs the ellipticity axis D",
        ),
        (
            "line_d.toml",
            format!("{head}M = [5]\nL = [0]\nD = [0.5]\n"),
            ":5: axes.D: the ellipticity axis D applies to contact = \"point\" only",
        ),
        (
            "log_range.toml",
            format!("{head}M = [5]\nL = {{ from = 0, to = 10, count = 3, scale = \"log\" }}\n"),
            ":4: axes.L.scale: a log range needs from > 0",
        ),
        (
            "count.toml",
            format!("{head}M = {{ from = 1, to = 10, count = 0 }}\nL = [0]\n"),
            ":3: axes.M.count: must be an integer",
        ),
        (
            "range_key.toml",
            format!("{head}M = {{ from = 1, to = 10, n = 4 }}\nL = [0]\n"),
            ":3: axes.M.n: unknown key",
        ),
        (
            "grid.toml",
            format!("{head}M = [5]\nL = [0]\n[numerics]\ngrid = 9\n"),
            ":6: numerics.grid: must be an integer from 33",
        ),
        (
            "roelands.toml",
            format!("{head}M = [5]\nL = [1]\n[models]\nviscosity = \"roelands\"\nph = 1e9\n"),
            ":6: models.viscosity: roelands needs exactly one of",
        ),
        (
            "syntax.toml",
            format!("{head}M = [5\nL = [0]\n"),
            ":4: invalid TOML: missing comma",
        ),
    ];
    for (file, text, want) in &cases {
        let spec = write(&dir, file, text);
        let out_dir = dir.join("out");
        let out = ehlmap(&[
            "sweep",
            spec.to_str().unwrap(),
            "--out",
            out_dir.to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{file}: {err}");
        let expected = format!("{}{want}", spec.display());
        assert!(
            err.contains(&expected),
            "{file}: want `{expected}` in `{err}`"
        );
        assert_eq!(err.lines().count(), 1, "{file}: one line: {err}");
        assert!(!out_dir.exists(), "{file}: nothing may run on a bad spec");
    }
    // Bad arguments are input errors too.
    let spec = write(&dir, "good.toml", SMALL);
    for (args, want) in [
        (vec!["--shard", "3/2"], "--shard 3/2"),
        (vec!["--shard", "x"], "--shard x"),
        (vec!["--resume"], "--resume"),
    ] {
        let mut a = vec!["sweep", spec.to_str().unwrap(), "--out"];
        let o = dir.join("out2");
        a.push(o.to_str().unwrap());
        a.extend(args);
        let out = ehlmap(&a);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains(want), "want {want} in {err}");
    }
    let missing = dir.join("missing.toml");
    let out = ehlmap(&["sweep", missing.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("missing.toml"));
}

#[test]
fn one_and_two_threads_give_identical_rows() {
    let dir = scratch("threads");
    let spec = write(&dir, "small.toml", SMALL);
    let mut sets = vec![];
    for t in ["1", "2"] {
        let out_dir = dir.join(format!("t{t}"));
        ok(&ehlmap(&[
            "sweep",
            spec.to_str().unwrap(),
            "--out",
            out_dir.to_str().unwrap(),
            "--threads",
            t,
            "--progress",
            "none",
        ]));
        let ds = out_dir.join("small");
        let parts = part_files(&ds).unwrap();
        assert_eq!(parts.len(), 1);
        assert_eq!(
            parts[0].file_name().unwrap().to_str().unwrap(),
            "part-1of1-0001.parquet"
        );
        let part = read_part(&parts[0]).unwrap();
        for key in [
            "ehlmap_version",
            "git_commit",
            "created",
            "spec_file",
            "run",
        ] {
            assert!(
                part.meta.get(key).is_some_and(|v| !v.is_empty()),
                "footer {key}"
            );
        }
        assert_eq!(part.meta["spec"], SMALL);
        assert_eq!(part.meta["shard"], "1/1");
        assert_eq!(part.meta["sweep"], "small");
        assert_eq!(part.meta["cases_total"], "6");
        let rows = read_dataset(&ds).unwrap();
        sets.push(rows);
    }
    let rows = &sets[0];
    assert_eq!(rows.len(), 6);
    for r in rows {
        assert_eq!(r.status, "converged", "{r:?}");
        assert!(r.valid && r.h_c.unwrap() > 0.0 && r.wall_s.unwrap() > 0.0);
        assert_eq!((r.d, r.k, r.y_min), (None, None, None));
        assert_eq!(r.grid, Some(257));
        assert_eq!(r.case_id.len(), 16);
    }
    // M = 20, L = 10: the solver's H_c within its discretisation error at 257 points.
    let r = rows.iter().find(|r| r.m == 20.0 && r.l == 10.0).unwrap();
    assert!((r.h_c.unwrap() / 5.27 - 1.0).abs() < 0.05, "{r:?}");
    assert_eq!(comparable(sets[0].clone()), comparable(sets[1].clone()));
}

#[test]
fn union_of_shards_equals_the_whole_sweep() {
    let dir = scratch("shards");
    let spec = write(&dir, "small.toml", SMALL);
    let run = |out: &Path, extra: &[&str], env: &[(&str, &str)]| {
        let mut a = vec![
            "sweep",
            spec.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--threads",
            "1",
        ];
        a.extend(extra);
        let mut c = ehlmap_cmd(&a);
        c.envs(env.iter().copied());
        ok(&c.output().unwrap());
        out.join("small")
    };
    let whole = read_dataset(&run(&dir.join("whole"), &[], &[])).unwrap();
    let sharded = dir.join("sharded");
    run(&sharded, &["--shard", "1/2"], &[]);
    run(&sharded, &["--shard", "2/2"], &[]);
    let files = part_files(&sharded.join("small")).unwrap();
    let names: Vec<_> = files
        .iter()
        .map(|p| p.file_name().unwrap().to_str().unwrap().to_string())
        .collect();
    assert_eq!(names, ["part-1of2-0001.parquet", "part-2of2-0001.parquet"]);
    let s1 = read_part(&files[0]).unwrap().rows;
    let s2 = read_part(&files[1]).unwrap().rows;
    assert!(!s1.is_empty() && !s2.is_empty());
    assert_eq!(s1.len() + s2.len(), whole.len());
    assert!(s1.iter().all(|a| s2.iter().all(|b| a.case_id != b.case_id)));
    assert_eq!(
        comparable(read_dataset(&sharded.join("small")).unwrap()),
        comparable(whole.clone())
    );
    // The Slurm array variables select the same slice as --shard (array 0-1: task 1 is 2/2).
    let slurm = run(
        &dir.join("slurm"),
        &[],
        &[
            ("SLURM_ARRAY_TASK_ID", "1"),
            ("SLURM_ARRAY_TASK_MIN", "0"),
            ("SLURM_ARRAY_TASK_COUNT", "2"),
            ("SLURM_CPUS_PER_TASK", "1"),
        ],
    );
    let files = part_files(&slurm).unwrap();
    assert_eq!(
        files[0].file_name().unwrap().to_str().unwrap(),
        "part-2of2-0001.parquet"
    );
    assert_eq!(comparable(read_dataset(&slurm).unwrap()), comparable(s2));
}

#[test]
fn rerun_and_resume_skip_stored_case_ids() {
    let dir = scratch("resume");
    let out = dir.join("out");
    let two =
        "name = \"r\"\ncontact = \"line\"\n[axes]\nM = [5, 20]\nL = [0]\n[numerics]\ngrid = 257\n";
    let three = "name = \"r\"\ncontact = \"line\"\n[axes]\nM = [5, 20, 100]\nL = [0]\n[numerics]\ngrid = 257\n";
    let spec = write(&dir, "r.toml", two);
    let args = |extra: &[&'static str]| {
        let mut a = vec![
            "sweep".to_string(),
            spec.to_str().unwrap().to_string(),
            "--out".to_string(),
            out.to_str().unwrap().to_string(),
        ];
        a.extend(extra.iter().map(|s| s.to_string()));
        a
    };
    let run = |extra: &[&'static str]| {
        let a = args(extra);
        let refs: Vec<&str> = a.iter().map(|s| s.as_str()).collect();
        let o = ehlmap(&refs);
        ok(&o);
        String::from_utf8_lossy(&o.stderr).into_owned()
    };
    let ds = out.join("r");
    run(&[]);
    assert_eq!(part_files(&ds).unwrap().len(), 1);
    let first = read_dataset(&ds).unwrap();
    // The spec gains a value: only the new case is solved, into a second file.
    std::fs::write(&spec, three).unwrap();
    let log = run(&["--resume"]);
    assert!(log.contains("2 already stored, 1 solved"), "{log}");
    let files = part_files(&ds).unwrap();
    assert_eq!(files.len(), 2);
    let new_rows = read_part(&files[1]).unwrap().rows;
    assert_eq!(new_rows.len(), 1);
    assert_eq!(new_rows[0].m, 100.0);
    assert_eq!(read_part(&files[0]).unwrap().rows, first);
    // Everything stored: a rerun solves nothing and writes nothing.
    let log = run(&[]);
    assert!(log.contains("3 already stored, 0 solved"), "{log}");
    assert_eq!(part_files(&ds).unwrap().len(), 2);
    let dry = ehlmap(
        &args(&["--dry-run"])
            .iter()
            .map(|s| s.as_str())
            .collect::<Vec<_>>(),
    );
    ok(&dry);
    let text = String::from_utf8_lossy(&dry.stdout);
    assert_eq!(text.lines().filter(|l| l.ends_with(" true")).count(), 3);
}

#[test]
fn kill_9_leaves_readable_files_and_a_rerun_completes_the_set() {
    let dir = scratch("kill");
    let spec = write(
        &dir,
        "k.toml",
        r#"
name = "k"
contact = "line"
[axes]
M = { from = 2, to = 400, count = 20, scale = "log" }
L = [0, 4, 8]
[numerics]
grid = 257
[output]
batch = 1
"#,
    );
    let out = dir.join("out");
    let ds = out.join("k");
    let args = [
        "sweep",
        spec.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--threads",
        "2",
        "--progress",
        "none",
    ];
    let total = 60;
    let mut killed_mid_run = 0;
    let mut stored_before = 0;
    for round in 0..4u64 {
        let mut child = ehlmap_cmd(&args)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("spawn ehlmap");
        // Wait until this run has flushed at least one new case (reading the dataset while it is
        // being written must always work), then kill it a few milliseconds later.
        let t0 = Instant::now();
        loop {
            let n = read_dataset(&ds).expect("readable while running").len();
            // Only complete part files are ever in the dataset directory (polars reads them all).
            for e in std::fs::read_dir(&ds).into_iter().flatten().flatten() {
                let name = e.file_name().to_string_lossy().into_owned();
                assert!(is_part_name(&name), "{name} in the dataset directory");
            }
            if n > stored_before || child.try_wait().unwrap().is_some() {
                break;
            }
            assert!(t0.elapsed() < Duration::from_secs(60), "no progress");
            std::thread::sleep(Duration::from_millis(1));
        }
        std::thread::sleep(Duration::from_millis(round * 7 % 11));
        if child.try_wait().unwrap().is_none() {
            killed_mid_run += 1;
        }
        child.kill().unwrap(); // SIGKILL
        child.wait().unwrap();
        // Whatever the moment of the kill: every part file reads, no case is stored twice.
        let mut stored = 0;
        for p in part_files(&ds).unwrap() {
            stored += read_part(&p).expect("a readable part file").rows.len();
        }
        let rows = read_dataset(&ds).unwrap();
        assert_eq!(rows.len(), stored, "a case stored twice");
        assert!(rows.len() > stored_before && rows.len() <= total);
        stored_before = rows.len();
    }
    assert!(
        killed_mid_run >= 3,
        "only {killed_mid_run} kills hit a running sweep"
    );
    let before = read_dataset(&ds).unwrap().len();
    assert!(
        before > 0 && before < total,
        "{before} of {total} cases before the rerun"
    );
    // Killed runs may leave their temporary file next to the dataset, never in it.
    assert!(part_files(&ds).unwrap().len() == std::fs::read_dir(&ds).unwrap().count());
    // The rerun solves exactly the missing cases and cleans up temporary files.
    let o = ehlmap(&args);
    ok(&o);
    let log = String::from_utf8_lossy(&o.stderr);
    assert!(
        log.contains(&format!(
            "{before} already stored, {} solved",
            total - before
        )),
        "{log}"
    );
    let rows = read_dataset(&ds).unwrap();
    assert_eq!(rows.len(), total);
    assert!(rows.iter().all(|r| r.status == "converged" && r.valid));
    let stray: Vec<_> = std::fs::read_dir(&out)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".tmp"))
        .collect();
    assert!(stray.is_empty(), "{stray:?}");
}

#[test]
fn a_case_time_limit_stores_timed_out_cases_as_results() {
    // A limit no case can meet: every case is stored, with status max-iterations and a reason
    // naming the limit; the sweep itself completes.
    let dir = scratch("case-limit");
    let spec = write(&dir, "small.toml", SMALL);
    let out_dir = dir.join("out");
    let out = ehlmap(&[
        "sweep",
        spec.to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
        "--progress",
        "none",
        "--case-time-limit",
        "1e-9",
    ]);
    ok(&out);
    let rows = read_dataset(&out_dir.join("small")).unwrap();
    assert_eq!(rows.len(), 6);
    for r in &rows {
        assert_eq!(r.status.as_str(), "max-iterations", "{}", r.reason);
        assert!(r.reason.contains("time limit"), "{}", r.reason);
    }
    // A bad limit is refused before any solve.
    let bad = ehlmap(&["sweep", spec.to_str().unwrap(), "--case-time-limit", "0"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("--case-time-limit 0"));
}
