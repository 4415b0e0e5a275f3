//! The kriging residual of a corrected film law: H = H_law exp(k(z)), where H_law is the blend
//! times its interior correction ([`crate::fit::correction`]) and k is the posterior mean of a
//! zero-mean Gaussian process fitted to the law's log residuals r_i = ln(H_i / H_law,i):
//!
//! k(z) = sum_j w_j K(|z - z_j|_s), (K + nugget I) w = r, K_ij = K(|z_i - z_j|_s),
//!
//! with the Matern 5/2 kernel K(d) = (1 + sqrt5 d + 5 d^2 / 3) e^(-sqrt5 d) and the scaled
//! distance |dz|_s = |(da / s_a, dc / s_c, d ln D / s_D)|, in the correction's coordinates
//! (a = ln(H_EI/H_RI), c = ln(H_piezo/H_iso), ln D) of the law's own asymptotes; c is held at
//! `c_floor` below it (and at L = 0, where c = -infinity), so that the isoviscous cases are one
//! plane of the map.
//!
//! Invariants: k tends to 0 wherever a or c grows without bound (every asymptotic limit: RI and
//! EI at a -> -infinity / +infinity, RP and EP at c -> +infinity) and as ln D -> -infinity, like
//! e^(-sqrt5 d) in the scaled distance from the data: the law's asymptotes are the formula's. The
//! scales and the nugget are chosen by held-out error ([`select`]) among [`SCALES`] x [`NUGGETS`],
//! short enough in a that one decade of M beyond the data (a moves by about 4.3 per decade of M
//! for point contacts) a kernel has fallen to 0.11 of its value at the edge (s_a = 2). Reference:
//! Rasmussen & Williams, Gaussian Processes for Machine Learning (2006), eq. 2.25 and 4.17.
//!
//! The point H_c may take a fourth coordinate, phi = tanh(ln(M / M_j(L, D)) / [`JUMP_WIDTH`]),
//! the side of the corner's place M_j ([`crate::limits::jump`]) on which a case lies: 0 at the
//! corner, -1 well before it and 1 well past it, so that two cases a few per cent of M apart
//! across the corner are far apart to the process while the rest of the map barely changes
//! (phi saturates within a few widths). Its scale s_phi is chosen with the others
//! ([`JUMP_SCALES`], and infinity: the fourth coordinate ignored). phi is bounded, so the
//! invariants above hold with it.

use crate::fit::correction::Coordinates;
use crate::limits::jump::JumpTable;
use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// The length scales (s_a, s_c, s_D) tried.
pub const SCALES: [[f64; 3]; 7] = [
    [1.0, 0.5, 1.0],
    [1.0, 0.5, 2.0],
    [2.0, 0.5, 2.0],
    [1.0, 1.0, 2.0],
    [2.0, 1.0, 2.0],
    [2.0, 0.5, 1.0],
    [2.0, 1.0, 1.0],
];

/// The nuggets tried (relative to the kernel's unit variance).
pub const NUGGETS: [f64; 4] = [1e-5, 1e-4, 1e-3, 1e-2];

/// The width in ln M of the corner coordinate phi = tanh(ln(M / M_j) / JUMP_WIDTH).
pub const JUMP_WIDTH: f64 = 0.1;

/// The scales s_phi tried for the corner coordinate where a jump table is given (besides
/// infinity: the coordinate ignored).
pub const JUMP_SCALES: [f64; 2] = [0.5, 1.0];

/// Kriging coordinates (a, c, ln D, phi): phi = 0 without a corner coordinate.
pub type X = [f64; 4];

/// The corner coordinate of a kriging: where the corner lies and the scale of phi.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KrigingJump {
    /// ln M_j(L, D).
    pub table: JumpTable,
    /// The width of phi in ln M ([`JUMP_WIDTH`]).
    pub width: f64,
    /// s_phi.
    pub scale: f64,
}

/// phi = tanh(ln(M / M_j(L, D)) / width) at (M, L, D) (fits use [`JUMP_WIDTH`]).
pub fn phi(table: &JumpTable, width: f64, m: f64, l: f64, d: f64) -> f64 {
    ((m.ln() - table.ln_m_at(l, d)) / width).tanh()
}

/// A fitted kriging residual.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Kriging {
    /// Length scales (s_a, s_c, s_D).
    pub scales: [f64; 3],
    /// The value c is held at below it (and at L = 0).
    pub c_floor: f64,
    /// The nugget the weights were solved with.
    pub nugget: f64,
    /// The data cases' coordinates (a, c, ln D).
    pub centres: Vec<[f64; 3]>,
    /// Their weights w_j.
    pub weights: Vec<f64>,
    /// The corner coordinate (None: three coordinates).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub jump: Option<KrigingJump>,
    /// The data cases' phi (empty without a corner coordinate).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub phis: Vec<f64>,
}

/// How the kriging residual was chosen: its scales and nugget, and the held-out errors with and
/// without it (relative errors formula / data - 1 over the same folds).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct KrigingChoice {
    /// Length scales (s_a, s_c, s_D) kept.
    pub scales: [f64; 3],
    /// Nugget kept.
    pub nugget: f64,
    /// Candidates tried (scales x nuggets).
    pub tried: usize,
    /// Held-out RMS and max |error| with the kriging residual.
    pub rms: f64,
    /// See `rms`.
    pub max: f64,
    /// The scale s_phi of the corner coordinate kept (None: not used).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub jump_scale: Option<f64>,
    /// Held-out RMS and max |error| of the corrected blend alone.
    pub without_rms: f64,
    /// See `without_rms`.
    pub without_max: f64,
}

/// The Matern 5/2 kernel at scaled distance `d`.
pub fn matern52(d: f64) -> f64 {
    let s = 5f64.sqrt() * d;
    (1.0 + s + s * s / 3.0) * (-s).exp()
}

/// The kriging coordinates (a, max(c, c_floor), ln D) of `z`.
pub fn point(z: &Coordinates, c_floor: f64) -> [f64; 3] {
    let c = if z.c.is_finite() {
        z.c.max(c_floor)
    } else if z.c > 0.0 {
        f64::INFINITY
    } else {
        c_floor
    };
    [z.a, c, z.ln_d]
}

/// The floor of c for `z`: one below the least finite c (0 when none is finite).
pub fn c_floor(z: &[Coordinates]) -> f64 {
    z.iter()
        .map(|z| z.c)
        .filter(|c| c.is_finite())
        .fold(None, |m: Option<f64>, c| Some(m.map_or(c, |m| m.min(c))))
        .map_or(0.0, |c| c - 1.0)
}

fn kernel(x: &X, y: &X, s: &X) -> f64 {
    // s_phi = infinity: the corner coordinate ignored (0, not NaN, for equal phi).
    let d2: f64 = (0..4)
        .map(|i| {
            let t = x[i] - y[i];
            if t == 0.0 {
                0.0
            } else {
                (t / s[i]).powi(2)
            }
        })
        .sum();
    if d2.is_finite() {
        matern52(d2.sqrt())
    } else {
        0.0
    }
}

/// The coordinates (a, c, ln D) with phi.
pub fn with_phi(x: [f64; 3], phi: f64) -> X {
    [x[0], x[1], x[2], phi]
}

impl Kriging {
    /// k at the coordinates of the law's asymptotes `asym` at (M, L, D).
    pub fn log_factor(&self, asym: [f64; 4], m: f64, l: f64, d: f64) -> f64 {
        let p = self
            .jump
            .as_ref()
            .map_or(0.0, |j| phi(&j.table, j.width, m, l, d));
        self.at(&with_phi(
            point(&Coordinates::new(asym, d), self.c_floor),
            p,
        ))
    }

    /// The scales (s_a, s_c, s_D, s_phi), s_phi infinite without a corner coordinate.
    fn scales4(&self) -> X {
        let s = self.scales;
        [
            s[0],
            s[1],
            s[2],
            self.jump.as_ref().map_or(f64::INFINITY, |j| j.scale),
        ]
    }

    /// k at kriging coordinates `x` (0 where x is not finite: an asymptotic limit).
    pub fn at(&self, x: &X) -> f64 {
        let s = self.scales4();
        self.centres
            .iter()
            .zip(&self.weights)
            .enumerate()
            .map(|(j, (c, w))| {
                let p = self.phis.get(j).copied().unwrap_or(0.0);
                w * kernel(x, &with_phi(*c, p), &s)
            })
            .sum()
    }
}

/// The kriging residual through `residuals` at `centres` with the scales (s_a, s_c, s_D,
/// s_phi); the corner coordinate is kept (with `jump`'s table) where s_phi is finite. None when
/// the system is not positive definite or a weight is not finite.
pub fn fit(
    centres: &[X],
    residuals: &[f64],
    scales: X,
    nugget: f64,
    c_floor: f64,
    jump: Option<&JumpTable>,
) -> Option<Kriging> {
    let w = fit_weights(centres, residuals, scales, nugget)?;
    let jump = jump.filter(|_| scales[3].is_finite()).map(|t| KrigingJump {
        table: t.clone(),
        width: JUMP_WIDTH,
        scale: scales[3],
    });
    Some(Kriging {
        scales: [scales[0], scales[1], scales[2]],
        c_floor,
        nugget,
        centres: centres.iter().map(|c| [c[0], c[1], c[2]]).collect(),
        weights: w,
        phis: if jump.is_some() {
            centres.iter().map(|c| c[3]).collect()
        } else {
            vec![]
        },
        jump,
    })
}

/// The weights w of (K + nugget I) w = r; None when K is not positive definite or a weight is
/// not finite.
fn fit_weights(centres: &[X], residuals: &[f64], scales: X, nugget: f64) -> Option<Vec<f64>> {
    let n = centres.len();
    let k = DMatrix::from_fn(n, n, |i, j| {
        kernel(&centres[i], &centres[j], &scales) + if i == j { nugget } else { 0.0 }
    });
    let w = k.cholesky()?.solve(&DVector::from_column_slice(residuals));
    w.iter()
        .all(|v| v.is_finite())
        .then(|| w.iter().copied().collect())
}

/// One fold of the cross-validation: the law fitted without the fold, its log residuals at its
/// training cases and at the fold's cases (data index, coordinates, residual ln(H / H_law)).
pub struct Fold {
    /// Training cases: kriging coordinates and residuals.
    pub train: Vec<(X, f64)>,
    /// The fold's cases: data index, kriging coordinates, residual.
    pub test: Vec<(usize, X, f64)>,
}

/// What [`select`] returns: the scales and nugget kept and, per data case (NaN for a case in no
/// fold's test set), the held-out k and relative error exp(k - r) - 1.
pub struct Selection {
    /// Length scales (s_a, s_c, s_D, s_phi; s_phi infinite: phi ignored).
    pub scales: X,
    /// Nugget.
    pub nugget: f64,
    /// Each case's k, from the fit without its fold.
    pub k: Vec<f64>,
    /// Each case's held-out relative error (formula over data, less 1).
    pub errors: Vec<f64>,
}

/// The candidates (scales, nugget) of [`select`]: [`SCALES`] x [`NUGGETS`], each with s_phi
/// infinite and, where `jump`, also with each of [`JUMP_SCALES`].
pub fn candidates(jump: bool) -> Vec<(X, f64)> {
    let phis: &[f64] = if jump { &JUMP_SCALES } else { &[] };
    std::iter::once(f64::INFINITY)
        .chain(phis.iter().copied())
        .flat_map(|p| {
            SCALES
                .iter()
                .flat_map(move |s| NUGGETS.iter().map(move |g| ([s[0], s[1], s[2], p], *g)))
        })
        .collect()
}

/// The scales and nugget of the best held-out RMS among the [`candidates`] whose largest
/// held-out |error| is at most `max_bound` (None when no candidate qualifies). Candidates in
/// parallel, compared in order: the same at any thread count.
pub fn select(folds: &[Fold], cases: usize, max_bound: f64, jump: bool) -> Option<Selection> {
    let candidates = candidates(jump);
    let scored: Vec<Option<(f64, Selection)>> = candidates
        .par_iter()
        .map(|&(scales, nugget)| {
            let (mut k, mut errors) = (vec![f64::NAN; cases], vec![f64::NAN; cases]);
            for f in folds {
                let (x, r): (Vec<X>, Vec<f64>) = f.train.iter().copied().unzip();
                let fitted = fit_weights(&x, &r, scales, nugget)?;
                for (i, z, r) in &f.test {
                    k[*i] = x
                        .iter()
                        .zip(&fitted)
                        .map(|(c, w)| w * kernel(z, c, &scales))
                        .sum();
                    errors[*i] = (k[*i] - r).exp() - 1.0;
                }
            }
            let got: Vec<f64> = errors.iter().copied().filter(|v| !v.is_nan()).collect();
            if got.is_empty() || !got.iter().all(|v| v.is_finite()) {
                return None;
            }
            let rms = (got.iter().map(|v| v * v).sum::<f64>() / got.len() as f64).sqrt();
            if got.iter().any(|v| v.abs() > max_bound) {
                return None;
            }
            let sel = Selection {
                scales,
                nugget,
                k,
                errors,
            };
            Some((rms, sel))
        })
        .collect();
    // The first of the lowest RMS.
    let mut best: Option<(f64, Selection)> = None;
    for (rms, sel) in scored.into_iter().flatten() {
        if best.as_ref().is_none_or(|(b, _)| rms < *b) {
            best = Some((rms, sel));
        }
    }
    best.map(|(_, sel)| sel)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn f(x: &X) -> f64 {
        0.03 * (0.8 * x[0]).sin() * (-0.2 * x[1] * x[1]).exp() + 0.01 * x[2]
    }

    /// Five folds of the cases (x, r): case i in fold i mod 5.
    fn five_folds(x: &[X], r: &[f64]) -> Vec<Fold> {
        (0..5)
            .map(|k| Fold {
                train: (0..x.len())
                    .filter(|i| i % 5 != k)
                    .map(|i| (x[i], r[i]))
                    .collect(),
                test: (0..x.len())
                    .filter(|i| i % 5 == k)
                    .map(|i| (i, x[i], r[i]))
                    .collect(),
            })
            .collect()
    }

    /// Three coordinates, s_phi infinite.
    const S3: X = [1.5, 1.5, 2.0, f64::INFINITY];

    // The posterior mean interpolates a smooth function from a fixed lattice: at points between
    // the lattice nodes it is within 2 % of the function's range (the lattice spacing is a
    // third of the scales), and at the nodes within the nugget's smoothing.
    #[test]
    fn interpolates_a_smooth_function_between_its_nodes() {
        let mut x = vec![];
        for i in 0..13 {
            for j in 0..7 {
                for k in 0..4 {
                    x.push([
                        -3.0 + 0.5 * i as f64,
                        -1.5 + 0.5 * j as f64,
                        -0.7 * k as f64,
                        0.0,
                    ]);
                }
            }
        }
        let r: Vec<f64> = x.iter().map(f).collect();
        let k = fit(&x, &r, S3, 1e-8, -10.0, None).unwrap();
        assert!(k.jump.is_none() && k.phis.is_empty());
        for z in &x {
            assert!((k.at(z) - f(z)).abs() < 1e-5, "{z:?}");
        }
        let mut worst: f64 = 0.0;
        for i in 0..12 {
            for j in 0..6 {
                let z = [-2.75 + 0.5 * i as f64, -1.25 + 0.5 * j as f64, -1.05, 0.0];
                worst = worst.max((k.at(&z) - f(&z)).abs());
            }
        }
        assert!(worst < 0.02 * 0.06, "worst {worst}");
    }

    // Every asymptotic limit: a or c without bound (or not finite) gives 0, and one decade of
    // M beyond the data (a 4.3 further at the least scale tried) a tenth of the edge value or
    // less.
    #[test]
    fn vanishes_in_the_asymptotic_limits() {
        // With the corner coordinate too: phi is bounded, so only a, c and ln D reach the
        // limits, and there k is 0 whatever phi.
        let x = vec![
            [0.0, 0.0, 0.0, -1.0],
            [1.0, 0.5, 0.0, 0.3],
            [2.0, 1.0, -0.5, 1.0],
        ];
        let table = JumpTable::new(vec![0.0, 1.0], vec![-1.0, 0.0], vec![vec![1.0; 2]; 2]).unwrap();
        let k = fit(
            &x,
            &[0.02, -0.01, 0.015],
            [2.0, 1.0, 2.0, 0.5],
            1e-3,
            -5.0,
            Some(&table),
        )
        .unwrap();
        assert_eq!(k.phis, [-1.0, 0.3, 1.0]);
        for p in [-1.0, 0.0, 1.0] {
            for far in [
                [1e3, 0.0, 0.0, p],
                [-1e3, 0.0, 0.0, p],
                [0.0, 1e3, 0.0, p],
                [f64::INFINITY, 0.0, 0.0, p],
                [0.0, f64::INFINITY, 0.0, p],
                [0.0, 0.0, f64::NEG_INFINITY, p],
            ] {
                assert_eq!(k.at(&far), 0.0, "{far:?}");
            }
        }
        let w = JUMP_WIDTH;
        assert!(phi(&table, w, 1e-30, 3.0, 0.5) == -1.0 && phi(&table, w, 1e30, 3.0, 0.5) == 1.0);
        assert!(matern52(4.3 / 2.0) < 0.12);
        assert_eq!(matern52(0.0), 1.0);
        let z = Coordinates {
            a: 0.0,
            b: f64::NAN,
            c: f64::NEG_INFINITY,
            ln_d: 0.0,
            w: 0.0,
        };
        assert_eq!(point(&z, -5.0), [0.0, -5.0, 0.0]);
    }

    // Selection by held-out error picks a candidate and returns every case's error.
    #[test]
    fn select_scores_every_case() {
        let mut x = vec![];
        for i in 0..20 {
            for j in 0..5 {
                x.push([-2.0 + 0.25 * i as f64, -1.0 + 0.5 * j as f64, 0.0, 0.0]);
            }
        }
        let r: Vec<f64> = x.iter().map(f).collect();
        let folds = five_folds(&x, &r);
        let Selection {
            scales: s,
            nugget: g,
            k,
            errors: e,
        } = select(&folds, x.len(), f64::INFINITY, false).unwrap();
        for (i, (k, e)) in k.iter().zip(&e).enumerate() {
            assert!(((k - r[i]).exp() - 1.0 - e).abs() < 1e-15);
        }
        assert!(
            select(&folds, x.len(), 1e-9, false).is_none(),
            "no candidate that close"
        );
        assert!(SCALES.contains(&[s[0], s[1], s[2]]) && NUGGETS.contains(&g));
        assert_eq!(s[3], f64::INFINITY);
        assert_eq!(e.len(), x.len());
        let rms = (e.iter().map(|v| v * v).sum::<f64>() / e.len() as f64).sqrt();
        assert!(rms < 2e-3, "held-out RMS {rms}");
    }

    // A residual that steps across a corner (a = 0, where phi changes sign) between cases 4 %
    // of M apart: the corner coordinate separates the two sides, and the held-out error falls.
    #[test]
    fn the_corner_coordinate_follows_a_step_across_the_corner() {
        let mut x = vec![];
        let mut r = vec![];
        for i in 0..60 {
            for j in 0..4 {
                // a moves by about 1.87 per unit of ln M for point contacts.
                let t = -1.2 + 0.04 * f64::from(i) + 0.013;
                let c = -1.0 + 0.5 * f64::from(j);
                x.push([1.87 * t, c, 0.0, (t / JUMP_WIDTH).tanh()]);
                r.push(0.04 * (t / 0.005).tanh() + 0.01 * (1.5 * t).sin() + 0.005 * c);
            }
        }
        let rms = |e: &[f64]| (e.iter().map(|v| v * v).sum::<f64>() / e.len() as f64).sqrt();
        let with = select(&five_folds(&x, &r), x.len(), f64::INFINITY, true).unwrap();
        let without = select(&five_folds(&x, &r), x.len(), f64::INFINITY, false).unwrap();
        assert!(JUMP_SCALES.contains(&with.scales[3]), "{:?}", with.scales);
        let (a, b) = (rms(&with.errors), rms(&without.errors));
        assert!(
            a < 0.5 * b,
            "held-out RMS {a} with the corner coordinate, {b} without"
        );
        assert_eq!(
            candidates(true).len(),
            (1 + JUMP_SCALES.len()) * candidates(false).len()
        );
    }
}
