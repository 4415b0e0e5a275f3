//! `ehlmap case FILE.toml`: a dimensional case, its groups, the numerical solve and the published
//! formulas, as a readable report or JSON; `--plot` draws the solution. The case file is checked
//! (values, grid, the solve's memory) and the `--plot` directory created before the solve.

use crate::cli::error::{input, CliError};
use crate::cli::formula_arg::formula_arg;
use crate::cli::limits::{check_memory, estimate, Solver};
use crate::cli::output::{note, out, outln, prepare_dir, report_plot};
use crate::cli::solve_args::time_limit_arg;
use ehlmap::strategy::solve_case::{default_max_grid, DEFAULT_ACCURACY};
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct CaseArgs {
    /// The case file (TOML, SI units), e.g. sweeps/cases/example-7-1.toml.
    pub file: PathBuf,
    /// Print the report as JSON.
    #[arg(long)]
    pub json: bool,
    /// Only the groups and formulas, no numerical solve.
    #[arg(long)]
    pub no_solve: bool,
    /// Draw the pictures (PNG and SVG) of the solution into this directory.
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Skip the solve with rough surfaces that a roughness (rq) in the file asks for.
    #[arg(long)]
    pub smooth_only: bool,
    /// Stop solving after this many seconds (all solves together): an unconverged solve ends
    /// with status max-iterations, the accuracy ladder with the finest grid solved by then;
    /// the reason says so. Default: no limit.
    #[arg(long, allow_hyphen_values = true)]
    pub time_limit: Option<f64>,
    /// A fit report (fit.json, or its directory) whose formula answers the case without a
    /// solve where its held-out error map is below half the accuracy target (not with a grid
    /// in the case file).
    #[arg(long)]
    pub formula: Option<PathBuf>,
}

/// Run `ehlmap case`.
pub fn run_case(a: &CaseArgs) -> Result<(), CliError> {
    let path = a.file.display();
    let spec = ehlmap::cases::read_case(&a.file).map_err(|e| input(e.to_string()))?;
    if a.plot.is_some() && a.no_solve {
        return Err(input("--plot needs a solve: drop --no-solve"));
    }
    let derived = spec.derive().map_err(|e| input(format!("{path}: {e}")))?;
    if !a.no_solve {
        let contact = derived.case.contact();
        let (grid, what) = match derived.grid {
            Some(g) => (g, format!("{path}: grid = {g}")),
            None => {
                let g = default_max_grid(contact, DEFAULT_ACCURACY);
                (g, format!("{path}: the accuracy ladder's largest grid {g}"))
            }
        };
        check_memory(
            &what,
            &format!("a {contact} solve on this grid"),
            estimate(contact, grid, Solver::Multigrid),
        )?;
    }
    let time_limit = a
        .time_limit
        .map(|t| time_limit_arg("--time-limit", t))
        .transpose()?;
    let formula = a
        .formula
        .as_deref()
        .map(|p| formula_arg("--formula", p))
        .transpose()?;
    if formula.is_some() && (a.no_solve || derived.grid.is_some()) {
        return Err(input(format!(
            "--formula answers a solve with an accuracy target: {}",
            if a.no_solve {
                "drop --no-solve".to_string()
            } else {
                format!("{path} names a grid (drop it to let the accuracy target pick)")
            }
        )));
    }
    if let Some(dir) = &a.plot {
        prepare_dir("--plot", dir)?;
    }
    let opts = ehlmap::cases::RunOptions {
        solve: !a.no_solve,
        keep_fields: a.plot.is_some(),
        rough: !a.smooth_only,
        time_limit,
        formula,
    };
    let (r, fields) = ehlmap::cases::run(&spec, opts).map_err(|e| input(format!("{path}: {e}")))?;
    let plotted = match (&a.plot, &r.numerical) {
        (Some(dir), Some(o)) => {
            let stem = a
                .file
                .file_stem()
                .map_or("case".into(), |s| s.to_string_lossy());
            match &fields {
                Some(ehlmap::cases::CaseFields::Line(p)) => {
                    report_plot(dir, ehlmap::render::pictures::draw_line(dir, &stem, p, o))
                }
                Some(ehlmap::cases::CaseFields::Point(f)) => {
                    report_plot(dir, ehlmap::render::pictures::draw_point(dir, &stem, f, o))
                }
                None => {
                    note!(
                        "ehlmap: --plot: the solve returned no fields ({}), no pictures",
                        o.status
                    );
                    Ok(())
                }
            }
        }
        _ => Ok(()),
    };
    let printed = if a.json {
        outln!(
            "{}",
            serde_json::to_string_pretty(&r).expect("report serialises")
        )
    } else {
        out!("{}", ehlmap::cases::summary(&r))
    };
    plotted.and(printed)
}
