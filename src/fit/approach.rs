//! The approach factor g(M, D) of the point elastic-isoviscous law
//! ([`PointModel::approach`]) from the data's elastic-isoviscous cases.
//!
//! Equation: at L = 0 the point blend is H = [H_RI^r + (H_EI^-4 + H_00^-4)^(-r/4)]^(1/r) (the
//! piezoviscous bracket is dropped and s cancels), so a case's film gives its H_EI once the other
//! asymptotes are known: H_EI = [(H^r - H_RI^r)^(-4/r) - H_00^-4]^(-1/4). With H_EI = E(M, D)
//! g(M, D), E the law without g, ln g = sum_j (c_j0 + c_j1 ln D + c_j2 (ln D)^2) (1 + M)^(-p_j)
//! is linear in the c's, which are the least-squares solution over the cases at L = 0 and
//! M >= [`APPROACH_MIN_M`], where H_EI carries most of the film (H_RI/H_EI of order 0.05 at
//! D >= 0.1, about 0.35 at M = 139, D = 0.01, where the blend's form weighs more in the
//! inversion).
//!
//! Inputs: the model (its H_RI, H_00, r and the EI law E; its own approach coefficients are
//! ignored) and the samples. Output: the model with the approach coefficients set
//! ([`fit_approach`]), the ln D terms only with two D values or more, the (ln D)^2 terms with
//! three or more; g = 1 (coefficients 0) when fewer than two M values or fewer cases than
//! coefficients qualify. Invariant: g -> 1 as M -> infinity, so the EI law stays exact there
//! ([`crate::limits::point_ei`]).

use crate::fit::lsq::Sample;
use crate::fit::point_model::{approach_term, PointModel, APPROACH_M0, APPROACH_POWERS};
use nalgebra::{DMatrix, DVector};

/// The smallest M of the cases that set the approach factor.
pub const APPROACH_MIN_M: f64 = 100.0;

/// How the approach factor was fitted: the cases used and the RMS of the log residual of H_EI.
#[derive(Clone, Debug, PartialEq)]
pub struct ApproachFit {
    /// The model with the approach coefficients set.
    pub model: PointModel,
    /// The cases that set them (L = 0, M >= [`APPROACH_MIN_M`], an invertible blend), anchors
    /// included.
    pub cases: usize,
    /// RMS of ln(H_EI of the case / H_EI of the law with g); 0 when no coefficient was fitted.
    pub rms_log: f64,
}

/// The number of distinct values.
fn distinct(mut v: Vec<f64>) -> usize {
    v.sort_by(f64::total_cmp);
    v.dedup();
    v.len()
}

/// The approach factor of `model` fitted to `data` and the `anchors` (module doc).
pub fn fit_approach(model: &PointModel, data: &[Sample], anchors: &[Sample]) -> ApproachFit {
    let mut base = model.clone();
    for k in PointModel::APPROACH {
        base.x[k] = 0.0;
    }
    base.approach_m0 = 0.0;
    let m0 = if anchors.is_empty() { 0.0 } else { APPROACH_M0 };
    let r = base.x[15];
    // Each qualifying case's (M, ln D, ln(H_EI / E)).
    let rows: Vec<(f64, f64, f64)> = data
        .iter()
        .filter(|s| s.l == 0.0 && s.m >= APPROACH_MIN_M)
        .chain(anchors.iter().filter(|s| s.l == 0.0))
        .filter_map(|s| {
            let [h_ri, e, _, _] = base.asymptotes(s.m, 0.0, s.d);
            let h_00 = base.x[14].exp() / s.d;
            let iso = (s.h.powf(r) - h_ri.powf(r)).powf(-4.0 / r) - h_00.powi(-4);
            let h_ei = iso.powf(-0.25);
            (h_ei.is_finite() && h_ei > 0.0).then(|| (s.m, s.d.ln(), (h_ei / e).ln()))
        })
        .collect();
    let n_d = distinct(rows.iter().map(|r| r.1).collect());
    let terms: Vec<usize> = PointModel::APPROACH
        .iter()
        .copied()
        .filter(|k| (k - PointModel::APPROACH[0]) / 3 < 2 || !anchors.is_empty())
        .filter(|k| match (k - PointModel::APPROACH[0]) % 3 {
            0 => true,
            1 => n_d >= 2,
            _ => n_d >= 3,
        })
        .collect();
    let none = ApproachFit {
        model: base.clone(),
        cases: rows.len(),
        rms_log: 0.0,
    };
    if distinct(rows.iter().map(|r| r.0).collect()) < 2 || rows.len() <= terms.len() {
        return none;
    }
    let basis = |k: usize, m: f64, ln_d: f64| {
        let j = (k - PointModel::APPROACH[0]) / 3;
        let n = (k - PointModel::APPROACH[0]) % 3;
        ln_d.powi(n as i32) * approach_term(m, m0, APPROACH_POWERS[j])
    };
    let a = DMatrix::from_fn(rows.len(), terms.len(), |i, c| {
        basis(terms[c], rows[i].0, rows[i].1)
    });
    let y = DVector::from_iterator(rows.len(), rows.iter().map(|r| r.2));
    let Ok(c) = a.clone().svd(true, true).solve(&y, 1e-12) else {
        return none;
    };
    let mut out = base;
    out.approach_m0 = m0;
    for (t, v) in terms.iter().zip(c.iter()) {
        out.x[*t] = *v;
    }
    let resid = &a * &c - &y;
    ApproachFit {
        model: out,
        cases: rows.len(),
        rms_log: (resid.norm_squared() / rows.len() as f64).sqrt(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Films made by a model with a known approach factor are fitted back exactly: the
    /// inversion of the L = 0 blend and the linear least squares are consistent; the third power
    /// only with anchors.
    #[test]
    fn a_known_approach_factor_is_recovered() {
        let mut truth = PointModel::nvm();
        truth.ei_exact = true;
        let c = [0.3, -0.4, -0.05, -0.6, 0.25, 0.04, 0.0, 0.0, 0.0];
        truth.x[16..].copy_from_slice(&c);
        let sample = |truth: &PointModel, m: f64, l: f64, d: f64| Sample {
            m,
            l,
            d,
            h: truth.eval(m, l, d),
        };
        let mut data = vec![];
        for m in [50.0, 139.0, 373.0, 1000.0, 3162.0] {
            for d in [0.01, 0.1, 0.5, 1.0] {
                for l in [0.0, 5.0] {
                    data.push(sample(&truth, m, l, d));
                }
            }
        }
        let f = fit_approach(&truth, &data, &[]);
        assert_eq!(f.cases, 16, "L = 0 and M >= 100 only");
        assert_eq!(f.model.approach_m0, 0.0, "M_g = M without anchors");
        for (k, want) in c.iter().enumerate() {
            assert!(
                (f.model.x[16 + k] - want).abs() < 1e-8,
                "{k}: {:?}",
                f.model.x
            );
        }
        assert!(f.rms_log < 1e-10);
        // With the third power, anchors beyond the data pin it.
        let mut three = truth.clone();
        three.x[22..].copy_from_slice(&[0.5, 0.1, -0.02]);
        three.approach_m0 = APPROACH_M0;
        let data3: Vec<Sample> = data.iter().map(|s| sample(&three, s.m, s.l, s.d)).collect();
        let anchors: Vec<Sample> = [0.01, 0.1, 0.5, 1.0]
            .iter()
            .flat_map(|&d| [1e4, 3e4].map(|m| sample(&three, m, 0.0, d)))
            .collect();
        let f3 = fit_approach(&three, &data3, &anchors);
        assert_eq!(f3.cases, 24);
        assert_eq!(f3.model.approach_m0, APPROACH_M0);
        for k in 16..25 {
            assert!(
                (f3.model.x[k] - three.x[k]).abs() < 1e-6,
                "{k}: {:?}",
                f3.model.x
            );
        }
        let without = fit_approach(&three, &data3, &[]);
        assert!(without.model.x[22..].iter().all(|v| *v == 0.0));
        assert!(without.rms_log > 1e-6);
        // One D: only the constant terms; one M: none.
        let one_d: Vec<Sample> = data.iter().copied().filter(|s| s.d == 0.5).collect();
        let g = fit_approach(&truth, &one_d, &[]);
        assert_eq!(g.model.x[17], 0.0);
        assert_eq!(g.model.x[18], 0.0);
        assert!(g.model.x[16] != 0.0 && g.model.x[19] != 0.0);
        let one_m: Vec<Sample> = data.iter().copied().filter(|s| s.m == 373.0).collect();
        let h = fit_approach(&truth, &one_m, &[]);
        assert!(h.model.x[16..].iter().all(|v| *v == 0.0));
    }
}
