//! Writing Parquet: [`write_batch_file`] is the one place that sets the writer properties (zstd,
//! footer key-value metadata headed by `ehlmap_version`); [`write_table`] builds a small columnar
//! table (f64, i64, bool, string; NaN stored as null) for profiles, bench and stability results.

use crate::store::error::StoreError;
use arrow_array::{ArrayRef, BooleanArray, Float64Array, Int64Array, RecordBatch, StringArray};
use arrow_schema::{DataType, Field, Schema};
use parquet::arrow::ArrowWriter;
use parquet::basic::{Compression, ZstdLevel};
use parquet::file::metadata::KeyValue;
use parquet::file::properties::WriterProperties;
use std::fs::File;
use std::path::Path;
use std::sync::Arc;

/// One column of a table: its name and values.
pub enum Column {
    /// Floats (nullable: a non-finite value is stored as null).
    F64(&'static str, Vec<f64>),
    /// Integers.
    I64(&'static str, Vec<i64>),
    /// Booleans.
    Bool(&'static str, Vec<bool>),
    /// Strings.
    Str(&'static str, Vec<String>),
}

/// Write the columns (equal lengths) to `path` with `meta` in the footer.
pub fn write_table(
    path: &Path,
    cols: Vec<Column>,
    meta: &[(&str, String)],
) -> Result<(), StoreError> {
    let mut fields = vec![];
    let mut arrays: Vec<ArrayRef> = vec![];
    for c in cols {
        match c {
            Column::F64(n, v) => {
                fields.push(Field::new(n, DataType::Float64, true));
                let v: Vec<Option<f64>> =
                    v.into_iter().map(|x| x.is_finite().then_some(x)).collect();
                arrays.push(Arc::new(Float64Array::from(v)));
            }
            Column::I64(n, v) => {
                fields.push(Field::new(n, DataType::Int64, false));
                arrays.push(Arc::new(Int64Array::from(v)));
            }
            Column::Bool(n, v) => {
                fields.push(Field::new(n, DataType::Boolean, false));
                arrays.push(Arc::new(BooleanArray::from(v)));
            }
            Column::Str(n, v) => {
                fields.push(Field::new(n, DataType::Utf8, false));
                arrays.push(Arc::new(StringArray::from(v)));
            }
        }
    }
    let schema = Arc::new(Schema::new(fields));
    let batch = RecordBatch::try_new(schema, arrays).map_err(|source| StoreError::Arrow {
        path: path.to_path_buf(),
        source,
    })?;
    let meta: Vec<(String, String)> = meta
        .iter()
        .map(|(k, v)| (k.to_string(), v.clone()))
        .collect();
    write_batch_file(path, &batch, &meta).map(|_| ())
}

/// Write one record batch to a new Parquet file at `path` (zstd; footer: `ehlmap_version`, then
/// `meta`). Returns the file, written and closed by the Parquet writer, so callers can sync it.
pub fn write_batch_file(
    path: &Path,
    batch: &RecordBatch,
    meta: &[(String, String)],
) -> Result<File, StoreError> {
    let mut kv = vec![KeyValue::new(
        "ehlmap_version".into(),
        env!("CARGO_PKG_VERSION").to_string(),
    )];
    kv.extend(
        meta.iter()
            .map(|(k, v)| KeyValue::new(k.clone(), v.clone())),
    );
    let props = WriterProperties::builder()
        .set_compression(Compression::ZSTD(ZstdLevel::default()))
        .set_key_value_metadata(Some(kv))
        .build();
    let at = |source| StoreError::Parquet {
        path: path.to_path_buf(),
        source,
    };
    let file = File::create(path).map_err(|source| StoreError::Io {
        op: "create",
        path: path.to_path_buf(),
        source,
    })?;
    let mut w = ArrowWriter::try_new(file, batch.schema(), Some(props)).map_err(at)?;
    w.write(batch).map_err(at)?;
    w.into_inner().map_err(at)
}
