//! The Hertzian start of a thin isoviscous film: where the coarse grids cannot represent the
//! film, the FMG ascent starts on the first level that resolves it, from the dry (Hertzian)
//! pressure.
//!
//! Contract. Inputs: a point multigrid built for a case (its domain's central-film estimate
//! H_e in Hertzian units, [`crate::discrete::point::domain::PointDomain::h_estimate`], and its
//! levels). Let l_h = sqrt(2 H_e) be the hydrodynamic length and l_s the coarsest level whose
//! spacing h_x along the rolling direction satisfies l_h >= [`RESOLVE_CELLS`] h_x. Where the
//! surfaces are elastic, the lubricant isoviscous (alpha_bar = 0), l_s has at least
//! [`MIN_START_INTERVALS`] intervals per direction and l_s is below the finest level, [`hertz_start`] returns a [`Seed`] on level l_s:
//!
//! * P = sqrt(1 - X^2 - (Y/k)^2) inside the Hertz ellipse, 0 outside (its load is the case's,
//!   2 pi k / 3);
//! * H0 such that the film at the centre is f H_e, f = [`START_FILM_FACTOR`]:
//!   H0 = f H_e - c (K*P)(0, 0), the gap being 0 there (c (K*P)(0, 0) is the Hertzian
//!   approach: 1 for the circle, 1.317 at D = 0.215).
//!
//! Otherwise None, and the solve starts its ascent from the coarsest level as usual.
//!
//! Why: at high M the film (H_e ~ 2e-3 at M = 5720, D = 1) is a small difference of the gap and
//! the deformation, which a coarse grid of spacing h carries only to O(h^2) ~ 4e-2: the coarse
//! levels' solutions are not films of the case, and an ascent from them diverges on the finer
//! levels. The coarse levels still serve as FAS correction grids. Measured in
//! docs/robustness.md ("The Hertzian start of thin isoviscous films"). Reference: Venner &
//! Lubrecht, Multilevel Methods in Lubrication (2000), ch. 7 (the Hertzian initial pressure of
//! highly loaded contacts).

use crate::discrete::physics::Physics;
use crate::discrete::point::domain::{PointDomain, PointDomainParams};
use crate::discrete::point::operator::PointPhysics;
use crate::model::case::PointCase;
use crate::solve::multilevel::Seed;
use crate::solve::point::multigrid::{hertz_pressure, PointMultigrid};

/// The hydrodynamic length l_h must span at least this many cells of a level for the film to
/// be represented there.
pub const RESOLVE_CELLS: f64 = 4.0;

/// The start's film at the centre, in units of the estimate H_e: a start at H_e itself can
/// cut through the film where the dry pressure exceeds the lubricated one (measured:
/// docs/robustness.md), and the load balance thins a thicker start within a few cycles.
pub const START_FILM_FACTOR: f64 = 2.0;

/// The start is used only where the first level that resolves the film has this many intervals
/// per direction (257^2 nodes) or more: coarser starts are the usual FMG ascent.
pub const MIN_START_INTERVALS: usize = 256;

/// Whether a resolving level with `intervals` per direction is fine enough for the start
/// ([`MIN_START_INTERVALS`]).
fn fine_enough(intervals: usize) -> bool {
    intervals >= MIN_START_INTERVALS
}

/// The level l_s of the module doc: the coarsest whose spacing `hx[l]` the hydrodynamic length
/// of the film `h_e` (Hertzian units) spans [`RESOLVE_CELLS`] times; None if none does.
pub fn resolving_level(h_e: f64, hx: &[f64]) -> Option<usize> {
    let lh = (2.0 * h_e.max(0.0)).sqrt();
    hx.iter().position(|&h| lh >= RESOLVE_CELLS * h)
}

/// Whether the physics admit the start: elastic surfaces, a lubricated (not dry) contact and an
/// isoviscous lubricant (alpha_bar = 0).
fn admits(common: &Physics) -> bool {
    common.elastic && !common.dry && common.fluid.alpha_bar == 0.0
}

/// The level l_s of the module doc for `case` on the domain of `p`, where the start applies on
/// grids finer than it ([`fine_enough`]); None where it never applies.
fn start_level(case: &PointCase, p: &PointDomainParams) -> Option<(usize, usize)> {
    if !admits(&PointPhysics::from_case(case).common) {
        return None;
    }
    let dom = PointDomain::of_case(case, p);
    let width = dom.x_out - dom.x_in;
    let hx: Vec<f64> = (0..16).map(|l| width / (dom.n0 << l) as f64).collect();
    let l = resolving_level(dom.h_estimate, &hx).filter(|&l| fine_enough(dom.n0 << l))?;
    Some((l, dom.n0))
}

/// The coarsest grid (points per direction) on which `case` takes the start: the grid one level
/// above l_s. Coarser grids cannot resolve the film on a level below their finest, and their
/// ascent from the coarsest level fails (the accuracy ladder starts here:
/// [`crate::strategy::accuracy::solve_point_to_accuracy`]). None where the start never applies.
pub fn first_start_grid(case: &PointCase, p: &PointDomainParams) -> Option<usize> {
    start_level(case, p).map(|(l, n0)| (n0 << (l + 1)) + 1)
}

/// The seed of the module doc for `mg`, or None where the usual ascent is kept.
pub fn hertz_start(mg: &mut PointMultigrid) -> Option<Seed> {
    if !admits(&mg.phys.common) {
        return None;
    }
    let top = mg.levels.len() - 1;
    let hx: Vec<f64> = mg.levels.iter().map(|lv| lv.hx).collect();
    let h_e = mg.domain.h_estimate;
    let l = resolving_level(h_e, &hx).filter(|&l| fine_enough(mg.levels[l].nx - 1) && l < top)?;
    let k = mg.phys.k;
    let lv = &mut mg.levels[l];
    let (nx, ny) = (lv.nx, lv.ny);
    let mut p = vec![0.0; nx * ny];
    for (j, &y) in lv.y.iter().enumerate() {
        for (i, &x) in lv.x.iter().enumerate() {
            p[j * nx + i] = hertz_pressure(x, y, k);
        }
    }
    let mut w = vec![0.0; nx * ny];
    lv.deformation_of(&mg.phys, &p, &mut w);
    let (ic, jc) = mg.domain.centre(nx - 1);
    let h0 = START_FILM_FACTOR * h_e - w[jc * nx + ic];
    Some(Seed {
        x: lv.x.clone(),
        y: lv.y.clone(),
        p,
        h0_moes: h0 * mg.phys.h_scale,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_resolving_level_is_the_first_whose_cells_the_hydrodynamic_length_spans_four_times() {
        // Spacings of a 3-wide domain on 16, 32, ... 1024 intervals.
        let hx: Vec<f64> = (0..7).map(|l| 3.0 / (16 << l) as f64).collect();
        // l_h = 0.06 (H_e = 1.8e-3): 0.06 / (3 / 256) = 5.1 cells on level 4, 2.6 on level 3.
        assert_eq!(resolving_level(1.8e-3, &hx), Some(4));
        // A thick film (l_h = 1) is resolved on the coarsest level.
        assert_eq!(resolving_level(0.5, &hx), Some(0));
        // A film no level resolves.
        assert_eq!(resolving_level(1e-7, &hx), None);
    }
}
