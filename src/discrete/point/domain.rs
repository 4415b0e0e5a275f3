//! The computational domain and the coarsest grid of a point contact, chosen from (M, L, D).
//!
//! Hertzian units X = x/b, Y = y/b: the Hertz contact is the ellipse X^2 + (Y/k)^2 <= 1. Let H_e be
//! the Nijenbanning-Venner-Moes estimate of the central film in these units (H_NVM / h_scale; for
//! rigid surfaces the rigid asymptotes alone) and l_h = sqrt(2 H_e) the hydrodynamic length, the
//! distance over which the rigid gap H_e + X^2/2 doubles. Then
//!
//! * inlet   X_in   = -max(1 + clamp(inlet_elastic H_e^(2/3), 0.5, 3.5), g inlet_lh l_h)
//! * outlet  X_out  =  max(1.5, g outlet_lh l_h)
//! * sides   Y_half =  max(k + side / sqrt(D k), g side_lh l_h / sqrt(D))
//!
//! with g = 1 + w, w = min(1, H_RI/H_e)^2 the weight of the rigid-isoviscous regime (w = 1 for
//! rigid surfaces): the rigid pressure spreads over several l_h, and at M = 1, D = 1 the inlet
//! 4.5 l_h cut H_c by 25 % against 9 l_h (measured on 129^2).
//!
//! (defaults inlet_elastic = 20, inlet_lh = 4.5, outlet_lh = 1.5, side = 2, side_lh = 3). At
//! M = 20, L = 10, D = 1 this is the classic [-4.5, 1.5] x [-3, 3]. The inlet shrinks towards -1.5
//! for thin films (high M), where a fixed -4.5 leaves too few points across the contact, and grows
//! with l_h for thick ones (low M, rigid), where the pressure spreads over a few l_h. Across the
//! rolling direction the gap grows like D k (|Y| - k) beyond the contact edge, so the margin
//! beyond k grows like 1/sqrt(D k) for slender contacts. For rigid surfaces there is no Hertzian
//! zone: g [-inlet_lh l_h, outlet_lh l_h] x [-side_lh l_h, side_lh l_h] (with D Y^2/2 in the gap the
//! side extent is stretched by 1/sqrt(D)).
//!
//! **Truncation bias.** The pressure of a rigid-like contact spreads far into the inlet and decays
//! slowly, and a truncated domain carries less load at a given film, so H comes out low. Doubling
//! the inlet and side extents (257^2 nodes) raised H_c or H_min by 18 % at (M, L, D) = (1, 0, 1)
//! (w = 0.99), 18 % at (3, 0, 0.25) (w = 0.98), 10 % at (3, 10, 1) (w = 0.52), 9 % at (5, 0, 1)
//! (w = 0.42), 3.6 % at (20, 0, 0.25) (w = 0.15), 1.3 % at (10, 0, 1) (w = 0.06), 1.0 % at
//! (10, 10, 1) (w = 0.007, the elastic inlet) and 0.1 % at (30, 0, 1): about
//! [`DOMAIN_BIAS_PER_W`] w. The change shrinks only by a factor of about 1.65 per doubling
//! (at (3, 0, 1): +15 %, then +8 %), so the bias of the default domain is larger still (about
//! 30 % at M = 3, D = 1); uniform grids cannot reach 1 % there. [`PointDomain::bias`] is reported
//! with every point solve where it is 1 % or more, and the fit leaves such rows out.
//!
//! The coarsest grid has `n0` intervals per direction (16 by default: about 300 unknowns for the
//! exact Newton solve); the domain is shifted so that X = 0 is a node of every level (Y = 0 is one
//! by symmetry).

use crate::model::formulas::{nvm_point_asymptotes, nvm_point_hc};

/// Relative change of H_c and H_min per unit rigid weight w when the domain is doubled (see the
/// module doc): the domain-sensitivity estimate [`PointDomain::bias`].
pub const DOMAIN_BIAS_PER_W: f64 = 0.25;

/// [`PointDomain::bias`] from which a point solve's reason carries a caution.
pub const BIAS_CAUTION: f64 = 0.01;

/// The truncation error of the default domain over its doubling change [`PointDomain::bias`]:
/// the change shrank by a factor of 1.65 per doubling at (M, L, D) = (3, 0, 1) and 2.3 at the
/// rigid M = 1, so the sum of all further doublings is 1.75-2.5 times the first.
pub const TRUNCATION_OVER_BIAS: f64 = 2.5;

/// Tunable constants of the domain rule.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointDomainParams {
    pub inlet_elastic: f64,
    pub inlet_lh: f64,
    pub outlet_lh: f64,
    pub side: f64,
    pub side_lh: f64,
    /// Intervals per direction of the coarsest grid.
    pub n0: usize,
}

impl Default for PointDomainParams {
    fn default() -> Self {
        PointDomainParams {
            inlet_elastic: 20.0,
            inlet_lh: 4.5,
            outlet_lh: 1.5,
            side: 2.0,
            side_lh: 3.0,
            n0: 16,
        }
    }
}

/// A point-contact domain [x_in, x_out] x [-y_half, y_half] with n0 x n0 coarsest intervals.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointDomain {
    pub x_in: f64,
    pub x_out: f64,
    pub y_half: f64,
    pub n0: usize,
    /// Central film estimate (Hertzian units).
    pub h_estimate: f64,
    /// Weight w of the rigid-isoviscous regime (1 for rigid surfaces).
    pub rigid_weight: f64,
}

impl PointDomain {
    /// The rule above; `h_scale` = H_Moes/H_Hertzian and `k` = a/b of the case.
    #[allow(clippy::too_many_arguments)]
    pub fn for_case(
        m: f64,
        l: f64,
        d: f64,
        k: f64,
        h_scale: f64,
        rigid: bool,
        p: &PointDomainParams,
    ) -> Self {
        let h_moes = if rigid {
            let [h_ri, _, h_rp, _, _] = nvm_point_asymptotes(m, l, d);
            (h_ri.powi(3) + h_rp.powi(3)).cbrt()
        } else {
            nvm_point_hc(m, l, d)
        };
        let h_e = h_moes / h_scale;
        let lh = (2.0 * h_e).sqrt();
        // Weight of the rigid-isoviscous regime: the l_h-scaled extents double as it takes over.
        let w = if rigid {
            1.0
        } else {
            (nvm_point_asymptotes(m, l, d)[0] / h_moes).min(1.0).powi(2)
        };
        let g = 1.0 + w;
        let (x_in, x_out, y_half) = if rigid {
            (
                -g * p.inlet_lh * lh,
                g * p.outlet_lh * lh,
                g * p.side_lh * lh / d.sqrt(),
            )
        } else {
            (
                -(1.0 + (p.inlet_elastic * h_e.powf(2.0 / 3.0)).clamp(0.5, 3.5))
                    .max(g * p.inlet_lh * lh),
                (1.5f64).max(g * p.outlet_lh * lh),
                (k + p.side / (d * k).sqrt()).max(g * p.side_lh * lh / d.sqrt()),
            )
        };
        let n0 = p.n0.max(4).next_power_of_two();
        let h0 = (x_out - x_in) / n0 as f64;
        let i0 = (-x_in / h0).round().clamp(1.0, n0 as f64 - 1.0);
        let x_in = -i0 * h0;
        PointDomain {
            x_in,
            x_out: x_in + n0 as f64 * h0,
            y_half,
            n0,
            h_estimate: h_e,
            rigid_weight: w,
        }
    }

    /// Estimated relative rise of H_c and H_min when the domain is doubled, `DOMAIN_BIAS_PER_W`
    /// times the rigid weight: a lower bound of how far the truncated domain biases H low.
    pub fn bias(&self) -> f64 {
        DOMAIN_BIAS_PER_W * self.rigid_weight
    }

    /// Estimated relative error of H_c and H_min from the truncation of the domain (H is low by
    /// about this much): `TRUNCATION_OVER_BIAS` times [`PointDomain::bias`].
    pub fn truncation_error(&self) -> f64 {
        TRUNCATION_OVER_BIAS * self.bias()
    }

    /// The domain of a point case with the domain constants `p`.
    pub fn of_case(case: &crate::model::case::PointCase, p: &PointDomainParams) -> Self {
        let v = case.venner();
        let rigid = case.models.elasticity == crate::model::case::Elasticity::Rigid;
        Self::for_case(case.m, case.l, case.d, v.k, v.h_scale, rigid, p)
    }

    /// Index (i, j) of X = Y = 0 on a grid with n intervals per direction (a multiple of n0).
    pub fn centre(&self, n: usize) -> (usize, usize) {
        let i = (-self.x_in / (self.x_out - self.x_in) * n as f64).round() as usize;
        (i, n / 2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classic_domain_for_the_reference_case() {
        let d = PointDomain::for_case(20.0, 10.0, 1.0, 1.0, 9.655, false, &Default::default());
        assert!(
            (d.x_in + 4.5).abs() < 0.2 && (d.x_out - 1.5).abs() < 0.2,
            "{d:?}"
        );
        assert!((d.y_half - 3.0).abs() < 1e-12, "{d:?}");
        let n = 128;
        let (i, j) = d.centre(n);
        let h = (d.x_out - d.x_in) / n as f64;
        assert!((d.x_in + i as f64 * h).abs() < 1e-9 && j == 64);
    }
}
