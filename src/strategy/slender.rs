//! Slender elliptic contacts answered by a line contact.
//!
//! As D = Rx/Ry -> 0 the Hertz ellipse grows long across the rolling direction (k = a/b -> inf)
//! and its centre line behaves like a line contact of the same radius Rx and the same Hertz
//! half-width b. That line case has the same Hertzian film H = h Rx/b^2 when its Moes
//! conversion factor equals the point one: h_scale,line = 8 M_line/pi = h_scale,point, so
//!
//!   M_line = pi h_scale / 8,  L_line = L,
//!
//! and its H_c, H_min (Moes units) stand for the point ones. Pressures differ by the Hertzian
//! scales: p_h,ellipse/p_h,line = (1 + D)/E(m), so P_point = P_line E/(1 + D).
//!
//! The centre-line film of the ellipse is below the line film (side leakage), and where the
//! equivalent line case is not elastic the side leakage changes the film entirely. Hence the
//! gate and the bound used by the model selection (`crate::strategy::select`):
//!
//! * gate ([`gap_bound`] is `Some`): D <= [`D_MAX`], M_line >= [`M_LINE_MIN`], L <= [`L_MAX`],
//!   elastic surfaces, Barus viscosity and an incompressible lubricant (the pressure-dependent
//!   models are written for one p_h, and the two cases' p_h differ by (1 + D)/E);
//! * bound on |H_line/H_point - 1| for H_c and H_min: (0.005 + 0.4 D)(1 + L/20), set above every
//!   measured gap inside the gate and checked on a separate validation set in `tests/slender.rs`.
//!
//! (Measured gaps: docs/validation.md, "Slender ellipses against the equivalent line contact".)

use crate::model::case::{Elasticity, LineCase, PointCase};
use crate::model::lubricant::{Density, Viscosity};
use crate::solve::solution::Solution;
use crate::solve::solution::{CentreLine, Outputs, Spike};
use std::f64::consts::PI;

/// The largest ellipticity D = Rx/Ry answered by a line contact.
pub const D_MAX: f64 = 0.1;
/// The smallest M of the equivalent line case: below it the line case is not elastic and the gap
/// is not bounded (docs/validation.md).
pub const M_LINE_MIN: f64 = 2.5;
/// The largest L of the gap measurements the bound was set from.
pub const L_MAX: f64 = 20.0;
/// The finest line grid of an accuracy-target solve of the equivalent line case.
pub const LINE_MAX_GRID: usize = 4097;

/// The line case with the same Hertz half-width b, radius Rx and Hertzian film scale.
pub fn equivalent_line(case: &PointCase) -> LineCase {
    LineCase {
        m: PI * case.venner().h_scale / 8.0,
        l: case.l,
        models: case.models,
    }
}

/// Bound on the relative difference of H_c and H_min between the point case and its
/// equivalent line case, or `None` outside the gate (see the module doc).
pub fn gap_bound(case: &PointCase) -> Option<f64> {
    let models_ok = case.models.elasticity == Elasticity::Elastic
        && case.models.viscosity == Viscosity::Barus
        && case.models.density == Density::Incompressible;
    let inside =
        models_ok && case.d <= D_MAX && case.l <= L_MAX && equivalent_line(case).m >= M_LINE_MIN;
    inside.then(|| (0.005 + 0.4 * case.d) * (1.0 + case.l / 20.0))
}

/// The point outputs of a line solve of [`equivalent_line`]: films as they are (Moes units),
/// pressures converted to the ellipse's p_h, `Y_min` = 0 (the centre line, whose minimum film
/// is then H_min, with its estimate), `D` and `k` set; `H0` and `f` are NaN (the line's film
/// constant and traction are not the ellipse's).
pub fn point_outputs(case: &PointCase, line: &Outputs) -> Outputs {
    let el = case.ellipse();
    let p = el.e / (1.0 + case.d);
    Outputs {
        y_min: Some(0.0),
        centre_line: Some(CentreLine {
            h_min: line.h_min,
            x_min: line.x_min,
            h_min_err: line.h_min_err,
        }),
        d: Some(case.d),
        k: Some(el.k),
        p_max: line.p_max * p,
        spike: line.spike.map(|s| Spike { x: s.x, p: s.p * p }),
        h0: f64::NAN,
        f: f64::NAN,
        ..line.clone()
    }
}

/// [`point_outputs`] for a whole line solution (no point fields).
pub fn point_solution(case: &PointCase, line: Solution) -> Solution {
    Solution {
        outputs: point_outputs(case, &line.outputs),
        info: line.info,
        fields: None,
        attempt: line.attempt,
        profile: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equivalent_line_has_the_same_hertzian_film_scale() {
        let pc = PointCase::new(100.0, 10.0, 0.02).unwrap();
        let lc = equivalent_line(&pc);
        assert!((lc.venner().h_scale / pc.venner().h_scale - 1.0).abs() < 1e-12);
        assert_eq!(lc.l, pc.l);
        // M_line of the (M, L, D) = (100, 10, 0.02) case of the gap measurements.
        assert!((lc.m - 2.461).abs() < 1e-3, "{}", lc.m);
    }

    #[test]
    fn gate_and_bound() {
        let b = |m, l, d| gap_bound(&PointCase::new(m, l, d).unwrap());
        assert!((b(1000.0, 0.0, 0.02).unwrap() - 0.013).abs() < 1e-12);
        assert!((b(1000.0, 20.0, 0.05).unwrap() - 0.05).abs() < 1e-12);
        assert_eq!(b(1000.0, 10.0, 0.2), None, "D too large");
        assert_eq!(b(10.0, 10.0, 0.02), None, "rigid-like line case");
        assert_eq!(b(100.0, 10.0, 0.01), None, "M_line = 1.88");
        assert_eq!(b(1000.0, 25.0, 0.02), None, "L beyond the data");
        let roelands = crate::model::case::Models {
            viscosity: Viscosity::Roelands { z: 0.6, ph_pa: 1e9 },
            ..Default::default()
        };
        let pc = PointCase::with_models(1000.0, 10.0, 0.02, roelands).unwrap();
        assert_eq!(gap_bound(&pc), None);
    }

    #[test]
    fn pressures_convert_to_the_ellipse_hertz_scale() {
        let pc = PointCase::new(1000.0, 0.0, 0.05).unwrap();
        let mut line = crate::strategy::closed_form::closed_form_line(3.0).outputs;
        line.p_max = 1.0;
        let o = point_outputs(&pc, &line);
        let el = pc.ellipse();
        assert!((o.p_max - el.e / 1.05).abs() < 1e-12);
        assert_eq!(o.h_c, line.h_c);
        assert_eq!(o.k, Some(el.k));
        assert_eq!(o.y_min, Some(0.0));
        assert!(o.h0.is_nan() && o.f.is_nan());
    }
}
