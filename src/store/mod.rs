//! Storage: Parquet files written with arrow-rs (zstd), readable by polars and pyarrow.

pub mod fields;
pub mod profile;
pub mod results;
pub mod table;
