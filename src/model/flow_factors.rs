//! Patir & Cheng flow factors for Gaussian roughness: the pressure flow factors `phi_x`,
//! `phi_y` and the shear flow factor `phi_s` of the average Reynolds equation, as functions of
//! the film ratio `H = h/sigma` and the orientation parameter `gamma`.
//!
//! Inputs are dimensionless: `h` the nominal film (the compliance: the separation of the mean
//! planes, seed figure 7-8), `sigma = sqrt(Rq1^2 + Rq2^2)` the composite RMS roughness (seed
//! 7-47), `gamma = lambda_x*/lambda_y*` Peklenik's ratio of the correlation lengths along `x`
//! (the rolling direction) and `y` (the seed's `lambda`, 7-48): `gamma = 1` isotropic,
//! `gamma < 1` transverse ridges (across the rolling direction), `gamma > 1` longitudinal.
//! References: the seed chapter (`shared/seeds/002_e3b91dad40c55bf4.txt`, sections 7-7 and 7-8,
//! equations 7-49 to 7-58, Tables 7-2 and 7-3), Patir & Cheng, J. Lubr. Technol. 100 (1978)
//! 12-17 (pressure flow) and 101 (1979) 220-229 (shear flow).
//!
//! # Pressure flow (seed 7-49 to 7-52, Table 7-2)
//!
//! ```text
//! phi_x(H, gamma) = 1 - C exp(-r H)     gamma <= 1          (7-50)
//! phi_x(H, gamma) = 1 + C H^(-r)        gamma > 1           (7-51)
//! phi_y(H, gamma) = phi_x(H, 1/gamma)                       (7-52)
//! ```
//!
//! with `C`, `r` and the validity range from Table 7-2: `gamma = 1/9, 1/6`: `H > 1`;
//! `gamma = 1/3`: `H > 0.75`; `gamma = 1, 3, 6, 9`: `H > 0.5`. Transverse roughness blocks the
//! flow along `x` (`phi_x < 1` for every `gamma <= 1`), longitudinal roughness channels it
//! (`phi_x > 1` on the rows `gamma = 3, 6, 9`); at fixed `H`, `phi_x` grows with `gamma`, so
//! between the rows `gamma = 1` (isotropic, `phi_x < 1`) and `gamma = 3` it crosses 1 at an
//! `H`-dependent `gamma` (interpolated: `phi_x(1, 2) = 0.95`). Both tend to 1 as `H` grows.
//!
//! # Shear flow (seed 7-53 to 7-58, Table 7-3)
//!
//! The flow along `x` is `q_x = -phi_x h^3/(12 eta) dp/dx + (U1 + U2)/2 h_T_bar
//! + (U1 - U2)/2 sigma phi_s` (7-37, 7-43), with
//!
//! ```text
//! phi_s = Vr1 Phi_s(H, gamma1) - Vr2 Phi_s(H, gamma2),   Vri = Rqi^2 / sigma^2   (7-53)
//! Phi_s(H, gamma) = A1 H^a1 exp(-a2 H + a3 H^2)    H <= 5                        (7-57)
//! Phi_s(H, gamma) = A2 exp(-H/4)                    H > 5                         (7-58)
//! ```
//!
//! `Phi_s` is the factor of a single rough surface. Sign convention: surface 1 moves at `U1`;
//! when only surface 1 is rough (`Vr1 = 1`, 7-56) `phi_s = +Phi_s`, and the shear term adds
//! flow when the rough surface moves faster (`U1 > U2`) and removes it when the smooth one does
//! (the seed's figure 7-10); when only surface 2 is rough `phi_s = -Phi_s` (7-54); equal
//! roughness on both (same `gamma`) gives `phi_s = 0`. [`FlowFactors::phi_s`] is `Phi_s`
//! (surface 1 rough); [`shear_flow_factor`] applies the variance ratios with one `gamma` for
//! both surfaces. The seed gives no lower limit of `H` for 7-57, and the formula is used as
//! written for every `H >= 0` (it tends to 0 as `H -> 0`); at `H = 5` the two branches of each
//! row agree to within 0.1 % (the test `shear_branches_meet_at_five`).
//!
//! # Between and beyond the tables
//!
//! - **Interpolation in `gamma`:** the factor (not the coefficients) is interpolated linearly in
//!   `ln gamma` between the two neighbouring table rows; for `gamma` outside `[1/9, 9]` the end
//!   row is used (clamped). Table rows are reproduced exactly, and since the rows are
//!   symmetric in `ln gamma`, `phi_y(H, gamma) = phi_x(H, 1/gamma)` holds for every `gamma`.
//! - **Below the tabulated range of `H`:** each row is evaluated at `max(H, H_min(row))`
//!   (constant below its lower limit) and [`FlowFactors::below_range`] is set.
//! - **Large `H`:** the formulas are used as they stand; `phi_x, phi_y -> 1` (as
//!   `exp(-r H)`, or as `H^-1.5` for `gamma > 1`) and `phi_s -> 0` as `exp(-H/4)`.
//! - **Smooth surfaces** (`sigma = 0`, `H` infinite) are the caller's case:
//!   [`FlowFactors::SMOOTH`] (`phi_x = phi_y = 1`, `phi_s = 0`).
//!
//! Negative `H` (the mean planes interpenetrating) is rejected: the caller clamps the film ratio
//! if its nominal film can be negative.

use crate::model::error::{check, ParamError};

/// A Table 7-2 row: `gamma`, `C`, `r`, and the lower limit of `H`.
struct PressureRow {
    gamma: f64,
    c: f64,
    r: f64,
    h_min: f64,
}

/// A Table 7-3 row: `gamma`, `A1`, `alpha1`, `alpha2`, `alpha3`, `A2`.
struct ShearRow {
    gamma: f64,
    a1: f64,
    alpha1: f64,
    alpha2: f64,
    alpha3: f64,
    a2: f64,
}

const fn pr(gamma: f64, c: f64, r: f64, h_min: f64) -> PressureRow {
    PressureRow { gamma, c, r, h_min }
}

const fn sr(gamma: f64, a1: f64, alpha1: f64, alpha2: f64, alpha3: f64, a2: f64) -> ShearRow {
    ShearRow {
        gamma,
        a1,
        alpha1,
        alpha2,
        alpha3,
        a2,
    }
}

/// Seed Table 7-2 (Patir & Cheng 1978, Table 1).
const PRESSURE: [PressureRow; 7] = [
    pr(1.0 / 9.0, 1.48, 0.42, 1.0),
    pr(1.0 / 6.0, 1.38, 0.42, 1.0),
    pr(1.0 / 3.0, 1.18, 0.42, 0.75),
    pr(1.0, 0.90, 0.56, 0.5),
    pr(3.0, 0.225, 1.5, 0.5),
    pr(6.0, 0.520, 1.5, 0.5),
    pr(9.0, 0.870, 1.5, 0.5),
];

/// Seed Table 7-3 (Patir & Cheng 1979).
const SHEAR: [ShearRow; 7] = [
    sr(1.0 / 9.0, 2.046, 1.12, 0.78, 0.03, 1.856),
    sr(1.0 / 6.0, 1.962, 1.08, 0.77, 0.03, 1.754),
    sr(1.0 / 3.0, 1.858, 1.01, 0.76, 0.03, 1.561),
    sr(1.0, 1.899, 0.98, 0.92, 0.05, 1.126),
    sr(3.0, 1.560, 0.85, 1.13, 0.08, 0.556),
    sr(6.0, 1.290, 0.62, 1.09, 0.08, 0.388),
    sr(9.0, 1.011, 0.54, 1.07, 0.08, 0.295),
];

/// The flow factors at one film ratio and orientation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlowFactors {
    /// Pressure flow factor along `x` (the rolling direction).
    pub phi_x: f64,
    /// Pressure flow factor along `y`, `phi_x(H, 1/gamma)`.
    pub phi_y: f64,
    /// Shear flow factor with surface 1 rough and surface 2 smooth (`Phi_s`, seed 7-56).
    pub phi_s: f64,
    /// `H` is below the tabulated range of a row used for `phi_x` or `phi_y`, whose values are
    /// then those at the row's lower limit.
    pub below_range: bool,
}

impl FlowFactors {
    /// Smooth surfaces (`sigma = 0`): the plain Reynolds equation.
    pub const SMOOTH: FlowFactors = FlowFactors {
        phi_x: 1.0,
        phi_y: 1.0,
        phi_s: 0.0,
        below_range: false,
    };
}

/// The film ratio `h/sigma` from a film and a composite RMS roughness: `sigma` finite and
/// `> 0` (`sigma = 0` is the smooth surface, [`FlowFactors::SMOOTH`]), `h` finite and `>= 0`.
pub fn film_ratio(h: f64, sigma: f64) -> Result<f64, ParamError> {
    check(
        "sigma",
        sigma,
        sigma > 0.0,
        "must be finite and > 0 (sigma = 0 is the smooth surface)",
    )?;
    check("h", h, h >= 0.0, "must be finite and >= 0")?;
    Ok(h / sigma)
}

/// `phi_x`, `phi_y` and `Phi_s` at `H = h/sigma >= 0` and orientation `gamma > 0` (module docs).
pub fn flow_factors(h_over_sigma: f64, gamma: f64) -> Result<FlowFactors, ParamError> {
    check_inputs(h_over_sigma, gamma)?;
    let (phi_x, below_x) = pressure_factor(h_over_sigma, gamma);
    let (phi_y, below_y) = pressure_factor(h_over_sigma, 1.0 / gamma);
    Ok(FlowFactors {
        phi_x,
        phi_y,
        phi_s: single_shear_factor(h_over_sigma, gamma),
        below_range: below_x || below_y,
    })
}

/// The combined shear flow factor `phi_s = (Vr1 - Vr2) Phi_s(H, gamma)`, `Vr2 = 1 - Vr1`
/// (seed 7-53 with one `gamma` for both surfaces): `Vr1 = Rq1^2/sigma^2` in `[0, 1]` is the
/// share of the roughness variance on surface 1 (1: only surface 1 rough, 0: only surface 2).
pub fn shear_flow_factor(
    h_over_sigma: f64,
    gamma: f64,
    variance_ratio_1: f64,
) -> Result<f64, ParamError> {
    check_inputs(h_over_sigma, gamma)?;
    let vr1 = variance_ratio_1;
    check("Vr1", vr1, (0.0..=1.0).contains(&vr1), "must be in [0, 1]")?;
    Ok((2.0 * vr1 - 1.0) * single_shear_factor(h_over_sigma, gamma))
}

fn check_inputs(h_over_sigma: f64, gamma: f64) -> Result<(), ParamError> {
    check(
        "h/sigma",
        h_over_sigma,
        h_over_sigma >= 0.0,
        "must be finite and >= 0",
    )?;
    check("gamma", gamma, gamma > 0.0, "must be finite and > 0")
}

/// The two rows around `gamma` (rows in increasing `gamma`) and the weight of the second,
/// linear in `ln gamma`; clamped to the end rows outside the table.
fn bracket<R>(rows: &[R], row_gamma: fn(&R) -> f64, gamma: f64) -> (usize, usize, f64) {
    let last = rows.len() - 1;
    if gamma <= row_gamma(&rows[0]) {
        return (0, 0, 0.0);
    }
    if gamma >= row_gamma(&rows[last]) {
        return (last, last, 0.0);
    }
    let j = rows
        .iter()
        .position(|row| row_gamma(row) > gamma)
        .unwrap_or(last);
    let (g0, g1) = (row_gamma(&rows[j - 1]), row_gamma(&rows[j]));
    (j - 1, j, (gamma / g0).ln() / (g1 / g0).ln())
}

/// `phi_x(H, gamma)` interpolated between rows, and whether `H` was below a row's range.
pub(crate) fn pressure_factor(h: f64, gamma: f64) -> (f64, bool) {
    let (i, j, w) = bracket(&PRESSURE, |row| row.gamma, gamma);
    let (a, below_a) = pressure_row(&PRESSURE[i], h);
    if w == 0.0 {
        return (a, below_a);
    }
    let (b, below_b) = pressure_row(&PRESSURE[j], h);
    ((1.0 - w) * a + w * b, below_a || below_b)
}

/// One row of 7-50/7-51, evaluated at `max(H, H_min)`.
fn pressure_row(row: &PressureRow, h: f64) -> (f64, bool) {
    let hc = h.max(row.h_min);
    let phi = if row.gamma <= 1.0 {
        1.0 - row.c * (-row.r * hc).exp()
    } else {
        1.0 + row.c * hc.powf(-row.r)
    };
    (phi, h < row.h_min)
}

/// `Phi_s(H, gamma)` interpolated between rows.
pub(crate) fn single_shear_factor(h: f64, gamma: f64) -> f64 {
    let (i, j, w) = bracket(&SHEAR, |row| row.gamma, gamma);
    let a = shear_row(&SHEAR[i], h);
    if w == 0.0 {
        return a;
    }
    (1.0 - w) * a + w * shear_row(&SHEAR[j], h)
}

/// One row of 7-57/7-58.
fn shear_row(row: &ShearRow, h: f64) -> f64 {
    if h <= 5.0 {
        row.a1 * h.powf(row.alpha1) * (-row.alpha2 * h + row.alpha3 * h * h).exp()
    } else {
        row.a2 * (-0.25 * h).exp()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    const GAMMAS: [f64; 7] = [1.0 / 9.0, 1.0 / 6.0, 1.0 / 3.0, 1.0, 3.0, 6.0, 9.0];

    /// phi_x at H = 1, 2, 4 per Table 7-2 row, evaluated by hand (Python) from the printed
    /// coefficients: `1 - C exp(-r H)` or `1 + C H^-r`.
    #[test]
    fn pressure_table_rows_reproduced() {
        let want: [[f64; 3]; 7] = [
            [0.027570706673715972, 0.361068425324962, 0.7241665154616732],
            [0.09327538865522178, 0.40423947766787005, 0.7428039130656143],
            [0.22468475261823306, 0.490581582353686, 0.7800787082734962],
            [0.48591184253606656, 0.7063481848392645, 0.9041873460586725],
            [1.225, 1.0795495128834867, 1.028125],
            [1.52, 1.1838477631085023, 1.065],
            [1.87, 1.3075914498161483, 1.10875],
        ];
        assert_table(&want, [1.0, 2.0, 4.0], "phi_x", |f| {
            assert!(!f.below_range);
            f.phi_x
        });
    }

    /// Each `want[row][k]` is the factor `pick` of the Table row's gamma at `hs[k]`, to 1e-14.
    fn assert_table(
        want: &[[f64; 3]; 7],
        hs: [f64; 3],
        name: &str,
        pick: impl Fn(&FlowFactors) -> f64,
    ) {
        for (g, row) in GAMMAS.iter().zip(want.iter()) {
            for (h, w) in hs.iter().zip(row.iter()) {
                let v = pick(&flow_factors(*h, *g).unwrap());
                assert!(rel(v, *w) < 1e-14, "{name}({h}, {g}) = {v}");
            }
        }
    }

    /// Phi_s at H = 1, 3 (7-57) and 6 (7-58) per Table 7-3 row, by hand from the coefficients.
    #[test]
    fn shear_table_rows_reproduced() {
        let want: [[f64; 3]; 7] = [
            [0.9664619669081159, 0.8836735523999566, 0.41412957723548577],
            [0.9360975022522694, 0.8356592312692402, 0.3913703009003459],
            [0.8953869035875962, 0.7551031262104753, 0.34830617999169894],
            [0.7955889920212664, 0.5532017447493206, 0.25124456032713194],
            [0.5459028886134025, 0.2748599088797391, 0.12406036904252699],
            [0.4698424836472651, 0.19904623139886016, 0.08657450213759077],
            [0.3756640346232881, 0.1517062150558541, 0.06582339724378679],
        ];
        assert_table(&want, [1.0, 3.0, 6.0], "Phi_s", |f| f.phi_s);
    }

    /// An independent check of the Table 7-3 transcription: 7-57 and 7-58 meet at H = 5 for
    /// each row to the table's printed precision (A2 has 3-4 digits).
    #[test]
    fn shear_branches_meet_at_five() {
        for row in &SHEAR {
            let below = shear_row(row, 5.0);
            let above = row.a2 * (-1.25f64).exp();
            assert!(
                rel(below, above) < 1e-3,
                "gamma {}: {below} vs {above}",
                row.gamma
            );
        }
    }

    #[test]
    fn limits_for_thick_films() {
        for g in GAMMAS.iter().chain([0.05, 0.5, 2.0, 20.0].iter()) {
            let f = flow_factors(200.0, *g).unwrap();
            assert!(
                (f.phi_x - 1.0).abs() < 2e-3 && (f.phi_y - 1.0).abs() < 2e-3,
                "{g}"
            );
            assert!(f.phi_s.abs() < 1e-21, "{g}: {}", f.phi_s);
        }
        // On each table row |phi_x - 1| falls monotonically with H (between the gamma = 1 and 3
        // rows the interpolated phi_x crosses 1, so this holds on the rows only).
        for g in GAMMAS.iter() {
            let mut last = f64::INFINITY;
            for k in 0..40 {
                let h = 0.5 + 0.5 * k as f64;
                let d = (flow_factors(h, *g).unwrap().phi_x - 1.0).abs();
                assert!(
                    d <= last,
                    "|phi_x - 1| not decreasing at H = {h}, gamma {g}"
                );
                last = d;
            }
        }
        assert!(flow_factors(60.0, 1.0).unwrap().phi_s < 1e-6);
    }

    #[test]
    fn orientation_identity_and_direction() {
        for &g in GAMMAS
            .iter()
            .chain([0.05, 0.2, 0.5, 0.77, 1.3, 2.0, 4.5, 7.0, 30.0].iter())
        {
            for &h in &[0.2, 0.6, 1.0, 1.7, 3.0, 6.0] {
                let f = flow_factors(h, g).unwrap();
                let r = flow_factors(h, 1.0 / g).unwrap();
                assert!(rel(f.phi_y, r.phi_x) < 1e-14, "phi_y({h}, {g})");
                assert!(rel(f.phi_x, r.phi_y) < 1e-14, "phi_x({h}, {g})");
                if g <= 1.0 {
                    assert!(f.phi_x < 1.0, "transverse {g} at {h}");
                }
                if g >= 3.0 {
                    assert!(f.phi_x > 1.0 && f.phi_y < 1.0, "longitudinal {g} at {h}");
                }
                if g <= 1.0 / 3.0 {
                    assert!(f.phi_y > 1.0, "transverse {g} at {h}");
                }
                if g == 1.0 {
                    assert_eq!(f.phi_x, f.phi_y);
                }
            }
        }
    }

    /// At fixed H, phi_x grows with gamma (more longitudinal, more flow along x; constant beyond
    /// the table's ends), and for
    /// 1 < gamma < 3 it crosses 1: isotropic roughness blocks the flow, gamma = 3 channels it.
    #[test]
    fn pressure_factor_grows_with_gamma() {
        for &h in &[0.3, 0.5, 1.0, 2.0, 4.0, 8.0] {
            let mut last = 0.0;
            for k in 0..=80 {
                let g = (1.0f64 / 12.0).ln() + (144.0f64).ln() * k as f64 / 80.0;
                let phi = flow_factors(h, g.exp()).unwrap().phi_x;
                let inside = (1.0 / 9.0..=9.0).contains(&g.exp());
                let ok = if inside { phi > last } else { phi >= last };
                assert!(
                    ok,
                    "phi_x not increasing in gamma at H = {h}, gamma {}",
                    g.exp()
                );
                last = phi;
            }
        }
        let at2 = flow_factors(1.0, 2.0).unwrap().phi_x;
        assert!(at2 < 1.0, "gamma = 2, H = 1: {at2}");
        assert!(flow_factors(4.0, 2.0).unwrap().phi_x < 1.0);
    }

    #[test]
    fn interpolation_in_log_gamma() {
        let h = 2.0;
        // Midway in ln gamma between 1 and 3 is sqrt(3).
        let f = flow_factors(h, 3f64.sqrt()).unwrap();
        let (a, b) = (flow_factors(h, 1.0).unwrap(), flow_factors(h, 3.0).unwrap());
        assert!(rel(f.phi_x, 0.5 * (a.phi_x + b.phi_x)) < 1e-14);
        assert!(rel(f.phi_s, 0.5 * (a.phi_s + b.phi_s)) < 1e-14);
        // Clamped beyond the table.
        assert_eq!(
            flow_factors(h, 100.0).unwrap(),
            flow_factors(h, 9.0).unwrap()
        );
        assert_eq!(
            flow_factors(h, 1e-3).unwrap(),
            flow_factors(h, 1.0 / 9.0).unwrap()
        );
        // Continuous in gamma at a table row.
        let g = 1.0 / 3.0;
        let (lo, hi) = (
            flow_factors(h, g * (1.0 - 1e-9)),
            flow_factors(h, g * (1.0 + 1e-9)),
        );
        assert!((lo.unwrap().phi_x - hi.unwrap().phi_x).abs() < 1e-9);
    }

    #[test]
    fn below_range_clamps_and_flags() {
        // gamma = 1/9 is tabulated for H > 1: below, phi_x is its value at H = 1.
        let f = flow_factors(0.4, 1.0 / 9.0).unwrap();
        assert!(f.below_range);
        assert_eq!(f.phi_x, flow_factors(1.0, 1.0 / 9.0).unwrap().phi_x);
        // phi_y uses gamma = 9 (H > 0.5): clamped as well at H = 0.4.
        assert_eq!(f.phi_y, flow_factors(0.5, 9.0).unwrap().phi_x);
        // Isotropic H = 0.6 is inside its range; gamma = 1/3 at H = 0.6 is not (H > 0.75).
        assert!(!flow_factors(0.6, 1.0).unwrap().below_range);
        assert!(flow_factors(0.6, 1.0 / 3.0).unwrap().below_range);
        assert!(flow_factors(0.0, 1.0).unwrap().below_range);
        // Phi_s has no tabulated lower limit: the formula as written, 0 at H = 0.
        assert_eq!(flow_factors(0.0, 1.0).unwrap().phi_s, 0.0);
    }

    #[test]
    fn shear_sign_convention() {
        let (h, g) = (1.5, 1.0);
        let single = flow_factors(h, g).unwrap().phi_s;
        assert!(single > 0.0);
        assert_eq!(shear_flow_factor(h, g, 1.0).unwrap(), single);
        assert_eq!(shear_flow_factor(h, g, 0.0).unwrap(), -single);
        assert_eq!(shear_flow_factor(h, g, 0.5).unwrap(), 0.0);
        assert!(rel(shear_flow_factor(h, g, 0.8).unwrap(), 0.6 * single) < 1e-15);
    }

    #[test]
    fn bad_inputs_name_the_input() {
        let name = |e: ParamError| match e {
            ParamError::Invalid { name, .. } => name,
            other => panic!("unexpected {other:?}"),
        };
        assert_eq!(name(flow_factors(-0.1, 1.0).unwrap_err()), "h/sigma");
        assert_eq!(name(flow_factors(f64::NAN, 1.0).unwrap_err()), "h/sigma");
        assert_eq!(
            name(flow_factors(f64::INFINITY, 1.0).unwrap_err()),
            "h/sigma"
        );
        assert_eq!(name(flow_factors(1.0, 0.0).unwrap_err()), "gamma");
        assert_eq!(name(flow_factors(1.0, -2.0).unwrap_err()), "gamma");
        assert_eq!(name(flow_factors(1.0, f64::NAN).unwrap_err()), "gamma");
        assert_eq!(name(shear_flow_factor(1.0, 1.0, 1.5).unwrap_err()), "Vr1");
        assert_eq!(name(film_ratio(1.0, -0.2).unwrap_err()), "sigma");
        assert_eq!(name(film_ratio(1.0, 0.0).unwrap_err()), "sigma");
        assert_eq!(name(film_ratio(f64::NAN, 0.2).unwrap_err()), "h");
        assert!(rel(film_ratio(0.3, 0.2).unwrap(), 1.5) < 1e-15);
        let msg = flow_factors(1.0, -2.0).unwrap_err().to_string();
        assert!(msg.contains("gamma") && msg.contains("-2"), "{msg}");
    }
}
