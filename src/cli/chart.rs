//! `ehlmap chart regimes`: the regime map, with a case file's (M, L) marked.

use crate::cli::error::{input, io, CliError};
use crate::cli::output::{outln, prepare_dir};
use ehlmap::model::regimes::{regime, short};
use ehlmap::render::regime_map::write_regime_map;
use std::path::PathBuf;

/// `ehlmap chart regimes [--out DIR] [--case FILE.toml] [--D d]`.
#[derive(clap::Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct ChartArgs {
    /// Which chart (only `regimes`).
    #[arg(value_parser = ["regimes"])]
    pub what: String,
    /// Output directory.
    #[arg(long, default_value = "charts")]
    pub out: PathBuf,
    /// Mark this case (a case file) on the map; a point case sets D.
    #[arg(long)]
    pub case: Option<PathBuf>,
    /// A point contact of this ellipticity D = Rx/Ry in (0, 1] (default: line contact).
    #[arg(long = "D", allow_hyphen_values = true)]
    pub d: Option<f64>,
}

/// Run `ehlmap chart`.
pub fn run_chart(a: &ChartArgs) -> Result<(), CliError> {
    let mut d = a.d;
    if let Some(d) = d {
        if !(d > 0.0 && d <= 1.0) {
            return Err(input(format!(
                "--D {} is invalid: give D in (0, 1]",
                ehlmap::model::error::num(d)
            )));
        }
    }
    let mut mark = None;
    if let Some(path) = &a.case {
        let spec = ehlmap::cases::read_case(path).map_err(|e| input(e.to_string()))?;
        let r = ehlmap::cases::report(&spec, false)
            .map_err(|e| input(format!("{}: {e}", path.display())))?;
        if let Some(dc) = r.groups.d {
            if d.is_some_and(|x| (x - dc).abs() > 1e-12 * dc) {
                return Err(input(format!(
                    "--D {} contradicts the case's D = {dc}",
                    d.unwrap_or(f64::NAN)
                )));
            }
            d = Some(dc);
        } else if d.is_some() {
            return Err(input("--D with a line-contact --case: drop --D"));
        }
        let label = path
            .file_stem()
            .map_or("case".into(), |s| s.to_string_lossy().into_owned());
        mark = Some((
            r.groups.m,
            r.groups.l,
            format!("{label} ({})", short(regime(r.groups.m, r.groups.l, d))),
        ));
    }
    prepare_dir("--out", &a.out)?;
    let files = write_regime_map(&a.out, d, mark.as_ref().map(|m| (m.0, m.1, m.2.as_str())))
        .map_err(|e| io(format!("--out {}: chart regimes: {e}", a.out.display())))?;
    for f in files {
        outln!("{}", f.display())?;
    }
    Ok(())
}
