//! A dimensional line-contact case (SI units in, engineering units out): equivalent radius,
//! reduced modulus, the Hamrock/Dowson groups (mean speed u_m) and Moes' groups (sum speed u_s),
//! Hertz half width and pressure, a numerical solve, and the published formulas beside it.
//!
//! R = 1/(1/R1 + 1/R2) (convex radii positive, a concave race negative), 2/E' = (1-nu1^2)/E1 +
//! (1-nu2^2)/E2, W' = w'/(E'R), U_m = eta0 u_m/(E'R), G = alpha E', M = W' U_s^-1/2,
//! L = G U_s^1/4 with U_s = 2 U_m, b = R sqrt(8W'/pi), p_h = E'b/(4R), h = H_Moes R U_s^1/2.
//! Point contacts join when their solver lands.

use crate::formulas::{
    dowson_higginson_line_hmin, dowson_toyoda_line_hc, line_g_params, line_regime_hmin,
    moes_line_hc, HdGroups,
};
use crate::params::LineCase;
use crate::solver::line::{solve_line, LineSolveParams};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// One body: radius in the rolling direction (m; negative for concave), modulus (Pa), Poisson.
#[derive(Clone, Copy, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Body {
    pub radius_x: f64,
    #[serde(rename = "E")]
    pub e: f64,
    pub nu: f64,
    /// RMS roughness Rq (m), optional.
    #[serde(default)]
    pub rq: Option<f64>,
}

/// The case file.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CaseSpec {
    pub contact: String,
    pub body1: Body,
    pub body2: Body,
    /// Load (N) over the contact length (m).
    pub load: f64,
    pub length: f64,
    /// Surface speeds (m/s).
    pub u1: f64,
    pub u2: f64,
    /// Ambient viscosity (Pa s) and pressure-viscosity coefficient (1/Pa).
    pub eta0: f64,
    pub alpha: f64,
    #[serde(default = "default_grid")]
    pub grid: usize,
}

fn default_grid() -> usize {
    4097
}

/// Everything derived from a case, and the results.
#[derive(Clone, Debug, Serialize)]
pub struct CaseReport {
    pub r: f64,
    pub e_reduced: f64,
    pub w_prime: f64,
    pub u_mean: f64,
    pub g: f64,
    pub m: f64,
    pub l: f64,
    pub b: f64,
    pub p_h: f64,
    pub g_v: f64,
    pub g_e: f64,
    pub regime: String,
    pub numerical: Option<crate::solution::Outputs>,
    /// Film thicknesses in m: (name, h_c or h_min, value).
    pub films: Vec<(String, String, f64)>,
    pub p_max: Option<f64>,
    pub film_parameter: Option<f64>,
    pub film_reading: Option<String>,
}

fn check(name: &str, v: f64, ok: bool, why: &str) -> Result<(), String> {
    if v.is_finite() && ok {
        Ok(())
    } else {
        Err(format!("{name} = {v} is invalid: {why}"))
    }
}

impl CaseSpec {
    pub fn validate(&self) -> Result<(), String> {
        if self.contact != "line" {
            return Err(format!(
                "contact = {:?}: only \"line\" is available in this build",
                self.contact
            ));
        }
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
            check(
                &format!("{n}.radius_x"),
                b.radius_x,
                b.radius_x != 0.0,
                "a radius cannot be zero (m)",
            )?;
            if let Some(rq) = b.rq {
                check(
                    &format!("{n}.rq"),
                    rq,
                    rq >= 0.0,
                    "roughness must be >= 0 (m)",
                )?;
            }
        }
        let inv = 1.0 / self.body1.radius_x + 1.0 / self.body2.radius_x;
        check(
            "1/R1 + 1/R2",
            inv,
            inv > 0.0,
            "the surfaces do not form a convex contact (concave radius too small)",
        )?;
        check(
            "load",
            self.load,
            self.load > 0.0,
            "the load must be positive (N)",
        )?;
        check(
            "length",
            self.length,
            self.length > 0.0,
            "the contact length must be positive (m)",
        )?;
        check(
            "u1 + u2",
            self.u1 + self.u2,
            self.u1 + self.u2 > 0.0,
            "the speed sum must be positive (m/s)",
        )?;
        check(
            "eta0",
            self.eta0,
            self.eta0 > 0.0,
            "the viscosity must be positive (Pa s)",
        )?;
        check(
            "alpha",
            self.alpha,
            self.alpha >= 0.0,
            "the pressure-viscosity coefficient must be >= 0 (1/Pa)",
        )?;
        if self.grid < 33 {
            return Err(format!(
                "grid = {} is too small: at least 33 points",
                self.grid
            ));
        }
        Ok(())
    }

    /// Derive the groups; with `solve`, also solve numerically.
    pub fn report(&self, solve: bool) -> Result<CaseReport, String> {
        self.validate()?;
        let r = 1.0 / (1.0 / self.body1.radius_x + 1.0 / self.body2.radius_x);
        let e_red = 2.0
            / ((1.0 - self.body1.nu.powi(2)) / self.body1.e
                + (1.0 - self.body2.nu.powi(2)) / self.body2.e);
        let w_prime = self.load / self.length / (e_red * r);
        let u_m = self.eta0 * 0.5 * (self.u1 + self.u2) / (e_red * r);
        let g = self.alpha * e_red;
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
        let gp = line_g_params(gr);
        let (regime, hmin_regime) = line_regime_hmin(gr);
        let to_h = |h_moes: f64| h_moes * r * u_s.sqrt();
        let mut films = vec![
            (
                "Moes 1992".to_string(),
                "h_c".to_string(),
                to_h(moes_line_hc(m, l)),
            ),
            (
                "Dowson-Toyoda 1979".to_string(),
                "h_c".to_string(),
                dowson_toyoda_line_hc(gr) * r,
            ),
            (
                "Dowson-Higginson".to_string(),
                "h_min".to_string(),
                dowson_higginson_line_hmin(gr) * r,
            ),
            (
                format!("textbook regime formula ({regime:?})"),
                "h_min".to_string(),
                hmin_regime * r,
            ),
        ];
        let mut numerical = None;
        let mut p_max = None;
        if solve {
            let case = LineCase::new(m, l).map_err(|e| e.to_string())?;
            let mut p = LineSolveParams::default();
            p.mg.grid = self.grid;
            let o = solve_line(&case, &p).outputs;
            // Only a converged solve is a number to compare with; a failure is still reported.
            if o.status == crate::solver::Status::Converged {
                films.insert(
                    0,
                    ("ehlmap (numerical)".into(), "h_min".into(), to_h(o.h_min)),
                );
                films.insert(0, ("ehlmap (numerical)".into(), "h_c".into(), to_h(o.h_c)));
                p_max = Some(o.p_max * p_h);
            }
            numerical = Some(o);
        }
        let sigma = match (self.body1.rq, self.body2.rq) {
            (Some(a), Some(b)) => Some((a * a + b * b).sqrt()),
            (Some(a), None) | (None, Some(a)) => Some(a),
            (None, None) => None,
        };
        let h_min = films.iter().find(|f| f.1 == "h_min").map(|f| f.2);
        let film_parameter = match (sigma, h_min) {
            (Some(s), Some(h)) if s > 0.0 => Some(h / s),
            _ => None,
        };
        let film_reading = film_parameter.map(|lam| {
            if lam < 1.0 {
                "boundary lubrication (Lambda < 1)".to_string()
            } else if lam <= 3.0 {
                "mixed lubrication (1 <= Lambda <= 3)".to_string()
            } else {
                "full film (Lambda > 3)".to_string()
            }
        });
        Ok(CaseReport {
            r,
            e_reduced: e_red,
            w_prime,
            u_mean: u_m,
            g,
            m,
            l,
            b,
            p_h,
            g_v: gp.g_v,
            g_e: gp.g_e,
            regime: format!("{regime:?}"),
            numerical,
            films,
            p_max,
            film_parameter,
            film_reading,
        })
    }
}

/// A readable report in engineering units.
pub fn summary(r: &CaseReport) -> String {
    let mut s = format!(
        "line contact: R = {:.3} mm, E' = {:.1} GPa, b = {:.4} mm, p_h = {:.3} GPa\n\
         groups (u_m): W' = {:.3e}, U = {:.3e}, G = {:.0}; g_v = {:.0}, g_e = {:.2}, regime {}\n\
         Moes (u_s): M = {:.3}, L = {:.3}\n",
        r.r * 1e3,
        r.e_reduced * 1e-9,
        r.b * 1e3,
        r.p_h * 1e-9,
        r.w_prime,
        r.u_mean,
        r.g,
        r.g_v,
        r.g_e,
        r.regime,
        r.m,
        r.l
    );
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
