//! Storage: Parquet files written with arrow-rs (zstd), readable by polars and pyarrow. Every
//! failure is a [`StoreError`] naming the file.

pub mod error;
pub mod fields;
pub mod profile;
pub mod results;
pub mod table;

pub use error::StoreError;
