//! Test utilities shared by the line and point tests of the discrete problem (compiled for tests
//! only).
//!
//! Contract: [`lcg`] is a deterministic random stream (the same seed gives the same values on
//! every machine), [`assert_agree`] compares a fast product with its direct oracle relative to the
//! oracle's largest magnitude, [`nodes`] lays out a uniform grid, and
//! [`isoviscous_incompressible`] is the simplest lubricant (eta = rho = 1) for manufactured checks
//! of the operators.

use crate::discrete::physics::Fluid;
use crate::model::lubricant::{Density, Viscosity};

/// The next value in [0, 1) of a 64-bit linear congruential generator (Knuth's MMIX constants).
pub fn lcg(seed: &mut u64) -> f64 {
    *seed = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    ((*seed >> 11) as f64) / ((1u64 << 53) as f64)
}

/// Asserts |fast_i - direct_i| <= rel max|direct| at every node; `what` names the grid.
pub fn assert_agree(direct: &[f64], fast: &[f64], rel: f64, what: &str) {
    assert_eq!(direct.len(), fast.len(), "{what}: lengths differ");
    let scale = direct.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (i, (a, b)) in direct.iter().zip(fast).enumerate() {
        assert!((a - b).abs() <= rel * scale, "{what} node {i}: {a} vs {b}");
    }
}

/// The spacing h = (b - a)/(n - 1) and the n nodes a + i h of a uniform grid on [a, b].
pub fn nodes(a: f64, b: f64, n: usize) -> (f64, Vec<f64>) {
    let h = (b - a) / (n - 1) as f64;
    (h, (0..n).map(|i| a + i as f64 * h).collect())
}

/// eta = 1 (Barus with alpha_bar = 0), rho = 1.
pub fn isoviscous_incompressible() -> Fluid {
    Fluid {
        viscosity: Viscosity::Barus,
        density: Density::Incompressible,
        alpha_bar: 0.0,
    }
}
