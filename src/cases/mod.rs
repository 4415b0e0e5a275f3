//! A dimensional case (SI units in, engineering units out), line or point contact: the case file,
//! its validation (errors name the input), the lubricant (eta0 and alpha directly, or a Walther
//! oil at a temperature, [`crate::model::oils`]), the film parameter, and the readable report.
//!
//! Common definitions: `2/E' = (1-nu1^2)/E1 + (1-nu2^2)/E2`, `G = alpha E'`, `u_s = u1 + u2`,
//! `u_m = u_s/2`; Hamrock/Dowson groups use `u_m`, Moes groups `u_s` (see [`crate::model::formulas`]).
//! Film parameter `Lambda = h_min/sigma`, `sigma = sqrt(Rq1^2 + Rq2^2)`: `< 1` boundary, `1..3`
//! mixed, `> 3` full film. Line contacts: [`line`]; point contacts: [`point`].

pub mod line;
pub mod point;

use crate::model::case::Models;
use crate::model::lubricant::{Density, Viscosity};
use crate::model::oils::{LubricantSpec, Resolved};
use serde::{Deserialize, Serialize};

/// One body: radii (m; negative for concave; `radius_y` omitted or `inf` for a cylinder axis),
/// modulus (Pa), Poisson ratio, optional RMS roughness (m).
#[derive(Clone, Copy, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Body {
    pub radius_x: f64,
    #[serde(default)]
    pub radius_y: Option<f64>,
    #[serde(rename = "E")]
    pub e: f64,
    pub nu: f64,
    #[serde(default)]
    pub rq: Option<f64>,
}

/// The case file.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CaseSpec {
    /// "line" or "point".
    pub contact: String,
    pub body1: Body,
    pub body2: Body,
    /// Load (N): over the contact `length` (m) for a line contact.
    pub load: f64,
    #[serde(default)]
    pub length: Option<f64>,
    /// Surface speeds (m/s).
    pub u1: f64,
    pub u2: f64,
    /// Ambient viscosity (Pa s) and pressure-viscosity coefficient (1/Pa), or `[lubricant]`.
    #[serde(default)]
    pub eta0: Option<f64>,
    #[serde(default)]
    pub alpha: Option<f64>,
    #[serde(default)]
    pub lubricant: Option<LubricantSpec>,
    /// Finest grid: points (line, default 4097) or points per direction (point, default 129).
    #[serde(default)]
    pub grid: Option<usize>,
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

/// Everything derived from a case, and the results (SI units).
#[derive(Clone, Debug, Serialize)]
pub struct CaseReport {
    pub contact: String,
    /// Line: R; point: Rx (m).
    pub r: f64,
    /// Point: Ry (m), D = Rx/Ry, exact k = a/b, a = semi-axis across rolling (m).
    pub ry: Option<f64>,
    pub d: Option<f64>,
    pub k: Option<f64>,
    pub a: Option<f64>,
    pub e_reduced: f64,
    pub eta0: f64,
    pub alpha: f64,
    pub lubricant: Option<Resolved>,
    /// The solver's lubricant models (the published formulas are Barus, incompressible).
    pub models: Models,
    /// Load group (u_m convention): W' (line) or W (point).
    pub w_prime: f64,
    pub u_mean: f64,
    pub g: f64,
    pub m: f64,
    pub l: f64,
    /// Solver (Venner) groups lambda and alpha_bar.
    pub lambda: f64,
    pub alpha_bar: f64,
    /// Hertz semi-width along x (m) and maximum Hertz pressure (Pa).
    pub b: f64,
    pub p_h: f64,
    pub g_v: f64,
    pub g_e: f64,
    pub regime: String,
    pub numerical: Option<crate::solve::solution::Outputs>,
    /// Film thicknesses in m: (name, h_c or h_min, value).
    pub films: Vec<(String, String, f64)>,
    pub p_max: Option<f64>,
    pub film_parameter: Option<f64>,
    pub film_reading: Option<String>,
}

/// The solution fields of a case, for pictures.
pub enum CaseFields {
    Line(crate::solve::solution::Profile),
    Point(crate::solve::point::PointFields),
}

pub(crate) fn check(name: &str, v: f64, ok: bool, why: &str) -> Result<(), String> {
    if v.is_finite() && ok {
        Ok(())
    } else {
        Err(format!("{name} = {v} is invalid: {why}"))
    }
}

/// Reduced modulus `E'`.
pub(crate) fn e_reduced(b1: &Body, b2: &Body) -> f64 {
    2.0 / ((1.0 - b1.nu.powi(2)) / b1.e + (1.0 - b2.nu.powi(2)) / b2.e)
}

impl CaseSpec {
    /// The checks common to line and point contacts.
    fn validate_common(&self) -> Result<(), String> {
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
                return Err(format!(
                    "{n}.radius_x = {} is invalid: a radius cannot be zero (m)",
                    b.radius_x
                ));
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
    pub fn lubricant(&self) -> Result<(f64, f64, Option<Resolved>), String> {
        let (eta0, alpha, res) = match (&self.lubricant, self.eta0, self.alpha) {
            (Some(l), None, None) => {
                let r = l.resolve()?;
                (r.eta0, r.alpha, Some(r))
            }
            (None, Some(e), Some(a)) => (e, a, None),
            (Some(_), _, _) => {
                return Err("eta0/alpha and [lubricant] are contradictory: give one of them".into())
            }
            (None, e, _) => {
                let missing = if e.is_none() { "eta0" } else { "alpha" };
                return Err(format!(
                    "{missing} is missing (or give a [lubricant] table)"
                ));
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

    /// Validate, derive the groups; with `solve`, also solve numerically (and keep the fields
    /// with `keep_fields`).
    pub fn run(
        &self,
        solve: bool,
        keep_fields: bool,
    ) -> Result<(CaseReport, Option<CaseFields>), String> {
        self.validate_common()?;
        match self.contact.as_str() {
            "line" => line::run(self, solve, keep_fields),
            "point" => point::run(self, solve, keep_fields),
            c => Err(format!("contact = {c:?} is invalid: \"line\" or \"point\"")),
        }
    }

    /// Derive the groups; with `solve`, also solve numerically.
    pub fn report(&self, solve: bool) -> Result<CaseReport, String> {
        self.run(solve, false).map(|r| r.0)
    }

    /// The solver's models: Roelands (`roelands_z`, or `roelands = true` for z from eta0) and
    /// Dowson-Higginson density need the Hertzian pressure `p_h` (Pa).
    pub fn models(&self, eta0: f64, alpha: f64, p_h: f64) -> Result<Models, String> {
        let viscosity = match (self.roelands_z, self.roelands) {
            (Some(_), true) => {
                return Err("roelands_z and roelands = true are contradictory: give one".into())
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
            (None, true) => Viscosity::roelands_from_eta0(eta0, p_h, alpha * p_h)
                .map_err(|e| format!("roelands (z from eta0): {e}"))?,
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
    fn sigma(&self) -> Option<f64> {
        match (self.body1.rq, self.body2.rq) {
            (Some(a), Some(b)) => Some((a * a + b * b).sqrt()),
            (Some(a), None) | (None, Some(a)) => Some(a),
            (None, None) => None,
        }
    }
}

/// Read and parse a case file; the error names the file (and the TOML problem).
pub fn read_case(path: &std::path::Path) -> Result<CaseSpec, String> {
    let name = path.display();
    let text = std::fs::read_to_string(path).map_err(|e| format!("{name}: {e}"))?;
    toml::from_str(&text).map_err(|e| {
        format!(
            "{name}: {}",
            e.to_string().lines().collect::<Vec<_>>().join(" ")
        )
    })
}

/// Put a converged numerical answer at the head of the film comparison (a failure is still
/// reported, but is no number to compare with); returns its p_max in Pa.
fn add_numerical(
    films: &mut Vec<(String, String, f64)>,
    o: &crate::solve::solution::Outputs,
    to_h: impl Fn(f64) -> f64,
    p_h: f64,
) -> Option<f64> {
    if o.status != crate::solve::Status::Converged {
        return None;
    }
    films.insert(
        0,
        ("ehlmap (numerical)".into(), "h_min".into(), to_h(o.h_min)),
    );
    films.insert(0, ("ehlmap (numerical)".into(), "h_c".into(), to_h(o.h_c)));
    Some(o.p_max * p_h)
}

/// Fills the film parameter and its reading from the first `h_min` of the films.
pub(crate) fn film_parameter(spec: &CaseSpec, r: &mut CaseReport) {
    let h_min = r.films.iter().find(|f| f.1 == "h_min").map(|f| f.2);
    r.film_parameter = match (spec.sigma(), h_min) {
        (Some(s), Some(h)) if s > 0.0 => Some(h / s),
        _ => None,
    };
    r.film_reading = r.film_parameter.map(|lam| {
        if lam < 1.0 {
            "boundary lubrication (Lambda < 1)".to_string()
        } else if lam <= 3.0 {
            "mixed lubrication (1 <= Lambda <= 3)".to_string()
        } else {
            "full film (Lambda > 3)".to_string()
        }
    });
}

/// A readable report in engineering units.
pub fn summary(r: &CaseReport) -> String {
    let mut s = if r.contact == "point" {
        format!(
            "point contact: Rx = {:.3} mm, Ry = {:.3} mm, D = Rx/Ry = {:.5}, k = a/b = {:.4}\n\
             Hertz: a = {:.4} mm, b = {:.4} mm, p_h = {:.3} GPa, E' = {:.1} GPa\n\
             groups (u_m): W = {:.3e}, U = {:.3e}, G = {:.0}; g_v = {:.3e}, g_e = {:.3e}, regime {}\n",
            r.r * 1e3,
            r.ry.unwrap_or(f64::NAN) * 1e3,
            r.d.unwrap_or(f64::NAN),
            r.k.unwrap_or(f64::NAN),
            r.a.unwrap_or(f64::NAN) * 1e3,
            r.b * 1e3,
            r.p_h * 1e-9,
            r.e_reduced * 1e-9,
            r.w_prime,
            r.u_mean,
            r.g,
            r.g_v,
            r.g_e,
            r.regime
        )
    } else {
        format!(
            "line contact: R = {:.3} mm, E' = {:.1} GPa, b = {:.4} mm, p_h = {:.3} GPa\n\
             groups (u_m): W' = {:.3e}, U = {:.3e}, G = {:.0}; g_v = {:.0}, g_e = {:.2}, regime {}\n",
            r.r * 1e3,
            r.e_reduced * 1e-9,
            r.b * 1e3,
            r.p_h * 1e-9,
            r.w_prime,
            r.u_mean,
            r.g,
            r.g_v,
            r.g_e,
            r.regime
        )
    };
    if let Some(l) = &r.lubricant {
        s.push_str(&format!(
            "lubricant: {} at {:.1} C: nu = {:.2} mm^2/s, rho = {:.0} kg/m^3 (Walther A = {:.4}, B = {:.4})\n",
            l.name, l.temperature, l.nu, l.rho, l.walther.a, l.walther.b
        ));
    }
    let z = match r.models.viscosity {
        Viscosity::Roelands { z, .. } => format!(" z = {z:.3}"),
        Viscosity::Barus => String::new(),
    };
    s.push_str(&format!(
        "solver models: {}{z}, {}\n",
        r.models.viscosity.name(),
        r.models.density.name()
    ));
    s.push_str(&format!(
        "eta0 = {:.4} Pa s, alpha = {:.3e} 1/Pa\n\
         Moes (u_s): M = {:.3}, L = {:.3}; solver: lambda = {:.4e}, alpha_bar = {:.3}\n",
        r.eta0, r.alpha, r.m, r.l, r.lambda, r.alpha_bar
    ));
    if let Some(o) = &r.numerical {
        s.push_str(&format!("numerical solve: {} ({})\n", o.status, o.reason));
    }
    for (name, what, h) in &r.films {
        let base = r
            .films
            .iter()
            .find(|f| f.0.starts_with("ehlmap") && &f.1 == what);
        let dev = match base {
            Some(b) if !name.starts_with("ehlmap") => {
                format!("  ({:+.1} % vs ehlmap)", 100.0 * (h / b.2 - 1.0))
            }
            _ => String::new(),
        };
        s.push_str(&format!("{what:<6} {:>9.4} um  {name}{dev}\n", h * 1e6));
    }
    if let Some(p) = r.p_max {
        s.push_str(&format!("p_max  {:.3} GPa\n", p * 1e-9));
    }
    if let (Some(l), Some(t)) = (r.film_parameter, &r.film_reading) {
        s.push_str(&format!(
            "film parameter Lambda = h_min/sigma = {l:.2}: {t}\n"
        ));
    }
    s
}
