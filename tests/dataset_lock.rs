//! Datasets locked per shard and tied to their spec (`ehlmap sweep`, src/sweep/lock.rs,
//! src/sweep/dataset.rs): a second run of a running shard refuses naming the holder (exit 1), an
//! overlapping shard too; a stale lock (killed holder, a pid that does not exist, an unreadable
//! file, a holder on another host that stopped refreshing it) is taken over with a warning; the
//! lock goes at the end of a run, normal or refused. A run into a dataset of other settings
//! (`--resume` or not) refuses naming the setting (exit 2), `--new-dataset` moves the old parts
//! aside, and a spec with the same settings (more axis values) resumes as before.

use ehlmap::store::results::{part_files, read_dataset, read_part};
use ehlmap::sweep::lock::{lock_path, Holder};
use ehlmap::sweep::plan::Shard;
use ehlmap::sweep::settings::Settings;
use ehlmap::sweep::spec;
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant, SystemTime};

mod common;
use common::SLURM_VARS;

fn cmd(spec: &Path, out: &Path, extra: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_ehlmap"));
    c.arg("sweep")
        .arg(spec)
        .arg("--out")
        .arg(out)
        .args(["--progress", "none", "--threads", "1"])
        .args(extra);
    for v in SLURM_VARS {
        c.env_remove(v);
    }
    c
}

fn sweep(spec: &Path, out: &Path, extra: &[&str]) -> (Option<i32>, String) {
    let o: Output = cmd(spec, out, extra).output().expect("run ehlmap");
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// A fresh scratch directory for one test, removed when the test passes.
fn scratch(name: &str) -> common::Scratch {
    common::Scratch::new(&format!("lock-{name}"))
}

fn spec_text(name: &str, m: &str, grid: usize) -> String {
    format!(
        "name = \"{name}\"\ncontact = \"line\"\n[axes]\nM = {m}\nL = [0, 5]\n[numerics]\n\
         grid = {grid}\n[output]\nbatch = 1\n"
    )
}

/// Every case id of the dataset stored once, over all its part files.
fn no_duplicates(ds: &Path) -> usize {
    let stored: usize = part_files(ds)
        .unwrap()
        .iter()
        .map(|p| read_part(p).unwrap().rows.len())
        .sum();
    let distinct = read_dataset(ds).unwrap().len();
    assert_eq!(stored, distinct, "a case stored twice in {}", ds.display());
    distinct
}

/// Nothing left next to the dataset after a run: no lock, no takeover or temporary file.
fn no_leftovers(out: &Path) {
    let left: Vec<String> = std::fs::read_dir(out)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.'))
        .collect();
    assert!(left.is_empty(), "left next to the dataset: {left:?}");
}

fn hostname() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .map(|s| s.trim().to_string())
        .unwrap_or_else(|_| "unknown".into())
}

/// A lock as a run of `spec` on `host` with `pid` would write it.
fn holder(spec: &Path, shard: &str, pid: u32, host: &str) -> Holder {
    let settings = Settings::of_spec(&spec::load(spec).unwrap());
    Holder {
        pid,
        host: host.to_string(),
        boot_id: None,
        proc_start: None,
        started: "2025-01-01T00:00:00Z".into(),
        command: "ehlmap sweep fabricated-by-the-test".into(),
        dataset: "x".into(),
        shard: shard.into(),
        spec_hash: settings.hash(),
        spec_settings: settings.to_string(),
        token: "test".into(),
    }
}

fn write_lock(path: &Path, h: &Holder, age: Duration) {
    std::fs::write(path, serde_json::to_string(h).unwrap()).unwrap();
    set_age(path, age);
}

fn set_age(path: &Path, age: Duration) {
    let f = std::fs::OpenOptions::new().write(true).open(path).unwrap();
    f.set_modified(SystemTime::now() - age).unwrap();
}

#[test]
fn a_second_run_refuses_naming_the_holder_and_a_killed_holder_is_taken_over() {
    let dir = scratch("live");
    let out = dir.join("out");
    let spec = dir.join("lk.toml");
    // Long enough to be running while the second run starts (it is killed long before the end).
    let long = "{ from = 1, to = 3000, count = 60, scale = \"log\" }";
    std::fs::write(&spec, spec_text("lk", long, 4097)).unwrap();
    let ds = out.join("lk");
    let lock = lock_path(&ds, &Shard::WHOLE);
    let mut first = cmd(&spec, &out, &[])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    let held: Holder = loop {
        let parsed = std::fs::read(&lock)
            .ok()
            .and_then(|b| serde_json::from_slice(&b).ok());
        if let Some(h) = parsed {
            break h;
        }
        assert!(first.try_wait().unwrap().is_none(), "the first run ended");
        assert!(t0.elapsed() < Duration::from_secs(60), "no lock appeared");
        std::thread::sleep(Duration::from_millis(5));
    };
    assert_eq!(
        (held.pid, held.host.as_str()),
        (first.id(), hostname().as_str())
    );
    assert_eq!(held.shard, "1/1");
    assert!(held.command.contains("sweep") && held.command.contains("lk.toml"));
    assert!(held.started.ends_with('Z'));
    // Once the first run has stored a case (so that --resume has a dataset to resume) ...
    while part_files(&ds).unwrap().is_empty() {
        assert!(first.try_wait().unwrap().is_none(), "the first run ended");
        assert!(
            t0.elapsed() < Duration::from_secs(120),
            "no part file appeared"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
    // The same shard, and an overlapping one: refused, naming the holder and the lock file.
    for extra in [&[][..], &["--shard", "2/3"][..], &["--resume"][..]] {
        let (code, err) = sweep(&spec, &out, extra);
        assert!(first.try_wait().unwrap().is_none(), "the first run ended");
        assert_eq!(code, Some(1), "{extra:?}: {err}");
        let want = format!("pid {} on {}", first.id(), hostname());
        assert!(err.contains(&want), "{extra:?}: want `{want}` in {err}");
        assert!(err.contains(&lock.display().to_string()), "{err}");
        assert_eq!(
            err.lines().filter(|l| l.starts_with("ehlmap:")).count(),
            1,
            "{err}"
        );
    }
    let (_, err) = sweep(&spec, &out, &["--shard", "2/3"]);
    assert!(err.contains("overlaps shard 1/1"), "{err}");
    // kill -9: the lock stays behind, stale.
    first.kill().unwrap();
    first.wait().unwrap();
    assert!(lock.exists());
    let before = no_duplicates(&ds);
    // Same settings, fewer cases: the rerun takes the lock over, with a warning, and completes.
    std::fs::write(&spec, spec_text("lk", "[1, 2]", 4097)).unwrap();
    let (code, err) = sweep(&spec, &out, &[]);
    assert_eq!(code, Some(0), "{err}");
    let want = format!(
        "warning: took over the stale lock {} of pid {}",
        lock.display(),
        held.pid
    );
    assert!(err.contains(&want), "want `{want}` in {err}");
    assert!(
        err.contains(&format!("process {} no longer runs", held.pid)),
        "{err}"
    );
    assert!(no_duplicates(&ds) >= before.max(1));
    no_leftovers(&out);
}

#[test]
fn stale_locks_are_taken_over_live_ones_refuse() {
    let dir = scratch("stale");
    let out = dir.join("out");
    std::fs::create_dir_all(&out).unwrap();
    let spec = dir.join("st.toml");
    std::fs::write(&spec, spec_text("st", "[5, 20]", 257)).unwrap();
    let lock = lock_path(&out.join("st"), &Shard::WHOLE);
    let host = hostname();
    let fresh = Duration::ZERO;
    // A pid that does not exist on this host.
    write_lock(&lock, &holder(&spec, "1/1", 999_999_999, &host), fresh);
    let (code, err) = sweep(&spec, &out, &[]);
    assert_eq!(code, Some(0), "{err}");
    assert!(err.contains("took over the stale lock"), "{err}");
    assert!(err.contains("process 999999999 no longer runs"), "{err}");
    no_leftovers(&out);
    // A live holder (this test process) on this host: refused.
    write_lock(
        &lock,
        &holder(&spec, "1/1", std::process::id(), &host),
        fresh,
    );
    let (code, err) = sweep(&spec, &out, &[]);
    assert_eq!(code, Some(1), "{err}");
    let want = format!(
        "pid {} on {host} since 2025-01-01T00:00:00Z",
        std::process::id()
    );
    assert!(err.contains(&want), "{err}");
    assert!(err.contains("ehlmap sweep fabricated-by-the-test"), "{err}");
    assert!(
        lock.exists(),
        "a refused run leaves the holder's lock alone"
    );
    // Another host: live while refreshed, stale when not refreshed for ten minutes.
    write_lock(&lock, &holder(&spec, "1/1", 1, "elsewhere"), fresh);
    let (code, err) = sweep(&spec, &out, &[]);
    assert_eq!(code, Some(1), "{err}");
    assert!(err.contains("pid 1 on elsewhere"), "{err}");
    set_age(&lock, Duration::from_secs(3600));
    let (code, err) = sweep(&spec, &out, &[]);
    assert_eq!(code, Some(0), "{err}");
    assert!(err.contains("not refreshed for 60 min"), "{err}");
    no_leftovers(&out);
    // An unreadable lock (a holder killed before it wrote its file), not young: taken over.
    std::fs::write(&lock, b"").unwrap();
    set_age(&lock, Duration::from_secs(60));
    let (code, err) = sweep(&spec, &out, &[]);
    assert_eq!(code, Some(0), "{err}");
    assert!(err.contains("not a readable lock"), "{err}");
    no_leftovers(&out);
    assert_eq!(no_duplicates(&out.join("st")), 4);
}

#[test]
fn other_shards_run_side_by_side_unless_their_settings_differ() {
    let dir = scratch("shards");
    let out = dir.join("out");
    std::fs::create_dir_all(&out).unwrap();
    let spec = dir.join("sh.toml");
    std::fs::write(&spec, spec_text("sh", "[5, 20, 100]", 257)).unwrap();
    let other = dir.join("other.toml");
    std::fs::write(&other, spec_text("sh", "[5, 20, 100]", 513)).unwrap();
    let ds = out.join("sh");
    let lock2 = lock_path(&ds, &Shard { index: 2, count: 2 });
    let me = std::process::id();
    // Shard 2/2 held (by this process) with the same settings: shard 1/2 runs.
    write_lock(
        &lock2,
        &holder(&spec, "2/2", me, &hostname()),
        Duration::ZERO,
    );
    let (code, err) = sweep(&spec, &out, &["--shard", "1/2"]);
    assert_eq!(code, Some(0), "{err}");
    // Held with other settings: refused, naming the setting.
    write_lock(
        &lock2,
        &holder(&other, "2/2", me, &hostname()),
        Duration::ZERO,
    );
    let (code, err) = sweep(&spec, &out, &["--shard", "1/2"]);
    assert_eq!(code, Some(1), "{err}");
    assert!(
        err.contains("with other settings (line.grid: 513 there, 257 in this spec)"),
        "{err}"
    );
    // A 1/4 shard overlaps 1/2's cases only: with 2/2 held, 2/4 and 4/4 overlap it.
    write_lock(
        &lock2,
        &holder(&spec, "2/2", me, &hostname()),
        Duration::ZERO,
    );
    for (shard, code_want) in [("1/4", 0), ("3/4", 0), ("2/4", 1), ("4/4", 1)] {
        let (code, err) = sweep(&spec, &out, &["--shard", shard]);
        assert_eq!(code, Some(code_want), "{shard}: {err}");
    }
    std::fs::remove_file(&lock2).unwrap();
    no_leftovers(&out);
    no_duplicates(&ds);
}

#[test]
fn a_changed_spec_refuses_new_dataset_moves_the_old_parts_same_settings_resume() {
    let dir = scratch("hash");
    let out = dir.join("out");
    let spec = dir.join("r.toml");
    let ds = out.join("r");
    std::fs::write(&spec, spec_text("r", "[5, 20]", 257)).unwrap();
    let (code, err) = sweep(&spec, &out, &[]);
    assert_eq!(code, Some(0), "{err}");
    let first = read_dataset(&ds).unwrap();
    let part = read_part(&part_files(&ds).unwrap()[0]).unwrap();
    let old = Settings::of_spec(&spec::load(&spec).unwrap());
    assert_eq!(part.meta["spec_hash"], old.hash());
    assert_eq!(part.meta["spec_settings"], old.to_string());
    assert!(part.meta["spec_settings"].contains("line.grid=257"));
    // The grid changes: a resume, and a plain rerun, refuse naming the setting; nothing runs.
    std::fs::write(&spec, spec_text("r", "[5, 20]", 513)).unwrap();
    for extra in [&["--resume"][..], &[][..]] {
        let (code, err) = sweep(&spec, &out, extra);
        assert_eq!(code, Some(2), "{err}");
        for want in [
            "holds rows of other settings than",
            "line.grid = 257 in part-1of1-0001.parquet, 513 in the spec",
            "nothing was run",
            "--new-dataset",
        ] {
            assert!(err.contains(want), "want `{want}` in {err}");
        }
        assert_eq!(
            err.lines().filter(|l| l.starts_with("ehlmap:")).count(),
            1,
            "{err}"
        );
        assert_eq!(part_files(&ds).unwrap().len(), 1);
        assert_eq!(read_dataset(&ds).unwrap(), first);
        no_leftovers(&out);
    }
    let (code, err) = sweep(&spec, &out, &["--resume", "--new-dataset"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("--new-dataset") && err.contains("--resume"),
        "{err}"
    );
    // --new-dataset: the old part moves to r.old-<its hash>/, a readable dataset of its own.
    let (code, err) = sweep(&spec, &out, &["--new-dataset"]);
    assert_eq!(code, Some(0), "{err}");
    let moved_dir = out.join(format!("r.old-{}", old.hash()));
    assert!(
        err.contains("moved") && err.contains(&moved_dir.display().to_string()),
        "{err}"
    );
    assert!(err.contains("0 already stored, 4 solved"), "{err}");
    assert_eq!(read_dataset(&moved_dir).unwrap(), first);
    let rows = read_dataset(&ds).unwrap();
    assert_eq!(rows.len(), 4);
    assert!(rows.iter().all(|r| r.grid_requested == 513));
    // Same settings, one more axis value: resumes as before, solving only the new cases.
    std::fs::write(&spec, spec_text("r", "[5, 20, 100]", 513)).unwrap();
    let (code, err) = sweep(&spec, &out, &["--resume"]);
    assert_eq!(code, Some(0), "{err}");
    assert!(err.contains("4 already stored, 2 solved"), "{err}");
    assert_eq!(no_duplicates(&ds), 6);
    // --new-dataset with nothing of other settings moves nothing.
    let (code, err) = sweep(&spec, &out, &["--new-dataset"]);
    assert_eq!(code, Some(0), "{err}");
    assert!(
        err.contains("6 already stored, 0 solved") && !err.contains("moved"),
        "{err}"
    );
    // Back to 257: the dataset is now of 513 points, so that refuses in turn; a second
    // --new-dataset keeps both old generations apart.
    std::fs::write(&spec, spec_text("r", "[5, 20]", 257)).unwrap();
    let (code, err) = sweep(&spec, &out, &[]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("line.grid = 513 in part-1of1-"), "{err}");
    let (code, err) = sweep(&spec, &out, &["--new-dataset"]);
    assert_eq!(code, Some(0), "{err}");
    assert_eq!(read_dataset(&ds).unwrap().len(), 4);
    assert_eq!(read_dataset(&moved_dir).unwrap(), first);
    no_leftovers(&out);
}
