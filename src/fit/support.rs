//! Where a point lattice correction's data are: the range of a = ln(H_EI/H_RI) that the fitted cases
//! span at each D, and the taper that takes the correction to 0 beyond it.
//!
//! Equation: with the distinct ln D of the cases as nodes and, at each, the smallest and largest
//! a of its cases, a_lo(ln D) and a_hi(ln D) are the piecewise-linear interpolants of those
//! values (held constant beyond the end nodes). A correction C (its sum of basis functions) is
//! applied as F C, F = t((a - a_hi(ln D)) / W) t((a_lo(ln D) - a) / W), t(u) = 1 for u <= 0,
//! (1 + cos(pi u)) / 2 for 0 < u < 1 and 0 for u >= 1, W = [`FADE_WIDTH`].
//!
//! Why: the lattice bumps centred just past the data's a at some D are seen only by their tails
//! (and by the cases of other D through their polynomial in ln D), so beyond the data they are
//! not determined by it (docs/validation.md, "The correction beyond the data"). Beyond the data
//! the formula is then its blend, whose asymptotes are the held limits.
//!
//! Inputs: (ln D, a) of the fitted cases ([`Support::of`]). Output: F in [0, 1] at any
//! (a, ln D) ([`Support::fade`]). Invariants: F = 1 at every case the support was built from
//! (its a lies within its own node's range), F is continuous with a continuous first
//! derivative in a, and F = 0 at least W beyond the range at every D.

use crate::limits::jump::interval;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The width W of the taper in a = ln(H_EI/H_RI): 2 is about half a decade of M where the film
/// is elastic (a grows like (2 - 2/15) ln M for point contacts).
pub const FADE_WIDTH: f64 = 2.0;

/// The range of a spanned by the cases at each ln D (module doc).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Support {
    /// The distinct ln D of the cases, increasing.
    pub ln_d: Vec<f64>,
    /// The smallest a of the cases at each node.
    pub lo: Vec<f64>,
    /// The largest a of the cases at each node.
    pub hi: Vec<f64>,
}

/// The taper t(u) (module doc).
fn taper(u: f64) -> f64 {
    if u <= 0.0 {
        1.0
    } else if u >= 1.0 {
        0.0
    } else {
        0.5 * (1.0 + (PI * u).cos())
    }
}

impl Support {
    /// The support of cases at (ln D, a); None without a case with both finite.
    pub fn of(cases: impl IntoIterator<Item = (f64, f64)>) -> Option<Support> {
        let mut rows: Vec<(f64, f64)> = cases
            .into_iter()
            .filter(|(ln_d, a)| a.is_finite() && ln_d.is_finite())
            .collect();
        rows.sort_by(|x, y| x.0.total_cmp(&y.0));
        let mut s = Support {
            ln_d: vec![],
            lo: vec![],
            hi: vec![],
        };
        for (ln_d, a) in rows {
            if s.ln_d.last() == Some(&ln_d) {
                let k = s.ln_d.len() - 1;
                s.lo[k] = s.lo[k].min(a);
                s.hi[k] = s.hi[k].max(a);
            } else {
                s.ln_d.push(ln_d);
                s.lo.push(a);
                s.hi.push(a);
            }
        }
        (!s.ln_d.is_empty()).then_some(s)
    }

    /// The range (a_lo, a_hi) at `ln_d`.
    pub fn range(&self, ln_d: f64) -> (f64, f64) {
        let (i, j, w) = interval(&self.ln_d, ln_d);
        let at = |v: &[f64]| (1.0 - w) * v[i] + w * v[j];
        (at(&self.lo), at(&self.hi))
    }

    /// F at (a, ln D): 1 within the range, 0 beyond it by [`FADE_WIDTH`] or more.
    pub fn fade(&self, a: f64, ln_d: f64) -> f64 {
        let (lo, hi) = self.range(ln_d);
        taper((a - hi) / FADE_WIDTH) * taper((lo - a) / FADE_WIDTH)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(a: f64, d: f64) -> (f64, f64) {
        (d.ln(), a)
    }

    fn fade(s: &Support, (ln_d, a): (f64, f64)) -> f64 {
        s.fade(a, ln_d)
    }

    /// The support's range at and between its nodes, and the taper: 1 at every case it was
    /// built from, 1/2 half a width beyond the range, 0 a width beyond, smooth at both ends.
    #[test]
    fn the_fade_is_one_over_the_data_and_zero_a_width_beyond() {
        let z = vec![
            at(1.0, 0.1),
            at(7.0, 0.1),
            at(3.0, 0.1),
            at(2.0, 1.0),
            at(10.0, 1.0),
        ];
        let s = Support::of(z.iter().copied()).unwrap();
        assert_eq!(s.lo, vec![1.0, 2.0]);
        assert_eq!(s.hi, vec![7.0, 10.0]);
        for c in &z {
            assert_eq!(fade(&s, *c), 1.0);
        }
        // Halfway in ln D: the range is halfway too; beyond the end nodes it is held.
        let mid = (0.5 * (0.1f64.ln() + 0.0)).exp();
        let (lo, hi) = s.range(mid.ln());
        assert!((lo - 1.5).abs() < 1e-12 && (hi - 8.5).abs() < 1e-12);
        assert_eq!(s.range(0.01f64.ln()), (1.0, 7.0));
        assert_eq!(s.range(2.0f64.ln()), (2.0, 10.0));
        let w = FADE_WIDTH;
        assert!((fade(&s, at(7.0 + 0.5 * w, 0.1)) - 0.5).abs() < 1e-12);
        assert!((fade(&s, at(1.0 - 0.5 * w, 0.1)) - 0.5).abs() < 1e-12);
        assert_eq!(fade(&s, at(7.0 + w, 0.1)), 0.0);
        assert_eq!(fade(&s, at(1.0 - 3.0 * w, 0.1)), 0.0);
        assert_eq!(fade(&s, at(8.5 + 1.01 * w, mid)), 0.0);
        // Continuous with a continuous slope at both ends of the taper.
        let e = 1e-7;
        for u in [0.0, 1.0] {
            let (l, r) = (taper(u - e), taper(u + e));
            assert!((l - r).abs() < 1e-6, "value at {u}");
            let slope = |x: f64| (taper(x + e) - taper(x - e)) / (2.0 * e);
            assert!(slope(u - 2.0 * e).abs() < 1e-5 && slope(u + 2.0 * e).abs() < 1e-5);
        }
        assert!(Support::of([at(f64::NAN, 1.0)]).is_none());
    }
}
