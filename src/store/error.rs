//! The storage layer's error: every failure of writing or reading a Parquet file, naming the file
//! (or, for a row that cannot be written, the case and the column) and the cause.

use std::path::PathBuf;

/// A failure of [`crate::store`]: a file operation, the Parquet or Arrow library, or data that
/// does not fit the file layout. The message names the file (or case) and the column involved.
#[derive(Debug, thiserror::Error)]
pub enum StoreError {
    /// A file-system operation (`op`: "create", "open", "read", "sync") on `path` failed.
    #[error("cannot {op} {}: {source}", path.display())]
    Io {
        /// What was attempted, as a verb.
        op: &'static str,
        /// The file or directory.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// Renaming a written temporary file over its destination failed.
    #[error("cannot rename {} to {}: {source}", from.display(), to.display())]
    Rename {
        /// The temporary file.
        from: PathBuf,
        /// The destination.
        to: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The Parquet library failed on `path`.
    #[error("{}: {source}", path.display())]
    Parquet {
        /// The file being written or read.
        path: PathBuf,
        /// The Parquet library's error.
        source: parquet::errors::ParquetError,
    },
    /// Arrow failed on `path` (decoding a record batch, or building one to write there).
    #[error("{}: {source}", path.display())]
    Arrow {
        /// The file being written or read.
        path: PathBuf,
        /// The Arrow library's error.
        source: arrow_schema::ArrowError,
    },
    /// Columns that do not form a record batch (built in memory, before any file).
    #[error("{0}")]
    Batch(#[source] arrow_schema::ArrowError),
    /// A file lacks a column its schema requires: a Parquet file of another layout.
    #[error("{}: not an ehlmap dataset: missing column `{column}`", path.display())]
    NoColumn {
        /// The file.
        path: PathBuf,
        /// The missing column.
        column: String,
    },
    /// A column of a file has a type the layout's cannot be read from.
    #[error(
        "{}: not an ehlmap dataset: column `{column}` is {found}, expected {expected}",
        path.display()
    )]
    ColumnType {
        /// The file.
        path: PathBuf,
        /// The column.
        column: String,
        /// Its type in the file.
        found: String,
        /// The layout's type.
        expected: String,
    },
    /// A Parquet file compressed with a codec this build does not decompress.
    #[error(
        "{}: compressed with {codec}, which ehlmap does not read (it reads uncompressed, zstd, \
         snappy, gzip and lz4 Parquet): re-save it with one of those",
        path.display()
    )]
    Compression {
        /// The file.
        path: PathBuf,
        /// The codec, as the Parquet library names it.
        codec: String,
    },
    /// A value of a named column (a contact, status, model ...) is not one of the known names.
    #[error("{}: column `{column}`: value {value:?} not understood: {reason}", path.display())]
    BadValue {
        /// The file.
        path: PathBuf,
        /// The column.
        column: &'static str,
        /// The stored value.
        value: String,
        /// Why it is not understood (the known names).
        reason: String,
    },
    /// A required float of a row to write is NaN or infinite (the row would not be storable
    /// without a null in a non-null column).
    #[error("case {case_id}: {column} = {value} is not finite")]
    NotFinite {
        /// The row's case id.
        case_id: String,
        /// The column.
        column: &'static str,
        /// The offending value.
        value: f64,
    },
    /// A point solve's fields whose P or H do not hold one value per node.
    #[error(
        "fields of {nx} x {ny} nodes need {} values of P and H (got {p} and {h})",
        nx * ny
    )]
    FieldsShape {
        /// Nodes along X.
        nx: usize,
        /// Nodes along Y.
        ny: usize,
        /// Values of P given.
        p: usize,
        /// Values of H given.
        h: usize,
    },
}
