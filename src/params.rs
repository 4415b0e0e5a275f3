//! Physical case description in Moes parameters and its conversion to the Hertzian (Venner) scaling
//! used inside the solvers.
//!
//! Line contact (PHYSICS.md section 1), with u_s = u1 + u2 the sum velocity:
//! W' = w'/(E'R), U = eta0 u_s/(E'R), M = W' U^(-1/2), L = G U^(1/4), H_Moes = (h/R) U^(-1/2).
//! Venner scaling X = x/b, P = p/p_h, H = hR/b^2 with b = R sqrt(8W'/pi), p_h = E'b/(4R) gives
//!
//! * lambda    = 12 eta0 u_m R^2/(b^3 p_h) = 3 pi^2/(8 M^2)
//! * alpha_bar = alpha p_h                 = L sqrt(M/(2 pi))
//! * H_Moes    = H_Venner * 8 M / pi
//!
//! The inverse maps are exact: M = pi sqrt(3/(8 lambda)), L = alpha_bar sqrt(2 pi/M).

use crate::lubricant::{Density, Viscosity};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use std::fmt;

/// Whether the surfaces deform (the elastic film integral) or stay rigid.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Elasticity {
    /// Elastic deformation by the half-space integral (default).
    #[default]
    Elastic,
    /// Deformation switched off: H = H0 + X^2/2.
    Rigid,
}

impl fmt::Display for Elasticity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Elasticity::Elastic => "elastic",
            Elasticity::Rigid => "rigid",
        })
    }
}

/// Lubricant and solid models of a case.
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
pub struct Models {
    pub elasticity: Elasticity,
    pub viscosity: Viscosity,
    pub density: Density,
}

/// Invalid case input; the message names the offending value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ParamError {
    #[error("{name} = {value} is invalid: {why}")]
    Invalid {
        name: &'static str,
        value: f64,
        why: &'static str,
    },
}

pub(crate) fn check(
    name: &'static str,
    value: f64,
    ok: bool,
    why: &'static str,
) -> Result<(), ParamError> {
    if value.is_finite() && ok {
        Ok(())
    } else {
        Err(ParamError::Invalid { name, value, why })
    }
}

/// A steady isothermal line contact in Moes parameters.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct LineCase {
    /// Moes load parameter M > 0.
    pub m: f64,
    /// Moes lubricant parameter L >= 0.
    pub l: f64,
    pub models: Models,
}

/// The line-contact groups of the Hertzian (Venner) scaling.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VennerLine {
    pub lambda: f64,
    pub alpha_bar: f64,
    /// H_Moes / H_Venner.
    pub h_scale: f64,
}

impl LineCase {
    /// A case with the default models (elastic, Barus, incompressible), validated.
    pub fn new(m: f64, l: f64) -> Result<Self, ParamError> {
        Self::with_models(m, l, Models::default())
    }

    pub fn with_models(m: f64, l: f64, models: Models) -> Result<Self, ParamError> {
        let c = LineCase { m, l, models };
        c.validate()?;
        Ok(c)
    }

    pub fn validate(&self) -> Result<(), ParamError> {
        check(
            "M",
            self.m,
            self.m > 0.0,
            "the load parameter must be positive and finite",
        )?;
        check(
            "L",
            self.l,
            self.l >= 0.0,
            "the lubricant parameter must be >= 0 and finite",
        )?;
        self.models.viscosity.validate()?;
        self.models.density.validate()
    }

    pub fn venner(&self) -> VennerLine {
        VennerLine {
            lambda: 3.0 * PI * PI / (8.0 * self.m * self.m),
            alpha_bar: self.l * (self.m / (2.0 * PI)).sqrt(),
            h_scale: 8.0 * self.m / PI,
        }
    }

    /// Inverse of [`LineCase::venner`]: (M, L) from (lambda, alpha_bar).
    pub fn moes_from_venner(lambda: f64, alpha_bar: f64) -> (f64, f64) {
        let m = PI * (3.0 / (8.0 * lambda)).sqrt();
        let l = alpha_bar * (2.0 * PI / m).sqrt();
        (m, l)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn venner_groups_match_closed_forms() {
        // Direct evaluation from dimensional quantities: pick W', U, G and compare.
        let (w, u, g) = (1.0e-4_f64, 2.5e-11_f64, 5000.0_f64);
        let m = w / u.sqrt();
        let l = g * u.powf(0.25);
        let c = LineCase::new(m, l).unwrap();
        let v = c.venner();
        // b/R and p_h/E' from their definitions.
        let b = (8.0 * w / PI).sqrt();
        let ph = b / 4.0;
        let u_m = u / 2.0;
        let lambda = 12.0 * u_m / (b.powi(3) * ph);
        assert!((v.lambda / lambda - 1.0).abs() < 1e-12);
        assert!((v.alpha_bar / (g * ph) - 1.0).abs() < 1e-12);
        // H scaling: h/R = H_V b^2, H_Moes = (h/R) U^-1/2.
        assert!((v.h_scale / (b * b / u.sqrt()) - 1.0).abs() < 1e-12);
        let (m2, l2) = LineCase::moes_from_venner(v.lambda, v.alpha_bar);
        assert!((m2 / m - 1.0).abs() < 1e-12 && (l2 / l - 1.0).abs() < 1e-12);
    }

    #[test]
    fn rejects_bad_input() {
        assert!(LineCase::new(0.0, 1.0).is_err());
        assert!(LineCase::new(f64::NAN, 1.0).is_err());
        assert!(LineCase::new(10.0, -1.0).is_err());
        assert!(LineCase::new(10.0, f64::INFINITY).is_err());
        let e = LineCase::new(-3.0, 1.0).unwrap_err().to_string();
        assert!(e.contains("M = -3"), "{e}");
    }
}
