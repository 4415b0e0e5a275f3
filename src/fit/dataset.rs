//! Reading sweep datasets for the fit: every part file of each directory (arrow-rs reader),
//! deduplicated by case id across directories, line-contact converged valid rows only; failed
//! rows and duplicates are counted for the report.

use crate::fit::report::{FitInput, FitPoint};
use crate::io::results::read_dataset;
use std::collections::BTreeMap;
use std::path::PathBuf;

/// Load the fit input from one or more dataset directories.
pub fn load_fit_input(dirs: &[PathBuf]) -> Result<FitInput, String> {
    let mut by_id = BTreeMap::new();
    let mut duplicates = 0;
    for dir in dirs {
        if !dir.is_dir() {
            return Err(format!("{}: not a dataset directory", dir.display()));
        }
        for row in read_dataset(dir)? {
            if by_id.contains_key(&row.case_id) {
                duplicates += 1;
            } else {
                by_id.insert(row.case_id.clone(), row);
            }
        }
    }
    let mut input = FitInput {
        datasets: dirs.iter().map(|d| d.display().to_string()).collect(),
        duplicates,
        ..FitInput::default()
    };
    for row in by_id.values() {
        match (
            row.contact.as_str(),
            row.status.as_str(),
            row.valid,
            row.h_c,
            row.h_min,
        ) {
            ("line", "converged", true, Some(h_c), Some(h_min)) if h_c > 0.0 && h_min > 0.0 => {
                input.points.push(FitPoint {
                    m: row.m,
                    l: row.l,
                    h_c,
                    h_min,
                })
            }
            _ => input.failed += 1,
        }
    }
    Ok(input)
}
