//! The multigrid smoothers for the line contact.
//!
//! [`line_sweep`] (the default) relaxes the whole line at once: one banded solve per sweep of the
//! Jacobian with the kernel kept within `band` cells, in distributed variables where
//! xi_i = min(eps_{i-1/2}, eps_{i+1/2})/h^2 < xi_threshold (see its doc).
//!
//! [`relax_sweep`] is Venner and Lubrecht's classic point smoother, kept for comparison:
//!
//! * xi_i >= xi_threshold: Gauss-Seidel, P_i += omega_gs r_i / (dL_i/dP_i), the derivative including
//!   the wedge term's dependence on P_i through the kernel, dH_k/dP_i = -(1/pi) K_{|k-i|}. The film
//!   at the nodes i-2..=i+2 is corrected locally at once.
//! * xi_i < xi_threshold (and both neighbours pressurised): distributive Jacobi. The change
//!   delta_i = r_i / (dL_i/d delta) is applied after the sweep as P_i += omega_ja delta,
//!   P_{i+-1} -= omega_ja delta/2, where dL_i/d delta is the derivative of L_i for that distributed
//!   change: its kernel is K_|m| - (K_|m-1| + K_|m+1|)/2.
//!
//! After a sweep P is projected on P >= 0 (the cavitation condition) and H, rho, eps are
//! recomputed by the fast deformation product.

use crate::discrete::line::operator::{LineLevel, LinePhysics};
use crate::discrete::stencil::upwind;
use crate::solve::banded::solve_banded;
use crate::solve::line::jacobian::JacRow;
use crate::solve::line::spike::spike_newton;
use crate::solve::relax::{
    distributed, distributed_row, mirror_kernel, node_kind, pinned_row, relaxed, undistributed,
    viscosity_step_limit, xi, Kind, RelaxParams, Smoother,
};
use std::f64::consts::PI;

/// Work buffers of the line smoother. Owned by the caller and reused across sweeps and levels,
/// so once they have grown to the finest level's size a sweep allocates nothing.
#[derive(Default)]
pub struct LineScratch {
    rows: Vec<JacRow>,
    kind: Vec<Kind>,
    jset: Vec<bool>,
    a: Vec<f64>,
    rhs: Vec<f64>,
    ent: Vec<f64>,
    ksym: Vec<f64>,
}

/// One sweep of the chosen smoother.
pub fn relax(
    lv: &mut LineLevel,
    phys: &LinePhysics,
    h0: f64,
    rp: &RelaxParams,
    scratch: &mut LineScratch,
) {
    match rp.smoother {
        Smoother::Line => line_sweep(lv, phys, h0, rp, scratch),
        Smoother::Point => relax_sweep(lv, phys, h0, rp),
    }
}

/// Line relaxation: all interior nodes at once. With the change of variables dP = D dQ, where D
/// distributes dQ_i as (-1/2, 1, -1/2) at the low-xi nodes (set J) and is the identity elsewhere,
/// solve (J_band D) dQ = f - L(P) with the exact Jacobian entries (see
/// [`crate::solve::line::jacobian`]) kept for |i - j| <= band; the distributed kernel decays like
/// 1/d^3, so what is dropped is smooth and left to the coarse grids. Cavitated nodes (Newton point
/// value P_i + r_i/J_ii <= 0) and frozen coarse nodes get the row dP_i = -P_i resp. 0. Then
/// P += omega_line dP, projected on P >= 0.
pub fn line_sweep(
    lv: &mut LineLevel,
    phys: &LinePhysics,
    h0: f64,
    rp: &RelaxParams,
    scratch: &mut LineScratch,
) {
    let n = lv.len();
    let m = n - 2;
    let bw = rp.band + 1;
    let w = 2 * bw + 1;
    let h2 = lv.h * lv.h;
    let LineScratch {
        rows,
        kind,
        jset,
        a,
        rhs,
        ent,
        ksym,
    } = scratch;
    rows.clear();
    rows.extend((1..n - 1).map(|i| {
        if rp.picard {
            JacRow::picard(lv, phys, i)
        } else {
            JacRow::new(lv, phys, i)
        }
    }));
    kind.clear();
    kind.resize(n, Kind::Active);
    rhs.clear();
    rhs.resize(m, 0.0);
    for i in 1..n - 1 {
        let r = lv.f[i] - lv.reynolds(phys, i);
        rhs[i - 1] = r;
        let d = rows[i - 1].entry(&lv.kernel, i);
        kind[i] = node_kind(lv.frozen[i], lv.p[i], r, d);
    }
    kind[0] = Kind::Frozen;
    kind[n - 1] = Kind::Frozen;
    jset.clear();
    jset.extend(
        (0..n).map(|i| distributed(kind, i, || phys.dry || xi(&lv.eps, i, h2) < rp.xi_threshold)),
    );
    // Every row writes all its band entries (pinned_row, distributed_row): no clearing.
    a.resize(m * w, 0.0);
    ent.clear();
    ent.resize(2 * bw + 3, 0.0);
    mirror_kernel(&lv.kernel, bw + 3, ksym);
    for i in 1..n - 1 {
        let row = i - 1;
        let a_row = &mut a[row * w..][..w];
        if kind[i] != Kind::Active {
            pinned_row(a_row, &mut rhs[row], bw, kind[i], lv.p[i]);
            continue;
        }
        // Row entries J(i, j) for j = i-bw-1 ..= i+bw+1 (zero outside the interior).
        let j0 = i as isize - bw as isize - 1;
        rows[row].window(ksym, bw, ent);
        for (t, v) in ent.iter_mut().enumerate() {
            let j = j0 + t as isize;
            if j < 1 || j >= n as isize - 1 {
                *v = 0.0;
            }
        }
        let ent = &*ent;
        distributed_row(a_row, i, bw, n - 2, jset, |j| {
            ent[(j as isize - j0) as usize]
        });
    }
    if !solve_banded(a, m, bw, rhs) || rhs.iter().any(|v| !v.is_finite()) {
        // A zero pivot (the band is not dominant enough): fall back to the point sweep.
        relax_sweep(lv, phys, h0, rp);
        return;
    }
    let max_dp = viscosity_step_limit(phys.fluid.alpha_bar);
    for i in 1..n - 1 {
        let dp = undistributed(rhs, jset, i);
        lv.p[i] = relaxed(
            kind[i],
            lv.p[i],
            rp.omega_line,
            dp,
            max_dp,
            rp.relative_step,
        );
    }
    lv.update_film(phys, h0);
    if let Some(sn) = &rp.spike_newton {
        if spike_newton(lv, phys, sn) > 0 {
            lv.update_film(phys, h0);
        }
    }
}

/// d(wedge_i)/d(unknown) for a change whose film response at node k is -(1/pi) kd(k - i) per unit.
#[inline]
fn wedge_derivative(
    lv: &LineLevel,
    phys: &LinePhysics,
    i: usize,
    kd: impl Fn(isize) -> f64,
) -> f64 {
    if !phys.elastic {
        return 0.0;
    }
    let c = upwind(phys.second_order, i);
    let mut s = 0.0;
    for (k, &ck) in c.iter().enumerate() {
        if ck != 0.0 {
            s += ck * lv.rho[i - k] * (-kd(-(k as isize)) / PI);
        }
    }
    s / lv.h
}

/// One relaxation sweep on a level; returns nothing, updates P, H, rho, eps.
pub fn relax_sweep(lv: &mut LineLevel, phys: &LinePhysics, h0: f64, rp: &RelaxParams) {
    let n = lv.len();
    let law = phys.coefficients();
    let h2 = lv.h * lv.h;
    let k = |d: isize| -> f64 {
        let d = d.unsigned_abs();
        if d < lv.kernel.len() {
            lv.kernel[d]
        } else {
            0.0
        }
    };
    let kern: [f64; 5] = std::array::from_fn(|d| k(d as isize));
    let kv = |d: isize| kern[d.unsigned_abs().min(4)];
    let kdist = |m: isize| kv(m) - 0.5 * (kv(m - 1) + kv(m + 1));
    lv.delta.fill(0.0);
    for i in 1..n - 1 {
        if lv.frozen[i] {
            continue;
        }
        let em = 0.5 * (lv.eps[i - 1] + lv.eps[i]);
        let ep = 0.5 * (lv.eps[i] + lv.eps[i + 1]);
        let r = lv.f[i] - lv.reynolds(phys, i);
        let xi = em.min(ep) / h2;
        let jacobi = phys.dry || (xi < rp.xi_threshold && lv.p[i - 1] > 0.0 && lv.p[i + 1] > 0.0);
        if jacobi {
            let d = -1.5 * (em + ep) / h2 - wedge_derivative(lv, phys, i, kdist);
            if d < 0.0 {
                lv.delta[i] = r / d;
            }
        } else {
            let d = -(em + ep) / h2 - wedge_derivative(lv, phys, i, kv);
            if d >= 0.0 {
                continue;
            }
            let new = (lv.p[i] + rp.omega_gs * r / d).max(0.0);
            let change = new - lv.p[i];
            lv.p[i] = new;
            if phys.elastic && change != 0.0 {
                for kk in i.saturating_sub(2)..(i + 3).min(n) {
                    lv.film[kk] -= kv(kk as isize - i as isize) * change / PI;
                    lv.nodes.refresh_rough_at(&law, kk);
                }
            }
        }
    }
    for i in 1..n - 1 {
        let d = lv.delta[i];
        if d != 0.0 {
            let c = rp.omega_ja * d;
            lv.p[i] += c;
            lv.p[i - 1] -= 0.5 * c;
            lv.p[i + 1] -= 0.5 * c;
        }
    }
    lv.p[0] = 0.0;
    lv.p[n - 1] = 0.0;
    for p in lv.p.iter_mut() {
        *p = p.max(0.0);
    }
    lv.update_film(phys, h0);
}
