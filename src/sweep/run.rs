//! The executor: solve the cases of one shard on a rayon pool and write them to the dataset in
//! batches.
//!
//! `threads` workers of a dedicated rayon pool take cases from a shared queue in plan order
//! (largest cost first) and send finished rows to the calling thread, which owns the part file:
//! after `batch` rows, or `flush_seconds` after the previous flush, it rewrites the file with all
//! rows of this run through a temporary file and an atomic rename. A solve that panics becomes a
//! row with status `panic` instead of ending the sweep.

use crate::io::results::{self, finite, CaseRow};
use crate::lubricant::{Density, Viscosity};
use crate::params::ParamError;
use crate::solution::Outputs;
use crate::solver::line::{solve_line, solve_line_to_accuracy, LineSolveParams, ESTIMATE_ORDER};
use crate::solver::multigrid::CycleType;
use crate::solver::point::{solve_point, PointSolveParams};
use crate::solver::Status;
use crate::sweep::plan::{Case, Shard};
use crate::sweep::spec::{Contact, SweepSpec};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

/// How progress is shown on stderr.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Progress {
    /// A bar when stderr is a terminal, else log lines.
    Auto,
    Bar,
    Log,
    None,
}

/// Where and how to run.
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// The dataset directory `<out>/<name>`.
    pub dataset: PathBuf,
    pub threads: usize,
    pub shard: Shard,
    pub progress: Progress,
}

/// What a run did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RunReport {
    /// Cases of the whole sweep, of this shard, and of this shard already stored before the run.
    pub total: usize,
    pub in_shard: usize,
    pub already_stored: usize,
    /// Cases solved and written by this run, and how many of them failed (status other than
    /// converged, or not valid).
    pub solved: usize,
    pub failed: usize,
    /// The part file this run wrote (none when there was nothing to do).
    pub file: Option<PathBuf>,
    pub wall_s: f64,
}

/// The input columns of a case; outputs empty, status "not-run".
pub fn input_row(case: &Case, sweep: &str) -> CaseRow {
    let n = &case.numerics;
    let (z, ph_v) = match case.models.viscosity {
        Viscosity::Barus => (None, None),
        Viscosity::Roelands { z, ph_pa } => (Some(z), Some(ph_pa)),
    };
    let ph_d = match case.models.density {
        Density::Incompressible => None,
        Density::DowsonHigginson { ph_pa } => Some(ph_pa),
    };
    CaseRow {
        case_id: case.id_hex(),
        sweep: sweep.to_string(),
        contact: case.contact.as_str().to_string(),
        m: case.m,
        l: case.l,
        d: case.d,
        // Exact Hertz ellipse ratio of D (point contacts), known before any solve.
        k: case.point_case().ok().map(|p| p.ellipse().k),
        elasticity: case.models.elasticity.to_string(),
        viscosity: case.models.viscosity.name().to_string(),
        density: case.models.density.name().to_string(),
        z,
        eta0: case.eta0,
        ph: ph_v.or(ph_d),
        grid_requested: n.grid as i64,
        cycle: match n.cycle {
            CycleType::V => "v",
            CycleType::W => "w",
        }
        .to_string(),
        max_cycles: n.max_cycles as i64,
        fallback: n.fallback,
        tol_load: n.tol_load,
        tol_h: n.tol_h,
        error_estimate: n.error_estimate,
        grid: None,
        levels: None,
        h_c: None,
        h_c_pmax: None,
        h_min: None,
        x_min: None,
        y_min: None,
        p_max: None,
        spike_x: None,
        spike_p: None,
        h0: None,
        f: None,
        load_error: None,
        h_c_err: None,
        h_min_err: None,
        status: "not-run".to_string(),
        reason: String::new(),
        attempt: None,
        work_units: None,
        wall_s: None,
        valid: true,
    }
}

fn solve_params(case: &Case, grid: usize) -> LineSolveParams {
    let n = &case.numerics;
    let mut p = LineSolveParams::default();
    p.mg.grid = grid;
    p.mg.cycle = n.cycle;
    p.mg.max_cycles = n.max_cycles;
    p.mg.tol_load = n.tol_load;
    p.mg.tol_h = n.tol_h;
    p.fallback = n.fallback;
    p.keep_profile = false;
    p
}

/// Solve one case and turn it into a row (line cases with [`solve_line`], point cases with
/// [`solve_point`]). With `error_estimate` the case is also solved on the half grid and
/// `H_c_err`, `H_min_err` hold relative error estimates (both solves converged): Richardson with
/// the conservative order [`ESTIMATE_ORDER`] of the accuracy targets, the same estimate
/// `ehlmap solve --accuracy` reports; `work_units`, `wall_s` are the cost of both solves.
/// Every float goes through [`finite`]: a non-finite output is null and the row not `valid`.
pub fn solve_case(case: &Case, sweep: &str) -> CaseRow {
    match case.contact {
        Contact::Line => solve_line_row(case, sweep),
        Contact::Point => solve_point_row(case, sweep),
    }
}

/// A row for a case that is not a valid case.
fn invalid_row(case: &Case, sweep: &str, e: ParamError) -> CaseRow {
    let mut row = input_row(case, sweep);
    row.status = "invalid".into();
    row.reason = e.to_string();
    row.valid = false;
    row
}

/// Does the case ask for a half-grid error estimate, and does `grid` have a half grid that the
/// contact accepts?
fn wants_half_grid(case: &Case, grid: usize) -> bool {
    let min = case.contact.grid_range().0;
    case.numerics.error_estimate && grid >= 2 * min - 1
}

/// The half grid of `grid` (half the intervals).
fn half_grid(grid: usize) -> usize {
    (grid - 1) / 2 + 1
}

/// Relative error estimates of H_c and H_min from a solve and its half-grid twin: Richardson with
/// order [`ESTIMATE_ORDER`]; none unless both converged, none for a non-finite estimate.
fn half_grid_errors(fine: &Outputs, coarse: &Outputs) -> (Option<f64>, Option<f64>) {
    if fine.status != Status::Converged || coarse.status != Status::Converged {
        return (None, None);
    }
    let factor = 1.0 / (2f64.powf(ESTIMATE_ORDER) - 1.0);
    let est = |a: f64, b: f64| {
        let e = factor * ((b - a) / b).abs();
        e.is_finite().then_some(e)
    };
    (est(coarse.h_c, fine.h_c), est(coarse.h_min, fine.h_min))
}

/// Copy a solve's outputs into `row` (non-finite values become null and clear `valid`).
fn fill_outputs(row: &mut CaseRow, o: &Outputs, attempt: usize, valid: &mut bool) {
    row.grid = Some(o.grid as i64);
    row.levels = Some(o.levels as i64);
    row.h_c = finite(o.h_c, valid);
    row.h_c_pmax = finite(o.h_c_pmax, valid);
    row.h_min = finite(o.h_min, valid);
    row.x_min = finite(o.x_min, valid);
    row.y_min = o.y_min.and_then(|y| finite(y, valid));
    row.p_max = finite(o.p_max, valid);
    if let Some(sp) = o.spike {
        row.spike_x = finite(sp.x, valid);
        row.spike_p = finite(sp.p, valid);
    }
    row.h0 = finite(o.h0, valid);
    row.f = finite(o.f, valid);
    row.load_error = finite(o.load_error, valid);
    row.status = o.status.as_str().to_string();
    row.reason = o.reason.clone();
    row.attempt = Some(attempt as i64);
}

fn solve_line_row(case: &Case, sweep: &str) -> CaseRow {
    let mut row = input_row(case, sweep);
    let lc = match case.line_case() {
        Ok(lc) => lc,
        Err(e) => return invalid_row(case, sweep, e),
    };
    let s = match case.numerics.accuracy {
        Some(target) => solve_line_to_accuracy(
            &lc,
            &solve_params(case, case.numerics.grid),
            target,
            case.numerics.grid,
        ),
        None => solve_line(&lc, &solve_params(case, case.numerics.grid)),
    };
    let o = &s.outputs;
    let mut valid = true;
    fill_outputs(&mut row, o, s.attempt, &mut valid);
    let (mut wu, mut wall) = (o.work_units, o.wall_s);
    if let Some(est) = o.error_estimate {
        // Accuracy target: the estimate of the chosen grid (max over H_c and H_min).
        row.h_c_err = finite(est, &mut valid);
        row.h_min_err = row.h_c_err;
    } else if wants_half_grid(case, o.grid) {
        let coarse = solve_line(&lc, &solve_params(case, half_grid(o.grid)));
        wu += coarse.outputs.work_units;
        wall += coarse.outputs.wall_s;
        (row.h_c_err, row.h_min_err) = half_grid_errors(o, &coarse.outputs);
    }
    row.work_units = finite(wu, &mut valid);
    row.wall_s = finite(wall, &mut valid);
    row.valid = valid;
    row
}

fn point_params(case: &Case, grid: usize) -> PointSolveParams {
    let n = &case.numerics;
    // Field by field over the defaults: settings the point solver gains later keep theirs.
    let mut p = PointSolveParams::default();
    p.mg.grid = grid;
    p.mg.cycle = n.cycle;
    p.mg.max_cycles = n.max_cycles;
    p.mg.tol_load = n.tol_load;
    p.mg.tol_h = n.tol_h;
    p.fallback = n.fallback;
    p.keep_fields = false;
    p
}

fn solve_point_row(case: &Case, sweep: &str) -> CaseRow {
    let mut row = input_row(case, sweep);
    let pc = match case.point_case() {
        Ok(pc) => pc,
        Err(e) => return invalid_row(case, sweep, e),
    };
    // The spec rejects accuracy targets for point contacts (no solve_point_to_accuracy yet).
    let s = solve_point(&pc, &point_params(case, case.numerics.grid));
    let o = &s.outputs;
    let mut valid = true;
    fill_outputs(&mut row, o, s.attempt, &mut valid);
    // D and k are inputs (k from the exact Hertz ellipse, set by input_row); a solver that
    // reports them must agree.
    debug_assert!(o.d.is_none_or(|d| d == pc.d));
    let (mut wu, mut wall) = (o.work_units, o.wall_s);
    if wants_half_grid(case, o.grid) {
        let coarse = solve_point(&pc, &point_params(case, half_grid(o.grid)));
        wu += coarse.outputs.work_units;
        wall += coarse.outputs.wall_s;
        (row.h_c_err, row.h_min_err) = half_grid_errors(o, &coarse.outputs);
    }
    row.work_units = finite(wu, &mut valid);
    row.wall_s = finite(wall, &mut valid);
    row.valid = valid;
    row
}

fn solve_guarded(case: &Case, sweep: &str) -> CaseRow {
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| solve_case(case, sweep))) {
        Ok(r) => r,
        Err(p) => {
            let msg = p
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| p.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".to_string());
            let mut row = input_row(case, sweep);
            row.status = "panic".into();
            row.reason = format!("the solver panicked: {msg}");
            row.valid = false;
            row
        }
    }
}

fn is_failure(r: &CaseRow) -> bool {
    r.status != Status::Converged.as_str() || !r.valid
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
fn claim_part(dir: &Path, shard: &Shard) -> Result<PathBuf, String> {
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
            Err(e) => return Err(format!("cannot create {}: {e}", tmp.display())),
        }
    }
}

/// Remove temporary files that killed runs of this shard left behind.
fn remove_stale_temps(dir: &Path, shard: &Shard) {
    for (p, _) in shard_temps(dir, shard) {
        let _ = std::fs::remove_file(p);
    }
}

struct Reporter {
    bar: Option<ProgressBar>,
    log: bool,
    prefix: String,
    total: usize,
    start: Instant,
    last_log: Instant,
    last_logged_decile: usize,
}

impl Reporter {
    fn new(mode: Progress, prefix: String, total: usize) -> Self {
        let tty = std::io::stderr().is_terminal();
        let (bar, log) = match mode {
            Progress::None => (false, false),
            Progress::Bar => (true, false),
            Progress::Log => (false, true),
            Progress::Auto => (tty, !tty),
        };
        let bar = bar.then(|| {
            let pb =
                ProgressBar::with_draw_target(Some(total as u64), ProgressDrawTarget::stderr());
            let style = ProgressStyle::with_template(
                "{prefix} [{bar:30}] {pos}/{len} {msg} elapsed {elapsed} ETA {eta}",
            )
            .map(|s| s.progress_chars("=> "))
            .unwrap_or_else(|_| ProgressStyle::default_bar());
            pb.set_style(style);
            pb.set_prefix(prefix.clone());
            pb.set_message("failures 0");
            pb
        });
        Reporter {
            bar,
            log,
            prefix,
            total,
            start: Instant::now(),
            last_log: Instant::now(),
            last_logged_decile: 0,
        }
    }

    fn update(&mut self, done: usize, failed: usize) {
        if let Some(pb) = &self.bar {
            pb.set_position(done as u64);
            pb.set_message(format!("failures {failed}"));
        }
        if self.log {
            let decile = done * 10 / self.total.max(1);
            let due = self.last_log.elapsed() >= Duration::from_secs(30);
            if decile > self.last_logged_decile || due || done == self.total {
                self.last_logged_decile = decile;
                self.last_log = Instant::now();
                let el = self.start.elapsed().as_secs_f64();
                let eta = if done > 0 {
                    el / done as f64 * (self.total - done) as f64
                } else {
                    f64::NAN
                };
                eprintln!(
                    "{}: {done}/{} done, {failed} failures, {el:.1} s elapsed, ETA {eta:.1} s",
                    self.prefix, self.total
                );
            }
        }
    }

    fn finish(&self) {
        if let Some(pb) = &self.bar {
            pb.finish();
        }
    }
}

/// Run the cases of `opts.shard` that the dataset does not hold yet. `cases` is the whole plan
/// (largest cost first). Returns an error message on an I/O failure; numerical failures are
/// rows.
pub fn execute(spec: &SweepSpec, cases: &[Case], opts: &RunOptions) -> Result<RunReport, String> {
    let start = Instant::now();
    let dir = &opts.dataset;
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let stored = results::stored_ids(dir)?;
    let shard_cases: Vec<&Case> = cases.iter().filter(|c| opts.shard.contains(c.id)).collect();
    let todo: Vec<&Case> = shard_cases
        .iter()
        .copied()
        .filter(|c| !stored.contains(&c.id_hex()))
        .collect();
    let mut report = RunReport {
        total: cases.len(),
        in_shard: shard_cases.len(),
        already_stored: shard_cases.len() - todo.len(),
        ..RunReport::default()
    };
    if todo.is_empty() {
        report.wall_s = start.elapsed().as_secs_f64();
        return Ok(report);
    }
    remove_stale_temps(dir, &opts.shard);
    let threads = opts.threads.max(1);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .thread_name(|i| format!("ehlmap-sweep-{i}"))
        .build()
        .map_err(|e| format!("cannot start {threads} threads: {e}"))?;
    let created = iso8601(SystemTime::now());
    let meta_base = vec![
        (
            "git_commit".to_string(),
            env!("EHLMAP_GIT_COMMIT").to_string(),
        ),
        ("sweep".to_string(), spec.name.clone()),
        ("spec_file".to_string(), spec.file.clone()),
        ("spec".to_string(), spec.text.clone()),
        ("created".to_string(), created),
        ("shard".to_string(), opts.shard.to_string()),
        ("cases_total".to_string(), cases.len().to_string()),
        ("cases_shard".to_string(), shard_cases.len().to_string()),
    ];
    let mut reporter = Reporter::new(
        opts.progress,
        format!("sweep {} [shard {}]", spec.name, opts.shard),
        todo.len(),
    );

    let next = AtomicUsize::new(0);
    let stop = AtomicBool::new(false);
    let (tx, rx) = mpsc::channel::<CaseRow>();
    let flush_every = Duration::from_secs_f64(spec.output.flush_seconds);
    let batch = spec.output.batch.max(1);
    let mut rows: Vec<CaseRow> = vec![];
    let mut part: Option<PathBuf> = None;
    let mut failure: Option<String> = None;

    std::thread::scope(|ts| {
        let (next, stop, todo, pool) = (&next, &stop, &todo, &pool);
        let sweep = spec.name.as_str();
        ts.spawn(move || {
            pool.scope(|s| {
                for _ in 0..threads {
                    let tx = tx.clone();
                    s.spawn(move |_| loop {
                        if stop.load(Ordering::Relaxed) {
                            break;
                        }
                        let i = next.fetch_add(1, Ordering::Relaxed);
                        let Some(case) = todo.get(i) else { break };
                        if tx.send(solve_guarded(case, sweep)).is_err() {
                            break;
                        }
                    });
                }
            });
            drop(tx);
        });

        let mut pending = 0usize;
        let mut last_flush = Instant::now();
        let flush = |rows: &mut Vec<CaseRow>, part: &mut Option<PathBuf>| -> Result<(), String> {
            if part.is_none() {
                *part = Some(claim_part(dir, &opts.shard)?);
            }
            let path = part.as_ref().expect("claimed");
            let run = path
                .file_name()
                .and_then(|n| run_number(&n.to_string_lossy(), &opts.shard.label()))
                .unwrap_or(0);
            rows.sort_by(|a, b| a.case_id.cmp(&b.case_id));
            let mut meta = meta_base.clone();
            meta.push(("run".to_string(), run.to_string()));
            meta.push(("rows".to_string(), rows.len().to_string()));
            results::write_part(path, rows, &meta)
        };
        loop {
            let wait = flush_every.saturating_sub(last_flush.elapsed());
            match rx.recv_timeout(wait.max(Duration::from_millis(1))) {
                Ok(row) => {
                    report.solved += 1;
                    report.failed += is_failure(&row) as usize;
                    rows.push(row);
                    pending += 1;
                    reporter.update(report.solved, report.failed);
                }
                Err(mpsc::RecvTimeoutError::Timeout) => {}
                Err(mpsc::RecvTimeoutError::Disconnected) => break,
            }
            if pending > 0 && (pending >= batch || last_flush.elapsed() >= flush_every) {
                if let Err(e) = flush(&mut rows, &mut part) {
                    failure = Some(e);
                    stop.store(true, Ordering::Relaxed);
                    break;
                }
                pending = 0;
                last_flush = Instant::now();
            }
        }
        if failure.is_none() && pending > 0 {
            if let Err(e) = flush(&mut rows, &mut part) {
                failure = Some(e);
            }
        }
        // Dropping the receiver ends the workers after their current case on an error.
        drop(rx);
    });
    reporter.finish();
    if let Some(e) = failure {
        return Err(e);
    }
    report.file = part;
    report.wall_s = start.elapsed().as_secs_f64();
    Ok(report)
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

    fn outputs(status: Status, h_c: f64, h_min: f64) -> Outputs {
        Outputs {
            h_c,
            h_c_pmax: h_c,
            h_min,
            x_min: 0.9,
            y_min: None,
            d: None,
            k: None,
            p_max: 1.0,
            spike: None,
            h0: 0.0,
            f: 0.0,
            load_error: 0.0,
            status,
            reason: String::new(),
            grid: 129,
            levels: 4,
            work_units: 1.0,
            wall_s: 0.0,
            error_estimate: None,
            accuracy_met: None,
        }
    }

    #[test]
    fn half_grid_errors_need_two_converged_solves() {
        let fine = outputs(Status::Converged, 5.0, 4.0);
        let coarse = outputs(Status::Converged, 5.1, 3.9);
        let (c, m) = half_grid_errors(&fine, &coarse);
        let factor = 1.0 / (2f64.powf(ESTIMATE_ORDER) - 1.0);
        assert!((c.unwrap() - factor * 0.1 / 5.0).abs() < 1e-14);
        assert!((m.unwrap() - factor * 0.1 / 4.0).abs() < 1e-14);
        let failed = outputs(Status::Diverged, 5.1, 3.9);
        assert_eq!(half_grid_errors(&fine, &failed), (None, None));
        let nan = outputs(Status::Converged, f64::NAN, 3.9);
        assert_eq!(half_grid_errors(&fine, &nan).0, None);
        assert_eq!(half_grid(129), 65);
    }

    #[test]
    fn point_cases_become_point_rows() {
        let text = "contact = \"point\"\n[axes]\nM = [10]\nL = [0]\nD = [0.5, 1]\n\
                    [numerics]\ngrid = 33\nerror_estimate = true\n";
        let spec = crate::sweep::spec::parse("p.toml", text, "p").unwrap();
        let cases = crate::sweep::plan::plan(&spec).unwrap();
        for c in &cases {
            let row = solve_case(c, "p");
            assert_eq!(row.contact, "point");
            assert_eq!(row.d, c.d);
            let k = row.k.unwrap();
            if c.d == Some(1.0) {
                assert_eq!(k, 1.0);
            } else {
                assert!(k > 1.0, "k = {k}");
            }
            assert_eq!(row.grid_requested, 33);
            assert!(row.grid.is_some() && row.attempt.is_some());
            // Whatever the solver returns, no non-finite value survives, and a dropped one
            // clears `valid`.
            let all = [row.h_c, row.h_min, row.x_min, row.y_min, row.p_max, row.h0];
            assert!(all.iter().flatten().all(|v| v.is_finite()));
            if all.iter().any(|v| v.is_none()) {
                assert!(!row.valid);
            }
            assert_eq!(row.status, "converged", "{}", row.reason);
            assert!(row.valid && row.y_min.is_some());
            assert!(row.h_c_err.is_some() && row.h_min_err.is_some());
        }
        // Line rows keep D, k and Y_min null.
        let line = crate::sweep::spec::parse(
            "l.toml",
            "contact = \"line\"\n[axes]\nM = [20]\nL = [0]\n[numerics]\ngrid = 129\n",
            "l",
        )
        .unwrap();
        let row = solve_case(&crate::sweep::plan::plan(&line).unwrap()[0], "l");
        assert_eq!((row.d, row.k, row.y_min), (None, None, None));
        assert_eq!(row.status, "converged");
    }
}
