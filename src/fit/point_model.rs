//! The point-contact (elliptic) film model fitted to point sweeps: the Nijenbanning-Venner-Moes
//! (1994) blend of four asymptotes, with NVM's D dependence times a free power-law correction.
//!
//! With D = Rx/Ry and each D factor normalised to 1 at D = 1
//! (c(D) = 1 + 0.006 ln D + 0.63 D^(4/7)):
//!
//! H_RI = c_RI  f_RI(D) D^e_RI M^-2,            f_RI = [(1 + a D^p)/(1 + a)]^q / D
//! H_EI = a M^alpha f_EI(D) D^e_EI g(M, D),     f_EI = [c(D)/c(1)]^(-14/25) D^(-1/15) (NVM)
//!                                              or k^(2/15) [4 E(m)/(pi (1 + D))]^(2/3) (exact)
//! g = exp(sum_j (c_j0 + c_j1 ln D + c_j2 (ln D)^2) (1 + M_g)^(-p_j)),  p = 4/15, 8/15, 12/15,
//! M_g = (M^2 + M_0^2)^(1/2), M_0 = 100 with anchors and 0 without,
//! H_RP = b L^beta  f_RP(D) D^e_RP,             f_RP = [(1 + 0.691 D)/1.691]^(-2/3) (NVM)
//!                                              or f_RI(D) D psi(D) (the solver's)
//! H_EP = d M^gamma L^delta f_EP(D) D^e_EP,     f_EP = [c(D)/c(1)]^(-7/20) D^(-1/24)
//! H_00 = c_00 / D,
//! H = { [H_RI^r + (H_EI^-4 + H_00^-4)^(-r/4)]^(s/r) + (H_RP^-8 + H_EP^-8)^(-s/8) }^(1/s),
//! s = s0 (1 + exp(-s1 H_EI/H_RI));
//!
//! at L = 0 the piezoviscous bracket is dropped. The approach factor g (1 in NVM's form, all c_jk =
//! 0) is the slow approach of the solver's films to the exact EI limit, which vanishes as M ->
//! infinity (corrections of order (l/b)^(1/2) ~ M^(-4/15), its square and cube, l the inlet
//! length; [`crate::limits::point_ei`]); it is fitted only where H_EI is held at that limit, to
//! cases at M >= 100 and, given anchors (limit solves beyond the data,
//! [`crate::limits::anchors`]), to them with the third power, M_g then holding g near its value
//! at M_0 below M_0, where no case sets it. Parameters:
//! the vector of [`POINT_PARAM_NAMES`] (constants as logarithms), the three constants (a, p, q) of
//! f_RI and, when the RP law is the solver's, the three of psi(D) = [(1 + a D^p)/(1 + a)]^q
//! ([`crate::limits::rigid_rp`]); none of them fitted. [`PointModel::nvm`] (all e_i = 0, NVM's
//! f_RI: a = 0.796, p = 14/15, q = -15/7, c_00 = 1.8, r = 3/2 and NVM's constants) reproduces NVM
//! 1994 exactly (docs/physics.md section 4); the fit frees c_00 and r with the other blend
//! parameters once the data are many (as the line model frees its blending powers).
//!
//! Why this D form: NVM's D factors carry the Hertzian geometry (the contact ellipse and the load per unit
//! length at y = 0), which is what makes the elliptic EI and EP asymptotes tend to the line ones as
//! D -> 0; the free exponent e_i only corrects the residual D trend over the swept D range. The
//! M^-2 of H_RI is exact for a rigid isoviscous point contact (the pressure scales with 1/H^2 at
//! fixed load); the fits hold its constant at the solver's own domain-extrapolated value
//! ([`crate::limits::rigid_point`]) and its D factor at the solver's own, exact in the slender
//! limit ([`crate::limits::rigid_d_factor`]; e_RI = 0), since the fitted rows barely see the
//! rigid-isoviscous regime; the fits hold the exponents of H_EI and H_EP at asymptotic theory's
//! (NVM's), the H_pm fit (and with `ehlmap fit --point-ei-limit` the H_c fit) H_EI at its limit
//! with the exact f_EI (`ei_exact`; [`crate::limits::point_ei`]) times g, and H_RP at the solver's
//! rigid-piezoviscous limit, beta = 2/3, b = c_RI pi(1), f_RP = f_RI(D) D psi(D), e_RP = 0
//! ([`crate::limits::rigid_rp`]). (Fit figures behind these choices: docs/validation.md, "Fit: the
//! nightly sweeps" and "The held asymptotes".)

use crate::fit::model::FilmModel;
use crate::limits::point_ei::ei_d_factor;
use crate::limits::rigid_rp::psi;
use serde::{Deserialize, Serialize};

/// Names of the parameters, in vector order.
pub const POINT_PARAM_NAMES: [&str; POINT_PARAMS] = [
    "ln_c_RI", "e_RI", "ln_a_EI", "alpha_EI", "e_EI", "ln_b_RP", "beta_RP", "e_RP", "ln_d_EP",
    "gamma_EP", "delta_EP", "e_EP", "s0", "s1", "ln_c_00", "r", "g1", "g1_lnD", "g1_lnD2", "g2",
    "g2_lnD", "g2_lnD2", "g3", "g3_lnD", "g3_lnD2",
];

/// The number of point parameters: the NVM form's 16, then the 9 of the approach factor g.
pub const POINT_PARAMS: usize = 25;

/// The powers p_j of the approach factor's terms (1 + M_g)^(-p_j) (module doc): 4/15, 8/15 and
/// 12/15, the first three powers of (l/b)^(1/2) ~ H^(1/3) in Hertzian units (l the inlet length,
/// b the semi-axis along rolling; [`crate::limits::point_ei`]).
pub const APPROACH_POWERS: [f64; 3] = [4.0 / 15.0, 8.0 / 15.0, 12.0 / 15.0];

/// M_0 of the approach factor's M_g = (M^2 + M_0^2)^(1/2) when it has anchors (module doc): the
/// smallest M of the cases that set it ([`crate::fit::approach`]), so that g is held near its
/// value there below it, where no case fits it.
pub const APPROACH_M0: f64 = 100.0;

/// The approach factor's term (1 + M_g)^(-p), M_g = (M^2 + M_0^2)^(1/2) (module doc).
pub fn approach_term(m: f64, m0: f64, p: f64) -> f64 {
    (1.0 + m.hypot(m0)).powf(-p)
}

/// A point-contact film model: the parameters of [`POINT_PARAM_NAMES`] (module doc).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PointModel {
    /// The parameters of [`POINT_PARAM_NAMES`], in that order (constants c_RI, a, b, d, c_00 as
    /// logarithms). Stored models of the NVM form's 16 read back with g = 1 (its 9 zero), those of
    /// 22 (two powers of g) with the third power's 3 zero.
    #[serde(deserialize_with = "point_params")]
    pub x: [f64; POINT_PARAMS],
    /// The constants (a, p, q) of f_RI (not fitted; NVM's when absent from a stored model).
    #[serde(default = "nvm_ri_shape")]
    pub ri_shape: [f64; 3],
    /// The constants (a, p, q) of psi(D) when f_RP is the solver's, f_RI(D) D psi(D)
    /// ([`crate::limits::rigid_rp`]); None for NVM's f_RP (and in stored models before it).
    #[serde(default)]
    pub rp_shape: Option<[f64; 3]>,
    /// Whether f_EI is the exact D factor of the local inlet analysis
    /// ([`crate::limits::point_ei::ei_d_factor`]; the H_pm fit, and H_c's with `ehlmap fit
    /// --point-ei-limit`) instead of NVM's (false in stored models before it).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub ei_exact: bool,
    /// M_0 of the approach factor's M_g (module doc): [`APPROACH_M0`] when it was fitted with
    /// anchors, else 0 (M_g = M; and in stored models before it).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub approach_m0: f64,
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

/// The parameter vector from a stored model: [`POINT_PARAMS`] values, the NVM form's 16 (the
/// approach factor's then 0) or the 22 of an approach factor with two powers (the third's 0).
fn point_params<'de, De: serde::Deserializer<'de>>(
    de: De,
) -> Result<[f64; POINT_PARAMS], De::Error> {
    let v: Vec<f64> = Vec::deserialize(de)?;
    if ![16, 22, POINT_PARAMS].contains(&v.len()) {
        return Err(serde::de::Error::invalid_length(
            v.len(),
            &"16, 22 or 25 point parameters",
        ));
    }
    let mut x = [0.0; POINT_PARAMS];
    x[..v.len()].copy_from_slice(&v);
    Ok(x)
}

/// NVM's (a, p, q) of f_RI.
pub fn nvm_ri_shape() -> [f64; 3] {
    [0.796, 14.0 / 15.0, -15.0 / 7.0]
}

/// f_RI(D) = [(1 + a D^p)/(1 + a)]^q / D for the constants (a, p, q): 1 at D = 1.
pub fn ri_d_factor(shape: [f64; 3], d: f64) -> f64 {
    psi(shape, d) / d
}

fn c_nvm(d: f64) -> f64 {
    1.0 + 0.006 * d.ln() + 0.63 * d.powf(4.0 / 7.0)
}

/// NVM's D factors [f_RI, f_EI, f_RP, f_EP], each 1 at D = 1.
pub fn nvm_d_factors(d: f64) -> [f64; 4] {
    let c = c_nvm(d) / 1.63;
    [
        ri_d_factor(nvm_ri_shape(), d),
        c.powf(-14.0 / 25.0) * d.powf(-1.0 / 15.0),
        ((1.0 + 0.691 * d) / 1.691).powf(-2.0 / 3.0),
        c.powf(-7.0 / 20.0) * d.powf(-1.0 / 24.0),
    ]
}

impl PointModel {
    /// The fitted asymptote parameters: the constants and D corrections of H_EI and H_EP, whose
    /// exponents are held at asymptotic theory's (EI M^(-2/15), EP M^(-1/12) L^(3/4); NVM's
    /// values, the start). H_RI is held: c_RI at the solver's domain-extrapolated rigid value
    /// ([`crate::limits::rigid_point`]), its D factor at the solver's
    /// ([`crate::limits::rigid_d_factor`]) and its D correction e_RI at 0; so is H_RP, at the
    /// solver's rigid-piezoviscous limit ([`crate::limits::rigid_rp`]).
    pub const ASYMPTOTES: [usize; 4] = [2, 4, 8, 11];
    /// Indices of the D-correction exponents (held at 0 when the data have a single D).
    pub const D_EXPONENTS: [usize; 4] = [1, 4, 7, 11];
    /// Indices of the piezoviscous parameters (held when the data have no L > 0).
    pub const PIEZO: [usize; 7] = [5, 6, 7, 8, 9, 10, 11];

    /// NVM 1994 as a parameter vector.
    pub fn nvm() -> Self {
        PointModel {
            x: [
                (145.0 * 1.796f64.powf(-15.0 / 7.0)).ln(),
                0.0,
                (3.18 * 1.63f64.powf(-14.0 / 25.0)).ln(),
                -2.0 / 15.0,
                0.0,
                (1.29 * 1.691f64.powf(-2.0 / 3.0)).ln(),
                2.0 / 3.0,
                0.0,
                (1.48 * 1.63f64.powf(-7.0 / 20.0)).ln(),
                -1.0 / 12.0,
                0.75,
                0.0,
                1.5,
                1.2,
                1.8f64.ln(),
                1.5,
                0.0,
                0.0,
                0.0,
                0.0,
                0.0,
                0.0,
                0.0,
                0.0,
                0.0,
            ],
            ri_shape: nvm_ri_shape(),
            rp_shape: None,
            ei_exact: false,
            approach_m0: 0.0,
        }
    }

    /// Indices of the approach factor's coefficients (c_j0, c_j1, c_j2 for each of
    /// [`APPROACH_POWERS`]; 0 in NVM's form).
    pub const APPROACH: [usize; 9] = [16, 17, 18, 19, 20, 21, 22, 23, 24];

    /// The approach factor g(M, D) = exp(sum_j (c_j0 + c_j1 ln D + c_j2 (ln D)^2) (1 + M_g)^(-p_j))
    /// of H_EI (module doc, [`approach_term`]): 1 as M -> infinity, bounded as M -> 0.
    pub fn approach(&self, m: f64, d: f64) -> f64 {
        let ln_d = d.ln();
        let c = &self.x[Self::APPROACH[0]..];
        let sum: f64 = APPROACH_POWERS
            .iter()
            .enumerate()
            .map(|(j, p)| {
                (c[3 * j] + ln_d * (c[3 * j + 1] + ln_d * c[3 * j + 2]))
                    * approach_term(m, self.approach_m0, *p)
            })
            .sum();
        sum.exp()
    }

    /// The four asymptotes [H_RI, H_EI, H_RP, H_EP] at (M, L, D).
    pub fn asymptotes(&self, m: f64, l: f64, d: f64) -> [f64; 4] {
        let x = &self.x;
        let mut f = nvm_d_factors(d);
        f[0] = ri_d_factor(self.ri_shape, d);
        // f_RP: NVM's, or the solver's f_RI(D) D psi(D) when `rp_shape` is set.
        if let Some(s) = self.rp_shape {
            f[2] = f[0] * d * psi(s, d);
        }
        if self.ei_exact {
            f[1] = ei_d_factor(d);
        }
        [
            x[0].exp() * f[0] * d.powf(x[1]) / (m * m),
            x[2].exp() * m.powf(x[3]) * f[1] * d.powf(x[4]) * self.approach(m, d),
            x[5].exp() * l.powf(x[6]) * f[2] * d.powf(x[7]),
            x[8].exp() * m.powf(x[9]) * l.powf(x[10]) * f[3] * d.powf(x[11]),
        ]
    }

    /// The blended film H(M, L, D).
    pub fn eval(&self, m: f64, l: f64, d: f64) -> f64 {
        let x = &self.x;
        let [h_ri, h_ei, h_rp, h_ep] = self.asymptotes(m, l, d);
        let h_00 = x[14].exp() / d;
        let s = x[12] * (1.0 + (-x[13] * h_ei / h_ri).exp());
        let r = x[15];
        let ei = (h_ei.powi(-4) + h_00.powi(-4)).powf(-r / 4.0);
        let iso = (h_ri.powf(r) + ei).powf(s / r);
        let piezo = if l > 0.0 {
            (h_rp.powi(-8) + h_ep.powi(-8)).powf(-s / 8.0)
        } else {
            0.0
        };
        (iso + piezo).powf(1.0 / s)
    }

    /// Parameters in a physical range: film falling with M in both elastic asymptotes, rising
    /// with L, a positive blending exponent.
    pub fn physical(&self) -> bool {
        let x = &self.x;
        x[3] < 0.0
            && x[9] < 0.0
            && x[6] > 0.0
            && x[10] > 0.0
            && x[12] > 0.3
            && x[13] > 0.0
            && x[15] > 0.3
            && x.iter().all(|v| v.abs() < 50.0)
    }
}

impl FilmModel for PointModel {
    fn x(&self) -> &[f64] {
        &self.x
    }
    fn x_mut(&mut self) -> &mut [f64] {
        &mut self.x
    }
    fn film(&self, m: f64, l: f64, d: f64) -> f64 {
        self.eval(m, l, d)
    }
    fn asymptotes(&self, m: f64, l: f64, d: f64) -> [f64; 4] {
        PointModel::asymptotes(self, m, l, d)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::formulas::{nvm_point_asymptotes, nvm_point_hc};

    #[test]
    fn nvm_parameters_reproduce_the_published_formula() {
        let p = PointModel::nvm();
        for (m, l, d) in [
            (20.0, 10.0, 1.0),
            (5.0, 0.0, 0.5),
            (1000.0, 20.0, 0.1),
            (1.0, 5.0, 0.25),
        ] {
            let a = p.eval(m, l, d);
            let b = nvm_point_hc(m, l, d);
            assert!((a / b - 1.0).abs() < 1e-12, "M={m} L={l} D={d}: {a} vs {b}");
            let pa = p.asymptotes(m, l, d);
            let na = nvm_point_asymptotes(m, l, d);
            // At L = 0 the piezoviscous asymptotes are both 0.
            for k in 0..if l > 0.0 { 4 } else { 2 } {
                assert!((pa[k] / na[k] - 1.0).abs() < 1e-12, "asymptote {k}");
            }
        }
        // docs/physics.md section 4: circular M = 20, L = 10 gives 4.71.
        assert!((p.eval(20.0, 10.0, 1.0) - 4.71).abs() < 0.01);
    }

    /// The approach factor g: its closed form, 1 as M -> infinity (the EI law exact there), and
    /// bounded as M -> 0; a stored model of the NVM form's 16 parameters reads back with g = 1.
    #[test]
    fn the_approach_factor_tends_to_one_and_old_models_read_back() {
        let mut p = PointModel::nvm();
        let c = [0.4, -0.1, 0.02, -0.7, 0.05, -0.01, 0.3, 0.02, -0.03];
        p.x[16..].copy_from_slice(&c);
        p.approach_m0 = 100.0;
        let (m, d) = (300.0f64, 0.2f64);
        let ln_d = d.ln();
        let mg = (m * m + 100.0 * 100.0).sqrt();
        let want = ((c[0] + c[1] * ln_d + c[2] * ln_d * ln_d) * (1.0 + mg).powf(-4.0 / 15.0)
            + (c[3] + c[4] * ln_d + c[5] * ln_d * ln_d) * (1.0 + mg).powf(-8.0 / 15.0)
            + (c[6] + c[7] * ln_d + c[8] * ln_d * ln_d) * (1.0 + mg).powf(-12.0 / 15.0))
        .exp();
        assert!((p.approach(m, d) / want - 1.0).abs() < 1e-14);
        // Below M_0 = 100 g is flat: M_g = M_0 (1 + (M/M_0)^2 / 2 + ...).
        let at = |m: f64| p.approach(m, d).ln();
        assert!(
            (at(1.0) - at(0.0)).abs() < 1e-5 * at(0.0).abs(),
            "{}",
            at(0.0)
        );
        assert!((at(100.0) - at(0.0)).abs() > 1e-2 * at(0.0).abs());
        let nvm = PointModel::nvm();
        let ratio = p.asymptotes(m, 0.0, d)[1] / nvm.asymptotes(m, 0.0, d)[1];
        assert!((ratio / want - 1.0).abs() < 1e-14);
        // The gap falls like M^(-4/15): below 1e-3 at M = 1e12.
        assert!((p.approach(1e12, d) - 1.0).abs() < 1e-3);
        assert!((p.approach(1e12, d) - 1.0).abs() < (p.approach(1e9, d) - 1.0).abs());
        let bound = c.iter().map(|v| v.abs()).sum::<f64>() * (1.0 + ln_d * ln_d);
        for m in [1e-12, 1e-3, 1.0] {
            assert!(p.approach(m, d).ln().abs() <= bound);
        }
        let mut stored = serde_json::to_value(&nvm).unwrap();
        stored["x"] = serde_json::json!(nvm.x[..16].to_vec());
        let back: PointModel = serde_json::from_value(stored.clone()).unwrap();
        assert_eq!(back, nvm);
        // A model with two powers of g and M_g = M (before anchors) reads back as it was.
        let mut two = nvm.clone();
        two.x[16..22].copy_from_slice(&c[..6]);
        let mut stored = serde_json::to_value(&two).unwrap();
        assert!(stored.get("approach_m0").is_none());
        stored["x"] = serde_json::json!(two.x[..22].to_vec());
        let back: PointModel = serde_json::from_value(stored.clone()).unwrap();
        assert_eq!(back, two);
        let plain = ((c[0] + c[1] * ln_d + c[2] * ln_d * ln_d) * (1.0 + m).powf(-4.0 / 15.0)
            + (c[3] + c[4] * ln_d + c[5] * ln_d * ln_d) * (1.0 + m).powf(-8.0 / 15.0))
        .exp();
        assert!((back.approach(m, d) / plain - 1.0).abs() < 1e-14);
        stored["x"] = serde_json::json!(nvm.x[..15].to_vec());
        assert!(serde_json::from_value::<PointModel>(stored).is_err());
    }
}
