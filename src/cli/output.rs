//! Where the commands write: stdout through [`write_stdout`] (a closed stdout stops the command
//! quietly, [`CliError::Closed`], instead of the panic of `println!`), stderr through [`note`]
//! (a closed stderr is ignored: the work goes on), and the checks of output paths made before
//! any solve, so that an unwritable output fails at once with exit code 1.

use crate::cli::error::{io, CliError};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Write to stdout and flush: a closed stdout (EPIPE) is [`CliError::Closed`], any other
/// failure (a full disk behind `>`) an I/O error naming stdout.
pub fn write_stdout(args: std::fmt::Arguments) -> Result<(), CliError> {
    let mut o = std::io::stdout().lock();
    o.write_fmt(args)
        .and_then(|()| o.flush())
        .map_err(|e| match e.kind() {
            std::io::ErrorKind::BrokenPipe => CliError::Closed,
            _ => io(format!("stdout: {e}")),
        })
}

/// Print to stdout like `print!`; evaluates to `Result<(), CliError>` (a closed stdout is
/// [`CliError::Closed`]).
macro_rules! out {
    ($($t:tt)*) => {
        $crate::cli::output::write_stdout(format_args!($($t)*))
    };
}

/// Print a line to stdout like `println!`; evaluates to `Result<(), CliError>`.
macro_rules! outln {
    ($($t:tt)*) => {
        $crate::cli::output::write_stdout(format_args!("{}\n", format_args!($($t)*)))
    };
}

/// Print a line to stderr like `eprintln!`, but never panic: a closed stderr is ignored.
macro_rules! note {
    ($($t:tt)*) => {{
        let _ = $crate::cli::output::write_stderr(format_args!("{}\n", format_args!($($t)*)));
    }};
}

pub(crate) use {note, out, outln};

/// Write to stderr; a failure is ignored (there is nowhere left to report it) but returned as
/// `false`, so that a caller can stop writing progress there.
pub fn write_stderr(args: std::fmt::Arguments) -> bool {
    let mut e = std::io::stderr().lock();
    e.write_fmt(args).and_then(|()| e.flush()).is_ok()
}

/// The output directory `dir` of option `flag`, created (with its parents) and checked
/// writable by creating and removing a probe file: an I/O error (exit 1) naming the flag
/// otherwise. Called before any solve.
pub fn prepare_dir(flag: &str, dir: &Path) -> Result<(), CliError> {
    let shown = dir.display();
    if dir.exists() && !dir.is_dir() {
        return Err(io(format!("{flag} {shown}: not a directory")));
    }
    std::fs::create_dir_all(dir)
        .map_err(|e| io(format!("{flag} {shown}: cannot create the directory: {e}")))?;
    probe(flag, dir, &shown.to_string())
}

/// The output file `path` of option `flag`: its directory must exist and be writable and the
/// path must not be a directory; an I/O error (exit 1) naming the flag otherwise. Called before
/// any solve; nothing is created.
pub fn check_file(flag: &str, path: &Path) -> Result<(), CliError> {
    let shown = path.display();
    if path.is_dir() {
        return Err(io(format!("{flag} {shown}: is a directory, not a file")));
    }
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    if !parent.is_dir() {
        let why = if parent.exists() {
            "is not a directory"
        } else {
            "does not exist"
        };
        return Err(io(format!("{flag} {shown}: {} {why}", parent.display())));
    }
    probe(flag, &parent, &shown.to_string())
}

/// Create and remove a probe file in `dir`: can files be written there?
fn probe(flag: &str, dir: &Path, shown: &str) -> Result<(), CliError> {
    let p = dir.join(format!(".ehlmap-write-probe-{}", std::process::id()));
    match std::fs::File::create(&p) {
        Ok(_) => {
            let _ = std::fs::remove_file(&p);
            Ok(())
        }
        Err(e) => Err(io(format!("{flag} {shown}: cannot write there: {e}"))),
    }
}

/// Say which pictures `--plot DIR` wrote (stderr), or fail with an I/O error naming the option.
pub fn report_plot(
    dir: &Path,
    files: Result<Vec<PathBuf>, ehlmap::render::style::RenderError>,
) -> Result<(), CliError> {
    match files {
        Ok(f) => {
            match f.first() {
                Some(first) => note!(
                    "ehlmap: --plot wrote {} files, e.g. {}",
                    f.len(),
                    first.display()
                ),
                None => note!("ehlmap: --plot wrote no files"),
            }
            Ok(())
        }
        Err(e) => Err(io(format!("--plot {}: no pictures: {e}", dir.display()))),
    }
}

/// `DATASET-<suffix>` beside the dataset, outside it: a dataset folder holds only Parquet parts
/// (polars' scan_parquet on the folder fails on anything else).
pub fn beside_dataset(dataset: &Path, suffix: &str) -> PathBuf {
    let name = dataset
        .file_name()
        .map_or("dataset".into(), |n| n.to_string_lossy().into_owned());
    dataset.with_file_name(format!("{name}-{suffix}"))
}
