//! Line-contact case: `R = 1/(1/R1 + 1/R2)` (convex radii positive, a concave race negative),
//! `W' = w'/(E'R)`, `U_m = eta0 u_m/(E'R)`, `G = alpha E'`, `M = W' U_s^-1/2`, `L = G U_s^1/4`
//! with `U_s = 2 U_m`, `b = R sqrt(8W'/pi)`, `p_h = E'b/(4R)`, `h = H_Moes R U_s^1/2`; the
//! numerical solve ([`solve_line`]) beside Moes 1992, Dowson-Toyoda, Dowson-Higginson and the
//! textbook regime formula.

use super::{add_numerical, check, e_reduced, film_parameter, CaseFields, CaseReport, CaseSpec};
use crate::model::case::LineCase;
use crate::model::formulas::{
    dowson_higginson_line_hmin, dowson_toyoda_line_hc, line_g_params, line_regime_hmin,
    moes_line_hc, HdGroups,
};
use crate::solve::line::{solve_line, LineSolveParams};
use std::f64::consts::PI;

pub(super) fn run(
    spec: &CaseSpec,
    solve: bool,
    keep_fields: bool,
) -> Result<(CaseReport, Option<CaseFields>), String> {
    for (n, b) in [("body1", &spec.body1), ("body2", &spec.body2)] {
        if matches!(b.radius_y, Some(r) if r.is_finite()) {
            return Err(format!(
                "{n}.radius_y applies to point contacts (a line contact's bodies are cylinders)"
            ));
        }
    }
    let inv = 1.0 / spec.body1.radius_x + 1.0 / spec.body2.radius_x;
    check(
        "1/R1 + 1/R2",
        inv,
        inv > 0.0,
        "the surfaces do not form a convex contact (concave radius too small)",
    )?;
    let length = spec
        .length
        .ok_or("length (m) is missing: a line contact needs the contact length")?;
    check(
        "length",
        length,
        length > 0.0,
        "the contact length must be positive (m)",
    )?;
    let (eta0, alpha, lub) = spec.lubricant()?;
    let grid = spec.grid.unwrap_or(4097);
    if grid < 33 {
        return Err(format!("grid = {grid} is too small: at least 33 points"));
    }
    let r = 1.0 / inv;
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
    let gp = line_g_params(gr);
    let (regime, hmin_regime) = line_regime_hmin(gr);
    let to_h = |h_moes: f64| h_moes * r * u_s.sqrt();
    let mut films = vec![
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
    let models = spec.models(eta0, alpha, p_h)?;
    let case = LineCase::with_models(m, l, models).map_err(|e| e.to_string())?;
    let venner = case.venner();
    let mut numerical = None;
    let mut p_max = None;
    let mut fields = None;
    if solve {
        let mut p = LineSolveParams::default();
        p.mg.grid = grid;
        p.keep_profile = keep_fields;
        let s = solve_line(&case, &p);
        let o = s.outputs;
        p_max = add_numerical(&mut films, &o, to_h, p_h);
        fields = s.profile.map(CaseFields::Line);
        numerical = Some(o);
    }
    let mut rep = CaseReport {
        contact: "line".into(),
        r,
        ry: None,
        d: None,
        k: None,
        a: None,
        e_reduced: e_red,
        eta0,
        alpha,
        lubricant: lub,
        models,
        w_prime,
        u_mean: u_m,
        g,
        m,
        l,
        lambda: venner.lambda,
        alpha_bar: venner.alpha_bar,
        b,
        p_h,
        g_v: gp.g_v,
        g_e: gp.g_e,
        regime: format!("{regime:?}"),
        numerical,
        films,
        p_max,
        film_parameter: None,
        film_reading: None,
    };
    film_parameter(spec, &mut rep);
    Ok((rep, fields))
}
