//! The memory a solve needs, estimated from its grid before anything is allocated, and checked
//! against the memory there is: `MemAvailable` of /proc/meminfo, the cgroup's limit (Slurm,
//! containers) and `EHLMAP_MAX_MEMORY` (e.g. `8G`, `512M`, bytes), whichever is smallest. A grid
//! whose estimate exceeds it is bad input (exit 2) naming the grid, instead of an abort when the
//! memory runs out.
//!
//! Per finest-grid node, measured with `/usr/bin/time` (peak resident set, multigrid and
//! relaxation; docs/cli.md): line contacts about 630 bytes (65537 points 45 MB, 262145 points
//! 166 MB), point contacts about 205 bytes (513^2 nodes 60 MB, 1025^2 nodes 214 MB, with the
//! Anderson step's three vectors); the dense Newton baseline about
//! 16 N^2 bytes for N unknowns (line 4097 points: 269 MB). The estimate adds a margin over these
//! and rounds the grid up as the solver does (2^k intervals).

use crate::cli::error::{input, CliError};
use ehlmap::model::case::Contact;

/// Bytes per node of a line solve (measured about 630).
const LINE_BYTES_PER_NODE: u64 = 800;
/// Bytes per node of a point solve (measured about 205).
const POINT_BYTES_PER_NODE: u64 = 220;
/// Bytes per Jacobian entry of the dense Newton baseline (measured about 16).
const NEWTON_BYTES_PER_ENTRY: u64 = 20;
/// The process without its grids.
const BASE_BYTES: u64 = 32 << 20;

/// The solver whose memory is estimated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Solver {
    /// Full multigrid, or single-grid relaxation (the same arrays).
    Multigrid,
    /// The dense Newton baseline.
    Newton,
}

/// The finest grid the solver uses for `grid`: 2^k intervals plus one.
pub fn rounded_grid(grid: usize) -> usize {
    (grid.max(2) - 1).next_power_of_two() + 1
}

/// The estimated peak memory (bytes) of one solve of `contact` on `grid` (points, per
/// direction for point contacts).
pub fn estimate(contact: Contact, grid: usize, solver: Solver) -> u64 {
    let g = rounded_grid(grid) as u64;
    let nodes = match contact {
        Contact::Line => g,
        Contact::Point => g.saturating_mul(g),
    };
    let grid_bytes = match (solver, contact) {
        (Solver::Newton, _) => nodes.saturating_mul(nodes) * NEWTON_BYTES_PER_ENTRY,
        (Solver::Multigrid, Contact::Line) => nodes * LINE_BYTES_PER_NODE,
        (Solver::Multigrid, Contact::Point) => nodes * POINT_BYTES_PER_NODE,
    };
    grid_bytes.saturating_add(BASE_BYTES)
}

/// The memory this process may use (bytes) and where that figure comes from, when known.
pub fn available() -> Result<Option<(u64, String)>, CliError> {
    let mut best: Option<(u64, String)> = None;
    let mut take = |v: u64, from: String| {
        if best.as_ref().is_none_or(|b| v < b.0) {
            best = Some((v, from));
        }
    };
    if let Some(v) = meminfo_available() {
        take(v, "available memory (MemAvailable)".into());
    }
    if let Some(v) = cgroup_limit() {
        take(v, "the cgroup's memory limit".into());
    }
    if let Ok(s) = std::env::var("EHLMAP_MAX_MEMORY") {
        let v = parse_bytes(&s).ok_or_else(|| {
            input(format!(
                "EHLMAP_MAX_MEMORY={s} is invalid: give bytes, or a number with K, M, G or T, e.g. 8G"
            ))
        })?;
        take(v, format!("EHLMAP_MAX_MEMORY={s}"));
    }
    Ok(best)
}

/// Refuse (exit 2, naming `what`) a grid whose `copies` simultaneous solves need more memory
/// than there is. `what` names the input that set the grid, e.g. `--grid 1048577` or
/// `grid = 2049`; `why` says what runs (for the message), e.g. `a line solve`.
pub fn check_memory(what: &str, why: &str, need: u64) -> Result<(), CliError> {
    let Some((have, from)) = available()? else {
        return Ok(());
    };
    if need > have {
        return Err(input(format!(
            "{what}: {why} would need about {}, more than the {} of {from}; give a smaller grid",
            human(need),
            human(have)
        )));
    }
    Ok(())
}

/// Bytes as `1.2 GB`, `350 MB`.
pub fn human(b: u64) -> String {
    let b = b as f64;
    if b >= 1e9 {
        format!("{:.1} GB", b / 1e9)
    } else {
        format!("{:.0} MB", (b / 1e6).max(1.0))
    }
}

/// `8G`, `512M`, `100K`, `1T` (powers of 1024) or plain bytes.
pub fn parse_bytes(s: &str) -> Option<u64> {
    let t = s.trim();
    let (num, mult) = match t.chars().last()?.to_ascii_uppercase() {
        'K' => (&t[..t.len() - 1], 1u64 << 10),
        'M' => (&t[..t.len() - 1], 1 << 20),
        'G' => (&t[..t.len() - 1], 1 << 30),
        'T' => (&t[..t.len() - 1], 1 << 40),
        _ => (t, 1),
    };
    let x: f64 = num.trim().parse().ok()?;
    let bytes = x * mult as f64;
    (1.0..1.8e19).contains(&bytes).then_some(bytes as u64)
}

/// `MemAvailable` of /proc/meminfo in bytes (Linux).
fn meminfo_available() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// The cgroup v2 (`memory.max` less `memory.current`) or v1 limit of this process, in bytes.
fn cgroup_limit() -> Option<u64> {
    let read = |p: &str| -> Option<u64> { std::fs::read_to_string(p).ok()?.trim().parse().ok() };
    if let Some(max) = read("/sys/fs/cgroup/memory.max") {
        let used = read("/sys/fs/cgroup/memory.current").unwrap_or(0);
        return Some(max.saturating_sub(used));
    }
    let limit = read("/sys/fs/cgroup/memory/memory.limit_in_bytes")?;
    // v1 reports "no limit" as a huge number
    (limit < (1 << 60)).then(|| {
        let used = read("/sys/fs/cgroup/memory/memory.usage_in_bytes").unwrap_or(0);
        limit.saturating_sub(used)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn estimates_cover_the_measurements() {
        // measured peaks (resident set): line 262145 points 166 MB, point 513^2 50 MB,
        // Newton line 4097 points 269 MB
        let line = estimate(Contact::Line, 262145, Solver::Multigrid);
        assert!(line > 170_000_000 && line < 300_000_000, "{line}");
        let point = estimate(Contact::Point, 513, Solver::Multigrid);
        assert!(point > 51_000_000 && point < 100_000_000, "{point}");
        let newton = estimate(Contact::Line, 4097, Solver::Newton);
        assert!(newton > 275_000_000 && newton < 400_000_000, "{newton}");
        // the grid is rounded up as the solver does
        assert_eq!(rounded_grid(600_000), 1_048_577);
        assert_eq!(rounded_grid(2049), 2049);
    }

    #[test]
    fn byte_sizes_parse() {
        assert_eq!(parse_bytes("8G"), Some(8 << 30));
        assert_eq!(parse_bytes("512m"), Some(512 << 20));
        assert_eq!(parse_bytes("1000"), Some(1000));
        assert_eq!(parse_bytes("0.5K"), Some(512));
        for bad in ["", "G", "-1G", "0", "0.1", "abc", "1e30T", "NaN"] {
            assert_eq!(parse_bytes(bad), None, "{bad}");
        }
    }
}
