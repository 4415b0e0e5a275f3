//! Fast Greenwood-Tripp integrals for the solver's inner loops: `F_0`, `F_1` and `F_5/2` of
//! [`crate::model::asperity`] tabulated once and interpolated.
//!
//! Contract. `ln F_n(t)` is tabulated for `n = 0, 1, 5/2` on `t in [-16, 8]` at step `1/64` (1537
//! nodes, computed once by the quadrature of [`crate::model::asperity::gt_integral`], the oracle)
//! and interpolated by the 4-point Lagrange cubic of the nearest nodes; the logarithm keeps the
//! relative error uniform in the Gaussian tail. Beyond the table:
//! * `F_0(t) = 1 - F_0(-t)` and `F_1(t) = -t + F_1(-t)` (the symmetry of the Gaussian) for
//!   `t < -16`; `F_0 = F_1 = 0` for `t > 8` (both are below `1e-15` of their values at 0 there);
//! * `F_5/2(t) = 0` for `t > 7` ([`ASPERITY_CUTOFF`]), and for `t < -16` (surfaces pressed 16
//!   sigma through their mean planes: an intermediate iterate, never a converged solve) the
//!   moment series `s^(5/2) (1 + 15/(8 s^2) - 15/(128 s^4) - 0.0732/s^6)`, `s = -t`, of
//!   `E[(X + s)^(5/2)]` (its next term is below `1e-10` relative at `s = 16`).
//!
//! Invariant: the relative error against the quadrature is below `1e-8` (the tests
//! `table_matches_the_quadrature` and `beyond_the_table_the_symmetries_and_the_series_hold`);
//! no evaluation calls the quadrature.

use crate::model::asperity::{f_n, ASPERITY_CUTOFF};
use std::sync::OnceLock;

const T_LO: f64 = -16.0;
const T_HI: f64 = 8.0;
const PER_UNIT: f64 = 64.0;
const NODES: usize = 1537;

struct Table {
    /// ln F_0, ln F_1, ln F_5/2 at t = T_LO + k/PER_UNIT.
    ln: [Vec<f64>; 3],
}

fn table() -> &'static Table {
    static TABLE: OnceLock<Table> = OnceLock::new();
    TABLE.get_or_init(|| {
        let t = |k: usize| T_LO + k as f64 / PER_UNIT;
        let col = |n: f64| (0..NODES).map(|k| f_n(n, t(k)).ln()).collect::<Vec<_>>();
        Table {
            ln: [col(0.0), col(1.0), col(2.5)],
        }
    })
}

/// F_n(t) from column `which` of the table, `t` in [T_LO, T_HI].
fn interpolate(which: usize, t: f64) -> f64 {
    let y = &table().ln[which];
    let s = (t - T_LO) * PER_UNIT;
    let k = (s.floor() as usize).clamp(1, NODES - 3);
    let u = s - k as f64; // in [-1, 2] at the ends, [0, 1) inside
    let (a, b, c, d) = (y[k - 1], y[k], y[k + 1], y[k + 2]);
    // Lagrange cubic through nodes -1, 0, 1, 2 at u.
    let l = -a * u * (u - 1.0) * (u - 2.0) / 6.0 + b * (u + 1.0) * (u - 1.0) * (u - 2.0) / 2.0
        - c * (u + 1.0) * u * (u - 2.0) / 2.0
        + d * (u + 1.0) * u * (u - 1.0) / 6.0;
    l.exp()
}

/// The `s^-6` coefficient of the series of `F_5/2(-s)`: binomial(5/2, 6) E[X^6] = -225/46080 x 15.
const SERIES_6: f64 = -225.0 / 46080.0 * 15.0;

/// `F_0(t)`, the Gaussian tail `Q(t)`.
pub fn f0(t: f64) -> f64 {
    if t > T_HI {
        0.0
    } else if t < T_LO {
        1.0 - f0(-t)
    } else {
        interpolate(0, t)
    }
}

/// `F_1(t)`, the mean of `max(X - t, 0)` for a standard Gaussian `X`.
pub fn f1(t: f64) -> f64 {
    if t > T_HI {
        0.0
    } else if t < T_LO {
        -t + f1(-t)
    } else {
        interpolate(1, t)
    }
}

/// `F_5/2(t)`, exactly 0 for `t > 7`.
pub fn f52(t: f64) -> f64 {
    if t > ASPERITY_CUTOFF {
        0.0
    } else if t < T_LO {
        let r = 1.0 / (t * t);
        (-t).powf(2.5) * (1.0 + r * (15.0 / 8.0 + r * (-15.0 / 128.0 + r * SERIES_6)))
    } else {
        interpolate(2, t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::asperity::gt_integral;

    #[test]
    fn table_matches_the_quadrature() {
        // Off-node points across the whole table (a fixed irrational step), against the
        // quadrature oracle.
        let mut worst = [0.0f64; 3];
        let mut t = -15.999;
        while t < 7.0 {
            for (w, (n, fast)) in worst.iter_mut().zip([
                (0.0, f0 as fn(f64) -> f64),
                (1.0, f1 as fn(f64) -> f64),
                (2.5, f52 as fn(f64) -> f64),
            ]) {
                let exact = gt_integral(n, t).unwrap();
                *w = w.max(((fast(t) - exact) / exact).abs());
            }
            t += 0.0371 * std::f64::consts::SQRT_2;
        }
        for (n, w) in ["F_0", "F_1", "F_5/2"].iter().zip(worst) {
            assert!(w < 1e-8, "{n}: worst relative error {w:.2e}");
        }
    }

    #[test]
    fn beyond_the_table_the_symmetries_and_the_series_hold() {
        for t in [-40.0, -25.0, -16.5, -16.001] {
            assert!((f0(t) - 1.0).abs() < 1e-15);
            let exact = gt_integral(1.0, t).unwrap();
            assert!(((f1(t) - exact) / exact).abs() < 1e-12, "t {t}");
            let exact = gt_integral(2.5, t).unwrap();
            assert!(
                ((f52(t) - exact) / exact).abs() < 1e-10,
                "t {t}: {} {exact}",
                f52(t)
            );
        }
        // The series and the table meet at t = -16.
        let (a, b) = (f52(-16.0 - 1e-9), f52(-16.0 + 1e-9));
        assert!(((a - b) / b).abs() < 1e-8, "{a} {b}");
        assert_eq!(f52(7.0001), 0.0);
        assert!(f52(6.9) > 0.0);
        assert_eq!(f1(9.0), 0.0);
    }
}
