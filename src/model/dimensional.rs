//! A dimensional case file (SI units) and its conversion to Moes' parameters: the bodies, the
//! lubricant (eta0 and alpha directly, or a Walther oil at a temperature,
//! [`crate::model::oils`]), validation (errors name the input), the Hertzian and Hamrock/Dowson
//! groups, and the published formulas' films.
//!
//! Common definitions: `2/E' = (1-nu1^2)/E1 + (1-nu2^2)/E2`, `G = alpha E'`, `u_s = u1 + u2`,
//! `u_m = u_s/2`; Hamrock/Dowson groups use `u_m`, Moes groups `u_s` (see
//! [`crate::model::formulas`]). Film parameter `Lambda = h_min/sigma`,
//! `sigma = sqrt(Rq1^2 + Rq2^2)`.
//!
//! Line contacts: `R = 1/(1/R1 + 1/R2)` (convex radii positive, a concave race negative),
//! `W' = w'/(E'R)`, `U_m = eta0 u_m/(E'R)`, `G = alpha E'`, `M = W' U_s^-1/2`, `L = G U_s^1/4`
//! with `U_s = 2 U_m`, `b = R sqrt(8W'/pi)`, `p_h = E'b/(4R)`, `h = H_Moes R U_s^1/2`; compared
//! with Moes 1992, Dowson-Toyoda, Dowson-Higginson and the
//! textbook regime formula.
//!
//! Point contacts. Rolling along x: `1/Rx = 1/Rx1 + 1/Rx2`, `1/Ry = 1/Ry1 + 1/Ry2` (convex
//! positive, concave negative, an omitted or infinite `radius_y` is a cylinder axis), both must be
//! positive. `D = Rx/Ry` must be in `(0, 1]`: the ellipse's long axis across the rolling direction
//! (a ball on a race, crossed cylinders rolling along the smaller radius). `D > 1` (long axis
//! along the rolling direction) is another problem, not a swap of axes: it exits with code 2.
//!
//! Exact Hertz ([`crate::model::hertz::ellipse_from_d`]): `k = a/b`, `E` the complete elliptic integral
//! of the second kind, `b^3 = 6 E w R/(pi k E')` with `R = Rx/(1 + D)`, `a = k b`,
//! `p_h = 3w/(2 pi a b)`. Groups: `W = w/(E'Rx^2)`, `U_m = eta0 u_m/(E'Rx)`, `G = alpha E'`,
//! Moes `M = W U_s^-3/4`, `L = G U_s^1/4` (`U_s = 2U_m`), `h = H_Moes Rx U_s^1/2`. Compared
//! with: NVM 1994 central film, Hamrock-Dowson 1977 central and minimum films, the textbook
//! elliptic regime formula (g-parameters).

use crate::model::case::{Case, Contact, LineCase, Models, PointCase};
use crate::model::error::ParamError;
use crate::model::formulas::{
    dowson_higginson_line_hmin, dowson_toyoda_line_hc, elliptic_g_params, elliptic_regime_hmin,
    hamrock_dowson_hc, hamrock_dowson_hmin, line_g_params, line_regime_hmin, moes_line_hc,
    nvm_point_hc, GParams, HdGroups, Regime,
};
use crate::model::hertz::{ellipse_from_d, Ellipse};
use crate::model::lubricant::{Density, Viscosity};
use crate::model::oils::{LubricantSpec, Resolved};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Default finest grid of a line case: points.
pub const LINE_CASE_GRID: usize = 4097;
/// Default finest grid of a point case: points per direction.
pub const POINT_CASE_GRID: usize = 129;

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
    fn invalid(msg: impl Into<String>) -> Self {
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
    /// Finest grid: points (line, default [`LINE_CASE_GRID`]) or points per direction (point,
    /// default [`POINT_CASE_GRID`]).
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

fn check(name: &str, v: f64, ok: bool, why: &str) -> Result<(), CaseError> {
    if v.is_finite() && ok {
        Ok(())
    } else {
        Err(CaseError::invalid(format!(
            "{name} = {v} is invalid: {why}"
        )))
    }
}

/// Reduced modulus `E'`.
fn e_reduced(b1: &Body, b2: &Body) -> f64 {
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
            (None, true) => Viscosity::roelands_from_eta0(eta0, p_h, alpha * p_h)
                .map_err(|e| CaseError::invalid(format!("roelands (z from eta0): {e}")))?,
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
        CaseError::invalid(format!(
            "{name}: {}",
            e.to_string().lines().collect::<Vec<_>>().join(" ")
        ))
    })
}

/// A case's groups in SI units and Moes' parameters (the JSON fields of `ehlmap case`).
#[derive(Clone, Debug, Serialize)]
pub struct Groups {
    /// Line: R; point: Rx (m).
    pub r: f64,
    /// Point: Ry (m).
    pub ry: Option<f64>,
    /// Point: ellipticity D = Rx/Ry.
    pub d: Option<f64>,
    /// Point: exact k = a/b >= 1.
    pub k: Option<f64>,
    /// Point: Hertz semi-axis across the rolling direction a (m).
    pub a: Option<f64>,
    /// Reduced modulus E' (Pa).
    pub e_reduced: f64,
    /// Ambient viscosity eta0 (Pa s).
    pub eta0: f64,
    /// Pressure-viscosity coefficient alpha (1/Pa).
    pub alpha: f64,
    /// The Walther oil the viscosity came from, when the case file named one.
    pub lubricant: Option<Resolved>,
    /// The solver's lubricant models (the published formulas are Barus, incompressible).
    pub models: Models,
    /// Load group (u_m convention): W' (line) or W (point).
    pub w_prime: f64,
    /// Speed group U (u_m convention): `eta0 u_m/(E'R)` (line) or `eta0 u_m/(E'Rx)` (point).
    pub u_mean: f64,
    /// Materials group G = alpha E'.
    pub g: f64,
    /// Moes' load parameter M (u_s convention).
    pub m: f64,
    /// Moes' lubricant parameter L (u_s convention).
    pub l: f64,
    /// Solver (Venner) Reynolds coefficient lambda.
    pub lambda: f64,
    /// Solver (Venner) pressure-viscosity group alpha_bar = alpha p_h.
    pub alpha_bar: f64,
    /// Hertz semi-width along x (m).
    pub b: f64,
    /// Maximum Hertz pressure p_h (Pa).
    pub p_h: f64,
    /// The textbook's viscosity parameter g_v (line or elliptic definition).
    pub g_v: f64,
    /// The textbook's elasticity parameter g_e (line or elliptic definition).
    pub g_e: f64,
    /// The textbook regime (the formula with the largest g_h), as the [`Regime`] variant's name.
    pub regime: String,
}

/// A case file derived: its groups, the Moes case the solver takes, and the published formulas'
/// films (m).
#[derive(Clone, Debug)]
pub struct Derived {
    /// The case in Moes' parameters with the solver's models.
    pub case: Case,
    /// Finest grid of the solve.
    pub grid: usize,
    /// The speed group U_s = 2 U_m: a film is h = H_Moes r U_s^(1/2) (m).
    pub u_s: f64,
    /// The groups.
    pub groups: Groups,
    /// The published formulas' films in m: (name, h_c or h_min, value).
    pub films: Vec<(String, String, f64)>,
}

impl Derived {
    /// A film in Moes units as metres.
    pub fn to_h(&self, h_moes: f64) -> f64 {
        h_moes * self.groups.r * self.u_s.sqrt()
    }
}

impl CaseSpec {
    /// Validate the case and derive its groups, its Moes case and the published films.
    pub fn derive(&self) -> Result<Derived, CaseError> {
        self.validate_common()?;
        match self.contact {
            Contact::Line => line_groups(self),
            Contact::Point => point_groups(self),
        }
    }
}

/// `radius_y`: a line contact's bodies are cylinders (omitted or infinite); a point contact's
/// must be nonzero (infinite or omitted: a cylinder axis).
fn check_radius_y(spec: &CaseSpec, contact: Contact) -> Result<(), CaseError> {
    for (n, b) in [("body1", &spec.body1), ("body2", &spec.body2)] {
        match (contact, b.radius_y) {
            (Contact::Line, Some(r)) if r.is_finite() => {
                return Err(CaseError::invalid(format!(
                    "{n}.radius_y applies to point contacts (a line contact's bodies are cylinders)"
                )))
            }
            (Contact::Point, Some(r)) if r == 0.0 || r.is_nan() => {
                return Err(CaseError::invalid(format!(
                    "{n}.radius_y = {r} is invalid: nonzero (m), or inf/omitted for a cylinder axis"
                )))
            }
            _ => {}
        }
    }
    Ok(())
}

/// A sum of inverse radii `inv` (1/m), which must be positive for a convex contact.
fn curvature(name: &str, inv: f64, why: &str) -> Result<f64, CaseError> {
    check(name, inv, inv > 0.0, why)?;
    Ok(inv)
}

/// The bodies' radius_y checked for the contact, and 1/Rx1 + 1/Rx2 (1/m), which must be
/// positive.
fn x_curvature(spec: &CaseSpec, contact: Contact) -> Result<f64, CaseError> {
    check_radius_y(spec, contact)?;
    let (name, why) = match contact {
        Contact::Line => (
            "1/R1 + 1/R2",
            "the surfaces do not form a convex contact (concave radius too small)",
        ),
        Contact::Point => (
            "1/Rx1 + 1/Rx2",
            "the surfaces do not form a convex contact along x (concave radius too small)",
        ),
    };
    curvature(
        name,
        1.0 / spec.body1.radius_x + 1.0 / spec.body2.radius_x,
        why,
    )
}

/// A line case's radius R and contact length (m), validated.
fn line_geometry(spec: &CaseSpec) -> Result<(f64, f64), CaseError> {
    let inv = x_curvature(spec, Contact::Line)?;
    let length = spec.length.ok_or(CaseError::invalid(
        "length (m) is missing: a line contact needs the contact length",
    ))?;
    check(
        "length",
        length,
        length > 0.0,
        "the contact length must be positive (m)",
    )?;
    Ok((1.0 / inv, length))
}

/// A line case's textbook parameters, regime and the published formulas' films (m).
fn line_films(
    gr: HdGroups,
    m: f64,
    l: f64,
    r: f64,
    u_s: f64,
) -> (GParams, Regime, Vec<(String, String, f64)>) {
    let gp = line_g_params(gr);
    let (regime, hmin_regime) = line_regime_hmin(gr);
    let to_h = |h_moes: f64| h_moes * r * u_s.sqrt();
    let films = vec![
        ("Moes 1992".into(), "h_c".into(), to_h(moes_line_hc(m, l))),
        (
            "Dowson-Toyoda 1979".into(),
            "h_c".into(),
            dowson_toyoda_line_hc(gr) * r,
        ),
        (
            "Dowson-Higginson".into(),
            "h_min".into(),
            dowson_higginson_line_hmin(gr) * r,
        ),
        (
            format!("textbook regime formula ({regime:?})"),
            "h_min".into(),
            hmin_regime * r,
        ),
    ];
    (gp, regime, films)
}

fn line_groups(spec: &CaseSpec) -> Result<Derived, CaseError> {
    let (r, length) = line_geometry(spec)?;
    let (eta0, alpha, lub) = spec.lubricant()?;
    let grid = spec.grid.unwrap_or(LINE_CASE_GRID);
    if grid < 33 {
        return Err(CaseError::invalid(format!(
            "grid = {grid} is too small: at least 33 points"
        )));
    }
    let e_red = e_reduced(&spec.body1, &spec.body2);
    let w_prime = spec.load / length / (e_red * r);
    let u_m = eta0 * 0.5 * (spec.u1 + spec.u2) / (e_red * r);
    let g = alpha * e_red;
    let gr = HdGroups {
        u: u_m,
        g,
        w: w_prime,
    };
    let u_s = 2.0 * u_m;
    let m = w_prime / u_s.sqrt();
    let l = g * u_s.powf(0.25);
    let b = r * (8.0 * w_prime / PI).sqrt();
    let p_h = e_red * b / (4.0 * r);
    let (gp, regime, films) = line_films(gr, m, l, r, u_s);
    let models = spec.models(eta0, alpha, p_h)?;
    let case = Case::Line(LineCase::with_models(m, l, models)?);
    let lubricant = Lubricant::new(eta0, alpha, lub, models);
    let loads = Loads::new(e_red, w_prime, u_m, g, b, p_h);
    let shape = Shape::new(r, None, None);
    Ok(assemble(
        case, grid, u_s, shape, lubricant, loads, gp, regime, films,
    ))
}

fn inv_radius(r: Option<f64>) -> f64 {
    r.map_or(0.0, |r| 1.0 / r)
}

/// A point case's radii Rx, Ry (m) and D = Rx/Ry, validated.
fn point_geometry(spec: &CaseSpec) -> Result<(f64, f64, f64), CaseError> {
    if spec.length.is_some() {
        return Err(CaseError::invalid(
            "length applies to line contacts only (a point contact's load is in N)",
        ));
    }
    let inv_x = x_curvature(spec, Contact::Point)?;
    let inv_y = inv_radius(spec.body1.radius_y) + inv_radius(spec.body2.radius_y);
    check(
        "1/Ry1 + 1/Ry2",
        inv_y,
        inv_y > 0.0,
        "the surfaces do not form a convex contact across x (concave radius_y too small, or two cylinder axes: a line contact)",
    )?;
    let (rx, ry) = (1.0 / inv_x, 1.0 / inv_y);
    let d = rx / ry;
    if d > 1.0 {
        return Err(CaseError::invalid(format!(
            "D = Rx/Ry = {d:.4} > 1 (Rx = {:.4} mm, Ry = {:.4} mm): the contact ellipse is long along \
             the rolling direction x; this solver needs D in (0, 1] (long axis across x). Check which \
             radius is radius_x (the rolling direction)",
            rx * 1e3,
            ry * 1e3
        )));
    }
    Ok((rx, ry, d))
}

/// A point case's textbook parameters, regime and the published formulas' films (m).
fn point_films(
    gr: HdGroups,
    el: &Ellipse,
    m: f64,
    l: f64,
    d: f64,
    rx: f64,
    u_s: f64,
) -> (GParams, Regime, Vec<(String, String, f64)>) {
    let gp = elliptic_g_params(gr);
    let (regime, hmin_regime) = elliptic_regime_hmin(gr, el);
    let to_h = |h_moes: f64| h_moes * rx * u_s.sqrt();
    let films = vec![
        ("NVM 1994".into(), "h_c".into(), to_h(nvm_point_hc(m, l, d))),
        (
            "Hamrock-Dowson 1977".into(),
            "h_c".into(),
            hamrock_dowson_hc(gr, el.k) * rx,
        ),
        (
            "Hamrock-Dowson 1977".into(),
            "h_min".into(),
            hamrock_dowson_hmin(gr, el.k) * rx,
        ),
        (
            format!("textbook elliptic regime formula ({regime:?})"),
            "h_min".into(),
            hmin_regime * rx,
        ),
    ];
    (gp, regime, films)
}

fn point_groups(spec: &CaseSpec) -> Result<Derived, CaseError> {
    let (rx, ry, d) = point_geometry(spec)?;
    let (eta0, alpha, lub) = spec.lubricant()?;
    let grid = spec.grid.unwrap_or(POINT_CASE_GRID);
    if !(17..=2049).contains(&grid) {
        return Err(CaseError::invalid(format!(
            "grid = {grid} is invalid: 17 to 2049 points per direction"
        )));
    }
    let el = ellipse_from_d(d).map_err(|e| CaseError::invalid(format!("D: {e}")))?;
    let e_red = e_reduced(&spec.body1, &spec.body2);
    let w = spec.load / (e_red * rx * rx);
    let u_m = eta0 * 0.5 * (spec.u1 + spec.u2) / (e_red * rx);
    let g = alpha * e_red;
    let gr = HdGroups { u: u_m, g, w };
    let u_s = 2.0 * u_m;
    let m = w / u_s.powf(0.75);
    let l = g * u_s.powf(0.25);
    let r_eq = rx / (1.0 + d);
    let b = (6.0 * el.e * spec.load * r_eq / (PI * el.k * e_red)).cbrt();
    let a = el.k * b;
    let p_h = 3.0 * spec.load / (2.0 * PI * a * b);
    let (gp, regime, films) = point_films(gr, &el, m, l, d, rx, u_s);
    let models = spec.models(eta0, alpha, p_h)?;
    let case = Case::Point(PointCase::with_models(m, l, d, models)?);
    let lubricant = Lubricant::new(eta0, alpha, lub, models);
    let loads = Loads::new(e_red, w, u_m, g, b, p_h);
    let shape = Shape::new(rx, Some(ry), Some((d, el.k, a)));
    Ok(assemble(
        case, grid, u_s, shape, lubricant, loads, gp, regime, films,
    ))
}

/// A contact's radii: R (line) or Rx, Ry and the ellipse (D, k, a) (point).
struct Shape {
    r: f64,
    ry: Option<f64>,
    ellipse: Option<(f64, f64, f64)>,
}

/// The lubricant of a case: its viscosity, pressure-viscosity coefficient, oil and models.
struct Lubricant {
    eta0: f64,
    alpha: f64,
    lub: Option<Resolved>,
    models: Models,
}

/// The reduced modulus, the load, speed and materials groups, and the Hertz width and pressure.
struct Loads {
    e_reduced: f64,
    w_prime: f64,
    u_mean: f64,
    g: f64,
    b: f64,
    p_h: f64,
}

impl Shape {
    fn new(r: f64, ry: Option<f64>, ellipse: Option<(f64, f64, f64)>) -> Self {
        Shape { r, ry, ellipse }
    }
}

impl Lubricant {
    fn new(eta0: f64, alpha: f64, lub: Option<Resolved>, models: Models) -> Self {
        Lubricant {
            eta0,
            alpha,
            lub,
            models,
        }
    }
}

impl Loads {
    fn new(e_reduced: f64, w_prime: f64, u_mean: f64, g: f64, b: f64, p_h: f64) -> Self {
        Loads {
            e_reduced,
            w_prime,
            u_mean,
            g,
            b,
            p_h,
        }
    }
}

/// One case's [`Derived`] from its contact-specific parts.
#[allow(clippy::too_many_arguments)]
fn assemble(
    case: Case,
    grid: usize,
    u_s: f64,
    shape: Shape,
    lubricant: Lubricant,
    loads: Loads,
    gp: GParams,
    regime: Regime,
    films: Vec<(String, String, f64)>,
) -> Derived {
    let (lambda, alpha_bar) = match &case {
        Case::Line(c) => (c.venner().lambda, c.venner().alpha_bar),
        Case::Point(c) => (c.venner().lambda, c.venner().alpha_bar),
    };
    let groups = Groups {
        r: shape.r,
        ry: shape.ry,
        d: shape.ellipse.map(|e| e.0),
        k: shape.ellipse.map(|e| e.1),
        a: shape.ellipse.map(|e| e.2),
        e_reduced: loads.e_reduced,
        eta0: lubricant.eta0,
        alpha: lubricant.alpha,
        lubricant: lubricant.lub,
        models: lubricant.models,
        w_prime: loads.w_prime,
        u_mean: loads.u_mean,
        g: loads.g,
        m: case.m(),
        l: case.l(),
        lambda,
        alpha_bar,
        b: loads.b,
        p_h: loads.p_h,
        g_v: gp.g_v,
        g_e: gp.g_e,
        regime: format!("{regime:?}"),
    };
    Derived {
        case,
        grid,
        u_s,
        groups,
        films,
    }
}
