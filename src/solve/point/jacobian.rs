//! Exact derivatives of the discrete point-contact Reynolds operator, one row at a time (the 2D
//! counterpart of [`crate::solve::line::jacobian`]).
//!
//! With q = rho H and eps = rho H^3/(eta lambda), row (i, j) of dL/dP collects
//! * the film response of the eps values in the stencil, (i-1, j), (i, j), (i+1, j), (i, j-1),
//!   (i, j+1), and of the wedge term, (i-2..=i, j), through dH_m/dP_n = c K(m - n): a weighted sum
//!   of kernel values, `g_h` for the nodes (i-2..=i+1, j) and `g_y` for (i, j-1), (i, j+1);
//! * local terms: the Poiseuille stencil and the dependence of eps and rho on P at the node itself,
//!   `local` for (i-2..=i+2, j) and `local_y` for (i, j-1), (i, j+1).
//!
//! dL/dH0 = sum of all film weights, since dH/dH0 = 1. Any entry costs O(1). The x-direction terms
//! are those of the line contact, computed by the same functions ([`crate::discrete::stencil`]).

use crate::discrete::point::far_field::Slave;
use crate::discrete::point::operator::{PointLevel, PointPhysics};
use crate::discrete::point::strip::RowsRef;
use crate::discrete::stencil::{
    deps_dh, deps_dp, drho, face, jacobian_x_with, upwind, Fields, NodeDerivatives,
};
use crate::solve::newton::{
    dense_jacobian, newton_level_common, rows_on_pool, NewtonLevel, RowMatrix,
};
use crate::solve::relax::mirror_kernel;

/// Row (i, j) of the Jacobian of L with respect to (P, H0).
pub struct PointJacRow {
    i: usize,
    j: usize,
    g_h: [f64; 4],
    g_y: [f64; 2],
    local: [f64; 5],
    local_y: [f64; 2],
    /// c for elastic surfaces, 0 for rigid ones.
    coef: f64,
}

impl PointJacRow {
    /// The Jacobian row of the interior node (i, j) of `lv`.
    pub fn new(lv: &RowsRef, phys: &PointPhysics, i: usize, j: usize) -> Self {
        Self::build::<true>(lv, phys, i, j, |f, c, w| {
            NodeDerivatives::at(&phys.fluid, f, c, w)
        })
    }

    /// [`PointJacRow::new`] with the nodal derivatives of row j taken from `row` (filled for
    /// i - 2..=i + 1) and without the local terms of the rows j - 1 and j + 1 (left 0): for
    /// [`PointJacRow::row_entries`] and [`PointJacRow::diagonal`], which read row j only and
    /// then give the values of a row from `new` to the bit.
    #[inline]
    pub fn in_row(
        lv: &RowsRef,
        phys: &PointPhysics,
        i: usize,
        j: usize,
        row: &RowDerivatives,
    ) -> Self {
        Self::build::<false>(lv, phys, i, j, |_, _, w| row.at(i, w))
    }

    /// The row, with the nodal derivatives from `derivs(fields, c, upwind weights)`, and the
    /// local terms of the rows j - 1 and j + 1 when `Y`.
    #[inline(always)]
    fn build<const Y: bool>(
        lv: &RowsRef,
        phys: &PointPhysics,
        i: usize,
        j: usize,
        derivs: impl FnOnce(Fields, usize, [f64; 3]) -> NodeDerivatives,
    ) -> Self {
        let coef = if phys.elastic { phys.coef } else { 0.0 };
        if phys.dry {
            return PointJacRow {
                i,
                j,
                g_h: [0.0, 0.0, -1.0, 0.0],
                g_y: [0.0; 2],
                local: [0.0; 5],
                local_y: [0.0; 2],
                coef,
            };
        }
        let nx = lv.nx;
        let c = lv.at(i, j);
        let (hx2, hy2) = (lv.hx * lv.hx, lv.hy * lv.hy);
        let (p, e, film) = (&lv.p, &lv.eps, &lv.film);
        let ey = lv.eps_y();
        let a = (p[c - 1] - p[c]) / hx2;
        let b = (p[c + 1] - p[c]) / hx2;
        let ay = (p[c - nx] - p[c]) / hy2;
        let by = (p[c + nx] - p[c]) / hy2;
        // dL/d eps at (i-1, j), (i, j), (i+1, j); the y faces' share of the centre node scaled
        // by eps_y/eps (1 unless rough anisotropic surfaces give y its own flow factor).
        let centre = if lv.eps_along_y.is_empty() || e[c] <= 0.0 {
            a + b + ay + by
        } else {
            a + b + (ay + by) * (ey[c] / e[c])
        };
        let dle = [0.5 * a, 0.5 * centre, 0.5 * b];
        let f = Fields::new(p, film, e, lv.rho, lv.wedge_film());
        let w = upwind(phys.second_order, i);
        let d = derivs(f, c, w);
        let (g_h, mut local) = jacobian_x_with(f, c, w, lv.hx, dle, &d);
        let g_y = [
            0.5 * ay * deps_dh(ey, film, c - nx),
            0.5 * by * deps_dh(ey, film, c + nx),
        ];
        let exm = face(e, c - 1, c);
        let exp = face(e, c, c + 1);
        let eym = face(ey, c - nx, c);
        let eyp = face(ey, c, c + nx);
        local[1] += exm / hx2;
        local[3] += exp / hx2;
        local[2] -= (exm + exp) / hx2 + (eym + eyp) / hy2;
        let mut local_y = [0.0; 2];
        if Y {
            let fl = &phys.fluid;
            local_y = [
                0.5 * ay * deps_dp(fl, ey, p, c - nx) + eym / hy2,
                0.5 * by * deps_dp(fl, ey, p, c + nx) + eyp / hy2,
            ];
        }
        PointJacRow {
            i,
            j,
            g_h,
            g_y,
            local,
            local_y,
            coef,
        }
    }

    /// A zero row for the node (i, j) whose equation is not relaxed (frozen or cavitated).
    pub fn pinned(i: usize, j: usize) -> Self {
        PointJacRow {
            i,
            j,
            g_h: [0.0; 4],
            g_y: [0.0; 2],
            local: [0.0; 5],
            local_y: [0.0; 2],
            coef: 0.0,
        }
    }

    /// dL_ij/dP at node (k, l); `kernel` and `nx` of the level.
    #[inline]
    pub fn entry(&self, kernel: &[f64], nx: usize, k: usize, l: usize) -> f64 {
        let mut v = 0.0;
        if self.coef != 0.0 {
            let mut s = 0.0;
            let dy = self.j.abs_diff(l);
            for (t, &g) in self.g_h.iter().enumerate() {
                if g != 0.0 {
                    s += g * kernel[dy * nx + (self.i + t - 2).abs_diff(k)];
                }
            }
            let dx = self.i.abs_diff(k);
            if self.g_y[0] != 0.0 {
                s += self.g_y[0] * kernel[(self.j - 1).abs_diff(l) * nx + dx];
            }
            if self.g_y[1] != 0.0 {
                s += self.g_y[1] * kernel[(self.j + 1).abs_diff(l) * nx + dx];
            }
            v = self.coef * s;
        }
        if l == self.j {
            let off = k as isize - self.i as isize + 2;
            if (0..5).contains(&off) {
                v += self.local[off as usize];
            }
        } else if k == self.i {
            if l + 1 == self.j {
                v += self.local_y[0];
            } else if l == self.j + 1 {
                v += self.local_y[1];
            }
        }
        v
    }

    /// dL_ij/dP_ij, the diagonal: [`PointJacRow::entry`] at (i, j) to the bit (the same sum in
    /// the same order; the zero weights that `entry` skips add exact zeros here); `win` holds
    /// offsets up to at least 2.
    #[inline]
    pub fn diagonal(&self, win: &KernelWindow) -> f64 {
        let mut v = 0.0;
        if self.coef != 0.0 {
            let r = win.reach;
            let [g0, g1, g2, g3] = self.g_h;
            let [gy0, gy1] = self.g_y;
            let (k0, k1, k2, ky) = (win.row0[r], win.row0[r + 1], win.row0[r + 2], win.row1[r]);
            let s = 0.0 + g0 * k2 + g1 * k1 + g2 * k0 + g3 * k1;
            v = self.coef * (s + gy0 * ky + gy1 * ky);
        }
        v + self.local[2]
    }

    /// dL_ij/dP at the nodes (k, j) of the row itself for k in lo..=hi (within
    /// [`KernelWindow::reach`] of i), into `out[k]`: the values of [`PointJacRow::entry`],
    /// computed together (the zero weights that `entry` skips add exact zeros here, so the values
    /// are the same to the bit).
    pub fn row_entries(&self, win: &KernelWindow, lo: usize, hi: usize, out: &mut [f64]) {
        let i = self.i;
        let r = win.reach;
        debug_assert!(i - lo <= r - 2 && hi - i <= r - 2);
        let out = &mut out[lo..=hi];
        if self.coef != 0.0 {
            let [g0, g1, g2, g3] = self.g_h;
            let [gy0, gy1] = self.g_y;
            // Node k reads the mirrored row 0 at c - 2..=c + 1 and row 1 at c, c = r + i - k:
            // windows from k = lo (c largest) on.
            let (c_lo, c_hi) = (r + i - hi, r + i - lo);
            let w0 = win.row0[c_lo - 2..=c_hi + 1].windows(4).rev();
            let w1 = win.row1[c_lo..=c_hi].iter().rev();
            for ((o, w), &k1) in out.iter_mut().zip(w0).zip(w1) {
                let s = 0.0 + g0 * w[0] + g1 * w[1] + g2 * w[2] + g3 * w[3];
                *o = self.coef * (s + gy0 * k1 + gy1 * k1);
            }
        } else {
            out.fill(0.0);
        }
        // local[t] belongs to node k = i + t - 2, within lo..=hi for t in t_lo..=t_hi (lo <= i <= hi).
        let (t_lo, t_hi) = ((lo + 2).saturating_sub(i), (hi + 2 - i).min(4));
        for (o, &v) in out[i + t_lo - 2 - lo..]
            .iter_mut()
            .zip(&self.local[t_lo..=t_hi])
        {
            *o += v;
        }
    }

    /// [`PointJacRow::entry`] for every interior node (k, l) of an nx x ny level, in the order
    /// of the unknowns (l = 1..ny-1 outer, k = 1..nx-1 inner), into `out`: the same sums in the
    /// same order, so the same values to the bit, with the kernel rows looked up once per l.
    pub fn dense_row(&self, kernel: &[f64], nx: usize, ny: usize, out: &mut [f64]) {
        let (i, j) = (self.i, self.j);
        let m = nx - 2;
        for (l, o) in (1..ny - 1).zip(out.chunks_exact_mut(m)) {
            if self.coef != 0.0 {
                let k0 = &kernel[j.abs_diff(l) * nx..][..nx];
                let km = &kernel[(j - 1).abs_diff(l) * nx..][..nx];
                let kp = &kernel[(j + 1).abs_diff(l) * nx..][..nx];
                for (k, v) in (1..nx - 1).zip(o.iter_mut()) {
                    let mut s = 0.0;
                    for (t, &g) in self.g_h.iter().enumerate() {
                        if g != 0.0 {
                            s += g * k0[(i + t - 2).abs_diff(k)];
                        }
                    }
                    let dx = i.abs_diff(k);
                    if self.g_y[0] != 0.0 {
                        s += self.g_y[0] * km[dx];
                    }
                    if self.g_y[1] != 0.0 {
                        s += self.g_y[1] * kp[dx];
                    }
                    *v = self.coef * s;
                }
            } else {
                o.fill(0.0);
            }
            if l == j {
                for (t, &v) in self.local.iter().enumerate() {
                    if let Some(k) = (i + t).checked_sub(2).filter(|k| (1..nx - 1).contains(k)) {
                        o[k - 1] += v;
                    }
                }
            } else if l + 1 == j {
                o[i - 1] += self.local_y[0];
            } else if l == j + 1 {
                o[i - 1] += self.local_y[1];
            }
        }
    }

    /// dL_ij/dH0.
    pub fn d_h0(&self) -> f64 {
        self.g_h.iter().sum::<f64>() + self.g_y.iter().sum::<f64>()
    }
}

/// The kernel values of a level's rows dy = 0 and 1 at the offsets -reach..=reach along x
/// (index reach + offset), mirrored from the stored |offset| so that a window of a Jacobian row
/// is read in order ([`PointJacRow::row_entries`]).
#[derive(Default)]
pub struct KernelWindow {
    /// The largest |offset| held.
    pub reach: usize,
    row0: Vec<f64>,
    row1: Vec<f64>,
}

impl KernelWindow {
    /// Fill from `kernel` (rows of length `nx`) for offsets up to `reach` (< nx).
    pub fn fill(&mut self, kernel: &[f64], nx: usize, reach: usize) {
        assert!(reach < nx);
        self.reach = reach;
        mirror_kernel(&kernel[..nx], reach, &mut self.row0);
        mirror_kernel(&kernel[nx..2 * nx], reach, &mut self.row1);
    }
}

/// The nodal derivatives of one grid row that the x-direction Jacobian terms read
/// ([`NodeDerivatives`]), computed once per node for all the Jacobian rows of the row
/// ([`PointJacRow::in_row`]), indexed by i.
#[derive(Default)]
pub struct RowDerivatives {
    deps_dh: Vec<f64>,
    deps_dp: Vec<f64>,
    drho: Vec<f64>,
}

impl RowDerivatives {
    /// Fill for the nodes (i, j), i in `range` (the others left stale), of `lv`.
    pub fn fill(
        &mut self,
        lv: &RowsRef,
        phys: &PointPhysics,
        j: usize,
        range: std::ops::RangeInclusive<usize>,
    ) {
        let nx = lv.nx;
        for v in [&mut self.deps_dh, &mut self.deps_dp, &mut self.drho] {
            v.resize(nx, 0.0);
        }
        let fl = &phys.fluid;
        for i in range {
            let c = lv.at(i, j);
            self.deps_dh[i] = deps_dh(lv.eps, lv.film, c);
            self.deps_dp[i] = deps_dp(fl, lv.eps, lv.p, c);
            self.drho[i] = drho(fl, lv.rho, lv.p, c);
        }
    }

    /// [`NodeDerivatives::at`] of node i for the upwind weights w.
    #[inline]
    fn at(&self, i: usize, w: [f64; 3]) -> NodeDerivatives {
        let mut d = NodeDerivatives {
            deps_dh: [self.deps_dh[i - 1], self.deps_dh[i], self.deps_dh[i + 1]],
            deps_dp: [self.deps_dp[i - 1], self.deps_dp[i], self.deps_dp[i + 1]],
            drho: [0.0; 3],
        };
        for (k, &wk) in w.iter().enumerate() {
            if wk != 0.0 {
                d.drho[k] = self.drho[i - k];
            }
        }
        d
    }
}

impl NewtonLevel for PointLevel {
    type Phys = PointPhysics;
    fn unknowns(&self) -> Vec<usize> {
        let mut u = Vec::with_capacity(self.len());
        for j in 1..self.ny - 1 {
            for i in 1..self.nx - 1 {
                u.push(self.at(i, j));
            }
        }
        u
    }
    fn dense_jacobian(&self, phys: &PointPhysics, unknowns: &[usize]) -> RowMatrix {
        let (nx, ny) = (self.nx, self.ny);
        // dense_row covers every interior node in order: the unknowns of this level.
        debug_assert_eq!(unknowns.len(), (nx - 2) * (ny - 2));
        let rows = self.rows();
        let slaves = self.far_slaves();
        let row = |c| PointJacRow::new(&rows, phys, c % nx, c / nx);
        let fill = |r: &PointJacRow, out: &mut [f64]| {
            r.dense_row(&self.kernel, nx, ny, out);
            self.fold_far_row(r, &slaves, |q, v| out[q] += v);
        };
        let cell = self.hx * self.hy;
        let parallel = self.parallel_jacobian;
        let mut jac = dense_jacobian(unknowns, cell, parallel, row, fill, PointJacRow::d_h0);
        // The load row: the boundary nodes' load weights, and their films' dependence on H0.
        let m = unknowns.len();
        let mut d_h0 = 0.0;
        for s in &slaves {
            for &(q, a) in &s.links {
                jac[(m, self.unknown_column(q))] += (cell + s.load_extra) * a;
            }
            d_h0 += s.d_load_extra_dh * self.p[s.node];
        }
        jac[(m, m)] += d_h0;
        jac
    }
    fn jacobian_diagonal(&self, phys: &PointPhysics, unknowns: &[usize]) -> Vec<f64> {
        use rayon::prelude::*;
        let nx = self.nx;
        let rows = self.rows();
        let slaves = self.far_slaves();
        // The boundary nodes that depend on each column's node, in slave order, each once.
        let mut linked: Vec<Vec<&Slave>> = vec![Vec::new(); unknowns.len()];
        for s in &slaves {
            for &(q, _) in &s.links {
                let l = &mut linked[self.unknown_column(q)];
                if !l.last().is_some_and(|t| std::ptr::eq(*t, s)) {
                    l.push(s);
                }
            }
        }
        let one = |(col, &c): (usize, &usize)| {
            let row = PointJacRow::new(&rows, phys, c % nx, c / nx);
            // entry() is dense_row's value to the bit; the far field's terms for this column
            // follow in the same order, from the boundary nodes that depend on this node.
            let mut d = row.entry(&self.kernel, nx, c % nx, c / nx);
            self.fold_far_row(&row, linked[col].iter().copied(), |q, v| {
                if q == col {
                    d += v;
                }
            });
            d
        };
        // On the pool where the Jacobian's rows are (each value computed alone: the same bits).
        if rows_on_pool(self.parallel_jacobian, unknowns.len()) {
            unknowns.par_iter().enumerate().map(one).collect()
        } else {
            unknowns.iter().enumerate().map(one).collect()
        }
    }
    fn residual_at(&self, phys: &PointPhysics, c: usize) -> f64 {
        self.f[c] - self.reynolds(phys, c % self.nx, c / self.nx)
    }
    newton_level_common!(PointPhysics);
}

impl PointLevel {
    /// The far field's boundary nodes with their dependence on interior pressures at the
    /// current film (none without a far field).
    fn far_slaves(&self) -> Vec<Slave> {
        match &self.far {
            Some(far) => far.slaves(&self.gap, self.h0).collect(),
            None => Vec::new(),
        }
    }

    /// The Jacobian column of the interior node at storage index c.
    fn unknown_column(&self, c: usize) -> usize {
        (c / self.nx - 1) * (self.nx - 2) + (c % self.nx - 1)
    }

    /// The far field's part of Jacobian row `row`: the boundary values are functions of
    /// interior pressures, so their columns fold into those of the interior nodes by the chain
    /// rule; `add(column, value)` for each term, in slave order.
    fn fold_far_row<'a>(
        &self,
        row: &PointJacRow,
        slaves: impl IntoIterator<Item = &'a Slave>,
        mut add: impl FnMut(usize, f64),
    ) {
        let nx = self.nx;
        for s in slaves {
            let v = row.entry(&self.kernel, nx, s.node % nx, s.node / nx);
            if v != 0.0 {
                for &(q, a) in &s.links {
                    add(self.unknown_column(q), v * a);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests;
