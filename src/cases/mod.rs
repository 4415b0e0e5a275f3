//! A dimensional case, line or point contact: read and derived by
//! [`crate::model::dimensional`], solved by [`crate::strategy::solve_case::solve`] (to the
//! default 1 % accuracy target, or on the case's `grid` when it names one), and set beside the published formulas in engineering units, with the film parameter
//! `Lambda = h_min/sigma`: `< 1` boundary, `1..3` mixed, `> 3` full film. With a roughness
//! (`rq` of a body) the case is also solved with rough surfaces (Patir-Cheng average flow,
//! Greenwood-Tripp asperity contact; [`crate::solve::mixed`]): sigma = sqrt(Rq1^2 + Rq2^2), the
//! orientation `gamma` of the file (default 1), the slide-to-roll ratio from the speeds, the
//! share of the roughness on body 1 from the Rq, and p_h/E' from the Hertz solution.

use crate::model::asperity::AsperityParams;
use crate::model::case::Contact;
pub use crate::model::case_file::{read_case, Body, CaseError, CaseSpec};
use crate::model::dimensional::Derived;
pub use crate::model::dimensional::Groups;
use crate::model::lubricant::Viscosity;
use crate::model::roughness::Roughness;
use crate::solve::solution::{with_error, ModelUsed, Outputs, PointFields, Profile};
use crate::solve::Status;
use crate::strategy::formula::FormulaRef;
use crate::strategy::solve_case::{solve as solve_case, solve_rough_beside, SolveParams};
use serde::Serialize;

/// Everything derived from a case, and the results (SI units).
#[derive(Clone, Debug, Serialize)]
pub struct CaseReport {
    /// Line or point contact.
    pub contact: Contact,
    /// The case's groups.
    #[serde(flatten)]
    pub groups: Groups,
    /// The numerical solve, when there was one (converged or not).
    pub numerical: Option<Outputs>,
    /// Film thicknesses in m: (name, h_c or h_min, value); a converged solve first.
    pub films: Vec<(String, String, f64)>,
    /// The solve's maximum pressure (Pa), when it converged.
    pub p_max: Option<f64>,
    /// Lambda = h_min/sigma from the first h_min of `films` (the numerical one when the solve
    /// converged), when a positive roughness is given.
    pub film_parameter: Option<f64>,
    /// The reading of Lambda as text: boundary lubrication (`< 1`), mixed lubrication
    /// (`1..=3`) or full film (`> 3`).
    pub film_reading: Option<String>,
    /// The solve with rough surfaces, when the case gives a roughness (films in Moes units;
    /// `mixed` carries Lambda, the asperity share and the smooth films).
    pub mixed: Option<Outputs>,
}

/// The solution fields of a case, for pictures.
pub enum CaseFields {
    /// A line contact's pressure and film along X on the finest grid.
    Line(Profile),
    /// A point contact's pressure and film fields on the finest grid.
    Point(PointFields),
}

/// What [`run`] does besides deriving the groups.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunOptions {
    /// Solve the case numerically.
    pub solve: bool,
    /// Keep the solution's profile or fields (for pictures).
    pub keep_fields: bool,
    /// With a roughness in the file, also solve the case with rough surfaces.
    pub rough: bool,
    /// Seconds all solves together may take ([`SolveParams::time_limit`]; `None`: no limit).
    pub time_limit: Option<f64>,
    /// A fitted film formula that may answer the case ([`SolveParams::formula`]).
    pub formula: Option<FormulaRef>,
}

/// Validate a case file, derive its groups; with `solve`, also solve it numerically (keeping the
/// profile or fields with `keep_fields`) and set the answer beside the published formulas; with
/// `rough` and a roughness in the file, solve it with rough surfaces too.
pub fn run(
    spec: &CaseSpec,
    opts: RunOptions,
) -> Result<(CaseReport, Option<CaseFields>), CaseError> {
    let RunOptions {
        solve,
        keep_fields,
        rough: with_rough,
        time_limit,
        formula,
    } = opts;
    let d = spec.derive()?;
    let mut films = d.films.clone();
    let (mut numerical, mut p_max, mut fields, mut mixed) = (None, None, None, None);
    if solve {
        let params = SolveParams {
            grid: d.grid,
            keep_fields,
            formula,
            ..SolveParams::default()
        }
        .time_limit(time_limit);
        let s = solve_case(&d.case, &params);
        p_max = add_numerical(&mut films, &s.outputs, |h| d.to_h(h), d.groups.p_h);
        fields = match (s.profile, s.fields) {
            (Some(p), _) => Some(CaseFields::Line(p)),
            (_, Some(f)) => Some(CaseFields::Point(f)),
            _ => None,
        };
        if let Some(r) = roughness(spec, &d).filter(|_| with_rough) {
            let rough = d.case.with_roughness(Some(r));
            let params = SolveParams {
                keep_fields: false,
                ..params
            };
            mixed = Some(solve_rough_beside(&rough, &params, &s.outputs).outputs);
        }
        numerical = Some(s.outputs);
    }
    let mut rep = CaseReport {
        contact: d.case.contact(),
        groups: d.groups,
        numerical,
        films,
        p_max,
        film_parameter: None,
        film_reading: None,
        mixed,
    };
    film_parameter(spec, &mut rep);
    Ok((rep, fields))
}

/// The rough surfaces of a case file with a positive roughness (module docs).
fn roughness(spec: &CaseSpec, d: &Derived) -> Option<Roughness> {
    let sigma = spec.sigma().filter(|&s| s > 0.0)?;
    let rq1 = spec.body1.rq.unwrap_or(0.0);
    let u_m = 0.5 * (spec.u1 + spec.u2);
    let summits = AsperityParams::default();
    Some(Roughness {
        sigma: sigma / d.to_h(1.0),
        gamma: spec.gamma.unwrap_or(1.0),
        slide_roll: (spec.u1 - spec.u2) / u_m,
        variance_ratio_1: rq1 * rq1 / (sigma * sigma),
        ph_over_e: d.groups.p_h / d.groups.e_reduced,
        asperity: AsperityParams {
            eta_beta_sigma: spec.eta_beta_sigma.unwrap_or(summits.eta_beta_sigma),
            sigma_over_beta: spec.sigma_over_beta.unwrap_or(summits.sigma_over_beta),
        },
    })
}

/// Derive the groups; with `solve`, also solve numerically (and with rough surfaces when the
/// file gives a roughness).
pub fn report(spec: &CaseSpec, solve: bool) -> Result<CaseReport, CaseError> {
    let opts = RunOptions {
        solve,
        keep_fields: false,
        rough: true,
        time_limit: None,
        formula: None,
    };
    run(spec, opts).map(|r| r.0)
}

/// Put a converged numerical answer at the head of the film comparison (a failure is still
/// reported, but is no number to compare with); returns its p_max in Pa (None for a formula's
/// answer).
fn add_numerical(
    films: &mut Vec<(String, String, f64)>,
    o: &Outputs,
    to_h: impl Fn(f64) -> f64,
    p_h: f64,
) -> Option<f64> {
    if o.status != Status::Converged {
        return None;
    }
    // A fitted formula's answer (no solve) is named as such, and has no pressure.
    let name = if o.model_used == ModelUsed::Formula {
        "ehlmap (fitted formula)"
    } else {
        "ehlmap (numerical)"
    };
    films.insert(0, (name.into(), "h_min".into(), to_h(o.h_min)));
    films.insert(0, (name.into(), "h_c".into(), to_h(o.h_c)));
    Some(o.p_max * p_h).filter(|p| p.is_finite())
}

/// Fills the film parameter and its reading from the first `h_min` of the films.
fn film_parameter(spec: &CaseSpec, r: &mut CaseReport) {
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

/// Whether the numerical answer met its accuracy target, in words.
fn accuracy_words(o: &Outputs) -> String {
    match (o.error_estimate, o.accuracy_met) {
        (Some(e), Some(true)) => format!("target met, error estimate {:.1} %", 100.0 * e),
        (Some(e), Some(false)) => format!(
            "target NOT met: error estimate {:.1} % at the finest grid allowed (see the solve's reason)",
            100.0 * e
        ),
        (Some(e), None) => format!("error estimate {:.1} % (fixed grid, against its half grid)", 100.0 * e),
        (None, _) => "no error estimate (see the solve's reason)".to_string(),
    }
}

/// A readable report in engineering units.
pub fn summary(r: &CaseReport) -> String {
    let mut s = if r.contact == Contact::Point {
        format!(
            "point contact: Rx = {:.3} mm, Ry = {:.3} mm, D = Rx/Ry = {:.5}, k = a/b = {:.4}\n\
             Hertz: a = {:.4} mm, b = {:.4} mm, p_h = {:.3} GPa, E' = {:.1} GPa\n\
             groups (u_m): W = {:.3e}, U = {:.3e}, G = {:.0}; g_v = {:.3e}, g_e = {:.3e}, regime {}\n",
            r.groups.r * 1e3,
            r.groups.ry.unwrap_or(f64::NAN) * 1e3,
            r.groups.d.unwrap_or(f64::NAN),
            r.groups.k.unwrap_or(f64::NAN),
            r.groups.a.unwrap_or(f64::NAN) * 1e3,
            r.groups.b * 1e3,
            r.groups.p_h * 1e-9,
            r.groups.e_reduced * 1e-9,
            r.groups.w_prime,
            r.groups.u_mean,
            r.groups.g,
            r.groups.g_v,
            r.groups.g_e,
            r.groups.regime
        )
    } else {
        format!(
            "line contact: R = {:.3} mm, E' = {:.1} GPa, b = {:.4} mm, p_h = {:.3} GPa\n\
             groups (u_m): W' = {:.3e}, U = {:.3e}, G = {:.0}; g_v = {:.0}, g_e = {:.2}, regime {}\n",
            r.groups.r * 1e3,
            r.groups.e_reduced * 1e-9,
            r.groups.b * 1e3,
            r.groups.p_h * 1e-9,
            r.groups.w_prime,
            r.groups.u_mean,
            r.groups.g,
            r.groups.g_v,
            r.groups.g_e,
            r.groups.regime
        )
    };
    if let Some(l) = &r.groups.lubricant {
        s.push_str(&format!(
            "lubricant: {} at {:.1} C: nu = {:.2} mm^2/s, rho = {:.0} kg/m^3 (Walther A = {:.4}, B = {:.4})\n",
            l.name, l.temperature, l.nu, l.rho, l.walther.a, l.walther.b
        ));
    }
    let z = match r.groups.models.viscosity {
        Viscosity::Roelands { z, .. } => format!(" z = {z:.3}"),
        Viscosity::Barus => String::new(),
    };
    s.push_str(&format!(
        "solver models: {}{z}, {}\n",
        r.groups.models.viscosity.name(),
        r.groups.models.density.name()
    ));
    s.push_str(&format!(
        "eta0 = {:.4} Pa s, alpha = {:.3e} 1/Pa\n\
         Moes (u_s): M = {:.3}, L = {:.3}; solver: lambda = {:.4e}, alpha_bar = {:.3}\n",
        r.groups.eta0, r.groups.alpha, r.groups.m, r.groups.l, r.groups.lambda, r.groups.alpha_bar
    ));
    if let Some(o) = &r.numerical {
        s.push_str(&format!("numerical solve: {} ({})\n", o.status, o.reason));
        s.push_str(&format!("accuracy: {}\n", accuracy_words(o)));
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
        let value = match (&r.numerical, name.starts_with("ehlmap"), what.as_str()) {
            (Some(o), true, "h_c") => with_error(h * 1e6, o.h_c_err),
            (Some(o), true, "h_min") => with_error(h * 1e6, o.h_min_err),
            _ => format!("{:.4}", h * 1e6),
        };
        s.push_str(&format!("{what:<6} {value:>9} um  {name}{dev}\n"));
    }
    if let Some(p) = r.p_max {
        s.push_str(&format!("p_max  {:.3} GPa\n", p * 1e-9));
    }
    if let (Some(l), Some(t)) = (r.film_parameter, &r.film_reading) {
        s.push_str(&format!(
            "film parameter Lambda = h_min/sigma = {l:.2}: {t}\n"
        ));
    }
    if let (Some(o), Some(x)) = (&r.mixed, r.mixed.as_ref().and_then(|o| o.mixed.as_ref())) {
        // Moes film units to um: the smooth solve's ratio of h_c (m) to H_c.
        let um = r
            .films
            .iter()
            .find(|f| f.0.starts_with("ehlmap") && f.1 == "h_c")
            .zip(r.numerical.as_ref())
            .map(|(f, n)| f.2 / n.h_c * 1e6);
        s.push_str(&format!(
            "rough surfaces (Patir-Cheng flow factors, Greenwood-Tripp asperities; gamma = {}, \
             slide-roll {:.3}): {} ({})\n",
            x.gamma, x.slide_roll, o.status, o.reason
        ));
        if let (Some(um), true) = (um, o.status == Status::Converged) {
            s.push_str(&format!(
                "h_c    {:>9} um  ehlmap (rough)  ({:+.1} % vs smooth)\n\
                 h_min  {:>9} um  ehlmap (rough)  ({:+.1} % vs smooth)\n\
                 Lambda = h_min/sigma = {:.2} (rough film); asperities carry {:.2} % of the load\n",
                with_error(o.h_c * um, o.h_c_err),
                x.h_c_smooth.map_or(f64::NAN, |h| 100.0 * (o.h_c / h - 1.0)),
                with_error(o.h_min * um, o.h_min_err),
                x.h_min_smooth
                    .map_or(f64::NAN, |h| 100.0 * (o.h_min / h - 1.0)),
                x.lambda_min,
                100.0 * x.asperity_load_fraction
            ));
        }
    }
    s
}
