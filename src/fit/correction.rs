//! The interior correction of a blended film formula: H = H_blend exp(sum_k c_k phi_k), where
//! every basis function phi_k vanishes wherever one asymptote dominates, so the correction
//! changes the formula between its asymptotes and never in their limits.
//!
//! Coordinates, from the blend's four asymptotes [H_RI, H_EI, H_RP, H_EP] at (M, L, D):
//! a = ln(H_EI/H_RI) (rigid to elastic, isoviscous), b = ln(H_EP/H_RP) (rigid to elastic,
//! piezoviscous), c = ln(H_piezo/H_iso) with H_iso = (H_RI^4 + H_EI^4)^(1/4) and
//! H_piezo = (H_RP^-4 + H_EP^-4)^(-1/4) (isoviscous to piezoviscous; c = -infinity at L = 0),
//! w = 1/(1 + e^-c), and ln D (both brackets evaluated scaled by their larger / smaller term, so
//! that they stay finite far into the corners). The three transition bumps, each 1 at its centre
//! and decaying like e^-|t| away from it, and the elastic tail:
//!
//! Isoviscous: g(a) (1 - w); Piezoviscous: g(b) w; Outer: g(c); g(t) = 2/(1 + cosh t);
//! Tail: t(a) (1 - w), t(a) = e^(-a/TAIL) / (1 + e^-a) (0 in the rigid limit, decaying like
//! e^(-a/TAIL) into the elastic-isoviscous one, which the data approach slowly).
//!
//! Lattice bumps (where the data are dense enough to place them; point fits also take each one
//! times powers of ln D, [`lattice_terms_in_d`]): Shifted g(a/W - i) (1 - w) and Cell g(a/W - i) g(c/W - j) (0 at L = 0), centred
//! on the lattice (a, c) = (i W, j W), W = [`LATTICE`] / 2^level (level 0 or 1: a lattice of half
//! the spacing follows sharper features where the data are dense, such as the line H_c where the
//! pressure peak crosses X = 0); [`lattice_terms`] keeps those some data case sees. Each tends to 0 at every corner, since a or c goes to infinity there, and they are
//! fitted with a ridge penalty (lambda |c|^2, chosen by held-out error) instead of being tried in
//! order.
//!
//! A basis function is a bump times a monomial in (a, b, c, ln D, w) ([`Term`]); a polynomial
//! grows slower than the bump decays, so every phi_k tends to 0 at each of the four corners
//! (RI: a, c -> -infinity; EI: a -> infinity, c -> -infinity; RP: b, c -> infinity; EP:
//! b -> -infinity, c -> infinity: the piezoviscous bracket follows the smaller of H_RP and H_EP).
//! The approach is as slow as the crossovers of the blend itself (e^-|t| is a power of M or L),
//! slower for the tail. At L = 0 the piezoviscous and outer terms are exactly 0. The terms are
//! tried in the nested order of [`line_terms`] / [`point_terms`]; how many are kept is chosen by
//! held-out error ([`crate::fit::heldout`]). Given the blend, the coefficients solve a linear
//! least-squares problem in log space (SVD, [`fit_correction`]).

use crate::fit::support::Support;
use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

/// Which transition a basis function lives on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Transition {
    /// Rigid to elastic, isoviscous: g(a) (1 - w).
    Isoviscous,
    /// Rigid to elastic, piezoviscous: g(b) w.
    Piezoviscous,
    /// Isoviscous to piezoviscous: g(c).
    Outer,
    /// The slow approach to the elastic-isoviscous limit: t(a) (1 - w), t(a) = e^(-a/TAIL) /
    /// (1 + e^-a) (0 at the rigid corner, decaying like e^(-a/TAIL) into the elastic one).
    Tail,
    /// A lattice bump on the isoviscous transition: g(a/W - i) (1 - w), W = [`LATTICE`] /
    /// 2^level.
    Shifted,
    /// A lattice bump in the (a, c) plane: g(a/W - i) g(c/W - j) (0 at L = 0).
    Cell,
}

/// The spacing (and width) W of the level-0 lattice bumps in the coordinates a and c (level n:
/// W / 2^n).
pub const LATTICE: f64 = 0.75;

/// A lattice bump is kept when it reaches at least this value at some data case.
pub const LATTICE_REACH: f64 = 0.1;

/// The decay length of the [`Transition::Tail`] bump in a = ln(H_EI/H_RI).
pub const TAIL: f64 = 8.0;

fn tail(a: f64) -> f64 {
    if a < 0.0 {
        (a - a / TAIL).exp() / (a.exp() + 1.0)
    } else {
        (-a / TAIL).exp() / (1.0 + (-a).exp())
    }
}

/// One basis function: a transition bump times a^i b^j c^k (ln D)^l w^n, `powers` = [i, j, k, l,
/// n]. An isoviscous term uses no b or c (they are infinite at L = 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Term {
    /// The transition bump.
    pub transition: Transition,
    /// Powers of (a, b, c, ln D, w).
    pub powers: [u8; 5],
    /// The lattice centre (i, j) of a Shifted or Cell bump (unused by the other transitions).
    #[serde(default)]
    pub at: [i8; 2],
    /// The lattice level of a Shifted or Cell bump: spacing [`LATTICE`] / 2^level (0 in fit
    /// reports written before levels existed).
    #[serde(default)]
    pub level: u8,
}

/// The coordinates of one case (module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coordinates {
    /// ln(H_EI/H_RI).
    pub a: f64,
    /// ln(H_EP/H_RP) (NaN at L = 0).
    pub b: f64,
    /// ln(H_piezo/H_iso) (-infinity at L = 0).
    pub c: f64,
    /// ln D (0 for a line contact).
    pub ln_d: f64,
    /// 1/(1 + e^-c): 0 isoviscous, 1 piezoviscous.
    pub w: f64,
}

impl Coordinates {
    /// From the blend's asymptotes [H_RI, H_EI, H_RP, H_EP] (the last two 0 at L = 0) and D.
    pub fn new(asym: [f64; 4], d: f64) -> Self {
        let [ri, ei, rp, ep] = asym;
        // (x^4 + y^4)^(1/4) and (x^-4 + y^-4)^(-1/4), scaled by the larger / smaller of the two
        // so that neither overflows nor underflows far into a corner.
        let (hi, lo) = (ri.max(ei), ri.min(ei));
        let iso = hi * (1.0 + (lo / hi).powi(4)).powf(0.25);
        let piezo_flag = rp > 0.0 && ep > 0.0;
        let (b, c) = if piezo_flag {
            let (hi, lo) = (rp.max(ep), rp.min(ep));
            let piezo = lo * (1.0 + (lo / hi).powi(4)).powf(-0.25);
            ((ep / rp).ln(), (piezo / iso).ln())
        } else {
            (f64::NAN, f64::NEG_INFINITY)
        };
        Coordinates {
            a: (ei / ri).ln(),
            b,
            c,
            ln_d: d.ln(),
            w: 1.0 / (1.0 + (-c).exp()),
        }
    }
}

fn bump(t: f64) -> f64 {
    2.0 / (1.0 + t.cosh())
}

impl Term {
    /// The lattice spacing W of a Shifted or Cell bump: [`LATTICE`] / 2^level.
    pub fn width(&self) -> f64 {
        LATTICE * 0.5f64.powi(i32::from(self.level))
    }

    /// phi(z): 0 at L = 0 for the piezoviscous and outer terms.
    pub fn eval(&self, z: &Coordinates) -> f64 {
        let piezo = z.c > f64::NEG_INFINITY;
        let lw = self.width();
        let base = match self.transition {
            Transition::Isoviscous => bump(z.a) * (1.0 - z.w),
            Transition::Tail => tail(z.a) * (1.0 - z.w),
            Transition::Shifted => bump(z.a / lw - f64::from(self.at[0])) * (1.0 - z.w),
            Transition::Piezoviscous if piezo => bump(z.b) * z.w,
            Transition::Outer if piezo => bump(z.c),
            Transition::Cell if piezo => {
                bump(z.a / lw - f64::from(self.at[0])) * bump(z.c / lw - f64::from(self.at[1]))
            }
            _ => return 0.0,
        };
        if base == 0.0 {
            // Far into a corner: the bump underflowed (and a coordinate may be infinite).
            return 0.0;
        }
        let p = self.powers;
        let vars = [z.a, z.b, z.c, z.ln_d, z.w];
        vars.iter()
            .zip(p)
            .filter(|(_, k)| *k > 0)
            .fold(base, |acc, (v, k)| acc * v.powi(k as i32))
    }
}

use Transition::{Isoviscous as I, Outer as O, Piezoviscous as P, Tail as T};

/// The terms of a (transition, powers) list, in its order.
fn terms(list: &[(Transition, [u8; 5])]) -> Vec<Term> {
    list.iter()
        .map(|&(transition, powers)| Term {
            transition,
            powers,
            at: [0, 0],
            level: 0,
        })
        .collect()
}

/// The lattice bumps of spacing [`LATTICE`] / 2^`level` over the data's coordinates `z`: Shifted
/// bumps on the a range and Cell bumps on the (a, c) range (finite c only), each range widened by
/// one spacing, keeping those that reach [`LATTICE_REACH`] at some case; in (kind, i, j) order.
/// Empty when `z` is.
pub fn lattice_terms(z: &[Coordinates], level: u8) -> Vec<Term> {
    let lw = LATTICE * 0.5f64.powi(i32::from(level));
    let range = |v: &mut dyn Iterator<Item = f64>| {
        v.filter(|x| x.is_finite())
            .fold(None, |r: Option<(f64, f64)>, x| {
                Some(r.map_or((x, x), |(lo, hi)| (lo.min(x), hi.max(x))))
            })
    };
    let index = |(lo, hi): (f64, f64)| {
        let clamp = |v: f64| v.clamp(f64::from(i8::MIN), f64::from(i8::MAX)) as i8;
        clamp((lo / lw).floor() - 1.0)..=clamp((hi / lw).ceil() + 1.0)
    };
    let reaches = |t: &Term| z.iter().any(|zi| t.eval(zi).abs() >= LATTICE_REACH);
    let term = |transition, i, j| Term {
        transition,
        powers: [0; 5],
        at: [i, j],
        level,
    };
    let mut out = vec![];
    let Some(a) = range(&mut z.iter().map(|zi| zi.a)) else {
        return out;
    };
    out.extend(
        index(a)
            .map(|i| term(Transition::Shifted, i, 0))
            .filter(|t| reaches(t)),
    );
    if let Some(c) = range(&mut z.iter().map(|zi| zi.c)) {
        for i in index(a) {
            out.extend(
                index(c)
                    .map(|j| term(Transition::Cell, i, j))
                    .filter(|t| reaches(t)),
            );
        }
    }
    out
}

/// [`lattice_terms`], then each of them times ln D, (ln D)^2, ... up to (ln D)^`ln_d_powers`
/// (0: the bumps alone), in that order.
pub fn lattice_terms_in_d(z: &[Coordinates], level: u8, ln_d_powers: u8) -> Vec<Term> {
    let bumps = lattice_terms(z, level);
    (0..=ln_d_powers)
        .flat_map(|n| {
            bumps.iter().map(move |t| Term {
                powers: [0, 0, 0, n, 0],
                ..*t
            })
        })
        .collect()
}

/// The line terms, in the order they are tried.
pub fn line_terms() -> Vec<Term> {
    terms(&[
        (O, [0, 0, 0, 0, 0]),
        (I, [0, 0, 0, 0, 0]),
        (P, [0, 0, 0, 0, 0]),
        (T, [0, 0, 0, 0, 0]),
        (O, [0, 0, 1, 0, 0]),
        (I, [1, 0, 0, 0, 0]),
        (P, [0, 1, 0, 0, 0]),
        (O, [1, 0, 0, 0, 0]),
        (I, [2, 0, 0, 0, 0]),
        (O, [0, 0, 2, 0, 0]),
        (P, [0, 2, 0, 0, 0]),
        (I, [0, 0, 0, 0, 1]),
        (O, [0, 1, 0, 0, 0]),
        (O, [1, 0, 1, 0, 0]),
        (I, [3, 0, 0, 0, 0]),
        (I, [1, 0, 0, 0, 1]),
    ])
}

/// The point terms (the line ones with ln D factors interleaved), in the order they are tried.
pub fn point_terms() -> Vec<Term> {
    terms(&[
        (O, [0, 0, 0, 0, 0]),
        (I, [0, 0, 0, 0, 0]),
        (P, [0, 0, 0, 0, 0]),
        (O, [0, 0, 0, 1, 0]),
        (I, [0, 0, 0, 1, 0]),
        (P, [0, 0, 0, 1, 0]),
        (T, [0, 0, 0, 0, 0]),
        (T, [0, 0, 0, 1, 0]),
        (O, [0, 0, 1, 0, 0]),
        (I, [1, 0, 0, 0, 0]),
        (P, [0, 1, 0, 0, 0]),
        (O, [1, 0, 0, 0, 0]),
        (I, [1, 0, 0, 1, 0]),
        (O, [0, 0, 1, 1, 0]),
        (I, [2, 0, 0, 0, 0]),
        (O, [0, 0, 2, 0, 0]),
        (P, [0, 2, 0, 0, 0]),
        (I, [0, 0, 0, 0, 1]),
        (I, [0, 0, 0, 2, 0]),
        (O, [0, 0, 0, 2, 0]),
        (O, [0, 1, 0, 0, 0]),
        (P, [0, 1, 0, 1, 0]),
        (T, [0, 0, 0, 2, 0]),
    ])
}

/// A fitted correction: the terms kept and their coefficients (empty: no correction).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Correction {
    /// The basis functions, in the order tried.
    pub terms: Vec<Term>,
    /// Their coefficients c_k.
    pub coef: Vec<f64>,
    /// Where the fitted cases are: the sum is tapered to 0 beyond their range of a at each D
    /// ([`Support::fade`]; the point lattice corrections). None: applied everywhere (nested and
    /// line corrections, and stored models before it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub support: Option<Support>,
}

impl Correction {
    /// sum_k c_k phi_k at the coordinates of the blend's asymptotes `asym` and D.
    pub fn log_factor(&self, asym: [f64; 4], d: f64) -> f64 {
        if self.terms.is_empty() {
            return 0.0;
        }
        self.log_factor_at(&Coordinates::new(asym, d))
    }

    /// sum_k c_k phi_k at coordinates `z`, times the support's fade where it has one.
    pub fn log_factor_at(&self, z: &Coordinates) -> f64 {
        let sum: f64 = self
            .terms
            .iter()
            .zip(&self.coef)
            .map(|(t, c)| c * t.eval(z))
            .sum();
        match &self.support {
            Some(s) if sum != 0.0 => sum * s.fade(z.a, z.ln_d),
            _ => sum,
        }
    }

    /// The corrected film: `blend` (the blend's film at the case) times exp([`Self::log_factor`]).
    pub fn apply(&self, blend: f64, asym: [f64; 4], d: f64) -> f64 {
        blend * self.log_factor(asym, d).exp()
    }
}

/// Relative size of the smallest singular value kept by the least-squares solve.
const SVD_EPS: f64 = 1e-10;

/// The c minimising |Phi c - r|^2 + ridge |c|^2: with ridge = 0 by SVD (singular values below
/// 1e-10 of the largest are dropped), else by the Cholesky factor of Phi^T Phi + ridge I (of
/// Phi Phi^T + ridge I when Phi has more columns than rows). None when the solve fails.
pub fn solve_ridge(phi: &DMatrix<f64>, rhs: &DVector<f64>, ridge: f64) -> Option<DVector<f64>> {
    let (cases, n) = phi.shape();
    if ridge > 0.0 && n > cases {
        // More terms than cases: the same minimiser from the smaller system,
        // c = Phi^T (Phi Phi^T + ridge I)^-1 r.
        let gram = phi * phi.transpose() + DMatrix::<f64>::identity(cases, cases) * ridge;
        Some(phi.tr_mul(&gram.cholesky()?.solve(rhs)))
    } else if ridge > 0.0 {
        let normal = phi.tr_mul(phi) + DMatrix::<f64>::identity(n, n) * ridge;
        Some(normal.cholesky()?.solve(&phi.tr_mul(rhs)))
    } else {
        let svd = phi.clone().svd(true, true);
        let tol = SVD_EPS * svd.singular_values.max();
        svd.solve(rhs, tol).ok()
    }
}

/// The coefficients of `terms` that fit the log residuals `r` (ln H_data - ln H_blend) at the
/// coordinates `z`: min |Phi c - r|^2 + ridge |c|^2 ([`solve_ridge`]). None when the solve fails
/// or gives a non-finite coefficient.
pub fn fit_correction(
    z: &[Coordinates],
    r: &[f64],
    terms: &[Term],
    ridge: f64,
) -> Option<Correction> {
    if terms.is_empty() {
        return Some(Correction::default());
    }
    let phi = DMatrix::from_fn(z.len(), terms.len(), |i, k| terms[k].eval(&z[i]));
    let c = solve_ridge(&phi, &DVector::from_column_slice(r), ridge)?;
    c.iter().all(|v| v.is_finite()).then(|| Correction {
        terms: terms.to_vec(),
        coef: c.iter().copied().collect(),
        support: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line_asym(m: f64, l: f64) -> [f64; 4] {
        let a = [
            2.4475 / m,
            2.621 * m.powf(-0.2),
            1.287 * l.powf(2.0 / 3.0),
            1.311 * m.powf(-0.125) * l.powf(0.75),
        ];
        if l > 0.0 {
            a
        } else {
            [a[0], a[1], 0.0, 0.0]
        }
    }

    #[test]
    fn every_term_vanishes_in_each_asymptotic_limit() {
        // RI: M -> 0 at L = 0 and small L; EI: M -> infinity at L = 0; RP: L -> infinity with
        // M << L^(2/3); EP: M >> L^(2/3) >> 1. The crossovers are powers of M and L with small
        // exponents (H_EP/H_RP ~ M^-1/8 L^1/12), hence the extreme values.
        let corners = [
            ("RI", 1e-12, 0.0),
            ("RI, L > 0", 1e-12, 1e-3),
            ("EI", 1e40, 0.0),
            ("RP", 1.0, 1e120),
            ("EP", 1e60, 1e12),
        ];
        let mut lattice = lattice_terms(&interior_cases(), 0);
        assert!(lattice.len() > 20, "{}", lattice.len());
        lattice.extend(lattice_terms(&interior_cases(), 1));
        for t in point_terms().iter().chain(&line_terms()).chain(&lattice) {
            for (name, m, l) in corners {
                let v = t.eval(&Coordinates::new(line_asym(m, l), 0.5));
                assert!(v.abs() < 1e-3, "{t:?} at {name}: {v}");
            }
            // And it is not zero everywhere: some interior case sees it (for the lattice bumps:
            // `the_lattice_covers_the_data_and_only_the_data`).
            if matches!(t.transition, Transition::Shifted | Transition::Cell) {
                continue;
            }
            let interior = [
                (1.0, 0.0),
                (3.0, 5.0),
                (100.0, 10.0),
                (10.0, 20.0),
                (1e4, 20.0),
            ]
            .iter()
            .map(|&(m, l)| t.eval(&Coordinates::new(line_asym(m, l), 0.5)).abs())
            .fold(0.0f64, f64::max);
            assert!(interior > 1e-3, "{t:?} is 0 in the interior");
        }
    }

    /// Line cases M 0.1 ... 3000 x L {0, 1, 5, 20} (seeded grid).
    fn interior_cases() -> Vec<Coordinates> {
        let mut z = vec![];
        for i in 0..24 {
            for l in [0.0, 1.0, 5.0, 20.0] {
                let m = 10f64.powf(-1.0 + 0.2 * f64::from(i));
                z.push(Coordinates::new(line_asym(m, l), 1.0));
            }
        }
        z
    }

    #[test]
    fn the_lattice_covers_the_data_and_only_the_data() {
        let z = interior_cases();
        for level in [0, 1] {
            lattice_covers(&z, level);
        }
        assert!(lattice_terms(&[], 0).is_empty());
        // The half-spacing lattice has bumps of half the width: more than twice as many terms
        // (2.3 times here: along c, four L values limit the cells that some case reaches).
        let n = |level| lattice_terms(&z, level).len() as f64;
        assert!(n(1) > 2.0 * n(0), "{} {}", n(0), n(1));
        assert!(lattice_terms(&z, 1)
            .iter()
            .all(|t| t.width() == LATTICE / 2.0));
    }

    fn lattice_covers(z: &[Coordinates], level: u8) {
        let lattice = lattice_terms(z, level);
        // Every case is reached by some Shifted bump (its isoviscous part) or, at L > 0, by some
        // Cell bump; and every term kept reaches some case.
        for zi in z {
            let best = |kind| {
                lattice
                    .iter()
                    .filter(|t| t.transition == kind)
                    .map(|t| t.eval(zi))
                    .fold(0.0f64, f64::max)
            };
            if zi.c == f64::NEG_INFINITY {
                assert!(best(Transition::Shifted) > 0.5, "{zi:?}");
                assert_eq!(best(Transition::Cell), 0.0, "{zi:?}");
            } else {
                assert!(
                    best(Transition::Shifted).max(best(Transition::Cell)) > 0.3,
                    "{zi:?}"
                );
            }
        }
        for t in &lattice {
            assert_eq!(t.level, level);
            assert!(z.iter().any(|zi| t.eval(zi) >= LATTICE_REACH), "{t:?}");
        }
    }

    #[test]
    fn a_small_ridge_recovers_known_lattice_coefficients_and_a_large_one_shrinks_them() {
        let z = interior_cases();
        let lattice = lattice_terms(&z, 0);
        let truth: Vec<f64> = (0..lattice.len())
            .map(|k| 0.02 * ((k * 5 % 11) as f64 - 5.0))
            .collect();
        let r: Vec<f64> = z
            .iter()
            .map(|zi| {
                lattice
                    .iter()
                    .zip(&truth)
                    .map(|(t, c)| c * t.eval(zi))
                    .sum()
            })
            .collect();
        let fitted = |ridge| {
            let c = fit_correction(&z, &r, &lattice, ridge).unwrap();
            z.iter()
                .zip(&r)
                .map(|(zi, ri)| (c.log_factor_at(zi) - ri).abs())
                .fold(0.0f64, f64::max)
        };
        // The residuals are reproduced (the coefficients themselves are not all identifiable from
        // 96 cases), and the ridge trades fit for size.
        assert!(fitted(1e-12) < 1e-6, "{}", fitted(1e-12));
        assert!(fitted(1.0) > 10.0 * fitted(1e-12));
    }

    #[test]
    fn the_ridge_fit_with_more_terms_than_cases_is_the_normal_equations_minimiser() {
        // 96 cases, some 400 half-spacing lattice terms: the solve takes the cases' system; the
        // oracle is the terms' normal equations (Phi^T Phi + ridge I) c = Phi^T r.
        let z = interior_cases();
        let lattice = lattice_terms(&z, 1);
        assert!(lattice.len() > z.len(), "{}", lattice.len());
        let r: Vec<f64> = z
            .iter()
            .enumerate()
            .map(|(i, zi)| 0.01 * (zi.a.sin() + ((i * 7 % 5) as f64 - 2.0) * 0.1))
            .collect();
        for ridge in [1e-4, 1e-2] {
            let fast = fit_correction(&z, &r, &lattice, ridge).unwrap();
            let phi = DMatrix::from_fn(z.len(), lattice.len(), |i, k| lattice[k].eval(&z[i]));
            let n = lattice.len();
            let normal = phi.tr_mul(&phi) + DMatrix::<f64>::identity(n, n) * ridge;
            let slow = normal
                .cholesky()
                .unwrap()
                .solve(&phi.tr_mul(&DVector::from_column_slice(&r)));
            let scale = slow.amax();
            for (a, b) in fast.coef.iter().zip(slow.iter()) {
                assert!((a - b).abs() < 1e-8 * scale, "{a} {b} (ridge {ridge})");
            }
        }
    }

    #[test]
    fn piezoviscous_and_outer_terms_are_zero_at_l_0() {
        let z = Coordinates::new(line_asym(3.0, 0.0), 1.0);
        for t in line_terms() {
            let v = t.eval(&z);
            assert!(v.is_finite());
            if matches!(t.transition, Transition::Piezoviscous | Transition::Outer) {
                assert_eq!(v, 0.0, "{t:?}");
            }
        }
    }

    #[test]
    fn recovers_known_coefficients() {
        // Residuals generated from three terms with fixed coefficients (seeded grid of cases).
        let terms = line_terms();
        let truth = [0.05, -0.03, 0.02];
        let mut z = vec![];
        for i in 0..12 {
            for l in [0.0, 2.0, 5.0, 10.0, 20.0] {
                let m = 10f64.powf(-1.0 + 0.4 * i as f64);
                z.push(Coordinates::new(line_asym(m, l), 1.0));
            }
        }
        let r: Vec<f64> = z
            .iter()
            .map(|zi| (0..3).map(|k| truth[k] * terms[k].eval(zi)).sum())
            .collect();
        let c = fit_correction(&z, &r, &terms[..3], 0.0).unwrap();
        for k in 0..3 {
            assert!((c.coef[k] - truth[k]).abs() < 1e-12, "{:?}", c.coef);
        }
    }
}
