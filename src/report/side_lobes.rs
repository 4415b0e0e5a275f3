//! The point H_min through the centre line ([`crate::fit::side`]): which cases the side-lobe
//! factor is fitted to, its held-out choice on the folds of the centre-line fit, and the held-out
//! errors of H_min composed of both parts.
//!
//! Inputs: the point cases of a fit ([`FitPoint`], carrying H_min and H_min,cl). Outputs: the
//! centre-line samples the H_min law's blend is fitted to, the factor with its held-out choice,
//! and [`composed`] held-out errors, each case predicted by the centre-line law and the factor
//! both fitted without that case's fold.

use crate::fit::dataset::FitPoint;
use crate::fit::heldout::{folds_of, CaseError, HeldOut, FOLDS};
use crate::fit::lsq::Sample;
use crate::fit::side::{select_side, SideCase, SideChoice, SideLobe, NO_LOBE};
use crate::solve::film::Film;

/// The point H_min fitted through the centre line: the side cases, the centre-line samples and
/// the factor chosen on their folds.
pub(super) struct SideLobes {
    /// The cases carrying H_min and H_min,cl, with y = ln(H_min,cl / H_min).
    pub(super) cases: Vec<SideCase>,
    /// The samples of H_min,cl (the data of the H_min law's blend and correction).
    pub(super) centre_line: Vec<Sample>,
    /// The factor fitted on all cases.
    pub(super) lobe: SideLobe,
    /// Its held-out choice.
    pub(super) choice: SideChoice,
}

/// The side-lobe fit of `pts` when at least `need` cases carry both films, some with a side lobe,
/// and the factor can be cross-validated (None: H_min is fitted directly).
pub(super) fn side_lobes(pts: &[FitPoint], need: usize) -> Option<SideLobes> {
    let cases = side_cases(pts);
    if cases.len() < need || !cases.iter().any(|c| c.y > NO_LOBE) {
        return None;
    }
    let centre_line = centre_line_samples(pts);
    let folds = folds_of(&centre_line);
    let fold: Vec<usize> = cases
        .iter()
        .map(|c| folds[index_in(&centre_line, c)])
        .collect();
    let (lobe, choice) = select_side(&cases, &fold, FOLDS)?;
    Some(SideLobes {
        cases,
        centre_line,
        lobe,
        choice,
    })
}

/// The cases carrying both the minimum film and the centre line's, with y = ln(H_min,cl /
/// H_min) (0 where rounding puts H_min above H_min,cl).
fn side_cases(pts: &[FitPoint]) -> Vec<SideCase> {
    pts.iter()
        .filter_map(|p| {
            let cl = p.centre_line_min()?;
            let h = p.film(Film::Minimum)?;
            Some(SideCase {
                m: p.m,
                l: p.l,
                d: p.dd(),
                y: (cl / h).ln().max(0.0),
            })
        })
        .collect()
}

/// The samples of the centre line's minimum film (the cases that carry it).
fn centre_line_samples(pts: &[FitPoint]) -> Vec<Sample> {
    pts.iter()
        .filter_map(|p| {
            p.centre_line_min().map(|h| Sample {
                m: p.m,
                l: p.l,
                d: p.dd(),
                h,
            })
        })
        .collect()
}

/// The index of the side case `c` among the centre-line samples `cl`.
fn index_in(cl: &[Sample], c: &SideCase) -> usize {
    cl.iter()
        .position(|s| s.m == c.m && s.l == c.l && s.d == c.d)
        .expect("a side case carries the centre line's film")
}

/// The held-out errors of H_min composed of the centre-line law's (`heldout`, on the
/// centre-line samples) and the factor's (on the side cases, the same folds): each case
/// predicted by both parts fitted without its fold. None without the centre line's held-out
/// errors.
pub(super) fn composed(
    s: &SideLobes,
    heldout: Option<HeldOut>,
    pts: &[FitPoint],
) -> Option<HeldOut> {
    let cl = &s.centre_line;
    let mut h = heldout.filter(|h| h.cases.len() == cl.len())?;
    h.cases = s
        .cases
        .iter()
        .zip(&s.choice.heldout_g)
        .map(|(c, g)| {
            let p = pts
                .iter()
                .find(|p| p.m == c.m && p.l == c.l && p.dd() == c.d)
                .expect("a side case is a data case");
            let h_min = p.film(Film::Minimum).expect("a side case carries H_min");
            let k = index_in(cl, c);
            let predicted = (1.0 + h.cases[k].error) * cl[k].h;
            CaseError {
                m: c.m,
                l: c.l,
                d: c.d,
                h: Some(h_min),
                error: predicted * (-g.max(0.0)).exp() / h_min - 1.0,
                estimate: p.estimate(Film::Minimum),
            }
        })
        .collect();
    Some(h.rescored())
}
