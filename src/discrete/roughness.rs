//! The rough-surface terms of the discrete Reynolds operator in Hertzian scaling, written once
//! for line and point contacts: the Patir-Cheng average Reynolds equation (seed 7-59)
//!
//! ```text
//! d/dX(phi_x eps dP/dX) + d/dY(phi_y eps dP/dY) - d/dX[rho (H_T(H) + s sigma Phi_s(H/sigma))] = 0
//! H_T(H) = sigma F_1(-H/sigma) = H + sigma F_1(H/sigma)     the average gap (7-35, 7-36)
//! s = (slide_roll/2)(2 Vr1 - 1)             the shear flow coefficient (7-43, 7-53)
//! P_a(H) = A F_5/2(H/sigma),  A = K'/(p_h/E')   Greenwood-Tripp asperity pressure over p_h
//! ```
//!
//! Contract. Inputs: the case's [`Roughness`] and `h_scale` = H_Moes/H_Hertzian (sigma is given
//! in Moes units and used in Hertzian ones). Outputs, per nodal nominal film H (the separation
//! of the mean planes, which may be negative under heavy asperity load): the pressure flow
//! factors at `max(H, 0)/sigma` ([`RoughLaw::factors`]), the wedge film `q(H)` that replaces H
//! in the wedge term ([`RoughLaw::wedge_film`]), and the asperity pressure
//! ([`RoughLaw::asperity_pressure`], exactly 0 for H/sigma > 7). A negative nominal film (the
//! mean planes pressed through each other: a coarse grid's intermediate iterate, never a
//! converged film with H_min/sigma >= 0) continues the average gap with the smooth operator's
//! slope, q(H) = H + sigma F_1(0) for H < 0, as the smooth operator continues H below 0 (an
//! average gap that stays positive there made the coarse Newton solves lose the load balance).
//! Invariant: as sigma -> 0, phi -> 1, q(H) -> H and P_a -> 0 at every H, the smooth operator;
//! sigma = 0 itself is never a `RoughLaw` (the smooth solver runs unchanged).

use crate::model::flow_factors::{pressure_factor, single_shear_factor};
use crate::model::gt_table::{f1, f52};
use crate::model::roughness::Roughness;

/// The rough-surface law of a case in Hertzian units (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughLaw {
    /// Composite RMS roughness (Hertzian film units).
    pub sigma: f64,
    /// Peklenik orientation gamma.
    pub gamma: f64,
    /// Shear flow coefficient s.
    pub shear: f64,
    /// A = K'/(p_h/E').
    pub asperity: f64,
}

impl RoughLaw {
    /// The law of `roughness` for a case with H_Moes = `h_scale` H; `None` when smooth.
    pub fn new(roughness: &Option<Roughness>, h_scale: f64) -> Option<Self> {
        let r = roughness.as_ref().filter(|r| r.is_rough())?;
        Some(RoughLaw {
            sigma: r.sigma / h_scale,
            gamma: r.gamma,
            shear: r.shear_coefficient(),
            asperity: r.asperity_coefficient(),
        })
    }

    /// Whether phi_x = phi_y (gamma = 1).
    #[inline]
    pub fn isotropic(&self) -> bool {
        self.gamma == 1.0
    }

    /// (phi_x, phi_y) at film H.
    #[inline]
    pub fn factors(&self, film: f64) -> (f64, f64) {
        let t = film.max(0.0) / self.sigma;
        let fx = pressure_factor(t, self.gamma).0;
        if self.isotropic() {
            (fx, fx)
        } else {
            (fx, pressure_factor(t, 1.0 / self.gamma).0)
        }
    }

    /// phi_x at film H.
    #[inline]
    pub fn phi_x(&self, film: f64) -> f64 {
        pressure_factor(film.max(0.0) / self.sigma, self.gamma).0
    }

    /// The wedge film q(H) = H + sigma F_1(max(H, 0)/sigma) + s sigma Phi_s(max(H, 0)/sigma):
    /// the average gap H_T(H) plus the shear flow for H >= 0 (module docs for H < 0).
    #[inline]
    pub fn wedge_film(&self, film: f64) -> f64 {
        let t = film.max(0.0) / self.sigma;
        let mut q = film + self.sigma * f1(t);
        if self.shear != 0.0 {
            q += self.shear * self.sigma * single_shear_factor(t, self.gamma);
        }
        q
    }

    /// The asperity pressure P_a(H) over p_h.
    #[inline]
    pub fn asperity_pressure(&self, film: f64) -> f64 {
        self.asperity * f52(film / self.sigma)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::asperity::{asperity_pressure, average_gap};
    use crate::model::flow_factors::flow_factors;

    #[test]
    fn the_law_is_the_models_functions_in_hertzian_units() {
        let r = Roughness {
            gamma: 3.0,
            slide_roll: 0.5,
            variance_ratio_1: 1.0,
            ..Roughness::isotropic(0.2)
        };
        let law = RoughLaw::new(&Some(r), 2.0).unwrap();
        assert_eq!(law.sigma, 0.1);
        for film in [0.03, 0.1, 0.25, 0.6] {
            let t = film / 0.1;
            let ff = flow_factors(t, 3.0).unwrap();
            let (fx, fy) = law.factors(film);
            assert!((fx - ff.phi_x).abs() < 1e-15 && (fy - ff.phi_y).abs() < 1e-15);
            let q = 0.1 * average_gap(t).unwrap().gap_over_sigma + 0.25 * 0.1 * ff.phi_s;
            assert!((law.wedge_film(film) - q).abs() < 1e-8 * q, "{film}");
            let pa = asperity_pressure(t, &r.asperity).unwrap() / r.ph_over_e;
            assert!(
                (law.asperity_pressure(film) - pa).abs() <= 1e-8 * pa,
                "{film}"
            );
        }
        // Smooth: no law at all.
        assert!(RoughLaw::new(&Some(Roughness::isotropic(0.0)), 1.0).is_none());
        assert!(RoughLaw::new(&None, 1.0).is_none());
    }

    #[test]
    fn far_from_the_asperities_the_law_is_smooth() {
        let law = RoughLaw::new(&Some(Roughness::isotropic(0.01)), 1.0).unwrap();
        let film = 0.2; // H/sigma = 20
        let (fx, fy) = law.factors(film);
        assert!((fx - 1.0).abs() < 1e-4 && (fy - 1.0).abs() < 1e-4);
        assert!((law.wedge_film(film) - film).abs() < 1e-15);
        assert_eq!(law.asperity_pressure(film), 0.0);
    }
}
