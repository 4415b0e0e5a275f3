//! A dimensional case ([`crate::model::case_file::CaseSpec`]) converted to Moes' parameters: the
//! geometry checked per contact, the Hertzian and Hamrock/Dowson groups, the Moes case the
//! solver takes, and the published formulas' films.
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
use crate::model::case_file::{check, e_reduced, CaseError, CaseSpec};
use crate::model::formulas::{
    dowson_higginson_line_hmin, dowson_toyoda_line_hc, elliptic_g_params, elliptic_regime_hmin,
    hamrock_dowson_hc, hamrock_dowson_hmin, line_g_params, line_regime_hmin, moes_line_hc,
    nvm_point_hc, GParams, HdGroups, Regime,
};
use crate::model::hertz::{ellipse_from_d, Ellipse};
use crate::model::oils::Resolved;
use serde::Serialize;
use std::f64::consts::PI;

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
    /// Fixed finest grid of the solve; `None`: the accuracy ladder picks it (the default).
    pub grid: Option<usize>,
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

/// The case's fixed finest grid when it names one, within the range every solve takes
/// ([`Contact::grid_range`], as `ehlmap solve --grid` and a sweep's `numerics.grid`).
fn case_grid(spec: &CaseSpec, contact: Contact) -> Result<Option<usize>, CaseError> {
    let unit = match contact {
        Contact::Line => "points",
        Contact::Point => "points per direction",
    };
    let Some(grid) = spec.grid else {
        return Ok(None);
    };
    let (lo, hi) = contact.grid_range();
    if !(lo..=hi).contains(&grid) {
        return Err(CaseError::invalid(format!(
            "grid = {grid} is invalid: {lo} to {hi} {unit} for {contact} contacts"
        )));
    }
    Ok(Some(grid))
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
    let inv = 1.0 / spec.body1.radius_x + 1.0 / spec.body2.radius_x;
    check(name, inv, inv > 0.0, why)?;
    Ok(inv)
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
    let grid = case_grid(spec, Contact::Line)?;
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
    let grid = case_grid(spec, Contact::Point)?;
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
    grid: Option<usize>,
    u_s: f64,
    shape: Shape,
    lubricant: Lubricant,
    loads: Loads,
    gp: GParams,
    regime: Regime,
    films: Vec<(String, String, f64)>,
) -> Derived {
    let (lambda, alpha_bar) = match &case {
        Case::Line(c) => {
            let v = c.venner();
            (v.lambda, v.alpha_bar)
        }
        Case::Point(c) => {
            let v = c.venner();
            (v.lambda, v.alpha_bar)
        }
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
