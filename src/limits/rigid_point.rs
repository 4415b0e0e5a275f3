//! The rigid-isoviscous constant of a point contact, from the solver's own rigid solves.
//!
//! A rigid isoviscous point contact obeys H M^2 = c_RI(D) exactly (the pressure scales with
//! 1/H^2 at fixed load; docs/physics.md section 5), and H_min = H_c (the gap is smallest at the
//! centre). Its pressure decays like r^-3 into the inlet and the sides, so a domain truncated at
//! R loses load like 1/R and the film comes out low like
//!
//! H(R) = H_inf (1 - a/R - b/R^2 - ...).
//!
//! [`RigidPointSolves::run`] solves the rigid case at M = 1, L = 0 on the default rigid domain
//! ([`crate::discrete::point::domain::PointDomain`]) truncated with P = 0 on its boundary (not
//! the solver's default far field, so that the constants stay a reference independent of it)
//! and enlarged by [`DOMAIN_SCALES`] = 1, 2, 4, with
//! the grid refined alongside ([`GRIDS`]: the spacing of the default 257^2 solve), and
//! [`extrapolate`] removes both terms by Richardson extrapolation in 1/R:
//!
//! E1(R) = 2 H(2R) - H(R),  H_inf = (4 E1(2R) - E1(R))/3.
//!
//! [`C_RI_CENTRE`] and [`C_RI_PMAX`] are these extrapolations at D = 1, held by the point fits
//! ([`crate::fit::point_model`]); across D the fits use NVM's D factor f_RI(D) (e_RI = 0). The
//! rigid-isoviscous check of the fit report re-solves scales 1, 2, 4 and compares their
//! extrapolation with the fitted law. (Solves, extrapolations and the check across D:
//! docs/validation.md, "The circular rigid-isoviscous constant"; timings: docs/performance.md.)

use crate::discrete::point::domain::PointDomainParams;
use crate::model::case::{Elasticity, Models, PointCase};
use crate::solve::film::Film;
use crate::solve::point::{solve_point, PointSolveParams};
use crate::solve::solution::Outputs;
use crate::solve::Status;
use rayon::prelude::*;

/// c_RI of H_c and H_min at D = 1 (the point model's f_RI(D) is 1 there): the domain-extrapolated
/// rigid solves, +-0.1 (docs/validation.md).
pub const C_RI_CENTRE: f64 = 35.5;
/// c_RI of the film at the pressure maximum at D = 1: the domain-extrapolated rigid solves, +-0.2
/// (docs/validation.md).
pub const C_RI_PMAX: f64 = 45.0;

/// The point model's fixed c_RI for a film.
pub fn c_ri(film: Film) -> f64 {
    match film {
        Film::PressureMax => C_RI_PMAX,
        Film::Centre | Film::Minimum => C_RI_CENTRE,
    }
}

/// Domain enlargement factors of the rigid solves.
pub const DOMAIN_SCALES: [f64; 3] = [1.0, 2.0, 4.0];
/// Points per direction at each scale: the spacing of the default 257^2 solve.
pub const GRIDS: [usize; 3] = [257, 513, 1025];

/// The domain limit from films on domains scaled 1, 2, 4 (Richardson in 1/R, two terms).
pub fn extrapolate(h: [f64; 3]) -> f64 {
    let e1 = [2.0 * h[1] - h[0], 2.0 * h[2] - h[1]];
    (4.0 * e1[1] - e1[0]) / 3.0
}

/// Rigid isoviscous solves at M = 1, L = 0 on the enlarged domains (run on the rayon pool).
pub struct RigidPointSolves {
    /// Ellipticity D = Rx/Ry of the solves.
    pub d: f64,
    /// (domain scale, outputs), in [`DOMAIN_SCALES`] order.
    pub solves: Vec<(f64, Outputs)>,
}

/// The rigid isoviscous point case at M = 1, L = 0 and ellipticity `d` (None for an invalid `d`).
pub fn rigid_case(d: f64) -> Option<PointCase> {
    let models = Models {
        elasticity: Elasticity::Rigid,
        ..Models::default()
    };
    PointCase::with_models(1.0, 0.0, d, models).ok()
}

impl RigidPointSolves {
    /// All three solves at ellipticity `d`, converged or not; None only for an invalid `d`.
    pub fn run(d: f64) -> Option<Self> {
        let case = rigid_case(d)?;
        // Independent deterministic solves: the same outputs on any number of threads.
        let solves: Vec<(f64, Outputs)> = DOMAIN_SCALES
            .into_par_iter()
            .zip(GRIDS)
            .map(|(scale, grid)| {
                let mut p = PointSolveParams::default();
                p.mg.grid = grid;
                // (A rigid domain has only l_h-scaled extents.)
                p.mg.domain = PointDomainParams {
                    far_field: false,
                    ..p.mg.domain.scaled(scale)
                };
                (scale, solve_point(&case, &p).outputs)
            })
            .collect();
        Some(RigidPointSolves { d, solves })
    }

    /// Whether every solve converged (the extrapolation needs all three).
    pub fn converged(&self) -> bool {
        self.solves
            .iter()
            .all(|(_, o)| o.status == Status::Converged)
    }

    /// The converged solve on the default domain (scale 1, 257^2: the plain rigid point solve).
    pub fn default_domain(&self) -> Option<&Outputs> {
        self.solves
            .first()
            .map(|(_, o)| o)
            .filter(|o| o.status == Status::Converged)
    }

    /// The film on each domain.
    pub fn films(&self, film: Film) -> [f64; 3] {
        [0, 1, 2].map(|k| film.of_outputs(&self.solves[k].1))
    }

    /// The extrapolated rigid film H M^2 (= H at M = 1): [`extrapolate`] of [`Self::films`].
    pub fn extrapolated(&self, film: Film) -> f64 {
        extrapolate(self.films(film))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extrapolation_removes_the_first_two_inverse_powers_of_the_domain() {
        // H(R) = 35.5 (1 - 0.6/R + 0.3/R^2) at R = 1, 2, 4: exact.
        let h = [1.0, 2.0, 4.0].map(|r: f64| 35.5 * (1.0 - 0.6 / r + 0.3 / (r * r)));
        assert!((extrapolate(h) - 35.5).abs() < 1e-12, "{}", extrapolate(h));
        // A 1/R^3 term is left at an eighth of its size at R = 1.
        let h3 = [1.0, 2.0, 4.0].map(|r: f64| 35.5 * (1.0 - 0.1 / (r * r * r)));
        assert!((extrapolate(h3) - 35.5 + 3.55 / 8.0).abs() < 1e-12);
    }
}
