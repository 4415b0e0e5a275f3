//! Stability map: each method over an (M, L) grid, classified by the solve status (converged,
//! diverged, stalled, max-iterations) with its reason. The multigrid is run with and without
//! its fallback ladder, so the map shows where the default smoother alone fails and the
//! fallback is needed. Point contacts (one ellipticity D per map) are mapped with the multigrid
//! only, with and without its fallback. A converged cell that took more than [`SLOW_FACTOR`]
//! times the default multigrid's wall time on the same (M, L) (and more than [`SLOW_FLOOR_S`])
//! is classed `too-slow`: it converged, but no one would run it that way.

use crate::model::case::{LineCase, PointCase};
use crate::solve::line::{solve_line, LineSolveParams};
use crate::solve::params::Method;
use crate::solve::point::{solve_point, PointSolveParams};
use crate::solve::relax::Smoother;
use crate::solve::solution::Outputs;
use serde::Serialize;

/// A converged cell slower than this many times the default multigrid on its (M, L) is too slow.
pub const SLOW_FACTOR: f64 = 20.0;
/// ... and slower than this (s), so that timer noise on millisecond solves classes nothing.
pub const SLOW_FLOOR_S: f64 = 0.05;

/// One cell of the map.
#[derive(Clone, Debug, Serialize)]
pub struct Cell {
    /// The method's name ([`map_methods`], or "multigrid" / "multigrid-no-fallback" for point
    /// maps).
    pub method: String,
    /// Moes' load parameter M.
    pub m: f64,
    /// Moes' lubricant parameter L.
    pub l: f64,
    /// Grid points of the solve (per direction for point contacts).
    pub grid: usize,
    /// The solve's status ("converged", "diverged", "stalled", "max-iterations"), or "too-slow"
    /// after [`classify_slow`].
    pub status: String,
    /// The attempt of the fallback ladder (1-based) that produced the result.
    pub attempt: usize,
    /// The solve's reason (for a too-slow cell prefixed by its timing).
    pub reason: String,
    /// Wall time of the solve, all attempts included, s.
    pub wall_s: f64,
}

/// The methods of the map and their grids: multigrid (default, with fallback), without
/// fallback, and with the classic point smoother (no fallback) on `grid`; dense Newton and single-grid relaxation on 257 points (their cost).
pub fn map_methods(grid: usize) -> Vec<(&'static str, LineSolveParams)> {
    let mut mg = LineSolveParams::default();
    mg.mg.grid = grid;
    let mut bare = mg;
    bare.fallback = false;
    // Venner and Lubrecht's point Gauss-Seidel / distributive Jacobi smoother in the same cycle.
    let mut classic = bare;
    classic.mg.relax.smoother = Smoother::Point;
    let mut newton = LineSolveParams {
        method: Method::Newton,
        ..LineSolveParams::default()
    };
    newton.mg.grid = 257;
    let mut relax = LineSolveParams {
        method: Method::Relax,
        relax_max_sweeps: 5000,
        ..LineSolveParams::default()
    };
    relax.mg.grid = 257;
    vec![
        ("multigrid", mg),
        ("multigrid-no-fallback", bare),
        ("multigrid-classic-smoother", classic),
        ("newton-257", newton),
        ("relax-257", relax),
    ]
}

/// Run the line-contact map over `ms` x `ls`.
pub fn run(ms: &[f64], ls: &[f64], grid: usize, log: &mut dyn FnMut(&str)) -> Vec<Cell> {
    let mut cells = vec![];
    for (name, p) in map_methods(grid) {
        map_one(name, ms, ls, &mut cells, log, |m, l| {
            let case = LineCase::new(m, l).expect("map values are valid");
            let s = solve_line(&case, &p);
            (s.outputs, s.attempt)
        });
    }
    classify_slow(&mut cells);
    cells
}

/// Re-class converged cells that took more than [`SLOW_FACTOR`] times the `multigrid` cell of
/// the same (M, L) (and more than [`SLOW_FLOOR_S`]) as `too-slow`.
pub fn classify_slow(cells: &mut [Cell]) {
    let reference: Vec<(f64, f64, f64)> = cells
        .iter()
        .filter(|c| c.method == "multigrid" && c.status == "converged")
        .map(|c| (c.m, c.l, c.wall_s))
        .collect();
    for c in cells.iter_mut().filter(|c| c.status == "converged") {
        let Some(&(_, _, t_mg)) = reference.iter().find(|r| r.0 == c.m && r.1 == c.l) else {
            continue;
        };
        if c.wall_s > SLOW_FACTOR * t_mg && c.wall_s > SLOW_FLOOR_S {
            c.reason = format!(
                "converged in {:.2} s, {:.0} x the multigrid's {:.3} s: {}",
                c.wall_s,
                c.wall_s / t_mg,
                t_mg,
                c.reason
            );
            c.status = "too-slow".to_string();
        }
    }
}

/// Run the point-contact map (ellipticity `d`) over `ms` x `ls`: the multigrid with and without
/// its fallback ladder on `grid` points per direction.
pub fn run_point(
    ms: &[f64],
    ls: &[f64],
    d: f64,
    grid: usize,
    log: &mut dyn FnMut(&str),
) -> Vec<Cell> {
    let mut mg = PointSolveParams::default();
    mg.mg.grid = grid;
    let bare = PointSolveParams {
        fallback: false,
        ..mg
    };
    let mut cells = vec![];
    for (name, p) in [("multigrid", mg), ("multigrid-no-fallback", bare)] {
        map_one(name, ms, ls, &mut cells, log, |m, l| {
            let case = PointCase::new(m, l, d).expect("map values are valid");
            let s = solve_point(&case, &p);
            (s.outputs, s.attempt)
        });
    }
    classify_slow(&mut cells);
    cells
}

fn map_one(
    name: &str,
    ms: &[f64],
    ls: &[f64],
    cells: &mut Vec<Cell>,
    log: &mut dyn FnMut(&str),
    mut solve: impl FnMut(f64, f64) -> (Outputs, usize),
) {
    let mut ok = 0;
    for &m in ms {
        for &l in ls {
            let (o, attempt) = solve(m, l);
            ok += usize::from(o.status == crate::solve::Status::Converged);
            cells.push(Cell {
                method: name.to_string(),
                m,
                l,
                grid: o.grid,
                status: o.status.to_string(),
                attempt,
                reason: o.reason,
                wall_s: o.wall_s,
            });
        }
    }
    log(&format!("{name}: {ok}/{} converged", ms.len() * ls.len()));
}

/// Fraction converged per method.
pub fn summary(cells: &[Cell]) -> Vec<(String, usize, usize)> {
    let mut names: Vec<&str> = cells.iter().map(|c| c.method.as_str()).collect();
    names.dedup();
    names
        .into_iter()
        .map(|n| {
            let all: Vec<_> = cells.iter().filter(|c| c.method == n).collect();
            let ok = all.iter().filter(|c| c.status == "converged").count();
            (n.to_string(), ok, all.len())
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slow_converged_cells_are_too_slow() {
        let cell = |method: &str, status: &str, wall_s: f64| Cell {
            method: method.into(),
            m: 20.0,
            l: 10.0,
            grid: 257,
            status: status.into(),
            attempt: 1,
            reason: "r".into(),
            wall_s,
        };
        let mut cells = vec![
            cell("multigrid", "converged", 0.01),
            cell("relax-257", "converged", 0.5),
            cell("newton-257", "converged", 0.04),
            cell("other", "diverged", 9.0),
        ];
        classify_slow(&mut cells);
        let st: Vec<&str> = cells.iter().map(|c| c.status.as_str()).collect();
        // 50 x slower: too slow; 4 x (and under the floor): fine; failures keep their class.
        assert_eq!(st, ["converged", "too-slow", "converged", "diverged"]);
        assert!(cells[1].reason.starts_with("converged in 0.50 s, 50 x"));
    }

    #[test]
    fn point_map_classifies_each_cell() {
        let cells = run_point(&[20.0], &[0.0, 10.0], 0.5, 33, &mut |_| {});
        assert_eq!(cells.len(), 4);
        assert!(cells
            .iter()
            .all(|c| c.status == "converged" && c.grid == 33));
        let s = summary(&cells);
        assert_eq!(
            s,
            vec![
                ("multigrid".into(), 2, 2),
                ("multigrid-no-fallback".into(), 2, 2)
            ]
        );
    }
}
