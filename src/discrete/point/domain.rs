//! The computational domain and the coarsest grid of a point contact, chosen from (M, L, D).
//!
//! Units: Hertzian X = x/b, Y = y/b; the Hertz contact is the ellipse X^2 + (Y/k)^2 <= 1,
//! k = a/b. Inputs: the Moes parameters (M, L, D), k and h_scale = H_Moes/H_Hertzian of the
//! case, whether the surfaces are rigid, and [`PointDomainParams`]. Let
//!
//! * H_e = H_NVM / h_scale, the Nijenbanning-Venner-Moes 1994 central-film estimate in Hertzian
//!   units (for rigid surfaces (H_RI^3 + H_RP^3)^(1/3) of the NVM asymptotes alone);
//! * l_h = sqrt(2 H_e), the hydrodynamic length (the rigid gap H_e + X^2/2 doubles over it);
//! * w = min(1, H_RI/H_NVM)^2 (NVM's rigid-isoviscous asymptote over its film), the weight of the
//!   rigid-isoviscous regime (w = 1 for rigid surfaces), and g = 1 + w.
//!
//! Output: the domain [X_in, X_out] x [-Y_half, Y_half] with
//!
//! * inlet   X_in   = -max(1 + clamp(inlet_elastic H_e^(2/3), 0.5, 3.5), g inlet_lh l_h)
//! * outlet  X_out  =  max(1.5, g outlet_lh l_h)
//! * sides   Y_half =  max(k + clamp(inlet_elastic H_e^(2/3), side_thin, side) / sqrt(D k),
//!   g side_lh l_h / sqrt(D))
//!
//! and for rigid surfaces (no Hertzian zone) g [-inlet_lh l_h, outlet_lh l_h] x
//! [-side_lh l_h/sqrt(D), side_lh l_h/sqrt(D)]. Defaults: inlet_elastic = 20, inlet_lh = 4.5,
//! outlet_lh = 1.5, side = 2, side_thin = 0.5, side_lh = 3; at M = 20, L = 10, D = 1 this is
//! the classic [-4.5, 1.5] x [-3, 3].
//!
//! Rationale (docs/method.md, Point contact): the elastic inlet shrinks towards -1.5 for thin
//! films (high M), where a fixed -4.5 leaves too few points across the contact, and the side
//! margin with it (towards k + 0.5 at D = 1): outside the Hertzian ellipse the elastic gap grows
//! like the 3/2 power of the distance from its edge across the rolling direction as along it, and
//! the side lobes of the film, where H_min lies, need the points; the l_h terms
//! make the domain grow with the rigid pressure, which spreads over several l_h; across the
//! rolling direction the gap grows like D k (|Y| - k) beyond the contact edge, hence the margin
//! 1/sqrt(D k), and with D Y^2/2 in the gap the rigid side extent is stretched by 1/sqrt(D).
//!
//! Invariants: the coarsest grid has `n0` intervals per direction (a power of two, at least 4;
//! 16 by default, 17^2 nodes for the exact Newton solve; at least `n0_thin` = 32 for a thin
//! elastic film, one whose side margin inlet_elastic H_e^(2/3) is below `side`: a 17^2 grid on
//! the narrower domain leaves the thin film's Newton start a few nodes across the contact, and
//! its first cycles diverged at M = 1000, L = 0, D = 1), and X_in is shifted so that X = 0 is a
//! node of every level (Y = 0 is one by symmetry).
//!
//! **Truncation estimate.** A rigid-like contact's pressure decays slowly into the inlet and the
//! sides, so a truncated domain (P = 0 on its boundary) carries less load at a given film and H
//! comes out low; the asymptotic far field ([`PointDomainParams::far_field`], the default;
//! [`crate::discrete::point::far_field`]) removes most of the bias, and the estimates below
//! then use its own measured constants.
//! [`PointDomain::bias`] = [`DOMAIN_BIAS_PER_W`] w estimates the rise of H_c and H_min when the
//! inlet and side extents are doubled, and [`PointDomain::truncation_error`] =
//! [`TRUNCATION_OVER_BIAS`] times the bias the total error of the default domain. A point
//! solve's reason carries a caution where the bias is [`BIAS_CAUTION`] or more; the fit leaves
//! out rows whose truncation estimate is above 2 %. (Measurements: docs/known-limits.md, "Point
//! contacts on the truncated domain are biased low below M of about 10-20".)

use crate::discrete::grid::align_origin;
use crate::model::formulas::{nvm_point_asymptotes, nvm_point_hc};

/// Relative rise of H_c and H_min per unit rigid weight w when the inlet and side extents are
/// doubled: the slope of the doubling measurements in docs/known-limits.md (used by
/// [`PointDomain::bias`]).
pub const DOMAIN_BIAS_PER_W: f64 = 0.25;

/// The largest [`PointDomain::bias`] with the asymptotic far field on the boundary
/// ([`PointDomainParams::far_field`]): doubling the domain changed H_c and H_min by at most
/// 0.09 % on rigid-like contacts and at most 0.20 % between them and the Hertzian regime (L = 0,
/// M 5-100, D 1-0.03, tight convergence, grid-extrapolated; docs/validation.md, "Far field";
/// tests/far_field.rs); 0.3 % bounds them.
pub const FAR_FIELD_BIAS: f64 = 0.003;

/// [`TRUNCATION_OVER_BIAS`] with the far field: the second doubling at (5, 1) moved the film
/// by 0.016 % and 0.022 %, a tenth of the first, so all later doublings add about 1.1 times the
/// first; 1.5 covers them.
pub const FAR_FIELD_TRUNCATION_OVER_BIAS: f64 = 1.5;

/// [`PointDomain::bias`] from which a point solve's reason carries a caution ("rigid-like case").
pub const BIAS_CAUTION: f64 = 0.01;

/// The truncation error of the default domain over its first doubling change
/// [`PointDomain::bias`]: the changes of all successive doublings sum to r/(r - 1) times the
/// first when they shrink by r per doubling; 2.5 is that sum for the slowest measured shrink
/// (docs/known-limits.md).
pub const TRUNCATION_OVER_BIAS: f64 = 2.5;

/// Tunable constants of the domain rule (module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointDomainParams {
    /// Elastic inlet margin beyond X = -1, in units of H_e^(2/3) (clamped to [0.5, 3.5]).
    pub inlet_elastic: f64,
    /// Inlet length in hydrodynamic lengths l_h, before the rigid factor g.
    pub inlet_lh: f64,
    /// Outlet length in l_h, before g.
    pub outlet_lh: f64,
    /// Side margin beyond Y = k, in units of 1/sqrt(D k), of thick films.
    pub side: f64,
    /// The least side margin, in units of 1/sqrt(D k), that thin films shrink it to (module
    /// doc; `side` or more keeps the margin of thick films at every film).
    pub side_thin: f64,
    /// Side half-width in l_h/sqrt(D), before g.
    pub side_lh: f64,
    /// Intervals per direction of the coarsest grid.
    pub n0: usize,
    /// The least intervals per direction of the coarsest grid of a thin elastic film, one whose
    /// side margin shrinks (module doc).
    pub n0_thin: usize,
    /// The asymptotic far field on the boundary ([`crate::discrete::point::far_field`]):
    /// boundary values and the load beyond the domain from the r^-3 decay instead of P = 0
    /// (default on; off: the truncated domain of the classic references).
    pub far_field: bool,
}

impl Default for PointDomainParams {
    fn default() -> Self {
        PointDomainParams {
            inlet_elastic: 20.0,
            inlet_lh: 4.5,
            outlet_lh: 1.5,
            side: 2.0,
            side_thin: 0.5,
            side_lh: 3.0,
            n0: 16,
            n0_thin: 32,
            far_field: true,
        }
    }
}

impl PointDomainParams {
    /// These constants with every extent of the domain rule (inlet, outlet and side, elastic
    /// and l_h-scaled) multiplied by `factor`: the domain scaled about the contact. (Scaling it
    /// at equal spacing needs the grid's intervals scaled too.)
    pub fn scaled(self, factor: f64) -> Self {
        PointDomainParams {
            inlet_elastic: factor * self.inlet_elastic,
            inlet_lh: factor * self.inlet_lh,
            outlet_lh: factor * self.outlet_lh,
            side: factor * self.side,
            side_thin: factor * self.side_thin,
            side_lh: factor * self.side_lh,
            ..self
        }
    }
}

/// A point-contact domain [x_in, x_out] x [-y_half, y_half] (Hertzian units) with n0 x n0
/// coarsest intervals; X = 0 lies on a node of every level.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointDomain {
    /// Inlet end X_in of the domain along the rolling direction (Hertzian units).
    pub x_in: f64,
    /// Outlet end X_out.
    pub x_out: f64,
    /// Half width of the domain across the rolling direction: Y in [-y_half, y_half].
    pub y_half: f64,
    /// Intervals per direction of the coarsest grid (a power of two, at least 4).
    pub n0: usize,
    /// Central film estimate (Hertzian units).
    pub h_estimate: f64,
    /// Weight w of the rigid-isoviscous regime (1 for rigid surfaces).
    pub rigid_weight: f64,
    /// Whether the boundary carries the asymptotic far field ([`PointDomainParams::far_field`]).
    pub far_field: bool,
}

impl PointDomain {
    /// The rule of the module doc for Moes parameters (m, l, d); `k` = a/b and `h_scale` =
    /// H_Moes/H_Hertzian of the case.
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
        let elastic_margin = p.inlet_elastic * h_e.powf(2.0 / 3.0);
        let side_margin = elastic_margin.clamp(p.side_thin.min(p.side), p.side);
        let (x_in, x_out, y_half) = if rigid {
            (
                -g * p.inlet_lh * lh,
                g * p.outlet_lh * lh,
                g * p.side_lh * lh / d.sqrt(),
            )
        } else {
            (
                -(1.0 + elastic_margin.clamp(0.5, 3.5)).max(g * p.inlet_lh * lh),
                (1.5f64).max(g * p.outlet_lh * lh),
                (k + side_margin / (d * k).sqrt()).max(g * p.side_lh * lh / d.sqrt()),
            )
        };
        // A thin film: the elastic margin is below the side margin of thick films.
        let thin = !rigid && elastic_margin < p.side;
        let n0 = if thin { p.n0.max(p.n0_thin) } else { p.n0 };
        let n0 = n0.max(4).next_power_of_two();
        let (x_in, x_out) = align_origin(x_in, x_out, n0);
        PointDomain {
            x_in,
            x_out,
            y_half,
            n0,
            h_estimate: h_e,
            rigid_weight: w,
            far_field: p.far_field,
        }
    }

    /// Estimated relative change of H_c and H_min when the domain is doubled:
    /// [`DOMAIN_BIAS_PER_W`] times the rigid weight (a lower bound of how far the truncated
    /// domain biases H low), with the far field at most [`FAR_FIELD_BIAS`].
    pub fn bias(&self) -> f64 {
        let truncated = DOMAIN_BIAS_PER_W * self.rigid_weight;
        if self.far_field {
            truncated.min(FAR_FIELD_BIAS)
        } else {
            truncated
        }
    }

    /// Estimated relative error of H_c and H_min from the truncation of the domain:
    /// [`TRUNCATION_OVER_BIAS`] times [`PointDomain::bias`] ([`FAR_FIELD_TRUNCATION_OVER_BIAS`]
    /// with the far field).
    pub fn truncation_error(&self) -> f64 {
        let over = if self.far_field {
            FAR_FIELD_TRUNCATION_OVER_BIAS
        } else {
            TRUNCATION_OVER_BIAS
        };
        over * self.bias()
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

    #[test]
    fn thin_films_shrink_the_side_margin_and_refine_the_coarsest_grid() {
        use crate::model::case::PointCase;
        let p = PointDomainParams::default();
        let wide = PointDomainParams {
            side_thin: p.side,
            ..p
        };
        let dom = |m: f64, l: f64, d: f64, q: &PointDomainParams| {
            PointDomain::of_case(&PointCase::new(m, l, d).unwrap(), q)
        };
        // Thick film: the classic sides and coarsest grid.
        let thick = dom(20.0, 10.0, 1.0, &p);
        assert_eq!((thick.y_half, thick.n0), (3.0, 16), "{thick:?}");
        // Thin film (H_e = 1.7e-3 Hertzian): the margin at its floor, k + 0.5, and 33^2.
        let thin = dom(5720.0, 0.0, 1.0, &p);
        assert!(thin.h_estimate < 2e-3, "{thin:?}");
        assert!((thin.y_half - 1.5).abs() < 1e-12, "{thin:?}");
        assert_eq!(thin.n0, 32);
        let coarse = PointDomainParams { n0_thin: 16, ..p };
        assert_eq!(dom(5720.0, 0.0, 1.0, &coarse).n0, 16);
        // Between them the margin is 20 H_e^(2/3) / sqrt(D k).
        let mid = dom(1000.0, 0.0, 1.0, &p);
        let margin = 20.0 * mid.h_estimate.powf(2.0 / 3.0);
        assert!(margin > 0.5 && margin < 2.0, "{mid:?}");
        assert!((mid.y_half - (1.0 + margin)).abs() < 1e-12, "{mid:?}");
        // The side rule leaves the rolling direction alone, and side_thin = side is the wide
        // side margin of thick films at every film.
        for (m, l, d) in [(5720.0, 0.0, 1.0), (1000.0, 0.0, 0.25), (3e4, 10.0, 0.01)] {
            let (a, b) = (dom(m, l, d, &p), dom(m, l, d, &wide));
            assert_eq!((a.x_in, a.x_out), (b.x_in, b.x_out), "M = {m}, D = {d}");
            assert!(a.y_half < b.y_half, "M = {m}, D = {d}");
            assert_eq!((a.n0, b.n0), (32, 32));
            let k = PointCase::new(m, l, d).unwrap().venner().k;
            assert!(
                (b.y_half - (k + 2.0 / (d * k).sqrt())).abs() < 1e-9,
                "{b:?}"
            );
        }
    }
}
