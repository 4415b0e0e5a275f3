//! `ehlmap fit --anchors FILE` and `--anchor-solves FILE`: the point approach factor's anchors
//! ([`ehlmap::limits::anchors`]) read from a file, or solved for the data and written to one.

use crate::cli::error::{input, io, CliError};
use crate::cli::output::note;
use ehlmap::fit::approach::APPROACH_MIN_M;
use ehlmap::fit::dataset::FitPoint;
use ehlmap::limits::anchors::{cases, solve, Anchor, AnchorFile, ANCHOR_FACTOR};
use std::path::PathBuf;

/// Where the anchors come from.
#[derive(Clone, Debug)]
pub enum AnchorArg {
    /// Read from a file.
    Read(PathBuf),
    /// Solved for the data and written to a file.
    Solve(PathBuf),
}

/// The anchor cases (M, D) of the point cases `pts` ([`cases`]).
fn wanted(pts: &[FitPoint]) -> Vec<(f64, f64)> {
    let data: Vec<(f64, f64, f64)> = pts.iter().map(|p| (p.m, p.l, p.dd())).collect();
    cases(&data, APPROACH_MIN_M)
}

/// Refuses `--anchor-solves` for data without a case to anchor (checked before anything is
/// written).
pub fn solvable(pts: &[FitPoint]) -> Result<(), CliError> {
    if wanted(pts).is_empty() {
        return Err(input(format!(
            "--anchor-solves: the data have no point case at L = 0, M >= {APPROACH_MIN_M}"
        )));
    }
    Ok(())
}

/// The anchors of `arg` for the point cases `pts`: read (refused when the file's cases are not
/// the data's: another dataset's anchors would pin g where these data stop elsewhere), or solved
/// and written.
pub fn anchors(arg: &AnchorArg, pts: &[FitPoint]) -> Result<Vec<Anchor>, CliError> {
    let want = wanted(pts);
    let file = match arg {
        AnchorArg::Read(path) => {
            let text = std::fs::read_to_string(path)
                .map_err(|e| input(format!("--anchors {}: {e}", path.display())))?;
            let file = serde_json::from_str::<AnchorFile>(&text)
                .map_err(|e| input(format!("--anchors {}: {e}", path.display())))?;
            let have: Vec<(f64, f64)> = file.anchors.iter().map(|a| (a.m, a.d)).collect();
            let same = have.len() == want.len()
                && have
                    .iter()
                    .zip(&want)
                    .all(|(a, b)| (a.0 / b.0 - 1.0).abs() < 1e-9 && (a.1 / b.1 - 1.0).abs() < 1e-9);
            if !same {
                return Err(input(format!(
                    "--anchors {}: its cases (M, D) are not those of these data ({} anchors, \
                     the data need {}: {ANCHOR_FACTOR:.4} x the largest M >= {APPROACH_MIN_M} \
                     of the L = 0 cases at each D); solve them with --anchor-solves",
                    path.display(),
                    have.len(),
                    want.len()
                )));
            }
            file
        }
        AnchorArg::Solve(path) => {
            solvable(pts)?;
            note!(
                "--anchor-solves: {} elastic-isoviscous solves half a decade of M beyond the \
                 data (one per D) on 513^2, 1025^2 and 2049^2 (1-30 s each, about 1 GB)",
                want.len()
            );
            let file = solve(&want, &|n, of| {
                note!("--anchor-solves: {n} of {of}");
            });
            let text = serde_json::to_string_pretty(&file).expect("anchor file serialises");
            std::fs::write(path, text)
                .map_err(|e| io(format!("--anchor-solves {}: {e}", path.display())))?;
            note!("--anchor-solves: wrote {}", path.display());
            file
        }
    };
    Ok(file.anchors)
}
