//! A solve's profile as Parquet: columns X, P (Hertzian units) and H (Moes units), one row per
//! node of the finest grid, zstd-compressed, with the case and the ehlmap version in the footer
//! key-value metadata.

use crate::solve::solution::Profile;
use crate::store::error::StoreError;
use crate::store::table::{write_table, Column};
use std::path::Path;

/// Write `profile` to `path` (created or replaced) with `meta` as footer key-value pairs.
pub fn write_profile(
    path: &Path,
    profile: &Profile,
    meta: &[(&str, String)],
) -> Result<(), StoreError> {
    let cols = vec![
        Column::F64("X", profile.x.clone()),
        Column::F64("P", profile.p.clone()),
        Column::F64("H", profile.h.clone()),
    ];
    write_table(path, cols, meta)
}
