//! H_c through its corner ([`crate::fit::corner`]): which cases follow H_pm, the H_c blend of
//! each held-out fold, and the held-out errors of the H_c law with its corner.
//!
//! Inputs: the cases of a fit ([`FitPoint`], carrying H_c and, where the solve resolved it,
//! H_pm), the H_c samples (their folds are the H_c fit's), the fitted H_c and H_pm blends, the
//! H_c blend fitted without each fold, and the contact's [`CornerParams`]. Output: the
//! corner law fitted on all cases with the ridges the held-out error chose, and the H_c held-out
//! errors of the formula with its corner, each case predicted by a law (its blend included)
//! fitted without that case's fold.

use crate::fit::corner::{
    rigid_ratio, select_corner, Corner, CornerCase, CornerChoice, CornerParams, CornerSelection,
    FOLLOWS,
};
use crate::fit::correction::Correction;
use crate::fit::dataset::FitPoint;
use crate::fit::fitted::Blend;
use crate::fit::heldout::{folds_of, HeldOut, FOLDS, LATTICE_MIN_CASES};
use crate::fit::lsq::Sample;
use crate::fit::model::FilmModel;
use crate::report::recipe::MIN_CASES;
use crate::solve::film::Film;

/// The corner law of H_c and its held-out errors.
pub(super) struct CornerFit {
    /// The law, fitted on all cases.
    pub(super) law: Corner,
    /// Its held-out choice.
    pub(super) choice: CornerChoice,
    /// The held-out errors of H_c with the corner (those of the smooth law's candidates kept for
    /// the report; `chosen` and `cases` replaced).
    pub(super) heldout: HeldOut,
    /// The law fitted without each fold (on that fold's H_c blend, [`Blends::folds`]).
    pub(super) folds: Vec<Corner>,
}

/// The blends of a corner fit: the fitted H_c and H_pm blends, the H_c blend fitted without
/// each fold, and the wrapping of a fitted model into a [`Blend`].
pub(super) struct Blends<'a, Mo> {
    /// The H_c blend fitted on all cases.
    pub(super) own: &'a Mo,
    /// The H_pm blend fitted on all cases (its rigid law sets rho; it judges the cases whose solve
    /// did not resolve H_pm, with its correction where [`CornerParams::pm_corrected`]).
    pub(super) pm: &'a Mo,
    /// The H_pm correction fitted with `pm`.
    pub(super) pm_correction: &'a Correction,
    /// The H_c blend fitted without each fold of [`folds_of`] the H_c samples, in fold order
    /// (the smooth law's cross-validation fits).
    pub(super) folds: &'a [Mo],
    /// The fitted model as a blend.
    pub(super) wrap: fn(Mo) -> Blend,
}

/// The corner fit of H_c (`data`: its samples, `plain`: its held-out errors without a corner)
/// with the contact's `params`, when the data have [`LATTICE_MIN_CASES`] cases and
/// [`MIN_CASES`] on each side of the corner. None otherwise or when a fit fails.
pub(super) fn corner_fit<Mo: FilmModel>(
    pts: &[FitPoint],
    data: &[Sample],
    blends: &Blends<Mo>,
    params: &CornerParams,
    plain: &HeldOut,
) -> Option<CornerFit> {
    let cases: Vec<CornerCase> = pts
        .iter()
        .filter_map(|p| {
            let h = p.film(Film::Centre)?;
            let h_pm = p.h_pm.unwrap_or_else(|| {
                let (m, l, d) = (p.m, p.l, p.dd());
                let blend = blends.pm.film(m, l, d);
                if params.pm_corrected {
                    let asym = blends.pm.asymptotes(m, l, d);
                    blends.pm_correction.apply(blend, asym, d)
                } else {
                    blend
                }
            });
            Some(CornerCase {
                m: p.m,
                l: p.l,
                d: p.dd(),
                h,
                follows: h >= FOLLOWS * h_pm,
            })
        })
        .collect();
    let n_follow = cases.iter().filter(|c| c.follows).count();
    if cases.len() != data.len()
        || cases.len() < LATTICE_MIN_CASES
        || n_follow < MIN_CASES
        || cases.len() - n_follow < MIN_CASES
        || plain.cases.len() != cases.len()
    {
        return None;
    }
    let wrap = blends.wrap;
    let own = wrap(blends.own.clone());
    let rho = rigid_ratio(&wrap(blends.pm.clone()), &own)?;
    if blends.folds.len() != FOLDS {
        return None;
    }
    let fold = folds_of(data);
    let bases: Vec<Blend> = blends.folds.iter().cloned().map(wrap).collect();
    let CornerSelection {
        law,
        choice,
        errors,
        folds,
    } = select_corner(&cases, &fold, &bases, &own, rho, params)?;
    let heldout = plain.clone().with_errors(&errors);
    Some(CornerFit {
        law,
        choice,
        heldout,
        folds,
    })
}
