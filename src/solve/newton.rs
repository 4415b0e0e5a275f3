//! Damped Newton-Raphson for a discrete contact problem on one level (line or point, through
//! [`NewtonLevel`], implemented next to each contact's Jacobian rows in
//! [`crate::solve::line::jacobian`] and [`crate::solve::point::jacobian`]) (dense Jacobian, LU with
//! partial pivoting from faer), with the cavitation condition as a semi-smooth active set.
//!
//! Unknowns: P_1..P_{n-2} and H0. Equations: L_i(P, H0) = f_i on the pressurised set, P_i = 0 on the
//! cavitated set, h sum P = g. The Jacobian is exact: with q = rho H and eps = rho H^3/(eta lambda),
//! dL_i/dP_j collects the Poiseuille stencil, the local dependence of eps and rho on P_j, and the
//! film response dH_m/dP_j = -(1/pi) K_{|m-j|} of eps_m (m = i-1, i, i+1) and of the wedge term
//! (m = i-2..i); dH_m/dH0 = 1. Node i is pressurised when its Newton point value
//! t_i = P_i + (f_i - L_i)/J_ii is positive (complementarity P >= 0, L - f <= 0, P (L - f) = 0).
//! Steps are damped by backtracking on the semi-smooth residual norm. That norm and the active
//! set need the residuals and the Jacobian's diagonal only ([`NewtonLevel::jacobian_diagonal`]):
//! the dense Jacobian is built only where a step is taken.
//!
//! Used as the exact coarsest-grid solver of the multigrid and as the Newton baseline.

use nalgebra::DVector;
use std::ops::{Index, IndexMut};

/// The [`NewtonParams::stall_window`] of a multigrid's coarsest-level solves.
pub const MULTIGRID_STALL_WINDOW: usize = 8;

/// Newton settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonParams {
    /// Iterations allowed.
    pub max_iter: usize,
    /// Converged when the scaled residual norm is below this.
    pub tol: f64,
    /// Also converged when the scaled residual norm is below this fraction of its value at the
    /// start (0: only `tol`). A multigrid's coarsest-level solves inside a cycle need not go
    /// further than the cycle's own contraction.
    pub rel_tol: f64,
    /// With `rel_tol`: that stop also needs the load equation's part of the residual norm below
    /// this fraction of the norm's value at the start (infinite: no such condition). Where the
    /// film follows H0 closely (rigid-like contacts), an H0 left inexact by the coarsest solve
    /// moves the finer films by more than the cycle's own contraction.
    pub load_rel_tol: f64,
    /// Hold H0 fixed and drop the load equation.
    pub fix_h0: bool,
    /// Give up when the residual norm has not halved over this many iterations (0: never). A
    /// multigrid's coarsest-level solves have a fallback for a failed solve, and a damped
    /// semi-smooth Newton that crawls rarely converges within its iteration budget.
    pub stall_window: usize,
    /// Stop iterating once this instant has passed (the solve's deadline; `None`: no limit).
    pub deadline: Option<std::time::Instant>,
}

impl NewtonParams {
    /// The full solve that starts a multigrid of `levels` levels on its coarsest level:
    /// `max_iter` iterations, given up when stalled ([`MULTIGRID_STALL_WINDOW`]) except by the
    /// Newton baseline (one level), which has no fallback and runs its budget; stopped at the
    /// solve's `deadline`.
    pub fn coarsest_start(
        max_iter: usize,
        levels: usize,
        deadline: Option<std::time::Instant>,
    ) -> Self {
        NewtonParams {
            max_iter,
            deadline,
            stall_window: if levels > 1 {
                MULTIGRID_STALL_WINDOW
            } else {
                0
            },
            ..NewtonParams::default()
        }
    }
}

impl Default for NewtonParams {
    fn default() -> Self {
        NewtonParams {
            max_iter: 40,
            tol: 1e-10,
            rel_tol: 0.0,
            load_rel_tol: f64::INFINITY,
            fix_h0: false,
            stall_window: 0,
            deadline: None,
        }
    }
}

/// Result of a Newton solve on one level.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonOutcome {
    /// Iterations made.
    pub iterations: usize,
    /// Whether the residual met the tolerance.
    pub converged: bool,
    /// Final scaled residual norm.
    pub residual: f64,
    /// Whether the linear solve ever failed (singular Jacobian).
    pub singular: bool,
    /// The pressure unit of the absolute tolerances ([`pressure_unit`]): `tol` and a caller's
    /// acceptance of `residual` hold in this unit.
    pub unit: f64,
}

/// The pressure unit of a Newton solve's absolute tolerances: min(1, max P over the unknowns at
/// its start). The residual norm is a norm of pressure corrections, in Hertz pressures; where
/// the pressure is far below one (rigid-like contacts: P of 1e-11 at M = 0.01, D = 1), an
/// absolute tolerance of 1e-10 would pass a solve that has not started. The smallest positive
/// number where every P is 0.
pub fn pressure_unit(p: &[f64], unknowns: &[usize]) -> f64 {
    let max = unknowns.iter().map(|&c| p[c].abs()).fold(0.0, f64::max);
    max.clamp(f64::MIN_POSITIVE, 1.0)
}

/// The Newton system J x = rhs at the current state.
struct Linearisation {
    jac: RowMatrix,
    rhs: DVector<f64>,
}

/// The row of the Newton system that an unknown gets ([`evaluate`] decides, [`system`] builds).
#[derive(Clone, Copy, PartialEq, Eq)]
enum RowKind {
    /// Held fixed: dP = 0.
    Frozen,
    /// The Jacobian row, with rhs f - L.
    Pressurised,
    /// P + dP = 0.
    Cavitated,
}

/// The semi-smooth residual at the current state (film up to date), without the Jacobian: each
/// unknown's residual f - L and row kind, and the norms that the stopping rule and the line
/// search compare.
struct Evaluation {
    res: Vec<f64>,
    kind: Vec<RowKind>,
    merit: f64,
    /// The load equation's part of `merit` (0 at fixed H0).
    load: f64,
}

/// A dense square matrix stored row after row: the Newton Jacobian, whose rows are assembled
/// independently of each other.
#[derive(Clone, Debug, PartialEq)]
pub struct RowMatrix {
    n: usize,
    data: Vec<f64>,
}

impl RowMatrix {
    /// The n x n zero matrix.
    pub fn zeros(n: usize) -> Self {
        Self {
            n,
            data: vec![0.0; n * n],
        }
    }

    /// The n x n matrix with these entries, row after row.
    #[cfg(test)]
    fn from_rows(n: usize, entries: &[f64]) -> Self {
        assert_eq!(entries.len(), n * n, "an n x n matrix needs n^2 entries");
        Self {
            n,
            data: entries.to_vec(),
        }
    }

    /// Row r.
    pub fn row(&self, r: usize) -> &[f64] {
        &self.data[r * self.n..][..self.n]
    }

    /// Row r, to change.
    pub fn row_mut(&mut self, r: usize) -> &mut [f64] {
        &mut self.data[r * self.n..][..self.n]
    }
}

impl Index<(usize, usize)> for RowMatrix {
    type Output = f64;
    fn index(&self, (r, c): (usize, usize)) -> &f64 {
        &self.data[r * self.n + c]
    }
}

impl IndexMut<(usize, usize)> for RowMatrix {
    fn index_mut(&mut self, (r, c): (usize, usize)) -> &mut f64 {
        &mut self.data[r * self.n + c]
    }
}

/// Unknowns from which [`dense_jacobian`] assembles its rows on the rayon pool (where asked
/// and the pool has more than one thread). Each row is computed alone, so the matrix is the
/// same to the bit either way.
pub const PARALLEL_JACOBIAN_ROWS: usize = 128;

/// Whether `rows` Jacobian rows (or diagonal entries), computed one by one, go to the rayon
/// pool: where `parallel` is asked, from [`PARALLEL_JACOBIAN_ROWS`] on, on a pool of more than
/// one thread.
pub fn rows_on_pool(parallel: bool, rows: usize) -> bool {
    parallel && rows >= PARALLEL_JACOBIAN_ROWS && rayon::current_num_threads() > 1
}

/// The dense Jacobian of (L at the unknowns, the load sum) with respect to (the unknowns, H0), H0
/// last, for either contact: `row(c)` is the Jacobian row of L at storage index c,
/// `fill(row, out)` writes its derivatives with respect to P at every unknown (in the order of
/// `unknowns`), `d_h0(row)` its derivative with respect to H0, and `cell` the load sum's weight of
/// each pressure (h, or hx hy). Rows are assembled on the rayon pool where `parallel`, from
/// [`PARALLEL_JACOBIAN_ROWS`] unknowns on.
pub fn dense_jacobian<R>(
    unknowns: &[usize],
    cell: f64,
    parallel: bool,
    row: impl Fn(usize) -> R + Sync,
    fill: impl Fn(&R, &mut [f64]) + Sync,
    d_h0: impl Fn(&R) -> f64 + Sync,
) -> RowMatrix {
    use rayon::prelude::*;
    let m = unknowns.len();
    let n = m + 1;
    let mut jac = RowMatrix::zeros(n);
    let (body, load) = jac.data.split_at_mut(m * n);
    let one = |(r, out): (usize, &mut [f64])| {
        let row = row(unknowns[r]);
        fill(&row, &mut out[..m]);
        out[m] = d_h0(&row);
    };
    if rows_on_pool(parallel, m) {
        body.par_chunks_mut(n).enumerate().for_each(one);
    } else {
        body.chunks_mut(n).enumerate().for_each(one);
    }
    load[..m].fill(cell);
    jac
}

/// A discrete level that Newton can solve: unknown pressures at the interior nodes (storage
/// indices from [`NewtonLevel::unknowns`]) and H0.
pub trait NewtonLevel {
    /// The discrete physics of the level.
    type Phys;
    /// Storage indices of the unknown pressures, in Jacobian order.
    fn unknowns(&self) -> Vec<usize>;
    /// The exact Jacobian of (L at the unknowns, the load sum) with respect to (the unknowns, H0),
    /// H0 last (film must be up to date).
    fn dense_jacobian(&self, phys: &Self::Phys, unknowns: &[usize]) -> RowMatrix;
    /// The diagonal of [`NewtonLevel::dense_jacobian`] at the unknowns, the same values to the
    /// bit, without the rest of the matrix (film must be up to date).
    fn jacobian_diagonal(&self, phys: &Self::Phys, unknowns: &[usize]) -> Vec<f64>;
    /// f - L at storage index c.
    fn residual_at(&self, phys: &Self::Phys, c: usize) -> f64;
    /// Whether the node at storage index c is held fixed (frozen).
    fn frozen_at(&self, c: usize) -> bool;
    /// The pressure P at every node, to update.
    fn pressure(&mut self) -> &mut [f64];
    /// The load sum of the level (the left-hand side of the load equation).
    fn load_sum(&self) -> f64;
    /// The load equation's right-hand side g.
    fn load_rhs(&self) -> f64;
    /// Recompute the film and coefficients for H0.
    fn refresh(&mut self, phys: &Self::Phys, h0: f64);
}

/// The [`NewtonLevel`] methods that both contacts' levels implement alike, from their fields `p`,
/// `frozen`, `g` and their methods `load` and `update_film`: `frozen_at`, `pressure`, `load_sum`,
/// `load_rhs` and `refresh`. Invoked inside `impl NewtonLevel for ...` with the physics type.
macro_rules! newton_level_common {
    ($phys:ty) => {
        fn frozen_at(&self, c: usize) -> bool {
            self.frozen[c]
        }
        fn pressure(&mut self) -> &mut [f64] {
            &mut self.p
        }
        fn load_sum(&self) -> f64 {
            self.load()
        }
        fn load_rhs(&self) -> f64 {
            self.g
        }
        fn refresh(&mut self, phys: &$phys, h0: f64) {
            self.update_film(phys, h0)
        }
    };
}
pub(crate) use newton_level_common;

/// Estimate dG/dH0 (G = load sum - g) on a level solved at `h0`: solve again at fixed H0 + dh
/// (stopped at the absolute tolerance or once the residual has fallen by `rel_tol`, 0 for
/// none) and difference the load; P and the film are restored afterwards. Falls back to
/// `fallback` when that solve fails or the slope is not negative. Returns the slope and the
/// Newton iterations spent.
pub fn load_slope<T: NewtonLevel>(
    lv: &mut T,
    phys: &T::Phys,
    h0: f64,
    dh: f64,
    fallback: f64,
    rel_tol: f64,
) -> (f64, usize) {
    let saved = lv.pressure().to_vec();
    let e0 = lv.load_sum() - lv.load_rhs();
    let mut h1 = h0 + dh;
    let np = NewtonParams {
        fix_h0: true,
        stall_window: MULTIGRID_STALL_WINDOW,
        rel_tol,
        ..NewtonParams::default()
    };
    let out = newton_solve(lv, phys, &mut h1, &np);
    let s = (lv.load_sum() - lv.load_rhs() - e0) / dh;
    lv.pressure().copy_from_slice(&saved);
    lv.refresh(phys, h0);
    let slope = if out.converged && s.is_finite() && s < 0.0 {
        s
    } else {
        fallback
    };
    (slope, out.iterations)
}

/// The Newton step J x = rhs, each row scaled first by the power of two nearest the reciprocal of
/// its largest entry (row equilibration: exact in floating point, so it only changes which rows
/// partial pivoting picks). The rows differ in scale by the film cubed across the domain and the
/// load row is in other units; where those scales spread over many orders (rigid-like point
/// contacts at M <= 0.01, whose films are 1e9-1e10 Hertzian units), unscaled pivoting returned
/// steps whose H0 part was off by orders of magnitude.
fn solve_equilibrated(lin: &Linearisation) -> DVector<f64> {
    use faer::linalg::solvers::Solve;
    let (jac, n) = (&lin.jac, lin.rhs.len());
    // Zero, subnormal or non-finite rows are left as they are (a subnormal largest entry would
    // ask for a factor beyond the largest finite power of two).
    let scale: Vec<f64> = (0..n)
        .map(|r| {
            let b = jac.row(r).iter().fold(0.0f64, |b, v| b.max(v.abs()));
            if b.is_normal() {
                2f64.powi(-(b.log2().round() as i32))
            } else {
                1.0
            }
        })
        .collect();
    let a = faer::Mat::<f64>::from_fn(n, n, |r, c| jac[(r, c)] * scale[r]);
    let b = faer::Col::<f64>::from_fn(n, |r| lin.rhs[r] * scale[r]);
    // A zero pivot shows as a non-finite step, which the caller reports as singular.
    let x = a.partial_piv_lu().solve(b);
    DVector::from_fn(n, |r, _| x[r])
}

/// Evaluate the semi-smooth residual at the current state (film must be up to date). Node c is
/// pressurised when its Newton point value t = P + r/J_cc is positive (J_cc < 0); its part of
/// the merit is then the scaled residual r/J_cc, else the pressure itself.
fn evaluate<T: NewtonLevel>(
    lv: &mut T,
    phys: &T::Phys,
    unknowns: &[usize],
    fix_h0: bool,
) -> Evaluation {
    let diag = lv.jacobian_diagonal(phys, unknowns);
    let mut res = Vec::with_capacity(unknowns.len());
    let mut kind = Vec::with_capacity(unknowns.len());
    let mut merit = 0.0;
    let mut load = 0.0;
    for (&c, &d) in unknowns.iter().zip(&diag) {
        let r = lv.residual_at(phys, c);
        res.push(r);
        let p = lv.pressure()[c];
        let t = if d < 0.0 { p + r / d } else { p };
        kind.push(if lv.frozen_at(c) {
            RowKind::Frozen
        } else if t > 0.0 {
            let s = if d != 0.0 { r / d } else { r };
            merit += s * s;
            RowKind::Pressurised
        } else {
            merit += p * p;
            RowKind::Cavitated
        });
    }
    if !fix_h0 {
        let g = lv.load_rhs();
        let lr = g - lv.load_sum();
        merit += (lr / g) * (lr / g);
        load = (lr / g).abs();
    }
    Evaluation {
        res,
        kind,
        merit: merit.sqrt(),
        load,
    }
}

/// Build the semi-smooth Newton system at the state of `ev` (the film unchanged since): the
/// pressurised rows of the Jacobian with rhs r, a frozen row P_c fixed, a cavitated row
/// P_c + dP_c = 0; the load row (or H0 fixed).
fn system<T: NewtonLevel>(
    lv: &mut T,
    phys: &T::Phys,
    unknowns: &[usize],
    fix_h0: bool,
    ev: &Evaluation,
) -> Linearisation {
    let m = unknowns.len();
    let hcol = m;
    let mut jac = lv.dense_jacobian(phys, unknowns);
    let mut rhs = DVector::<f64>::zeros(m + 1);
    for (row, &c) in unknowns.iter().enumerate() {
        rhs[row] = match ev.kind[row] {
            RowKind::Pressurised => ev.res[row],
            RowKind::Frozen => 0.0,
            RowKind::Cavitated => -lv.pressure()[c],
        };
        if ev.kind[row] != RowKind::Pressurised {
            jac.row_mut(row).fill(0.0);
            jac[(row, row)] = 1.0;
        }
    }
    if fix_h0 {
        jac.row_mut(hcol).fill(0.0);
        jac[(hcol, hcol)] = 1.0;
        rhs[hcol] = 0.0;
    } else {
        rhs[hcol] = lv.load_rhs() - lv.load_sum();
    }
    Linearisation { jac, rhs }
}

/// Newton-solve the level's discrete problem (with its right-hand sides f, g) for P and H0.
pub fn newton_solve<T: NewtonLevel>(
    lv: &mut T,
    phys: &T::Phys,
    h0: &mut f64,
    np: &NewtonParams,
) -> NewtonOutcome {
    let unknowns = lv.unknowns();
    let m = unknowns.len();
    let unit = pressure_unit(lv.pressure(), &unknowns);
    let tol = np.tol * unit;
    lv.refresh(phys, *h0);
    let mut ev = evaluate(lv, phys, &unknowns, np.fix_h0);
    let mut out = NewtonOutcome {
        iterations: 0,
        converged: false,
        residual: ev.merit,
        singular: false,
        unit,
    };
    let goal = tol.max(np.rel_tol * ev.merit);
    let load_goal = tol.max(np.load_rel_tol * ev.merit);
    let done = |e: &Evaluation| e.merit < tol || (e.merit < goal && e.load <= load_goal);
    let mut p_old = vec![0.0; m];
    let mut merits = Vec::with_capacity(np.max_iter);
    for it in 0..np.max_iter {
        if done(&ev) {
            out.converged = true;
            break;
        }
        merits.push(ev.merit);
        if crate::solve::deadline::past(np.deadline) {
            break;
        }
        if np.stall_window > 0
            && it >= np.stall_window
            && ev.merit > 0.5 * merits[it - np.stall_window]
        {
            break;
        }
        out.iterations = it + 1;
        // The Jacobian only where a step is taken: the evaluations of the stopping rule and
        // the line search need its diagonal only.
        let step = solve_equilibrated(&system(lv, phys, &unknowns, np.fix_h0, &ev));
        if step.iter().any(|v| !v.is_finite()) {
            out.singular = true;
            break;
        }
        for (o, &c) in p_old.iter_mut().zip(&unknowns) {
            *o = lv.pressure()[c];
        }
        let h0_old = *h0;
        let mut alpha = 1.0;
        let mut accepted = false;
        for _ in 0..12 {
            let p = lv.pressure();
            for (k, &c) in unknowns.iter().enumerate() {
                p[c] = (p_old[k] + alpha * step[k]).max(0.0);
            }
            *h0 = h0_old + alpha * step[m];
            lv.refresh(phys, *h0);
            let trial = evaluate(lv, phys, &unknowns, np.fix_h0);
            if trial.merit.is_finite() && trial.merit < ev.merit * (1.0 - 1e-4 * alpha) {
                ev = trial;
                accepted = true;
                break;
            }
            alpha *= 0.5;
        }
        if !accepted {
            // Keep the smallest step anyway: the active set may have to change to make progress.
            ev = evaluate(lv, phys, &unknowns, np.fix_h0);
        }
        out.residual = ev.merit;
    }
    if done(&ev) {
        out.converged = true;
    }
    out.residual = ev.merit;
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discrete::line::operator::{LineLevel, LinePhysics};
    use crate::model::case::LineCase;

    /// A 65-point line level of M = 20, L = 2 started from the Hertzian pressure.
    fn level() -> (LineLevel, LinePhysics) {
        let phys = LinePhysics::from_case(&LineCase::new(20.0, 2.0).unwrap());
        let mut lv = LineLevel::new(-3.0, 1.5, 64);
        for i in 1..lv.len() - 1 {
            lv.p[i] = (1.0 - lv.x[i] * lv.x[i]).max(0.0).sqrt();
        }
        (lv, phys)
    }

    #[test]
    fn row_equilibration_keeps_pivoting_accurate_across_row_scales() {
        // A large row that partial pivoting picks for its first column, whose second entry then
        // swamps the other row: x1 comes out 0 without scaling. The solution is (1, 1) to
        // within 1e-20.
        let rows = [2.0, 2e20, 1.0, 1.0];
        let rhs = DVector::<f64>::from_row_slice(&[2e20 + 2.0, 2.0]);
        let plain = nalgebra::DMatrix::<f64>::from_row_slice(2, 2, &rows)
            .lu()
            .solve(&rhs)
            .expect("regular");
        assert!((plain[0] - 1.0).abs() > 0.5, "{plain}");
        let lin = Linearisation {
            jac: RowMatrix::from_rows(2, &rows),
            rhs,
        };
        let x = solve_equilibrated(&lin);
        assert!(
            (x[0] - 1.0).abs() < 1e-12 && (x[1] - 1.0).abs() < 1e-12,
            "{x}"
        );
        // Rows near the ends of the exponent range scale to finite factors.
        let lin = Linearisation {
            jac: RowMatrix::from_rows(2, &[1e-300, 2e-301, 3e300, 1e300]),
            rhs: DVector::<f64>::from_row_slice(&[1.2e-300, 4e300]),
        };
        let x = solve_equilibrated(&lin);
        assert!(x.iter().all(|v| (v - 1.0).abs() < 1e-12), "{x}");
    }

    #[test]
    fn a_relative_tolerance_stops_at_the_asked_reduction() {
        let solve = |np: NewtonParams| {
            let (mut lv, phys) = level();
            let mut h0 = -0.3;
            (newton_solve(&mut lv, &phys, &mut h0, &np), lv.load())
        };
        let start = solve(NewtonParams {
            max_iter: 0,
            ..NewtonParams::default()
        })
        .0
        .residual;
        let (full, w_full) = solve(NewtonParams::default());
        let (rel, w_rel) = solve(NewtonParams {
            rel_tol: 1e-2,
            ..NewtonParams::default()
        });
        assert!(full.converged && full.residual < 1e-10, "{full:?}");
        assert!(rel.converged, "{rel:?}");
        // Stopped at the asked reduction, not at the absolute tolerance, and in fewer steps.
        assert!(rel.residual < 1e-2 * start, "{rel:?} from {start}");
        assert!(rel.residual > 1e-10, "{rel:?}");
        assert!(rel.iterations < full.iterations, "{rel:?} vs {full:?}");
        // The load balance (the last equation) holds to the reduced residual.
        let g = std::f64::consts::FRAC_PI_2;
        assert!((w_full / g - 1.0).abs() < 1e-10, "{w_full}");
        assert!((w_rel / g - 1.0).abs() < 1e-2 * start, "{w_rel}");
    }
}
