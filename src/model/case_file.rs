//! A dimensional case file (SI units, TOML): the bodies (radii, modulus, Poisson ratio,
//! roughness), the load and speeds, the lubricant (eta0 and alpha directly, or a Walther oil at
//! a temperature, [`crate::model::oils`]), the solver's models and grid; reading, and validation
//! whose errors name the input. [`crate::model::dimensional`] turns a case file into Moes'
//! parameters.
//!
//! Common definitions: `2/E' = (1-nu1^2)/E1 + (1-nu2^2)/E2`, `sigma = sqrt(Rq1^2 + Rq2^2)`.

use crate::model::case::{Contact, Models};
use crate::model::error::num;
use crate::model::error::ParamError;
use crate::model::lubricant::{Density, Viscosity};
use crate::model::oils::{LubricantSpec, Resolved};
use serde::{Deserialize, Serialize};

/// A case file that cannot be read or is not a valid case; the message names the input.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CaseError {
    /// The file cannot be read or parsed, or an input is missing, contradictory or out of its
    /// domain; the message names the file or the input.
    #[error("{0}")]
    Invalid(String),
    /// The derived Moes case or the lubricant was rejected by the model layer.
    #[error(transparent)]
    Param(#[from] ParamError),
}

impl CaseError {
    pub(crate) fn invalid(msg: impl Into<String>) -> Self {
        CaseError::Invalid(msg.into())
    }
}

/// One body: radii (m; negative for concave; `radius_y` omitted or `inf` for a cylinder axis),
/// modulus (Pa), Poisson ratio, optional RMS roughness (m).
#[derive(Clone, Copy, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Body {
    /// Radius in the rolling direction x (m); negative for a concave surface, never zero.
    pub radius_x: f64,
    /// Radius across the rolling direction (m), point contacts only; omitted or `inf` for a
    /// cylinder axis, negative for a concave surface.
    #[serde(default)]
    pub radius_y: Option<f64>,
    /// Young's modulus E (Pa), positive; the TOML key is `E`.
    #[serde(rename = "E")]
    pub e: f64,
    /// Poisson's ratio, in (-1, 0.5).
    pub nu: f64,
    /// RMS surface roughness Rq (m), >= 0; used only for the film parameter `Lambda`.
    #[serde(default)]
    pub rq: Option<f64>,
}

/// The case file.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CaseSpec {
    /// Line or point contact (`contact = "line"` or `"point"`).
    pub contact: Contact,
    /// The first body (`[body1]`).
    pub body1: Body,
    /// The second body (`[body2]`).
    pub body2: Body,
    /// Load (N), positive: over the contact `length` (m) for a line contact.
    pub load: f64,
    /// Contact length (m) of a line contact, required there; not allowed for a point contact.
    #[serde(default)]
    pub length: Option<f64>,
    /// Surface speed of body 1 in the rolling direction (m/s); `u1 + u2` must be positive.
    pub u1: f64,
    /// Surface speed of body 2 in the rolling direction (m/s).
    pub u2: f64,
    /// Ambient viscosity eta0 (Pa s), given with `alpha` instead of `[lubricant]`.
    #[serde(default)]
    pub eta0: Option<f64>,
    /// Pressure-viscosity coefficient alpha (1/Pa), given with `eta0` instead of `[lubricant]`.
    #[serde(default)]
    pub alpha: Option<f64>,
    /// The `[lubricant]` table (a Walther oil at a temperature), instead of `eta0` and `alpha`.
    #[serde(default)]
    pub lubricant: Option<LubricantSpec>,
    /// A fixed finest grid: points (line) or points per direction (point). By default the
    /// accuracy ladder of `ehlmap solve` picks the grid (1 % target on H_c and H_min).
    #[serde(default)]
    pub grid: Option<usize>,
    /// The roughness orientation gamma of the mixed-lubrication solve (1 isotropic, the default;
    /// < 1 transverse, > 1 longitudinal); with a roughness `rq`.
    #[serde(default)]
    pub gamma: Option<f64>,
    /// Greenwood-Tripp summit statistics of the mixed-lubrication solve: eta_s beta sigma
    /// (default 0.04); with a roughness `rq`.
    #[serde(default)]
    pub eta_beta_sigma: Option<f64>,
    /// sigma/beta (default 1e-3); with a roughness `rq`.
    #[serde(default)]
    pub sigma_over_beta: Option<f64>,
    /// Roelands viscosity in the solve with this index z (default: Barus) ...
    #[serde(default)]
    pub roelands_z: Option<f64>,
    /// ... or with z from eta0, `z = alpha p0/(ln eta0 + 9.67)`.
    #[serde(default)]
    pub roelands: bool,
    /// Dowson-Higginson density in the solve (default: incompressible).
    #[serde(default)]
    pub dowson_higginson: bool,
}

pub(crate) fn check(name: &str, v: f64, ok: bool, why: &str) -> Result<(), CaseError> {
    if v.is_finite() && ok {
        Ok(())
    } else {
        Err(CaseError::invalid(format!(
            "{name} = {} is invalid: {why}",
            num(v)
        )))
    }
}

/// Reduced modulus `E'`.
pub(crate) fn e_reduced(b1: &Body, b2: &Body) -> f64 {
    2.0 / ((1.0 - b1.nu.powi(2)) / b1.e + (1.0 - b2.nu.powi(2)) / b2.e)
}

impl CaseSpec {
    /// The checks common to line and point contacts.
    pub fn validate_common(&self) -> Result<(), CaseError> {
        for (n, b) in [("body1", &self.body1), ("body2", &self.body2)] {
            check(
                &format!("{n}.E"),
                b.e,
                b.e > 0.0,
                "Young's modulus must be positive (Pa)",
            )?;
            check(
                &format!("{n}.nu"),
                b.nu,
                b.nu > -1.0 && b.nu < 0.5,
                "Poisson's ratio must be in (-1, 0.5)",
            )?;
            if b.radius_x == 0.0 || b.radius_x.is_nan() {
                return Err(CaseError::invalid(format!(
                    "{n}.radius_x = {} is invalid: a radius cannot be zero (m)",
                    b.radius_x
                )));
            }
            if let Some(rq) = b.rq {
                check(
                    &format!("{n}.rq"),
                    rq,
                    rq >= 0.0,
                    "roughness must be >= 0 (m)",
                )?;
            }
        }
        for (key, v) in [
            ("gamma", self.gamma),
            ("eta_beta_sigma", self.eta_beta_sigma),
            ("sigma_over_beta", self.sigma_over_beta),
        ] {
            let Some(v) = v else { continue };
            check(key, v, v > 0.0, "must be > 0")?;
            if self.sigma().is_none_or(|s| s <= 0.0) {
                return Err(CaseError::invalid(format!(
                    "{key} = {v}: a roughness input needs a roughness: give body1.rq or body2.rq (m)"
                )));
            }
        }
        check(
            "load",
            self.load,
            self.load > 0.0,
            "the load must be positive (N)",
        )?;
        check(
            "u1 + u2",
            self.u1 + self.u2,
            self.u1 + self.u2 > 0.0,
            "the speed sum must be positive (m/s)",
        )?;
        Ok(())
    }

    /// eta0 and alpha: given directly, or from `[lubricant]` (not both).
    pub fn lubricant(&self) -> Result<(f64, f64, Option<Resolved>), CaseError> {
        let (eta0, alpha, res) = match (&self.lubricant, self.eta0, self.alpha) {
            (Some(l), None, None) => {
                let r = l.resolve()?;
                (r.eta0, r.alpha, Some(r))
            }
            (None, Some(e), Some(a)) => (e, a, None),
            (Some(_), _, _) => {
                return Err(CaseError::invalid(
                    "eta0/alpha and [lubricant] are contradictory: give one of them",
                ))
            }
            (None, e, _) => {
                let missing = if e.is_none() { "eta0" } else { "alpha" };
                return Err(CaseError::invalid(format!(
                    "{missing} is missing (or give a [lubricant] table)"
                )));
            }
        };
        check(
            "eta0",
            eta0,
            eta0 > 0.0,
            "the viscosity must be positive (Pa s)",
        )?;
        check(
            "alpha",
            alpha,
            alpha >= 0.0,
            "the pressure-viscosity coefficient must be >= 0 (1/Pa)",
        )?;
        Ok((eta0, alpha, res))
    }

    /// The solver's models: Roelands (`roelands_z`, or `roelands = true` for z from eta0) and
    /// Dowson-Higginson density need the Hertzian pressure `p_h` (Pa).
    pub fn models(&self, eta0: f64, alpha: f64, p_h: f64) -> Result<Models, CaseError> {
        let viscosity = match (self.roelands_z, self.roelands) {
            (Some(_), true) => {
                return Err(CaseError::invalid(
                    "roelands_z and roelands = true are contradictory: give one",
                ))
            }
            (Some(z), false) => {
                check(
                    "roelands_z",
                    z,
                    z > 0.0,
                    "the Roelands index must be positive",
                )?;
                Viscosity::Roelands { z, ph_pa: p_h }
            }
            (None, true) => Viscosity::roelands_from_eta0(eta0, p_h, alpha * p_h).map_err(|e| {
                // eta0 from a [lubricant] table comes from its temperature: name that too.
                let from = self.lubricant.as_ref().map_or(String::new(), |l| {
                    format!(
                        " (eta0 from [lubricant] at lubricant.temperature = {} C)",
                        l.temperature
                    )
                });
                CaseError::invalid(format!("roelands = true (z from eta0): {e}{from}"))
            })?,
            (None, false) => Viscosity::Barus,
        };
        let density = if self.dowson_higginson {
            Density::DowsonHigginson { ph_pa: p_h }
        } else {
            Density::Incompressible
        };
        Ok(Models {
            viscosity,
            density,
            ..Models::default()
        })
    }

    /// `sigma = sqrt(Rq1^2 + Rq2^2)` when a roughness is given.
    pub fn sigma(&self) -> Option<f64> {
        match (self.body1.rq, self.body2.rq) {
            (Some(a), Some(b)) => Some((a * a + b * b).sqrt()),
            (Some(a), None) | (None, Some(a)) => Some(a),
            (None, None) => None,
        }
    }
}

/// Read and parse a case file; the error names the file (and the TOML problem).
pub fn read_case(path: &std::path::Path) -> Result<CaseSpec, CaseError> {
    let name = path.display();
    let text =
        std::fs::read_to_string(path).map_err(|e| CaseError::invalid(format!("{name}: {e}")))?;
    toml::from_str(&text).map_err(|e| {
        // `FILE:LINE: message` on one line, as sweep specs report theirs.
        // (a span from the file's start is the whole document: no line to name)
        // and the line's text, which names the key (`load = "3 kN"`, `[body1]`)
        let line = match e.span() {
            Some(s) if s.start > 0 => {
                let start = s.start.min(text.len());
                let n = text[..start].matches('\n').count();
                let src: String = text
                    .lines()
                    .nth(n)
                    .unwrap_or("")
                    .trim()
                    .chars()
                    .take(60)
                    .collect();
                format!(":{}: {src}", n + 1)
            }
            _ => String::new(),
        };
        let msg = e.message().lines().next().unwrap_or("invalid TOML").trim();
        CaseError::invalid(format!("{name}{line}: {msg}"))
    })
}
