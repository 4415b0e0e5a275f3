//! The file names of a dataset directory: the part files ehlmap writes ([`is_part_name`]), the
//! files a reader reads ([`is_dataset_file`], [`part_files`]) and where a part's temporary file
//! lives while it is written ([`temp_path`]). Pure path logic plus one directory listing; no
//! Parquet.

use crate::store::error::StoreError;
use std::path::{Path, PathBuf};

/// The temporary file that [`crate::store::results::write_part`] writes before renaming it to
/// `path`: in the parent of the dataset directory (same file system, so the rename is atomic),
/// named `.<dataset>.<part name>.tmp`. Keeping it out of the dataset directory matters: polars'
/// `scan_parquet(dir)` reads every file of a directory and fails on a foreign one.
pub fn temp_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let dir = path.parent();
    match dir.and_then(|d| Some((d.parent()?, d.file_name()?))) {
        Some((base, ds)) => base.join(format!(".{}.{name}.tmp", ds.to_string_lossy())),
        None => path.with_file_name(format!(".{name}.tmp")),
    }
}

/// Is `name` a part file as ehlmap writes them, `part-<shard>-<run>.parquet` (and not a temporary
/// or foreign file)?
pub fn is_part_name(name: &str) -> bool {
    name.starts_with("part-") && name.ends_with(".parquet")
}

/// Is `name` a file that readers of a dataset directory read: every `*.parquet` whose name does
/// not start with `.` or `_` (pyarrow's convention for hidden files), so a part re-saved from a
/// notebook under another name is read (or named in an error), never silently skipped.
pub fn is_dataset_file(name: &str) -> bool {
    name.ends_with(".parquet") && !name.starts_with('.') && !name.starts_with('_')
}

/// The Parquet files of a dataset directory ([`is_dataset_file`]: the part files and any other
/// visible `*.parquet`), sorted by name (empty when `dir` does not exist). Subdirectories and
/// other files are not read.
pub fn part_files(dir: &Path) -> Result<Vec<PathBuf>, StoreError> {
    let cannot_read = |source| StoreError::Io {
        op: "read",
        path: dir.to_path_buf(),
        source,
    };
    let rd = match std::fs::read_dir(dir) {
        Ok(rd) => rd,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(vec![]),
        Err(e) => return Err(cannot_read(e)),
    };
    let mut v = vec![];
    for ent in rd {
        let ent = ent.map_err(cannot_read)?;
        let name = ent.file_name().to_string_lossy().into_owned();
        if is_dataset_file(&name) && ent.file_type().map(|t| t.is_file()).unwrap_or(false) {
            v.push(ent.path());
        }
    }
    v.sort();
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn temp_files_sit_next_to_the_dataset() {
        assert_eq!(
            temp_path(Path::new("out/smoke/part-1of2-0003.parquet")),
            Path::new("out/.smoke.part-1of2-0003.parquet.tmp")
        );
        assert!(is_part_name("part-1of2-0003.parquet"));
        assert!(!is_part_name(".part-1of1-0002.parquet.tmp"));
        assert!(!is_part_name("notes.txt"));
        assert!(is_dataset_file("part-1of2-0003.parquet") && is_dataset_file("resaved.parquet"));
        assert!(!is_dataset_file(".part-1of1-0002.parquet.tmp"));
        assert!(!is_dataset_file("_metadata") && !is_dataset_file("_common.parquet"));
        assert!(!is_dataset_file("notes.txt") && !is_dataset_file(".hidden.parquet"));
    }
}
