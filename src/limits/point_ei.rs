//! The elastic-isoviscous limit of the point films at the centre (H_c) and at the pressure
//! maximum (H_pm), from the line's by the local inlet analysis.
//!
//! As M -> infinity at L = 0 the pressure is Hertzian and the film is flat in the Hertzian zone;
//! the film on the centre line is set in an inlet zone at the leading point of the ellipse whose
//! length l is small against the edge's radius of curvature. There the problem is the line
//! contact's: plane-strain elasticity (reduced modulus E'), the Hertzian pressure near the edge
//! p = A s^(1/2) (s the distance into the contact) and the gap outside it (8/3)(A/E') |s|^(3/2),
//! the 1D Reynolds equation in s with the entrainment speed. Dimensional analysis of that problem
//! gives h = C (eta0 u_s)^(3/5) E'^(1/5) A^(-4/5) with one universal C, so two contacts with the
//! same eta0 u_s and E' have films in the ratio (A_1/A_2)^(-4/5). With A = p_h (2/b)^(1/2) (b the
//! semi-axis along rolling; line: b = R (8W'/pi)^(1/2), p_h = E' b/(4R); point: p_h = 3w/(2 pi a b),
//! b^3 = 6 E W Rx^3/(pi k (1 + D)), docs/physics.md section 1) the point law in Moes units is
//!
//! H_EI = a_line [`CIRCULAR_OVER_LINE`] f_EI(D) M^(-2/15),
//! CIRCULAR_OVER_LINE = [(pi/6) (8/pi)^(1/4) (3/2)^(5/6)]^(4/5) = 0.941415,
//! f_EI(D) = k^(2/15) [4 E(m)/(pi (1 + D))]^(2/3)   (1 at D = 1),
//!
//! with a_line the line law's constant (H_EI = a_line M^(-1/5)), k = a/b and E(m) of
//! [`crate::model::hertz`]. The exponents are asymptotic theory's (M^(-1/5) for the line, hence
//! U^(3/5) W^(-2/15), M^(-2/15), for the point); the D factor is exact, and as D -> 0 the law
//! becomes the line law of the centre line's load per unit length w' = 3w/(4a) (the equivalent
//! line contact). H_pm has the same limit: the Hertzian pressure peaks at the centre. Outputs:
//! [`ei_d_factor`], [`CIRCULAR_OVER_LINE`]. Corrections are of order l/b (the edge's curvature
//! turns the entrainment, fluid leaves the centre line), so the solver's films approach the law
//! slowly (docs/validation.md, "The point elastic-isoviscous limit").

use crate::model::hertz::ellipse_from_d;
use std::f64::consts::PI;

/// The point H_c (and H_pm) elastic-isoviscous constant at D = 1 over the line's (module doc).
pub fn circular_over_line() -> f64 {
    let ratio = PI / 6.0 * (8.0 / PI).powf(0.25) * 1.5f64.powf(5.0 / 6.0);
    ratio.powf(0.8)
}

/// [`circular_over_line`] to 6 digits, for the docs.
pub const CIRCULAR_OVER_LINE: f64 = 0.941415;

/// f_EI(D) = k^(2/15) [4 E(m)/(pi (1 + D))]^(2/3), the exact D factor of the point
/// elastic-isoviscous law (1 at D = 1; module doc). NaN for D outside (0, 1].
pub fn ei_d_factor(d: f64) -> f64 {
    match ellipse_from_d(d) {
        Ok(e) => e.k.powf(2.0 / 15.0) * (4.0 * e.e / (PI * (1.0 + d))).powf(2.0 / 3.0),
        Err(_) => f64::NAN,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A = p_h (2/b)^(1/2) of a line contact of load W' (E' = R = 1).
    fn a_line(w: f64) -> f64 {
        let b = (8.0 * w / PI).sqrt();
        b / 4.0 * (2.0 / b).sqrt()
    }

    /// A of a point contact of load W and ellipticity D (E' = Rx = 1), from Hertz's a, b, p_h.
    fn a_point(w: f64, d: f64) -> (f64, f64) {
        let e = ellipse_from_d(d).unwrap();
        let b = (6.0 * e.e * w / (PI * e.k * (1.0 + d))).cbrt();
        let a = e.k * b;
        let p_h = 3.0 * w / (2.0 * PI * a * b);
        (p_h * (2.0 / b).sqrt(), a)
    }

    /// The point law against the universal inlet law h = C U^(3/5) A^(-4/5), C from the line
    /// law H = a_line M^(-1/5) at an arbitrary load: the closed form is the Hertz algebra.
    #[test]
    fn the_closed_form_is_the_ratio_of_the_edge_pressure_coefficients() {
        assert!((circular_over_line() - CIRCULAR_OVER_LINE).abs() < 5e-7);
        let a_l = 2.488;
        let u: f64 = 3e-11;
        for w_line in [1e-5, 3e-4] {
            // The line film h/R = a_l M^(-1/5) U^(1/2), M = W' U^(-1/2).
            let h_line = a_l * (w_line / u.sqrt()).powf(-0.2) * u.sqrt();
            let c = h_line * a_line(w_line).powf(0.8);
            for (w, d) in [(1e-6, 1.0), (2e-5, 0.5), (1e-6, 0.1), (4e-7, 0.01)] {
                let h = c * a_point(w, d).0.powf(-0.8);
                let m = w * u.powf(-0.75);
                let law = a_l * circular_over_line() * ei_d_factor(d) * m.powf(-2.0 / 15.0);
                let h_moes = h / u.sqrt();
                assert!((h_moes / law - 1.0).abs() < 1e-12, "W' {w_line}, D {d}");
            }
        }
    }

    /// As D -> 0 the centre line is a line contact of load w' = 3w/(4a): the point law tends to
    /// the line law at that load (the gap closes like the slender Hertz ellipse's b to the line
    /// b of w', logarithmically).
    #[test]
    fn the_slender_limit_is_the_equivalent_line_contact() {
        let u: f64 = 3e-11;
        let w = 1e-6;
        let mut last = f64::INFINITY;
        for d in [1e-2, 1e-4, 1e-6, 1e-8] {
            let (_, a) = a_point(w, d);
            let m_line = 3.0 * w / (4.0 * a) / u.sqrt();
            let m = w * u.powf(-0.75);
            let point = circular_over_line() * ei_d_factor(d) * m.powf(-2.0 / 15.0);
            let line = m_line.powf(-0.2);
            let gap = (point / line - 1.0).abs();
            assert!(gap < last, "D {d}: {gap} after {last}");
            last = gap;
        }
        assert!(last < 2e-3, "{last}");
    }

    /// NVM 1994 built their D factor from the same Hertzian geometry (the equivalent line
    /// contact): the exact factor agrees with theirs within 0.3 % for D >= 0.25 and 3 % at 0.01.
    #[test]
    fn the_factor_is_close_to_nvm_where_their_geometry_holds() {
        let nvm = |d: f64| {
            let c = |d: f64| 1.0 + 0.006 * d.ln() + 0.63 * d.powf(4.0 / 7.0);
            (c(d) / c(1.0)).powf(-14.0 / 25.0) * d.powf(-1.0 / 15.0)
        };
        assert_eq!(ei_d_factor(1.0), 1.0);
        for (d, tol) in [
            (0.7, 3e-3),
            (0.5, 3e-3),
            (0.25, 3e-3),
            (0.1, 1.5e-2),
            (0.01, 3e-2),
        ] {
            let r = ei_d_factor(d) / nvm(d);
            assert!((r - 1.0).abs() < tol, "D {d}: {r}");
        }
        assert!(ei_d_factor(0.0).is_nan() && ei_d_factor(1.5).is_nan());
    }
}
