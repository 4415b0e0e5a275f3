//! What the commands tell the user besides their results (stderr).

use ehlmap::render::style::RenderError;
use std::path::PathBuf;

/// Say which pictures were written (stderr), or why none were (a failed solve is a result).
pub fn report_plot(files: Result<Vec<PathBuf>, RenderError>) {
    match files {
        Ok(f) => eprintln!(
            "ehlmap: --plot wrote {} files, e.g. {}",
            f.len(),
            f[0].display()
        ),
        Err(e) => eprintln!("ehlmap: --plot: no pictures: {e}"),
    }
}
