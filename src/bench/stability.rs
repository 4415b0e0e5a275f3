//! Stability map: each method over an (M, L) grid, classified by the solve status (converged,
//! diverged, stalled, max-iterations) with its reason. The multigrid is run with and without
//! its fallback ladder, so the map shows where the default smoother alone fails and the
//! fallback is needed.

use crate::params::LineCase;
use crate::solver::line::{solve_line, LineSolveParams, Method};
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

/// The methods of the map and their grids: multigrid (default, with fallback) and without
/// fallback on `grid`; dense Newton and single-grid relaxation on 257 points (their cost).
pub fn map_methods(grid: usize) -> Vec<(&'static str, LineSolveParams)> {
    let mut mg = LineSolveParams::default();
    mg.mg.grid = grid;
    let mut bare = mg;
    bare.fallback = false;
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
        ("newton-257", newton),
        ("relax-257", relax),
    ]
}

/// Run the map over `ms` x `ls`.
pub fn run(ms: &[f64], ls: &[f64], grid: usize, log: &mut dyn FnMut(&str)) -> Vec<Cell> {
    let mut cells = vec![];
    for (name, p) in map_methods(grid) {
        let mut ok = 0;
        for &m in ms {
            for &l in ls {
                let case = LineCase::new(m, l).expect("map values are valid");
                let s = solve_line(&case, &p);
                ok += usize::from(s.outputs.status == crate::solver::Status::Converged);
                cells.push(Cell {
                    method: name.to_string(),
                    m,
                    l,
                    grid: s.outputs.grid,
                    status: s.outputs.status.to_string(),
                    attempt: s.attempt,
                    reason: s.outputs.reason,
                    wall_s: s.outputs.wall_s,
                });
            }
        }
        log(&format!("{name}: {ok}/{} converged", ms.len() * ls.len()));
    }
    cells
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
