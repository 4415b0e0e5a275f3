//! `ehlmap fit DATASET... [--out DIR] [--json]`: fit, report, charts. A mixed dataset is fitted
//! per contact (line charts `parity.png` ..., point charts `point_parity.png` ...); a contact with
//! too few cases is reported as skipped; exit 2 only when nothing could be fitted.

use crate::cli::error::InputError;
use ehlmap::fit::dataset::load_fit_input;
use ehlmap::fit::dataset::FitInput;
use ehlmap::render::charts::write_charts;
use ehlmap::report::markdown::to_markdown;
use ehlmap::report::{fit_report, FitReport};
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug)]
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
}

/// Run `ehlmap fit`; returns the exit code.
pub fn run_fit(a: &FitArgs) -> Result<i32, InputError> {
    fit_datasets(&a.datasets, a.out.clone(), a.json, !a.no_limit_solves)
}

/// Fit the datasets and write the report, fit.json and charts to `out` (default beside the
/// first dataset); prints the report (or fit.json with `json`). Also the second step of
/// `ehlmap sweep --fit`.
pub fn fit_datasets(
    datasets: &[PathBuf],
    out: Option<PathBuf>,
    json: bool,
    limit_solves: bool,
) -> Result<i32, InputError> {
    let input = load_fit_input(datasets).map_err(|e| InputError(e.to_string()))?;
    if limit_solves && !input.point.is_empty() {
        eprintln!(
            "fitting; the point asymptote checks solve the limit cases on the data's grid \
             (minutes for fine grids; --no-limit-solves skips them)"
        );
    }
    let report = fit_report(&input, limit_solves).map_err(|e| InputError(e.to_string()))?;
    let out = out.unwrap_or_else(|| default_out(&datasets[0]));
    std::fs::create_dir_all(&out)
        .map_err(|e| InputError(format!("--out {}: {e}", out.display())))?;
    let text = serde_json::to_string_pretty(&report).expect("report serialises");
    let mut md = to_markdown(&report);
    let charts = charts(&out, &input, &report)?;
    if !charts.is_empty() {
        md.push_str("\n## Charts\n\n");
        for c in &charts {
            md.push_str(&format!("![{c}]({c}.png)\n"));
        }
    }
    let write = |name: &str, text: &str| {
        std::fs::write(out.join(name), text)
            .map_err(|e| InputError(format!("{}: {e}", out.join(name).display())))
    };
    write("report.md", &md)?;
    write("fit.json", &text)?;
    if json {
        println!("{text}");
    } else {
        println!("{md}");
        eprintln!(
            "wrote {}/report.md, fit.json and {} charts (PNG, SVG)",
            out.display(),
            charts.len()
        );
    }
    Ok(0)
}

/// DATASET-report beside the dataset, outside it: the dataset folder holds only Parquet parts
/// (polars' scan_parquet on the folder fails on anything else).
fn default_out(dataset: &Path) -> PathBuf {
    let name = dataset
        .file_name()
        .map_or("dataset".into(), |n| n.to_string_lossy().into_owned());
    dataset.with_file_name(format!("{name}-report"))
}

/// The charts of each fitted contact (point ones prefixed `point_`); returns their stems.
fn charts(out: &Path, input: &FitInput, report: &FitReport) -> Result<Vec<String>, InputError> {
    let mut charts = vec![];
    for (prefix, pts, c) in [
        ("", &input.line, &report.line),
        ("point_", &input.point, &report.point),
    ] {
        if let Some(q) = &c.h_c {
            charts.extend(
                write_charts(out, prefix, pts, &q.model)
                    .map_err(|e| InputError(format!("charts: {e}")))?,
            );
        }
    }
    Ok(charts)
}
