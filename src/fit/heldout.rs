//! Held-out errors of a fitted formula, and the size of its interior correction chosen by them.
//!
//! K-fold cross-validation ([`FOLDS`] folds): the cases are ranked by (M, L, D) and case k goes to
//! fold k mod K, so every fold spans the whole map. For each fold the blend is refitted on the
//! other folds (the caller's `fit_blend`), then each candidate correction ([`Basis`]: the first n
//! terms of a nested list, [`nested`], or a lattice fitted with a ridge weight;
//! [`crate::fit::correction`]) alone on that blend (cheap); the blend alone and the
//! [`JOINT_CANDIDATES`] best candidates are then cross-validated again with blend and correction
//! fitted together ([`joint`]: what the final formula is). The fold's cases are predicted by each
//! formula: each case is predicted exactly once per candidate, by a formula that never saw it. The
//! candidate kept is the first joint one (in the caller's order, simplest first) whose held-out
//! RMS relative error is within [`RMS_SLACK`] of the best. Inputs: the samples (M, L, D, H), the
//! candidates and how the blend is refitted ([`Refit`]); output: [`HeldOut`] (per candidate: RMS,
//! max; the one kept; each case's held-out error with it).

use crate::fit::correction::{fit_correction, lattice_terms_in_d, Coordinates, Correction, Term};
use crate::fit::lsq::{fit, Sample};
use crate::fit::model::FilmModel;
use crate::fit::support::Support;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// Number of cross-validation folds.
pub const FOLDS: usize = 5;

/// A size within this factor of the best held-out RMS counts as good as the best.
pub const RMS_SLACK: f64 = 1.02;

/// Sizes cross-validated with the joint fit (besides the blend alone): the best by the cheap
/// cross-validation of the correction alone.
pub const JOINT_CANDIDATES: usize = 4;

/// Each fold's training set must have this many more cases than the correction has terms.
const SPARE: usize = 10;

/// One candidate correction: its terms and the ridge weight lambda of their fit (min |Phi c -
/// r|^2 + lambda |c|^2; 0: plain least squares).
#[derive(Clone, Debug, PartialEq)]
pub struct Basis {
    /// The basis functions.
    pub terms: Vec<Term>,
    /// The ridge weight.
    pub ridge: f64,
    /// Whether the fitted correction fades beyond its cases' range of a at each D
    /// ([`crate::fit::support`]; the point lattice candidates).
    pub fade: bool,
}

/// The candidates of a nested term list: its first n terms for n = 0 ..= len, no ridge.
pub fn nested(terms: &[Term]) -> Vec<Basis> {
    (0..=terms.len())
        .map(|n| Basis {
            terms: terms[..n].to_vec(),
            ridge: 0.0,
            fade: false,
        })
        .collect()
}

/// Fewest cases for which [`lattice`] offers candidates: with fewer, some hundred lattice terms
/// against a few dozen cases are chosen by folds of a handful of cases each.
pub const LATTICE_MIN_CASES: usize = 100;

/// The lattice candidates of spacing [`crate::fit::correction::LATTICE`] / 2^`level` over data at
/// coordinates `z` ([`lattice_terms_in_d`]: each bump also times ln D, ..., (ln D)^`ln_d_powers`),
/// one per ridge weight; none below [`LATTICE_MIN_CASES`] cases.
pub fn lattice(z: &[Coordinates], level: u8, ridges: &[f64], ln_d_powers: u8) -> Vec<Basis> {
    if z.len() < LATTICE_MIN_CASES {
        return vec![];
    }
    let terms = lattice_terms_in_d(z, level, ln_d_powers);
    ridges
        .iter()
        .map(|&ridge| Basis {
            terms: terms.clone(),
            ridge,
            fade: false,
        })
        .collect()
}

/// Held-out errors of one candidate correction.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SizeScore {
    /// Number of correction terms (0: the blend alone).
    pub terms: usize,
    /// The candidate's ridge weight (0: plain least squares).
    #[serde(default)]
    pub ridge: f64,
    /// The candidate's index in the list given to [`select`].
    #[serde(default)]
    pub candidate: usize,
    /// The lattice level of a lattice candidate (spacing
    /// [`crate::fit::correction::LATTICE`] / 2^level; 0 for the nested terms and in reports
    /// written before levels existed).
    #[serde(default)]
    pub level: u8,
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
    /// The data's film at this case (None in fit reports before it was recorded).
    #[serde(default)]
    pub h: Option<f64>,
    /// formula / data - 1, the formula fitted without this case's fold.
    pub error: f64,
    /// The data's own relative error estimate of this film (None: not estimated); the caller
    /// fills it ([`HeldOut::with_estimates`]).
    #[serde(default)]
    pub estimate: Option<f64>,
}

/// The cross-validation of one film's formula.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct HeldOut {
    /// Folds used.
    pub folds: usize,
    /// Every candidate tried with the correction alone on each fold's blend, in the caller's
    /// order.
    pub sizes: Vec<SizeScore>,
    /// The candidates tried with the blend and the correction fitted together ([`joint`]): the
    /// blend alone and the [`JOINT_CANDIDATES`] best of `sizes`.
    #[serde(default)]
    pub joint: Vec<SizeScore>,
    /// The candidate kept (an entry of `joint`: its held-out errors are those of the formula as
    /// fitted).
    pub chosen: SizeScore,
    /// Each case's held-out error with the candidate kept, in the data's order (the validity
    /// map).
    #[serde(default)]
    pub cases: Vec<CaseError>,
}

impl HeldOut {
    /// These held-out errors with the chosen candidate's RMS, max and worst case taken again from
    /// the cases' errors (after a law on top of the candidate replaced them).
    pub fn rescored(mut self) -> Self {
        let e: Vec<f64> = self.cases.iter().map(|c| c.error).collect();
        let (worst, rms) = worst_and_rms(&e);
        let w = &self.cases[worst];
        self.chosen.rms = rms;
        self.chosen.max = e[worst];
        self.chosen.worst = (w.m, w.l, w.d);
        self
    }

    /// These held-out errors with each case's error replaced by `errors` (in the cases' order),
    /// [`HeldOut::rescored`].
    pub fn with_errors(mut self, errors: &[f64]) -> Self {
        for (c, e) in self.cases.iter_mut().zip(errors) {
            c.error = *e;
        }
        self.rescored()
    }

    /// These held-out errors with each case's data error estimate (`estimates` in the data's
    /// order, as the samples were given to [`select`]).
    pub fn with_estimates(mut self, estimates: &[Option<f64>]) -> Self {
        for (c, e) in self.cases.iter_mut().zip(estimates) {
            c.estimate = *e;
        }
        self
    }
}

/// A blend under a fixed correction, as the least-squares fit sees it: its parameters are the
/// blend's, its film the blend's times the correction.
#[derive(Clone)]
struct Corrected<'a, Mo> {
    blend: Mo,
    correction: &'a Correction,
}

impl<Mo: FilmModel> FilmModel for Corrected<'_, Mo> {
    fn x(&self) -> &[f64] {
        self.blend.x()
    }
    fn x_mut(&mut self) -> &mut [f64] {
        self.blend.x_mut()
    }
    fn film(&self, m: f64, l: f64, d: f64) -> f64 {
        let b = &self.blend;
        self.correction
            .apply(b.film(m, l, d), b.asymptotes(m, l, d), d)
    }
    fn asymptotes(&self, m: f64, l: f64, d: f64) -> [f64; 4] {
        self.blend.asymptotes(m, l, d)
    }
}

/// How the blend is refitted under its correction ([`joint`]).
pub struct Refit<'a, Mo> {
    /// The blend parameters freed.
    pub free: &'a [usize],
    /// Whether a refitted blend is physical (else the previous one is kept).
    pub physical: &'a (dyn Fn(&Mo) -> bool + Sync),
}

/// Rounds of the alternating fit in [`joint`].
pub const JOINT_ROUNDS: usize = 2;

/// The blend and the correction of `basis` fitted together to `data`, by alternating: the
/// correction on the blend's residuals (linear), then the blend's `refit.free` parameters under
/// that correction (Levenberg-Marquardt), [`JOINT_ROUNDS`] times; a blend step is kept only when
/// it is physical and lowers the RMS log error. Returns the blend, the correction and the
/// one-sigma uncertainties of the blend's parameters from the last blend step kept (None: no step
/// kept, or no correction terms). None when the first correction fails.
pub fn joint<Mo: FilmModel>(
    data: &[Sample],
    blend: &Mo,
    basis: &Basis,
    refit: &Refit<Mo>,
) -> Option<JointFit<Mo>> {
    let mut blend = blend.clone();
    let mut c = correction_for(&blend, data, basis)?;
    let mut sigma = None;
    if basis.terms.is_empty() {
        return Some((blend, c, sigma));
    }
    let rms = |b: &Mo, c: &Correction| rms_log(data, b, c);
    for _ in 0..JOINT_ROUNDS {
        let start = Corrected {
            blend: blend.clone(),
            correction: &c,
        };
        let before = rms(&blend, &c);
        if let Ok(f) = fit(data, &start, refit.free) {
            let b = f.model.blend;
            if (refit.physical)(&b) && f.rms_log.is_finite() && f.rms_log < before {
                blend = b;
                sigma = Some(f.sigma);
            }
        }
        match correction_for(&blend, data, basis) {
            Some(next) if rms(&blend, &next) <= rms(&blend, &c) => c = next,
            _ => {}
        }
    }
    Some((blend, c, sigma))
}

/// The RMS log error of `blend` times `correction` on `data`.
fn rms_log<Mo: FilmModel>(data: &[Sample], blend: &Mo, correction: &Correction) -> f64 {
    let f = Corrected {
        blend: blend.clone(),
        correction,
    };
    let ss: f64 = data
        .iter()
        .map(|s| (f.film(s.m, s.l, s.d) / s.h).ln().powi(2))
        .sum();
    (ss / data.len() as f64).sqrt()
}

/// A [`joint`] fit: the blend, the correction and the blend's one-sigma uncertainties.
pub type JointFit<Mo> = (Mo, Correction, Option<Vec<f64>>);

/// [`joint`] from each blend of `starts`, the fit with the lowest RMS log error on `data` kept
/// (the first on a tie); None when every start fails. The final fit of a film starts from the
/// blend fitted on all cases and from each fold's blend of [`select`]: a nonlinear fit on all
/// cases can settle where the folds' fits do better.
pub fn joint_best<Mo: FilmModel>(
    data: &[Sample],
    starts: &[&Mo],
    basis: &Basis,
    refit: &Refit<Mo>,
) -> Option<JointFit<Mo>> {
    let rms = |(b, c, _): &JointFit<Mo>| rms_log(data, b, c);
    // The starts in parallel, compared in their order: the same at any thread count.
    let fits: Vec<Option<JointFit<Mo>>> = starts
        .par_iter()
        .map(|&start| joint(data, start, basis, refit))
        .collect();
    let mut best: Option<(JointFit<Mo>, f64)> = None;
    for fit in fits.into_iter().flatten() {
        let r = rms(&fit);
        if r.is_finite() && best.as_ref().is_none_or(|(_, b)| r < *b) {
            best = Some((fit, r));
        }
    }
    best.map(|(fit, _)| fit)
}

fn coords<Mo: FilmModel>(model: &Mo, s: &Sample) -> Coordinates {
    Coordinates::new(model.asymptotes(s.m, s.l, s.d), s.d)
}

/// The correction of `basis` fitted to `data` on top of `blend`; None when the solve fails.
pub fn correction_for<Mo: FilmModel>(
    blend: &Mo,
    data: &[Sample],
    basis: &Basis,
) -> Option<Correction> {
    let z: Vec<_> = data.iter().map(|s| coords(blend, s)).collect();
    let r: Vec<_> = data
        .iter()
        .map(|s| s.h.ln() - blend.film(s.m, s.l, s.d).ln())
        .collect();
    let c = fit_correction(&z, &r, &basis.terms, basis.ridge)?;
    Some(Correction {
        support: if basis.fade {
            Support::of(z.iter().map(|z| (z.ln_d, z.a)))
        } else {
            None
        },
        ..c
    })
}

/// The fold of each sample (module doc): ranked by (M, L, D), the sample of rank k in fold
/// k mod [`FOLDS`].
pub fn folds_of(data: &[Sample]) -> Vec<usize> {
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
    fold
}

/// Cross-validate the `candidates` (those without a ridge only when the folds have [`SPARE`] more
/// cases than terms): the scores, and the blend fitted on each fold's training cases. None when
/// there are fewer than 2 [`FOLDS`] cases, a fold's blend fit fails or no candidate without
/// terms (the blend alone) is scored.
pub fn select<Mo: FilmModel>(
    data: &[Sample],
    candidates: &[Basis],
    fit_blend: &(dyn Fn(&[Sample]) -> Option<Mo> + Sync),
    refit: &Refit<Mo>,
) -> Option<Selected<Mo>> {
    if data.len() < 2 * FOLDS {
        return None;
    }
    let fold = folds_of(data);
    let smallest_train = (0..FOLDS)
        .map(|f| fold.iter().filter(|&&g| g != f).count())
        .min()?;
    let usable: Vec<usize> = (0..candidates.len())
        .filter(|&k| {
            candidates[k].ridge > 0.0 || candidates[k].terms.len() + SPARE <= smallest_train
        })
        .collect();
    let trains: Vec<Vec<Sample>> = (0..FOLDS)
        .map(|f| {
            (0..data.len())
                .filter(|&i| fold[i] != f)
                .map(|i| data[i])
                .collect()
        })
        .collect();
    // The folds are fitted in parallel, each on its own, and collected in fold order: the same
    // result at any thread count.
    let blends: Vec<Mo> = trains
        .par_iter()
        .map(|t| fit_blend(t))
        .collect::<Option<_>>()?;
    // The held-out relative error of each case with candidate k; `plain`: the correction alone
    // on each fold's blend, `joint`: blend and correction fitted together.
    type FoldFit<Mo> = Option<(Mo, Correction)>;
    let held_out = |k: usize, together: bool| -> (Vec<f64>, Vec<FoldFit<Mo>>) {
        let mut row = vec![f64::NAN; data.len()];
        let basis = &candidates[k];
        let fitted: Vec<_> = (0..FOLDS)
            .into_par_iter()
            .map(|f| {
                if together {
                    joint(&trains[f], &blends[f], basis, refit).map(|(b, c, _)| (b, c))
                } else {
                    correction_for(&blends[f], &trains[f], basis).map(|c| (blends[f].clone(), c))
                }
            })
            .collect();
        for (f, fitted) in fitted.iter().enumerate() {
            let Some((b, c)) = fitted else {
                continue;
            };
            let formula = Corrected {
                blend: b.clone(),
                correction: c,
            };
            for i in (0..data.len()).filter(|&i| fold[i] == f) {
                let s = &data[i];
                row[i] = formula.film(s.m, s.l, s.d) / s.h - 1.0;
            }
        }
        (row, fitted)
    };
    let scored = |k: usize, together: bool| {
        let (row, fits) = held_out(k, together);
        score(data, &candidates[k], k, row).map(|(s, e)| (s, e, fits))
    };
    let plain: Vec<(SizeScore, Vec<f64>)> = usable
        .iter()
        .filter_map(|&k| scored(k, false).map(|(s, e, _)| (s, e)))
        .collect();
    // The joint fit is costly (a Levenberg-Marquardt refit per fold and candidate): it is
    // cross-validated for the blend alone and the JOINT_CANDIDATES candidates best without it.
    let mut ranked: Vec<usize> = plain.iter().map(|(s, _)| s.candidate).collect();
    ranked.sort_by(|&i, &j| plain_rms(&plain, i).total_cmp(&plain_rms(&plain, j)));
    let mut chosen_k: Vec<usize> = ranked.into_iter().take(JOINT_CANDIDATES).collect();
    chosen_k.push(
        usable
            .iter()
            .copied()
            .find(|&k| candidates[k].terms.is_empty())?,
    );
    chosen_k.sort_unstable();
    chosen_k.dedup();
    let mut joint_scores: Vec<(SizeScore, Vec<f64>, Vec<FoldFit<Mo>>)> =
        chosen_k.iter().filter_map(|&k| scored(k, true)).collect();
    let best = joint_scores
        .iter()
        .map(|(s, _, _)| s.rms)
        .fold(f64::INFINITY, f64::min);
    let at = joint_scores
        .iter()
        .position(|(s, _, _)| s.rms <= RMS_SLACK * best)?;
    let joint: Vec<SizeScore> = joint_scores.iter().map(|(s, _, _)| s.clone()).collect();
    let (chosen, errors, fits) = joint_scores.swap_remove(at);
    let cases = data
        .iter()
        .zip(&errors)
        .map(|(s, &error)| CaseError {
            m: s.m,
            l: s.l,
            d: s.d,
            h: Some(s.h),
            error,
            estimate: None,
        })
        .collect();
    let h = HeldOut {
        folds: FOLDS,
        sizes: plain.into_iter().map(|(s, _)| s).collect(),
        joint,
        chosen,
        cases,
    };
    Some(Selected {
        heldout: h,
        blends,
        fits,
    })
}

/// What [`select`] returns: the held-out errors, the blend fitted on each fold's training cases,
/// and the candidate kept as fitted on each fold's training cases (blend and correction together;
/// None where that fit failed), in fold order.
pub struct Selected<Mo> {
    /// The cross-validation.
    pub heldout: HeldOut,
    /// Each fold's blend alone.
    pub blends: Vec<Mo>,
    /// Each fold's formula with the candidate kept.
    pub fits: Vec<Option<(Mo, Correction)>>,
}

/// The held-out RMS of candidate `k` among the `plain` scores.
fn plain_rms(plain: &[(SizeScore, Vec<f64>)], k: usize) -> f64 {
    plain
        .iter()
        .find(|(s, _)| s.candidate == k)
        .map_or(f64::INFINITY, |(s, _)| s.rms)
}

/// The index of the largest |error| and the RMS of non-empty relative errors `e`.
pub fn worst_and_rms(e: &[f64]) -> (usize, f64) {
    let worst = (0..e.len())
        .max_by(|&i, &j| e[i].abs().total_cmp(&e[j].abs()))
        .expect("non-empty");
    (
        worst,
        (e.iter().map(|v| v * v).sum::<f64>() / e.len() as f64).sqrt(),
    )
}

/// The score of candidate `k` (`basis`) from each case's held-out error (None when one is not
/// finite).
fn score(data: &[Sample], basis: &Basis, k: usize, e: Vec<f64>) -> Option<(SizeScore, Vec<f64>)> {
    if !e.iter().all(|v| v.is_finite()) {
        return None;
    }
    let (worst, rms) = worst_and_rms(&e);
    let s = SizeScore {
        terms: basis.terms.len(),
        ridge: basis.ridge,
        candidate: k,
        level: basis.terms.first().map_or(0, |t| t.level),
        rms,
        max: e[worst],
        worst: (data[worst].m, data[worst].l, data[worst].d),
    };
    Some((s, e))
}
