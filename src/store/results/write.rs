//! Writing a part file: rows to one record batch in the layout of
//! [`COLUMNS`] ([`to_batch`]), then to Parquet through a synced temporary file renamed over the
//! part ([`write_part`]), so a reader only ever sees complete files.
//!
//! No NaN or infinity reaches a file: a non-finite optional float is written as null and its
//! row's `valid` is false; a non-finite required float refuses the whole batch.

use crate::store::error::StoreError;
use crate::store::results::columns::{schema, Access, COLUMNS, SCHEMA_VERSION};
use crate::store::results::files::temp_path;
use crate::store::results::row::CaseRow;
use crate::store::table::write_batch_file;
use arrow_array::{ArrayRef, BooleanArray, Float64Array, Int64Array, RecordBatch, StringArray};
use std::io::Write;
use std::path::Path;
use std::sync::Arc;

/// `r` with every non-finite optional float replaced by null, and `valid` cleared when one was.
fn sanitise(r: &CaseRow) -> CaseRow {
    let mut r = r.clone();
    let mut valid = r.valid;
    for c in COLUMNS {
        if let Access::OptF64 { get, set } = c.access {
            if get(&r).is_some_and(|x| !x.is_finite()) {
                set(&mut r, None);
                valid = false;
            }
        }
    }
    r.valid = valid;
    r
}

/// The first non-finite required float of `r`, as an error naming the case and the column.
fn check_required(r: &CaseRow) -> Result<(), StoreError> {
    for c in COLUMNS {
        if let Access::F64 { get, .. } = c.access {
            let v = get(r);
            if !v.is_finite() {
                return Err(StoreError::NotFinite {
                    case_id: r.case_id.clone(),
                    column: c.name,
                    value: v,
                });
            }
        }
    }
    Ok(())
}

/// The Arrow array of column `access` over `rows`.
fn array(access: Access, rows: &[CaseRow]) -> ArrayRef {
    match access {
        Access::Str { get, .. } => {
            Arc::new(StringArray::from(rows.iter().map(get).collect::<Vec<_>>()))
        }
        Access::OptStr { get, .. } => {
            Arc::new(StringArray::from(rows.iter().map(get).collect::<Vec<_>>()))
        }
        Access::F64 { get, .. } => {
            Arc::new(Float64Array::from(rows.iter().map(get).collect::<Vec<_>>()))
        }
        Access::OptF64 { get, .. } => {
            Arc::new(Float64Array::from(rows.iter().map(get).collect::<Vec<_>>()))
        }
        Access::I64 { get, .. } => {
            Arc::new(Int64Array::from(rows.iter().map(get).collect::<Vec<_>>()))
        }
        Access::OptI64 { get, .. } => {
            Arc::new(Int64Array::from(rows.iter().map(get).collect::<Vec<_>>()))
        }
        Access::Bool { get, .. } => {
            Arc::new(BooleanArray::from(rows.iter().map(get).collect::<Vec<_>>()))
        }
    }
}

/// Rows to one Arrow record batch in the layout of [`COLUMNS`] (sanitised: see the module
/// docs). Fails on a non-finite required float, naming the case and the column.
pub fn to_batch(rows: &[CaseRow]) -> Result<RecordBatch, StoreError> {
    let rows: Vec<CaseRow> = rows.iter().map(sanitise).collect();
    for r in &rows {
        check_required(r)?;
    }
    let cols: Vec<ArrayRef> = COLUMNS.iter().map(|c| array(c.access, &rows)).collect();
    RecordBatch::try_new(schema(), cols).map_err(StoreError::Batch)
}

/// Write `rows` to `path` atomically: to [`temp_path`] first (synced), then renamed over `path`.
/// `meta` goes to the footer key-value metadata after `ehlmap_version` and `ehlmap_schema`.
/// On failure the temporary file is removed and `path` is untouched.
pub fn write_part(
    path: &Path,
    rows: &[CaseRow],
    meta: &[(String, String)],
) -> Result<(), StoreError> {
    let tmp = temp_path(path);
    let r = write_file(&tmp, rows, meta).and_then(|_| {
        std::fs::rename(&tmp, path).map_err(|source| StoreError::Rename {
            from: tmp.clone(),
            to: path.to_path_buf(),
            source,
        })
    });
    if r.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    r
}

/// Write `rows` to a new file at `path` and sync it to disk.
fn write_file(path: &Path, rows: &[CaseRow], meta: &[(String, String)]) -> Result<(), StoreError> {
    let batch = to_batch(rows)?;
    let mut kv = vec![("ehlmap_schema".to_string(), SCHEMA_VERSION.to_string())];
    kv.extend(meta.iter().cloned());
    let mut file = write_batch_file(path, &batch, &kv)?;
    file.flush()
        .and_then(|_| file.sync_all())
        .map_err(|source| StoreError::Io {
            op: "sync",
            path: path.to_path_buf(),
            source,
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::store::results::row::sample;

    #[test]
    fn non_finite_floats_become_null_or_refuse_the_batch() {
        let mut bad = sample("00000000000000bb");
        bad.h_c = Some(f64::NAN);
        bad.wall_s = Some(f64::INFINITY);
        let s = sanitise(&bad);
        assert_eq!((s.h_c, s.wall_s, s.valid), (None, None, false));
        assert_eq!(s.h_min, bad.h_min);
        assert!(sanitise(&sample("00000000000000aa")).valid);
        let b = to_batch(&[sample("00000000000000aa"), bad.clone()]).unwrap();
        assert_eq!((b.num_rows(), b.num_columns()), (2, COLUMNS.len()));
        bad.tol_h = f64::NAN;
        let e = to_batch(&[bad]).unwrap_err().to_string();
        assert_eq!(e, "case 00000000000000bb: tol_h = NaN is not finite");
    }
}
