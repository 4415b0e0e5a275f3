//! `ehlmap case FILE.toml`: a dimensional case, its groups, the numerical solve and the published
//! formulas, as a readable report or JSON; `--plot` draws the solution.

use crate::cli::error::InputError;
use crate::cli::output::report_plot;
use ehlmap::render::style::RenderError;
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
}

/// Run `ehlmap case`.
pub fn run_case(a: &CaseArgs) -> Result<i32, InputError> {
    let path = a.file.display();
    let spec = ehlmap::cases::read_case(&a.file).map_err(|e| InputError(e.to_string()))?;
    if a.plot.is_some() && a.no_solve {
        return Err(InputError("--plot needs a solve: drop --no-solve".into()));
    }
    let (r, fields) = ehlmap::cases::run(&spec, !a.no_solve, a.plot.is_some())
        .map_err(|e| InputError(format!("{path}: {e}")))?;
    if let (Some(dir), Some(o)) = (&a.plot, &r.numerical) {
        let stem = a
            .file
            .file_stem()
            .map_or("case".into(), |s| s.to_string_lossy());
        let files = match &fields {
            Some(ehlmap::cases::CaseFields::Line(p)) => {
                ehlmap::render::pictures::draw_line(dir, &stem, p, o)
            }
            Some(ehlmap::cases::CaseFields::Point(f)) => {
                ehlmap::render::pictures::draw_point(dir, &stem, f, o)
            }
            None => Err(RenderError(format!(
                "the solve returned no fields ({})",
                o.status
            ))),
        };
        report_plot(files);
    }
    if a.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&r).expect("report serialises")
        );
    } else {
        print!("{}", ehlmap::cases::summary(&r));
    }
    Ok(0)
}
