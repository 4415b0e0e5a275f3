//! Reading sweep datasets back: one part file ([`read_part`]) or a whole directory deduplicated
//! by case id ([`read_dataset`], [`stored_ids`]), driven by the column table
//! [`COLUMNS`].
//!
//! Files of every schema are read. A file whose `error_estimate` column is boolean is of schema
//! 1: that column is today's `half_grid_estimate`, the columns introduced later (`since` > 1)
//! keep the [`CaseRow::default`] value (`model_used = "full"`, the rest null; files before
//! schema 3 read `converge = "tight"`, the only rule then), and `error_estimate` is derived by [`larger_error`] from `H_c_err` and `H_min_err`. A missing
//! column of the file's schema, a column of another type, or an unknown name (status, contact
//! ...) is an error naming the file and the column.

use crate::solve::params::Converge;
use crate::store::error::StoreError;
use crate::store::results::columns::{Access, Column, COLUMNS, SCHEMA_VERSION};
use crate::store::results::files::part_files;
use crate::store::results::row::{larger_error, CaseRow, RowStatus};
use arrow_array::{Array, BooleanArray, Float64Array, Int64Array, RecordBatch, StringArray};
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
use std::collections::{BTreeMap, HashSet};
use std::fs::File;
use std::path::{Path, PathBuf};

/// One part file read back: its rows and its footer key-value metadata.
#[derive(Clone, Debug)]
pub struct Part {
    /// The file.
    pub path: PathBuf,
    /// Its rows, in file order.
    pub rows: Vec<CaseRow>,
    /// Its footer key-value metadata (`ehlmap_version`, `ehlmap_schema`, `spec`, ...).
    pub meta: BTreeMap<String, String>,
}

/// Columns renamed since: (today's name, the last schema of the old name, the old name).
const RENAMED: &[(&str, u32, &str)] = &[("half_grid_estimate", 1, "error_estimate")];

/// The schema version of a batch: 1 when `error_estimate` is boolean, 2 without `converge`,
/// else [`SCHEMA_VERSION`].
fn schema_of(b: &RecordBatch) -> u32 {
    let v1 = b
        .column_by_name("error_estimate")
        .is_some_and(|c| c.as_any().is::<BooleanArray>());
    if v1 {
        1
    } else if b.column_by_name("converge").is_none() {
        2
    } else {
        SCHEMA_VERSION
    }
}

/// The name of column `c` in a file of schema `schema`.
fn name_in(c: &Column, schema: u32) -> &'static str {
    RENAMED
        .iter()
        .find(|(now, last, _)| *now == c.name && schema <= *last)
        .map_or(c.name, |(_, _, old)| old)
}

/// Puts the value of row `j` of one column into a row; `Err` holds why a name is not understood
/// together with the stored value.
type Setter<'a> = Box<dyn Fn(&mut CaseRow, usize) -> Result<(), (String, String)> + 'a>;

/// The setter of column `c` over the batch's array `a`, or `None` when `a` has another type.
fn bind<'a>(c: &Column, a: &'a dyn Array) -> Option<Setter<'a>> {
    let any = a.as_any();
    let opt = move |j: usize| !a.is_null(j);
    Some(match c.access {
        Access::Str { set, .. } => {
            let a = any.downcast_ref::<StringArray>()?;
            Box::new(move |r, j| {
                set(r, a.value(j)).map_err(|e| (a.value(j).to_string(), e.to_string()))
            })
        }
        Access::OptStr { set, .. } => {
            let a = any.downcast_ref::<StringArray>()?;
            Box::new(move |r, j| {
                set(r, opt(j).then(|| a.value(j)));
                Ok(())
            })
        }
        Access::F64 { set, .. } => {
            let a = any.downcast_ref::<Float64Array>()?;
            Box::new(move |r, j| {
                set(r, a.value(j));
                Ok(())
            })
        }
        Access::OptF64 { set, .. } => {
            let a = any.downcast_ref::<Float64Array>()?;
            Box::new(move |r, j| {
                set(r, opt(j).then(|| a.value(j)));
                Ok(())
            })
        }
        Access::I64 { set, .. } => {
            let a = any.downcast_ref::<Int64Array>()?;
            Box::new(move |r, j| {
                set(r, a.value(j));
                Ok(())
            })
        }
        Access::OptI64 { set, .. } => {
            let a = any.downcast_ref::<Int64Array>()?;
            Box::new(move |r, j| {
                set(r, opt(j).then(|| a.value(j)));
                Ok(())
            })
        }
        Access::Bool { set, .. } => {
            let a = any.downcast_ref::<BooleanArray>()?;
            Box::new(move |r, j| {
                set(r, a.value(j));
                Ok(())
            })
        }
    })
}

/// The rows of one record batch of the file `path`.
fn batch_rows(b: &RecordBatch, path: &Path) -> Result<Vec<CaseRow>, StoreError> {
    let schema = schema_of(b);
    let mut setters = vec![];
    for c in COLUMNS.iter().filter(|c| c.since <= schema) {
        let name = name_in(c, schema);
        let a = b.column_by_name(name).ok_or_else(|| StoreError::NoColumn {
            path: path.to_path_buf(),
            column: name.to_string(),
        })?;
        let set = bind(c, a.as_ref()).ok_or_else(|| StoreError::ColumnType {
            path: path.to_path_buf(),
            column: name.to_string(),
        })?;
        setters.push((c.name, set));
    }
    let derive_error = COLUMNS
        .iter()
        .any(|c| c.name == "error_estimate" && c.since > schema);
    let mut rows = Vec::with_capacity(b.num_rows());
    for j in 0..b.num_rows() {
        let mut r = CaseRow::default();
        for (column, set) in &setters {
            set(&mut r, j).map_err(|(value, reason)| StoreError::BadValue {
                path: path.to_path_buf(),
                column,
                value,
                reason,
            })?;
        }
        if derive_error {
            r.error_estimate = larger_error(r.h_c_err, r.h_min_err);
        }
        if schema < 3 {
            // Before schema 3 every solve converged to the tolerances.
            r.converge = Converge::Tight;
        }
        rows.push(r);
    }
    Ok(rows)
}

/// Read one part file: its rows (see the module docs for older schemas) and footer.
pub fn read_part(path: &Path) -> Result<Part, StoreError> {
    let parquet = |source| StoreError::Parquet {
        path: path.to_path_buf(),
        source,
    };
    let file = File::open(path).map_err(|source| StoreError::Io {
        op: "open",
        path: path.to_path_buf(),
        source,
    })?;
    let builder = ParquetRecordBatchReaderBuilder::try_new(file).map_err(parquet)?;
    let meta: BTreeMap<String, String> = builder
        .metadata()
        .file_metadata()
        .key_value_metadata()
        .map(|kv| {
            kv.iter()
                .map(|k| (k.key.clone(), k.value.clone().unwrap_or_default()))
                .collect()
        })
        .unwrap_or_default();
    let mut rows = vec![];
    for batch in builder.build().map_err(parquet)? {
        let b = batch.map_err(|source| StoreError::Arrow {
            path: path.to_path_buf(),
            source,
        })?;
        rows.extend(batch_rows(&b, path)?);
    }
    Ok(Part {
        path: path.to_path_buf(),
        rows,
        meta,
    })
}

/// Is `a` a better record of the same case than `b` (converged and valid beats the rest)?
fn better(a: &CaseRow, b: &CaseRow) -> bool {
    let score = |r: &CaseRow| (r.status == RowStatus::Converged) as u8 * 2 + r.valid as u8;
    score(a) > score(b)
}

/// All rows of a dataset directory, one per case id (sorted by case id). When a case is stored
/// more than once (an overlap of reruns), a converged valid row is preferred, then the first
/// one in file-name order. Temporary files are ignored; a part file that cannot be read is an
/// error naming it. A directory that does not exist is an empty dataset.
pub fn read_dataset(dir: &Path) -> Result<Vec<CaseRow>, StoreError> {
    let mut by_id: BTreeMap<String, CaseRow> = BTreeMap::new();
    for path in part_files(dir)? {
        for r in read_part(&path)?.rows {
            match by_id.get(&r.case_id) {
                Some(old) if !better(&r, old) => {}
                _ => {
                    by_id.insert(r.case_id.clone(), r);
                }
            }
        }
    }
    Ok(by_id.into_values().collect())
}

/// The case ids stored in a dataset directory.
pub fn stored_ids(dir: &Path) -> Result<HashSet<String>, StoreError> {
    let mut ids = HashSet::new();
    for path in part_files(dir)? {
        for r in read_part(&path)?.rows {
            ids.insert(r.case_id);
        }
    }
    Ok(ids)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::case::Contact;
    use crate::solve::solution::ModelUsed;
    use crate::store::results::files::temp_path;
    use crate::store::results::row::sample;
    use crate::store::results::write::{to_batch, write_part};

    #[test]
    fn round_trip_and_nan_flagged() {
        let dir = std::env::temp_dir().join(format!("ehlmap-results-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let mut bad = sample("00000000000000bb");
        bad.h_c = Some(f64::NAN);
        bad.f = Some(f64::INFINITY);
        bad.status = RowStatus::Diverged;
        let good = sample("00000000000000aa");
        let path = dir.join("part-1of1-0001.parquet");
        write_part(&path, &[bad.clone(), good.clone()], &[]).unwrap();
        // Stray files that are not parts are ignored by the reader.
        std::fs::write(dir.join(".part-1of1-0002.parquet.tmp"), b"garbage").unwrap();
        std::fs::write(dir.join("notes.txt"), b"garbage").unwrap();
        let rows = read_dataset(&dir).unwrap();
        assert_eq!(rows.len(), 2);
        assert_eq!(rows[0], good);
        assert_eq!(rows[1].h_c, None);
        assert_eq!(rows[1].f, None);
        assert!(!rows[1].valid);
        assert_eq!(rows[1].h_min, bad.h_min);
        // Duplicates across files: the converged row wins.
        let mut dup = sample("00000000000000bb");
        dup.h_c = Some(7.0);
        write_part(&dir.join("part-1of1-0003.parquet"), &[dup], &[]).unwrap();
        let rows = read_dataset(&dir).unwrap();
        assert_eq!(rows.len(), 2);
        assert_eq!(rows[1].h_c, Some(7.0));
        assert!(!temp_path(&path).exists());
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn unknown_names_are_errors_naming_file_column_and_value() {
        let b = to_batch(&[sample("00000000000000aa")]).unwrap();
        let i = b.schema().index_of("model_used").unwrap();
        let mut cols = b.columns().to_vec();
        cols[i] = std::sync::Arc::new(StringArray::from(vec!["magic"]));
        let b = RecordBatch::try_new(b.schema(), cols).unwrap();
        let e = batch_rows(&b, Path::new("d/part-1of1-0001.parquet"))
            .unwrap_err()
            .to_string();
        for want in ["d/part-1of1-0001.parquet", "`model_used`", "\"magic\""] {
            assert!(e.contains(want), "{e}");
        }
    }

    /// The committed datasets: schema 1 (`smoke-line`, a boolean `error_estimate`) and 2.
    #[test]
    fn committed_datasets_of_schema_1_and_2_read() {
        let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
        let old = read_dataset(&data.join("smoke-line")).unwrap();
        assert!(!old.is_empty());
        for r in &old {
            assert_eq!((r.contact, r.model_used), (Contact::Line, ModelUsed::Full));
            assert_eq!((r.accuracy, r.level, &r.warm_start), (None, None, &None));
            assert_eq!(r.error_estimate, larger_error(r.h_c_err, r.h_min_err));
        }
        assert!(old
            .iter()
            .any(|r| r.half_grid_estimate && r.error_estimate.is_some()));
        let new = read_dataset(&data.join("point-257")).unwrap();
        assert!(!new.is_empty() && new.iter().all(|r| r.contact == Contact::Point));
        assert!(new.iter().any(|r| r.status == RowStatus::Converged));
    }
}
