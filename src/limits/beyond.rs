//! The point elastic-isoviscous limit solve a decade of M beyond the data: the check of issue 24
//! that the formula still follows the solver where no data case constrains it.
//!
//! Inputs: the largest M of the data's L = 0 cases, m_ei, and the check's D. The case (M_b, L,
//! D) = ([`BEYOND_FACTOR`] m_ei, 0, D) is solved on each of [`BEYOND_GRIDS`] (without the
//! half-grid estimate), and each film is extrapolated to zero spacing by [`richardson`]: with
//! three grids h, h/2, h/4 and films F_1, F_2, F_3 the observed order is p = log2((F_2 - F_1) /
//! (F_3 - F_2)) and F = F_3 + (F_3 - F_2) / (2^p - 1). Where the three do not show an order in
//! [`ORDER_RANGE`] (the differences change sign, or a solve failed) p = 2, the discretisation's
//! own order, is taken, and the order is reported as None. Output: the films per grid, the
//! extrapolated film and its error bar |F - F_3| (the extrapolation's whole step: the solves at
//! M = 3162 and 1e4 show p = 2.07-2.25, so the step over-states what is left).
//!
//! Invariant: no solve, no value: a failed solve on the finest grid leaves the solver's value
//! None. Reference: Roache, Verification and Validation in Computational Science and
//! Engineering (1998), ch. 5 (generalised Richardson extrapolation).

use crate::limits::solves::point_solve;
use crate::model::case::Elasticity;
use crate::solve::film::Film;
use crate::solve::solution::Outputs;
use serde::{Deserialize, Serialize};

/// M of the beyond solve over the largest M of the data's L = 0 cases: a decade.
pub const BEYOND_FACTOR: f64 = 10.0;

/// The grids of the beyond solve (points per direction), coarsest first: each spacing half the
/// last.
pub const BEYOND_GRIDS: [usize; 3] = [513, 1025, 2049];

/// The largest domain-truncation estimate of a beyond solve (that of the fit's data rows; far
/// below it a decade beyond the data, where the films are elastic).
pub const MAX_TRUNCATION: f64 = 0.02;

/// Observed orders accepted by [`richardson`] (the discretisation is second order).
pub const ORDER_RANGE: (f64, f64) = (1.0, 4.0);

/// A film extrapolated to zero grid spacing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Extrapolated {
    /// The extrapolated film.
    pub value: f64,
    /// The observed order p; None where the solves did not show one in [`ORDER_RANGE`] (p = 2
    /// taken).
    pub order: Option<f64>,
    /// |value - finest film|: the extrapolation's step, taken as its error bar.
    pub error_bar: f64,
}

/// Richardson extrapolation of films on three grids, each of half the spacing of the last
/// (module doc); None when a film is not finite.
pub fn richardson(f: [f64; 3]) -> Option<Extrapolated> {
    if !f.iter().all(|v| v.is_finite()) {
        return None;
    }
    let (d1, d2) = (f[1] - f[0], f[2] - f[1]);
    let observed = (d1 * d2 > 0.0).then(|| (d1 / d2).log2());
    let order = observed.filter(|p| (ORDER_RANGE.0..=ORDER_RANGE.1).contains(p));
    let p = order.unwrap_or(2.0);
    let value = f[2] + d2 / (2f64.powf(p) - 1.0);
    Some(Extrapolated {
        value,
        order,
        error_bar: (value - f[2]).abs(),
    })
}

/// The solves of the beyond check at (m, 0, d): one per grid of [`BEYOND_GRIDS`], None where it
/// did not converge.
#[derive(Clone, Debug)]
pub struct BeyondSolves {
    /// M of the solves.
    pub m: f64,
    /// D of the solves.
    pub d: f64,
    /// (grid, outputs) per grid, coarsest first.
    pub solves: Vec<(usize, Option<Outputs>)>,
}

impl BeyondSolves {
    /// Solve at [`BEYOND_FACTOR`] `m_ei`, L = 0, `d` on every grid.
    pub fn run(m_ei: f64, d: f64) -> Self {
        Self::at(BEYOND_FACTOR * m_ei, d)
    }

    /// Solve at (m, 0, d) on every grid of [`BEYOND_GRIDS`].
    pub fn at(m: f64, d: f64) -> Self {
        let solves = BEYOND_GRIDS
            .iter()
            .map(|&g| {
                let o = point_solve(m, 0.0, d, Elasticity::Elastic, g, MAX_TRUNCATION);
                (g, o.map(|o| o.0))
            })
            .collect();
        BeyondSolves { m, d, solves }
    }

    /// The check of one film ([`Beyond`], without the formula's value).
    pub fn of(&self, film: Film) -> Beyond {
        let films: Vec<Option<f64>> = self
            .solves
            .iter()
            .map(|(_, o)| o.as_ref().map(|o| film.of_outputs(o)))
            .collect();
        let e = match films.as_slice() {
            [Some(a), Some(b), Some(c)] => richardson([*a, *b, *c]),
            _ => None,
        };
        Beyond {
            m: self.m,
            d: self.d,
            grids: self.solves.iter().map(|s| s.0).collect(),
            films,
            solver: e.map(|e| e.value),
            order: e.and_then(|e| e.order),
            error_bar: e.map(|e| e.error_bar),
            formula: None,
            ratio: None,
        }
    }
}

/// The elastic-isoviscous check a decade beyond the data, for one film.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Beyond {
    /// M of the solves ([`BEYOND_FACTOR`] times the largest M of the data's L = 0 cases).
    pub m: f64,
    /// D of the solves (L = 0).
    pub d: f64,
    /// The grids, coarsest first.
    pub grids: Vec<usize>,
    /// The film on each grid (None: that solve did not converge).
    pub films: Vec<Option<f64>>,
    /// The film extrapolated to zero spacing ([`richardson`]); None without all three solves.
    pub solver: Option<f64>,
    /// The observed order (None: p = 2 taken, or no extrapolation).
    pub order: Option<f64>,
    /// The extrapolation's error bar.
    pub error_bar: Option<f64>,
    /// The whole formula (blend, correction, kriging, corner law) at (m, 0, d).
    pub formula: Option<f64>,
    /// solver / formula.
    pub ratio: Option<f64>,
}

impl Beyond {
    /// With the formula's film `h` at (m, 0, d): sets `formula` and `ratio`.
    pub fn with_formula(mut self, h: f64) -> Self {
        self.formula = Some(h);
        self.ratio = self.solver.map(|s| s / h);
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn richardson_recovers_the_limit_of_a_known_expansion() {
        // F(h) = 1 + 0.3 h^2.2: three grids h = 1/4, 1/8, 1/16.
        let f = |h: f64| 1.0 + 0.3 * h.powf(2.2);
        let e = richardson([f(0.25), f(0.125), f(0.0625)]).unwrap();
        assert!((e.order.unwrap() - 2.2).abs() < 1e-12, "{e:?}");
        assert!((e.value - 1.0).abs() < 1e-12, "{e:?}");
        assert!((e.error_bar - 0.3 * 0.0625f64.powf(2.2)).abs() < 1e-12);
        // A sign change between the differences: no order; p = 2 taken.
        let e = richardson([1.0, 1.01, 1.008]).unwrap();
        assert_eq!(e.order, None);
        assert!((e.value - (1.008 - 0.002 / 3.0)).abs() < 1e-15);
        // An order outside the accepted range (differences nearly equal: p near 0) is not
        // taken either.
        assert_eq!(richardson([1.0, 1.01, 1.0199]).unwrap().order, None);
        assert!(richardson([1.0, f64::NAN, 1.0]).is_none());
    }

    #[test]
    fn a_failed_solve_leaves_no_solver_value() {
        let s = BeyondSolves {
            m: 1e4,
            d: 1.0,
            solves: vec![(513, None), (1025, None), (2049, None)],
        };
        let b = s.of(Film::Centre).with_formula(0.66);
        assert_eq!(b.films, vec![None, None, None]);
        assert_eq!((b.solver, b.ratio), (None, None));
        assert_eq!(b.formula, Some(0.66));
    }
}
