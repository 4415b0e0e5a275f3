//! The computational domain and the coarsest grid of a line contact, chosen from (M, L).
//!
//! Units: Hertzian X = x/b. Inputs: the Moes parameters (M, L), whether the surfaces are rigid,
//! [`DomainParams`] and the finest grid's interval count (which caps n0). Let
//!
//! * H_e = H_Moes pi/(8M), the Moes 1992 central-film estimate in Hertzian units (for rigid
//!   surfaces (H_RI^3 + H_RP^3)^(1/3) of Moes' asymptotes alone);
//! * l_h = sqrt(2 H_e), the hydrodynamic length (the rigid gap H_e + X^2/2 doubles over it);
//! * w = min(1, H_RI/H_Moes)^2, the weight of the rigid-isoviscous regime (w = 1 for rigid
//!   surfaces).
//!
//! Output: the domain [X_in, X_out] with
//!
//! * inlet  X_in  = -max(1 + clamp(inlet_elastic H_e^(2/3), 0.5, 3.5), (inlet_factor + w inlet_rigid) l_h)
//! * outlet X_out =  max(min_outlet, outlet_factor l_h)
//!
//! and for rigid surfaces (no Hertzian zone) [-(inlet_factor + inlet_rigid) l_h, outlet_factor l_h]
//! for any M. Defaults: inlet_elastic = 20, inlet_factor = 16, inlet_rigid = 32,
//! outlet_factor = min_outlet = 1.5.
//!
//! Rationale (docs/method.md, Line contact): outside the Hertzian zone the elastic gap grows like
//! (|X| - 1)^(3/2) and reaches about 100 H_e at |X| - 1 ~ 20 H_e^(2/3); that inlet is capped at
//! Venner's classic -4.5 for thick films and shrinks towards -1.5 at high M, where a fixed
//! [-4.5, 1.5] wastes most points on a dry inlet and leaves too few across the thin film. As
//! M -> 0 the contact is rigid and every length scales with l_h (the Martin pressure decays like
//! |X|^-3 into the inlet and cavitates at X = 0.475 l_h), so the domain grows with l_h and the
//! relative inlet truncation error of H_c stays a fixed fraction, about 3.8/factor^2 for an inlet
//! of factor l_h (figures: docs/validation.md, Line contacts).
//!
//! Coarsest grid: the fewest intervals n0 (a power of two, at least 16, at most the finest
//! grid's) with spacing h0 <= max(min(coarse_h_max max(1, l_h/2), coarse_lh l_h), 0.4 w l_h),
//! for rigid surfaces h0 <= 0.4 l_h: coarse grids that cannot see the film (h0 much larger than
//! l_h at high M) make corrections of the wrong kind, and rigid-like films (w -> 1) have no
//! feature finer than l_h (at M = 0.01 the elastic term alone asks for n0 = 1024, whose dense
//! coarsest solve took 2-3 s of a 0.04 s solve on 4097 points), and n0 is at most
//! [`MAX_COARSEST_INTERVALS`]: the coarsest solve is dense, and above M of about 2e4 (L = 0) the
//! spacing rule would give it thousands of unknowns (hours per solve); there the coarse grids
//! cannot see the film and the solve fails in minutes instead (docs/known-limits.md).
//! Invariant: X_in is shifted so that X = 0 is a node of every level.

use crate::discrete::grid::align_origin;
use crate::model::formulas::{moes_line_asymptotes, moes_line_hc};
use std::f64::consts::PI;

/// The coarsest spacing of rigid surfaces, in hydrodynamic lengths l_h (module doc).
const RIGID_COARSE_LH: f64 = 0.4;

/// The most intervals the rule gives the coarsest grid, whose solve is a dense Newton method
/// (O(n0^3) per iteration; module doc).
pub const MAX_COARSEST_INTERVALS: usize = 1024;

/// Tunable constants of the domain rule (module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DomainParams {
    /// Elastic inlet margin beyond X = -1, in units of H_e^(2/3) (clamped to [0.5, 3.5]).
    pub inlet_elastic: f64,
    /// Inlet length in hydrodynamic lengths l_h.
    pub inlet_factor: f64,
    /// Extra inlet length in l_h at full rigid weight w = 1.
    pub inlet_rigid: f64,
    /// Outlet length in l_h.
    pub outlet_factor: f64,
    /// Smallest outlet X_out (Hertzian units).
    pub min_outlet: f64,
    /// Largest coarsest spacing for films with l_h <= 2 (scaled by l_h/2 above).
    pub coarse_h_max: f64,
    /// The coarsest spacing is at most this many hydrodynamic lengths l_h.
    pub coarse_lh: f64,
}

impl Default for DomainParams {
    fn default() -> Self {
        DomainParams {
            inlet_elastic: 20.0,
            inlet_factor: 16.0,
            inlet_rigid: 32.0,
            outlet_factor: 1.5,
            min_outlet: 1.5,
            coarse_h_max: 0.15,
            coarse_lh: 1.0,
        }
    }
}

/// A line domain with its coarsest grid: X_in + i h0, i = 0..=n0, with X = 0 at i = i0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineDomain {
    /// Inlet end X_in of the domain (Hertzian units, X = 0 on a node).
    pub x_in: f64,
    /// Outlet end X_out of the domain.
    pub x_out: f64,
    /// Intervals of the coarsest grid.
    pub n0: usize,
    /// Central film estimate used by the rule (Hertzian units).
    pub h_estimate: f64,
}

impl LineDomain {
    /// The rule of the module doc for Moes parameters (m, l); `max_intervals` (the finest grid's
    /// intervals) caps n0.
    pub fn for_case(m: f64, l: f64, rigid: bool, p: &DomainParams, max_intervals: usize) -> Self {
        let h_moes = if rigid {
            // Moes' formula without its elastic asymptotes (s = 3 in that limit).
            let [h_ri, _, h_rp, _] = moes_line_asymptotes(m, l);
            (h_ri.powi(3) + h_rp.powi(3)).cbrt()
        } else {
            moes_line_hc(m, l)
        };
        let h_e = h_moes * PI / (8.0 * m);
        let lh = (2.0 * h_e).sqrt();
        let w = if rigid {
            1.0
        } else {
            (3.0 / m / h_moes).min(1.0).powi(2)
        };
        let elastic_inlet = 1.0 + (p.inlet_elastic * h_e.powf(2.0 / 3.0)).clamp(0.5, 3.5);
        let (x_in, x_out) = if rigid {
            // No Hertzian zone: every length scales with l_h.
            (-(p.inlet_factor + p.inlet_rigid) * lh, p.outlet_factor * lh)
        } else {
            (
                -(elastic_inlet.max((p.inlet_factor + w * p.inlet_rigid) * lh)),
                p.min_outlet.max(p.outlet_factor * lh),
            )
        };
        let width = x_out - x_in;
        // Rigid surfaces have no feature finer than l_h: 0.4 l_h over a 49.5 l_h domain is about
        // 124 intervals whatever M (the elastic rule alone would ask for thousands at M << 1,
        // and the coarsest grid's dense Newton solve would cost seconds). Elastic surfaces blend
        // toward it with the rigid weight w.
        let h_target = if rigid {
            RIGID_COARSE_LH * lh
        } else {
            (p.coarse_h_max * (0.5 * lh).max(1.0))
                .min(p.coarse_lh * lh)
                .max(w * RIGID_COARSE_LH * lh)
        };
        let mut n0 = 16usize;
        let max_intervals = max_intervals.min(MAX_COARSEST_INTERVALS);
        while width / n0 as f64 > h_target && n0 < max_intervals {
            n0 *= 2;
        }
        let n0 = n0.min(max_intervals);
        Self::aligned(x_in, x_out, n0, h_e)
    }

    /// Shift [x_in, x_out] to the nearest domain of the same width with X = 0 on a node.
    pub fn aligned(x_in: f64, x_out: f64, n0: usize, h_estimate: f64) -> Self {
        let (x_in, x_out) = align_origin(x_in, x_out, n0);
        LineDomain {
            x_in,
            x_out,
            n0,
            h_estimate,
        }
    }

    /// Index of X = 0 on a grid with `n` intervals (a multiple of n0).
    pub fn centre_index(&self, n: usize) -> usize {
        (-self.x_in / (self.x_out - self.x_in) * n as f64).round() as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classic_domain_in_elastic_regime_and_growth_when_rigid() {
        // 16 l_h = 7.2 here: longer than the classic -4.5.
        let d = LineDomain::for_case(20.0, 10.0, false, &DomainParams::default(), 4096);
        assert!(
            d.x_in <= -4.5 && d.x_in > -7.5 && d.x_out >= 1.4 && d.x_out < 1.8,
            "{d:?}"
        );
        let e = LineDomain::for_case(1000.0, 0.0, false, &DomainParams::default(), 4096);
        assert!(e.x_in <= -1.4 && e.x_in > -1.8, "{e:?}");
        let r = LineDomain::for_case(0.1, 0.0, true, &DomainParams::default(), 4096);
        assert!(r.x_in < -100.0 && r.x_out > 10.0, "{r:?}");
        for d in [d, e, r] {
            let n = d.n0 * 8;
            let h = (d.x_out - d.x_in) / n as f64;
            let x0 = d.x_in + d.centre_index(n) as f64 * h;
            assert!(x0.abs() < 1e-9 * h.max(1.0));
        }
    }

    #[test]
    fn the_coarsest_grid_stays_within_a_dense_solve_s_reach() {
        // M = 1e5, L = 0: l_h is about 1.4e-3, so the spacing rule alone asks for n0 = 4096 on
        // 4097 points and more (a one-level dense Newton solve of 4096 unknowns, which ran for
        // more than 25 min); capped at MAX_COARSEST_INTERVALS whatever the finest grid.
        let p = DomainParams::default();
        for fine in [4096, 16384, 65536] {
            let d = LineDomain::for_case(1e5, 0.0, false, &p, fine);
            assert_eq!(d.n0, MAX_COARSEST_INTERVALS, "{d:?}");
        }
        // Below the cap the rule is unchanged: M = 1000 asks for fewer intervals.
        let d = LineDomain::for_case(1000.0, 0.0, false, &p, 16384);
        assert!(d.n0 < MAX_COARSEST_INTERVALS && d.n0 >= 16, "{d:?}");
    }
}
