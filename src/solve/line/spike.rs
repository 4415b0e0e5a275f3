//! Newton windows at the outlet spike of a line contact: a local nonlinear solve after the line
//! smoother's sweep where a piezoviscous pressure spike is steeper than the grid.
//!
//! Under Barus viscosity at high alpha_bar the pressure at the outlet can fall from its spike
//! value to nearly zero within one cell of a fine grid, so that eps = rho H^3/(eta lambda)
//! changes by many orders of magnitude between neighbours. The line sweep's linearised step then
//! overshoots at those few nodes and the cycles stall with a residual of order 1e4 there while
//! the film has settled. [`spike_newton`] picks the nodes whose |r| exceeds `factor` times the mean
//! |r| over the pressurised nodes ([`residual_limit`]), widens each by 3 nodes on both sides, merges overlapping
//! windows and runs up to `iterations` Newton steps on each window's equations L_i = f_i with the
//! exact Jacobian entries ([`crate::solve::line::jacobian::JacRow`], kernel terms within the
//! window) and a backtracking line search on the window's sum of r^2 (a step is taken only if it
//! lowers it; P is projected on P >= 0). Each trial updates the film of the window and 3 nodes
//! beyond it by the near kernel terms and rho, eps there; the caller refreshes H exactly by the
//! FFT product afterwards.
//!
//! Inputs: a level after a sweep (film current), its physics. Output: P, H, rho, eps changed in
//! the windows only. Invariants: P >= 0; a window's sum of r^2 never grows; smooth, rigid, dry
//! and rough contacts are left alone (no windows).

use crate::discrete::line::operator::{LineLevel, LinePhysics};
use crate::solve::line::jacobian::JacRow;
use crate::solve::relax::SpikeNewton;
use nalgebra::{DMatrix, DVector};
use std::f64::consts::PI;

/// Nodes added on each side of a node with a large residual.
const HALF_WIDTH: usize = 3;

/// Backtracking halvings of a Newton step before the window gives up.
const MAX_HALVINGS: usize = 12;

/// `factor` times the mean |r| over the pressurised nodes (P > 0) of a level with pressure `p`
/// and residual `r`; infinite where no node is pressurised. The threshold of the Newton windows
/// and of the coarse grids' frozen spike ([`crate::solve::params::MgParams::spike_freeze`]).
pub fn residual_limit(p: &[f64], r: &[f64], factor: f64) -> f64 {
    let (sum, count) = p
        .iter()
        .zip(r)
        .filter(|(&p, _)| p > 0.0)
        .fold((0.0, 0usize), |(s, c), (_, &v)| (s + v.abs(), c + 1));
    if count == 0 {
        f64::INFINITY
    } else {
        factor * sum / count as f64
    }
}

/// The windows of `lv` (closed node ranges, merged where they overlap or touch) around the
/// pressurised, unfrozen nodes with |r| above [`residual_limit`] at `factor`. The residual is
/// computed in the level's work buffer `delta`, whose contents no caller keeps across a sweep.
pub fn windows(lv: &mut LineLevel, phys: &LinePhysics, factor: f64) -> Vec<(usize, usize)> {
    let n = lv.len();
    let mut r = std::mem::take(&mut lv.nodes.delta);
    lv.residual(phys, false, &mut r);
    let limit = residual_limit(&lv.p, &r, factor);
    let mut out: Vec<(usize, usize)> = vec![];
    for i in 1..n - 1 {
        if lv.p[i] > 0.0 && !lv.frozen[i] && r[i].abs() > limit {
            let a = i.saturating_sub(HALF_WIDTH).max(1);
            let b = (i + HALF_WIDTH).min(n - 2);
            match out.last_mut() {
                Some(w) if a <= w.1 + 1 => w.1 = b,
                _ => out.push((a, b)),
            }
        }
    }
    lv.nodes.delta = r;
    out
}

/// Run the Newton windows on `lv` (module doc). Returns the number of windows.
pub fn spike_newton(lv: &mut LineLevel, phys: &LinePhysics, sn: &SpikeNewton) -> usize {
    if phys.dry || phys.rough.is_some() || !phys.elastic || lv.len() < sn.min_points {
        return 0;
    }
    let found = windows(lv, phys, sn.factor);
    for &(a, b) in &found {
        if (a..=b).any(|i| lv.frozen[i]) {
            continue;
        }
        for _ in 0..sn.iterations {
            if !newton_step(lv, phys, a, b) {
                break;
            }
        }
    }
    found.len()
}

/// Sum of r^2 over the window a..=b.
pub fn merit(lv: &LineLevel, phys: &LinePhysics, a: usize, b: usize) -> f64 {
    (a..=b)
        .map(|i| (lv.f[i] - lv.reynolds(phys, i)).powi(2))
        .sum()
}

/// One damped Newton step on the window a..=b; false when no step lowers its merit.
fn newton_step(lv: &mut LineLevel, phys: &LinePhysics, a: usize, b: usize) -> bool {
    let n = lv.len();
    let m = b - a + 1;
    let rhs = DVector::from_fn(m, |r, _| lv.f[a + r] - lv.reynolds(phys, a + r));
    // The window's merit (as [`merit`] sums it) from the residual just computed.
    let m0: f64 = rhs.iter().map(|v| v.powi(2)).sum();
    if m0 == 0.0 {
        return false;
    }
    let rows: Vec<JacRow> = (a..=b).map(|i| JacRow::new(lv, phys, i)).collect();
    let jac = DMatrix::from_fn(m, m, |r, c| rows[r].entry(&lv.kernel, a + c));
    let Some(step) = jac.lu().solve(&rhs) else {
        return false;
    };
    if step.iter().any(|v| !v.is_finite()) {
        return false;
    }
    let (lo, hi) = (a.saturating_sub(HALF_WIDTH), (b + HALF_WIDTH).min(n - 1));
    let p_old: Vec<f64> = lv.p[a..=b].to_vec();
    let film_old: Vec<f64> = lv.film[lo..=hi].to_vec();
    let mut t = 1.0;
    for _ in 0..MAX_HALVINGS {
        for (c, j) in (a..=b).enumerate() {
            lv.p[j] = (p_old[c] + t * step[c]).max(0.0);
        }
        set_window(lv, phys, a, b, lo, hi, &p_old, &film_old);
        if merit(lv, phys, a, b) < (1.0 - 1e-4 * t) * m0 {
            return true;
        }
        t *= 0.5;
    }
    lv.p[a..=b].copy_from_slice(&p_old);
    set_window(lv, phys, a, b, lo, hi, &p_old, &film_old);
    false
}

/// The film of nodes lo..=hi from its old values and the pressure change of a..=b (near kernel
/// terms), with rho, eps and the divisor there from the new P and H.
#[allow(clippy::too_many_arguments)]
fn set_window(
    lv: &mut LineLevel,
    phys: &LinePhysics,
    a: usize,
    b: usize,
    lo: usize,
    hi: usize,
    p_old: &[f64],
    film_old: &[f64],
) {
    let law = phys.coefficients();
    for k in lo..=hi {
        let dh: f64 = (a..=b)
            .zip(p_old)
            .map(|(j, &po)| lv.kernel[k.abs_diff(j)] * (lv.p[j] - po))
            .sum();
        lv.film[k] = film_old[k - lo] - dh / PI;
        let (rho, eps, divisor) = law.at(lv.p[k], lv.film[k]);
        lv.nodes.rho[k] = rho;
        lv.nodes.eps[k] = eps;
        lv.nodes.divisor[k] = divisor;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_residual_limit_is_a_factor_of_the_mean_over_pressurised_nodes() {
        let mut p = [0.0, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0];
        // Pressurised |r|: 1, 3, 1, 3 (mean 2); cavitated nodes do not count.
        let r = [9.0, 1.0, -3.0, 1.0, 3.0, 100.0, 0.0, 0.0, 0.0];
        assert_eq!(residual_limit(&p, &r, 10.0), 20.0);
        p.fill(0.0);
        assert_eq!(residual_limit(&p, &r, 10.0), f64::INFINITY);
    }
}
