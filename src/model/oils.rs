//! Lubricant properties at the operating temperature: the Walther (ASTM D341) viscosity-temperature
//! line through two kinematic viscosities, and a small table of named oils.
//!
//! Walther (ASTM D341; docs/physics.md section 2, Lubricant):
//! `log10 log10(nu + 0.7) = A - B log10 T` (nu in mm^2/s, T in K), fitted exactly through
//! (40 C, nu40) and (100 C, nu100). Density: `rho(T) = rho15 (1 - 6.5e-4 (T - 15 C))` (a typical
//! mineral-oil expansion coefficient). Dynamic viscosity `eta0 = rho nu 1e-6` (Pa s). The
//! pressure-viscosity coefficient alpha is taken as given (no temperature dependence).
//!
//! Input: a [`LubricantSpec`] (the `[lubricant]` table of a case file); output: a [`Resolved`]
//! lubricant at the operating temperature, or an error naming the offending `lubricant.*` input.
//!
//! Named oils: ISO VG mineral oils of viscosity index about 95-100 with typical values
//! (nu40 = the grade, nu100 from the usual VI-100 tables, density at 15 C, alpha about 2e-8 1/Pa);
//! they are "typical values", not a supplier's data sheet.

use crate::model::error::{num, ParamError};
use serde::{Deserialize, Serialize};

/// `(name, nu40 mm^2/s, nu100 mm^2/s, rho15 kg/m^3, alpha 1/Pa)`: typical values.
pub const OILS: [(&str, f64, f64, f64, f64); 5] = [
    ("ISO VG 32", 32.0, 5.4, 860.0, 1.9e-8),
    ("ISO VG 46", 46.0, 6.8, 865.0, 2.0e-8),
    ("ISO VG 68", 68.0, 8.7, 870.0, 2.1e-8),
    ("ISO VG 100", 100.0, 11.1, 875.0, 2.2e-8),
    ("ISO VG 220", 220.0, 19.0, 890.0, 2.4e-8),
];

const K0: f64 = 273.15;

/// A Walther line `log10 log10(nu + 0.7) = a - b log10 T`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Walther {
    /// Intercept A (T in K, nu in mm^2/s).
    pub a: f64,
    /// Slope B against log10 T (T in K); positive for a line from [`Walther::through`].
    pub b: f64,
}

fn z(nu: f64) -> f64 {
    (nu + 0.7).log10().log10()
}

impl Walther {
    /// The line through `(t1 C, nu1)` and `(t2 C, nu2)` (mm^2/s); errors unless
    /// `t1 < t2`, `nu1 > nu2` and both viscosities are finite and above 0.3 mm^2/s.
    pub fn through(t1: f64, nu1: f64, t2: f64, nu2: f64) -> Result<Self, ParamError> {
        if !(nu1 > 0.3 && nu2 > 0.3 && nu1.is_finite() && nu2.is_finite()) {
            return Err(ParamError::Input(format!(
                "kinematic viscosities {nu1}, {nu2} mm^2/s: must be finite and > 0.3"
            )));
        }
        if !(t1 < t2 && nu1 > nu2) {
            return Err(ParamError::Input(format!(
                "nu({t1} C) = {nu1} must exceed nu({t2} C) = {nu2}: viscosity falls with temperature"
            )));
        }
        let (l1, l2) = ((t1 + K0).log10(), (t2 + K0).log10());
        let b = (z(nu1) - z(nu2)) / (l2 - l1);
        Ok(Walther {
            a: z(nu1) + b * l1,
            b,
        })
    }

    /// Kinematic viscosity (mm^2/s) at `t` C.
    pub fn nu(&self, t: f64) -> f64 {
        10f64.powf(10f64.powf(self.a - self.b * (t + K0).log10())) - 0.7
    }
}

/// The `[lubricant]` table of a case: a named oil, or nu40/nu100/density/alpha, at a temperature.
#[derive(Clone, Debug, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LubricantSpec {
    /// A name of [`OILS`] (e.g. "ISO VG 68").
    pub oil: Option<String>,
    /// Kinematic viscosity at 40 C (mm^2/s); given with `nu100` instead of `oil`.
    pub nu40: Option<f64>,
    /// Kinematic viscosity at 100 C (mm^2/s); given with `nu40` instead of `oil`.
    pub nu100: Option<f64>,
    /// Density at 15 C (kg/m^3).
    pub density: Option<f64>,
    /// Pressure-viscosity coefficient (1/Pa); overrides the named oil's.
    pub alpha: Option<f64>,
    /// Operating temperature (C).
    pub temperature: f64,
}

/// A lubricant resolved at its operating temperature.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Resolved {
    /// The named oil, or "nu40/nu100 oil".
    pub name: String,
    /// Operating temperature (C).
    pub temperature: f64,
    /// Kinematic viscosity at the operating temperature (mm^2/s).
    pub nu: f64,
    /// Density at the operating temperature (kg/m^3).
    pub rho: f64,
    /// Dynamic viscosity at the operating temperature (Pa s).
    pub eta0: f64,
    /// Pressure-viscosity coefficient (1/Pa).
    pub alpha: f64,
    /// The Walther line through nu40 and nu100.
    pub walther: Walther,
}

impl LubricantSpec {
    /// eta0 and alpha at the operating temperature; errors name the `lubricant.*` input.
    pub fn resolve(&self) -> Result<Resolved, ParamError> {
        let t = self.temperature;
        if !(t.is_finite() && t > -K0) {
            return Err(ParamError::Input(format!(
                "lubricant.temperature = {} is invalid: give the operating temperature in C",
                num(t)
            )));
        }
        let (name, nu40, nu100, rho15, alpha) = match (&self.oil, self.nu40, self.nu100) {
            (Some(o), None, None) => {
                let row = OILS
                    .iter()
                    .find(|r| r.0.eq_ignore_ascii_case(o))
                    .ok_or_else(|| {
                        let names: Vec<_> = OILS.iter().map(|r| r.0).collect();
                        format!("lubricant.oil = {o:?} is unknown: one of {names:?}")
                    })?;
                let rho = self.density.unwrap_or(row.3);
                (
                    row.0.to_string(),
                    row.1,
                    row.2,
                    rho,
                    self.alpha.unwrap_or(row.4),
                )
            }
            (None, Some(a), Some(b)) => {
                let rho = self
                    .density
                    .ok_or("lubricant.density (kg/m^3 at 15 C) is missing")?;
                let alpha = self
                    .alpha
                    .ok_or("lubricant.alpha (pressure-viscosity coefficient, 1/Pa) is missing")?;
                ("nu40/nu100 oil".to_string(), a, b, rho, alpha)
            }
            _ => {
                return Err(
                    "lubricant: give either oil = \"ISO VG ..\" or both nu40 and nu100".into(),
                )
            }
        };
        let walther = Walther::through(40.0, nu40, 100.0, nu100)
            .map_err(|e| format!("lubricant.nu40/nu100: {e}"))?;
        if !(rho15 > 0.0 && rho15.is_finite()) {
            return Err(ParamError::Input(format!(
                "lubricant.density = {rho15} is invalid: must be > 0"
            )));
        }
        if !(alpha >= 0.0 && alpha.is_finite()) {
            return Err(ParamError::Input(format!(
                "lubricant.alpha = {alpha} is invalid: must be >= 0 (1/Pa)"
            )));
        }
        let nu = walther.nu(t);
        let rho = rho15 * (1.0 - 6.5e-4 * (t - 15.0));
        // The viscosity and density at the temperature: a temperature beyond where the
        // Walther line or the linear density law give a positive finite value is named as
        // such, not as the eta0 it would produce.
        if !(nu.is_finite() && nu > 0.0) {
            return Err(ParamError::Input(format!(
                "lubricant.temperature = {} is invalid: the Walther line gives nu = {nu:.3e} \
                 mm^2/s there (give the operating temperature in C)",
                num(t)
            )));
        }
        if !(rho.is_finite() && rho > 0.0) {
            return Err(ParamError::Input(format!(
                "lubricant.temperature = {} is invalid: the density rho15 (1 - 6.5e-4 (T - 15 C)) \
                 is {rho:.3e} kg/m^3 there, not positive (T below {:.0} C; give the operating \
                 temperature in C)",
                num(t),
                15.0 + 1.0 / 6.5e-4
            )));
        }
        let eta0 = rho * nu * 1e-6;
        if !(eta0.is_finite() && eta0 > 0.0) {
            return Err(ParamError::Input(format!(
                "lubricant.temperature = {} is invalid: eta0 = rho nu = {eta0:.3e} Pa s there",
                num(t)
            )));
        }
        Ok(Resolved {
            name,
            temperature: t,
            nu,
            rho,
            eta0,
            alpha,
            walther,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn walther_through_its_points_and_the_d341_standard_form() {
        let w = Walther::through(40.0, 68.0, 100.0, 8.7).unwrap();
        assert!((w.nu(40.0) / 68.0 - 1.0).abs() < 1e-12);
        assert!((w.nu(100.0) / 8.7 - 1.0).abs() < 1e-12);
        // Third point at 60 C from ASTM D341's standard form, which adds to nu + 0.7 the
        // low-viscosity term exp(-1.47 - 1.84 nu - 0.51 nu^2): its own line through the same two
        // points, solved at 60 C by bisection. Above 2 mm^2/s the two forms agree within 0.1 %.
        let zz = |nu: f64| {
            (nu + 0.7 + (-1.47 - 1.84 * nu - 0.51 * nu * nu).exp())
                .log10()
                .log10()
        };
        let (l40, l100, l60) = (313.15f64.log10(), 373.15f64.log10(), 333.15f64.log10());
        let b = (zz(68.0) - zz(8.7)) / (l100 - l40);
        let target = zz(68.0) - b * (l60 - l40);
        let (mut lo, mut hi) = (8.7, 68.0);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if zz(mid) > target {
                hi = mid
            } else {
                lo = mid
            }
        }
        let nu60 = 0.5 * (lo + hi);
        assert!(
            (w.nu(60.0) / nu60 - 1.0).abs() < 1e-3,
            "{} {nu60}",
            w.nu(60.0)
        );
        // and it is a plausible VG 68 figure at 60 C (about 29-30 mm^2/s)
        assert!(nu60 > 28.0 && nu60 < 32.0, "{nu60}");
        let mut prev = f64::INFINITY;
        for t in (0..=150).step_by(5) {
            let v = w.nu(t as f64);
            assert!(v < prev, "not decreasing at {t} C");
            prev = v;
        }
    }

    #[test]
    fn a_temperature_out_of_the_laws_range_is_named() {
        for t in [1e6, 2000.0, -273.0, -273.15, f64::NAN, f64::INFINITY] {
            let s = LubricantSpec {
                oil: Some("ISO VG 68".into()),
                temperature: t,
                ..Default::default()
            };
            let e = s.resolve().unwrap_err().to_string();
            assert!(e.starts_with("lubricant.temperature = "), "{t}: {e}");
        }
    }

    #[test]
    fn named_oil_resolves_and_bad_inputs_are_named() {
        let s = LubricantSpec {
            oil: Some("iso vg 46".into()),
            temperature: 40.0,
            ..Default::default()
        };
        let r = s.resolve().unwrap();
        // 46 mm^2/s x 865 (1 - 6.5e-4 x 25) kg/m^3 = 0.03915 Pa s
        assert!((r.eta0 / (46e-6 * 865.0 * (1.0 - 6.5e-4 * 25.0)) - 1.0).abs() < 1e-12);
        let bad = LubricantSpec {
            oil: Some("VG 9".into()),
            temperature: 40.0,
            ..Default::default()
        };
        assert!(bad
            .resolve()
            .unwrap_err()
            .to_string()
            .contains("lubricant.oil"));
        let inv = LubricantSpec {
            nu40: Some(10.0),
            nu100: Some(20.0),
            density: Some(870.0),
            alpha: Some(2e-8),
            temperature: 40.0,
            ..Default::default()
        };
        assert!(inv
            .resolve()
            .unwrap_err()
            .to_string()
            .contains("lubricant.nu40/nu100"));
    }
}
