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

use crate::fit::correction::Coordinates;
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

fn kernel(x: &[f64; 3], y: &[f64; 3], s: &[f64; 3]) -> f64 {
    let d2: f64 = (0..3).map(|i| ((x[i] - y[i]) / s[i]).powi(2)).sum();
    if d2.is_finite() {
        matern52(d2.sqrt())
    } else {
        0.0
    }
}

impl Kriging {
    /// k at the coordinates of the law's asymptotes `asym` and D.
    pub fn log_factor(&self, asym: [f64; 4], d: f64) -> f64 {
        self.at(&point(&Coordinates::new(asym, d), self.c_floor))
    }

    /// k at kriging coordinates `x` (0 where x is not finite: an asymptotic limit).
    pub fn at(&self, x: &[f64; 3]) -> f64 {
        self.centres
            .iter()
            .zip(&self.weights)
            .map(|(c, w)| w * kernel(x, c, &self.scales))
            .sum()
    }
}

/// The kriging residual through `residuals` at `centres`; None when the system is not positive
/// definite or a weight is not finite.
pub fn fit(
    centres: &[[f64; 3]],
    residuals: &[f64],
    scales: [f64; 3],
    nugget: f64,
    c_floor: f64,
) -> Option<Kriging> {
    let n = centres.len();
    let k = DMatrix::from_fn(n, n, |i, j| {
        kernel(&centres[i], &centres[j], &scales) + if i == j { nugget } else { 0.0 }
    });
    let w = k.cholesky()?.solve(&DVector::from_column_slice(residuals));
    if !w.iter().all(|v| v.is_finite()) {
        return None;
    }
    Some(Kriging {
        scales,
        c_floor,
        nugget,
        centres: centres.to_vec(),
        weights: w.iter().copied().collect(),
    })
}

/// One fold of the cross-validation: the law fitted without the fold, its log residuals at its
/// training cases and at the fold's cases (data index, coordinates, residual ln(H / H_law)).
pub struct Fold {
    /// Training cases: kriging coordinates and residuals.
    pub train: Vec<([f64; 3], f64)>,
    /// The fold's cases: data index, kriging coordinates, residual.
    pub test: Vec<(usize, [f64; 3], f64)>,
}

/// What [`select`] returns: the scales and nugget kept and, per data case (NaN for a case in no
/// fold's test set), the held-out k and relative error exp(k - r) - 1.
pub struct Selection {
    /// Length scales (s_a, s_c, s_D).
    pub scales: [f64; 3],
    /// Nugget.
    pub nugget: f64,
    /// Each case's k, from the fit without its fold.
    pub k: Vec<f64>,
    /// Each case's held-out relative error (formula over data, less 1).
    pub errors: Vec<f64>,
}

/// The scales and nugget of the best held-out RMS among the candidates whose largest held-out
/// |error| is at most `max_bound` (None when no candidate qualifies). Candidates in parallel,
/// compared in order: the same at any thread count.
pub fn select(folds: &[Fold], c_floor: f64, cases: usize, max_bound: f64) -> Option<Selection> {
    let candidates: Vec<([f64; 3], f64)> = SCALES
        .iter()
        .flat_map(|s| NUGGETS.iter().map(move |g| (*s, *g)))
        .collect();
    let scored: Vec<Option<(f64, Selection)>> = candidates
        .par_iter()
        .map(|&(scales, nugget)| {
            let (mut k, mut errors) = (vec![f64::NAN; cases], vec![f64::NAN; cases]);
            for f in folds {
                let (x, r): (Vec<[f64; 3]>, Vec<f64>) = f.train.iter().copied().unzip();
                let fitted = fit(&x, &r, scales, nugget, c_floor)?;
                for (i, z, r) in &f.test {
                    k[*i] = fitted.at(z);
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

    fn f(x: &[f64; 3]) -> f64 {
        0.03 * (0.8 * x[0]).sin() * (-0.2 * x[1] * x[1]).exp() + 0.01 * x[2]
    }

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
                    ]);
                }
            }
        }
        let r: Vec<f64> = x.iter().map(f).collect();
        let k = fit(&x, &r, [1.5, 1.5, 2.0], 1e-8, -10.0).unwrap();
        for z in &x {
            assert!((k.at(z) - f(z)).abs() < 1e-5, "{z:?}");
        }
        let mut worst: f64 = 0.0;
        for i in 0..12 {
            for j in 0..6 {
                let z = [-2.75 + 0.5 * i as f64, -1.25 + 0.5 * j as f64, -1.05];
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
        let x = vec![[0.0, 0.0, 0.0], [1.0, 0.5, 0.0], [2.0, 1.0, -0.5]];
        let k = fit(&x, &[0.02, -0.01, 0.015], [2.0, 1.0, 2.0], 1e-3, -5.0).unwrap();
        for far in [
            [1e3, 0.0, 0.0],
            [-1e3, 0.0, 0.0],
            [0.0, 1e3, 0.0],
            [f64::INFINITY, 0.0, 0.0],
            [0.0, f64::INFINITY, 0.0],
            [0.0, 0.0, f64::NEG_INFINITY],
        ] {
            assert_eq!(k.at(&far), 0.0, "{far:?}");
        }
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
                x.push([-2.0 + 0.25 * i as f64, -1.0 + 0.5 * j as f64, 0.0]);
            }
        }
        let r: Vec<f64> = x.iter().map(f).collect();
        let folds: Vec<Fold> = (0..5)
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
            .collect();
        let Selection {
            scales: s,
            nugget: g,
            k,
            errors: e,
        } = select(&folds, -10.0, x.len(), f64::INFINITY).unwrap();
        for (i, (k, e)) in k.iter().zip(&e).enumerate() {
            assert!(((k - r[i]).exp() - 1.0 - e).abs() < 1e-15);
        }
        assert!(
            select(&folds, -10.0, x.len(), 1e-9).is_none(),
            "no candidate that close"
        );
        assert!(SCALES.contains(&s) && NUGGETS.contains(&g));
        assert_eq!(e.len(), x.len());
        let rms = (e.iter().map(|v| v * v).sum::<f64>() / e.len() as f64).sqrt();
        assert!(rms < 2e-3, "held-out RMS {rms}");
    }
}
