//! The line film-thickness model fitted to the sweeps: Moes' (1992) blend of four power-law
//! asymptotes, every exponent, the blending powers and the blending-exponent laws a parameter
//! (which of them the fit frees is the report's choice: `crate::report`).
//!
//! H_RI = c_RI / M (fixed: the exact rigid-isoviscous constant of the film, 2.4475 for H_c and
//! H_min, 3 for H_pm), H_EI = a M^alpha, H_RP = b L^beta, H_EP = d M^gamma L^delta,
//!
//! H = [ (H_RI^p + H_EI^p)^(s/p) + (H_RP^-q + H_EP^-q)^(-s/q) ]^(1/s),
//! s = s0 + s1 exp(-s2 H_EI/H_RI), p = p0 + p1 exp(-s2 H_EI/H_RI);
//!
//! at L = 0 the piezoviscous bracket is dropped. Parameters: the vector of [`PARAM_NAMES`]
//! (constants as logarithms) and c_RI. The p law (p1 = 0 is Moes) lets the isoviscous blend
//! sharpen through the RI-EI transition the way Moes' s law does for the outer blend: at L = 0 the
//! s law cancels and a constant p cannot follow the numerics near M = 1-3 (figures:
//! docs/validation.md, "Earlier fit changes"). Moes 1992 is [`LineModel::moes`]: a = 2.621,
//! alpha = -1/5, b = 1.287, beta = 2/3, d = 1.311, gamma = -1/8, delta = 3/4, p = 7/3, q = 7/2,
//! s0 = 7/5, s1 = 8/5, s2 = 2, p1 = 0, c_RI = 3 (docs/physics.md section 4).

use serde::{Deserialize, Serialize};

/// A film formula with a flat parameter vector, as the least-squares fit sees it (plain data,
/// shared across the threads that fit the held-out folds).
pub trait FilmModel: Clone + Send + Sync {
    /// All parameters (fixed and free).
    fn x(&self) -> &[f64];
    /// All parameters, mutable (the fit sets the free ones through this).
    fn x_mut(&mut self) -> &mut [f64];
    /// The film H at (M, L, D); line models ignore D.
    fn film(&self, m: f64, l: f64, d: f64) -> f64;
    /// The four asymptotes [H_RI, H_EI, H_RP, H_EP] at (M, L, D) (the last two 0 at L = 0).
    fn asymptotes(&self, m: f64, l: f64, d: f64) -> [f64; 4];
}

impl FilmModel for LineModel {
    fn x(&self) -> &[f64] {
        &self.x
    }
    fn x_mut(&mut self) -> &mut [f64] {
        &mut self.x
    }
    fn film(&self, m: f64, l: f64, _d: f64) -> f64 {
        self.eval(m, l)
    }
    fn asymptotes(&self, m: f64, l: f64, _d: f64) -> [f64; 4] {
        LineModel::asymptotes(self, m, l)
    }
}

/// Names of the fitted parameters, in vector order.
pub const PARAM_NAMES: [&str; 13] = [
    "ln_a_EI", "alpha_EI", "ln_b_RP", "beta_RP", "ln_d_EP", "gamma_EP", "delta_EP", "p", "q", "s0",
    "s1", "s2", "p1",
];

/// A line-contact film model: the fixed rigid-isoviscous constant `c_ri` and the 13 parameters
/// `x` of [`PARAM_NAMES`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LineModel {
    /// The rigid-isoviscous constant c_RI of H_RI = c_RI / M (held, never fitted).
    pub c_ri: f64,
    /// The parameters of [`PARAM_NAMES`], in that order (constants a, b, d as logarithms).
    pub x: [f64; 13],
}

impl LineModel {
    /// Indices of the seven asymptote parameters (EI, RP, EP); the rest are the blend's.
    pub const ASYMPTOTES: [usize; 7] = [0, 1, 2, 3, 4, 5, 6];

    /// Moes 1992 (central film; `c_ri` = 3 is his flux-thickness constant).
    pub fn moes() -> Self {
        LineModel {
            c_ri: 3.0,
            x: [
                2.621f64.ln(),
                -0.2,
                1.287f64.ln(),
                2.0 / 3.0,
                1.311f64.ln(),
                -0.125,
                0.75,
                7.0 / 3.0,
                3.5,
                1.4,
                1.6,
                2.0,
                0.0,
            ],
        }
    }

    /// The four asymptotes [H_RI, H_EI, H_RP, H_EP] at (M, L).
    pub fn asymptotes(&self, m: f64, l: f64) -> [f64; 4] {
        let x = &self.x;
        [
            self.c_ri / m,
            x[0].exp() * m.powf(x[1]),
            x[2].exp() * l.powf(x[3]),
            x[4].exp() * m.powf(x[5]) * l.powf(x[6]),
        ]
    }

    /// The blended film H(M, L).
    pub fn eval(&self, m: f64, l: f64) -> f64 {
        let x = &self.x;
        let [h_ri, h_ei, h_rp, h_ep] = self.asymptotes(m, l);
        let decay = (-x[11] * h_ei / h_ri).exp();
        let (p, q) = (x[7] + x[12] * decay, x[8]);
        let s = x[9] + x[10] * decay;
        let iso = (h_ri.powf(p) + h_ei.powf(p)).powf(s / p);
        let piezo = if l > 0.0 {
            (h_rp.powf(-q) + h_ep.powf(-q)).powf(-s / q)
        } else {
            0.0
        };
        (iso + piezo).powf(1.0 / s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moes_parameters_reproduce_the_published_formula() {
        let m = LineModel::moes();
        for (mm, l) in [(20.0, 10.0), (5.0, 0.0), (1000.0, 20.0), (1.0, 5.0)] {
            let a = m.eval(mm, l);
            let b = crate::model::formulas::moes_line_hc(mm, l);
            assert!((a / b - 1.0).abs() < 1e-12, "M={mm} L={l}: {a} vs {b}");
        }
    }
}
