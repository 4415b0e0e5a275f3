//! The line H_c through its corner ([`crate::fit::corner`]): which cases follow H_pm, the base
//! blend of each held-out fold, and the held-out errors of the H_c law with its corner.
//!
//! Inputs: the cases of a fit ([`FitPoint`], carrying H_c and, where the solve resolved it,
//! H_pm), the H_c samples (their folds are the H_c fit's), the fitted H_c and H_pm blends.
//! Output: the corner law fitted on all cases with the ridges the held-out error chose, and the
//! H_c held-out errors of the formula with its corner, each case predicted by a law (its base
//! blend included) fitted without that case's fold.

use crate::fit::corner::{select_corner, Corner, CornerCase, CornerChoice, FOLLOWS};
use crate::fit::dataset::FitPoint;
use crate::fit::fitted::Blend;
use crate::fit::heldout::{folds_of, worst_and_rms, HeldOut, FOLDS, LATTICE_MIN_CASES};
use crate::fit::lsq::Sample;
use crate::fit::model::{FilmModel, LineModel};
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
}

/// How the H_pm blend is had: its samples, its fit on a training set (None: failed), and the
/// wrapping of a fitted model into a [`Blend`] (a line blend has a corner law, others none).
pub(super) struct PmBlends<'a, Mo> {
    /// The H_pm samples.
    pub(super) data: &'a [Sample],
    /// The H_pm blend fitted on a training set.
    pub(super) fit: &'a dyn Fn(&[Sample]) -> Option<Mo>,
    /// The fitted model as a blend.
    pub(super) wrap: fn(Mo) -> Blend,
}

/// The line blend of a model (None for a point model).
fn line_of<Mo>(wrap: fn(Mo) -> Blend, m: Mo) -> Option<LineModel> {
    match wrap(m) {
        Blend::Line(x) => Some(x),
        Blend::Point(_) => None,
    }
}

/// The corner fit of H_c (`data`: its samples, `own`: its blend, `plain`: its held-out errors
/// without a corner) on the H_pm blend `pm`, whose refit without each fold `pms` gives, when the
/// data have [`LATTICE_MIN_CASES`] cases and [`MIN_CASES`] on each side of the corner. None
/// otherwise, for a point contact, or when a fit fails.
pub(super) fn corner_fit<Mo: FilmModel>(
    pts: &[FitPoint],
    data: &[Sample],
    own: &Mo,
    pm: &Mo,
    pms: &PmBlends<Mo>,
    plain: &HeldOut,
) -> Option<CornerFit> {
    let cases: Vec<CornerCase> = pts
        .iter()
        .filter_map(|p| {
            let h = p.film(Film::Centre)?;
            let h_pm = p.h_pm.unwrap_or_else(|| pm.film(p.m, p.l, p.dd()));
            Some(CornerCase {
                m: p.m,
                l: p.l,
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
    let fold = folds_of(data);
    let bases = (0..FOLDS)
        .map(|f| {
            let held = |s: &Sample| {
                (0..data.len()).any(|i| fold[i] == f && data[i].m == s.m && data[i].l == s.l)
            };
            let train: Vec<Sample> = pms.data.iter().copied().filter(|s| !held(s)).collect();
            line_of(pms.wrap, (pms.fit)(&train)?)
        })
        .collect::<Option<Vec<_>>>()?;
    let (law, choice, errors) = select_corner(
        &cases,
        &fold,
        &bases,
        &line_of(pms.wrap, pm.clone())?,
        &line_of(pms.wrap, own.clone())?,
    )?;
    let mut heldout = plain.clone();
    for (c, e) in heldout.cases.iter_mut().zip(&errors) {
        c.error = *e;
    }
    let (worst, rms) = worst_and_rms(&errors);
    let w = &heldout.cases[worst];
    heldout.chosen.rms = rms;
    heldout.chosen.max = errors[worst];
    heldout.chosen.worst = (w.m, w.l, w.d);
    Some(CornerFit {
        law,
        choice,
        heldout,
    })
}
