//! The discrete line-contact problem on one grid level (Hertzian scaling, PHYSICS.md sections 2, 6b).
//!
//! Nodes X_i = X_in + i h, i = 0..n-1, P_0 = P_{n-1} = 0. At interior nodes
//!
//! L_i(P, H0) = [eps_{i-1/2}(P_{i-1} - P_i) + eps_{i+1/2}(P_{i+1} - P_i)]/h^2 - D_x(rho H)_i = f_i
//!
//! with eps = rho H^3/(eta lambda), eps_{i+-1/2} the mean of the nodal values, and D_x the second
//! order upwind difference (1.5 q_i - 2 q_{i-1} + 0.5 q_{i-2})/h (first order at i = 1, or
//! everywhere when asked). The film is H_i = H0 + X_i^2/2 - (1/pi) sum_j K_{|i-j|} P_j (the sum
//! dropped for rigid surfaces) and the load equation is h sum_i P_i = g. A dry contact replaces L_i by
//! -H_i (the contact condition). On the finest level f = 0
//! and g = pi/2; coarser levels carry the FAS right-hand sides. In the dry limit eps = 0.

use crate::discrete::level::{deref_nodes, NodeFields};
use crate::discrete::line::kernel::{direct_product, log_kernel, DeformPlan1d};
use crate::discrete::physics::Physics;
use crate::discrete::stencil::{flux_difference, upwind, wedge};
use crate::model::case::LineCase;
use std::f64::consts::PI;

/// The physics of a line case in Hertzian scaling, shared by all levels.
pub type LinePhysics = Physics;

impl Physics {
    /// The physics of a line case.
    pub fn from_case(case: &LineCase) -> Self {
        let v = case.venner();
        Physics::of(&case.models, v.lambda, v.alpha_bar).with_roughness(&case.models, v.h_scale)
    }
}

/// One grid level of a line contact: its grid, the deformation kernel and the node fields
/// ([`NodeFields`], which the level dereferences to).
pub struct LineLevel {
    /// Grid spacing (Hertzian units).
    pub h: f64,
    /// Node coordinates X.
    pub x: Vec<f64>,
    /// The node fields.
    pub nodes: NodeFields,
    /// K_d, d = 0..n-1.
    pub kernel: Vec<f64>,
    deform: DeformPlan1d,
    /// Compute the deformation by the O(N^2) direct sum instead of the FFT (baseline).
    pub direct_deformation: bool,
    /// Seconds spent in this level's deformation products so far
    /// ([`crate::solve::phases::PhaseTimes::deformation`]).
    pub deform_seconds: f64,
}

deref_nodes!(LineLevel);

impl LineLevel {
    /// A level with `intervals` intervals on [x_in, x_out], P = 0.
    pub fn new(x_in: f64, x_out: f64, intervals: usize) -> Self {
        let n = intervals + 1;
        let h = (x_out - x_in) / intervals as f64;
        let kernel = log_kernel(n, h);
        LineLevel {
            h,
            x: (0..n).map(|i| x_in + i as f64 * h).collect(),
            nodes: NodeFields::new(n, PI / 2.0),
            deform: DeformPlan1d::new(&kernel),
            kernel,
            direct_deformation: false,
            deform_seconds: 0.0,
        }
    }

    /// Points of the level.
    pub fn points(&self) -> usize {
        self.len()
    }

    /// Nodes of the level (the same as [`LineLevel::points`]).
    pub fn len(&self) -> usize {
        self.x.len()
    }

    /// True for a level without nodes (never built by the solver).
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }

    /// Recompute H (by the fast product), rho and eps from P and H0.
    pub fn update_film(&mut self, phys: &LinePhysics, h0: f64) {
        let n = self.len();
        let start = std::time::Instant::now();
        if phys.elastic && self.direct_deformation {
            direct_product(&self.kernel, &self.nodes.p, &mut self.nodes.work);
        } else if phys.elastic {
            self.deform.apply(&self.nodes.p, &mut self.nodes.work);
        } else {
            self.work.fill(0.0);
        }
        if phys.elastic {
            self.deform_seconds += start.elapsed().as_secs_f64();
        }
        // Mixed lubrication: the asperity deformation joins the fluid's.
        let nodes = &mut self.nodes;
        for (w, &a) in nodes.work.iter_mut().zip(&nodes.asperity_gap) {
            *w += a;
        }
        for i in 0..n {
            self.film[i] = h0 + 0.5 * self.x[i] * self.x[i] + self.work[i];
        }
        self.update_coefficients(phys);
    }

    /// The deformation (film units, as it enters H) by a pressure `field` on this level's nodes,
    /// into `out`: 0 for rigid surfaces.
    pub fn deformation_of(&mut self, phys: &LinePhysics, field: &[f64], out: &mut [f64]) {
        if !phys.elastic {
            out.fill(0.0);
            return;
        }
        let start = std::time::Instant::now();
        if self.direct_deformation {
            direct_product(&self.kernel, field, out);
        } else {
            self.deform.apply(field, out);
        }
        self.deform_seconds += start.elapsed().as_secs_f64();
    }

    /// `fine_field` (on the nodes of a finer level of the same domain) at this level's nodes.
    pub fn inject_field(&self, fine: &LineLevel, fine_field: &[f64]) -> Vec<f64> {
        let step = (fine.len() - 1) / (self.len() - 1);
        (0..self.len()).map(|i| fine_field[i * step]).collect()
    }

    /// The area of one cell, h (the load is cell_area x sum P).
    pub fn cell_area(&self) -> f64 {
        self.h
    }

    /// Recompute rho and eps from P and the current H.
    pub fn update_coefficients(&mut self, phys: &LinePhysics) {
        self.nodes.update_coefficients(phys.coefficients());
    }

    /// L_i, the discrete Reynolds operator at interior node i.
    #[inline]
    pub fn reynolds(&self, phys: &LinePhysics, i: usize) -> f64 {
        if phys.dry {
            return -self.film[i];
        }
        let h = self.h;
        let pois = flux_difference(&self.eps, &self.p, i, 1) / (h * h);
        let w = upwind(phys.second_order, i);
        pois - wedge(w, &self.rho, self.wedge_film(), i) / h
    }

    /// r_i = f_i - L_i at interior nodes, 0 at the boundaries; with `active_only`, 0 also where
    /// P_i = 0 (the cavitated set, where the complementarity condition replaces the equation).
    pub fn residual(&self, phys: &LinePhysics, active_only: bool, out: &mut [f64]) {
        let n = self.len();
        out[0] = 0.0;
        out[n - 1] = 0.0;
        for i in 1..n - 1 {
            out[i] = if active_only && self.p[i] <= 0.0 {
                0.0
            } else {
                self.f[i] - self.reynolds(phys, i)
            };
        }
    }

    /// h sum_i P_i (trapezoid rule with P = 0 at both ends).
    pub fn load(&self) -> f64 {
        self.h * self.p.iter().sum::<f64>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discrete::testing::isoviscous_incompressible;

    #[test]
    fn rigid_reynolds_operator_is_second_order() {
        // Manufactured check: for P(X) = exp(-X^2), H = 1 + X^2/2 (rigid, incompressible, lambda = 1),
        // L = (H^3 P')' - H' exactly; the discrete operator converges at second order.
        let phys = LinePhysics {
            lambda: 1.0,
            fluid: isoviscous_incompressible(),
            elastic: false,
            dry: false,
            second_order: true,
            rough: None,
            fluid_share: 1.0,
        };
        let exact = |x: f64| {
            let hh = 1.0 + 0.5 * x * x;
            let p1 = -2.0 * x * (-x * x).exp();
            let p2 = (4.0 * x * x - 2.0) * (-x * x).exp();
            3.0 * hh * hh * x * p1 + hh * hh * hh * p2 - x
        };
        let mut errs = vec![];
        for n in [64usize, 128, 256] {
            let mut lv = LineLevel::new(-4.0, 4.0, n);
            for i in 0..lv.len() {
                lv.p[i] = (-lv.x[i] * lv.x[i]).exp();
            }
            lv.update_film(&phys, 1.0);
            let i = lv.len() / 2 + n / 8; // X = 1
            errs.push((lv.reynolds(&phys, i) - exact(lv.x[i])).abs());
        }
        let rate = (errs[1] / errs[2]).log2();
        assert!(rate > 1.8 && rate < 2.2, "rate {rate}, errs {errs:?}");
    }
}
