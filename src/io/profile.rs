//! A solve's profile as Parquet: columns X, P (Hertzian units) and H (Moes units), one row per
//! node of the finest grid, zstd-compressed, with the case and the ehlmap version in the footer
//! key-value metadata.

use crate::solution::Profile;
use arrow_array::{ArrayRef, Float64Array, RecordBatch};
use arrow_schema::{DataType, Field, Schema};
use parquet::arrow::ArrowWriter;
use parquet::basic::{Compression, ZstdLevel};
use parquet::file::metadata::KeyValue;
use parquet::file::properties::WriterProperties;
use std::fs::File;
use std::path::Path;
use std::sync::Arc;

/// Write `profile` to `path` (created or replaced) with `meta` as footer key-value pairs.
pub fn write_profile(
    path: &Path,
    profile: &Profile,
    meta: &[(&str, String)],
) -> Result<(), String> {
    let schema = Arc::new(Schema::new(vec![
        Field::new("X", DataType::Float64, false),
        Field::new("P", DataType::Float64, false),
        Field::new("H", DataType::Float64, false),
    ]));
    let cols: Vec<ArrayRef> = vec![
        Arc::new(Float64Array::from(profile.x.clone())),
        Arc::new(Float64Array::from(profile.p.clone())),
        Arc::new(Float64Array::from(profile.h.clone())),
    ];
    let batch = RecordBatch::try_new(schema.clone(), cols).map_err(|e| e.to_string())?;
    let mut kv = vec![KeyValue::new(
        "ehlmap_version".to_string(),
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
    let file = File::create(path).map_err(|e| format!("cannot create {}: {e}", path.display()))?;
    let mut w = ArrowWriter::try_new(file, schema, Some(props)).map_err(|e| e.to_string())?;
    w.write(&batch).map_err(|e| e.to_string())?;
    w.close().map_err(|e| e.to_string())?;
    Ok(())
}
