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
//! `valid` column is false. The columns are listed in [`columns`] and documented in
//! `outputs/README.md`.

use crate::store::table::write_batch_file;
use arrow_array::{ArrayRef, BooleanArray, Float64Array, Int64Array, RecordBatch, StringArray};
use arrow_schema::{DataType, Field, Schema};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Version of the row layout, stored in the footer as `ehlmap_schema`.
/// Schema 2 added `accuracy`, `model_used`, `level`, `error_estimate` (a float) and
/// `warm_start`, and renamed schema 1's boolean `error_estimate` to `half_grid_estimate`.
pub const SCHEMA_VERSION: &str = "2";

/// One case of a sweep: its inputs and every output of its solve.
///
/// Optional floats are null when they do not apply (`D`, `k`, `Y_min` for line contacts,
/// `spike_*` when there is no spike, `*_err` without an error estimate) or when the solver
/// produced a non-finite value (then `valid` is false).
#[derive(Clone, Debug, PartialEq)]
pub struct CaseRow {
    /// 16 hex digits: FNV-1a hash of the canonical case string (see `sweep::plan`).
    pub case_id: String,
    /// Name of the sweep (the spec's `name`).
    pub sweep: String,
    /// "line" or "point".
    pub contact: String,
    pub m: f64,
    pub l: f64,
    pub d: Option<f64>,
    pub k: Option<f64>,
    pub elasticity: String,
    pub viscosity: String,
    pub density: String,
    /// Roelands pressure-viscosity index (derived from `eta0` when the spec gives eta0).
    pub z: Option<f64>,
    pub eta0: Option<f64>,
    pub ph: Option<f64>,
    pub grid_requested: i64,
    pub cycle: String,
    pub max_cycles: i64,
    pub fallback: bool,
    pub tol_load: f64,
    pub tol_h: f64,
    /// The spec asked for a half-grid twin solve and its Richardson error columns.
    pub half_grid_estimate: bool,
    /// The spec's target relative accuracy of H_c and H_min, when it gave one.
    pub accuracy: Option<f64>,
    /// The model that answered the case (see `crate::strategy::select`): "full", "rigid", "isoviscous",
    /// "rigid-isoviscous", "closed-form" or "slender-line".
    pub model_used: String,
    /// Refinement level of the finest grid: log2 of its intervals over the first grid of the
    /// accuracy ladder (256 line intervals, 32 point intervals per direction); null without a
    /// grid (a closed-form answer).
    pub level: Option<i64>,
    /// Estimated relative error of H_c and H_min (the larger): the discretisation estimate
    /// plus, for a simplified model, the estimated effect of what it neglects.
    pub error_estimate: Option<f64>,
    /// Case id of the neighbour this case was warm-started from, when it was.
    pub warm_start: Option<String>,
    pub grid: Option<i64>,
    pub levels: Option<i64>,
    pub h_c: Option<f64>,
    pub h_c_pmax: Option<f64>,
    pub h_min: Option<f64>,
    pub x_min: Option<f64>,
    pub y_min: Option<f64>,
    pub p_max: Option<f64>,
    pub spike_x: Option<f64>,
    pub spike_p: Option<f64>,
    pub h0: Option<f64>,
    pub f: Option<f64>,
    pub load_error: Option<f64>,
    pub h_c_err: Option<f64>,
    pub h_min_err: Option<f64>,
    pub status: String,
    pub reason: String,
    pub attempt: Option<i64>,
    pub work_units: Option<f64>,
    pub wall_s: Option<f64>,
    pub valid: bool,
}

/// The column names in file order with their Arrow types and nullability.
pub fn columns() -> Vec<(&'static str, DataType, bool)> {
    use DataType::{Boolean as B, Float64 as F, Int64 as I, Utf8 as S};
    vec![
        ("case_id", S, false),
        ("sweep", S, false),
        ("contact", S, false),
        ("M", F, false),
        ("L", F, false),
        ("D", F, true),
        ("k", F, true),
        ("elasticity", S, false),
        ("viscosity", S, false),
        ("density", S, false),
        ("z", F, true),
        ("eta0", F, true),
        ("ph", F, true),
        ("grid_requested", I, false),
        ("cycle", S, false),
        ("max_cycles", I, false),
        ("fallback", B, false),
        ("tol_load", F, false),
        ("tol_h", F, false),
        ("half_grid_estimate", B, false),
        ("accuracy", F, true),
        ("model_used", S, false),
        ("level", I, true),
        ("error_estimate", F, true),
        ("warm_start", S, true),
        ("grid", I, true),
        ("levels", I, true),
        ("H_c", F, true),
        ("H_c_pmax", F, true),
        ("H_min", F, true),
        ("X_min", F, true),
        ("Y_min", F, true),
        ("P_max", F, true),
        ("spike_X", F, true),
        ("spike_P", F, true),
        ("H0", F, true),
        ("f", F, true),
        ("load_error", F, true),
        ("H_c_err", F, true),
        ("H_min_err", F, true),
        ("status", S, false),
        ("reason", S, false),
        ("attempt", I, true),
        ("work_units", F, true),
        ("wall_s", F, true),
        ("valid", B, false),
    ]
}

/// The `error_estimate` column from the two error columns: the larger, or the one given.
pub fn larger_error(h_c_err: Option<f64>, h_min_err: Option<f64>) -> Option<f64> {
    match (h_c_err, h_min_err) {
        (Some(a), Some(b)) => Some(a.max(b)),
        (a, b) => a.or(b),
    }
}

/// `Some(v)` for a finite `v`, else `None`; clears `valid` when a value had to be dropped.
pub fn finite(v: f64, valid: &mut bool) -> Option<f64> {
    if v.is_finite() {
        Some(v)
    } else {
        *valid = false;
        None
    }
}

fn schema() -> Arc<Schema> {
    Arc::new(Schema::new(
        columns()
            .into_iter()
            .map(|(n, t, null)| Field::new(n, t, null))
            .collect::<Vec<_>>(),
    ))
}

/// Replace any non-finite float that slipped into an optional column by null (and clear
/// `valid`); required floats that are non-finite make the row invalid too and are kept out of
/// the file by the check in [`to_batch`].
fn sanitise(r: &CaseRow) -> CaseRow {
    let mut r = r.clone();
    let mut valid = r.valid;
    for v in [
        &mut r.d,
        &mut r.k,
        &mut r.z,
        &mut r.eta0,
        &mut r.ph,
        &mut r.h_c,
        &mut r.h_c_pmax,
        &mut r.h_min,
        &mut r.x_min,
        &mut r.y_min,
        &mut r.p_max,
        &mut r.spike_x,
        &mut r.spike_p,
        &mut r.h0,
        &mut r.f,
        &mut r.load_error,
        &mut r.h_c_err,
        &mut r.h_min_err,
        &mut r.accuracy,
        &mut r.error_estimate,
        &mut r.work_units,
        &mut r.wall_s,
    ] {
        if let Some(x) = *v {
            if !x.is_finite() {
                *v = None;
                valid = false;
            }
        }
    }
    r.valid = valid;
    r
}

/// Rows to one Arrow record batch in the schema of [`columns`].
pub fn to_batch(rows: &[CaseRow]) -> Result<RecordBatch, String> {
    let rows: Vec<CaseRow> = rows.iter().map(sanitise).collect();
    for r in &rows {
        for (name, v) in [
            ("M", r.m),
            ("L", r.l),
            ("tol_load", r.tol_load),
            ("tol_h", r.tol_h),
        ] {
            if !v.is_finite() {
                return Err(format!("case {}: {name} = {v} is not finite", r.case_id));
            }
        }
    }
    let s = |f: fn(&CaseRow) -> &str| -> ArrayRef {
        Arc::new(StringArray::from(rows.iter().map(f).collect::<Vec<_>>()))
    };
    let f = |g: fn(&CaseRow) -> f64| -> ArrayRef {
        Arc::new(Float64Array::from(rows.iter().map(g).collect::<Vec<_>>()))
    };
    let o = |g: fn(&CaseRow) -> Option<f64>| -> ArrayRef {
        Arc::new(Float64Array::from(rows.iter().map(g).collect::<Vec<_>>()))
    };
    let i = |g: fn(&CaseRow) -> i64| -> ArrayRef {
        Arc::new(Int64Array::from(rows.iter().map(g).collect::<Vec<_>>()))
    };
    let oi = |g: fn(&CaseRow) -> Option<i64>| -> ArrayRef {
        Arc::new(Int64Array::from(rows.iter().map(g).collect::<Vec<_>>()))
    };
    let b = |g: fn(&CaseRow) -> bool| -> ArrayRef {
        Arc::new(BooleanArray::from(rows.iter().map(g).collect::<Vec<_>>()))
    };
    let cols: Vec<ArrayRef> = vec![
        s(|r| &r.case_id),
        s(|r| &r.sweep),
        s(|r| &r.contact),
        f(|r| r.m),
        f(|r| r.l),
        o(|r| r.d),
        o(|r| r.k),
        s(|r| &r.elasticity),
        s(|r| &r.viscosity),
        s(|r| &r.density),
        o(|r| r.z),
        o(|r| r.eta0),
        o(|r| r.ph),
        i(|r| r.grid_requested),
        s(|r| &r.cycle),
        i(|r| r.max_cycles),
        b(|r| r.fallback),
        f(|r| r.tol_load),
        f(|r| r.tol_h),
        b(|r| r.half_grid_estimate),
        o(|r| r.accuracy),
        s(|r| &r.model_used),
        oi(|r| r.level),
        o(|r| r.error_estimate),
        Arc::new(StringArray::from(
            rows.iter()
                .map(|r| r.warm_start.as_deref())
                .collect::<Vec<_>>(),
        )),
        oi(|r| r.grid),
        oi(|r| r.levels),
        o(|r| r.h_c),
        o(|r| r.h_c_pmax),
        o(|r| r.h_min),
        o(|r| r.x_min),
        o(|r| r.y_min),
        o(|r| r.p_max),
        o(|r| r.spike_x),
        o(|r| r.spike_p),
        o(|r| r.h0),
        o(|r| r.f),
        o(|r| r.load_error),
        o(|r| r.h_c_err),
        o(|r| r.h_min_err),
        s(|r| &r.status),
        s(|r| &r.reason),
        oi(|r| r.attempt),
        o(|r| r.work_units),
        o(|r| r.wall_s),
        b(|r| r.valid),
    ];
    RecordBatch::try_new(schema(), cols).map_err(|e| e.to_string())
}

/// The temporary file that [`write_part`] writes before renaming it to `path`: in the parent of
/// the dataset directory (same file system, so the rename is atomic), named
/// `.<dataset>.<part name>.tmp`. Keeping it out of the dataset directory matters: polars'
/// `scan_parquet(dir)` reads every file of a directory and fails on a foreign one.
pub fn temp_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let dir = path.parent();
    match dir.and_then(|d| Some((d.parent()?, d.file_name()?))) {
        Some((base, ds)) => base.join(format!(".{}.{name}.tmp", ds.to_string_lossy())),
        None => path.with_file_name(format!(".{name}.tmp")),
    }
}

/// Is `name` a part file of a dataset (and not a temporary or foreign file)?
pub fn is_part_name(name: &str) -> bool {
    name.starts_with("part-") && name.ends_with(".parquet")
}

/// Write `rows` to `path` atomically: to [`temp_path`] first (synced), then renamed over `path`.
/// `meta` goes to the footer key-value metadata after `ehlmap_version` and `ehlmap_schema`.
pub fn write_part(path: &Path, rows: &[CaseRow], meta: &[(String, String)]) -> Result<(), String> {
    let tmp = temp_path(path);
    let r = write_file(&tmp, rows, meta).and_then(|_| {
        std::fs::rename(&tmp, path)
            .map_err(|e| format!("cannot rename {} to {}: {e}", tmp.display(), path.display()))
    });
    if r.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    r
}

fn write_file(path: &Path, rows: &[CaseRow], meta: &[(String, String)]) -> Result<(), String> {
    let batch = to_batch(rows)?;
    let mut kv = vec![("ehlmap_schema".to_string(), SCHEMA_VERSION.to_string())];
    kv.extend(meta.iter().cloned());
    let mut file = write_batch_file(path, &batch, &kv)?;
    file.flush()
        .and_then(|_| file.sync_all())
        .map_err(|e| format!("cannot sync {}: {e}", path.display()))?;
    Ok(())
}

/// The part files of a dataset directory, sorted by name (empty when `dir` does not exist).
pub fn part_files(dir: &Path) -> Result<Vec<PathBuf>, String> {
    let rd = match std::fs::read_dir(dir) {
        Ok(rd) => rd,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(vec![]),
        Err(e) => return Err(format!("cannot read {}: {e}", dir.display())),
    };
    let mut v = vec![];
    for ent in rd {
        let ent = ent.map_err(|e| format!("cannot read {}: {e}", dir.display()))?;
        let name = ent.file_name().to_string_lossy().into_owned();
        if is_part_name(&name) && ent.file_type().map(|t| t.is_file()).unwrap_or(false) {
            v.push(ent.path());
        }
    }
    v.sort();
    Ok(v)
}

mod read;
pub use read::{read_dataset, read_part, stored_ids, Part};

#[cfg(test)]
mod tests {
    use super::*;

    pub(crate) fn row(id: &str) -> CaseRow {
        CaseRow {
            case_id: id.into(),
            sweep: "t".into(),
            contact: "line".into(),
            m: 20.0,
            l: 10.0,
            d: None,
            k: None,
            elasticity: "elastic".into(),
            viscosity: "barus".into(),
            density: "incompressible".into(),
            z: None,
            eta0: None,
            ph: None,
            grid_requested: 257,
            cycle: "v".into(),
            max_cycles: 60,
            fallback: true,
            tol_load: 1e-7,
            tol_h: 1e-6,
            half_grid_estimate: false,
            accuracy: Some(0.005),
            model_used: "full".into(),
            level: Some(0),
            error_estimate: Some(2e-3),
            warm_start: Some("00000000000000cc".into()),
            grid: Some(257),
            levels: Some(4),
            h_c: Some(5.2),
            h_c_pmax: Some(4.9),
            h_min: Some(3.9),
            x_min: Some(0.9),
            y_min: None,
            p_max: Some(1.1),
            spike_x: Some(0.8),
            spike_p: Some(0.7),
            h0: Some(-1.0),
            f: Some(1e-3),
            load_error: Some(1e-8),
            h_c_err: None,
            h_min_err: None,
            status: "converged".into(),
            reason: "ok".into(),
            attempt: Some(1),
            work_units: Some(50.0),
            wall_s: Some(0.01),
            valid: true,
        }
    }

    #[test]
    fn round_trip_and_nan_flagged() {
        let dir = std::env::temp_dir().join(format!("ehlmap-results-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let mut bad = row("00000000000000bb");
        bad.h_c = Some(f64::NAN);
        bad.f = Some(f64::INFINITY);
        bad.status = "diverged".into();
        let good = row("00000000000000aa");
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
        let mut dup = row("00000000000000bb");
        dup.h_c = Some(7.0);
        write_part(&dir.join("part-1of1-0003.parquet"), &[dup], &[]).unwrap();
        let rows = read_dataset(&dir).unwrap();
        assert_eq!(rows.len(), 2);
        assert_eq!(rows[1].h_c, Some(7.0));
        assert!(!temp_path(&path).exists());
        assert_eq!(
            temp_path(Path::new("out/smoke/part-1of2-0003.parquet")),
            Path::new("out/.smoke.part-1of2-0003.parquet.tmp")
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
}
