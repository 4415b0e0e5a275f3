//! The dataset a run writes into, checked against the spec before anything is solved: which
//! case ids it stores, and whether its rows were solved with the spec's settings
//! ([`crate::sweep::settings`]).
//!
//! The settings of a part file are its footer's `spec_settings`; a part written before the
//! footer held them (or re-saved without the footer) is judged by the input columns of its
//! rows. A part whose settings conflict with the spec's (a grid, a tolerance, a model ...)
//! makes the run refuse, naming the setting, the part and both values; with `--new-dataset`
//! such parts are moved, not deleted, to the sibling directory `<out>/<name>.old-<hash>/`
//! (`<hash>` the part's settings hash), which is itself a readable dataset, and the run starts
//! the dataset afresh with the parts of the spec's settings (a job array whose every task passes
//! `--new-dataset` therefore moves only the old parts, never a sibling task's new ones).

use crate::store::error::StoreError;
use crate::store::results::{part_files, read_part};
use crate::sweep::settings::{Difference, Settings};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// One part file of the dataset: its case ids and the settings of its rows.
#[derive(Clone, Debug)]
pub struct StoredPart {
    /// The file.
    pub path: PathBuf,
    /// The case ids of its rows.
    pub ids: Vec<String>,
    /// The footer's settings, else the distinct settings of its rows.
    pub settings: Vec<Settings>,
}

/// A part whose rows conflict with the spec's settings.
#[derive(Clone, Debug)]
pub struct Conflict {
    /// Index of the part in the scan.
    pub part: usize,
    /// The settings that differ (`ours`: the spec's value, `theirs`: the part's).
    pub differences: Vec<Difference>,
    /// The part's settings hash (names the directory it is moved to).
    pub hash: String,
}

/// Read every part file of `dir` (none when it does not exist).
pub fn scan(dir: &Path) -> Result<Vec<StoredPart>, StoreError> {
    let mut parts = vec![];
    for path in part_files(dir)? {
        let part = read_part(&path)?;
        let footer = part
            .meta
            .get("spec_settings")
            .and_then(|s| Settings::parse(s));
        let settings = match footer {
            Some(s) => vec![s],
            None => part
                .rows
                .iter()
                .map(Settings::of_row)
                .collect::<BTreeSet<_>>()
                .into_iter()
                .collect(),
        };
        parts.push(StoredPart {
            path,
            ids: part.rows.into_iter().map(|r| r.case_id).collect(),
            settings,
        });
    }
    Ok(parts)
}

/// The parts of `parts` whose settings conflict with `spec`'s.
pub fn conflicts(parts: &[StoredPart], spec: &Settings) -> Vec<Conflict> {
    let mut v = vec![];
    for (i, p) in parts.iter().enumerate() {
        for s in &p.settings {
            let differences = spec.conflicts(s);
            if !differences.is_empty() {
                v.push(Conflict {
                    part: i,
                    differences,
                    hash: s.hash(),
                });
                break;
            }
        }
    }
    v
}

fn file_name(p: &Path) -> String {
    p.file_name()
        .map_or(String::new(), |n| n.to_string_lossy().into_owned())
}

/// The refusal of a run into `dir` whose spec `spec_file` conflicts with stored parts.
pub fn refusal(dir: &Path, spec_file: &str, parts: &[StoredPart], c: &[Conflict]) -> String {
    let first = &c[0];
    let diffs: Vec<String> = first
        .differences
        .iter()
        .map(|d| {
            format!(
                "{} = {} in {}, {} in the spec",
                d.key,
                d.theirs,
                file_name(&parts[first.part].path),
                d.ours
            )
        })
        .collect();
    let more = match c.len() {
        1 => String::new(),
        n => format!(" (and {} more part files)", n - 1),
    };
    format!(
        "{} holds rows of other settings than {spec_file}: {}{more}; nothing was run. \
         --new-dataset moves those parts to {} and starts the dataset afresh; --out DIR \
         writes elsewhere",
        dir.display(),
        diffs.join(", "),
        old_dir(dir, &first.hash).display()
    )
}

/// `<out>/<name>.old-<hash>`: where parts of the settings `hash` are moved.
pub fn old_dir(dir: &Path, hash: &str) -> PathBuf {
    let name = file_name(dir);
    dir.with_file_name(format!("{name}.old-{hash}"))
}

/// Move the conflicting parts out of `dir` (module docs); returns (from, to) per file. A name
/// taken in the destination gets a `.N` before `.parquet`, so nothing is overwritten.
pub fn move_aside(
    dir: &Path,
    parts: &[StoredPart],
    c: &[Conflict],
) -> Result<Vec<(PathBuf, PathBuf)>, String> {
    let mut moved = vec![];
    for conflict in c {
        let from = &parts[conflict.part].path;
        let to_dir = old_dir(dir, &conflict.hash);
        std::fs::create_dir_all(&to_dir)
            .map_err(|e| format!("cannot create {}: {e}", to_dir.display()))?;
        let name = file_name(from);
        let stem = name.strip_suffix(".parquet").unwrap_or(&name).to_string();
        let mut to = to_dir.join(&name);
        let mut n = 1;
        while to.exists() {
            to = to_dir.join(format!("{stem}.{n}.parquet"));
            n += 1;
        }
        match std::fs::rename(from, &to) {
            Ok(()) => moved.push((from.clone(), to)),
            // Moved meanwhile by another task of the same job array.
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
            Err(e) => {
                return Err(format!(
                    "cannot move {} to {}: {e}",
                    from.display(),
                    to.display()
                ))
            }
        }
    }
    Ok(moved)
}

/// The case ids of the parts not in `c` (the rows a run keeps).
pub fn kept_ids(parts: &[StoredPart], c: &[Conflict]) -> std::collections::HashSet<String> {
    let gone: BTreeSet<usize> = c.iter().map(|c| c.part).collect();
    parts
        .iter()
        .enumerate()
        .filter(|(i, _)| !gone.contains(i))
        .flat_map(|(_, p)| p.ids.iter().cloned())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The committed datasets predate the footer's settings: their rows' settings are those of
    /// the spec text their footer holds, and a changed grid conflicts with them.
    #[test]
    fn committed_datasets_agree_with_their_own_specs() {
        let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
        for name in ["smoke-line", "point-257"] {
            let parts = scan(&data.join(name)).unwrap();
            assert_eq!(parts.len(), 1);
            assert_eq!(parts[0].settings.len(), 1, "{name}: one setting per part");
            let meta = read_part(&parts[0].path).unwrap().meta;
            assert!(!meta.contains_key("spec_settings"));
            let text = &meta["spec"];
            let mut spec = crate::sweep::spec::parse("s.toml", text, name).unwrap();
            // Written before the stopping rule was a setting: converged to the tolerances.
            for c in &mut spec.contacts {
                c.numerics.converge = crate::solve::params::Converge::Tight;
            }
            // Written before the far field existed: today's default conflicts with the rows' P = 0
            // on the boundary.
            if spec.has(crate::sweep::spec::Contact::Point) {
                let c = conflicts(&parts, &Settings::of_spec(&spec));
                assert_eq!(c.len(), 1, "{name}");
                let msg = refusal(Path::new("out/x"), "x.toml", &parts, &c);
                assert!(
                    msg.contains("far_field = false in part-1of1-0001.parquet, true in the spec"),
                    "{msg}"
                );
                for c in &mut spec.contacts {
                    c.numerics.far_field = false;
                }
            }
            assert!(
                conflicts(&parts, &Settings::of_spec(&spec)).is_empty(),
                "{name}"
            );
            let grid = spec.contacts[0].numerics.grid;
            let mut other = spec.clone();
            other.contacts[0].numerics.grid = 2 * grid - 1;
            let c = conflicts(&parts, &Settings::of_spec(&other));
            assert_eq!(c.len(), 1);
            let msg = refusal(Path::new("out/x"), "x.toml", &parts, &c);
            let want = format!(
                "grid = {grid} in part-1of1-0001.parquet, {} in the spec",
                2 * grid - 1
            );
            assert!(msg.contains(&want), "{msg}");
            assert_eq!(kept_ids(&parts, &c).len(), 0);
            assert_eq!(kept_ids(&parts, &[]).len(), parts[0].ids.len());
        }
    }

    #[test]
    fn old_parts_go_to_a_sibling_directory() {
        assert_eq!(
            old_dir(Path::new("out/smoke"), "00aa"),
            Path::new("out/smoke.old-00aa")
        );
    }
}
