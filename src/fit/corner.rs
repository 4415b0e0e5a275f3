//! The corner of the line central film: where the film at X = 0 meets the film at the pressure
//! maximum.
//!
//! At L >= 8 the line H_c rises ever faster with M until it meets H_pm (near M = 1.8) and
//! follows it from there (H_c / H_pm within 1.000-1.02): a corner between two smooth branches
//! that no smooth correction follows (docs/validation.md). The law of H_c is therefore
//!
//! H_c = R exp(-delta),  delta = rho (max(0, h) / rho)^k,  R = H_pm,blend exp(C_R),
//! h = rho r(z) + C_h,
//!
//! with H_pm,blend the blend of the H_pm law, C_R and C_h interior corrections
//! ([`crate::fit::correction`], lattice bumps in the coordinates z of that blend), rho =
//! ln(H_RI,pm / H_RI,c) (the rigid films' ratio: ln(3/2.4475)) and r(z) = (1 - w) / (1 + e^a) +
//! w / (1 + e^-b) the blend's rigidity (1 in both rigid limits, 0 in both elastic ones), and k =
//! [`DEFICIT_POWER`]. R is the branch that follows H_pm, exp(-delta) the deficit of the branch
//! that rises to it, and the corner is where h crosses 0; with k < 1 the deficit closes faster
//! than linearly there, as the data do (H_c rises ever faster until it meets H_pm).
//!
//! Invariants: H_c <= R everywhere. Each asymptote of H_c is the H_c blend's, exactly: the bumps
//! vanish in every limit, so h -> rho and H_c -> H_pm,blend exp(-rho) in the rigid limits (the
//! H_pm rigid laws are the H_c ones times e^rho: 3/M against 2.4475/M, and the same ratio for
//! the rigid-piezoviscous constants) and H_c -> H_pm,blend in the elastic ones (the two films
//! share their elastic constants). [`Corner::new`] checks those ratios.
//!
//! Fit ([`fit_corner`]): the cases are split by the data into those where H_c follows H_pm
//! (H_c at least [`FOLLOWS`] H_pm) and the rest. C_R fits ln(H_c / H_pm,blend) on the first,
//! and on the rest is only held from below the data (R at least H_c; a one-sided row is added
//! while it is violated, [`one_sided`]); C_h then fits h to rho (y / rho)^(1/k), y = max(0,
//! ln(R / H_c)), on the rest and is held from above by it on the first (h at most 0 where R is at
//! least H_c there). Both are ridge least squares ([`solve_ridge`]); the ridge weights are chosen
//! by held-out error ([`select_corner`]).

use crate::fit::correction::{lattice_terms, solve_ridge, Coordinates, Correction, Term};
use crate::fit::heldout::{worst_and_rms, RMS_SLACK};
use crate::fit::model::LineModel;
use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

/// H_c follows H_pm at a case where H_c >= FOLLOWS H_pm (the data's H_pm): past the corner the
/// ratio is 1.000-1.019, before it 0.82-0.96 in the data.
pub const FOLLOWS: f64 = 0.995;

/// The power k of the deficit (module doc): chosen by held-out error on the committed line data
/// and by the error on a dense band of cases around the corner (docs/validation.md; k = 1: the
/// hinge itself, 0.5 follows the smooth part worse).
pub const DEFICIT_POWER: f64 = 0.75;

/// The lattice level of both corrections (spacing [`crate::fit::correction::LATTICE`] / 2).
pub const LEVEL: u8 = 1;

/// The ridge weights (R, h) tried, in this order: the first whose held-out RMS is within
/// [`RMS_SLACK`] of the best is kept (on the committed line data 1e-3 / 3e-5; docs/validation.md).
pub const CORNER_RIDGES: [[f64; 2]; 6] = [
    [1e-3, 1e-5],
    [3e-4, 1e-5],
    [1e-4, 1e-5],
    [1e-3, 3e-5],
    [3e-4, 3e-5],
    [1e-4, 3e-5],
];

/// The H_c law with its corner (module doc).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Corner {
    /// The blend of the right branch R: the H_pm law's.
    pub base: LineModel,
    /// C_R, R's interior correction.
    pub branch: Correction,
    /// C_h, the deficit's interior part.
    pub deficit: Correction,
    /// rho = ln(H_RI,pm / H_RI,c).
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

impl Corner {
    /// A corner law on `base` (the H_pm blend) for the H_c blend `own`: None unless the two
    /// blends' asymptotes have the ratios of the module doc (rigid: a common e^rho > 1;
    /// elastic: 1), each to 1e-9.
    pub fn new(
        base: LineModel,
        own: &LineModel,
        branch: Correction,
        deficit: Correction,
    ) -> Option<Self> {
        let ratio = |m: f64, l: f64, k: usize| base.asymptotes(m, l)[k] / own.asymptotes(m, l)[k];
        let rigid = ratio(1.0, 1.0, 0);
        let same = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-9;
        (rigid > 1.0
            && same(ratio(1.0, 1.0, 2), rigid)
            && same(ratio(1.0, 1.0, 1), 1.0)
            && same(ratio(1.0, 1.0, 3), 1.0))
        .then(|| Corner {
            base,
            branch,
            deficit,
            rho: rigid.ln(),
        })
    }

    fn coords(&self, m: f64, l: f64) -> Coordinates {
        Coordinates::new(self.base.asymptotes(m, l), 1.0)
    }

    /// The right branch R at (M, L).
    pub fn right(&self, m: f64, l: f64) -> f64 {
        self.base.eval(m, l) * self.branch.log_factor_at(&self.coords(m, l)).exp()
    }

    /// h at (M, L) (before the hinge).
    pub fn h(&self, m: f64, l: f64) -> f64 {
        let z = self.coords(m, l);
        self.rho * rigidity(&z) + self.deficit.log_factor_at(&z)
    }

    /// The deficit delta = rho (max(0, h) / rho)^k at (M, L).
    pub fn deficit(&self, m: f64, l: f64) -> f64 {
        self.rho * (self.h(m, l).max(0.0) / self.rho).powf(DEFICIT_POWER)
    }

    /// H_c = R exp(-delta) at (M, L).
    pub fn eval(&self, m: f64, l: f64) -> f64 {
        self.right(m, l) * (-self.deficit(m, l)).exp()
    }
}

/// One case of the corner fit: M, L, the data's H_c and whether H_c follows H_pm there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CornerCase {
    /// Moes' M.
    pub m: f64,
    /// Moes' L.
    pub l: f64,
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

/// The corner law on `base` (the H_pm blend, with the H_c blend `own`) fitted to `cases` with
/// the lattice `terms` and the ridge weights (R, h) (module doc). None when the blends do not
/// share their asymptotes as [`Corner::new`] needs, a class of cases is empty or a solve fails.
pub fn fit_corner(
    cases: &[CornerCase],
    base: &LineModel,
    own: &LineModel,
    terms: &[Term],
    ridges: [f64; 2],
) -> Option<Corner> {
    let follows: Vec<bool> = cases.iter().map(|c| c.follows).collect();
    if follows.iter().all(|&f| f) || !follows.iter().any(|&f| f) {
        return None;
    }
    let empty = Correction::default();
    let mut corner = Corner::new(base.clone(), own, empty.clone(), empty)?;
    let z: Vec<Coordinates> = cases.iter().map(|c| corner.coords(c.m, c.l)).collect();
    let phi = DMatrix::from_fn(z.len(), terms.len(), |i, k| terms[k].eval(&z[i]));
    let y: Vec<f64> = cases
        .iter()
        .map(|c| (c.h / base.eval(c.m, c.l)).ln())
        .collect();
    let (coef, _) = one_sided(&phi, &y, &follows, ridges[0], true)?;
    // ln(R / H_c) = C_R - ln(H_c / H_pm,blend) at each case.
    let c_r = &phi * DVector::from_column_slice(&coef);
    corner.branch = Correction {
        terms: terms.to_vec(),
        coef,
    };
    let rho = corner.rho;
    let y: Vec<f64> = (0..cases.len())
        .map(|i| {
            let gap = (c_r[i] - y[i]).max(0.0);
            rho * (gap / rho).powf(1.0 / DEFICIT_POWER) - rho * rigidity(&z[i])
        })
        .collect();
    let rest: Vec<bool> = follows.iter().map(|f| !f).collect();
    let (coef, _) = one_sided(&phi, &y, &rest, ridges[1], false)?;
    corner.deficit = Correction {
        terms: terms.to_vec(),
        coef,
    };
    Some(corner)
}

/// The held-out choice of the corner law's ridge weights.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CornerChoice {
    /// The ridge weights (R, h) kept: the first of [`CORNER_RIDGES`] whose held-out RMS is within
    /// [`RMS_SLACK`] of the best.
    pub ridges: [f64; 2],
    /// Each candidate tried: its ridges, held-out RMS and largest |error| (sign kept).
    pub tried: Vec<([f64; 2], f64, f64)>,
    /// Lattice terms of each correction.
    pub terms: usize,
    /// The cases following H_pm, of all.
    pub follows: [usize; 2],
}

/// Cross-validate [`CORNER_RIDGES`] on `cases` (fold of case i: `fold[i]`, the base blend of
/// fold f: `bases[f]`, fitted without it) and fit the ridges kept on all cases with `base`.
/// The lattice is that of `base`'s coordinates over all cases. Returns the law, the choice and
/// each case's held-out relative error formula / data - 1 with the ridges kept (in the cases'
/// order). None when a candidate cannot be fitted on every fold or the final fit fails.
pub fn select_corner(
    cases: &[CornerCase],
    fold: &[usize],
    bases: &[LineModel],
    base: &LineModel,
    own: &LineModel,
) -> Option<(Corner, CornerChoice, Vec<f64>)> {
    let z: Vec<Coordinates> = cases
        .iter()
        .map(|c| Coordinates::new(base.asymptotes(c.m, c.l), 1.0))
        .collect();
    let terms = lattice_terms(&z, LEVEL);
    let mut scored = vec![];
    for ridges in CORNER_RIDGES {
        let mut e = vec![f64::NAN; cases.len()];
        for (f, b) in bases.iter().enumerate() {
            let train: Vec<CornerCase> = (0..cases.len())
                .filter(|&i| fold[i] != f)
                .map(|i| cases[i])
                .collect();
            let law = fit_corner(&train, b, own, &terms, ridges)?;
            for i in (0..cases.len()).filter(|&i| fold[i] == f) {
                e[i] = law.eval(cases[i].m, cases[i].l) / cases[i].h - 1.0;
            }
        }
        if !e.iter().all(|v| v.is_finite()) {
            return None;
        }
        let (worst, rms) = worst_and_rms(&e);
        scored.push((ridges, rms, e[worst], e));
    }
    let best = scored.iter().map(|s| s.1).fold(f64::INFINITY, f64::min);
    let kept = scored.iter().position(|s| s.1 <= RMS_SLACK * best)?;
    let ridges = scored[kept].0;
    let law = fit_corner(cases, base, own, &terms, ridges)?;
    let n_follow = cases.iter().filter(|c| c.follows).count();
    let choice = CornerChoice {
        ridges,
        tried: scored.iter().map(|s| (s.0, s.1, s.2)).collect(),
        terms: terms.len(),
        follows: [n_follow, cases.len()],
    };
    Some((law, choice, scored.swap_remove(kept).3))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Moes' blend as the H_pm law, and the same with the H_c rigid constants (2.4475/3 times
    /// Moes' RI and RP laws) as the H_c law.
    fn blends() -> (LineModel, LineModel) {
        let base = LineModel::moes();
        let mut own = base.clone();
        own.c_ri = 2.4475;
        own.x[2] += (2.4475f64 / 3.0).ln();
        (base, own)
    }

    /// Cases M = 0.1 ... 3000 (46, log) x L in {0, 1, 2, 4, 8, 12, 16, 20} whose H_c is the H_pm
    /// blend times exp(-max(0, rho r(z) - 0.05 - 0.002 ln(1 + L))): a corner where rho r(z)
    /// crosses 0.05 + 0.002 ln(1 + L), H_c following H_pm past it.
    fn cases(base: &LineModel, rho: f64) -> Vec<CornerCase> {
        let mut out = vec![];
        for i in 0..46 {
            let m = 10f64.powf(-1.0 + f64::from(i) / 10.0);
            for l in [0.0, 1.0, 2.0, 4.0, 8.0, 12.0, 16.0, 20.0] {
                let z = Coordinates::new(base.asymptotes(m, l), 1.0);
                let h_pm = base.eval(m, l);
                let h = h_pm * (-(rho * rigidity(&z) - 0.05 - 0.002 * l.ln_1p()).max(0.0)).exp();
                out.push(CornerCase {
                    m,
                    l,
                    h,
                    follows: h >= FOLLOWS * h_pm,
                });
            }
        }
        out
    }

    fn rho() -> f64 {
        (3.0f64 / 2.4475).ln()
    }

    #[test]
    fn the_blends_fix_rho_and_unrelated_blends_are_refused() {
        let (base, own) = blends();
        let c = Corner::new(
            base.clone(),
            &own,
            Correction::default(),
            Correction::default(),
        );
        assert!((c.expect("shared asymptotes").rho - rho()).abs() < 1e-15);
        // An H_c law whose EI constant differs from H_pm's has no corner law.
        let mut other = own.clone();
        other.x[0] += 0.01;
        let none = Corner::new(base, &other, Correction::default(), Correction::default());
        assert!(none.is_none());
    }

    #[test]
    fn one_sided_rows_hold_their_bound_and_the_rest_are_least_squares() {
        // A seeded random 60 x 12 problem: the first 30 rows own, the rest bounded.
        let mut seed = 12345u64;
        let mut rand = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let phi = DMatrix::from_fn(60, 12, |_, _| rand());
        let y: Vec<f64> = (0..60).map(|_| rand()).collect();
        let own: Vec<bool> = (0..60).map(|i| i < 30).collect();
        for floor in [true, false] {
            let (c, fitted) = one_sided(&phi, &y, &own, 1e-6, floor).expect("solves");
            let g = &phi * DVector::from_column_slice(&c);
            // Every row left out holds its bound; the fit is the ridge solution over the rest.
            for i in (0..60).filter(|&i| !fitted[i]) {
                assert!(if floor { g[i] >= y[i] } else { g[i] <= y[i] }, "row {i}");
            }
            let added = (30..60).filter(|&i| fitted[i]).count();
            assert!(added > 0 && added < 30, "floor {floor}: {added} rows added");
            let active: Vec<usize> = (0..60).filter(|&i| fitted[i]).collect();
            let sub = phi.select_rows(&active);
            let rhs = DVector::from_iterator(active.len(), active.iter().map(|&i| y[i]));
            let oracle = solve_ridge(&sub, &rhs, 1e-6).expect("oracle");
            let diff = (oracle - DVector::from_column_slice(&c)).amax();
            assert!(diff < 1e-8, "floor {floor}: {diff}");
        }
    }

    #[test]
    fn a_synthetic_corner_is_followed_in_and_out_of_sample() {
        let (base, own) = blends();
        let cases = cases(&base, rho());
        let follows = cases.iter().filter(|c| c.follows).count();
        assert!(
            follows > 50 && cases.len() - follows > 50,
            "{follows} of {}",
            cases.len()
        );
        let fold: Vec<usize> = (0..cases.len()).map(|i| i % 5).collect();
        let bases = vec![base.clone(); 5];
        let (law, choice, heldout) =
            select_corner(&cases, &fold, &bases, &base, &own).expect("fits");
        let worst_in = cases
            .iter()
            .map(|c| (law.eval(c.m, c.l) / c.h - 1.0).abs())
            .fold(0.0, f64::max);
        let worst_out = heldout.iter().fold(0.0f64, |a, e| a.max(e.abs()));
        eprintln!(
            "in sample {worst_in:e}, held out {worst_out:e}, ridges {:?}",
            choice.ridges
        );
        assert!(worst_in < 2e-3, "{worst_in}");
        assert!(worst_out < 5e-3, "{worst_out}");
        // H_c never exceeds the right branch.
        for c in &cases {
            assert!(law.eval(c.m, c.l) <= law.right(c.m, c.l));
        }
    }

    #[test]
    fn the_corner_law_keeps_the_h_c_asymptotes() {
        let (base, own) = blends();
        let cases = cases(&base, rho());
        let terms = lattice_terms(
            &cases
                .iter()
                .map(|c| Coordinates::new(base.asymptotes(c.m, c.l), 1.0))
                .collect::<Vec<_>>(),
            LEVEL,
        );
        let law = fit_corner(&cases, &base, &own, &terms, CORNER_RIDGES[0]).expect("fits");
        for (name, m, l) in [
            ("RI", 1e-12, 0.0),
            ("RI, L > 0", 1e-12, 1e-3),
            ("EI", 1e40, 0.0),
            ("RP", 1.0, 1e120),
            ("EP", 1e60, 1e12),
        ] {
            let ratio = law.eval(m, l) / own.eval(m, l);
            assert!((ratio - 1.0).abs() < 1e-3, "{name}: {ratio}");
        }
    }
}
