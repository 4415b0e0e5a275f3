//! The rough-surface inputs of a mixed-lubrication case (Patir & Cheng average flow model with
//! Greenwood-Tripp asperity contact; the seed chapter `shared/seeds/002_e3b91dad40c55bf4.txt`,
//! section 7-7, and docs/physics.md "Mixed lubrication").
//!
//! Contract. `sigma` is the composite RMS roughness `sqrt(Rq1^2 + Rq2^2)` in the film units of
//! the case's outputs (Moes units: the same scale as `H_c`); `sigma = 0` is the smooth solver.
//! `gamma` is Peklenik's orientation (1 isotropic, < 1 transverse ridges, > 1 longitudinal).
//! `slide_roll = (u1 - u2)/u_m` with `u_m = (u1 + u2)/2` and `variance_ratio_1 = Rq1^2/sigma^2`
//! set the shear flow term `(slide_roll/2)(2 Vr1 - 1) sigma Phi_s`; equal roughness on both
//! surfaces (`Vr1 = 1/2`, the default) or pure rolling has none. The asperity pressure
//! `p_a = K' E' F_5/2(h/sigma)` enters the Hertzian scaling through `p_h/E'` (`ph_over_e`),
//! which Moes' parameters do not fix: it defaults to [`DEFAULT_PH_OVER_E`] (1 GPa on steel) and
//! a dimensional case file sets it from its bodies and load.

use crate::model::asperity::AsperityParams;
use crate::model::error::{check, ParamError};
use serde::{Deserialize, Serialize};

/// `p_h/E'` of a Moes-parameter case: `p_h = 1 GPa` between steel bodies (`E = 210 GPa`,
/// `nu = 0.3`, `E' = E/(1 - nu^2) = 230.8 GPa`).
pub const DEFAULT_PH_OVER_E: f64 = 1.0e9 / 2.3077e11;

fn default_gamma() -> f64 {
    1.0
}
fn default_vr1() -> f64 {
    0.5
}
fn default_ph_over_e() -> f64 {
    DEFAULT_PH_OVER_E
}

/// Rough surfaces of a case (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Roughness {
    /// Composite RMS roughness in Moes film units.
    pub sigma: f64,
    /// Peklenik orientation parameter gamma.
    #[serde(default = "default_gamma")]
    pub gamma: f64,
    /// (u1 - u2)/u_m.
    #[serde(default)]
    pub slide_roll: f64,
    /// Rq1^2/sigma^2, the share of the roughness variance on surface 1.
    #[serde(default = "default_vr1")]
    pub variance_ratio_1: f64,
    /// Greenwood-Tripp summit statistics.
    #[serde(default)]
    pub asperity: AsperityParams,
    /// p_h/E'.
    #[serde(default = "default_ph_over_e")]
    pub ph_over_e: f64,
}

impl Roughness {
    /// Isotropic roughness `sigma` on both surfaces alike, pure rolling, default asperities.
    pub fn isotropic(sigma: f64) -> Self {
        Roughness {
            sigma,
            gamma: 1.0,
            slide_roll: 0.0,
            variance_ratio_1: 0.5,
            asperity: AsperityParams::default(),
            ph_over_e: DEFAULT_PH_OVER_E,
        }
    }

    /// Every input in range; the error names the input.
    pub fn validate(&self) -> Result<(), ParamError> {
        check(
            "sigma",
            self.sigma,
            self.sigma >= 0.0,
            "the RMS roughness must be finite and >= 0 (0 is the smooth surface)",
        )?;
        check(
            "gamma",
            self.gamma,
            self.gamma > 0.0,
            "the orientation parameter must be finite and > 0",
        )?;
        check(
            "slide_roll",
            self.slide_roll,
            (-2.0..=2.0).contains(&self.slide_roll),
            "the slide-to-roll ratio (u1 - u2)/u_m must be in [-2, 2]",
        )?;
        check(
            "variance_ratio_1",
            self.variance_ratio_1,
            (0.0..=1.0).contains(&self.variance_ratio_1),
            "Rq1^2/sigma^2 must be in [0, 1]",
        )?;
        self.asperity.validate()?;
        check(
            "ph_over_e",
            self.ph_over_e,
            self.ph_over_e > 0.0 && self.ph_over_e < 1.0,
            "p_h/E' must be in (0, 1)",
        )
    }

    /// Whether the surfaces are rough at all (`sigma > 0`).
    pub fn is_rough(&self) -> bool {
        self.sigma > 0.0
    }

    /// The coefficient of `sigma Phi_s` in the wedge flux per mean speed:
    /// `(slide_roll/2)(2 Vr1 - 1)`.
    pub fn shear_coefficient(&self) -> f64 {
        0.5 * self.slide_roll * (2.0 * self.variance_ratio_1 - 1.0)
    }

    /// `K'/(p_h/E')`: the asperity pressure over `p_h` is this times `F_5/2(h/sigma)`.
    pub fn asperity_coefficient(&self) -> f64 {
        self.asperity.k_prime() / self.ph_over_e
    }
}

/// The orientation in words: isotropic (gamma = 1), transverse (< 1) or longitudinal (> 1).
pub fn orientation(gamma: f64) -> &'static str {
    if gamma == 1.0 {
        "isotropic"
    } else if gamma < 1.0 {
        "transverse"
    } else {
        "longitudinal"
    }
}

/// gamma for labels: `1/n` for the reciprocal of an integer n (the table rows 1/3, 1/6, 1/9),
/// else its shortest decimal.
pub fn gamma_label(gamma: f64) -> String {
    let inv = 1.0 / gamma;
    if gamma < 1.0 && (inv - inv.round()).abs() < 1e-9 {
        format!("1/{}", inv.round())
    } else {
        format!("{gamma}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_inputs_name_themselves() {
        let ok = Roughness::isotropic(0.5);
        assert!(ok.validate().is_ok());
        for (name, r) in [
            ("sigma", Roughness { sigma: -0.1, ..ok }),
            ("gamma", Roughness { gamma: 0.0, ..ok }),
            ("gamma", Roughness { gamma: -1.0, ..ok }),
            (
                "slide_roll",
                Roughness {
                    slide_roll: 3.0,
                    ..ok
                },
            ),
            (
                "variance_ratio_1",
                Roughness {
                    variance_ratio_1: 1.5,
                    ..ok
                },
            ),
            (
                "ph_over_e",
                Roughness {
                    ph_over_e: 0.0,
                    ..ok
                },
            ),
        ] {
            let e = r.validate().unwrap_err().to_string();
            assert!(e.contains(name), "{name}: {e}");
        }
    }

    #[test]
    fn shear_coefficient_follows_the_rough_surface() {
        // Only surface 1 rough, surface 1 faster: +slide_roll/2; equal roughness: 0.
        let r = Roughness {
            slide_roll: 0.4,
            variance_ratio_1: 1.0,
            ..Roughness::isotropic(1.0)
        };
        assert_eq!(r.shear_coefficient(), 0.2);
        let r = Roughness {
            variance_ratio_1: 0.0,
            ..r
        };
        assert_eq!(r.shear_coefficient(), -0.2);
        let r = Roughness {
            variance_ratio_1: 0.5,
            ..r
        };
        assert_eq!(r.shear_coefficient(), 0.0);
        // K'/(p_h/E') with the defaults: 1.199e-4 / 4.333e-3.
        let k = Roughness::isotropic(1.0).asperity_coefficient();
        assert!((k - 1.199e-4 / DEFAULT_PH_OVER_E).abs() < 1e-3 * k, "{k}");
    }
}
