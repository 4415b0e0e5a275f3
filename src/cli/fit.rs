//! `ehlmap fit DATASET... [--out DIR] [--json]`: fit, report, charts. A mixed dataset is fitted
//! per contact (line charts `parity.png` ..., point charts `point_parity.png` ...); a contact with
//! too few cases is reported as skipped; exit 2 only when nothing could be fitted (or a dataset
//! cannot be read: the datasets are the input), exit 1 when the report cannot be written.

use crate::cli::error::{input, io, CliError};
use crate::cli::output::{beside_dataset, note, outln, prepare_dir};
use ehlmap::fit::dataset::load_fit_input;
use ehlmap::fit::dataset::FitInput;
use ehlmap::fit::heldout::FOLDS;
use ehlmap::render::charts::write_charts;
use ehlmap::report::formula_py::formula_py;
use ehlmap::report::markdown::to_markdown;
use ehlmap::report::{fit_report, FitReport};
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
    /// data's grid, at least 257^2: minutes for fine grids).
    #[arg(long)]
    pub no_limit_solves: bool,
    /// A check dataset (repeatable): its cases are compared with the fitted formula, never
    /// fitted (e.g. the midpoints between the data's cases, sweeps/nightly-*-mid.toml). A
    /// formula answers a solve (--formula) only between data cases whose check cases it meets.
    #[arg(long)]
    pub check: Vec<PathBuf>,
}

/// Run `ehlmap fit`.
pub fn run_fit(a: &FitArgs) -> Result<(), CliError> {
    fit_datasets(
        &a.datasets,
        &a.check,
        a.out.clone(),
        a.json,
        !a.no_limit_solves,
    )
}

/// Fit the datasets and write the report, fit.json, formula.py and charts to `out` (default beside the
/// first dataset), with the `check` datasets as the check set; prints the report (or fit.json
/// with `json`). Also the second step of `ehlmap sweep --fit`.
pub fn fit_datasets(
    datasets: &[PathBuf],
    check: &[PathBuf],
    out: Option<PathBuf>,
    json: bool,
    limit_solves: bool,
) -> Result<(), CliError> {
    let out = out.unwrap_or_else(|| beside_dataset(&datasets[0], "report"));
    if let Some(d) = datasets.iter().find(|d| same_dir(d, &out)) {
        return Err(input(format!(
            "--out {}: is the dataset {} (a dataset folder holds only Parquet parts)",
            out.display(),
            d.display()
        )));
    }
    let mut data = load_fit_input(datasets).map_err(|e| input(e.to_string()))?;
    if !check.is_empty() {
        let c = load_fit_input(check).map_err(|e| input(format!("--check: {e}")))?;
        data = data
            .with_check(c)
            .map_err(|e| input(format!("--check: {e}")))?;
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
            "the point asymptote checks solve the limit cases on the data's grid \
             (minutes for fine grids; --no-limit-solves skips them)"
        );
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
