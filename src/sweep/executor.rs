//! The executor: solve the cases of one shard on a rayon pool and write them to the dataset in
//! batches.
//!
//! Before anything is solved the run takes the shard's lock ([`crate::sweep::lock`]; a second
//! run refuses, a stale lock is taken over) and checks the stored parts against the spec's
//! settings ([`crate::sweep::dataset`]; other settings refuse, or with `new_dataset` are moved
//! aside). Only then are the stored case ids read, so a run never re-solves what a run that
//! ended just before it stored.
//!
//! `threads` workers of a dedicated rayon pool take cases from a shared queue in plan order
//! (largest cost first) and send finished rows to the calling thread, which owns the part file:
//! after `batch` rows, or `flush_seconds` after the previous flush, it rewrites the file with all
//! rows of this run through a temporary file and an atomic rename. A solve that panics becomes a
//! row with status `panic` instead of ending the sweep.

use crate::solve::Status;
use crate::store::error::StoreError;
use crate::store::results::{self, CaseRow};
use crate::strategy::formula::FormulaRef;
use crate::sweep::dataset;
use crate::sweep::lock::{self, DatasetLock, LockError, HEARTBEAT};
use crate::sweep::plan::{Case, Shard};
pub use crate::sweep::progress::Progress;
use crate::sweep::progress::{note, Reporter};
pub use crate::sweep::row::{input_row, solve_case};
use crate::sweep::row::{solve_guarded, CaseOptions};
use crate::sweep::settings::Settings;
use crate::sweep::spec::SweepSpec;
use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

/// Why a sweep run stopped: an I/O failure of the dataset (the message names the file), a
/// worker pool that could not start, a dataset another run is writing, or a dataset of other
/// settings. Numerical failures are rows, never errors.
#[derive(Debug, thiserror::Error)]
pub enum SweepError {
    /// A file or directory operation failed.
    #[error("{0}")]
    Io(String),
    /// A part file could not be read or written.
    #[error(transparent)]
    Store(#[from] StoreError),
    /// Another run holds the shard's lock, an overlapping shard's, or another shard's with
    /// other settings; the message names the holder and the lock file. Nothing was run.
    #[error("{0}")]
    Busy(String),
    /// The dataset holds rows of other settings than the spec (and `new_dataset` was not
    /// asked); the message names the setting, the part and both values. Nothing was run.
    #[error("{0}")]
    Settings(String),
}

impl SweepError {
    /// The exit code of the command line: 2 for a spec that conflicts with the dataset (bad
    /// input, like a bad spec), 1 for the rest (I/O, a busy dataset: a later run may succeed).
    pub fn exit_code(&self) -> i32 {
        match self {
            SweepError::Settings(_) => 2,
            _ => 1,
        }
    }
}

impl From<LockError> for SweepError {
    fn from(e: LockError) -> Self {
        match e {
            LockError::Busy(m) => SweepError::Busy(m),
            LockError::Io(m) => SweepError::Io(m),
        }
    }
}

impl From<String> for SweepError {
    fn from(msg: String) -> Self {
        SweepError::Io(msg)
    }
}

/// Where and how to run.
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// The dataset directory `<out>/<name>`.
    pub dataset: PathBuf,
    /// Worker threads of the solve pool (at least 1 is used).
    pub threads: usize,
    /// The slice of the sweep this process solves.
    pub shard: Shard,
    /// How progress is shown.
    pub progress: Progress,
    /// Start a new dataset: move the parts of other settings aside instead of refusing
    /// ([`crate::sweep::dataset`]).
    pub new_dataset: bool,
    /// Seconds each case may take (all its solves together): a case that reaches it is stored
    /// with status max-iterations and a reason naming the limit (`None`: no limit). Not a
    /// setting of the dataset: a case that ends before its limit is the same without one.
    pub case_time_limit: Option<f64>,
    /// A fitted film formula that answers the cases with an accuracy target where its held-out
    /// error map allows ([`crate::strategy::formula`]; the rows say `model_used = "formula"`).
    /// Not a setting of the dataset: every row names the model that answered it.
    pub formula: Option<FormulaRef>,
}

/// What a run did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RunReport {
    /// Cases of the whole sweep.
    pub total: usize,
    /// Cases of this shard.
    pub in_shard: usize,
    /// Cases of this shard the dataset held before the run (not solved again).
    pub already_stored: usize,
    /// Cases solved and written by this run.
    pub solved: usize,
    /// Cases of `solved` that failed: status other than converged, or not valid.
    pub failed: usize,
    /// Cases solved by this run per `model_used` (see `crate::strategy::select`).
    pub models: std::collections::BTreeMap<String, usize>,
    /// Their summed solve time (s) per `model_used`, check solves included.
    pub model_seconds: std::collections::BTreeMap<String, f64>,
    /// The part file this run wrote (none when there was nothing to do).
    pub file: Option<PathBuf>,
    /// Part files of other settings moved out of the dataset (`new_dataset`): (from, to).
    pub moved: Vec<(PathBuf, PathBuf)>,
    /// Wall time of the run (s).
    pub wall_s: f64,
}

fn is_failure(r: &CaseRow) -> bool {
    r.status != Status::Converged || !r.valid
}

/// ISO 8601 UTC time of `t`, e.g. `2025-01-31T12:00:00Z`.
pub fn iso8601(t: SystemTime) -> String {
    let secs = t.duration_since(UNIX_EPOCH).map_or(0, |d| d.as_secs()) as i64;
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    // Civil date from days since 1970-01-01 (H. Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + (m <= 2) as i64;
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem % 3600 / 60,
        rem % 60
    )
}

/// The run number of `part-<label>-<run>.parquet`, when `name` is such a part.
fn run_number(name: &str, label: &str) -> Option<u32> {
    let rest = name.strip_prefix(&format!("part-{label}-"))?;
    rest.strip_suffix(".parquet")?.parse().ok()
}

/// The directory that holds the temporary files of `dir`'s parts, and their name prefix.
fn temp_dir_and_prefix(dir: &Path) -> (PathBuf, String) {
    let probe = results::temp_path(&dir.join("part-x.parquet"));
    let tdir = probe.parent().map(Path::to_path_buf).unwrap_or_default();
    let name = probe
        .file_name()
        .map_or(String::new(), |n| n.to_string_lossy().into_owned());
    let prefix = name
        .strip_suffix("part-x.parquet.tmp")
        .unwrap_or("")
        .to_string();
    (tdir, prefix)
}

/// The temporary files of this shard's parts that exist now, with their run numbers.
fn shard_temps(dir: &Path, shard: &Shard) -> Vec<(PathBuf, u32)> {
    let (tdir, prefix) = temp_dir_and_prefix(dir);
    let label = shard.label();
    let list = if tdir.as_os_str().is_empty() {
        std::fs::read_dir(".")
    } else {
        std::fs::read_dir(&tdir)
    };
    let mut v = vec![];
    for ent in list.into_iter().flatten().flatten() {
        let name = ent.file_name().to_string_lossy().into_owned();
        let run = name
            .strip_prefix(prefix.as_str())
            .and_then(|r| r.strip_suffix(".tmp"))
            .and_then(|r| run_number(r, &label));
        if let Some(run) = run {
            v.push((tdir.join(&name), run));
        }
    }
    v
}

/// Claim the next run number of this shard: the part file path, whose temporary file now exists
/// (created exclusively, so two processes never get the same file).
fn claim_part(dir: &Path, shard: &Shard) -> Result<PathBuf, SweepError> {
    let label = shard.label();
    let mut next = 1;
    let rd = std::fs::read_dir(dir).map_err(|e| format!("cannot read {}: {e}", dir.display()))?;
    for ent in rd.flatten() {
        if let Some(n) = run_number(&ent.file_name().to_string_lossy(), &label) {
            next = next.max(n + 1);
        }
    }
    for (_, n) in shard_temps(dir, shard) {
        next = next.max(n + 1);
    }
    loop {
        let path = dir.join(format!("part-{label}-{next:04}.parquet"));
        let tmp = results::temp_path(&path);
        if path.exists() {
            next += 1;
            continue;
        }
        match std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)
        {
            Ok(_) => return Ok(path),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => next += 1,
            Err(e) => return Err(format!("cannot create {}: {e}", tmp.display()).into()),
        }
    }
}

/// Remove temporary files that killed runs of this shard left behind.
fn remove_stale_temps(dir: &Path, shard: &Shard) {
    for (p, _) in shard_temps(dir, shard) {
        let _ = std::fs::remove_file(p);
    }
}

/// Run the cases of `opts.shard` that the dataset does not hold yet. `cases` is the whole plan
/// (largest cost first). Returns an error message on an I/O failure; numerical failures are
/// rows.
pub fn execute(
    spec: &SweepSpec,
    cases: &[Case],
    opts: &RunOptions,
) -> Result<RunReport, SweepError> {
    let start = Instant::now();
    let created = iso8601(SystemTime::now());
    let dir = &opts.dataset;
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let settings = Settings::of_spec(spec);
    let (mut lock, warnings) = lock::acquire(dir, &opts.shard, &settings, &created)?;
    for w in warnings {
        note(&format!("ehlmap: warning: {w}"));
    }
    let parts = dataset::scan(dir)?;
    let conflicts = dataset::conflicts(&parts, &settings);
    let mut moved = vec![];
    if !conflicts.is_empty() {
        if !opts.new_dataset {
            let msg = dataset::refusal(dir, &spec.file, &parts, &conflicts);
            return Err(SweepError::Settings(msg));
        }
        moved = dataset::move_aside(dir, &parts, &conflicts)?;
    }
    let stored = dataset::kept_ids(&parts, &conflicts);
    let (shard_cases, todo) = cases_to_solve(&stored, cases, &opts.shard);
    let mut report = RunReport {
        total: cases.len(),
        in_shard: shard_cases.len(),
        already_stored: shard_cases.len() - todo.len(),
        moved,
        ..RunReport::default()
    };
    if todo.is_empty() {
        report.wall_s = start.elapsed().as_secs_f64();
        return Ok(report);
    }
    remove_stale_temps(dir, &opts.shard);
    let threads = opts.threads.max(1);
    let pool = worker_pool(threads)?;
    let mut writer = PartWriter {
        dir,
        shard: &opts.shard,
        meta: part_metadata(spec, &settings, &created, &opts.shard, &report),
        rows: vec![],
        part: None,
    };
    let mut reporter = Reporter::new(
        opts.progress,
        format!("sweep {} [shard {}]", spec.name, opts.shard),
        todo.len(),
    );

    let stop = AtomicBool::new(false);
    let (tx, rx) = mpsc::channel::<CaseRow>();
    let failure = std::thread::scope(|ts| {
        let (stop, todo, pool) = (&stop, &todo, &pool);
        let sweep = spec.name.as_str();
        let each = CaseOptions {
            time_limit: opts.case_time_limit,
            formula: opts.formula,
        };
        ts.spawn(move || solve_all(pool, threads, todo, sweep, each, stop, tx));
        let sink = Sink {
            report: &mut report,
            reporter: &mut reporter,
            writer: &mut writer,
            lock: &mut lock,
        };
        collect(rx, spec, sink, stop)
    });
    reporter.finish();
    if let Some(e) = failure {
        return Err(e);
    }
    report.file = writer.part;
    report.wall_s = start.elapsed().as_secs_f64();
    Ok(report)
}

/// The cases of `shard`, and those of them that are not in `stored`.
fn cases_to_solve<'c>(
    stored: &HashSet<String>,
    cases: &'c [Case],
    shard: &Shard,
) -> (Vec<&'c Case>, Vec<&'c Case>) {
    let shard_cases: Vec<&Case> = cases.iter().filter(|c| shard.contains(c.id)).collect();
    let todo: Vec<&Case> = shard_cases
        .iter()
        .copied()
        .filter(|c| !stored.contains(&c.id_hex()))
        .collect();
    (shard_cases, todo)
}

/// A dedicated rayon pool of `threads` workers.
fn worker_pool(threads: usize) -> Result<rayon::ThreadPool, SweepError> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .thread_name(|i| format!("ehlmap-sweep-{i}"))
        .build()
        .map_err(|e| format!("cannot start {threads} threads: {e}").into())
}

/// The footer metadata of every part file of this run (each flush adds `run` and `rows`).
fn part_metadata(
    spec: &SweepSpec,
    settings: &Settings,
    created: &str,
    shard: &Shard,
    report: &RunReport,
) -> Vec<(String, String)> {
    vec![
        (
            "git_commit".to_string(),
            env!("EHLMAP_GIT_COMMIT").to_string(),
        ),
        ("sweep".to_string(), spec.name.clone()),
        ("spec_file".to_string(), spec.file.clone()),
        ("spec".to_string(), spec.text.clone()),
        ("spec_hash".to_string(), settings.hash()),
        ("spec_settings".to_string(), settings.to_string()),
        ("created".to_string(), created.to_string()),
        ("shard".to_string(), shard.to_string()),
        ("cases_total".to_string(), report.total.to_string()),
        ("cases_shard".to_string(), report.in_shard.to_string()),
    ]
}

/// Solve `todo` on `pool`: `threads` workers take the next case in order and send its row to
/// `tx`, until no case is left, `stop` is set or the receiver is gone; each case with `each`.
fn solve_all(
    pool: &rayon::ThreadPool,
    threads: usize,
    todo: &[&Case],
    sweep: &str,
    each: CaseOptions,
    stop: &AtomicBool,
    tx: mpsc::Sender<CaseRow>,
) {
    let next = AtomicUsize::new(0);
    let next = &next;
    pool.scope(|s| {
        for _ in 0..threads {
            let tx = tx.clone();
            s.spawn(move |_| loop {
                if stop.load(Ordering::Relaxed) {
                    break;
                }
                let i = next.fetch_add(1, Ordering::Relaxed);
                let Some(case) = todo.get(i) else { break };
                if tx.send(solve_guarded(case, sweep, each)).is_err() {
                    break;
                }
            });
        }
    });
    drop(tx);
}

/// The part file of this run: claimed at the first flush, then rewritten with all rows of the
/// run at every flush.
struct PartWriter<'a> {
    dir: &'a Path,
    shard: &'a Shard,
    /// The footer metadata before `run` and `rows`.
    meta: Vec<(String, String)>,
    rows: Vec<CaseRow>,
    part: Option<PathBuf>,
}

impl PartWriter<'_> {
    fn flush(&mut self) -> Result<(), SweepError> {
        if self.part.is_none() {
            self.part = Some(claim_part(self.dir, self.shard)?);
        }
        let path = self.part.as_ref().expect("claimed");
        let run = path
            .file_name()
            .and_then(|n| run_number(&n.to_string_lossy(), &self.shard.label()))
            .unwrap_or(0);
        self.rows.sort_by(|a, b| a.case_id.cmp(&b.case_id));
        let mut meta = self.meta.clone();
        meta.push(("run".to_string(), run.to_string()));
        meta.push(("rows".to_string(), self.rows.len().to_string()));
        Ok(results::write_part(path, &self.rows, &meta)?)
    }
}

/// Count a solved row in `report`.
fn tally(report: &mut RunReport, row: &CaseRow) {
    report.solved += 1;
    report.failed += is_failure(row) as usize;
    *report.models.entry(row.model_used.to_string()).or_default() += 1;
    *report
        .model_seconds
        .entry(row.model_used.to_string())
        .or_default() += row.wall_s.unwrap_or(0.0);
}

/// Where [`collect`] puts what it receives: the run's report, its progress, its part file, and
/// the lock it refreshes.
struct Sink<'s, 'w> {
    report: &'s mut RunReport,
    reporter: &'s mut Reporter,
    writer: &'s mut PartWriter<'w>,
    lock: &'s mut DatasetLock,
}

/// The longest [`collect`] waits for a row before it looks at its flush, lock and progress
/// (shorter than the lock's [`HEARTBEAT`], so no refresh is late by more than a tick).
const IDLE_TICK: Duration = Duration::from_secs(5);
const _: () = assert!(IDLE_TICK.as_secs() <= HEARTBEAT.as_secs());

/// Receive the rows until the workers are done, flushing after `batch` rows or `flush_seconds`
/// (of `spec.output`) and refreshing the lock every [`HEARTBEAT`]; on a write error, set `stop`
/// and return the error.
fn collect(
    rx: mpsc::Receiver<CaseRow>,
    spec: &SweepSpec,
    sink: Sink,
    stop: &AtomicBool,
) -> Option<SweepError> {
    let Sink {
        report,
        reporter,
        writer,
        lock,
    } = sink;
    let flush_every = Duration::from_secs_f64(spec.output.flush_seconds);
    let batch = spec.output.batch.max(1);
    let mut failure: Option<SweepError> = None;
    let mut pending = 0usize;
    let mut last_flush = Instant::now();
    loop {
        if let Some(w) = lock.heartbeat() {
            note(&format!("ehlmap: warning: {w}"));
        }
        // Wake for the next flush (only when rows are pending) and at least every IDLE_TICK, for
        // the lock's heartbeat and the progress's idle line.
        let wait = if pending > 0 {
            flush_every
                .saturating_sub(last_flush.elapsed())
                .min(IDLE_TICK)
        } else {
            IDLE_TICK
        };
        match rx.recv_timeout(wait.max(Duration::from_millis(1))) {
            Ok(row) => {
                tally(report, &row);
                writer.rows.push(row);
                pending += 1;
                reporter.update(report.solved, report.failed);
            }
            Err(mpsc::RecvTimeoutError::Timeout) => reporter.idle(),
            Err(mpsc::RecvTimeoutError::Disconnected) => break,
        }
        if pending > 0 && (pending >= batch || last_flush.elapsed() >= flush_every) {
            if let Err(e) = writer.flush() {
                failure = Some(e);
                stop.store(true, Ordering::Relaxed);
                break;
            }
            pending = 0;
            last_flush = Instant::now();
        }
    }
    if failure.is_none() && pending > 0 {
        if let Err(e) = writer.flush() {
            failure = Some(e);
        }
    }
    // Dropping the receiver ends the workers after their current case on an error.
    drop(rx);
    failure
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn iso8601_known_dates() {
        assert_eq!(iso8601(UNIX_EPOCH), "1970-01-01T00:00:00Z");
        let t = UNIX_EPOCH + Duration::from_secs(951_782_400 + 3661); // 2000-02-29 01:01:01
        assert_eq!(iso8601(t), "2000-02-29T01:01:01Z");
    }

    #[test]
    fn run_numbers_parse() {
        assert_eq!(run_number("part-1of2-0003.parquet", "1of2"), Some(3));
        let (tdir, prefix) = temp_dir_and_prefix(Path::new("out/smoke"));
        assert_eq!(
            (tdir.as_path(), prefix.as_str()),
            (Path::new("out"), ".smoke.")
        );
        assert_eq!(run_number("part-2of2-0003.parquet", "1of2"), None);
    }
}
