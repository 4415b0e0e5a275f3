//! Tests of the side-lobe factor (`super`): exact recovery of factors of its own form, its
//! invariants, the held-out choice and the kriging residual.

use super::*;

/// A grid of cases in M 10 ... 1000, L 0 ... 20, D 0.1 ... 1 with y = max(0, g_true), g_true
/// of the factor's own form (degrees (1, 1, 1), the ramp from M_0 = 10) crossing 0 inside
/// the box.
fn hinge_cases() -> (Vec<SideCase>, SideLobe) {
    let mut cases = vec![];
    for i in 0..9 {
        for l in [0.0, 1.0, 5.0, 20.0] {
            for d in [0.1, 0.25, 0.5, 1.0] {
                cases.push(SideCase {
                    m: 10f64.powf(1.0 + 0.25 * f64::from(i)),
                    l,
                    d,
                    y: 0.0,
                });
            }
        }
    }
    let (lo, hi) = data_box(&cases);
    let truth = SideLobe {
        lo,
        hi,
        powers: tensor_powers([1, 1, 1]),
        coef: vec![0.1, 0.05, 0.2, 0.02, 0.3, 0.05, 0.1, 0.01],
        ramp: Some([lo[0], lo[0] + 0.25 * 10f64.ln()]),
        ramp_d: None,
        kriging: None,
    };
    for c in &mut cases {
        c.y = truth.g(c.m, c.l, c.d).max(0.0);
    }
    (cases, truth)
}

#[test]
fn the_hinge_fit_recovers_a_factor_of_its_own_form() {
    let (cases, truth) = hinge_cases();
    let lobes = cases.iter().filter(|c| c.y > NO_LOBE).count();
    assert!(lobes > 20 && lobes < cases.len() - 20, "{lobes}");
    let fit = fit_side(&cases, &tensor_powers([1, 1, 1]), 1e-12).unwrap();
    let (a, b) = (fit.ramp.unwrap(), truth.ramp.unwrap());
    assert!(
        (a[0] - b[0]).abs() + (a[1] - b[1]).abs() < 1e-12,
        "{a:?} {b:?}"
    );
    for (a, b) in fit.coef.iter().zip(&truth.coef) {
        assert!((a - b).abs() < 1e-6, "{:?} {:?}", fit.coef, truth.coef);
    }
    for c in &cases {
        let r = fit.factor(c.m, c.l, c.d) / (-c.y).exp();
        assert!((r - 1.0).abs() < 1e-8, "{c:?} {r}");
    }
}

#[test]
fn the_factor_never_lifts_the_film_and_is_constant_beyond_the_box() {
    let (cases, truth) = hinge_cases();
    for c in &cases {
        assert!(truth.factor(c.m, c.l, c.d) <= 1.0);
    }
    // Beyond the box (M 1e6, L 40, D 0.01; M 1e-3): the value at the nearest box point.
    let edge = truth.factor(1000.0, 20.0, 0.1);
    assert!(edge < 0.99, "{edge}");
    assert_eq!(truth.factor(1e6, 40.0, 0.01), edge);
    assert_eq!(truth.factor(1e-3, 0.0, 1.0), truth.factor(10.0, 0.0, 1.0));
    assert_eq!(truth.factor(10.0, 5.0, 1.0), 1.0, "the ramp is 0 at M_0");
    assert_eq!(
        truth.factor(100.0, 0.0, 0.1),
        1.0,
        "no side lobe in that corner"
    );
}

#[test]
fn held_out_selection_finds_the_exact_form_and_predicts_every_case() {
    let (cases, _) = hinge_cases();
    let fold: Vec<usize> = (0..cases.len()).map(|i| i % 5).collect();
    let (side, choice) = select_side(&cases, &fold, 5).unwrap();
    assert_eq!(choice.heldout_g.len(), cases.len());
    assert!(choice.rms < 1e-4 && choice.max.abs() < 1e-3, "{choice:?}");
    // The simplest candidate that holds the exact form is kept.
    assert_eq!(choice.chosen.degrees, [1, 1, 1]);
    assert_eq!(side.powers.len(), 8);
}

// A side lobe the polynomial cannot follow (the exact form plus a narrow bump in ln M and
// ln D at large M): the kriging residual is kept, lowers the held-out errors, and keeps the
// factor's invariants (F <= 1, F = 1 up to M_0 and beyond the box's low-M edge).
#[test]
fn a_kriging_residual_follows_what_the_polynomial_cannot() {
    let (mut cases, truth) = hinge_cases();
    for c in &mut cases {
        let bump = 0.03
            * (-(c.m.ln() - 800f64.ln()).powi(2) / 0.5 - (c.d.ln() - 0.3f64.ln()).powi(2)).exp();
        c.y = (truth.g(c.m, c.l, c.d).max(0.0) + bump * truth.ramp(c.m)).max(0.0);
    }
    let fold: Vec<usize> = (0..cases.len()).map(|i| i % 5).collect();
    let (side, choice) = select_side(&cases, &fold, 5).unwrap();
    let [rms0, max0] = choice.without.expect("kriging kept");
    assert!(side.kriging.is_some());
    assert!(choice.rms < 0.8 * rms0, "{} {rms0}", choice.rms);
    assert!(choice.max.abs() <= max0, "{} {max0}", choice.max);
    for c in &cases {
        assert!(side.factor(c.m, c.l, c.d) <= 1.0);
    }
    assert_eq!(side.factor(10.0, 5.0, 0.3), 1.0, "the ramp is 0 at M_0");
    assert_eq!(side.factor(1e-3, 20.0, 0.3), 1.0);
}

// Slender contacts without side lobes (D 0.01 and 0.03) below the lobes of D >= 0.1: the fit
// places the ramp in D between them, holds F = 1 at and below D_0 and recovers the factor.
#[test]
fn the_ramp_in_d_holds_slender_contacts_at_the_centre_line() {
    let (base, truth0) = hinge_cases();
    let mut cases = base.clone();
    for c in &base {
        for d in [0.01, 0.03] {
            cases.push(SideCase { d, ..*c });
        }
    }
    let (mut lo, hi) = data_box(&cases);
    lo[1] = 0.03f64.ln();
    let truth = SideLobe {
        lo,
        hi,
        ramp_d: Some([0.03f64.ln(), 0.1f64.ln()]),
        ..truth0.clone()
    };
    for c in &mut cases {
        c.y = truth.g(c.m, c.l, c.d).max(0.0);
    }
    assert!(cases.iter().any(|c| c.d == 0.1 && c.y > LOBE_D));
    let fit = fit_side(&cases, &tensor_powers([1, 1, 1]), 1e-12).unwrap();
    assert_eq!(fit.ramp_d, truth.ramp_d);
    assert_eq!(fit.lo, truth.lo);
    for c in &cases {
        let r = fit.factor(c.m, c.l, c.d) / (-c.y).exp();
        assert!((r - 1.0).abs() < 1e-8, "{c:?} {r}");
    }
    for d in [0.001, 0.01, 0.03] {
        assert_eq!(fit.factor(1000.0, 20.0, d), 1.0, "D = {d}");
    }
    assert!(fit.factor(1000.0, 20.0, 0.1) < 0.99);
    // Data whose smallest D has a side lobe: no ramp in D, as before.
    let (plain, _) = hinge_cases();
    let mut plain = plain;
    for c in &mut plain {
        c.y = truth0.g(c.m, c.l, c.d).max(0.0);
    }
    assert_eq!(
        fit_side(&plain, &tensor_powers([1, 1, 1]), 1e-12)
            .unwrap()
            .ramp_d,
        None
    );
}

#[test]
fn no_side_lobe_case_no_fit() {
    let (mut cases, _) = hinge_cases();
    for c in &mut cases {
        c.y = 0.0;
    }
    assert!(fit_side(&cases, &tensor_powers([1, 1, 1]), 1e-8).is_none());
}
