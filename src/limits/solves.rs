//! The solver's own limit solves of one contact: rigid L = 0, and elastic solves at the largest
//! M of the data at L = 0 and at the largest L (each at [`TREND_FRACTIONS`] of that M), and at
//! twice the largest L. Failed or untrusted solves are None, never a panic.

use crate::discrete::point::domain::PointDomain;
use crate::model::case::{Elasticity, LineCase, Models, PointCase};
use crate::solve::film::Film;
use crate::solve::line::LineSolveParams;
use crate::solve::point::{solve_point, PointSolveParams};
use crate::solve::solution::Outputs;
use crate::solve::Status;
use crate::strategy::accuracy::solve_line_to_accuracy;

/// The elastic checks are solved at these fractions of the largest M of the data, to show the
/// ratio approaching its limit.
pub const TREND_FRACTIONS: [f64; 3] = [0.1, 0.316_227_766_016_837_94, 1.0];

/// The default models (Barus, incompressible) with the given elasticity.
pub fn models(elasticity: Elasticity) -> Models {
    Models {
        elasticity,
        ..Models::default()
    }
}

/// The relative accuracy of the line limit solves (H_c and H_min, by the accuracy ladder): a
/// fifth of the 1 % the fitted formula aims at. (A fixed 4097-point grid left H_c 3.7 % low at
/// M = 3000, L = 0, which the elastic-isoviscous check then reported as the formula's error.)
pub const LINE_LIMIT_ACCURACY: f64 = 0.002;

/// The finest grid the line limit solves may refine to.
pub const LINE_LIMIT_MAX_GRID: usize = 65537;

/// A line limit solve at (M, L), refined from 257 points until its error estimate is within
/// [`LINE_LIMIT_ACCURACY`] (up to [`LINE_LIMIT_MAX_GRID`]): its outputs and alpha_bar at L = 1
/// (for [`rp_from_rigid`]); None for an invalid case, a solve that does not converge or one
/// whose estimate stays above the target.
pub fn line_solve(m: f64, l: f64, el: Elasticity) -> Option<(Outputs, f64)> {
    let ab1 = LineCase::with_models(m, 1.0, models(el))
        .ok()?
        .venner()
        .alpha_bar;
    let o = line_solve_to(m, l, el, LINE_LIMIT_ACCURACY, LINE_LIMIT_ACCURACY)?;
    Some((o, ab1))
}

/// A line limit solve at (M, L) by the accuracy ladder with the target `target` (up to
/// [`LINE_LIMIT_MAX_GRID`]), kept when it converged with an error estimate within `accept`;
/// None for an invalid case or a solve not kept.
pub fn line_solve_to(m: f64, l: f64, el: Elasticity, target: f64, accept: f64) -> Option<Outputs> {
    let case = LineCase::with_models(m, l, models(el)).ok()?;
    let o = solve_line_to_accuracy(
        &case,
        &LineSolveParams::default(),
        target,
        LINE_LIMIT_MAX_GRID,
    )
    .outputs;
    let met = o.error_estimate.is_some_and(|e| e <= accept);
    (o.status == Status::Converged && met).then_some(o)
}

/// Smallest point limit grid; the checks solve on the data's finest grid when that is finer.
/// (129^2 under-resolves the elastic solves at the largest M of a 257^2 sweep: at M = 1000,
/// D = 1 its H_min came out negative.)
pub const POINT_CHECK_GRID: usize = 257;

/// A point limit solve on `grid` points per direction; an elastic one in the rigid-like range
/// (domain-truncation error above `max_truncation`) is not trusted and not solved.
pub fn point_solve(
    m: f64,
    l: f64,
    d: f64,
    el: Elasticity,
    grid: usize,
    max_truncation: f64,
) -> Option<(Outputs, f64)> {
    let case = PointCase::with_models(m, l, d, models(el)).ok()?;
    let truncation = PointDomain::of_case(&case, &Default::default()).truncation_error();
    if el == Elasticity::Elastic && truncation > max_truncation {
        return None;
    }
    let mut p = PointSolveParams::default();
    p.mg.grid = grid;
    let s = solve_point(&case, &p);
    let ab1 = point_alpha_bar_1(m, d, el)?;
    (s.outputs.status == Status::Converged).then_some((s.outputs, ab1))
}

/// alpha_bar of a point case at L = 1 (the rigid-piezoviscous row scales it by L).
pub fn point_alpha_bar_1(m: f64, d: f64, el: Elasticity) -> Option<f64> {
    let case = PointCase::with_models(m, 1.0, d, models(el)).ok()?;
    Some(case.venner().alpha_bar)
}

/// H_RP at `l` from a rigid isoviscous solve: (c L)^(2/3), c = alpha_bar(L=1) P_max H^(3/2)
/// with H the film checked (the rigid-piezoviscous film has the rigid-isoviscous shape).
pub fn rp_from_rigid(o: &Outputs, alpha_bar_1: f64, l: f64, film: Film) -> f64 {
    let c = alpha_bar_1 * o.p_max * film.of_outputs(o).powf(1.5);
    (c * l).powf(2.0 / 3.0)
}

/// The largest M of the cases (M, L) at L = `l`; the largest M of all cases when none is at `l`.
pub fn largest_m_at(cases: &[(f64, f64)], l: f64) -> f64 {
    let top = |any_l: bool| {
        cases
            .iter()
            .filter(|c| any_l || c.1 == l)
            .fold(0.0, |m: f64, c| m.max(c.0))
    };
    Some(top(false))
        .filter(|m| *m > 0.0)
        .unwrap_or_else(|| top(true))
}

/// A limit solve: (M, outputs), None where it did not converge or was not trusted.
pub type Solve = (f64, Option<Outputs>);

/// The limit solves of one contact: rigid L = 0 at M = 1 (given by the caller); elastic at L = 0
/// up to the largest M of the data's L = 0 cases, and at the largest L up to the largest M of
/// those cases (each at [`TREND_FRACTIONS`] of that M), and at twice that L.
pub struct LimitSolves {
    /// Largest M of the data's L = 0 cases (the largest M of all cases when there are none):
    /// the top of the elastic-isoviscous trend.
    pub m_ei: f64,
    /// Largest M of the data's cases at `l_max` (the largest M of all cases when there are
    /// none): the top of the elastic-piezoviscous trend.
    pub m_ep: f64,
    /// Largest L of the data.
    pub l_max: f64,
    /// The rigid L = 0 solve at M = 1: outputs and alpha_bar at L = 1; None where it failed.
    pub rigid: Option<(Outputs, f64)>,
    /// Elastic solves at L = 0, at [`TREND_FRACTIONS`] of `m_ei`, smallest M first.
    pub ei: Vec<Solve>,
    /// Elastic solves at `l_max`, at [`TREND_FRACTIONS`] of `m_ep`, smallest M first; empty
    /// when `l_max` is 0.
    pub ep: Vec<Solve>,
    /// Elastic at `m_ep` and twice the largest L (L > 0 data only); unlike the other [`Solve`]s
    /// the first element is that L, `2 l_max`, not M.
    pub ep_beyond: Option<Solve>,
}

impl LimitSolves {
    /// `cases`: the (M, L) of the data's cases.
    pub fn new(
        cases: &[(f64, f64)],
        rigid: Option<(Outputs, f64)>,
        solve: impl Fn(f64, f64, Elasticity) -> Option<(Outputs, f64)>,
    ) -> Self {
        let l_max = cases.iter().map(|c| c.1).fold(0.0, f64::max);
        let (m_ei, m_ep) = (largest_m_at(cases, 0.0), largest_m_at(cases, l_max));
        let trend = |m_top: f64, l: f64| -> Vec<Solve> {
            TREND_FRACTIONS
                .iter()
                .map(|f| {
                    let m = f * m_top;
                    (m, solve(m, l, Elasticity::Elastic).map(|o| o.0))
                })
                .collect()
        };
        LimitSolves {
            m_ei,
            m_ep,
            l_max,
            rigid,
            ei: trend(m_ei, 0.0),
            ep: if l_max > 0.0 {
                trend(m_ep, l_max)
            } else {
                vec![]
            },
            ep_beyond: (l_max > 0.0).then(|| {
                let l2 = 2.0 * l_max;
                (l2, solve(m_ep, l2, Elasticity::Elastic).map(|o| o.0))
            }),
        }
    }

    /// The solve at the largest M.
    pub fn top(solves: &[Solve]) -> Option<&Outputs> {
        solves.last().and_then(|(_, o)| o.as_ref())
    }

    /// The rigid-piezoviscous film H_RP at `l_max` from the rigid solve ([`rp_from_rigid`]);
    /// None when the rigid solve failed.
    pub fn rp(&self, film: Film) -> Option<f64> {
        self.rigid
            .as_ref()
            .map(|(o, ab)| rp_from_rigid(o, *ab, self.l_max, film))
    }
}
