//! Speed-accuracy benchmark: methods x reference cases (line and point) x grid ladder. Point
//! grids count points per direction; dense Newton runs on point grids up to 33^2 only, the
//! smoother alone up to 65^2.

use crate::model::case::{LineCase, PointCase};
use crate::solve::line::{solve_line, LineSolveParams};
use crate::solve::params::Method;
use crate::solve::params::{Converge, CycleType};
use crate::solve::point::{solve_point, PointSolveParams};
use crate::solve::solution::Outputs;
use crate::strategy::accuracy::richardson2;
use serde::Serialize;
use std::time::Instant;

/// A benchmarked method: a label, its parameters and the largest grid it is run on.
#[derive(Clone, Debug)]
pub struct MethodSpec {
    /// The method's name in rows and charts, e.g. "multigrid-V", "newton", "relax".
    pub label: &'static str,
    /// The line-solve parameters of the method (point cases set theirs from the label).
    pub params: LineSolveParams,
    /// The largest line grid (points) the method is run on.
    pub max_grid: usize,
}

/// The methods compared: multigrid V cycles (default: 2 cycles per FMG level; 1 cycle per level;
/// the deformation by the O(N^2) direct sum instead of the FFT, up to 4097 points) and W cycles,
/// dense Newton-Raphson (O(N^3), up to 1025 points), and the multigrid smoother alone (up to 1025
/// points).
pub fn methods() -> Vec<MethodSpec> {
    let fast = LineSolveParams::default();
    let mut v = fast;
    v.mg.converge = Converge::Tight;
    let mut w = v;
    w.mg.cycle = CycleType::W;
    let newton = LineSolveParams {
        method: Method::Newton,
        ..v
    };
    let relax = LineSolveParams {
        method: Method::Relax,
        relax_max_sweeps: 50_000,
        ..v
    };
    let mut one = v;
    one.mg.fmg_cycles = 1;
    let mut direct = v;
    direct.mg.direct_deformation = true;
    vec![
        MethodSpec {
            label: "multigrid-V-fast",
            params: fast,
            max_grid: 1 << 20,
        },
        MethodSpec {
            label: "multigrid-V",
            params: v,
            max_grid: 1 << 20,
        },
        MethodSpec {
            label: "multigrid-V-1cycle",
            params: one,
            max_grid: 1 << 20,
        },
        MethodSpec {
            label: "multigrid-V-direct",
            params: direct,
            max_grid: 4097,
        },
        MethodSpec {
            label: "multigrid-W",
            params: w,
            max_grid: 1 << 20,
        },
        MethodSpec {
            label: "newton",
            params: newton,
            max_grid: 1025,
        },
        MethodSpec {
            label: "relax",
            params: relax,
            max_grid: 1025,
        },
    ]
}

/// One measurement.
#[derive(Clone, Debug, Serialize)]
pub struct BenchRow {
    /// The reference case's name.
    pub case: String,
    /// The method's label ([`MethodSpec::label`]).
    pub method: String,
    /// Grid points of the solve (per direction for point contacts).
    pub grid: usize,
    /// Median wall time of the repeats, s.
    pub wall_s: f64,
    /// Work units of the solve (one relaxation sweep on the finest grid each).
    pub work_units: f64,
    /// Central film H_c, Moes units.
    pub h_c: f64,
    /// Minimum film H_min, Moes units.
    pub h_min: f64,
    /// Relative error |H_c / H_c,ref - 1| against the case's [`Reference`].
    pub err_h_c: f64,
    /// Relative error |H_min / H_min,ref - 1| against the case's [`Reference`].
    pub err_h_min: f64,
    /// The solve's status: "converged", "diverged", "stalled" or "max-iterations".
    pub status: String,
}

/// A reference case and its Richardson-extrapolated reference values.
#[derive(Clone, Debug, Serialize)]
pub struct Reference {
    /// The case's name.
    pub case: String,
    /// Moes' load parameter M.
    pub m: f64,
    /// Moes' lubricant parameter L.
    pub l: f64,
    /// Richardson-extrapolated central film H_c, Moes units.
    pub h_c: f64,
    /// Richardson-extrapolated minimum film H_min, Moes units.
    pub h_min: f64,
    /// The two grids extrapolated from (coarse, fine), points (per direction for point contacts).
    pub grids: (usize, usize),
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

/// A benchmark case: a line or a point contact.
#[derive(Clone, Copy, Debug)]
pub enum BenchCase {
    /// A line contact.
    Line(LineCase),
    /// A point contact.
    Point(PointCase),
}

impl BenchCase {
    fn ml(&self) -> (f64, f64) {
        match self {
            BenchCase::Line(c) => (c.m, c.l),
            BenchCase::Point(c) => (c.m, c.l),
        }
    }

    /// Solve with the method `label` on `grid` points (per direction for point contacts);
    /// `tight` asks for the reference tolerances.
    fn solve(&self, label: &str, grid: usize, tight: bool) -> Outputs {
        match self {
            BenchCase::Line(c) => {
                let mut p = methods()
                    .into_iter()
                    .find(|m| m.label == label)
                    .expect("known method")
                    .params;
                p.mg.grid = grid;
                if tight {
                    p.mg.tol_load = 1e-9;
                    p.mg.tol_h = 1e-9;
                }
                solve_line(c, &p).outputs
            }
            BenchCase::Point(c) => {
                let mut p = PointSolveParams {
                    relax_max_sweeps: 20_000,
                    ..Default::default()
                };
                if label != "multigrid-V-fast" {
                    p.mg.converge = Converge::Tight;
                }
                match label {
                    "multigrid-W" => p.mg.cycle = CycleType::W,
                    "multigrid-V-1cycle" => p.mg.fmg_cycles = 1,
                    "multigrid-V-direct" => p.mg.direct_deformation = true,
                    "newton" => p.method = Method::Newton,
                    "relax" => p.method = Method::Relax,
                    _ => {}
                }
                p.mg.grid = grid;
                if tight {
                    p.mg.tol_load = 1e-9;
                    p.mg.tol_h = 1e-9;
                }
                solve_point(c, &p).outputs
            }
        }
    }

    /// (method label, largest grid) pairs run on this case.
    fn ladder(&self) -> Vec<(&'static str, usize)> {
        match self {
            BenchCase::Line(_) => methods().iter().map(|m| (m.label, m.max_grid)).collect(),
            // Dense 2D Newton: (N - 2)^2 unknowns, O(N^6) work; relaxation alone: O(N^2) sweeps.
            BenchCase::Point(_) => vec![
                ("multigrid-V-fast", 1 << 12),
                ("multigrid-V", 1 << 12),
                ("multigrid-V-1cycle", 1 << 12),
                // The direct 2D sum costs O(n^4) per film update.
                ("multigrid-V-direct", 65),
                ("multigrid-W", 1 << 12),
                ("newton", 33),
                ("relax", 65),
            ],
        }
    }
}

/// Reference values from multigrid on `fine` and `fine/2 + 1` points (second order assumed).
pub fn reference(name: &str, case: &BenchCase, fine: usize) -> Reference {
    let (a, b) = (
        case.solve("multigrid-V", fine / 2 + 1, true),
        case.solve("multigrid-V", fine, true),
    );
    let (m, l) = case.ml();
    Reference {
        case: name.to_string(),
        m,
        l,
        h_c: richardson2(a.h_c, b.h_c).extrapolated,
        h_min: richardson2(a.h_min, b.h_min).extrapolated,
        grids: (a.grid, b.grid),
    }
}

/// Run every method on every case over `grids`, `repeats` times each (median wall time), each
/// method only on the grids of its ladder; the reference of each case comes from `ref_grid`
/// ([`reference()`]). `log` receives one progress line per reference and per row. Returns the
/// references and the rows.
pub fn run(
    cases: &[(&str, BenchCase)],
    grids: &[usize],
    repeats: usize,
    ref_grid: usize,
    log: &mut dyn FnMut(&str),
) -> (Vec<Reference>, Vec<BenchRow>) {
    let mut refs = vec![];
    let mut rows = vec![];
    for (name, case) in cases {
        let r = reference(name, case, ref_grid);
        log(&format!(
            "{name}: reference H_c {:.6}, H_min {:.6} (Richardson over {:?} points)",
            r.h_c, r.h_min, r.grids
        ));
        for (label, max_grid) in case.ladder() {
            for &g in grids.iter().filter(|&&g| g <= max_grid) {
                let mut times = vec![];
                let mut last = None;
                for _ in 0..repeats.max(1) {
                    let t = Instant::now();
                    let o = case.solve(label, g, false);
                    times.push(t.elapsed().as_secs_f64());
                    last = Some(o);
                }
                let o = last.expect("one repeat");
                let row = BenchRow {
                    case: name.to_string(),
                    method: label.to_string(),
                    grid: o.grid,
                    wall_s: median(times),
                    work_units: o.work_units,
                    h_c: o.h_c,
                    h_min: o.h_min,
                    err_h_c: (o.h_c / r.h_c - 1.0).abs(),
                    err_h_min: (o.h_min / r.h_min - 1.0).abs(),
                    status: o.status.to_string(),
                };
                log(&format!(
                    "  {:<12} {:>6} pts  {:>9.4} s  err H_c {:.2e}  H_min {:.2e}  {}",
                    row.method, row.grid, row.wall_s, row.err_h_c, row.err_h_min, row.status
                ));
                rows.push(row);
            }
        }
        refs.push(r);
    }
    (refs, rows)
}

/// For each case and accuracy target, the fastest converged method and grid reaching it on
/// both H_c and H_min: the Pareto answer to "which method for which accuracy".
pub fn pareto(rows: &[BenchRow], targets: &[f64]) -> Vec<(String, f64, Option<BenchRow>)> {
    let mut out = vec![];
    let mut cases: Vec<&str> = rows.iter().map(|r| r.case.as_str()).collect();
    cases.dedup();
    for c in cases {
        for &t in targets {
            let best = rows
                .iter()
                .filter(|r| {
                    r.case == c && r.status == "converged" && r.err_h_c <= t && r.err_h_min <= t
                })
                .min_by(|a, b| a.wall_s.total_cmp(&b.wall_s))
                .cloned();
            out.push((c.to_string(), t, best));
        }
    }
    out
}
