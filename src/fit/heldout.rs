//! Held-out errors of a fitted formula, and the size of its interior correction chosen by them.
//!
//! K-fold cross-validation ([`FOLDS`] folds): the cases are ranked by (M, L, D) and case k goes to
//! fold k mod K, so every fold spans the whole map. For each fold the blend is refitted on the
//! other folds (the caller's `fit_blend`), then for each n the correction with the first n terms
//! of the nested list ([`crate::fit::correction`]); the fold's cases are predicted by that
//! formula. Each case is predicted exactly once per n, by a formula that never saw it. The size
//! kept is the smallest n whose held-out RMS relative error is within [`RMS_SLACK`] of the best
//! n's (fewer terms when more buy almost nothing). Inputs: the samples (M, L, D, H) and the
//! nested term list; output: [`HeldOut`] (per size: RMS, max; the size chosen; each case's
//! held-out error at that size).

use crate::fit::correction::{fit_correction, Coordinates, Correction, Term};
use crate::fit::lsq::Sample;
use crate::fit::model::FilmModel;
use serde::{Deserialize, Serialize};

/// Number of cross-validation folds.
pub const FOLDS: usize = 5;

/// A size within this factor of the best held-out RMS counts as good as the best.
pub const RMS_SLACK: f64 = 1.02;

/// Each fold's training set must have this many more cases than the correction has terms.
const SPARE: usize = 10;

/// Held-out errors of one correction size.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SizeScore {
    /// Number of correction terms (0: the blend alone).
    pub terms: usize,
    /// RMS of the held-out relative errors formula/data - 1.
    pub rms: f64,
    /// Largest |held-out relative error|, sign kept.
    pub max: f64,
    /// Where the largest error is: (M, L, D).
    pub worst: (f64, f64, f64),
}

/// The held-out relative error of one case (at the size kept).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CaseError {
    /// Moes' M.
    pub m: f64,
    /// Moes' L.
    pub l: f64,
    /// D (1 for a line contact).
    pub d: f64,
    /// formula / data - 1, the formula fitted without this case's fold.
    pub error: f64,
}

/// The cross-validation of one film's formula.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct HeldOut {
    /// Folds used.
    pub folds: usize,
    /// Every size tried, in increasing number of terms.
    pub sizes: Vec<SizeScore>,
    /// The size kept (an entry of `sizes`).
    pub chosen: SizeScore,
    /// Each case's held-out error at the size kept, in the data's order (the validity map).
    #[serde(default)]
    pub cases: Vec<CaseError>,
}

fn coords<Mo: FilmModel>(model: &Mo, s: &Sample) -> Coordinates {
    Coordinates::new(model.asymptotes(s.m, s.l, s.d), s.d)
}

/// The correction with the first `n` of `terms` fitted to `data` on top of `blend`; None when the
/// solve fails.
pub fn correction_for<Mo: FilmModel>(
    blend: &Mo,
    data: &[Sample],
    terms: &[Term],
) -> Option<Correction> {
    let z: Vec<_> = data.iter().map(|s| coords(blend, s)).collect();
    let r: Vec<_> = data
        .iter()
        .map(|s| s.h.ln() - blend.film(s.m, s.l, s.d).ln())
        .collect();
    fit_correction(&z, &r, terms)
}

/// Cross-validate the sizes 0..=terms.len() (those the folds have enough cases for). None when
/// there are fewer than 2 [`FOLDS`] cases or a fold's blend fit fails.
pub fn select<Mo: FilmModel>(
    data: &[Sample],
    terms: &[Term],
    fit_blend: &dyn Fn(&[Sample]) -> Option<Mo>,
) -> Option<HeldOut> {
    if data.len() < 2 * FOLDS {
        return None;
    }
    let mut order: Vec<usize> = (0..data.len()).collect();
    order.sort_by(|&i, &j| {
        let (a, b) = (&data[i], &data[j]);
        a.m.total_cmp(&b.m)
            .then(a.l.total_cmp(&b.l))
            .then(a.d.total_cmp(&b.d))
    });
    let mut fold = vec![0; data.len()];
    for (rank, &i) in order.iter().enumerate() {
        fold[i] = rank % FOLDS;
    }
    let smallest_train = (0..FOLDS)
        .map(|f| fold.iter().filter(|&&g| g != f).count())
        .min()?;
    let sizes = (0..=terms.len())
        .filter(|n| n + SPARE <= smallest_train)
        .count();
    // errors[n][i]: the held-out relative error of case i with n terms.
    let mut errors = vec![vec![f64::NAN; data.len()]; sizes];
    for f in 0..FOLDS {
        let train: Vec<Sample> = (0..data.len())
            .filter(|&i| fold[i] != f)
            .map(|i| data[i])
            .collect();
        let blend = fit_blend(&train)?;
        for (n, row) in errors.iter_mut().enumerate() {
            let Some(c) = correction_for(&blend, &train, &terms[..n]) else {
                continue;
            };
            for i in (0..data.len()).filter(|&i| fold[i] == f) {
                let s = &data[i];
                let log = c.log_factor(blend.asymptotes(s.m, s.l, s.d), s.d);
                row[i] = blend.film(s.m, s.l, s.d) * log.exp() / s.h - 1.0;
            }
        }
    }
    let scores: Vec<SizeScore> = errors
        .iter()
        .enumerate()
        .filter(|(_, e)| e.iter().all(|v| v.is_finite()))
        .map(|(n, e)| {
            let worst = (0..e.len())
                .max_by(|&i, &j| e[i].abs().total_cmp(&e[j].abs()))
                .expect("non-empty");
            SizeScore {
                terms: n,
                rms: (e.iter().map(|v| v * v).sum::<f64>() / e.len() as f64).sqrt(),
                max: e[worst],
                worst: (data[worst].m, data[worst].l, data[worst].d),
            }
        })
        .collect();
    let best = scores.iter().map(|s| s.rms).fold(f64::INFINITY, f64::min);
    let chosen = scores.iter().find(|s| s.rms <= RMS_SLACK * best)?.clone();
    let cases = data
        .iter()
        .zip(&errors[chosen.terms])
        .map(|(s, &error)| CaseError {
            m: s.m,
            l: s.l,
            d: s.d,
            error,
        })
        .collect();
    Some(HeldOut {
        folds: FOLDS,
        sizes: scores,
        chosen,
        cases,
    })
}
