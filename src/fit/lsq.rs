//! The least-squares problem in log space, solved by Levenberg-Marquardt (`levenberg-marquardt`
//! on nalgebra), with parameter uncertainties from the Jacobian: cov = sigma^2 (J^T J)^-1,
//! sigma^2 = sum r^2 / (m - n). Generic over [`FilmModel`]: the line and point models share it.

use crate::fit::error::FitError;
use crate::fit::model::FilmModel;
#[cfg(test)]
use crate::fit::model::LineModel;
use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra::storage::Owned;
use nalgebra::{DMatrix, DVector, Dyn};

/// One data point: (M, L, D) and the film value to fit (`d` is ignored by line models).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Moes' load parameter M (positive).
    pub m: f64,
    /// Moes' lubricant parameter L (non-negative).
    pub l: f64,
    /// Ellipticity D = Rx/Ry (1 for a line contact).
    pub d: f64,
    /// The film H to fit, in Moes units (positive, finite).
    pub h: f64,
}

const PENALTY: f64 = 1e3;

struct Problem<'a, Mo: FilmModel> {
    data: &'a [Sample],
    model: Mo,
    /// Indices of the free parameters in `model.x`.
    free: Vec<usize>,
}

impl<Mo: FilmModel> Problem<'_, Mo> {
    /// Log residuals; where the model is not finite (a trial step far outside the physical
    /// range) a large finite penalty steers the search back.
    fn residuals_at(&self, model: &Mo) -> DVector<f64> {
        DVector::from_iterator(
            self.data.len(),
            self.data.iter().map(|s| {
                let r = model.film(s.m, s.l, s.d).ln() - s.h.ln();
                if r.is_finite() {
                    r
                } else {
                    PENALTY
                }
            }),
        )
    }
}

impl<Mo: FilmModel> LeastSquaresProblem<f64, Dyn, Dyn> for Problem<'_, Mo> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, x: &DVector<f64>) {
        for (k, v) in self.free.iter().zip(x.iter()) {
            self.model.x_mut()[*k] = *v;
        }
    }

    fn params(&self) -> DVector<f64> {
        DVector::from_iterator(
            self.free.len(),
            self.free.iter().map(|&k| self.model.x()[k]),
        )
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        let r = self.residuals_at(&self.model);
        r.iter().all(|v| v.is_finite()).then_some(r)
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        let mut jac = DMatrix::zeros(self.data.len(), self.free.len());
        for (col, &k) in self.free.iter().enumerate() {
            let step = 1e-6 * (1.0 + self.model.x()[k].abs());
            let mut plus = self.model.clone();
            let mut minus = self.model.clone();
            plus.x_mut()[k] += step;
            minus.x_mut()[k] -= step;
            let d = (self.residuals_at(&plus) - self.residuals_at(&minus)) / (2.0 * step);
            if d.iter().any(|v| !v.is_finite()) {
                return None;
            }
            jac.set_column(col, &d);
        }
        Some(jac)
    }
}

/// Outcome of a fit.
#[derive(Clone, Debug, PartialEq)]
pub struct LsqFit<Mo> {
    /// The fitted model: the free parameters at the minimum, the others as given.
    pub model: Mo,
    /// One-sigma uncertainties of all parameters (0 for fixed ones, NaN where J^T J is singular).
    pub sigma: Vec<f64>,
    /// RMS of the log residuals.
    pub rms_log: f64,
    /// Whether Levenberg-Marquardt reported a successful termination.
    pub converged: bool,
    /// Residual evaluations counted by Levenberg-Marquardt (not those inside the
    /// finite-difference Jacobian).
    pub evaluations: usize,
}

/// Fit the parameters of `start` listed in `free` to `data` (needs more points than free
/// parameters); the others stay as they are. The residuals are ln(model) - ln(h), so the fit
/// minimises relative errors.
///
/// Errors: [`FitError::TooFewPoints`], [`FitError::BadData`] (M not positive, L negative, or a
/// film not positive and finite) and [`FitError::NotFinite`] (the fitted model not finite on the
/// data).
pub fn fit<Mo: FilmModel>(
    data: &[Sample],
    start: &Mo,
    free: &[usize],
) -> Result<LsqFit<Mo>, FitError> {
    let n = free.len();
    if data.len() <= n {
        return Err(FitError::TooFewPoints {
            points: data.len(),
            params: n,
        });
    }
    if data
        .iter()
        .any(|s| !(s.m > 0.0 && s.l >= 0.0 && s.h > 0.0 && s.h.is_finite()))
    {
        return Err(FitError::BadData);
    }
    let problem = Problem {
        data,
        model: start.clone(),
        free: free.to_vec(),
    };
    let (problem, report) = LevenbergMarquardt::new()
        .with_patience(400)
        .minimize(problem);
    let r = problem.residuals().ok_or(FitError::NotFinite)?;
    let m = data.len();
    let s2 = r.norm_squared() / (m - n) as f64;
    let mut sigma = vec![0.0; start.x().len()];
    let diag: Vec<f64> = match problem
        .jacobian()
        .and_then(|j| (j.transpose() * &j).try_inverse())
    {
        Some(cov) => (0..n).map(|k| (s2 * cov[(k, k)]).abs().sqrt()).collect(),
        None => vec![f64::NAN; n],
    };
    for (&k, d) in free.iter().zip(diag) {
        sigma[k] = d;
    }
    Ok(LsqFit {
        model: problem.model,
        sigma,
        rms_log: (r.norm_squared() / m as f64).sqrt(),
        converged: report.termination.was_successful(),
        evaluations: report.number_of_evaluations,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovers_known_parameters_from_synthetic_data() {
        // Data generated from a perturbed Moes model; start from Moes; recover the truth.
        let mut truth = LineModel::moes();
        truth.c_ri = 2.4475;
        truth.x[0] += 0.05;
        truth.x[1] -= 0.01;
        truth.x[6] += 0.02;
        truth.x[3] -= 0.02;
        let mut data = vec![];
        for i in 0..14 {
            let m = 10f64.powf(i as f64 * 3.3 / 13.0);
            for l in [0.0, 2.0, 5.0, 10.0, 15.0, 20.0] {
                data.push(Sample {
                    m,
                    l,
                    d: 1.0,
                    h: truth.eval(m, l),
                });
            }
        }
        let mut start = LineModel::moes();
        start.c_ri = 2.4475;
        let f = fit(&data, &start, &LineModel::ASYMPTOTES).unwrap();
        let worst = data
            .iter()
            .map(|s| (f.model.eval(s.m, s.l) / s.h - 1.0).abs())
            .fold(0.0f64, f64::max);
        assert!(worst < 1e-4, "worst relative error {worst}");
        assert!((f.model.x[1] - truth.x[1]).abs() < 1e-3, "{:?}", f.model.x);
    }

    #[test]
    fn too_few_points_is_an_error() {
        let data = vec![
            Sample {
                m: 1.0,
                l: 1.0,
                d: 1.0,
                h: 1.0
            };
            5
        ];
        assert!(fit(&data, &LineModel::moes(), &LineModel::ASYMPTOTES).is_err());
    }
}
