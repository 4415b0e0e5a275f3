//! Hertz contact ellipse from the ellipticity parameter `D = Rx/Ry`.
//!
//! Conventions (docs/physics.md sections 1 and 3): `x` is the rolling direction,
//! `1/Rx = 1/Rx1 + 1/Rx2`, `1/Ry` likewise, `D = Rx/Ry` in `(0, 1]` (`D = 1` circular, `D -> 0`
//! line contact). The Hertz ellipse has semi-axis `b` along `x` and `a` across (along `y`),
//! `a >= b` when `Ry >= Rx`; `kappa = b/a <= 1`, `k = a/b = 1/kappa >= 1`. `F = K(m)` and
//! `E = E(m)` are the complete elliptic integrals of the first and second kind with parameter
//! `m = 1 - kappa^2` (`m = e^2`, the squared eccentricity of the ellipse).
//!
//! Exact relation (solved here for `kappa`):
//!
//! ```text
//! D = kappa^2 (F - E) / (E - kappa^2 F)
//! ```
//!
//! Derivation: for the ellipsoidal Hertz pressure `p = p0 sqrt(1 - x^2/b^2 - y^2/a^2)` potential
//! theory gives an interior surface displacement `u = C - A' x^2 - B' y^2` with
//! `A' ~ Int_0^inf dw / (sqrt(w) (b^2 + w)^(3/2) (a^2 + w)^(1/2))` and
//! `B' ~ Int_0^inf dw / (sqrt(w) (b^2 + w)^(1/2) (a^2 + w)^(3/2))` (same prefactor). Matching the
//! gap `x^2/(2 Rx) + y^2/(2 Ry)` gives `D = Rx/Ry = B'/A'`; the test
//! `relation_matches_potential_theory_quadrature` checks the closed form against a plain
//! quadrature of these integrals, without any elliptic integral. Reference: Johnson, Contact
//! Mechanics, ch. 4 (curvature ratio `((a/b)^2 E - K)/(K - E)` along the short over the long
//! axis), inverted here because `D` is the long-axis over the short-axis curvature.
//!
//! Numerics: `K` and `E` come from the arithmetic-geometric mean started from the complementary
//! modulus `kappa` (so `m -> 1` loses no precision), `E = K (1 - sum_{n>=0} 2^(n-1) c_n^2)`,
//! `c_0^2 = m`. `D(kappa)` is evaluated as `kappa^2 (m/2 + t)/(m/2 - t)` with
//! `t = sum_{n>=1} 2^(n-1) c_n^2`, which avoids the cancellation in `F - E` and `E - kappa^2 F`
//! near `kappa = 1`. Near `kappa = 1`, `D ~ kappa^(3/2)`; for small `kappa`,
//! `D ~ kappa^2 (ln(4/kappa) - 1)`.
//!
//! Approximations, for comparison only (Moes' also starts the iteration of [`ellipse_from_d`]):
//! Moes `kappa = [1 + sqrt(ln(16/D)/(2D)) - sqrt(ln 4) + 0.16 ln D]^(-1)` (exact at `D = 1`) and
//! Hamrock-Brewe `k = 1.0339 D^(-0.636)`; their errors against the exact relation are in
//! docs/physics.md section 3 and docs/validation.md (Point contacts).

use crate::model::error::ParamError;
use std::f64::consts::{FRAC_PI_2, PI};

/// The Hertz ellipse for a given `D = Rx/Ry`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ellipse {
    /// Ellipticity parameter `D = Rx/Ry` in `(0, 1]`.
    pub d: f64,
    /// `kappa = b/a <= 1` (b along the rolling direction x, a across).
    pub kappa: f64,
    /// `k = a/b >= 1`.
    pub k: f64,
    /// `F = K(m)`, complete elliptic integral of the first kind, `m = 1 - kappa^2`.
    pub f: f64,
    /// `E = E(m)`, complete elliptic integral of the second kind.
    pub e: f64,
}

/// AGM core from the complementary modulus `kc = sqrt(1 - m)` in `(0, 1]`.
/// Returns `(K, t)` with `t = sum_{n>=1} 2^(n-1) c_n^2`.
fn agm_core(kc: f64) -> (f64, f64) {
    let mut a = 1.0_f64;
    let mut b = kc;
    let mut t = 0.0;
    let mut weight = 1.0; // 2^(n-1) for n = 1
    for _ in 0..80 {
        let c = 0.5 * (a - b);
        t += weight * c * c;
        let a_next = 0.5 * (a + b);
        b = (a * b).sqrt();
        a = a_next;
        weight *= 2.0;
        // c_{n+1} = c_n^2/(4 a_{n+1}): once c_n < 1e-10 a the remaining terms are below 1e-40.
        // (Iterating on would only add rounding noise times a growing weight.)
        if c.abs() <= 1e-10 * a {
            break;
        }
    }
    (PI / (2.0 * a), t)
}

/// Complete elliptic integrals `(K, E)` from the complementary modulus `kc = sqrt(1 - m)`,
/// `kc` in `(0, 1]`. Accurate also when `m` is within rounding of 1. Returns NaNs outside.
pub fn ellip_ke_kc(kc: f64) -> (f64, f64) {
    if !(kc > 0.0 && kc <= 1.0) {
        return (f64::NAN, f64::NAN);
    }
    let m = (1.0 - kc) * (1.0 + kc);
    let (k, t) = agm_core(kc);
    (k, k * (1.0 - 0.5 * m - t))
}

/// Complete elliptic integrals of the first and second kind `(K(m), E(m))`, parameter
/// `m = k^2` in `[0, 1)`, by the arithmetic-geometric mean (about 1e-15 relative accuracy).
/// Returns NaNs for `m` outside `[0, 1)`.
pub fn ellip_ke(m: f64) -> (f64, f64) {
    if !(0.0..1.0).contains(&m) {
        return (f64::NAN, f64::NAN);
    }
    ellip_ke_kc((1.0 - m).sqrt())
}

/// `D = Rx/Ry` as a function of `kappa = b/a` in `(0, 1]` (exact Hertz relation,
/// `D = kappa^2 (F - E)/(E - kappa^2 F)`, evaluated without cancellation). NaN outside.
pub fn d_from_kappa(kappa: f64) -> f64 {
    if !(kappa > 0.0 && kappa <= 1.0) {
        return f64::NAN;
    }
    if kappa == 1.0 {
        return 1.0;
    }
    let m = (1.0 - kappa) * (1.0 + kappa);
    let (_, t) = agm_core(kappa);
    kappa * kappa * (0.5 * m + t) / (0.5 * m - t)
}

/// Exact Hertz ellipse for `D` in `(0, 1]`: solves `D = d_from_kappa(kappa)` by a bracketed
/// Newton iteration on `ln D(ln kappa)` (bisection fallback), started from the Moes estimate.
/// `D = 1` returns `kappa = k = 1`, `E = F = pi/2` exactly. Errors for `D` outside `(0, 1]` or NaN.
pub fn ellipse_from_d(d: f64) -> Result<Ellipse, ParamError> {
    if !(d > 0.0 && d <= 1.0) {
        return Err(ParamError::Input(format!(
            "ellipse_from_d: D = {d} is not in (0, 1]"
        )));
    }
    if d == 1.0 {
        return Ok(Ellipse {
            d,
            kappa: 1.0,
            k: 1.0,
            f: FRAC_PI_2,
            e: FRAC_PI_2,
        });
    }
    let target = d.ln();
    // f(u) = ln D(e^u) - ln d, increasing in u, f(0) = -ln d > 0.
    let f = |u: f64| d_from_kappa(u.exp()).ln() - target;
    let u0 = kappa_moes(d).ln().min(0.0);
    let mut hi = 0.0_f64;
    let mut step = 0.05;
    let mut lo = u0 - step;
    while f(lo) > 0.0 {
        hi = lo;
        step *= 2.0;
        lo -= step;
        if lo < -1500.0 {
            return Err(ParamError::Input(format!(
                "ellipse_from_d: no bracket found for D = {d}"
            )));
        }
    }
    if u0 + 0.05 < hi && f(u0 + 0.05) > 0.0 {
        hi = u0 + 0.05;
    }
    let mut u = u0.clamp(lo, hi);
    for _ in 0..100 {
        let fu = f(u);
        if fu == 0.0 {
            break;
        }
        if fu > 0.0 {
            hi = u;
        } else {
            lo = u;
        }
        let h = 1e-6;
        let slope = if u + h <= 0.0 {
            (f(u + h) - f(u - h)) / (2.0 * h)
        } else {
            (fu - f(u - h)) / h
        };
        let mut u_next = u - fu / slope;
        if !(slope > 0.0 && u_next > lo && u_next < hi) {
            u_next = 0.5 * (lo + hi);
        }
        let du = (u_next - u).abs();
        u = u_next;
        if du <= 1e-15 * u.abs().max(1e-300) || hi - lo <= 1e-15 * u.abs() {
            break;
        }
    }
    let kappa = u.exp().min(1.0);
    let (f_int, e_int) = ellip_ke_kc(kappa);
    Ok(Ellipse {
        d,
        kappa,
        k: 1.0 / kappa,
        f: f_int,
        e: e_int,
    })
}

/// Moes approximation `kappa = [1 + sqrt(ln(16/D)/(2D)) - sqrt(ln 4) + 0.16 ln D]^(-1)`, exact
/// at `D = 1`; the Newton start of [`ellipse_from_d`] (its error: docs/validation.md).
pub fn kappa_moes(d: f64) -> f64 {
    1.0 / (1.0 + ((16.0 / d).ln() / (2.0 * d)).sqrt() - 4.0_f64.ln().sqrt() + 0.16 * d.ln())
}

/// Hamrock-Brewe fit `k = a/b = 1.0339 (Ry/Rx)^0.636 = 1.0339 D^(-0.636)`. For comparison only,
/// not exact even at `D = 1` (its error: docs/validation.md).
pub fn hamrock_brewe_k(d: f64) -> f64 {
    1.0339 * (1.0 / d).powf(0.636)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: f64, b: f64) -> f64 {
        ((a - b) / b).abs()
    }

    /// `K`, `E` by the trapezoid rule over `theta` in `[0, pi/2]` (spectrally accurate for this
    /// even periodic integrand); independent of the AGM.
    fn ke_quadrature(m: f64) -> (f64, f64) {
        let n = 2000;
        let h = FRAC_PI_2 / n as f64;
        let (mut k, mut e) = (0.0, 0.0);
        for i in 0..=n {
            let s = (i as f64 * h).sin();
            let q = 1.0 - m * s * s;
            let w = if i == 0 || i == n { 0.5 } else { 1.0 };
            k += w / q.sqrt();
            e += w * q.sqrt();
        }
        (k * h, e * h)
    }

    #[test]
    fn ellip_ke_known_values() {
        let (k0, e0) = ellip_ke(0.0);
        assert_eq!(k0, FRAC_PI_2);
        assert_eq!(e0, FRAC_PI_2);
        let (k, e) = ellip_ke(0.5);
        assert!(rel(k, 1.8540746773013719) < 1e-14, "K(0.5) = {k}");
        assert!(rel(e, 1.3506438810476755) < 1e-14, "E(0.5) = {e}");
        assert!(ellip_ke(1.0).0.is_nan() && ellip_ke(-0.1).1.is_nan());
        assert!(ellip_ke(f64::NAN).0.is_nan());
    }

    #[test]
    fn ellip_ke_matches_quadrature() {
        for &m in &[0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99] {
            let (k, e) = ellip_ke(m);
            let (kq, eq) = ke_quadrature(m);
            assert!(rel(k, kq) < 1e-13, "K({m}) = {k} vs {kq}");
            assert!(rel(e, eq) < 1e-13, "E({m}) = {e} vs {eq}");
        }
    }

    #[test]
    fn ellip_ke_near_one_matches_asymptotic_expansion() {
        // K ~ L + (m1/4)(L - 1) + (9 m1^2/64)(L - 7/6), E ~ 1 + (m1/2)(L - 1/2)
        // + (3 m1^2/16)(L - 13/12), L = ln(4/sqrt(m1)), m1 = 1 - m.
        for &m1_nominal in &[1e-6_f64, 1e-8, 1e-12] {
            let m = 1.0 - m1_nominal;
            let m1 = 1.0 - m; // exact (Sterbenz)
            let l = (4.0 / m1.sqrt()).ln();
            let k_as = l + 0.25 * m1 * (l - 1.0) + 9.0 / 64.0 * m1 * m1 * (l - 7.0 / 6.0);
            let e_as = 1.0 + 0.5 * m1 * (l - 0.5) + 3.0 / 16.0 * m1 * m1 * (l - 13.0 / 12.0);
            let (k, e) = ellip_ke(m);
            assert!(rel(k, k_as) < 1e-14, "K({m}) = {k} vs {k_as}");
            assert!(rel(e, e_as) < 1e-14, "E({m}) = {e} vs {e_as}");
        }
    }

    #[test]
    fn circular_is_exact() {
        let el = ellipse_from_d(1.0).unwrap();
        assert_eq!(el.kappa, 1.0);
        assert_eq!(el.k, 1.0);
        assert_eq!(el.f, FRAC_PI_2);
        assert_eq!(el.e, FRAC_PI_2);
        assert_eq!(d_from_kappa(1.0), 1.0);
    }

    #[test]
    fn invalid_d_is_an_error() {
        for &d in &[0.0, -0.5, 1.0 + 1e-12, 2.0, f64::NAN, f64::INFINITY] {
            assert!(ellipse_from_d(d).is_err(), "D = {d}");
        }
    }

    #[test]
    fn ellipse_from_d_round_trips() {
        let n = 200;
        for i in 0..=n {
            // D from 1e-6 to 1 (log spaced), plus points very close to 1
            let d = 10f64.powf(-6.0 * i as f64 / n as f64);
            let el = ellipse_from_d(d).unwrap();
            assert!(el.kappa > 0.0 && el.kappa <= 1.0 && el.k >= 1.0);
            assert!(rel(d_from_kappa(el.kappa), d) < 1e-13, "D = {d}");
            let (f, e) = ellip_ke_kc(el.kappa);
            assert_eq!((f, e), (el.f, el.e));
            if d < 0.999 {
                // the naive closed form (cancellation near D = 1) agrees too
                let k2 = el.kappa * el.kappa;
                let closed = k2 * (el.f - el.e) / (el.e - k2 * el.f);
                assert!(rel(closed, d) < 1e-11, "D = {d}: closed form {closed}");
            }
        }
        for &d in &[1.0 - 1e-15, 1.0 - 1e-10, 0.999_999] {
            let el = ellipse_from_d(d).unwrap();
            assert!(rel(d_from_kappa(el.kappa), d) < 1e-15, "D = {d}");
            // near 1: D ~ kappa^(3/2)
            assert!(rel(el.kappa, d.powf(2.0 / 3.0)) < 1e-5);
        }
    }

    /// `Int_0^inf dt / (sqrt(t) (kappa^2 + t)^p (1 + t)^q)` by the trapezoid rule in `s = ln t`.
    fn potential_integral(kappa: f64, p: f64, q: f64) -> f64 {
        let (s0, s1, h) = (-90.0, 60.0, 0.005);
        let n = ((s1 - s0) / h) as usize;
        let mut sum = 0.0;
        for i in 0..=n {
            let t = (s0 + i as f64 * h).exp();
            let w = if i == 0 || i == n { 0.5 } else { 1.0 };
            sum += w * t.sqrt() / ((kappa * kappa + t).powf(p) * (1.0 + t).powf(q));
        }
        sum * h
    }

    #[test]
    fn relation_matches_potential_theory_quadrature() {
        // With w = a^2 t: A' ~ Int dt/(sqrt t (kappa^2+t)^(3/2) (1+t)^(1/2)) (x, short axis b),
        // B' ~ Int dt/(sqrt t (kappa^2+t)^(1/2) (1+t)^(3/2)) (y, long axis a); D = B'/A'.
        for &kappa in &[0.01, 0.05, 0.2, 0.5, 0.8, 0.95, 0.999] {
            let a_coef = potential_integral(kappa, 1.5, 0.5);
            let b_coef = potential_integral(kappa, 0.5, 1.5);
            let d_quad = b_coef / a_coef;
            let d_exact = d_from_kappa(kappa);
            assert!(
                rel(d_exact, d_quad) < 1e-10,
                "kappa = {kappa}: {d_exact} vs {d_quad}"
            );
        }
    }

    #[test]
    fn small_kappa_asymptote() {
        // D ~ kappa^2 (ln(4/kappa) - 1) as kappa -> 0
        let kappa = 1e-8_f64;
        let d_as = kappa * kappa * ((4.0 / kappa).ln() - 1.0);
        assert!(rel(d_from_kappa(kappa), d_as) < 1e-12);
        let el = ellipse_from_d(1e-12).unwrap();
        assert!(rel(d_from_kappa(el.kappa), 1e-12) < 1e-13);
    }

    #[test]
    fn moes_approximation_within_0_8_percent() {
        assert!((kappa_moes(1.0) - 1.0).abs() < 1e-15);
        let n = 600;
        let mut worst = 0.0_f64;
        for i in 0..=n {
            let d = 10f64.powf(-3.0 * i as f64 / n as f64);
            let exact = ellipse_from_d(d).unwrap().kappa;
            worst = worst.max(rel(kappa_moes(d), exact));
        }
        // The maximum is 0.8016 % near D = 0.45 (0.80 % to the two digits Moes quotes).
        assert!(worst < 0.00802, "worst Moes error {worst}");
        assert!(worst > 0.0079, "worst Moes error {worst}");
    }

    #[test]
    fn hamrock_brewe_is_off() {
        let at_one = rel(hamrock_brewe_k(1.0), ellipse_from_d(1.0).unwrap().k);
        assert!((at_one - 0.0339).abs() < 1e-12, "{at_one}");
        let at_1000 = rel(hamrock_brewe_k(1e-3), ellipse_from_d(1e-3).unwrap().k);
        assert!((0.20..0.26).contains(&at_1000), "{at_1000}");
    }
}
