//! Reading sweep datasets back: one part file ([`read_part`]) or a whole directory deduplicated
//! by case id ([`read_dataset`], [`stored_ids`]), driven by the column table
//! [`COLUMNS`].
//!
//! Files of every schema are read. The schema of a file is its footer's `ehlmap_schema`; a file
//! without it (re-saved from a notebook without the footer) is of schema 1 when its
//! `error_estimate` column is boolean, else of the latest schema whose columns it all holds (when
//! none, the latest whose own new columns it holds, so that an error names the column it lost). In a
//! file of schema 1, `error_estimate` is today's `half_grid_estimate`, the columns introduced
//! later (`since` > 1) keep the [`CaseRow::default`] value (`model_used = "full"`, the rest
//! null), and `error_estimate` is derived by [`larger_error`] from `H_c_err` and `H_min_err`.
//! Files before schema 3 read `converge = "tight"`, the only stopping rule then.
//!
//! Files written by other tools read as long as they hold the columns: any codec the build
//! decompresses (zstd, snappy, gzip, lz4), types taken from the Parquet schema rather than an
//! embedded Arrow schema (so polars' large or view strings read as strings), floats stored as
//! float32 or integers, and integers stored as int32 or as integral floats (pandas turns an
//! integer column with nulls into floats). A missing column of the file's schema ("not an
//! ehlmap dataset: missing column X"), a column of another type, a null in a required column or
//! an unknown name (status, contact ...) is an error naming the file and the column.

use crate::solve::params::Converge;
use crate::store::error::StoreError;
use crate::store::results::columns::{Access, Column, COLUMNS, SCHEMA_VERSION};
use crate::store::results::files::part_files;
use crate::store::results::row::{larger_error, CaseRow, RowStatus};
use arrow_array::cast::AsArray;
use arrow_array::types::{
    Float32Type, Int16Type, Int32Type, Int64Type, Int8Type, UInt16Type, UInt32Type, UInt8Type,
};
use arrow_array::{Array, BooleanArray, Float64Array, Int64Array, RecordBatch, StringArray};
use arrow_schema::DataType;
use parquet::arrow::arrow_reader::{ArrowReaderOptions, ParquetRecordBatchReaderBuilder};
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

/// The schema version of a batch of a file whose footer says `footer` (module docs).
fn schema_of(b: &RecordBatch, footer: Option<u32>) -> u32 {
    if let Some(v) = footer {
        return v.clamp(1, SCHEMA_VERSION);
    }
    let v1 = b
        .column_by_name("error_estimate")
        .is_some_and(|c| c.as_any().is::<BooleanArray>());
    if v1 {
        return 1;
    }
    let holds_all = |v: u32| {
        COLUMNS
            .iter()
            .filter(|c| c.since <= v)
            .all(|c| b.column_by_name(name_in(c, v)).is_some())
    };
    // No version complete: the newest whose own columns are there (a file of that version that
    // lost another column), so that the error names the column it lost.
    let holds_own = |v: u32| {
        COLUMNS
            .iter()
            .filter(|c| c.since == v)
            .all(|c| b.column_by_name(name_in(c, v)).is_some())
    };
    (2..=SCHEMA_VERSION)
        .rev()
        .find(|&v| holds_all(v))
        .or_else(|| (2..=SCHEMA_VERSION).rev().find(|&v| holds_own(v)))
        .unwrap_or(1)
}

/// The name of column `c` in a file of schema `schema`.
fn name_in(c: &Column, schema: u32) -> &'static str {
    RENAMED
        .iter()
        .find(|(now, last, _)| *now == c.name && schema <= *last)
        .map_or(c.name, |(_, _, old)| old)
}

/// Puts the value of row `j` of one column into a row; `Err` holds the stored value and why it
/// is not understood.
type Setter = Box<dyn Fn(&mut CaseRow, usize) -> Result<(), (String, String)>>;

/// Why a column cannot be bound: its type, or a value that does not convert (value, reason).
enum BindError {
    Type(DataType),
    Value(String, String),
}

/// The floats of `a` (float64, float32 or integers), or `None` for another type.
fn floats(a: &dyn Array) -> Option<Float64Array> {
    fn conv<T: arrow_array::ArrowPrimitiveType>(
        a: &dyn Array,
        f: impl Fn(T::Native) -> f64,
    ) -> Float64Array {
        a.as_primitive::<T>().iter().map(|v| v.map(&f)).collect()
    }
    Some(match a.data_type() {
        DataType::Float64 => a.as_primitive::<arrow_array::types::Float64Type>().clone(),
        DataType::Float32 => conv::<Float32Type>(a, f64::from),
        DataType::Int64 => conv::<Int64Type>(a, |v| v as f64),
        DataType::Int32 => conv::<Int32Type>(a, f64::from),
        _ => return None,
    })
}

/// The integers of `a` (int64, smaller integers, or floats that are all integral).
fn integers(a: &dyn Array) -> Result<Int64Array, BindError> {
    fn conv<T: arrow_array::ArrowPrimitiveType>(
        a: &dyn Array,
        f: impl Fn(T::Native) -> i64,
    ) -> Int64Array {
        a.as_primitive::<T>().iter().map(|v| v.map(&f)).collect()
    }
    Ok(match a.data_type() {
        DataType::Int64 => a.as_primitive::<Int64Type>().clone(),
        DataType::Int32 => conv::<Int32Type>(a, i64::from),
        DataType::Int16 => conv::<Int16Type>(a, i64::from),
        DataType::Int8 => conv::<Int8Type>(a, i64::from),
        DataType::UInt32 => conv::<UInt32Type>(a, i64::from),
        DataType::UInt16 => conv::<UInt16Type>(a, i64::from),
        DataType::UInt8 => conv::<UInt8Type>(a, i64::from),
        DataType::Float64 | DataType::Float32 => {
            let f = floats(a).expect("a float column");
            if let Some(x) = f
                .iter()
                .flatten()
                .find(|x| x.fract() != 0.0 || x.abs() > 9.0e15)
            {
                return Err(BindError::Value(x.to_string(), "not an integer".into()));
            }
            f.iter().map(|v| v.map(|x| x as i64)).collect()
        }
        t => return Err(BindError::Type(t.clone())),
    })
}

/// The strings of `a` (utf8, large utf8 or utf8 view).
fn strings(a: &dyn Array) -> Option<StringArray> {
    Some(match a.data_type() {
        DataType::Utf8 => a.as_string::<i32>().clone(),
        DataType::LargeUtf8 => a.as_string::<i64>().iter().collect(),
        DataType::Utf8View => a.as_string_view().iter().collect(),
        _ => return None,
    })
}

/// The error of a null in a required column.
fn null_value() -> (String, String) {
    (
        "null".to_string(),
        "the column requires a value".to_string(),
    )
}

/// The setter of column `c` over the batch's array `a` (converted to the column's type).
fn bind(c: &Column, a: &dyn Array) -> Result<Setter, BindError> {
    let wrong = || BindError::Type(a.data_type().clone());
    Ok(match c.access {
        Access::Str { set, .. } => {
            let a = strings(a).ok_or_else(wrong)?;
            Box::new(move |r, j| {
                if a.is_null(j) {
                    return Err(null_value());
                }
                set(r, a.value(j)).map_err(|e| (a.value(j).to_string(), e.to_string()))
            })
        }
        Access::OptStr { set, .. } => {
            let a = strings(a).ok_or_else(wrong)?;
            Box::new(move |r, j| {
                set(r, (!a.is_null(j)).then(|| a.value(j)));
                Ok(())
            })
        }
        Access::F64 { set, .. } => {
            let a = floats(a).ok_or_else(wrong)?;
            Box::new(move |r, j| {
                if a.is_null(j) {
                    return Err(null_value());
                }
                set(r, a.value(j));
                Ok(())
            })
        }
        Access::OptF64 { set, .. } => {
            let a = floats(a).ok_or_else(wrong)?;
            Box::new(move |r, j| {
                set(r, (!a.is_null(j)).then(|| a.value(j)));
                Ok(())
            })
        }
        Access::I64 { set, .. } => {
            let a = integers(a)?;
            Box::new(move |r, j| {
                if a.is_null(j) {
                    return Err(null_value());
                }
                set(r, a.value(j));
                Ok(())
            })
        }
        Access::OptI64 { set, .. } => {
            let a = integers(a)?;
            Box::new(move |r, j| {
                set(r, (!a.is_null(j)).then(|| a.value(j)));
                Ok(())
            })
        }
        Access::Bool { set, .. } => {
            let a = a
                .as_any()
                .downcast_ref::<BooleanArray>()
                .ok_or_else(wrong)?
                .clone();
            Box::new(move |r, j| {
                if a.is_null(j) {
                    return Err(null_value());
                }
                set(r, a.value(j));
                Ok(())
            })
        }
    })
}

/// The rows of one record batch of the file `path`, whose footer gives the schema `footer`.
fn batch_rows(
    b: &RecordBatch,
    path: &Path,
    footer: Option<u32>,
) -> Result<Vec<CaseRow>, StoreError> {
    let schema = schema_of(b, footer);
    let mut setters = vec![];
    for c in COLUMNS.iter().filter(|c| c.since <= schema) {
        let name = name_in(c, schema);
        let a = b.column_by_name(name).ok_or_else(|| StoreError::NoColumn {
            path: path.to_path_buf(),
            column: name.to_string(),
        })?;
        let set = bind(c, a.as_ref()).map_err(|e| match e {
            BindError::Type(found) => StoreError::ColumnType {
                path: path.to_path_buf(),
                column: name.to_string(),
                found: found.to_string(),
                expected: c.access.data_type().to_string(),
            },
            BindError::Value(value, reason) => StoreError::BadValue {
                path: path.to_path_buf(),
                column: c.name,
                value,
                reason,
            },
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

/// The codec of a "Disabled feature at compile time: <codec>" error of the Parquet library.
fn disabled_codec(message: &str) -> Option<String> {
    let rest = message.split("Disabled feature at compile time: ").nth(1)?;
    Some(rest.split_whitespace().next().unwrap_or(rest).to_string())
}

/// Read one part file: its rows (see the module docs for older schemas and other writers) and
/// footer.
pub fn read_part(path: &Path) -> Result<Part, StoreError> {
    let parquet = |source: parquet::errors::ParquetError| match disabled_codec(&source.to_string())
    {
        Some(codec) => StoreError::Compression {
            path: path.to_path_buf(),
            codec,
        },
        None => StoreError::Parquet {
            path: path.to_path_buf(),
            source,
        },
    };
    let file = File::open(path).map_err(|source| StoreError::Io {
        op: "open",
        path: path.to_path_buf(),
        source,
    })?;
    // Types from the Parquet schema, not from an Arrow schema another writer embedded.
    let options = ArrowReaderOptions::new().with_skip_arrow_metadata(true);
    let builder =
        ParquetRecordBatchReaderBuilder::try_new_with_options(file, options).map_err(parquet)?;
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
    let footer = meta
        .get("ehlmap_schema")
        .and_then(|v| v.trim().parse().ok());
    let mut rows = vec![];
    for batch in builder.build().map_err(parquet)? {
        let b = batch.map_err(|source| match disabled_codec(&source.to_string()) {
            Some(codec) => StoreError::Compression {
                path: path.to_path_buf(),
                codec,
            },
            None => StoreError::Arrow {
                path: path.to_path_buf(),
                source,
            },
        })?;
        rows.extend(batch_rows(&b, path, footer)?);
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
        let e = batch_rows(&b, Path::new("d/part-1of1-0001.parquet"), Some(2))
            .unwrap_err()
            .to_string();
        for want in ["d/part-1of1-0001.parquet", "`model_used`", "\"magic\""] {
            assert!(e.contains(want), "{e}");
        }
    }

    #[test]
    fn a_codec_the_build_lacks_is_named() {
        let m = "Parquet error: Disabled feature at compile time: brotli";
        assert_eq!(disabled_codec(m).as_deref(), Some("brotli"));
        assert_eq!(disabled_codec("Parquet error: EOF"), None);
        let e = StoreError::Compression {
            path: "d/x.parquet".into(),
            codec: "brotli".into(),
        };
        assert!(
            e.to_string()
                .starts_with("d/x.parquet: compressed with brotli"),
            "{e}"
        );
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
