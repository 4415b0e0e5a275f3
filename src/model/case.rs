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

use crate::model::lubricant::{Density, Viscosity};
use crate::model::roughness::Roughness;
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

impl Elasticity {
    /// The name stored in TOML, JSON and Parquet (`elastic`, `rigid`).
    pub fn as_str(&self) -> &'static str {
        match self {
            Elasticity::Elastic => "elastic",
            Elasticity::Rigid => "rigid",
        }
    }
}

impl fmt::Display for Elasticity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl std::str::FromStr for Elasticity {
    type Err = ParamError;
    fn from_str(s: &str) -> Result<Self, ParamError> {
        [Elasticity::Elastic, Elasticity::Rigid]
            .into_iter()
            .find(|e| e.as_str() == s)
            .ok_or_else(|| ParamError::Unknown {
                what: "elasticity",
                name: s.to_string(),
                expected: "elastic or rigid",
            })
    }
}

impl PartialEq<&str> for Elasticity {
    fn eq(&self, other: &&str) -> bool {
        self.as_str() == *other
    }
}

/// Lubricant and solid models of a case.
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
pub struct Models {
    /// Elastic or rigid surfaces.
    pub elasticity: Elasticity,
    /// Pressure-viscosity law (Barus or Roelands).
    pub viscosity: Viscosity,
    /// Pressure-density law (incompressible or Dowson-Higginson).
    pub density: Density,
    /// Rough surfaces (mixed lubrication); `None` or `sigma = 0`: smooth.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub roughness: Option<Roughness>,
}

impl Models {
    /// The family name of these models: "elastic barus incompressible" (elasticity, viscosity
    /// and density names), with " rough" for rough surfaces. Cases of one family and equal
    /// (M, L, D) have equal films when the family is `Models::default()`'s.
    pub fn family(&self) -> String {
        let f = family(self.elasticity, self.viscosity.name(), self.density.name());
        match self.roughness.filter(|r| r.is_rough()) {
            Some(_) => f + " rough",
            None => f,
        }
    }
}

/// The family name from the stored names (see [`Models::family`]).
pub fn family(elasticity: Elasticity, viscosity: &str, density: &str) -> String {
    format!("{elasticity} {viscosity} {density}")
}

pub(crate) use crate::model::error::check;
pub use crate::model::error::ParamError;

/// A steady isothermal line contact in Moes parameters.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct LineCase {
    /// Moes load parameter M > 0.
    pub m: f64,
    /// Moes lubricant parameter L >= 0.
    pub l: f64,
    /// Elasticity, viscosity and density models.
    pub models: Models,
}

/// The line-contact groups of the Hertzian (Venner) scaling.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VennerLine {
    /// Reynolds coefficient `lambda = 12 eta0 u_m R^2/(b^3 p_h) = 3 pi^2/(8 M^2)`.
    pub lambda: f64,
    /// Dimensionless pressure-viscosity coefficient `alpha_bar = alpha p_h = L sqrt(M/(2 pi))`.
    pub alpha_bar: f64,
    /// H_Moes / H_Venner `= 8M/pi`.
    pub h_scale: f64,
}

impl LineCase {
    /// A case with the default models (elastic, Barus, incompressible), validated.
    pub fn new(m: f64, l: f64) -> Result<Self, ParamError> {
        Self::with_models(m, l, Models::default())
    }

    /// A case with the given models, validated as by [`LineCase::validate`].
    pub fn with_models(m: f64, l: f64, models: Models) -> Result<Self, ParamError> {
        let c = LineCase { m, l, models };
        c.validate()?;
        Ok(c)
    }

    /// Checks M > 0, L >= 0 (both finite) and the models' own parameters; the error names the
    /// first offending value.
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
        if let Some(r) = &self.models.roughness {
            r.validate()?;
        }
        self.models.density.validate()
    }

    /// The Hertzian (Venner) groups lambda, alpha_bar and the film scale of this case.
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

/// A steady isothermal point contact (circular or elliptic) in Moes parameters.
///
/// W = w/(E' Rx^2), U = eta0 u_s/(E' Rx), M = W U^(-3/4), L = G U^(1/4), H_Moes = (h/Rx) U^(-1/2),
/// D = Rx/Ry in (0, 1].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PointCase {
    /// Moes load parameter M > 0.
    pub m: f64,
    /// Moes lubricant parameter L >= 0.
    pub l: f64,
    /// Ellipticity parameter D = Rx/Ry in (0, 1] (1: circular).
    pub d: f64,
    /// Elasticity, viscosity and density models.
    pub models: Models,
}

/// The point-contact groups of the Hertzian scaling X = x/b, Y = y/b, P = p/p_h, H = h Rx/b^2
/// (b the semi-axis along the rolling direction x, a = k b across it).
///
/// Derivation. Hertz: p_h = 3w/(2 pi a b) and b^3 = 6 E w R/(pi k E') with 1/R = 1/Rx + 1/Ry,
/// i.e. R = Rx/(1 + D), E = E(1 - kappa^2) the complete elliptic integral of the second kind and
/// kappa = 1/k. Together: b E'/(p_h Rx) = 4E/(1 + D). Then
///
/// * film: h = h0 + x^2/(2Rx) + y^2/(2Ry) + (2/(pi E')) integral p/r, so
///   H = H0 + X^2/2 + D Y^2/2 + c integral P/R dX'dY' with c = (2/pi) p_h Rx/(E' b) = (1+D)/(2 pi E);
/// * load: p_h b^2 integral P = w, so integral P dX dY = 2 pi a b/(3 b^2) = 2 pi k/3;
/// * lambda = 12 eta0 u_m Rx^2/(b^3 p_h) = 4 pi k (pi k (1+D)/(6E))^(1/3) M^(-4/3);
/// * alpha_bar = alpha p_h = (3/(2 pi k)) (pi k (1+D)/(6E))^(2/3) L M^(1/3);
/// * H_Moes = H (b/Rx)^2 U^(-1/2) = H (6 E M/(pi k (1+D)))^(2/3).
///
/// At D = 1 (k = 1, E = pi/2) these are the circular forms lambda = pi (128/3)^(1/3) M^(-4/3),
/// alpha_bar = (3M/2)^(1/3) L/pi, H_Moes = H (3M/2)^(2/3), c = 2/pi^2, load 2 pi/3 (tested).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VennerPoint {
    /// Reynolds coefficient `lambda = 12 eta0 u_m Rx^2/(b^3 p_h)`.
    pub lambda: f64,
    /// Dimensionless pressure-viscosity coefficient `alpha_bar = alpha p_h`.
    pub alpha_bar: f64,
    /// H_Moes / H_Venner.
    pub h_scale: f64,
    /// k = a/b >= 1.
    pub k: f64,
    /// E(1 - 1/k^2).
    pub e_int: f64,
    /// Coefficient of the deformation integral, (1+D)/(2 pi E).
    pub film_coef: f64,
    /// Target of integral P dX dY, 2 pi k/3.
    pub load: f64,
}

impl PointCase {
    /// A case with the default models, validated.
    pub fn new(m: f64, l: f64, d: f64) -> Result<Self, ParamError> {
        Self::with_models(m, l, d, Models::default())
    }

    /// A case with the given models, validated as by [`PointCase::validate`].
    pub fn with_models(m: f64, l: f64, d: f64, models: Models) -> Result<Self, ParamError> {
        let c = PointCase { m, l, d, models };
        c.validate()?;
        Ok(c)
    }

    /// Checks M > 0, L >= 0, D in (0, 1] (all finite) and the models' own parameters; the error
    /// names the first offending value.
    pub fn validate(&self) -> Result<(), ParamError> {
        LineCase {
            m: self.m,
            l: self.l,
            models: self.models,
        }
        .validate()?;
        check(
            "D",
            self.d,
            self.d > 0.0 && self.d <= 1.0,
            "the ellipticity D = Rx/Ry must be in (0, 1]",
        )
    }

    /// The exact Hertz ellipse of D.
    pub fn ellipse(&self) -> crate::model::hertz::Ellipse {
        crate::model::hertz::ellipse_from_d(self.d).expect("D validated in (0, 1]")
    }

    /// The Hertzian (Venner) groups of this case, from the exact Hertz ellipse of D.
    pub fn venner(&self) -> VennerPoint {
        let el = self.ellipse();
        let (k, e, d, m) = (el.k, el.e, self.d, self.m);
        let q = PI * k * (1.0 + d) / (6.0 * e);
        VennerPoint {
            lambda: 4.0 * PI * k * q.cbrt() * m.powf(-4.0 / 3.0),
            alpha_bar: 3.0 / (2.0 * PI * k) * q.powf(2.0 / 3.0) * self.l * m.cbrt(),
            h_scale: (m / q).powf(2.0 / 3.0),
            k,
            e_int: e,
            film_coef: (1.0 + d) / (2.0 * PI * e),
            load: 2.0 * PI * k / 3.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contact_names_round_trip_and_unknown_names_are_errors() {
        for c in Contact::ALL {
            assert_eq!(c.as_str().parse::<Contact>(), Ok(c));
            assert_eq!(c, c.as_str());
        }
        let e = "circular".parse::<Contact>().unwrap_err().to_string();
        assert_eq!(e, "unknown contact \"circular\": expected line or point");
        let case = Case::Point(PointCase::new(20.0, 10.0, 0.5).unwrap());
        assert_eq!(
            (case.contact(), case.m(), case.l(), case.d()),
            (Contact::Point, 20.0, 10.0, Some(0.5))
        );
        let json = serde_json::to_value(case).unwrap();
        assert_eq!(json["contact"], "point");
    }

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

    #[test]
    fn point_groups_match_dimensional_hertz() {
        // From dimensional groups: W, U, G, D -> Hertz b, a, p_h by the textbook relations,
        // then lambda, alpha_bar, H scale, film coefficient and load from their definitions.
        for d in [1.0, 0.6, 0.25, 0.05] {
            let (w, u, g) = (3.0e-6_f64, 1.5e-11_f64, 4500.0_f64);
            let m = w * u.powf(-0.75);
            let l = g * u.powf(0.25);
            let c = PointCase::new(m, l, d).unwrap();
            let v = c.venner();
            let el = c.ellipse();
            // Units with E' = Rx = 1: R = Rx Ry/(Rx + Ry).
            let r = 1.0 / (1.0 + d);
            let b = (6.0 * el.e * w * r / (PI * el.k)).cbrt();
            let a = el.k * b;
            let ph = 3.0 * w / (2.0 * PI * a * b);
            let lambda = 12.0 * (u / 2.0) / (b.powi(3) * ph);
            assert!((v.lambda / lambda - 1.0).abs() < 1e-12, "D={d}");
            assert!((v.alpha_bar / (g * ph) - 1.0).abs() < 1e-12, "D={d}");
            assert!(
                (v.h_scale / (b * b / u.sqrt()) - 1.0).abs() < 1e-12,
                "D={d}"
            );
            // Film coefficient (2/(pi E')) p_h b / (b^2/Rx) and load w/(p_h b^2).
            assert!(
                (v.film_coef / (2.0 / PI * ph / b) - 1.0).abs() < 1e-12,
                "D={d}"
            );
            assert!((v.load / (w / (ph * b * b)) - 1.0).abs() < 1e-12, "D={d}");
        }
    }

    #[test]
    fn point_groups_reduce_to_circular_forms() {
        let (m, l) = (20.0, 10.0);
        let v = PointCase::new(m, l, 1.0).unwrap().venner();
        assert!(
            (v.lambda / (PI * (128.0_f64 / 3.0).cbrt() * m.powf(-4.0 / 3.0)) - 1.0).abs() < 1e-14
        );
        assert!((v.alpha_bar / ((1.5 * m).cbrt() * l / PI) - 1.0).abs() < 1e-14);
        assert!((v.h_scale / (1.5 * m).powf(2.0 / 3.0) - 1.0).abs() < 1e-14);
        assert!((v.film_coef * PI * PI / 2.0 - 1.0).abs() < 1e-14);
        assert!((v.load / (2.0 * PI / 3.0) - 1.0).abs() < 1e-14);
        // PHYSICS.md's worked numbers for M = 20, L = 10.
        assert!((v.lambda - 0.2022).abs() < 1e-4, "{}", v.lambda);
        assert!((v.alpha_bar - 9.891).abs() < 1e-3, "{}", v.alpha_bar);
        assert!((v.h_scale - 9.655).abs() < 1e-3, "{}", v.h_scale);
        assert!(PointCase::new(20.0, 10.0, 0.0).is_err());
        assert!(PointCase::new(20.0, 10.0, 1.5).is_err());
    }
}

/// Which contact a case is: a line contact (infinitely long cylinders) or a point contact of
/// ellipticity D. Stored by name (`line`, `point`) in JSON, TOML and Parquet.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Contact {
    /// Line contact (`line`): one-dimensional problem in X.
    Line,
    /// Point contact (`point`), circular or elliptic: two-dimensional problem in (X, Y).
    Point,
}

impl Contact {
    /// Both contacts.
    pub const ALL: [Contact; 2] = [Contact::Line, Contact::Point];

    /// The stored name.
    pub fn as_str(&self) -> &'static str {
        match self {
            Contact::Line => "line",
            Contact::Point => "point",
        }
    }

    /// Smallest and largest finest grid a solve accepts (points per direction for point
    /// contacts).
    pub fn grid_range(&self) -> (usize, usize) {
        match self {
            Contact::Line => (33, (1 << 20) + 1),
            Contact::Point => (17, 2049),
        }
    }
}

impl std::fmt::Display for Contact {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl std::str::FromStr for Contact {
    type Err = ParamError;
    fn from_str(s: &str) -> Result<Self, ParamError> {
        Contact::ALL
            .into_iter()
            .find(|c| c.as_str() == s)
            .ok_or_else(|| ParamError::Unknown {
                what: "contact",
                name: s.to_string(),
                expected: "line or point",
            })
    }
}

impl PartialEq<&str> for Contact {
    fn eq(&self, other: &&str) -> bool {
        self.as_str() == *other
    }
}

/// A case in Moes' parameters, line or point contact: what [`crate::strategy::solve_case::solve`] solves.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "contact", rename_all = "lowercase")]
pub enum Case {
    /// A line contact.
    Line(LineCase),
    /// A point contact of ellipticity D.
    Point(PointCase),
}

impl Case {
    /// Which contact.
    pub fn contact(&self) -> Contact {
        match self {
            Case::Line(_) => Contact::Line,
            Case::Point(_) => Contact::Point,
        }
    }

    /// Moes' load parameter M.
    pub fn m(&self) -> f64 {
        match self {
            Case::Line(c) => c.m,
            Case::Point(c) => c.m,
        }
    }

    /// Moes' lubricant parameter L.
    pub fn l(&self) -> f64 {
        match self {
            Case::Line(c) => c.l,
            Case::Point(c) => c.l,
        }
    }

    /// The ellipticity D = Rx/Ry of a point contact.
    pub fn d(&self) -> Option<f64> {
        match self {
            Case::Line(_) => None,
            Case::Point(c) => Some(c.d),
        }
    }

    /// The lubricant and elasticity models.
    pub fn models(&self) -> Models {
        match self {
            Case::Line(c) => c.models,
            Case::Point(c) => c.models,
        }
    }

    /// The same case with the surfaces `roughness` (`None`: smooth).
    pub fn with_roughness(mut self, roughness: Option<Roughness>) -> Case {
        match &mut self {
            Case::Line(c) => c.models.roughness = roughness,
            Case::Point(c) => c.models.roughness = roughness,
        }
        self
    }
}

impl From<LineCase> for Case {
    fn from(c: LineCase) -> Self {
        Case::Line(c)
    }
}

impl From<PointCase> for Case {
    fn from(c: PointCase) -> Self {
        Case::Point(c)
    }
}
