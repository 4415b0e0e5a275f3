//! `ehlmap sweep SPEC [--out DIR] [--threads N] [--shard i/n] [--resume] [--dry-run]`.
//!
//! * `--out DIR`: base directory of datasets (default: the spec's `[output] dir`, "outputs");
//!   the dataset is `DIR/<name>/`.
//! * `--threads N`: worker threads (default: `SLURM_CPUS_PER_TASK` when set, else all cores).
//! * `--shard i/n`: solve only shard i of n (default: from `SLURM_ARRAY_TASK_ID`,
//!   `SLURM_ARRAY_TASK_MIN`, `SLURM_ARRAY_TASK_STEP` and `SLURM_ARRAY_TASK_COUNT` when they are
//!   set, else the whole sweep).
//! * `--resume`: continue an earlier run; refuses to start when the dataset directory holds no
//!   part file (a plain rerun skips stored cases too, and may start a new dataset).
//! * `--dry-run`: print the planned cases of the shard (id, M, L, D for point contacts, estimated
//!   cost, stored or not) and exit; it takes every option of a real run and runs nothing.
//! * `--new-dataset`: when the dataset holds rows of other settings than the spec, move those
//!   part files to `<out>/<name>.old-<hash>/` instead of refusing.
//!
//! Exit codes: 2 for a bad spec or option, or a dataset of other settings (nothing runs), 1 when
//! the dataset directory cannot be created, read or written (checked before the first solve, and
//! while running) or another run holds the shard's lock.

use crate::cli::error::{input, io, CliError};
use crate::cli::formula_arg::formula_arg;
use crate::cli::limits::{check_memory, estimate, human, Solver};
use crate::cli::output::{note, out, write_stderr};
use crate::cli::solve_args::time_limit_arg;
use clap::ValueEnum;
use ehlmap::store::results;
use ehlmap::sweep::executor::{self, Progress, RunOptions};
use ehlmap::sweep::plan::{self, Shard};
use ehlmap::sweep::spec;
use std::path::PathBuf;

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub enum ProgressArg {
    /// A bar on a terminal, log lines otherwise.
    Auto,
    Bar,
    Log,
    None,
}

#[derive(clap::Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct SweepArgs {
    /// The sweep spec (TOML), e.g. sweeps/smoke.toml.
    pub spec: PathBuf,
    /// Base directory of the datasets (the dataset goes to DIR/<name>/).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Worker threads (default: SLURM_CPUS_PER_TASK, else all cores).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=4096))]
    pub threads: Option<u32>,
    /// Solve only shard i of n (1-based), e.g. 2/4.
    #[arg(long)]
    pub shard: Option<String>,
    /// Continue an earlier run (the dataset must exist); stored cases are always skipped.
    #[arg(long, conflicts_with = "new_dataset")]
    pub resume: bool,
    /// Start a new dataset: move the part files of other settings than the spec's to
    /// <out>/<name>.old-<hash>/ (a run into such a dataset refuses otherwise).
    #[arg(long)]
    pub new_dataset: bool,
    /// Seconds each case may take (all its solves together, > 0): a case that reaches it is
    /// stored with status max-iterations and a reason naming the limit, and the sweep goes on.
    /// Default: no limit. Not a setting of the dataset (a case that ends before its limit is
    /// the same without one), so a resumed run may change it.
    #[arg(long, allow_hyphen_values = true)]
    pub case_time_limit: Option<f64>,
    /// A fit report (fit.json, or its directory) whose formula answers the cases with an
    /// accuracy target where its held-out error map is below half the target (rows with
    /// model_used "formula"); the others are solved. Not a setting of the dataset.
    #[arg(long)]
    pub formula: Option<PathBuf>,
    /// Print the planned cases and exit without solving.
    #[arg(long)]
    pub dry_run: bool,
    #[arg(long, value_enum, default_value = "auto")]
    pub progress: ProgressArg,
    /// After the sweep, run the fit report on its dataset (`ehlmap fit DATASET`).
    #[arg(long)]
    pub fit: bool,
}

fn env_usize(name: &str) -> Result<Option<usize>, CliError> {
    match std::env::var(name) {
        Err(_) => Ok(None),
        Ok(v) if v.trim().is_empty() => Ok(None),
        Ok(v) => v
            .trim()
            .parse::<usize>()
            .map(Some)
            .map_err(|_| input(format!("{name}={v} is not a non-negative integer"))),
    }
}

/// The shard from `--shard`, else from the Slurm array variables, else the whole sweep.
pub fn resolve_shard(arg: Option<&str>) -> Result<Shard, CliError> {
    if let Some(s) = arg {
        return Shard::parse(s).map_err(|e| input(e.to_string()));
    }
    let Some(id) = env_usize("SLURM_ARRAY_TASK_ID")? else {
        return Ok(Shard::WHOLE);
    };
    let count = env_usize("SLURM_ARRAY_TASK_COUNT")?
        .ok_or_else(|| input("SLURM_ARRAY_TASK_ID is set but SLURM_ARRAY_TASK_COUNT is not"))?;
    let min = env_usize("SLURM_ARRAY_TASK_MIN")?.unwrap_or(0);
    let step = env_usize("SLURM_ARRAY_TASK_STEP")?.unwrap_or(1).max(1);
    if id < min || (id - min) % step != 0 || (id - min) / step >= count {
        return Err(input(format!(
            "SLURM_ARRAY_TASK_ID={id} does not fit SLURM_ARRAY_TASK_MIN={min}, \
             SLURM_ARRAY_TASK_STEP={step}, SLURM_ARRAY_TASK_COUNT={count}"
        )));
    }
    Ok(Shard {
        index: (id - min) / step + 1,
        count,
    })
}

/// `--threads`, else `SLURM_CPUS_PER_TASK`, else the available cores.
pub fn resolve_threads(arg: Option<u32>) -> Result<usize, CliError> {
    if let Some(n) = arg {
        return Ok(n as usize);
    }
    match env_usize("SLURM_CPUS_PER_TASK")? {
        Some(0) => Err(input("SLURM_CPUS_PER_TASK=0: need at least 1")),
        Some(n) => Ok(n),
        None => Ok(std::thread::available_parallelism().map_or(1, |n| n.get())),
    }
}

/// Run `ehlmap sweep` (exit code 1 on an I/O failure of the dataset, before or while running).
pub fn run_sweep(args: &SweepArgs) -> Result<(), CliError> {
    let spec = spec::load(&args.spec).map_err(|e| input(e.to_string()))?;
    let cases = plan::plan(&spec).map_err(|e| input(e.to_string()))?;
    let shard = resolve_shard(args.shard.as_deref())?;
    let threads = resolve_threads(args.threads)?;
    let case_time_limit = args
        .case_time_limit
        .map(|t| time_limit_arg("--case-time-limit", t))
        .transpose()?;
    let formula = args
        .formula
        .as_deref()
        .map(|p| formula_arg("--formula", p))
        .transpose()?;
    if formula.is_some() && cases.iter().all(|c| c.numerics.accuracy.is_none()) {
        return Err(input(format!(
            "--formula answers cases with an accuracy target, and {} names a grid for every \
             case (drop `grid` or set `accuracy` in its [numerics])",
            args.spec.display()
        )));
    }
    let (base, flag) = match &args.out {
        Some(o) => (o.clone(), "--out"),
        None => (spec.output.dir.clone(), "the spec's output.dir"),
    };
    let dataset = base.join(&spec.name);
    let unusable = |e: &dyn std::fmt::Display| {
        io(format!(
            "{flag} {}: the dataset directory {} cannot be used: {e}",
            base.display(),
            dataset.display()
        ))
    };
    let parts = results::part_files(&dataset).map_err(|e| unusable(&e))?;
    if args.resume && parts.is_empty() {
        return Err(input(format!(
            "--resume: {} holds no dataset to resume (run without --resume to start one)",
            dataset.display()
        )));
    }
    let in_shard = cases.iter().filter(|c| shard.contains(c.id)).count();
    if args.dry_run {
        return dry_run(&spec, &cases, shard, &dataset);
    }
    check_sweep_memory(&spec, threads.min(in_shard.max(1)))?;
    if dataset.exists() && !dataset.is_dir() {
        return Err(unusable(&"it is a file, not a directory"));
    }
    std::fs::create_dir_all(&dataset).map_err(|e| unusable(&format!("cannot create it: {e}")))?;
    // Part files are written beside the dataset directory and renamed into it: try writing
    // there (never inside the dataset, which holds only complete part files).
    let beside = dataset.parent().unwrap_or(std::path::Path::new("."));
    let probe = beside.join(format!(".ehlmap-write-probe-{}.tmp", std::process::id()));
    std::fs::File::create(&probe).map_err(|e| {
        unusable(&format!(
            "cannot write beside it in {}: {e}",
            beside.display()
        ))
    })?;
    let _ = std::fs::remove_file(&probe);
    if std::fs::metadata(&dataset).is_ok_and(|m| m.permissions().readonly()) {
        return Err(unusable(&"it is read-only"));
    }
    let stderr_open = write_stderr(format_args!(
        "sweep {}: {} cases, shard {shard} holds {}; {threads} thread{} -> {}\n",
        spec.name,
        cases.len(),
        in_shard,
        if threads == 1 { "" } else { "s" },
        dataset.display()
    ));
    let opts = RunOptions {
        dataset: dataset.clone(),
        threads,
        shard,
        // No progress on a stderr that is closed already (its log lines would fail).
        progress: match args.progress {
            _ if !stderr_open => Progress::None,
            ProgressArg::Auto => Progress::Auto,
            ProgressArg::Bar => Progress::Bar,
            ProgressArg::Log => Progress::Log,
            ProgressArg::None => Progress::None,
        },
        new_dataset: args.new_dataset,
        case_time_limit,
        formula,
    };
    match executor::execute(&spec, &cases, &opts) {
        Ok(r) => {
            report_run(&spec.name, &r);
            if args.fit {
                return crate::cli::fit::fit_datasets(
                    &[dataset],
                    &[],
                    None,
                    &crate::cli::fit::FitOptions::default(),
                );
            }
            Ok(())
        }
        Err(e) => {
            let message = format!("sweep {}: {e}", spec.name);
            Err(if e.exit_code() == 2 {
                input(message)
            } else {
                io(message)
            })
        }
    }
}

/// The memory of `threads` simultaneous solves on the spec's finest grid of each contact,
/// against the memory there is (exit 2 naming the grid and the threads).
fn check_sweep_memory(spec: &spec::SweepSpec, threads: usize) -> Result<(), CliError> {
    for c in &spec.contacts {
        let g = c.numerics.grid;
        let one = estimate(c.contact, g, Solver::Multigrid);
        let need = one.saturating_mul(threads as u64);
        let solves = if threads == 1 {
            "one solve".to_string()
        } else {
            format!("{threads} simultaneous solves of about {} each", human(one))
        };
        check_memory(
            &format!(
                "{}: numerics.grid = {g} ({} contacts) on {threads} threads (--threads)",
                spec.file,
                c.contact.as_str()
            ),
            &solves,
            need,
        )?;
    }
    Ok(())
}

/// `--dry-run`: the shard's cases, one a line, with whether each is stored already.
fn dry_run(
    spec: &spec::SweepSpec,
    cases: &[plan::Case],
    shard: Shard,
    dataset: &std::path::Path,
) -> Result<(), CliError> {
    let stored = results::stored_ids(dataset)
        .map_err(|e| io(format!("the dataset {}: {e}", dataset.display())))?;
    let mine: Vec<_> = cases.iter().filter(|c| shard.contains(c.id)).collect();
    let mut text = format!(
        "# sweep {}: {} cases, shard {shard}: {}, dataset {}\n# case_id contact M L D cost stored\n",
        spec.name,
        cases.len(),
        mine.len(),
        dataset.display()
    );
    for c in mine {
        let d = c.d.map_or("-".to_string(), |d| d.to_string());
        text.push_str(&format!(
            "{} {} {} {} {d} {:.0} {}\n",
            c.id_hex(),
            c.contact.as_str(),
            c.m,
            c.l,
            c.cost,
            stored.contains(&c.id_hex())
        ));
    }
    out!("{text}")
}

/// What a finished run did (stderr): cases stored, solved, failed, the file, the models used.
fn report_run(name: &str, r: &executor::RunReport) {
    let file = r
        .file
        .as_ref()
        .map_or("no file written".to_string(), |p| p.display().to_string());
    for (from, to) in &r.moved {
        note!("sweep {name}: moved {} to {}", from.display(), to.display());
    }
    note!(
        "sweep {name}: {} already stored, {} solved ({} failed) in {:.1} s; {}",
        r.already_stored,
        r.solved,
        r.failed,
        r.wall_s,
        file
    );
    if r.models.keys().any(|m| m != "full") {
        let counts: Vec<String> = r
            .models
            .iter()
            .map(|(m, n)| {
                let t = r.model_seconds.get(m).copied().unwrap_or(0.0);
                format!("{m} {n} ({t:.1} s)")
            })
            .collect();
        note!(
            "sweep {name}: models used: {} (ehlmap bench --selection SPEC measures the saving)",
            counts.join(", ")
        );
    }
}
