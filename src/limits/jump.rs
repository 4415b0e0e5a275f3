//! Where the point H_c meets H_pm: the place M_j(L, D) of the corner of the central film, by
//! solves that bisect M.
//!
//! At high L the film at the centre rises to the film under the pressure maximum within a few
//! per cent of M (a 20 % rise within 7 % of M at L = 10, D = 1), at a place that moves smoothly
//! with L and D (docs/validation.md, "Where the jump lies"). The data's M spacing (a factor
//! 1.08-1.64) brackets it only to a few per cent; these solves place it to [`TOLERANCE`] in M,
//! and the point H_c kriging takes the distance ln(M / M_j) as a coordinate
//! ([`crate::fit::kriging`]).
//!
//! Inputs: the (M, L, D, H_c / H_pm) of a point dataset's cases. For each (L, D) column whose
//! ratio crosses [`RATIO`] between two M (the last such pair in M), [`bisect`] solves the case
//! on a fixed grid ([`GRID`] by default) at M between them, regula falsi in ln M with every
//! third step a bisection, until the bracket is within [`TOLERANCE`] in ln M, the ratio of its
//! lower end below [`RATIO`] and of its upper end at or above it. Output: a [`JumpTable`],
//! ln M_j on the table's nodes (ln(1 + L), ln D), each node's M_j the geometric mean of its final
//! bracket; a node whose column has no crossing or whose bisection fails takes the data's
//! crossing interpolated linearly in ln M (marked in [`JumpColumn::solved`]), and the table is
//! None when a node has neither. Invariants: every column's solves are independent and each
//! solve is the same at any thread count, so the table is too.

use crate::model::case::{Models, PointCase};
use crate::solve::film::Film;
use crate::solve::point::{solve_point, PointSolveParams};
use crate::solve::Status;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// The ratio H_c / H_pm that marks the corner's place.
pub const RATIO: f64 = 0.95;

/// The bracket's width in ln M at which a bisection stops.
pub const TOLERANCE: f64 = 2e-3;

/// The grid of the bisection solves (points per direction).
pub const GRID: usize = 513;

/// Solves per column at most, the two ends of the data's bracket included.
pub const MAX_SOLVES: usize = 16;

/// ln M_j on a table over (ln(1 + L), ln D): bilinear between the nodes, clamped to the table's
/// box outside it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JumpTable {
    /// The nodes ln(1 + L), increasing.
    pub ln_l1: Vec<f64>,
    /// The nodes ln D, increasing.
    pub ln_d: Vec<f64>,
    /// ln M_j at each node: `ln_m[i][j]` at (`ln_l1[i]`, `ln_d[j]`).
    pub ln_m: Vec<Vec<f64>>,
}

/// The interval of `x` among increasing `nodes` and its weight in [0, 1] (clamped).
pub fn interval(nodes: &[f64], x: f64) -> (usize, usize, f64) {
    let n = nodes.len();
    if n < 2 || x <= nodes[0] {
        return (0, 0, 0.0);
    }
    if x >= nodes[n - 1] {
        return (n - 1, n - 1, 0.0);
    }
    let i = nodes.partition_point(|&v| v <= x);
    let (lo, hi) = (nodes[i - 1], nodes[i]);
    (i - 1, i, (x - lo) / (hi - lo))
}

impl JumpTable {
    /// A table checked for shape: nodes strictly increasing, one finite value per node.
    pub fn new(ln_l1: Vec<f64>, ln_d: Vec<f64>, ln_m: Vec<Vec<f64>>) -> Result<Self, String> {
        let increasing = |v: &[f64]| !v.is_empty() && v.windows(2).all(|w| w[0] < w[1]);
        if !increasing(&ln_l1) || !increasing(&ln_d) {
            return Err("jump table: nodes must be non-empty and strictly increasing".into());
        }
        if ln_m.len() != ln_l1.len()
            || ln_m
                .iter()
                .any(|r| r.len() != ln_d.len() || !r.iter().all(|v| v.is_finite()))
        {
            return Err(format!(
                "jump table: need {} x {} finite values of ln M_j",
                ln_l1.len(),
                ln_d.len()
            ));
        }
        Ok(JumpTable { ln_l1, ln_d, ln_m })
    }

    /// ln M_j at (L, D).
    pub fn ln_m_at(&self, l: f64, d: f64) -> f64 {
        let (i0, i1, u) = interval(&self.ln_l1, l.ln_1p());
        let (j0, j1, v) = interval(&self.ln_d, d.ln());
        let m = &self.ln_m;
        (1.0 - u) * ((1.0 - v) * m[i0][j0] + v * m[i0][j1])
            + u * ((1.0 - v) * m[i1][j0] + v * m[i1][j1])
    }
}

/// One solve of a bisection: M, H_c, H_pm and whether it converged.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct JumpSolve {
    /// Moes' M.
    pub m: f64,
    /// H_c (NaN when the solve did not converge).
    pub h_c: f64,
    /// H_pm (NaN when the solve did not converge).
    pub h_pm: f64,
}

impl JumpSolve {
    fn ratio(&self) -> f64 {
        self.h_c / self.h_pm
    }
}

/// One (L, D) column: its M_j and how it was found.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct JumpColumn {
    /// Moes' L.
    pub l: f64,
    /// D.
    pub d: f64,
    /// M_j (NaN when the column has no crossing).
    pub m_j: f64,
    /// The final bracket (lower, upper M).
    pub bracket: [f64; 2],
    /// Whether M_j is the bisection's (else the data's crossing, interpolated).
    pub solved: bool,
    /// The bisection's solves, in the order made.
    pub solves: Vec<JumpSolve>,
}

/// What `ehlmap fit --jump-solves` writes and `--jump` reads: the solves' settings, each
/// column and the table.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JumpFile {
    /// [`RATIO`].
    pub ratio: f64,
    /// The grid of the solves.
    pub grid: usize,
    /// [`TOLERANCE`].
    pub tolerance: f64,
    /// Each (L, D) column of the data.
    pub columns: Vec<JumpColumn>,
    /// The table (None when a column had no crossing).
    pub table: Option<JumpTable>,
}

/// A point case of the data: (M, L, D, H_c, H_pm), H_pm the solve's film at the pressure
/// maximum whether or not the fit uses it (the outlet spike or a central Barus peak may be the
/// maximum: the ratio still marks the corner).
pub type Case = (f64, f64, f64, f64, f64);

/// The solve of the corner's bisection at (M, L, D) on `grid`.
pub fn solve_at(m: f64, l: f64, d: f64, grid: usize) -> JumpSolve {
    let nan = JumpSolve {
        m,
        h_c: f64::NAN,
        h_pm: f64::NAN,
    };
    let Ok(case) = PointCase::with_models(m, l, d, Models::default()) else {
        return nan;
    };
    let mut p = PointSolveParams::default();
    p.mg.grid = grid;
    let o = solve_point(&case, &p).outputs;
    if o.status != Status::Converged {
        return nan;
    }
    JumpSolve {
        m,
        h_c: Film::Centre.of_outputs(&o),
        h_pm: Film::PressureMax.of_outputs(&o),
    }
}

/// Bisect M between `lo` and `hi` (ratio below [`RATIO`] at `lo`, at or above at `hi`) with
/// `solve`: regula falsi in ln M (Illinois-weighted, the step kept within 5-95 % of the
/// bracket), every third step a bisection. Returns the final bracket and the solves; None when
/// the ends do not bracket the ratio or a solve fails.
pub fn bisect(
    lo: f64,
    hi: f64,
    solve: impl Fn(f64) -> JumpSolve,
) -> (Option<[f64; 2]>, Vec<JumpSolve>) {
    let mut solves = vec![solve(lo), solve(hi)];
    let (mut a, mut b) = (solves[0], solves[1]);
    if !(a.ratio() < RATIO && b.ratio() >= RATIO) {
        return (None, solves);
    }
    let mut kept = 0i8;
    for step in 0..MAX_SOLVES - 2 {
        if (b.m / a.m).ln() < TOLERANCE {
            break;
        }
        let (mut fa, mut fb) = (a.ratio() - RATIO, b.ratio() - RATIO);
        if kept < 0 {
            fb *= 0.5;
        } else if kept > 0 {
            fa *= 0.5;
        }
        let t = if step % 3 == 2 {
            0.5
        } else {
            (fa / (fa - fb)).clamp(0.05, 0.95)
        };
        let s = solve(between(a.m, b.m, t));
        solves.push(s);
        if !s.ratio().is_finite() {
            return (None, solves);
        }
        if s.ratio() < RATIO {
            a = s;
            kept = -1;
        } else {
            b = s;
            kept = 1;
        }
    }
    let found = ((b.m / a.m).ln() < TOLERANCE).then_some([a.m, b.m]);
    (found, solves)
}

/// The M a fraction `t` of the way from `lo` to `hi` in ln M.
fn between(lo: f64, hi: f64, t: f64) -> f64 {
    (lo.ln() + t * (hi / lo).ln()).exp()
}

/// The last bracket in M of a column's cases (sorted by M) across [`RATIO`] (a case below it
/// and the next at or above it), with the data's crossing interpolated linearly in ln M.
fn data_bracket(column: &[Case]) -> Option<([f64; 2], f64)> {
    let ratio = |c: &Case| c.3 / c.4;
    column
        .windows(2)
        .rev()
        .find(|w| ratio(&w[0]) < RATIO && ratio(&w[1]) >= RATIO)
        .map(|w| {
            let (ra, rb) = (ratio(&w[0]), ratio(&w[1]));
            let t = (RATIO - ra) / (rb - ra);
            ([w[0].0, w[1].0], between(w[0].0, w[1].0, t))
        })
}

/// The distinct values of `v`, sorted.
fn distinct(mut v: Vec<f64>) -> Vec<f64> {
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// The corner's place in each (L, D) column of `cases` (L >= 0, D > 0), by
/// bisection solves on `grid` (columns in parallel on the calling pool), and the
/// table of all columns (None when a column has no crossing at all). `progress` is called after
/// each column with (columns done, of).
pub fn jump_columns(
    cases: &[Case],
    grid: usize,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> (Vec<JumpColumn>, Option<JumpTable>) {
    let ls = distinct(cases.iter().map(|c| c.1).collect());
    let ds = distinct(cases.iter().map(|c| c.2).collect());
    let keys: Vec<(f64, f64)> = ls
        .iter()
        .flat_map(|&l| ds.iter().map(move |&d| (l, d)))
        .collect();
    let done = std::sync::atomic::AtomicUsize::new(0);
    let columns: Vec<JumpColumn> = keys
        .par_iter()
        .map(|&(l, d)| {
            let mut col: Vec<Case> = cases
                .iter()
                .filter(|c| c.1 == l && c.2 == d)
                .copied()
                .collect();
            col.sort_by(|a, b| a.0.total_cmp(&b.0));
            let out = match data_bracket(&col) {
                None => JumpColumn {
                    l,
                    d,
                    m_j: f64::NAN,
                    bracket: [f64::NAN; 2],
                    solved: false,
                    solves: vec![],
                },
                Some((br, guess)) => {
                    let (found, solves) = bisect(br[0], br[1], |m| solve_at(m, l, d, grid));
                    JumpColumn {
                        l,
                        d,
                        m_j: found.map_or(guess, |b| (b[0] * b[1]).sqrt()),
                        bracket: found.unwrap_or(br),
                        solved: found.is_some(),
                        solves,
                    }
                }
            };
            let n = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            progress(n, keys.len());
            out
        })
        .collect();
    let ln_m: Vec<Vec<f64>> = (0..ls.len())
        .map(|i| {
            (0..ds.len())
                .map(|j| columns[i * ds.len() + j].m_j.ln())
                .collect()
        })
        .collect();
    let table = JumpTable::new(
        ls.iter().map(|l| l.ln_1p()).collect(),
        ds.iter().map(|d| d.ln()).collect(),
        ln_m,
    )
    .ok();
    (columns, table)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_is_bilinear_in_its_box_and_clamped_outside() {
        // ln M_j = 1 + 0.3 ln(1 + L) - 0.7 ln D + 0.1 ln(1 + L) ln D: bilinear, so exact.
        let f = |u: f64, v: f64| 1.0 + 0.3 * u - 0.7 * v + 0.1 * u * v;
        let lu: Vec<f64> = [0.0, 1.0, 5.0, 20.0]
            .iter()
            .map(|l: &f64| l.ln_1p())
            .collect();
        let lv: Vec<f64> = [0.01, 0.1, 1.0].iter().map(|d: &f64| d.ln()).collect();
        let m = lu
            .iter()
            .map(|&u| lv.iter().map(|&v| f(u, v)).collect())
            .collect();
        let t = JumpTable::new(lu.clone(), lv.clone(), m).unwrap();
        for (l, d) in [
            (0.0, 0.01),
            (2.0, 0.05),
            (7.5, 0.5),
            (20.0, 1.0),
            (0.3, 0.3),
        ] {
            let want = f(f64::ln_1p(l), f64::ln(d));
            assert!((t.ln_m_at(l, d) - want).abs() < 1e-12, "{l} {d}");
        }
        // Outside the box: the nearest edge's value.
        assert!((t.ln_m_at(40.0, 2.0) - f(lu[3], 0.0)).abs() < 1e-12);
        assert!((t.ln_m_at(0.0, 1e-4) - f(0.0, lv[0])).abs() < 1e-12);
        assert!(JumpTable::new(vec![1.0, 0.0], vec![0.0], vec![vec![1.0], vec![1.0]]).is_err());
        assert!(JumpTable::new(vec![0.0], vec![0.0], vec![vec![f64::NAN]]).is_err());
    }

    #[test]
    fn the_bisection_finds_a_steep_rise_to_the_tolerance() {
        // A smooth step of the ratio from 0.8 to 1.0 across 1 % of M at M = 5.4321.
        let m_j = 5.4321f64;
        let ratio = |m: f64| 0.9 + 0.1 * ((m / m_j).ln() / 0.01 + 0.5).tanh();
        let at = |m: f64| JumpSolve {
            m,
            h_c: ratio(m),
            h_pm: 1.0,
        };
        let (found, solves) = bisect(4.0, 7.0, at);
        let [a, b] = found.expect("brackets");
        assert!((b / a).ln() < TOLERANCE);
        assert!(ratio(a) < RATIO && ratio(b) >= RATIO);
        // The crossing of this ratio lies at ln(M/m_j) = 0.01 (atanh(0.5) - 0.5).
        let exact = m_j * (0.01 * (0.5f64.atanh() - 0.5)).exp();
        assert!(a <= exact && exact <= b, "{a} {exact} {b}");
        assert!(solves.len() <= MAX_SOLVES, "{} solves", solves.len());
        // Ends that do not bracket the ratio: no bisection.
        assert!(bisect(6.0, 7.0, at).0.is_none());
    }

    #[test]
    fn the_data_bracket_is_the_last_crossing() {
        let case = |m: f64, r: f64| (m, 10.0, 1.0, r, 1.0);
        // Below, a crossing that falls back, the last crossing: the last is taken, and the
        // crossing interpolated in ln M.
        let col = [
            case(1.0, 0.8),
            case(2.0, 0.96),
            case(3.0, 0.9),
            case(4.0, 0.85),
            case(5.0, 1.05),
        ];
        let (br, m) = data_bracket(&col).unwrap();
        assert_eq!(br, [4.0, 5.0]);
        let want = (4f64.ln() + (0.95 - 0.85) / (1.05 - 0.85) * (1.25f64).ln()).exp();
        assert!((m - want).abs() < 1e-12, "{m}");
        // A case without H_pm (NaN) closes no bracket.
        assert!(data_bracket(&[case(4.0, 0.85), (5.0, 10.0, 1.0, 1.0, f64::NAN)]).is_none());
        // No crossing: none.
        assert!(data_bracket(&[case(1.0, 0.8), case(2.0, 0.9)]).is_none());
    }

    #[test]
    fn a_coarse_circular_column_brackets_its_corner() {
        // L = 10, D = 1 on 129^2 (about a second per solve): the bracket of the data's M.
        let (found, solves) = bisect(5.0, 6.2, |m| solve_at(m, 10.0, 1.0, 129));
        let [a, b] = found.expect("the coarse solves bracket the corner");
        let ratio = |m: f64| {
            let s = solves.iter().find(|s| s.m == m).unwrap();
            s.h_c / s.h_pm
        };
        assert!(ratio(a) < RATIO && ratio(b) >= RATIO);
        assert!((b / a).ln() < TOLERANCE);
        // 513^2 puts it at 5.51 (docs/validation.md); 129^2 within 5 % of that.
        assert!((a.ln() - 5.51f64.ln()).abs() < 0.05, "{a}");
    }
}
