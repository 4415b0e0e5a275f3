//! Tests of the corner law (`super`): synthetic line and point corners followed in and out of
//! sample, the one-sided least squares against a ridge oracle, the asymptotes kept and the fade
//! beyond the data.

use super::*;
use crate::fit::model::LineModel;
use crate::fit::point_model::PointModel;

/// Moes' blend as the H_pm law, and the same with the H_c rigid constants (2.4475/3 times
/// Moes' RI and RP laws) as the H_c law.
fn blends() -> (Blend, Blend) {
    let pm = LineModel::moes();
    let mut own = pm.clone();
    own.c_ri = 2.4475;
    own.x[2] += (2.4475f64 / 3.0).ln();
    (Blend::Line(pm), Blend::Line(own))
}

/// The synthetic H_pm = B exp(rho r(z)) and H_c = H_pm exp(-max(0, rho r(z) - g)) on the H_c
/// blend B: a corner where rho r(z) crosses g, H_c following H_pm past it.
fn case(own: &Blend, rho: f64, m: f64, l: f64, d: f64, g: f64) -> CornerCase {
    let z = Coordinates::new(own.asymptotes(m, l, d), d);
    let h_pm = own.eval(m, l, d) * (rho * rigidity(&z)).exp();
    let h = h_pm * (-(rho * rigidity(&z) - g).max(0.0)).exp();
    CornerCase {
        m,
        l,
        d,
        h,
        follows: h >= FOLLOWS * h_pm,
    }
}

/// Line cases M = 0.1 ... 3000 (46, log) x L in {0, 1, 2, 4, 8, 12, 16, 20}, the corner at
/// g = 0.05 + 0.002 ln(1 + L).
fn cases(own: &Blend, rho: f64) -> Vec<CornerCase> {
    let mut out = vec![];
    for i in 0..46 {
        let m = 10f64.powf(-1.0 + f64::from(i) / 10.0);
        for l in [0.0, 1.0, 2.0, 4.0, 8.0, 12.0, 16.0, 20.0] {
            out.push(case(own, rho, m, l, 1.0, 0.05 + 0.002 * l.ln_1p()));
        }
    }
    out
}

fn rho() -> f64 {
    (3.0f64 / 2.4475).ln()
}

fn eval(law: &Corner, own: &Blend, c: &CornerCase) -> f64 {
    law.apply(own.eval(c.m, c.l, c.d), own.asymptotes(c.m, c.l, c.d), c.d)
}

#[test]
fn rho_is_the_rigid_ratio_and_unrelated_blends_have_none() {
    let (pm, own) = blends();
    let line = rigid_ratio(&pm, &own).expect("H_pm above H_c when rigid");
    assert!((line - rho()).abs() < 1e-15);
    assert!(rigid_ratio(&own, &pm).is_none());
    assert!(rigid_ratio(&own, &own).is_none());
    // The circular point: ln(45.0 / 35.5) from the two rigid constants.
    let mut p_pm = PointModel::nvm();
    let mut p_c = p_pm.clone();
    p_pm.x[0] = 45.0f64.ln();
    p_c.x[0] = 35.5f64.ln();
    let point = rigid_ratio(&Blend::Point(p_pm), &Blend::Point(p_c)).expect("positive");
    assert!((point - (45.0f64 / 35.5).ln()).abs() < 1e-14);
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

/// Cross-validate `cases` (5 folds, the same blend on each) and return the law, the largest
/// error in sample and held out.
fn followed(cases: &[CornerCase], own: &Blend, params: &CornerParams) -> (Corner, f64, f64) {
    let follows = cases.iter().filter(|c| c.follows).count();
    assert!(
        follows > 50 && cases.len() - follows > 50,
        "{follows} of {}",
        cases.len()
    );
    let fold: Vec<usize> = (0..cases.len()).map(|i| i % 5).collect();
    let bases = vec![own.clone(); 5];
    let CornerSelection {
        law,
        choice,
        errors: heldout,
        folds,
    } = select_corner(cases, &fold, &bases, own, rho(), params).expect("fits");
    assert_eq!(folds.len(), 5);
    let worst_in = cases
        .iter()
        .map(|c| (eval(&law, own, c) / c.h - 1.0).abs())
        .fold(0.0, f64::max);
    let worst_out = heldout.iter().fold(0.0f64, |a, e| a.max(e.abs()));
    eprintln!(
        "in sample {worst_in:e}, held out {worst_out:e}, ridges {:?}, {} terms",
        choice.ridges, choice.terms
    );
    // H_c never exceeds the right branch.
    for c in cases {
        let asym = own.asymptotes(c.m, c.l, c.d);
        let (right, h) = law.branches(own.eval(c.m, c.l, c.d), asym, c.d);
        assert!(h <= right);
    }
    (law, worst_in, worst_out)
}

#[test]
fn a_synthetic_line_corner_is_followed_in_and_out_of_sample() {
    let (_, own) = blends();
    let (_, worst_in, worst_out) = followed(&cases(&own, rho()), &own, &LINE);
    assert!(worst_in < 2e-3, "{worst_in}");
    assert!(worst_out < 5e-3, "{worst_out}");
}

#[test]
fn a_synthetic_point_corner_moving_with_d_is_followed_in_and_out_of_sample() {
    // NVM's point blend, the corner at g = 0.04 - 0.01 ln D (nearer the rigid side, at
    // lower M, for slender contacts: the opposite of the data, so that the ln D terms must
    // carry it), M = 1 ... 1000 (16, log) x L {0, 2, 5, 10, 20} x D {0.1, 0.25, 0.5, 1}.
    let own = Blend::Point(PointModel::nvm());
    let mut cases = vec![];
    for i in 0..16 {
        let m = 10f64.powf(f64::from(i) / 5.0);
        for l in [0.0, 2.0, 5.0, 10.0, 20.0] {
            for d in [0.1, 0.25, 0.5, 1.0] {
                cases.push(case(&own, rho(), m, l, d, 0.04 - 0.01 * f64::ln(d)));
            }
        }
    }
    let (law, worst_in, worst_out) = followed(&cases, &own, &POINT);
    assert!(worst_in < 5e-3, "{worst_in}");
    assert!(worst_out < 1e-2, "{worst_out}");
    // Its asymptotes are the blend's at every D, the ln D factors notwithstanding.
    for d in [0.01, 0.1, 0.5, 1.0] {
        for (name, m, l) in [
            ("RI", 1e-12, 0.0),
            ("EI", 1e60, 0.0),
            // (The point blend itself overflows beyond L of about 1e100.)
            ("RP", 1.0, 1e30),
            ("EP", 1e80, 1e12),
        ] {
            let c = CornerCase {
                m,
                l,
                d,
                h: 1.0,
                follows: false,
            };
            let ratio = eval(&law, &own, &c) / own.eval(m, l, d);
            assert!((ratio - 1.0).abs() < 1e-3, "{name}, D = {d}: {ratio}");
        }
    }
    // Without the ln D terms the moving corner is not followed as well.
    let flat = CornerParams {
        ln_d_powers: 0,
        ..POINT
    };
    let (_, flat_in, _) = followed(&cases, &own, &flat);
    assert!(flat_in > 2.0 * worst_in, "{flat_in} against {worst_in}");
    // Faded beyond the data: the same law at every case, the law without its corrections
    // (rho r alone) half a decade of a = ln(H_EI/H_RI) past the largest a of the cases at
    // each D (M = 1e5 here, 1000 in the data).
    let faded = CornerParams {
        fade: true,
        ..POINT
    };
    let (law_f, _, _) = followed(&cases, &own, &faded);
    for c in &cases {
        let (a, b) = (eval(&law_f, &own, c), eval(&law, &own, c));
        assert!((a / b - 1.0).abs() < 1e-12, "{c:?}: {a} against {b}");
    }
    let zero = |c: &Correction| Correction {
        terms: c.terms.clone(),
        coef: vec![0.0; c.coef.len()],
        support: None,
    };
    let bare = Corner {
        branch: zero(&law_f.branch),
        deficit: zero(&law_f.deficit),
        rho: law_f.rho,
    };
    assert!(law_f.branch.support.is_some() && law_f.deficit.support.is_some());
    let mut moved = 0.0f64;
    for d in [0.1, 0.25, 0.5, 1.0] {
        for l in [0.0, 5.0, 20.0] {
            let c = CornerCase {
                m: 1e5,
                l,
                d,
                h: 1.0,
                follows: true,
            };
            let bare = eval(&bare, &own, &c);
            let ratio = eval(&law_f, &own, &c) / bare;
            assert!((ratio - 1.0).abs() < 1e-12, "D = {d}, L = {l}: {ratio}");
            moved = moved.max((eval(&law, &own, &c) / bare - 1.0).abs());
        }
    }
    // (Unfaded, the corrections' ln D polynomials still move the law there.)
    eprintln!("unfaded at M = 1e5: {moved:e} off the law without corrections");
}

#[test]
fn the_corner_law_keeps_the_h_c_asymptotes() {
    let (_, own) = blends();
    let cases = cases(&own, rho());
    let z: Vec<Coordinates> = cases
        .iter()
        .map(|c| Coordinates::new(own.asymptotes(c.m, c.l, 1.0), 1.0))
        .collect();
    let terms = lattice_terms_in_d(&z, LINE.level, LINE.ln_d_powers);
    let law = fit_corner(&cases, &own, rho(), &terms, LINE.ridges[0], false).expect("fits");
    for (name, m, l) in [
        ("RI", 1e-12, 0.0),
        ("RI, L > 0", 1e-12, 1e-3),
        ("EI", 1e40, 0.0),
        ("RP", 1.0, 1e120),
        ("EP", 1e60, 1e12),
    ] {
        let c = CornerCase {
            m,
            l,
            d: 1.0,
            h: 1.0,
            follows: false,
        };
        let ratio = eval(&law, &own, &c) / own.eval(m, l, 1.0);
        assert!((ratio - 1.0).abs() < 1e-3, "{name}: {ratio}");
    }
}
