//! A small columnar table written as Parquet (zstd, footer metadata): the bench and stability
//! results. Columns are f64, i64 or string; NaN is stored as null.

use arrow_array::{ArrayRef, Float64Array, Int64Array, RecordBatch, StringArray};
use arrow_schema::{DataType, Field, Schema};
use parquet::arrow::ArrowWriter;
use parquet::basic::{Compression, ZstdLevel};
use parquet::file::metadata::KeyValue;
use parquet::file::properties::WriterProperties;
use std::path::Path;
use std::sync::Arc;

/// One column of a table.
pub enum Column {
    F64(&'static str, Vec<f64>),
    I64(&'static str, Vec<i64>),
    Str(&'static str, Vec<String>),
}

/// Write the columns (equal lengths) to `path` with `meta` in the footer.
pub fn write_table(path: &Path, cols: Vec<Column>, meta: &[(&str, String)]) -> Result<(), String> {
    let mut fields = vec![];
    let mut arrays: Vec<ArrayRef> = vec![];
    for c in cols {
        match c {
            Column::F64(n, v) => {
                fields.push(Field::new(n, DataType::Float64, true));
                arrays.push(Arc::new(Float64Array::from(
                    v.into_iter()
                        .map(|x| x.is_finite().then_some(x))
                        .collect::<Vec<_>>(),
                )));
            }
            Column::I64(n, v) => {
                fields.push(Field::new(n, DataType::Int64, false));
                arrays.push(Arc::new(Int64Array::from(v)));
            }
            Column::Str(n, v) => {
                fields.push(Field::new(n, DataType::Utf8, false));
                arrays.push(Arc::new(StringArray::from(v)));
            }
        }
    }
    let schema = Arc::new(Schema::new(fields));
    let batch = RecordBatch::try_new(schema.clone(), arrays).map_err(|e| e.to_string())?;
    let mut kv = vec![KeyValue::new(
        "ehlmap_version".into(),
        env!("CARGO_PKG_VERSION").to_string(),
    )];
    kv.extend(
        meta.iter()
            .map(|(k, v)| KeyValue::new(k.to_string(), v.clone())),
    );
    let props = WriterProperties::builder()
        .set_compression(Compression::ZSTD(ZstdLevel::default()))
        .set_key_value_metadata(Some(kv))
        .build();
    let file = std::fs::File::create(path)
        .map_err(|e| format!("cannot create {}: {e}", path.display()))?;
    let mut w = ArrowWriter::try_new(file, schema, Some(props)).map_err(|e| e.to_string())?;
    w.write(&batch).map_err(|e| e.to_string())?;
    w.close().map_err(|e| e.to_string())?;
    Ok(())
}
