//! The corner of the central film: where the film at X = 0 meets the film at the pressure
//! maximum, for line and point contacts alike.
//!
//! At high L the line H_c rises ever faster with M until it meets H_pm (near M = 1.8 at L >= 8)
//! and follows it from there (H_c / H_pm within 1.000-1.02); the point H_c does the same (H_c /
//! H_pm 0.79-0.81 one M step before, 1 after: M about 4-7 at D = 1 up to 20-50 at D = 0.1): a
//! corner between two smooth branches that no smooth correction follows (docs/validation.md).
//! The law of H_c is therefore, on its own blend B (the smooth H_c law's),
//!
//! H_c = R exp(-delta),  R = B exp(rho r(z) + C_R),  delta = rho (max(0, h) / rho)^k,
//! h = rho r(z) + C_h,
//!
//! with z the coordinates of B's asymptotes ([`crate::fit::correction`]), r(z) = (1 - w) / (1 +
//! e^a) + w / (1 + e^-b) the blend's rigidity (1 in both rigid limits, 0 in both elastic ones),
//! rho = ln(H_RI,pm / H_RI,c) at D = 1 (the rigid films' ratio: ln(3/2.4475) for the line,
//! ln(45.0/35.5) for the circular point), C_R and C_h interior corrections (lattice bumps in z,
//! for point contacts also times powers of ln D: [`CornerParams`]) and k = [`DEFICIT_POWER`].
//! R is the branch that follows H_pm, exp(-delta) the deficit of the branch that rises to it, and
//! the corner is where h crosses 0; with k < 1 the deficit closes faster than linearly there, as
//! the data do (H_c rises ever faster until it meets H_pm).
//!
//! Invariants: H_c <= R everywhere. Each asymptote of H_c is B's, exactly, whatever rho: the
//! bumps vanish in every limit, so in the rigid ones (r -> 1) h -> rho, delta -> rho and H_c ->
//! B e^rho e^-rho, and in the elastic ones (r -> 0) H_c -> B.
//!
//! Fit ([`fit_corner`]): the cases are split by the data into those where H_c follows H_pm
//! (H_c at least [`FOLLOWS`] H_pm) and the rest. C_R fits ln(H_c / B) - rho r on the first, and
//! on the rest is only held from below the data (R at least H_c; a one-sided row is added while
//! it is violated, [`one_sided`]); C_h then fits h to rho (y / rho)^(1/k), y = max(0, ln(R /
//! H_c)), on the rest and is held from above by it on the first (h at most 0 where R is at least
//! H_c there). Both are ridge least squares ([`solve_ridge`]); the ridge weights are chosen by
//! held-out error ([`select_corner`]).

use crate::fit::blend::Blend;
use crate::fit::correction::{lattice_terms_in_d, solve_ridge, Coordinates, Correction, Term};
use crate::fit::heldout::{worst_and_rms, RMS_SLACK};
use crate::fit::support::Support;
use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// H_c follows H_pm at a case where H_c >= FOLLOWS H_pm (the data's H_pm): past the corner the
/// line ratio is 1.000-1.019, before it 0.82-0.96 in the data.
pub const FOLLOWS: f64 = 0.995;

/// The power k of the deficit (module doc): chosen by held-out error on the committed line data
/// and by the error on a dense band of cases around the corner (docs/validation.md; k = 1: the
/// hinge itself, 0.5 follows the smooth part worse).
pub const DEFICIT_POWER: f64 = 0.75;

/// The lattice and ridge weights of a contact's corner law.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CornerParams {
    /// The lattice level of both corrections (spacing [`crate::fit::correction::LATTICE`] /
    /// 2^level).
    pub level: u8,
    /// Each lattice bump is also taken times (ln D)^n for n = 1 ..= this (0: a line contact).
    pub ln_d_powers: u8,
    /// The ridge weights (R, h) tried, in this order: the first whose held-out RMS is within
    /// [`RMS_SLACK`] of the best is kept.
    pub ridges: &'static [[f64; 2]],
    /// Whether the cases whose H_pm is not resolved are judged (do they follow H_pm?) by the
    /// H_pm law with its correction (true) or by its bare blend. The line's such rows are Barus
    /// spike rows, where the correction, fitted without them, extrapolates (held out H_c 0.63 %
    /// with the blend, 2.90 % with the law on the committed line data); the point default
    /// judges by the bare H_pm blend (its EI law held at the limit times the approach factor:
    /// H_c held out 4.09 % / 0.55 % on `tests/data/fit-point-05`, 3.73 % / 0.69 % by the law),
    /// `ehlmap fit --point-ei-limit`, whose H_c law is held too, by the law (docs/validation.md,
    /// "The approach to the point elastic-isoviscous limit").
    pub pm_corrected: bool,
    /// Whether both corrections fade beyond the range of a that their cases span at each D
    /// ([`crate::fit::support`]), so that beyond the data the law is its blend (the point
    /// recipe's flag, set by [`crate::report`]; false in [`LINE`] and [`POINT`]).
    pub fade: bool,
}

/// The line corner law: level 1 (the corner is sharp in M), ridges chosen on the committed line
/// data (docs/validation.md).
pub const LINE: CornerParams = CornerParams {
    level: 1,
    ln_d_powers: 0,
    ridges: &[
        [1e-3, 1e-5],
        [3e-4, 1e-5],
        [1e-4, 1e-5],
        [1e-3, 3e-5],
        [3e-4, 3e-5],
        [1e-4, 3e-5],
    ],
    pm_corrected: false,
    fade: false,
};

/// The point corner law: level 0 bumps times 1, ln D and (ln D)^2 (the corner moves with D),
/// ridges chosen on the point fit data (docs/validation.md).
pub const POINT: CornerParams = CornerParams {
    level: 0,
    ln_d_powers: 2,
    ridges: &[[1e-2, 1e-3], [1e-3, 1e-4], [1e-2, 1e-4], [1e-1, 1e-3]],
    pm_corrected: false,
    fade: false,
};

/// The H_c law with its corner (module doc), on the H_c blend B that the fitted formula carries
/// ([`crate::fit::fitted::FittedModel`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Corner {
    /// C_R, R's interior correction.
    pub branch: Correction,
    /// C_h, the deficit's interior part.
    pub deficit: Correction,
    /// rho = ln(H_RI,pm / H_RI,c) at D = 1 (> 0).
    pub rho: f64,
}

/// The rigidity r(z) = (1 - w)/(1 + e^a) + w/(1 + e^-b) of a blend at coordinates z.
pub fn rigidity(z: &Coordinates) -> f64 {
    let logistic = |t: f64| {
        if t >= 0.0 {
            1.0 / (1.0 + (-t).exp())
        } else {
            let e = t.exp();
            e / (1.0 + e)
        }
    };
    let iso = logistic(-z.a);
    if z.w > 0.0 && z.b.is_finite() {
        (1.0 - z.w) * iso + z.w * logistic(z.b)
    } else {
        iso
    }
}

/// rho = ln(H_RI,pm / H_RI,c) at (M, L, D) = (1, 0, 1) of the H_pm blend `pm` and the H_c blend
/// `own`: None unless finite and positive.
pub fn rigid_ratio(pm: &Blend, own: &Blend) -> Option<f64> {
    let rho = (pm.asymptotes(1.0, 0.0, 1.0)[0] / own.asymptotes(1.0, 0.0, 1.0)[0]).ln();
    (rho.is_finite() && rho > 0.0).then_some(rho)
}

impl Corner {
    /// The logarithms (ln(R / B), h) at coordinates z.
    fn parts(&self, z: &Coordinates) -> (f64, f64) {
        let rigid = self.rho * rigidity(z);
        (
            rigid + self.branch.log_factor_at(z),
            rigid + self.deficit.log_factor_at(z),
        )
    }

    /// The deficit delta = rho (max(0, h) / rho)^k of h.
    fn delta(&self, h: f64) -> f64 {
        self.rho * (h.max(0.0) / self.rho).powf(DEFICIT_POWER)
    }

    /// (R, H_c) for the blend's film `blend` and asymptotes `asym` at D = `d`.
    pub fn branches(&self, blend: f64, asym: [f64; 4], d: f64) -> (f64, f64) {
        let (ln_r, h) = self.parts(&Coordinates::new(asym, d));
        let right = blend * ln_r.exp();
        (right, right * (-self.delta(h)).exp())
    }

    /// H_c = R exp(-delta) for the blend's film `blend` and asymptotes `asym` at D = `d`.
    pub fn apply(&self, blend: f64, asym: [f64; 4], d: f64) -> f64 {
        self.branches(blend, asym, d).1
    }

    /// h (before the hinge) at the blend's asymptotes `asym` and D = `d`.
    pub fn h(&self, asym: [f64; 4], d: f64) -> f64 {
        self.parts(&Coordinates::new(asym, d)).1
    }
}

/// One case of the corner fit: M, L, D, the data's H_c and whether H_c follows H_pm there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CornerCase {
    /// Moes' M.
    pub m: f64,
    /// Moes' L.
    pub l: f64,
    /// D (1 for a line contact).
    pub d: f64,
    /// The data's H_c.
    pub h: f64,
    /// H_c >= [`FOLLOWS`] H_pm at this case.
    pub follows: bool,
}

/// Rounds of [`one_sided`] at most (its active set only grows, so it ends in at most as many
/// rounds as cases; in practice 2-8).
const ROUNDS: usize = 100;

/// The coefficients c of min |Phi_A c - y_A|^2 + ridge |c|^2 over the rows A: the `own` rows,
/// and each other row once the fit violates its bound there (`floor`: Phi c >= y; else
/// Phi c <= y), with A. A row once added stays (the set grows, so the iteration ends); every
/// row outside A holds its bound. None when a solve fails or a coefficient is not finite.
pub fn one_sided(
    phi: &DMatrix<f64>,
    y: &[f64],
    own: &[bool],
    ridge: f64,
    floor: bool,
) -> Option<(Vec<f64>, Vec<bool>)> {
    let mut active = own.to_vec();
    for _ in 0..ROUNDS {
        let rows: Vec<usize> = (0..y.len()).filter(|&i| active[i]).collect();
        let sub = phi.select_rows(&rows);
        let rhs = DVector::from_iterator(rows.len(), rows.iter().map(|&i| y[i]));
        let c = solve_ridge(&sub, &rhs, ridge)?;
        if !c.iter().all(|v| v.is_finite()) {
            return None;
        }
        let g = phi * &c;
        let mut grew = false;
        for i in 0..y.len() {
            let violated = if floor { g[i] < y[i] } else { g[i] > y[i] };
            if !active[i] && violated {
                active[i] = true;
                grew = true;
            }
        }
        if !grew {
            return Some((c.iter().copied().collect(), active));
        }
    }
    None
}

/// The corner law on the H_c blend `base` fitted to `cases` with the `terms` and the ridge
/// weights (R, h) (module doc), both corrections fading beyond the cases' range of a at each D
/// with `fade` ([`Support`]: 1 at every case, so the fit is the same). None when rho is not
/// positive, a class of cases is empty or a solve fails.
pub fn fit_corner(
    cases: &[CornerCase],
    base: &Blend,
    rho: f64,
    terms: &[Term],
    ridges: [f64; 2],
    fade: bool,
) -> Option<Corner> {
    let follows: Vec<bool> = cases.iter().map(|c| c.follows).collect();
    if follows.iter().all(|&f| f) || !follows.iter().any(|&f| f) || rho.is_nan() || rho <= 0.0 {
        return None;
    }
    let z: Vec<Coordinates> = cases
        .iter()
        .map(|c| Coordinates::new(base.asymptotes(c.m, c.l, c.d), c.d))
        .collect();
    let phi = DMatrix::from_fn(z.len(), terms.len(), |i, k| terms[k].eval(&z[i]));
    // ln(H_c / B) - rho r: C_R's target where H_c follows H_pm, its floor elsewhere.
    let y: Vec<f64> = cases
        .iter()
        .zip(&z)
        .map(|(c, zi)| (c.h / base.eval(c.m, c.l, c.d)).ln() - rho * rigidity(zi))
        .collect();
    let (coef, _) = one_sided(&phi, &y, &follows, ridges[0], true)?;
    // ln(R / H_c) = C_R - y at each case.
    let c_r = &phi * DVector::from_column_slice(&coef);
    let support = fade
        .then(|| Support::of(z.iter().map(|z| (z.ln_d, z.a))))
        .flatten();
    let branch = Correction {
        terms: terms.to_vec(),
        coef,
        support: support.clone(),
    };
    let y: Vec<f64> = (0..cases.len())
        .map(|i| {
            let gap = (c_r[i] - y[i]).max(0.0);
            rho * (gap / rho).powf(1.0 / DEFICIT_POWER) - rho * rigidity(&z[i])
        })
        .collect();
    let rest: Vec<bool> = follows.iter().map(|f| !f).collect();
    let (coef, _) = one_sided(&phi, &y, &rest, ridges[1], false)?;
    Some(Corner {
        branch,
        deficit: Correction {
            terms: terms.to_vec(),
            coef,
            support,
        },
        rho,
    })
}

/// The held-out choice of the corner law's ridge weights.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CornerChoice {
    /// The ridge weights (R, h) kept: the first of the contact's [`CornerParams::ridges`] whose
    /// held-out RMS is within [`RMS_SLACK`] of the best.
    pub ridges: [f64; 2],
    /// Each candidate tried: its ridges, held-out RMS and largest |error| (sign kept).
    pub tried: Vec<([f64; 2], f64, f64)>,
    /// Lattice terms of each correction.
    pub terms: usize,
    /// The lattice spacing W of the bumps.
    #[serde(default)]
    pub width: f64,
    /// The highest power of ln D the bumps are taken times (0: none).
    #[serde(default)]
    pub ln_d_powers: u8,
    /// The cases following H_pm, of all.
    pub follows: [usize; 2],
}

/// Cross-validate the ridges of `params` on `cases` (fold of case i: `fold[i]`, the H_c blend of
/// fold f: `bases[f]`, fitted without it) and fit the ridges kept on all cases on the H_c blend
/// `base`. The terms are those of `base`'s coordinates over all cases ([`lattice_terms_in_d`]).
/// Returns the law, the choice and each case's held-out relative error formula / data - 1 with
/// the ridges kept (in the cases' order). None when a candidate cannot be fitted on every fold
/// or the final fit fails.
pub fn select_corner(
    cases: &[CornerCase],
    fold: &[usize],
    bases: &[Blend],
    base: &Blend,
    rho: f64,
    params: &CornerParams,
) -> Option<CornerSelection> {
    let z: Vec<Coordinates> = cases
        .iter()
        .map(|c| Coordinates::new(base.asymptotes(c.m, c.l, c.d), c.d))
        .collect();
    let terms = lattice_terms_in_d(&z, params.level, params.ln_d_powers);
    let mut scored = vec![];
    for &ridges in params.ridges {
        let mut e = vec![f64::NAN; cases.len()];
        // The folds in parallel, collected in fold order: the same at any thread count.
        let laws: Vec<Corner> = bases
            .par_iter()
            .enumerate()
            .map(|(f, b)| {
                let train: Vec<CornerCase> = (0..cases.len())
                    .filter(|&i| fold[i] != f)
                    .map(|i| cases[i])
                    .collect();
                fit_corner(&train, b, rho, &terms, ridges, params.fade)
            })
            .collect::<Option<_>>()?;
        for (f, (b, law)) in bases.iter().zip(&laws).enumerate() {
            for i in (0..cases.len()).filter(|&i| fold[i] == f) {
                let c = &cases[i];
                let h = law.apply(b.eval(c.m, c.l, c.d), b.asymptotes(c.m, c.l, c.d), c.d);
                e[i] = h / c.h - 1.0;
            }
        }
        if !e.iter().all(|v| v.is_finite()) {
            return None;
        }
        let (worst, rms) = worst_and_rms(&e);
        scored.push((ridges, rms, e[worst], e, laws));
    }
    let best = scored.iter().map(|s| s.1).fold(f64::INFINITY, f64::min);
    let kept = scored.iter().position(|s| s.1 <= RMS_SLACK * best)?;
    let ridges = scored[kept].0;
    let law = fit_corner(cases, base, rho, &terms, ridges, params.fade)?;
    let n_follow = cases.iter().filter(|c| c.follows).count();
    let choice = CornerChoice {
        ridges,
        tried: scored.iter().map(|s| (s.0, s.1, s.2)).collect(),
        terms: terms.len(),
        width: terms.first().map_or(0.0, Term::width),
        ln_d_powers: params.ln_d_powers,
        follows: [n_follow, cases.len()],
    };
    let (_, _, _, errors, folds) = scored.swap_remove(kept);
    Some(CornerSelection {
        law,
        choice,
        errors,
        folds,
    })
}

/// What [`select_corner`] returns: the law fitted on all cases with the ridges kept, the choice,
/// each case's held-out error (formula / data - 1) and the law fitted without each fold (in fold
/// order, on that fold's blend).
pub struct CornerSelection {
    /// The law on all cases.
    pub law: Corner,
    /// How it was chosen.
    pub choice: CornerChoice,
    /// Held-out errors, in the cases' order.
    pub errors: Vec<f64>,
    /// The law fitted without each fold.
    pub folds: Vec<Corner>,
}

#[cfg(test)]
mod tests;
