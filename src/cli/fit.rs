//! `ehlmap fit DATASET... [--out DIR] [--json]`: fit, report, charts. A mixed dataset is fitted
//! per contact (line charts `parity.png` ..., point charts `point_parity.png` ...); a contact with
//! too few cases is reported as skipped; exit 2 only when nothing could be fitted (or a dataset
//! cannot be read: the datasets are the input), exit 1 when the report cannot be written.

use crate::cli::anchor_arg::{anchors, solvable, AnchorArg};
use crate::cli::error::{input, io, CliError};
use crate::cli::output::{beside_dataset, note, outln, prepare_dir};
use ehlmap::fit::dataset::load_fit_input;
use ehlmap::fit::dataset::FitInput;
use ehlmap::fit::heldout::FOLDS;
use ehlmap::limits::jump::{jump_columns, Case, JumpFile, JumpTable, GRID, RATIO, TOLERANCE};
use ehlmap::model::case::Contact;
use ehlmap::render::charts::write_charts;
use ehlmap::report::formula_py::formula_py;
use ehlmap::report::markdown::to_markdown;
use ehlmap::report::{fit_report, FitReport};
use ehlmap::solve::solution::ModelUsed;
use ehlmap::store::results::read::{read_dataset, read_part};
use ehlmap::store::results::row::RowStatus;
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct FitArgs {
    /// Sweep dataset directories (all part files inside are read).
    #[arg(required = true)]
    pub datasets: Vec<PathBuf>,
    /// Where report.md, fit.json and the charts go (default: DATASET-report beside the first
    /// dataset, outside it, so that the dataset folder holds only Parquet parts).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Print fit.json to stdout instead of the Markdown report.
    #[arg(long)]
    pub json: bool,
    /// Skip the solver's asymptote limit solves (for point data they solve the limit cases on the
    /// data's grid, at least 257^2, and the elastic-isoviscous case a decade of M beyond the data
    /// on 513^2 to 2049^2, about 1 GB: minutes for fine grids).
    #[arg(long)]
    pub no_limit_solves: bool,
    /// A check dataset (repeatable): its cases are compared with the fitted formula, never
    /// fitted (e.g. the midpoints between the data's cases, sweeps/nightly-*-mid.toml). A
    /// formula answers a solve (--formula) only between data cases whose check cases it meets.
    #[arg(long)]
    pub check: Vec<PathBuf>,
    /// Read where the point H_c corner lies (a file written by --jump-solves): the point H_c
    /// kriging then also offers the corner coordinate (docs/method.md, "The corner coordinate of
    /// the point H_c").
    #[arg(long, value_name = "FILE", conflicts_with = "jump_solves")]
    pub jump: Option<PathBuf>,
    /// Solve where the point H_c corner lies in each (L, D) column of the data (M bisected for
    /// H_c / H_pm = 0.95 on 513^2 to 0.2 %: about 6 min for 91 columns on two cores), write
    /// it to FILE and use it as --jump does.
    #[arg(long, value_name = "FILE")]
    pub jump_solves: Option<PathBuf>,
    /// Read the point approach factor's anchors (a file written by --anchor-solves for the same
    /// data): the point H_c elastic-isoviscous law is then held as H_pm's is (--point-ei-limit
    /// implied) and the approach factor of both is fitted to them too, with a third power of M
    /// (docs/method.md, "Anchors").
    #[arg(long, value_name = "FILE", conflicts_with = "anchor_solves")]
    pub anchors: Option<PathBuf>,
    /// Solve the point approach factor's anchors: the L = 0 case at sqrt(10) times the largest
    /// M of the data's L = 0 cases at each D, on 513^2, 1025^2 and 2049^2, extrapolated to zero
    /// spacing (1-30 s per D, about 1 GB); write them to FILE and use them as --anchors does.
    #[arg(long, value_name = "FILE")]
    pub anchor_solves: Option<PathBuf>,
    /// Hold the point H_c elastic-isoviscous law at its limit as the H_pm fit always does: the
    /// line's carried over by the local inlet analysis (2.3422 f_EI(D) M^(-2/15), f_EI exact)
    /// times an approach factor fitted first to the data's L = 0, M >= 100 cases that tends to
    /// 1 as M -> infinity, instead of a fitted law: exact as M -> infinity, but without anchors
    /// H_c's held-out max rises; implied by --anchors and --anchor-solves; docs/method.md, "The
    /// approach factor".
    #[arg(long)]
    pub point_ei_limit: bool,
}

/// Where the point H_c corner's place comes from.
#[derive(Clone, Debug)]
pub enum JumpArg {
    /// Read from a file.
    Read(PathBuf),
    /// Solved and written to a file.
    Solve(PathBuf),
}

/// How [`fit_datasets`] fits and reports: the defaults are `ehlmap sweep --fit`'s (the report
/// printed, the limit solves run, no corner table, fitted H_c EI law).
#[derive(Clone, Debug, Default)]
pub struct FitOptions {
    /// Print fit.json instead of the report.
    pub json: bool,
    /// Skip the solver's limit solves (`--no-limit-solves`).
    pub no_limit_solves: bool,
    /// Where the point H_c corner's place comes from (`--jump`, `--jump-solves`).
    pub jump: Option<JumpArg>,
    /// Hold the point H_c EI law at its limit too (`--point-ei-limit`).
    pub point_ei_limit: bool,
    /// Where the point approach factor's anchors come from (`--anchors`, `--anchor-solves`).
    pub anchors: Option<AnchorArg>,
}

/// Run `ehlmap fit`.
pub fn run_fit(a: &FitArgs) -> Result<(), CliError> {
    let jump = match (&a.jump, &a.jump_solves) {
        (Some(f), _) => Some(JumpArg::Read(f.clone())),
        (None, Some(f)) => Some(JumpArg::Solve(f.clone())),
        (None, None) => None,
    };
    let opts = FitOptions {
        json: a.json,
        no_limit_solves: a.no_limit_solves,
        jump,
        point_ei_limit: a.point_ei_limit,
        anchors: match (&a.anchors, &a.anchor_solves) {
            (Some(f), _) => Some(AnchorArg::Read(f.clone())),
            (None, Some(f)) => Some(AnchorArg::Solve(f.clone())),
            (None, None) => None,
        },
    };
    fit_datasets(&a.datasets, &a.check, a.out.clone(), &opts)
}

/// The solved point cases of the `datasets` with their raw H_pm (the fit input leaves H_pm out
/// where the outlet spike or an unresolved central peak is the maximum, which the corner's
/// bracket still needs).
fn jump_cases(datasets: &[PathBuf]) -> Result<Vec<Case>, CliError> {
    let mut cases = vec![];
    for dir in datasets {
        let rows = if dir.is_file() {
            read_part(dir).map(|p| p.rows)
        } else {
            read_dataset(dir)
        }
        .map_err(|e| input(format!("{}: {e}", dir.display())))?;
        cases.extend(rows.iter().filter_map(|r| {
            let solved = r.status == RowStatus::Converged && r.valid && r.sigma.is_none();
            let (h_c, h_pm) = (r.h_c?, r.h_c_pmax?);
            let ok = solved && r.model_used != ModelUsed::Formula && h_c > 0.0 && h_pm > 0.0;
            (r.contact == Contact::Point && ok).then_some((r.m, r.l, r.d?, h_c, h_pm))
        }));
    }
    if cases.is_empty() {
        return Err(input(
            "--jump-solves: the data have no solved point cases".to_string(),
        ));
    }
    Ok(cases)
}

/// The jump table of `arg`: read, or solved for the point `cases` and written.
fn jump_table(arg: &JumpArg, cases: &[Case]) -> Result<JumpTable, CliError> {
    let file = match arg {
        JumpArg::Read(path) => {
            let text = std::fs::read_to_string(path)
                .map_err(|e| input(format!("--jump {}: {e}", path.display())))?;
            serde_json::from_str::<JumpFile>(&text)
                .map_err(|e| input(format!("--jump {}: {e}", path.display())))?
        }
        JumpArg::Solve(path) => {
            note!(
                "--jump-solves: bisecting M for H_c / H_pm = {RATIO} in each (L, D) column of \
                 the point data on {GRID}^2 (about 10 s per solve, 5-10 solves per column)"
            );
            let (columns, table) = jump_columns(cases, GRID, &|n, of| {
                note!("--jump-solves: {n} of {of} columns");
            });
            let file = JumpFile {
                ratio: RATIO,
                grid: GRID,
                tolerance: TOLERANCE,
                columns,
                table,
            };
            let text = serde_json::to_string_pretty(&file).expect("jump file serialises");
            std::fs::write(path, text)
                .map_err(|e| io(format!("--jump-solves {}: {e}", path.display())))?;
            let solved = file.columns.iter().filter(|c| c.solved).count();
            note!(
                "--jump-solves: wrote {} ({solved} of {} columns bisected)",
                path.display(),
                file.columns.len()
            );
            file
        }
    };
    file.table.ok_or_else(|| {
        input("--jump: the table is missing (a column of the data has no corner)".to_string())
    })
}

/// Fit the datasets and write the report, fit.json, formula.py and charts to `out` (default beside the
/// first dataset), with the `check` datasets as the check set and the options `opts`; prints the
/// report (or fit.json with `opts.json`). Also the second step of `ehlmap sweep --fit`.
pub fn fit_datasets(
    datasets: &[PathBuf],
    check: &[PathBuf],
    out: Option<PathBuf>,
    opts: &FitOptions,
) -> Result<(), CliError> {
    let (json, limit_solves, jump) = (opts.json, !opts.no_limit_solves, opts.jump.as_ref());
    let out = out.unwrap_or_else(|| beside_dataset(&datasets[0], "report"));
    if let Some(d) = datasets.iter().find(|d| same_dir(d, &out)) {
        return Err(input(format!(
            "--out {}: is the dataset {} (a dataset folder holds only Parquet parts)",
            out.display(),
            d.display()
        )));
    }
    let mut data = load_fit_input(datasets).map_err(|e| input(e.to_string()))?;
    data.point_ei_limit = opts.point_ei_limit;
    if !check.is_empty() {
        let c = load_fit_input(check).map_err(|e| input(format!("--check: {e}")))?;
        data = data
            .with_check(c)
            .map_err(|e| input(format!("--check: {e}")))?;
    }
    // A table to read is read first, and the cases to solve one for are gathered: bad input is
    // refused before anything is written.
    let solve_for = match jump {
        Some(j @ JumpArg::Read(_)) => {
            data.jump = Some(jump_table(j, &[])?);
            vec![]
        }
        Some(JumpArg::Solve(_)) => jump_cases(datasets)?,
        None => vec![],
    };
    match &opts.anchors {
        Some(a @ AnchorArg::Read(_)) => data.anchors = anchors(a, &data.point)?,
        Some(AnchorArg::Solve(_)) => solvable(&data.point)?,
        None => {}
    }
    // The report's directory before the fit (its limit solves can take minutes).
    prepare_dir("--out", &out)?;
    let cases = data.line.len() + data.point.len();
    if cases >= 2 * FOLDS {
        note!(
            "fitting {cases} cases: each film's formula is cross-validated ({FOLDS} folds, blend \
             and correction refitted per fold, the folds in parallel; on two cores about 30 s \
             for 600 line cases, a minute for 400 point cases, 5 min for 1500)"
        );
    }
    if limit_solves && !data.point.is_empty() {
        note!(
            "the point asymptote checks solve the limit cases on the data's grid, and \
             the elastic-isoviscous case a decade of M beyond the data on 513^2 to 2049^2 \
             (minutes for fine grids, about 1 GB; --no-limit-solves skips them)"
        );
    }
    if let Some(j @ JumpArg::Solve(_)) = jump {
        data.jump = Some(jump_table(j, &solve_for)?);
    }
    if let Some(a @ AnchorArg::Solve(_)) = &opts.anchors {
        data.anchors = anchors(a, &data.point)?;
    }
    let report = fit_report(&data, limit_solves).map_err(|e| input(e.to_string()))?;
    let text = serde_json::to_string_pretty(&report).expect("report serialises");
    let mut md = to_markdown(&report);
    let charts = charts(&out, &data, &report)?;
    if !charts.is_empty() {
        md.push_str("\n## Charts\n\n");
        for c in &charts {
            md.push_str(&format!("![{c}]({c}.png)\n"));
        }
    }
    let write = |name: &str, text: &str| {
        std::fs::write(out.join(name), text)
            .map_err(|e| io(format!("--out {}: {e}", out.join(name).display())))
    };
    write("report.md", &md)?;
    write("fit.json", &text)?;
    write("formula.py", &formula_py(&report))?;
    if json {
        outln!("{text}")
    } else {
        outln!("{md}")?;
        note!(
            "wrote {}/report.md, fit.json, formula.py and {} charts (PNG, SVG)",
            out.display(),
            charts.len()
        );
        Ok(())
    }
}

/// Whether two paths name the same existing directory.
fn same_dir(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(x), Ok(y)) => x == y,
        _ => false,
    }
}

/// The charts of each fitted contact (point ones prefixed `point_`); returns their stems.
fn charts(out: &Path, input: &FitInput, report: &FitReport) -> Result<Vec<String>, CliError> {
    let mut charts = vec![];
    for (prefix, pts, c) in [
        ("", &input.line, &report.line),
        ("point_", &input.point, &report.point),
    ] {
        if let Some(q) = &c.h_c {
            charts.extend(
                write_charts(out, prefix, pts, &q.model, q.heldout.as_ref())
                    .map_err(|e| io(format!("--out {}: charts: {e}", out.display())))?,
            );
        }
    }
    Ok(charts)
}
