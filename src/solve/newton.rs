//! Damped Newton-Raphson for a discrete contact problem on one level (line or point,
//! through [`NewtonLevel`]; the line contact's Jacobian is built here) (dense Jacobian, LU from
//! nalgebra), with the cavitation condition as a semi-smooth active set.
//!
//! Unknowns: P_1..P_{n-2} and H0. Equations: L_i(P, H0) = f_i on the pressurised set, P_i = 0 on the
//! cavitated set, h sum P = g. The Jacobian is exact: with q = rho H and eps = rho H^3/(eta lambda),
//! dL_i/dP_j collects the Poiseuille stencil, the local dependence of eps and rho on P_j, and the
//! film response dH_m/dP_j = -(1/pi) K_{|m-j|} of eps_m (m = i-1, i, i+1) and of the wedge term
//! (m = i-2..i); dH_m/dH0 = 1. Node i is pressurised when its Newton point value
//! t_i = P_i + (f_i - L_i)/J_ii is positive (complementarity P >= 0, L - f <= 0, P (L - f) = 0).
//! Steps are damped by backtracking on the semi-smooth residual norm.
//!
//! Used as the exact coarsest-grid solver of the multigrid and as the Newton baseline.

use crate::discrete::line::operator::{LineLevel, LinePhysics};
use crate::solve::line::jacobian::JacRow;
use nalgebra::{DMatrix, DVector};

/// Newton settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonParams {
    pub max_iter: usize,
    /// Converged when the scaled residual norm is below this.
    pub tol: f64,
    /// Hold H0 fixed and drop the load equation.
    pub fix_h0: bool,
}

impl Default for NewtonParams {
    fn default() -> Self {
        NewtonParams {
            max_iter: 40,
            tol: 1e-10,
            fix_h0: false,
        }
    }
}

/// Result of a Newton solve on one level.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonOutcome {
    pub iterations: usize,
    pub converged: bool,
    /// Final scaled residual norm.
    pub residual: f64,
    /// Whether the linear solve ever failed (singular Jacobian).
    pub singular: bool,
}

struct Linearisation {
    jac: DMatrix<f64>,
    rhs: DVector<f64>,
    merit: f64,
}

/// The exact Jacobian of (L_1..L_{n-2}, h sum P) with respect to (P_1..P_{n-2}, H0) at the
/// current state (film must be up to date).
pub fn jacobian(lv: &LineLevel, phys: &LinePhysics) -> DMatrix<f64> {
    let n = lv.len();
    let m = n - 1; // n-2 pressures + H0
    let hcol = n - 2;
    let mut jac = DMatrix::<f64>::zeros(m, m);
    for i in 1..n - 1 {
        let row = JacRow::new(lv, phys, i);
        for j in 1..n - 1 {
            jac[(i - 1, j - 1)] = row.entry(&lv.kernel, j);
        }
        jac[(i - 1, hcol)] = row.d_h0();
    }
    for j in 1..n - 1 {
        jac[(hcol, j - 1)] = lv.h;
    }
    jac
}

/// A discrete level that Newton can solve: unknown pressures at the interior nodes (storage
/// indices from [`NewtonLevel::unknowns`]) and H0.
pub trait NewtonLevel {
    type Phys;
    /// Storage indices of the unknown pressures, in Jacobian order.
    fn unknowns(&self) -> Vec<usize>;
    /// The exact Jacobian of (L at the unknowns, the load sum) with respect to (the unknowns, H0),
    /// H0 last (film must be up to date).
    fn dense_jacobian(&self, phys: &Self::Phys, unknowns: &[usize]) -> DMatrix<f64>;
    /// f - L at storage index c.
    fn residual_at(&self, phys: &Self::Phys, c: usize) -> f64;
    fn frozen_at(&self, c: usize) -> bool;
    fn pressure(&mut self) -> &mut [f64];
    fn load_sum(&self) -> f64;
    fn load_rhs(&self) -> f64;
    /// Recompute the film and coefficients for H0.
    fn refresh(&mut self, phys: &Self::Phys, h0: f64);
}

impl NewtonLevel for LineLevel {
    type Phys = LinePhysics;
    fn unknowns(&self) -> Vec<usize> {
        (1..self.len() - 1).collect()
    }
    fn dense_jacobian(&self, phys: &LinePhysics, _unknowns: &[usize]) -> DMatrix<f64> {
        jacobian(self, phys)
    }
    fn residual_at(&self, phys: &LinePhysics, c: usize) -> f64 {
        self.f[c] - self.reynolds(phys, c)
    }
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
    fn refresh(&mut self, phys: &LinePhysics, h0: f64) {
        self.update_film(phys, h0)
    }
}

/// Estimate dG/dH0 (G = load sum - g) on a level solved at `h0`: solve again at fixed H0 + dh
/// and difference the load; P and the film are restored afterwards. Falls back to `fallback`
/// when that solve fails or the slope is not negative. Returns the slope and the Newton
/// iterations spent.
pub fn load_slope<T: NewtonLevel>(
    lv: &mut T,
    phys: &T::Phys,
    h0: f64,
    dh: f64,
    fallback: f64,
) -> (f64, usize) {
    let saved = lv.pressure().to_vec();
    let e0 = lv.load_sum() - lv.load_rhs();
    let mut h1 = h0 + dh;
    let np = NewtonParams {
        fix_h0: true,
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

/// Build the semi-smooth Newton system at the current state (film must be up to date).
fn linearise<T: NewtonLevel>(
    lv: &mut T,
    phys: &T::Phys,
    unknowns: &[usize],
    fix_h0: bool,
) -> Linearisation {
    let m = unknowns.len();
    let hcol = m;
    let mut jac = lv.dense_jacobian(phys, unknowns);
    let mut rhs = DVector::<f64>::zeros(m + 1);
    let mut merit = 0.0;
    for (row, &c) in unknowns.iter().enumerate() {
        let r = lv.residual_at(phys, c);
        let d = jac[(row, row)];
        let p = lv.pressure()[c];
        let t = if d < 0.0 { p + r / d } else { p };
        if lv.frozen_at(c) {
            jac.row_mut(row).fill(0.0);
            jac[(row, row)] = 1.0;
            rhs[row] = 0.0;
        } else if t > 0.0 {
            rhs[row] = r;
            let s = if d != 0.0 { r / d } else { r };
            merit += s * s;
        } else {
            jac.row_mut(row).fill(0.0);
            jac[(row, row)] = 1.0;
            rhs[row] = -p;
            merit += p * p;
        }
    }
    if fix_h0 {
        jac.row_mut(hcol).fill(0.0);
        jac[(hcol, hcol)] = 1.0;
        rhs[hcol] = 0.0;
    } else {
        let g = lv.load_rhs();
        let lr = g - lv.load_sum();
        rhs[hcol] = lr;
        merit += (lr / g) * (lr / g);
    }
    Linearisation {
        jac,
        rhs,
        merit: merit.sqrt(),
    }
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
    lv.refresh(phys, *h0);
    let mut lin = linearise(lv, phys, &unknowns, np.fix_h0);
    let mut out = NewtonOutcome {
        iterations: 0,
        converged: false,
        residual: lin.merit,
        singular: false,
    };
    let mut p_old = vec![0.0; m];
    for it in 0..np.max_iter {
        if lin.merit < np.tol {
            out.converged = true;
            break;
        }
        out.iterations = it + 1;
        let Some(step) = lin.jac.clone().lu().solve(&lin.rhs) else {
            out.singular = true;
            break;
        };
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
            let trial = linearise(lv, phys, &unknowns, np.fix_h0);
            if trial.merit.is_finite() && trial.merit < lin.merit * (1.0 - 1e-4 * alpha) {
                lin = trial;
                accepted = true;
                break;
            }
            alpha *= 0.5;
        }
        if !accepted {
            // Keep the smallest step anyway: the active set may have to change to make progress.
            lin = linearise(lv, phys, &unknowns, np.fix_h0);
        }
        out.residual = lin.merit;
    }
    if lin.merit < np.tol {
        out.converged = true;
    }
    out.residual = lin.merit;
    out
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
        let jac = jacobian(&lv, &phys);
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
}
