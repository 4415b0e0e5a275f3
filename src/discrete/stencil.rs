//! The stencil of the discrete Reynolds operator along one grid direction, and its exact
//! derivatives, written once for line and point contacts (the operators in
//! [`crate::discrete::line::operator`] and [`crate::discrete::point::operator`]).
//!
//! Contract. Fields are nodal slices in a level's storage order; a node is a storage index c, its
//! neighbours along the direction at c - s and c + s (stride s: 1 along x, nx along y in a point
//! contact). The functions read c - 2s..=c + s only; the caller keeps these in range (interior
//! nodes, and c - 2 only where [`upwind`] gives a non-zero weight there). Outputs:
//! * [`flux_difference`]: eps_{c-1/2}(P_{c-s} - P_c) + eps_{c+1/2}(P_{c+s} - P_c), the face values
//!   the means of the nodal ones ([`face`]); divided by h^2 it is the Poiseuille term.
//! * [`wedge`]: sum_k w_k (rho H)_{c-k} with the upwind weights w of [`upwind`] (x only, stride 1);
//!   divided by h it is the wedge term D_x(rho H).
//! * [`deps_dh`], [`deps_dp`], [`drho`], [`jacobian_x`]: the derivatives a Jacobian row needs
//!   (see [`jacobian_x`]); [`jacobian_x_with`] takes the nodal derivatives computed beforehand
//!   ([`NodeDerivatives`]), with the same operations in the same order.
//!
//! Invariant: both contacts evaluate these terms only here, with the same operations in the same
//! order, so their operators and Jacobians agree to the bit on equal data.

use crate::discrete::physics::Fluid;

/// Second-order upwind weights of the wedge term at offsets 0, -1, -2.
pub const UPWIND2: [f64; 3] = [1.5, -2.0, 0.5];
/// First-order upwind weights of the wedge term at offsets 0, -1, -2.
pub const UPWIND1: [f64; 3] = [1.0, -1.0, 0.0];

/// The upwind weights at column i (along x): second order when asked and i >= 2, else first.
#[inline]
pub fn upwind(second_order: bool, i: usize) -> [f64; 3] {
    if second_order && i >= 2 {
        UPWIND2
    } else {
        UPWIND1
    }
}

/// The face value between nodes a and b: the mean of the nodal eps.
#[inline]
pub fn face(eps: &[f64], a: usize, b: usize) -> f64 {
    0.5 * (eps[a] + eps[b])
}

/// eps_{c-1/2}(P_{c-s} - P_c) + eps_{c+1/2}(P_{c+s} - P_c) along the direction of stride s.
#[inline]
pub fn flux_difference(eps: &[f64], p: &[f64], c: usize, s: usize) -> f64 {
    let em = face(eps, c - s, c);
    let ep = face(eps, c, c + s);
    em * (p[c - s] - p[c]) + ep * (p[c + s] - p[c])
}

/// sum_k w_k rho_{c-k} H_{c-k} over the non-zero weights.
#[inline]
pub fn wedge(w: [f64; 3], rho: &[f64], film: &[f64], c: usize) -> f64 {
    let mut s = 0.0;
    for (k, &wk) in w.iter().enumerate() {
        if wk != 0.0 {
            s += wk * rho[c - k] * film[c - k];
        }
    }
    s
}

/// d eps_k/dH_k at fixed P: 3 eps/H where H > 0, else 0.
#[inline]
pub fn deps_dh(eps: &[f64], film: &[f64], k: usize) -> f64 {
    let hh = film[k];
    if hh > 0.0 {
        3.0 * eps[k] / hh
    } else {
        0.0
    }
}

/// d eps_k/dP_k at fixed H: eps d ln(eps)/dP ([`Fluid::dln_eps`]).
#[inline]
pub fn deps_dp(fluid: &Fluid, eps: &[f64], p: &[f64], k: usize) -> f64 {
    eps[k] * fluid.dln_eps(p[k])
}

/// The nodal fields a Jacobian row reads, in storage order.
#[derive(Clone, Copy)]
pub struct Fields<'a> {
    /// Pressure P.
    pub p: &'a [f64],
    /// Film H.
    pub film: &'a [f64],
    /// eps = rho H^3/(eta lambda).
    pub eps: &'a [f64],
    /// Density rho.
    pub rho: &'a [f64],
    /// The film of the wedge term (H, or q(H) on rough surfaces).
    pub wfilm: &'a [f64],
}

impl<'a> Fields<'a> {
    /// The view of a level's P, H, eps, rho and wedge film.
    pub fn new(
        p: &'a [f64],
        film: &'a [f64],
        eps: &'a [f64],
        rho: &'a [f64],
        wfilm: &'a [f64],
    ) -> Self {
        Fields {
            p,
            film,
            eps,
            rho,
            wfilm,
        }
    }
}

/// The derivatives of the nodal coefficients that [`jacobian_x`] reads at node c: d eps/dH
/// ([`deps_dh`]) and d eps/dP ([`deps_dp`]) at c-1, c, c+1, and d rho/dP = rho d ln(rho)/dP at
/// c, c-1, c-2 (index k for node c - k; computed only where the upwind weight w_k is non-zero).
#[derive(Clone, Copy, Debug, Default)]
pub struct NodeDerivatives {
    /// d eps/dH at c-1, c, c+1.
    pub deps_dh: [f64; 3],
    /// d eps/dP at c-1, c, c+1.
    pub deps_dp: [f64; 3],
    /// d rho/dP at c - k.
    pub drho: [f64; 3],
}

impl NodeDerivatives {
    /// The derivatives at node c for the upwind weights w, from the fields.
    #[inline]
    pub fn at(fluid: &Fluid, f: Fields, c: usize, w: [f64; 3]) -> Self {
        let mut d = NodeDerivatives::default();
        for t in 0..3 {
            let k = c - 1 + t;
            d.deps_dh[t] = deps_dh(f.eps, f.film, k);
            d.deps_dp[t] = deps_dp(fluid, f.eps, f.p, k);
        }
        for (k, &wk) in w.iter().enumerate() {
            if wk != 0.0 {
                d.drho[k] = drho(fluid, f.rho, f.p, c - k);
            }
        }
        d
    }
}

/// d rho_k/dP_k: rho d ln(rho)/dP ([`Fluid::dln_rho`]).
#[inline]
pub fn drho(fluid: &Fluid, rho: &[f64], p: &[f64], k: usize) -> f64 {
    rho[k] * fluid.dln_rho(p[k])
}

/// The x-direction part of row c of the Jacobian of L: `g_h[m]` = dL/dH at nodes c-2..=c+1 and
/// `local[m]` = the local dL/dP at nodes c-2..=c+2 (both indexed from c - 2), from
/// * `dle` = dL/d eps at nodes c-1, c, c+1, through d eps/dH ([`deps_dh`]) and d eps/dP
///   ([`deps_dp`]);
/// * the wedge term -sum_k w_k (rho H)_{c-k}/h with its dependence on H and, through rho, on P
///   (on rough surfaces rho q(H), with dq/dH taken as 1: q' = Phi(H/sigma) <= 1 plus the small
///   shear term, so the row is diagonally heavier, never lighter).
///
/// The Poiseuille stencil's own entries (eps held fixed) are left to the caller.
#[inline]
pub fn jacobian_x(
    fluid: &Fluid,
    f: Fields,
    c: usize,
    w: [f64; 3],
    h: f64,
    dle: [f64; 3],
) -> ([f64; 4], [f64; 5]) {
    jacobian_x_with(f, c, w, h, dle, &NodeDerivatives::at(fluid, f, c, w))
}

/// [`jacobian_x`] with the nodal derivatives given (`d` = [`NodeDerivatives::at`], e.g. taken
/// from values computed once for a row of nodes): the same operations in the same order.
#[inline]
pub fn jacobian_x_with(
    f: Fields,
    c: usize,
    w: [f64; 3],
    h: f64,
    dle: [f64; 3],
    d: &NodeDerivatives,
) -> ([f64; 4], [f64; 5]) {
    let mut g_h = [0.0; 4];
    let mut local = [0.0; 5];
    for (t, &dl) in dle.iter().enumerate() {
        g_h[t + 1] += dl * d.deps_dh[t];
        local[t + 1] += dl * d.deps_dp[t];
    }
    for (k, &wk) in w.iter().enumerate() {
        if wk != 0.0 {
            let q = c - k;
            g_h[2 - k] -= wk * f.rho[q] / h;
            local[2 - k] -= wk * d.drho[k] * f.wfilm[q] / h;
        }
    }
    (g_h, local)
}
