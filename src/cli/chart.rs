//! `ehlmap chart regimes`: the regime map, with a case file's (M, L) marked.

use crate::cli::error::InputError;
use ehlmap::model::regimes::{regime, short};
use ehlmap::render::regime_map::write_regime_map;
use std::path::PathBuf;

/// `ehlmap chart regimes [--out DIR] [--case FILE.toml] [--D d]`.
#[derive(clap::Args, Debug)]
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
    #[arg(long = "D")]
    pub d: Option<f64>,
}

/// Run `ehlmap chart`.
pub fn run_chart(a: &ChartArgs) -> Result<i32, InputError> {
    let mut d = a.d;
    if let Some(d) = d {
        if !(d > 0.0 && d <= 1.0) {
            return Err(InputError(format!("--D {d} is invalid: give D in (0, 1]")));
        }
    }
    let mut mark = None;
    if let Some(path) = &a.case {
        let spec = ehlmap::cases::read_case(path).map_err(|e| InputError(e.to_string()))?;
        let r = ehlmap::cases::report(&spec, false)
            .map_err(|e| InputError(format!("{}: {e}", path.display())))?;
        if let Some(dc) = r.groups.d {
            if d.is_some_and(|x| (x - dc).abs() > 1e-12 * dc) {
                return Err(InputError(format!(
                    "--D {} contradicts the case's D = {dc}",
                    d.unwrap_or(f64::NAN)
                )));
            }
            d = Some(dc);
        } else if d.is_some() {
            return Err(InputError(
                "--D with a line-contact --case: drop --D".into(),
            ));
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
    let files = write_regime_map(&a.out, d, mark.as_ref().map(|m| (m.0, m.1, m.2.as_str())))
        .map_err(|e| InputError(format!("chart regimes: {e}")))?;
    for f in files {
        println!("{}", f.display());
    }
    Ok(0)
}
