//! Exact derivatives of the discrete line-contact Reynolds operator, one row at a time.
//!
//! With q = rho H and eps = rho H^3/(eta lambda), row i of dL/dP collects
//! * the film response of eps_m (m = i-1, i, i+1) and of the wedge term (m = i-2..=i) through
//!   dH_m/dP_j = -(1/pi) K_{|m-j|}: a sum of four kernel rows, `g_h[m] * dH_m/dP_j`;
//! * local terms at j = i-2..=i+1: the Poiseuille stencil, the dependence of eps and rho on P_j.
//!
//! dL_i/dH0 = sum_m `g_h[m]`, since dH_m/dH0 = 1. Any entry costs O(1), so dense Jacobians (Newton,
//! through [`NewtonLevel`] for [`LineLevel`]) and banded parts of it (line relaxation) share this
//! one definition. The x-direction terms are those of the point contact, computed by the same
//! functions ([`crate::discrete::stencil`]).

use crate::discrete::line::operator::{LineLevel, LinePhysics};
use crate::discrete::stencil::{face, jacobian_x, upwind, Fields};
use crate::solve::newton::{dense_jacobian, newton_level_common, NewtonLevel, RowMatrix};
use std::f64::consts::PI;

/// Row i of the Jacobian of L with respect to (P, H0).
pub struct JacRow {
    i: usize,
    /// dL_i/dH_m for m = i-2..=i+1.
    g_h: [f64; 4],
    /// Local part for j = i-2..=i+2.
    local: [f64; 5],
    elastic: bool,
}

impl JacRow {
    /// The exact row.
    pub fn new(lv: &LineLevel, phys: &LinePhysics, i: usize) -> Self {
        Self::build(lv, phys, i, false)
    }

    /// The row with eps frozen (Picard): drops d(eps)/dP and d(eps)/dH, keeping the Poiseuille
    /// stencil and the wedge term's film response. Its diagonal stays negative where the exact
    /// one can change sign (steep flanks of a piezoviscous spike, where the eps derivatives
    /// times large pressure gradients dominate).
    pub fn picard(lv: &LineLevel, phys: &LinePhysics, i: usize) -> Self {
        Self::build(lv, phys, i, true)
    }

    fn build(lv: &LineLevel, phys: &LinePhysics, i: usize, frozen_eps: bool) -> Self {
        if phys.dry {
            // L_i = -H_i.
            return JacRow {
                i,
                g_h: [0.0, 0.0, -1.0, 0.0],
                local: [0.0; 5],
                elastic: phys.elastic,
            };
        }
        let h = lv.h;
        let h2 = h * h;
        let a = (lv.p[i - 1] - lv.p[i]) / h2;
        let b = (lv.p[i + 1] - lv.p[i]) / h2;
        // dL_i/d eps_m for m = i-1, i, i+1.
        let dle = if frozen_eps {
            [0.0; 3]
        } else {
            [0.5 * a, 0.5 * (a + b), 0.5 * b]
        };
        let f = Fields::new(&lv.p, &lv.film, &lv.eps, &lv.rho, lv.wedge_film());
        let w = upwind(phys.second_order, i);
        let (g_h, mut local) = jacobian_x(&phys.fluid, f, i, w, h, dle);
        let em = face(&lv.eps, i - 1, i);
        let ep = face(&lv.eps, i, i + 1);
        local[1] += em / h2;
        local[2] -= (em + ep) / h2;
        local[3] += ep / h2;
        JacRow {
            i,
            g_h,
            local,
            elastic: phys.elastic,
        }
    }

    /// dL_i/dP_j.
    #[inline]
    pub fn entry(&self, kernel: &[f64], j: usize) -> f64 {
        let mut v = 0.0;
        if self.elastic {
            let mut s = 0.0;
            for (t, &g) in self.g_h.iter().enumerate() {
                if g != 0.0 {
                    s += g * kernel[(self.i + t - 2).abs_diff(j)];
                }
            }
            v = -s / PI;
        }
        let off = j as isize - self.i as isize + 2;
        if (0..5).contains(&off) {
            v += self.local[off as usize];
        }
        v
    }

    /// Entries dL_i/dP_j for the window j = i-bw-1 ..= i+bw+1 into `out` (length 2 bw + 3), with
    /// `ksym[bw + 3 + d] = K_|d|` for |d| <= bw + 3. Columns outside 1..n-1 must be cleared by the
    /// caller.
    #[inline]
    pub fn window(&self, ksym: &[f64], bw: usize, out: &mut [f64]) {
        let len = 2 * bw + 3;
        let out = &mut out[..len];
        out.fill(0.0);
        if self.elastic {
            // d = (i + t - 2) - j = t + bw - 1 - k for out[k], j = i - bw - 1 + k.
            for (t, &g) in self.g_h.iter().enumerate() {
                if g != 0.0 {
                    let g = -g / PI;
                    let base = 2 * bw + 2 + t;
                    for (k, o) in out.iter_mut().enumerate() {
                        *o += g * ksym[base - k];
                    }
                }
            }
        }
        for (off, &v) in self.local.iter().enumerate() {
            // j - i = off - 2, k = bw + 1 + off - 2.
            out[bw - 1 + off] += v;
        }
    }

    /// dL_i/dH0.
    pub fn d_h0(&self) -> f64 {
        self.g_h.iter().sum()
    }
}

impl NewtonLevel for LineLevel {
    type Phys = LinePhysics;
    fn unknowns(&self) -> Vec<usize> {
        (1..self.len() - 1).collect()
    }
    fn dense_jacobian(&self, phys: &LinePhysics, unknowns: &[usize]) -> RowMatrix {
        let row = |i| JacRow::new(self, phys, i);
        // Line solves are serial (a sweep runs one per thread).
        dense_jacobian(
            unknowns,
            self.h,
            false,
            row,
            |r, out| {
                for (o, &j) in out.iter_mut().zip(unknowns) {
                    *o = r.entry(&self.kernel, j);
                }
            },
            JacRow::d_h0,
        )
    }
    fn jacobian_diagonal(&self, phys: &LinePhysics, unknowns: &[usize]) -> Vec<f64> {
        unknowns
            .iter()
            .map(|&i| JacRow::new(self, phys, i).entry(&self.kernel, i))
            .collect()
    }
    fn residual_at(&self, phys: &LinePhysics, c: usize) -> f64 {
        self.f[c] - self.reynolds(phys, c)
    }
    newton_level_common!(LinePhysics);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::case::LineCase;

    #[test]
    fn jacobian_matches_finite_differences() {
        let case = LineCase::with_models(
            20.0,
            10.0,
            crate::model::case::Models {
                density: crate::model::lubricant::Density::DowsonHigginson { ph_pa: 0.5e9 },
                ..Default::default()
            },
        )
        .unwrap();
        let phys = LinePhysics::from_case(&case);
        let mut lv = LineLevel::new(-3.0, 1.5, 32);
        for i in 1..lv.len() - 1 {
            lv.p[i] = (1.0 - lv.x[i] * lv.x[i]).max(0.0).sqrt() + 0.05;
        }
        let h0 = 0.3;
        lv.update_film(&phys, h0);
        let jac = lv.dense_jacobian(&phys, &lv.unknowns());
        let n = lv.len();
        let e = 1e-7;
        for j in [3usize, 10, 20, 30] {
            let mut plus = LineLevel::new(-3.0, 1.5, 32);
            plus.p.copy_from_slice(&lv.p);
            plus.p[j] += e;
            plus.update_film(&phys, h0);
            for i in [2usize, 9, 10, 11, 25] {
                let fd = (plus.reynolds(&phys, i) - lv.reynolds(&phys, i)) / e;
                let an = jac[(i - 1, j - 1)];
                assert!(
                    (fd - an).abs() <= 1e-4 * (1.0 + an.abs()),
                    "i={i} j={j}: fd {fd} an {an}"
                );
            }
        }
        let mut plus = LineLevel::new(-3.0, 1.5, 32);
        plus.p.copy_from_slice(&lv.p);
        plus.update_film(&phys, h0 + e);
        for i in [2usize, 10, 25] {
            let fd = (plus.reynolds(&phys, i) - lv.reynolds(&phys, i)) / e;
            let an = jac[(i - 1, n - 2)];
            assert!(
                (fd - an).abs() <= 1e-4 * (1.0 + an.abs()),
                "i={i}: fd {fd} an {an}"
            );
        }
    }

    #[test]
    fn the_diagonal_alone_is_the_dense_jacobians_to_the_bit() {
        let phys = LinePhysics::from_case(&LineCase::new(20.0, 10.0).unwrap());
        let mut lv = LineLevel::new(-3.0, 1.5, 256);
        for i in 1..lv.len() - 1 {
            // A cavitated outlet: zero pressures after X = 1.
            lv.p[i] = (1.0 - lv.x[i] * lv.x[i]).max(0.0).sqrt();
        }
        lv.update_film(&phys, 0.3);
        let u = lv.unknowns();
        let jac = lv.dense_jacobian(&phys, &u);
        let diag = lv.jacobian_diagonal(&phys, &u);
        assert_eq!(diag.len(), u.len());
        for (r, d) in diag.iter().enumerate() {
            assert_eq!(d.to_bits(), jac[(r, r)].to_bits(), "row {r}");
        }
    }

    #[test]
    fn window_equals_entries() {
        let phys = LinePhysics::from_case(&LineCase::new(20.0, 10.0).unwrap());
        let mut lv = LineLevel::new(-3.0, 1.5, 64);
        for i in 1..lv.len() - 1 {
            lv.p[i] = (1.0 - lv.x[i] * lv.x[i]).max(0.0).sqrt() + 0.01;
        }
        lv.update_film(&phys, 0.2);
        let bw = 5;
        let ksym: Vec<f64> = (0..2 * bw + 7)
            .map(|q| lv.kernel[(q as isize - bw as isize - 3).unsigned_abs()])
            .collect();
        let mut out = vec![0.0; 2 * bw + 3];
        for i in [10usize, 30, 40] {
            let row = JacRow::new(&lv, &phys, i);
            row.window(&ksym, bw, &mut out);
            for (k, &v) in out.iter().enumerate() {
                let j = i + k - bw - 1;
                let e = row.entry(&lv.kernel, j);
                assert!(
                    (v - e).abs() <= 1e-12 * (1.0 + e.abs()),
                    "i={i} j={j}: {v} vs {e}"
                );
            }
        }
    }
}
