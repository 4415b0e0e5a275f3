//! Reading sweep datasets back: one part file ([`read_part`]) or a whole directory deduplicated
//! by case id ([`read_dataset`]). Files of schema 1 (before `model_used`, `level`,
//! `error_estimate` and `accuracy`; their boolean `error_estimate` is today's
//! `half_grid_estimate`) are read too, with `model_used = "full"`.

use super::{larger_error, part_files, CaseRow};
use arrow_array::{Array, BooleanArray, Float64Array, Int64Array, RecordBatch, StringArray};
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
use std::collections::{BTreeMap, HashSet};
use std::fs::File;
use std::path::{Path, PathBuf};

/// One part file read back: its rows and its footer key-value metadata.
#[derive(Clone, Debug)]
pub struct Part {
    pub path: PathBuf,
    pub rows: Vec<CaseRow>,
    pub meta: BTreeMap<String, String>,
}

fn col<'a, T: 'static>(b: &'a RecordBatch, name: &str, path: &Path) -> Result<&'a T, String> {
    b.column_by_name(name)
        .ok_or_else(|| format!("{}: no column `{name}`", path.display()))?
        .as_any()
        .downcast_ref::<T>()
        .ok_or_else(|| format!("{}: column `{name}` has an unexpected type", path.display()))
}

/// Read one part file.
pub fn read_part(path: &Path) -> Result<Part, String> {
    let err = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    let file = File::open(path).map_err(|e| err(&e))?;
    let builder = ParquetRecordBatchReaderBuilder::try_new(file).map_err(|e| err(&e))?;
    let meta: BTreeMap<String, String> = builder
        .metadata()
        .file_metadata()
        .key_value_metadata()
        .map(|kv| {
            kv.iter()
                .map(|k| (k.key.clone(), k.value.clone().unwrap_or_default()))
                .collect()
        })
        .unwrap_or_default();
    let mut rows = vec![];
    for batch in builder.build().map_err(|e| err(&e))? {
        let b = batch.map_err(|e| err(&e))?;
        let s = |n: &str| col::<StringArray>(&b, n, path);
        let f = |n: &str| col::<Float64Array>(&b, n, path);
        let i = |n: &str| col::<Int64Array>(&b, n, path);
        let bo = |n: &str| col::<BooleanArray>(&b, n, path);
        let of = |a: &Float64Array, j: usize| (!a.is_null(j)).then(|| a.value(j));
        let oi = |a: &Int64Array, j: usize| (!a.is_null(j)).then(|| a.value(j));
        let (case_id, sweep, contact) = (s("case_id")?, s("sweep")?, s("contact")?);
        let (m, l, d, k) = (f("M")?, f("L")?, f("D")?, f("k")?);
        let (elasticity, viscosity, density) = (s("elasticity")?, s("viscosity")?, s("density")?);
        let (z, eta0, ph) = (f("z")?, f("eta0")?, f("ph")?);
        let (grid_requested, cycle, max_cycles) =
            (i("grid_requested")?, s("cycle")?, i("max_cycles")?);
        let (fallback, tol_load, tol_h) = (bo("fallback")?, f("tol_load")?, f("tol_h")?);
        // Schema 1 had a boolean `error_estimate` and none of the selection columns.
        let v1 = b
            .column_by_name("error_estimate")
            .is_some_and(|c| c.as_any().is::<BooleanArray>());
        let half = bo(if v1 {
            "error_estimate"
        } else {
            "half_grid_estimate"
        })?;
        let opt_f = |n: &str| if v1 { Ok(None) } else { f(n).map(Some) };
        let (accuracy, error_estimate) = (opt_f("accuracy")?, opt_f("error_estimate")?);
        let (model_used, warm_start, level) = if v1 {
            (None, None, None)
        } else {
            (
                Some(s("model_used")?),
                Some(s("warm_start")?),
                Some(i("level")?),
            )
        };
        let (grid, levels) = (i("grid")?, i("levels")?);
        let (h_c, h_c_pmax, h_min, x_min, y_min, p_max) = (
            f("H_c")?,
            f("H_c_pmax")?,
            f("H_min")?,
            f("X_min")?,
            f("Y_min")?,
            f("P_max")?,
        );
        let (spike_x, spike_p, h0, ff, load_error) = (
            f("spike_X")?,
            f("spike_P")?,
            f("H0")?,
            f("f")?,
            f("load_error")?,
        );
        let (h_c_err, h_min_err) = (f("H_c_err")?, f("H_min_err")?);
        let (status, reason, attempt) = (s("status")?, s("reason")?, i("attempt")?);
        let (work_units, wall_s, valid) = (f("work_units")?, f("wall_s")?, bo("valid")?);
        for j in 0..b.num_rows() {
            rows.push(CaseRow {
                case_id: case_id.value(j).to_string(),
                sweep: sweep.value(j).to_string(),
                contact: contact.value(j).to_string(),
                m: m.value(j),
                l: l.value(j),
                d: of(d, j),
                k: of(k, j),
                elasticity: elasticity.value(j).to_string(),
                viscosity: viscosity.value(j).to_string(),
                density: density.value(j).to_string(),
                z: of(z, j),
                eta0: of(eta0, j),
                ph: of(ph, j),
                grid_requested: grid_requested.value(j),
                cycle: cycle.value(j).to_string(),
                max_cycles: max_cycles.value(j),
                fallback: fallback.value(j),
                tol_load: tol_load.value(j),
                tol_h: tol_h.value(j),
                half_grid_estimate: half.value(j),
                accuracy: accuracy.and_then(|a| of(a, j)),
                model_used: model_used.map_or("full".to_string(), |a| a.value(j).to_string()),
                level: level.and_then(|a| oi(a, j)),
                error_estimate: match error_estimate {
                    Some(a) => of(a, j),
                    None => larger_error(of(h_c_err, j), of(h_min_err, j)),
                },
                warm_start: warm_start
                    .and_then(|a| (!a.is_null(j)).then(|| a.value(j).to_string())),
                grid: oi(grid, j),
                levels: oi(levels, j),
                h_c: of(h_c, j),
                h_c_pmax: of(h_c_pmax, j),
                h_min: of(h_min, j),
                x_min: of(x_min, j),
                y_min: of(y_min, j),
                p_max: of(p_max, j),
                spike_x: of(spike_x, j),
                spike_p: of(spike_p, j),
                h0: of(h0, j),
                f: of(ff, j),
                load_error: of(load_error, j),
                h_c_err: of(h_c_err, j),
                h_min_err: of(h_min_err, j),
                status: status.value(j).to_string(),
                reason: reason.value(j).to_string(),
                attempt: oi(attempt, j),
                work_units: of(work_units, j),
                wall_s: of(wall_s, j),
                valid: valid.value(j),
            });
        }
    }
    Ok(Part {
        path: path.to_path_buf(),
        rows,
        meta,
    })
}

/// Is `a` a better record of the same case than `b` (converged and valid beats the rest)?
fn better(a: &CaseRow, b: &CaseRow) -> bool {
    let score = |r: &CaseRow| (r.status == "converged") as u8 * 2 + r.valid as u8;
    score(a) > score(b)
}

/// All rows of a dataset directory, one per case id (sorted by case id). When a case is stored
/// more than once (an overlap of reruns), a converged valid row is preferred, then the first
/// one in file-name order. Temporary files are ignored; a part file that cannot be read is an
/// error naming it. A directory that does not exist is an empty dataset.
pub fn read_dataset(dir: &Path) -> Result<Vec<CaseRow>, String> {
    let mut by_id: BTreeMap<String, CaseRow> = BTreeMap::new();
    for path in part_files(dir)? {
        for r in read_part(&path)?.rows {
            match by_id.get(&r.case_id) {
                Some(old) if !better(&r, old) => {}
                _ => {
                    by_id.insert(r.case_id.clone(), r);
                }
            }
        }
    }
    Ok(by_id.into_values().collect())
}

/// The case ids stored in a dataset directory.
pub fn stored_ids(dir: &Path) -> Result<HashSet<String>, String> {
    let mut ids = HashSet::new();
    for path in part_files(dir)? {
        for r in read_part(&path)?.rows {
            ids.insert(r.case_id);
        }
    }
    Ok(ids)
}
