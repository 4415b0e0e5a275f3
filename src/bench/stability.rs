//! Stability map: each method over an (M, L) grid, classified by the solve status (converged,
//! diverged, stalled, max-iterations) with its reason. The multigrid is run with and without
//! its fallback ladder, so the map shows where the default smoother alone fails and the
//! fallback is needed. Point contacts (one ellipticity D per map) are mapped with the multigrid
//! only, with and without its fallback.

use crate::params::{LineCase, PointCase};
use crate::solution::Outputs;
use crate::solver::line::{solve_line, LineSolveParams, Method};
use crate::solver::point::{solve_point, PointSolveParams};
use crate::solver::relax::Smoother;
use serde::Serialize;

/// One cell of the map.
#[derive(Clone, Debug, Serialize)]
pub struct Cell {
    pub method: String,
    pub m: f64,
    pub l: f64,
    pub grid: usize,
    pub status: String,
    pub attempt: usize,
    pub reason: String,
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
    cells
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
            ok += usize::from(o.status == crate::solver::Status::Converged);
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
