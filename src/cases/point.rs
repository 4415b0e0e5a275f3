//! Point-contact case. Rolling along x: `1/Rx = 1/Rx1 + 1/Rx2`, `1/Ry = 1/Ry1 + 1/Ry2` (convex
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

use super::{add_numerical, check, e_reduced, film_parameter, CaseFields, CaseReport, CaseSpec};
use crate::model::case::PointCase;
use crate::model::formulas::{
    elliptic_g_params, elliptic_regime_hmin, hamrock_dowson_hc, hamrock_dowson_hmin, nvm_point_hc,
    HdGroups,
};
use crate::model::hertz::ellipse_from_d;
use crate::solve::point::{solve_point, PointSolveParams};
use std::f64::consts::PI;

fn inv_radius(r: Option<f64>) -> f64 {
    r.map_or(0.0, |r| 1.0 / r)
}

pub(super) fn run(
    spec: &CaseSpec,
    solve: bool,
    keep_fields: bool,
) -> Result<(CaseReport, Option<CaseFields>), String> {
    if spec.length.is_some() {
        return Err("length applies to line contacts only (a point contact's load is in N)".into());
    }
    for (n, b) in [("body1", &spec.body1), ("body2", &spec.body2)] {
        if let Some(r) = b.radius_y {
            if r == 0.0 || r.is_nan() {
                return Err(format!(
                    "{n}.radius_y = {r} is invalid: nonzero (m), or inf/omitted for a cylinder axis"
                ));
            }
        }
    }
    let inv_x = 1.0 / spec.body1.radius_x + 1.0 / spec.body2.radius_x;
    check(
        "1/Rx1 + 1/Rx2",
        inv_x,
        inv_x > 0.0,
        "the surfaces do not form a convex contact along x (concave radius too small)",
    )?;
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
        return Err(format!(
            "D = Rx/Ry = {d:.4} > 1 (Rx = {:.4} mm, Ry = {:.4} mm): the contact ellipse is long along \
             the rolling direction x; this solver needs D in (0, 1] (long axis across x). Check which \
             radius is radius_x (the rolling direction)",
            rx * 1e3,
            ry * 1e3
        ));
    }
    let (eta0, alpha, lub) = spec.lubricant()?;
    let grid = spec.grid.unwrap_or(129);
    if !(17..=2049).contains(&grid) {
        return Err(format!(
            "grid = {grid} is invalid: 17 to 2049 points per direction"
        ));
    }
    let el = ellipse_from_d(d).map_err(|e| format!("D: {e}"))?;
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
    let gp = elliptic_g_params(gr);
    let (regime, hmin_regime) = elliptic_regime_hmin(gr, &el);
    let to_h = |h_moes: f64| h_moes * rx * u_s.sqrt();
    let mut films = vec![
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
    let models = spec.models(eta0, alpha, p_h)?;
    let case = PointCase::with_models(m, l, d, models).map_err(|e| e.to_string())?;
    let venner = case.venner();
    let mut numerical = None;
    let mut p_max = None;
    let mut fields = None;
    if solve {
        let mut p = PointSolveParams::default();
        p.mg.grid = grid;
        p.keep_fields = keep_fields;
        let s = solve_point(&case, &p);
        let o = s.outputs;
        p_max = add_numerical(&mut films, &o, to_h, p_h);
        fields = s.fields.map(CaseFields::Point);
        numerical = Some(o);
    }
    let mut rep = CaseReport {
        contact: "point".into(),
        r: rx,
        ry: Some(ry),
        d: Some(d),
        k: Some(el.k),
        a: Some(a),
        e_reduced: e_red,
        eta0,
        alpha,
        lubricant: lub,
        models,
        w_prime: w,
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
