//! The side-lobe factor of the elliptic-contact minimum film.
//!
//! Where the exit constriction of a point contact closes faster at its sides than on the centre
//! line, the minimum film H_min sits in a side lobe, below the centre line's minimum H_min,cl;
//! elsewhere the two are the same film. The point formula for H_min is therefore the
//! centre-line law (the blend and its interior correction fitted to H_min,cl) times
//!
//! F = exp(-max(0, g)),  g = r(M) r_D(D) sum_k c_k t_M^i t_D^j t_L^n,  (i, j, n) = powers of
//! term k,
//!
//! with t_M, t_D, t_L the coordinates ln M, ln D and ln(1 + L) mapped linearly onto [-1, 1] over
//! the box of the data fitted and clamped to it, and the ramp r(M) = (ln M - ln M_0) /
//! (ln M_1 - ln M_0) clamped to [0, 1], M_1 the smallest M of a side-lobe case and M_0 the
//! largest M of the data below it (r = 1 when the smallest M of the data already has a side
//! lobe): no side lobe up to M_0, the polynomial alone from M_1 on. The ramp in D, r_D(D) =
//! (ln D - ln D_0) / (ln D_1 - ln D_0) clamped to [0, 1], is the same in D, with D_1 the
//! smallest D of a lobe deeper than [`LOBE_D`] and the box's t_D starting at D_0 (r_D = 1 when
//! no data lie below D_1): slender contacts have no side lobe. Invariants: F <= 1 everywhere (the side lobe never
//! lifts the minimum above the centre line's); F = 1 exactly wherever g <= 0 (no side lobe),
//! in particular at every M <= M_0 and every D <= D_0, so the rigid limit is the centre line's; and beyond the
//! data's box F is its value at the nearest point of the box (each asymptote of H_min is the
//! centre-line asymptote times a constant factor).
//!
//! The coefficients minimise |Phi c - y|^2 + lambda |c|^2 over the hinge: y = ln(H_min,cl /
//! H_min) >= 0 at every case where the minimum is in a side lobe, and at a case without one
//! (y = 0) only while the fitted g is positive there (an active-set iteration from the side-lobe
//! cases; [`fit_side`]). Which powers and ridge weight are kept is chosen by held-out error
//! ([`select_side`]).

use crate::fit::heldout::{worst_and_rms, RMS_SLACK};
use crate::fit::kriging::{self, Fold, Kriging};
use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

/// One case of the side-lobe fit: M, L, D and y = ln(H_min,cl / H_min) (>= 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SideCase {
    /// Moes' M.
    pub m: f64,
    /// Moes' L.
    pub l: f64,
    /// D = Rx/Ry.
    pub d: f64,
    /// ln(H_min,cl / H_min): 0 where the minimum is on the centre line.
    pub y: f64,
}

/// The fitted side-lobe factor (module doc).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SideLobe {
    /// The box of the data in (ln M, ln D, ln(1 + L)): lower corner.
    pub lo: [f64; 3],
    /// Upper corner.
    pub hi: [f64; 3],
    /// The powers (i, j, n) of t_M, t_D, t_L of each term.
    pub powers: Vec<[u8; 3]>,
    /// The coefficient of each term.
    pub coef: Vec<f64>,
    /// ln M_0 and ln M_1 of the ramp (None: no ramp, r = 1).
    #[serde(default)]
    pub ramp: Option<[f64; 2]>,
    /// ln D_0 and ln D_1 of the ramp in D (None: no ramp, r_D = 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ramp_d: Option<[f64; 2]>,
    /// A kriging residual k in the box-clamped (ln M, ln(1 + L), ln D) (None: none): F =
    /// exp(-max(0, max(0, g) - r(M) r_D(D) k)).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kriging: Option<Kriging>,
}

/// A y below this counts as no side lobe (the centre line's minimum and the global one agree to
/// rounding).
pub const NO_LOBE: f64 = 1e-9;

/// A side lobe deeper than this (y, about the relative depth) places the ramp in D: lobes
/// shallower than the data's 0.5 % accuracy target are fitted but do not extend the factor to
/// slender contacts, which have none (the centre strip of a slender ellipse is a line contact).
pub const LOBE_D: f64 = 5e-3;

/// Rounds of the active-set iteration of [`fit_side`].
const ROUNDS: usize = 50;

fn raw(m: f64, l: f64, d: f64) -> [f64; 3] {
    [m.ln(), d.ln(), l.ln_1p()]
}

impl SideLobe {
    /// The coordinates (t_M, t_D, t_L) in [-1, 1] of (M, L, D), clamped to the box.
    pub fn coords(&self, m: f64, l: f64, d: f64) -> [f64; 3] {
        let x = raw(m, l, d);
        std::array::from_fn(|k| {
            let w = self.hi[k] - self.lo[k];
            if w > 0.0 {
                (2.0 * (x[k] - self.lo[k]) / w - 1.0).clamp(-1.0, 1.0)
            } else {
                0.0
            }
        })
    }

    /// The ramp r(M) (module doc).
    pub fn ramp(&self, m: f64) -> f64 {
        self.ramp
            .map_or(1.0, |[a, b]| ((m.ln() - a) / (b - a)).clamp(0.0, 1.0))
    }

    /// The ramp r_D(D) = (ln D - ln D_0) / (ln D_1 - ln D_0) clamped to [0, 1] (module doc).
    pub fn ramp_d(&self, d: f64) -> f64 {
        self.ramp_d
            .map_or(1.0, |[a, b]| ((d.ln() - a) / (b - a)).clamp(0.0, 1.0))
    }

    /// The weight r(M) r_D(D) of the polynomial and the kriging residual.
    pub fn weight(&self, m: f64, d: f64) -> f64 {
        self.ramp(m) * self.ramp_d(d)
    }

    /// g(M, L, D) before the hinge.
    pub fn g(&self, m: f64, l: f64, d: f64) -> f64 {
        let r = self.weight(m, d);
        if r == 0.0 {
            return 0.0;
        }
        let t = self.coords(m, l, d);
        r * self
            .powers
            .iter()
            .zip(&self.coef)
            .map(|(p, c)| c * monomial(t, *p))
            .sum::<f64>()
    }

    /// The kriging coordinates of (M, L, D): (ln M, ln(1 + L), ln D) clamped to the box.
    pub fn kriging_point(&self, m: f64, l: f64, d: f64) -> kriging::X {
        let x = raw(m, l, d);
        let at = |k: usize| x[k].clamp(self.lo[k], self.hi[k].max(self.lo[k]));
        [at(0), at(2), at(1), 0.0]
    }

    /// G = max(0, g) - r(M) k, the exponent before the outer hinge (k = 0 without a kriging
    /// residual).
    pub fn exponent(&self, m: f64, l: f64, d: f64) -> f64 {
        let g = self.g(m, l, d).max(0.0);
        match &self.kriging {
            Some(k) => {
                let r = self.weight(m, d);
                if r == 0.0 {
                    g
                } else {
                    g - r * k.at(&self.kriging_point(m, l, d))
                }
            }
            None => g,
        }
    }

    /// The factor F = exp(-max(0, G)) in (0, 1] (G = [`SideLobe::exponent`]).
    pub fn factor(&self, m: f64, l: f64, d: f64) -> f64 {
        (-self.exponent(m, l, d).max(0.0)).exp()
    }
}

fn monomial(t: [f64; 3], p: [u8; 3]) -> f64 {
    t.iter().zip(p).map(|(v, k)| v.powi(i32::from(k))).product()
}

/// The tensor powers (i, j, n) with i <= `deg[0]`, j <= `deg[1]`, n <= `deg[2]`.
pub fn tensor_powers(deg: [u8; 3]) -> Vec<[u8; 3]> {
    let mut out = vec![];
    for i in 0..=deg[0] {
        for j in 0..=deg[1] {
            for n in 0..=deg[2] {
                out.push([i, j, n]);
            }
        }
    }
    out
}

/// The box of `cases` in (ln M, ln D, ln(1 + L)).
pub fn data_box(cases: &[SideCase]) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for c in cases {
        let x = raw(c.m, c.l, c.d);
        for k in 0..3 {
            lo[k] = lo[k].min(x[k]);
            hi[k] = hi[k].max(x[k]);
        }
    }
    (lo, hi)
}

/// A ramp over `cases` in the coordinate `x` (ln M or ln D; module doc): [x_0, x_1], x_1 the
/// smallest x of a case whose side lobe is deeper than `depth` and x_0 the largest x of the
/// data below it; None where no lobe is that deep or no case lies below x_1.
fn ramp_of(cases: &[SideCase], x: impl Fn(&SideCase) -> f64, depth: f64) -> Option<[f64; 2]> {
    let x1 = cases
        .iter()
        .filter(|c| c.y > depth)
        .map(&x)
        .fold(f64::INFINITY, f64::min);
    if !x1.is_finite() {
        return None;
    }
    cases
        .iter()
        .map(&x)
        .filter(|&v| v < x1)
        .fold(None, |a: Option<f64>, v| Some(a.map_or(v, |a| a.max(v))))
        .map(|x0| [x0, x1])
}

/// The hinge fit of `powers` with ridge weight `ridge` to `cases` (module doc): least squares
/// over the side-lobe cases (y > [`NO_LOBE`]) and the cases without one where g > 0, iterated
/// until that set stops changing. None without a side-lobe case or when a solve fails.
pub fn fit_side(cases: &[SideCase], powers: &[[u8; 3]], ridge: f64) -> Option<SideLobe> {
    let (mut lo, hi) = data_box(cases);
    let ramp = ramp_of(cases, |c| c.m.ln(), NO_LOBE);
    let ramp_d = ramp_of(cases, |c| c.d.ln(), LOBE_D);
    if let Some([d0, _]) = ramp_d {
        lo[1] = d0;
    }
    let mut side = SideLobe {
        lo,
        hi,
        powers: powers.to_vec(),
        coef: vec![0.0; powers.len()],
        ramp,
        ramp_d,
        kriging: None,
    };
    let phi: Vec<Vec<f64>> = cases
        .iter()
        .map(|c| {
            let t = side.coords(c.m, c.l, c.d);
            let r = side.weight(c.m, c.d);
            powers.iter().map(|p| r * monomial(t, *p)).collect()
        })
        .collect();
    let mut active: Vec<bool> = cases.iter().map(|c| c.y > NO_LOBE).collect();
    if !active.iter().any(|a| *a) {
        return None;
    }
    for _ in 0..ROUNDS {
        let rows: Vec<usize> = (0..cases.len()).filter(|&i| active[i]).collect();
        let n = powers.len();
        let a = DMatrix::from_fn(rows.len(), n, |r, k| phi[rows[r]][k]);
        let b = DVector::from_iterator(rows.len(), rows.iter().map(|&i| cases[i].y.max(0.0)));
        let normal = a.tr_mul(&a) + DMatrix::<f64>::identity(n, n) * ridge;
        let c = normal.cholesky()?.solve(&a.tr_mul(&b));
        if !c.iter().all(|v| v.is_finite()) {
            return None;
        }
        side.coef = c.iter().copied().collect();
        let next: Vec<bool> = (0..cases.len())
            .map(|i| {
                cases[i].y > NO_LOBE
                    || phi[i]
                        .iter()
                        .zip(&side.coef)
                        .map(|(p, c)| p * c)
                        .sum::<f64>()
                        > 0.0
            })
            .collect();
        if next == active {
            break;
        }
        active = next;
    }
    Some(side)
}

/// A candidate of [`select_side`]: tensor degrees in (t_M, t_D, t_L) and the ridge weight.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SideCandidate {
    /// Largest power of t_M, t_D and t_L.
    pub degrees: [u8; 3],
    /// The ridge weight lambda.
    pub ridge: f64,
}

/// The ridge weights of the candidates (the coefficients of a polynomial on [-1, 1]^3 are
/// O(0.1 ... 1); the largest keeps the hinge's extrapolation into the cases without a side lobe
/// tame).
pub const SIDE_RIDGES: [f64; 4] = [1e-6, 1e-4, 1e-3, 1e-2];

/// The candidates tried, simplest first: tensor degrees up to (3, 3, 4) (the point data have
/// 4 D values and 7 L values), each with every ridge of [`SIDE_RIDGES`].
pub fn side_candidates() -> Vec<SideCandidate> {
    let mut out = vec![];
    for degrees in [
        [1, 1, 1],
        [1, 2, 2],
        [2, 2, 2],
        [2, 2, 3],
        [2, 3, 3],
        [3, 3, 3],
        [2, 3, 4],
        [3, 3, 4],
    ] {
        for ridge in SIDE_RIDGES {
            out.push(SideCandidate { degrees, ridge });
        }
    }
    out
}

/// The held-out choice of the side-lobe factor.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SideChoice {
    /// The candidate kept: the first whose held-out RMS log error is within
    /// [`crate::fit::heldout::RMS_SLACK`] of the best.
    pub chosen: SideCandidate,
    /// Its held-out RMS of ln F - ln(H_min / H_min,cl).
    pub rms: f64,
    /// Its largest |held-out log error|, sign kept.
    pub max: f64,
    /// Each case's held-out G (the fold's fit, before the outer hinge: [`SideLobe::exponent`]),
    /// in the cases' order.
    pub heldout_g: Vec<f64>,
    /// With a kriging residual: its held-out RMS and max |log error| without it (None: none kept).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub without: Option<[f64; 2]>,
}

/// Cross-validate [`side_candidates`] on `cases` with the fold of each case given (`fold[i]` in
/// 0..`folds`), keep the first within [`crate::fit::heldout::RMS_SLACK`] of the best held-out
/// RMS and fit it on all cases. None when no candidate can be fitted on every fold.
pub fn select_side(
    cases: &[SideCase],
    fold: &[usize],
    folds: usize,
) -> Option<(SideLobe, SideChoice)> {
    // Each candidate's held-out scores (log errors y - max(0, g)), with its fit on each fold's
    // training cases.
    let scored: Vec<(SideChoice, Vec<SideLobe>)> = side_candidates()
        .into_iter()
        .filter_map(|cand| {
            let powers = tensor_powers(cand.degrees);
            if powers.len() + 5 > cases.len() {
                return None;
            }
            let mut g = vec![f64::NAN; cases.len()];
            let mut fits = Vec::with_capacity(folds);
            for f in 0..folds {
                let train: Vec<SideCase> = (0..cases.len())
                    .filter(|&i| fold[i] != f)
                    .map(|i| cases[i])
                    .collect();
                let s = fit_side(&train, &powers, cand.ridge)?;
                for i in (0..cases.len()).filter(|&i| fold[i] == f) {
                    g[i] = s.g(cases[i].m, cases[i].l, cases[i].d);
                }
                fits.push(s);
            }
            if !g.iter().all(|v| v.is_finite()) {
                return None;
            }
            let e: Vec<f64> = g.iter().zip(cases).map(|(g, c)| c.y - g.max(0.0)).collect();
            let (worst, rms) = worst_and_rms(&e);
            let choice = SideChoice {
                chosen: cand,
                rms,
                max: e[worst],
                heldout_g: g,
                without: None,
            };
            Some((choice, fits))
        })
        .collect();
    let best = scored.iter().map(|s| s.0.rms).fold(f64::INFINITY, f64::min);
    let (choice, fits) = scored.into_iter().find(|s| s.0.rms <= RMS_SLACK * best)?;
    let c = choice.chosen;
    let side = fit_side(cases, &tensor_powers(c.degrees), c.ridge)?;
    Some(kriged_side(cases, fold, &fits, side.clone(), choice.clone()).unwrap_or((side, choice)))
}

/// The log residual ln(H_min / (H_min,cl e^-max(0, g))) = max(0, g) - y of `c` under `s`.
fn side_residual(s: &SideLobe, c: &SideCase) -> f64 {
    s.g(c.m, c.l, c.d).max(0.0) - c.y
}

/// The side factor `side` (chosen as `choice`, fitted without each fold as `fits`) with a
/// kriging residual of its log residuals over the cases with a side-lobe ramp (M >= M_1),
/// cross-validated on the same folds; None when a fit fails or it does not lower the held-out
/// RMS or raises the max.
fn kriged_side(
    cases: &[SideCase],
    fold: &[usize],
    fits: &[SideLobe],
    mut side: SideLobe,
    choice: SideChoice,
) -> Option<(SideLobe, SideChoice)> {
    let kfolds: Vec<Fold> = fits
        .iter()
        .enumerate()
        .map(|(f, s)| {
            let mut out = Fold {
                train: vec![],
                test: vec![],
            };
            for (i, c) in cases.iter().enumerate() {
                if s.weight(c.m, c.d) == 0.0 {
                    continue;
                }
                let x = side.kriging_point(c.m, c.l, c.d);
                let r = side_residual(s, c);
                if fold[i] == f {
                    out.test.push((i, x, r));
                } else {
                    out.train.push((x, r));
                }
            }
            out
        })
        .collect();
    if kfolds.iter().any(|f| f.train.is_empty()) {
        return None;
    }
    // Relative errors exp(k - r) - 1 against log errors |y - G| of the choice: the bound is
    // checked again on the log errors below.
    let kriging::Selection {
        scales, nugget, k, ..
    } = kriging::select(&kfolds, cases.len(), choice.max.abs().exp_m1(), false)?;
    // Each case's held-out G: the fold's max(0, g) less its kriging (0 without a ramp).
    let g: Vec<f64> = (0..cases.len())
        .map(|i| {
            let (s, c) = (&fits[fold[i]], &cases[i]);
            let k = if k[i].is_nan() { 0.0 } else { k[i] };
            s.g(c.m, c.l, c.d).max(0.0) - s.weight(c.m, c.d) * k
        })
        .collect();
    let e: Vec<f64> = g.iter().zip(cases).map(|(g, c)| c.y - g.max(0.0)).collect();
    if !e.iter().all(|v| v.is_finite()) {
        return None;
    }
    let (worst, rms) = worst_and_rms(&e);
    if rms >= choice.rms || e[worst].abs() > choice.max.abs() {
        return None;
    }
    let (x, r): (Vec<kriging::X>, Vec<f64>) = cases
        .iter()
        .filter(|c| side.weight(c.m, c.d) > 0.0)
        .map(|c| (side.kriging_point(c.m, c.l, c.d), side_residual(&side, c)))
        .unzip();
    side.kriging = Some(kriging::fit(&x, &r, scales, nugget, 0.0, None)?);
    Some((
        side,
        SideChoice {
            rms,
            max: e[worst],
            heldout_g: g,
            without: Some([choice.rms, choice.max.abs()]),
            ..choice
        },
    ))
}

#[cfg(test)]
mod tests;
