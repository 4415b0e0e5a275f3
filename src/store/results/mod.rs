//! Sweep datasets: one Parquet row per case, written crash-safely, read back deduplicated.
//!
//! A dataset is a directory `<out>/<sweep>/` of files `part-<shard>-<run>.parquet`
//! (e.g. `part-1of2-0003.parquet`: shard 1 of 2, third run of that shard). Each run of
//! `ehlmap sweep` owns exactly one file and rewrites it, with all the rows of that run so far,
//! after every batch: the rows go to the temporary file `<out>/.<sweep>.part-<shard>-<run>.parquet.tmp`
//! (next to the dataset directory, on the same file system), which is synced and then renamed
//! over the part file (atomic on POSIX). A reader therefore only ever sees complete files, even
//! `polars.scan_parquet(dir)`, which reads every file of the directory, and a `kill -9` loses at
//! most the rows that were not yet flushed. [`read_dataset`] also ignores every name in the
//! directory that does not match `part-*.parquet`.
//!
//! No NaN or infinity reaches a file: a non-finite output is written as null and the row's
//! `valid` column is false. The columns are listed once, in [`columns::COLUMNS`], and documented
//! in `docs/dataset-schema.md`.
//!
//! Files, one concept each (none imports this module):
//! * [`row`]: the row type [`CaseRow`] and its status [`RowStatus`];
//! * [`columns`]: the file layout, which drives writer, reader and schema;
//! * [`mod@write`]: rows to a part file; [`read`]: part files back to rows;
//! * [`files`]: part and temporary file names.

pub mod columns;
pub mod files;
pub mod read;
pub mod row;
pub mod write;

pub use columns::{schema, SCHEMA_VERSION};
pub use files::{is_dataset_file, is_part_name, part_files, temp_path};
pub use read::{read_dataset, read_part, stored_ids, Part};
pub use row::{finite, larger_error, CaseRow, RowStatus};
pub use write::{to_batch, write_part};
