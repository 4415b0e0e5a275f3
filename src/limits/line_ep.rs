//! The line elastic-piezoviscous limit from the solver's own solves.
//!
//! Asymptotic theory gives H_EP = d M^(-1/8) L^(3/4) (docs/physics.md section 5). At a large M
//! the solver's c(L) = H M^(1/8) L^(-3/4) tends to d as L grows, the elastic-isoviscous law's
//! share of the film fading (like L^(-3/4) against the EP law): [`LineEpLimit::run`] solves
//! M = [`EP_M`] at each L of [`EP_L`] (each twice the last) on the finest grid the accuracy
//! ladder reaches ([`EP_TARGET`]: 65537 points), each kept when its estimate is within
//! [`EP_ACCURACY`], and [`LineEpLimit::limit`] extrapolates c(L) by Aitken's delta-squared (the
//! differences shrink geometrically, about 0.46 times per doubling of L). Larger L fail on the
//! fine grids they need (the Barus spike; docs/known-limits.md), so three L values are what the
//! solver gives. The fits hold d at the extrapolation of these solves
//! (`crate::report::recipe::D_EP_CENTRAL`, `D_EP_MIN`); the report re-derives it from fresh
//! solves.

use crate::limits::solves::line_solve_to;
use crate::model::case::Elasticity;
use crate::solve::film::Film;
use crate::solve::solution::Outputs;
use rayon::prelude::*;

/// M of the solves.
pub const EP_M: f64 = 1e4;
/// L of the solves.
pub const EP_L: [f64; 3] = [20.0, 40.0, 80.0];
/// The accuracy ladder's target: finer than the finest grid meets, so every solve ends on
/// [`crate::limits::solves::LINE_LIMIT_MAX_GRID`] (the extrapolation amplifies differences
/// between grids: H_min at L = 80 is 0.2 % lower on the grid a 0.3 % target stops at, and its
/// limit 1 % lower).
pub const EP_TARGET: f64 = 0.001;
/// The relative accuracy each solve must reach (its Richardson estimate of H_c and H_min).
pub const EP_ACCURACY: f64 = 0.003;

/// The line elastic-piezoviscous limit solves at M = [`EP_M`], L = [`EP_L`].
pub struct LineEpLimit {
    /// (L, the solve's outputs; None where it failed or missed [`EP_ACCURACY`]).
    pub solves: Vec<(f64, Option<Outputs>)>,
}

impl LineEpLimit {
    /// The three solves, on the rayon pool.
    pub fn run() -> Self {
        let solves = EP_L
            .par_iter()
            .map(|&l| {
                let o = line_solve_to(EP_M, l, Elasticity::Elastic, EP_TARGET, EP_ACCURACY);
                (l, o)
            })
            .collect();
        LineEpLimit { solves }
    }

    /// c(L) = H M^(1/8) L^(-3/4) of `film` at each solved L.
    pub fn constants(&self, film: Film) -> Vec<(f64, f64)> {
        self.solves
            .iter()
            .filter_map(|(l, o)| {
                o.as_ref()
                    .map(|o| (*l, film.of_outputs(o) * EP_M.powf(0.125) / l.powf(0.75)))
            })
            .collect()
    }

    /// The limit d of `film`: Aitken's extrapolation of the three c(L); None unless all three
    /// solves converged and their differences shrink (ratio in (0, 1)).
    pub fn limit(&self, film: Film) -> Option<f64> {
        let c = self.constants(film);
        let [a, b, e] = [c.first()?.1, c.get(1)?.1, c.get(2)?.1];
        aitken([a, b, e])
    }
}

/// Aitken's delta-squared limit of three terms whose differences shrink geometrically; None when
/// they do not (ratio of the differences outside (0, 1)).
pub fn aitken([a, b, c]: [f64; 3]) -> Option<f64> {
    let r = (c - b) / (b - a);
    (r > 0.0 && r < 1.0).then(|| c + (c - b) * r / (1.0 - r))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn aitken_is_exact_for_a_geometric_approach() {
        // c(k) = 1.3 + 0.05 * 0.46^k
        let c = [0, 1, 2].map(|k| 1.3 + 0.05 * 0.46f64.powi(k));
        assert!((aitken(c).unwrap() - 1.3).abs() < 1e-14);
        assert_eq!(aitken([1.0, 2.0, 4.0]), None);
        assert_eq!(aitken([1.0, 2.0, 1.5]), None);
    }
}
