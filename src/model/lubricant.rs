//! Lubricant models in the Hertzian scaling: viscosity eta(P) = eta/eta0 and density rho(P) = rho/rho0
//! of the dimensionless pressure P = p/p_h.
//!
//! * Barus: eta = exp(alpha_bar P), alpha_bar = alpha p_h.
//! * Roelands: eta = exp{ (alpha p0/z) [ (1 + P p_h/p0)^z - 1 ] }, p0 = 1.96e8 Pa, with
//!   alpha = alpha_bar/p_h. Needs z and p_h; z may be derived from eta0 by
//!   z = alpha p0/(ln eta0 + 9.67) (eta0 in Pa s).
//! * Dowson-Higginson: rho = (0.59e9 + 1.34 p)/(0.59e9 + p), p = P p_h in Pa. Needs p_h.
//!
//! The exponent is capped at 700 so that eta stays finite (eps = rho H^3/(eta lambda) then simply
//! underflows to zero); negative P (never stored, but possible in a trial step) is treated as 0.

use crate::model::error::num;
use crate::model::error::{check, ParamError};
use serde::{Deserialize, Serialize};

/// Roelands' reference pressure p0 in Pa.
pub const ROELANDS_P0: f64 = 1.96e8;
const EXP_CAP: f64 = 700.0;

/// Pressure-viscosity model.
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(tag = "model", rename_all = "lowercase")]
pub enum Viscosity {
    /// Barus: `eta = exp(alpha_bar P)` (default).
    #[default]
    Barus,
    /// Roelands with pressure-viscosity index `z` and the Hertzian pressure `ph_pa` (Pa).
    Roelands {
        /// Roelands pressure-viscosity index z > 0.
        z: f64,
        /// Hertzian pressure p_h (Pa) that scales P = p/p_h.
        ph_pa: f64,
    },
}

impl Viscosity {
    /// Roelands model from the ambient viscosity eta0 (Pa s) instead of z.
    /// `alpha_bar` is alpha p_h of the case, so alpha = alpha_bar/p_h.
    pub fn roelands_from_eta0(eta0: f64, ph_pa: f64, alpha_bar: f64) -> Result<Self, ParamError> {
        check(
            "eta0",
            eta0,
            eta0 > 0.0,
            "the ambient viscosity must be positive (Pa s)",
        )?;
        check(
            "ph",
            ph_pa,
            ph_pa > 0.0,
            "the Hertzian pressure must be positive (Pa)",
        )?;
        let denom = eta0.ln() + 9.67;
        check(
            "eta0",
            eta0,
            denom > 0.0,
            "Roelands needs ln(eta0) + 9.67 > 0",
        )?;
        let z = (alpha_bar / ph_pa) * ROELANDS_P0 / denom;
        if !(z.is_finite() && z > 0.0) {
            // z is derived, never given: name the inputs it comes from.
            return Err(ParamError::Input(format!(
                "eta0 = {} gives the Roelands index z = alpha p0/(ln eta0 + 9.67) = {z:.3e} \
                 (alpha = {:.3e} 1/Pa), which must be positive and finite: Roelands from eta0 \
                 needs alpha > 0 (L > 0)",
                num(eta0),
                alpha_bar / ph_pa
            )));
        }
        let v = Viscosity::Roelands { z, ph_pa };
        v.validate()?;
        Ok(v)
    }

    /// Checks Roelands' z > 0 and p_h > 0 (both finite); Barus has no parameter to check.
    pub fn validate(&self) -> Result<(), ParamError> {
        if let Viscosity::Roelands { z, ph_pa } = *self {
            check("z", z, z > 0.0, "the Roelands index must be positive")?;
            check(
                "ph",
                ph_pa,
                ph_pa > 0.0,
                "the Hertzian pressure must be positive (Pa)",
            )?;
        }
        Ok(())
    }

    /// eta/eta0 at dimensionless pressure `p`, for alpha_bar = alpha p_h.
    #[inline]
    pub fn eta(&self, p: f64, alpha_bar: f64) -> f64 {
        if p <= 0.0 {
            // Both laws give exp(0) = 1 exactly at P <= 0 (the cavitated zone): no exp call.
            return 1.0;
        }
        let e = match *self {
            Viscosity::Barus => alpha_bar * p,
            Viscosity::Roelands { z, ph_pa } => roelands_exponent(p, alpha_bar, z, ph_pa),
        };
        e.min(EXP_CAP).exp()
    }

    /// d ln(eta)/dP at dimensionless pressure `p` (zero where the exponent is capped).
    #[inline]
    pub fn dln_eta(&self, p: f64, alpha_bar: f64) -> f64 {
        let p = p.max(0.0);
        match *self {
            Viscosity::Barus => {
                if alpha_bar * p < EXP_CAP {
                    alpha_bar
                } else {
                    0.0
                }
            }
            Viscosity::Roelands { z, ph_pa } => roelands_dln_eta(p, alpha_bar, z, ph_pa),
        }
    }

    /// The stored name (`barus`, `roelands`).
    pub fn name(&self) -> &'static str {
        match self {
            Viscosity::Barus => "barus",
            Viscosity::Roelands { .. } => "roelands",
        }
    }
}

/// Pressure-density model.
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
#[serde(tag = "model", rename_all = "kebab-case")]
pub enum Density {
    /// Constant density, rho = 1 (default).
    #[default]
    Incompressible,
    /// Dowson-Higginson with the Hertzian pressure `ph_pa` (Pa).
    DowsonHigginson {
        /// Hertzian pressure p_h (Pa) that scales P = p/p_h.
        ph_pa: f64,
    },
}

impl Density {
    /// Checks Dowson-Higginson's p_h > 0 (finite); incompressible has no parameter to check.
    pub fn validate(&self) -> Result<(), ParamError> {
        if let Density::DowsonHigginson { ph_pa } = *self {
            check(
                "ph",
                ph_pa,
                ph_pa > 0.0,
                "the Hertzian pressure must be positive (Pa)",
            )?;
        }
        Ok(())
    }

    /// rho/rho0 at dimensionless pressure `p`.
    #[inline]
    pub fn rho(&self, p: f64) -> f64 {
        match *self {
            Density::Incompressible => 1.0,
            Density::DowsonHigginson { ph_pa } => {
                let pp = p.max(0.0) * ph_pa;
                (0.59e9 + 1.34 * pp) / (0.59e9 + pp)
            }
        }
    }

    /// d ln(rho)/dP at dimensionless pressure `p`.
    #[inline]
    pub fn dln_rho(&self, p: f64) -> f64 {
        match *self {
            Density::Incompressible => 0.0,
            Density::DowsonHigginson { ph_pa } => dowson_higginson_dln_rho(p, ph_pa),
        }
    }

    /// The stored name (`incompressible`, `dowson-higginson`).
    pub fn name(&self) -> &'static str {
        match self {
            Density::Incompressible => "incompressible",
            Density::DowsonHigginson { .. } => "dowson-higginson",
        }
    }
}

// The laws' arithmetic beside Barus and incompressible is kept out of line: inlined, the
// compiler evaluates its divisions on every call, whichever law the match selects.

/// The Roelands exponent ln(eta/eta0) at dimensionless pressure p > 0.
#[inline(never)]
fn roelands_exponent(p: f64, alpha_bar: f64, z: f64, ph_pa: f64) -> f64 {
    let a = alpha_bar / ph_pa * ROELANDS_P0 / z;
    a * ((1.0 + p * ph_pa / ROELANDS_P0).powf(z) - 1.0)
}

/// Roelands' d ln(eta)/dP at dimensionless pressure p >= 0 (zero where the exponent is capped).
#[inline(never)]
fn roelands_dln_eta(p: f64, alpha_bar: f64, z: f64, ph_pa: f64) -> f64 {
    let a = alpha_bar / ph_pa * ROELANDS_P0 / z;
    let s = 1.0 + p * ph_pa / ROELANDS_P0;
    if a * (s.powf(z) - 1.0) < EXP_CAP {
        a * z * s.powf(z - 1.0) * ph_pa / ROELANDS_P0
    } else {
        0.0
    }
}

/// Dowson-Higginson's d ln(rho)/dP at dimensionless pressure p.
#[inline(never)]
fn dowson_higginson_dln_rho(p: f64, ph_pa: f64) -> f64 {
    let pp = p.max(0.0) * ph_pa;
    let drho = 0.34 * 0.59e9 / ((0.59e9 + pp) * (0.59e9 + pp)) * ph_pa;
    drho / Density::DowsonHigginson { ph_pa }.rho(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roelands_matches_dimensional_form() {
        // eta = eta0 exp{(ln eta0 + 9.67)[(1 + p/p0)^z - 1]} with z from eta0 and alpha.
        let (eta0, alpha, ph) = (0.04_f64, 2.0e-8_f64, 1.0e9_f64);
        let v = Viscosity::roelands_from_eta0(eta0, ph, alpha * ph).unwrap();
        let z = alpha * ROELANDS_P0 / (eta0.ln() + 9.67);
        for p in [0.0, 0.3, 1.0, 1.5] {
            let direct = ((eta0.ln() + 9.67) * ((1.0 + p * ph / ROELANDS_P0).powf(z) - 1.0)).exp();
            assert!((v.eta(p, alpha * ph) / direct - 1.0).abs() < 1e-12);
        }
        // Small pressures: Roelands slope equals Barus slope alpha.
        let dp = 1e-7;
        let slope = v.eta(dp, alpha * ph).ln() / (dp * ph);
        assert!((slope / alpha - 1.0).abs() < 1e-5);
    }

    #[test]
    fn dowson_higginson_limits() {
        let d = Density::DowsonHigginson { ph_pa: 1.0e9 };
        assert_eq!(d.rho(0.0), 1.0);
        // p -> infinity gives 1.34.
        assert!((d.rho(1e6) - 1.34).abs() < 1e-3);
        // 1 GPa: (0.59 + 1.34)/(1.59).
        assert!((d.rho(1.0) - 1.93 / 1.59).abs() < 1e-12);
    }

    #[test]
    fn log_derivatives_match_finite_differences() {
        let v = Viscosity::roelands_from_eta0(0.04, 1.0e9, 20.0).unwrap();
        let d = Density::DowsonHigginson { ph_pa: 1.0e9 };
        for p in [0.1, 0.7, 1.3] {
            let e = 1e-6;
            let fd = (v.eta(p + e, 20.0).ln() - v.eta(p - e, 20.0).ln()) / (2.0 * e);
            assert!((v.dln_eta(p, 20.0) / fd - 1.0).abs() < 1e-6);
            let fd = (d.rho(p + e).ln() - d.rho(p - e).ln()) / (2.0 * e);
            assert!((d.dln_rho(p) / fd - 1.0).abs() < 1e-6);
        }
    }

    #[test]
    fn roelands_from_eta0_names_eta0_not_z() {
        // alpha = 0 gives z = 0: the message names eta0 and alpha, the inputs z comes from.
        let e = Viscosity::roelands_from_eta0(1e300, 1e9, 0.0)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("eta0 = 1e300 gives"), "{e}");
        assert!(e.contains("alpha > 0"), "{e}");
        let e = Viscosity::roelands_from_eta0(1e-5, 1e9, 20.0)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("eta0 = 0.00001"), "{e}");
    }

    #[test]
    fn viscosity_never_overflows() {
        assert!(Viscosity::Barus.eta(10.0, 500.0).is_finite());
    }
}
