//! The fitted formula as a product: its interior correction, its held-out errors and
//! `formula.py`, on the committed datasets (`tests/data/smoke-line`, 32 line cases on 2049
//! points; `tests/data/point-257`, 51 point cases on 257^2).
//!
//! * `formula.py` (standard-library Python) reproduces the Rust evaluation to 1e-12 relative for
//!   every film of both contacts, inside and far outside the data (python3 runs it), with every
//!   kind of correction term, a side-lobe factor, a corner law, kriging residuals and the exact
//!   D factor of the held point elastic-isoviscous law with its approach factor in play.
//! * The held-out procedure: every size it tries predicts each case by a fit that did not see
//!   it, so its held-out errors are never below the fitted ones; and the formula's asymptotes are
//!   the blend's, so far into each asymptotic corner the formula equals its asymptote.

use ehlmap::fit::corner::Corner;
use ehlmap::fit::correction::{lattice_terms, Coordinates, Correction, Term, TAIL};
use ehlmap::fit::dataset::load_fit_input;
use ehlmap::fit::fitted::Blend;
use ehlmap::fit::kriging::{self, Kriging, KrigingJump};
use ehlmap::fit::side::{tensor_powers, SideLobe};
use ehlmap::fit::support::{Support, FADE_WIDTH};
use ehlmap::limits::jump::JumpTable;
use ehlmap::report::formula_py::formula_py;
use ehlmap::report::{fit_report, FitReport, QuantityFit};
use std::io::Write;
use std::path::PathBuf;
use std::process::{Command, Stdio};

/// The fit of the committed data, the point H_pm elastic-isoviscous law held at its limit
/// (`ehlmap fit --point-ei-limit`: its exact D factor is then in the formula).
fn report() -> FitReport {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let mut input = load_fit_input(&[dir.join("smoke-line"), dir.join("point-257")]).unwrap();
    input.point_ei_limit = true;
    fit_report(&input, false).unwrap()
}

fn films(r: &FitReport) -> Vec<(bool, &QuantityFit)> {
    let line = [&r.line.h_c, &r.line.h_pm, &r.line.h_min];
    let point = [&r.point.h_c, &r.point.h_pm, &r.point.h_min];
    line.into_iter()
        .flatten()
        .map(|q| (false, q))
        .chain(point.into_iter().flatten().map(|q| (true, q)))
        .collect()
}

/// The committed line data choose nested terms; the line H_pm formula gets a lattice correction
/// too (Shifted and Cell bumps of both lattice levels over a grid of cases, fixed coefficients),
/// so that formula.py is checked on every kind of term; the point H_min gets a side-lobe factor.
fn with_lattice(mut r: FitReport) -> FitReport {
    let q = r.line.h_pm.as_mut().expect("line H_pm fitted");
    let mut z = vec![];
    for i in 0..30 {
        for l in [0.0, 0.5, 2.0, 8.0, 20.0] {
            let m = 10f64.powf(-1.0 + 0.15 * f64::from(i));
            z.push(Coordinates::new(q.model.blend.asymptotes(m, l, 1.0), 1.0));
        }
    }
    let mut lattice = lattice_terms(&z, 0);
    lattice.extend(lattice_terms(&z, 1));
    let levels: std::collections::HashSet<_> = lattice.iter().map(|t| t.level).collect();
    assert_eq!(levels.len(), 2, "both lattice levels: {levels:?}");
    let kinds: std::collections::HashSet<_> = lattice.iter().map(|t| t.transition).collect();
    assert_eq!(kinds.len(), 2, "both lattice kinds: {kinds:?}");
    let c = &mut q.model.correction;
    for (k, t) in lattice.clone().into_iter().enumerate() {
        c.terms.push(t);
        c.coef.push(0.01 * ((k % 7) as f64 - 3.0));
    }
    // The line H_c gets a corner law on its blend, both corrections on the same lattice, its
    // hinge active at some cases and not at others; so does the point H_c, with its bumps also
    // times ln D and (ln D)^2.
    let n_terms = lattice.len();
    let coef = |scale: f64, n: usize, terms: usize| -> Vec<f64> {
        (0..terms).map(|k| scale * ((k % n) as f64 - 1.0)).collect()
    };
    let with_d: Vec<Term> = (0..3u8)
        .flat_map(|n| {
            lattice.iter().map(move |t| Term {
                powers: [0, 0, 0, n, 0],
                ..*t
            })
        })
        .collect();
    for (q, terms, d) in [
        (r.line.h_c.as_mut().expect("line H_c fitted"), &lattice, 1.0),
        (
            r.point.h_c.as_mut().expect("point H_c fitted"),
            &with_d,
            0.3,
        ),
    ] {
        let n = terms.len();
        let corner = Corner {
            branch: Correction {
                terms: terms.clone(),
                coef: coef(0.005, 3, n),
                support: None,
            },
            deficit: Correction {
                terms: terms.clone(),
                coef: vec![-0.01; n],
                support: None,
            },
            rho: 0.2,
        };
        let b = &q.model.blend;
        let h: Vec<f64> = [(0.1, 0.0), (1.0, 4.0), (3.0, 20.0), (50.0, 2.0), (1e4, 0.0)]
            .iter()
            .map(|&(m, l)| corner.h(b.asymptotes(m, l, d), d))
            .collect();
        assert!(
            h.iter().any(|v| *v > 0.0) && h.iter().any(|v| *v < 0.0),
            "{h:?}"
        );
        q.model.corner = Some(corner);
    }
    assert!(n_terms > 0);
    // The point H_min gets a side-lobe factor (the committed point data predate H_min,cl), over
    // M 10 ... 1000, D 0.1 ... 1, L 0 ... 20, lifting nothing and 1 in part of the box, below
    // the ramp's start, M = 20, and below the ramp in D's, D = 0.1.
    let q = r.point.h_min.as_mut().expect("point H_min fitted");
    let powers = tensor_powers([2, 2, 2]);
    let side = SideLobe {
        lo: [10f64.ln(), 0.1f64.ln(), 0.0],
        hi: [1000f64.ln(), 0.0, 21f64.ln()],
        coef: (0..powers.len())
            .map(|k| 0.05 * ((k % 5) as f64 - 1.0))
            .collect(),
        powers,
        ramp: Some([20f64.ln(), 40f64.ln()]),
        ramp_d: Some([0.1f64.ln(), 0.2f64.ln()]),
        kriging: None,
    };
    let f: Vec<f64> = [
        (30.0, 0.0, 0.2),
        (500.0, 5.0, 1.0),
        (3e4, 40.0, 0.01),
        (0.3, 0.0, 1.0),
    ]
    .iter()
    .map(|&(m, l, d)| side.factor(m, l, d))
    .collect();
    assert!(f.contains(&1.0) && f.iter().any(|v| *v < 0.99), "{f:?}");
    assert_eq!(side.factor(500.0, 5.0, 0.1), 1.0);
    assert!(side.factor(500.0, 5.0, 0.15) != side.factor(500.0, 5.0, 0.2));
    // ... and a kriging residual in its box-clamped (ln M, ln(1 + L), ln D), weights of both
    // signs, which moves the factor at some cases.
    q.model.side = Some(side.clone());
    let mut side = side;
    let centres: Vec<[f64; 3]> = (0..24)
        .map(|k| {
            let k = f64::from(k);
            [
                10f64.ln() + 0.2 * k,
                21f64.ln() * (k % 4.0) / 3.0,
                0.1f64.ln() * (k % 3.0) / 2.0,
            ]
        })
        .collect();
    let weights = (0..centres.len())
        .map(|k| 0.02 * ((k % 5) as f64 - 2.0))
        .collect();
    side.kriging = Some(Kriging {
        scales: [1.0, 1.0, 2.0],
        c_floor: 0.0,
        nugget: 1e-3,
        centres,
        weights,
        jump: None,
        phis: vec![],
    });
    let plain = q.model.side.clone().unwrap_or_else(|| side.clone());
    let moved = [(500.0, 5.0, 1.0), (100.0, 1.0, 0.3), (1000.0, 20.0, 0.1)]
        .iter()
        .any(|&(m, l, d)| (side.factor(m, l, d) - plain.factor(m, l, d)).abs() > 1e-4);
    assert!(moved);
    assert_eq!(side.factor(0.3, 0.0, 1.0), 1.0);
    q.model.side = Some(side);
    // The point H_pm and the line H_min get kriging residuals, centred at cases over the data's
    // box, weights of both signs (the point one with the isoviscous plane at its c floor).
    for (q, ds) in [
        (
            r.point.h_pm.as_mut().expect("point H_pm fitted"),
            &[0.1, 0.3, 1.0][..],
        ),
        (
            r.line.h_min.as_mut().expect("line H_min fitted"),
            &[1.0][..],
        ),
    ] {
        let mut z = vec![];
        for i in 0..12 {
            for l in [0.0, 1.0, 5.0, 20.0] {
                for &d in ds {
                    let m = 10f64.powf(0.25 * f64::from(i));
                    z.push(Coordinates::new(q.model.blend.asymptotes(m, l, d), d));
                }
            }
        }
        let floor = kriging::c_floor(&z);
        let centres: Vec<[f64; 3]> = z.iter().map(|z| kriging::point(z, floor)).collect();
        let weights = (0..centres.len())
            .map(|k| 0.004 * ((k % 5) as f64 - 2.0))
            .collect();
        // The point one also takes the corner coordinate phi, on a table of ln M_j over L {0,
        // 5, 20} x D {0.1, 0.5, 1} (ln M_j = 2 + 0.1 ln(1 + L) - 0.7 ln D), which the cases
        // below cross and leave.
        let jump = (ds.len() > 1).then(|| {
            let (lu, lv) = (
                [0.0f64, 5.0, 20.0].map(f64::ln_1p),
                [0.1f64, 0.5, 1.0].map(f64::ln),
            );
            let ln_m = lu
                .iter()
                .map(|u| lv.iter().map(|v| 2.0 + 0.1 * u - 0.7 * v).collect())
                .collect();
            KrigingJump {
                table: JumpTable::new(lu.to_vec(), lv.to_vec(), ln_m).unwrap(),
                width: kriging::JUMP_WIDTH,
                scale: 0.5,
            }
        });
        let phis = match &jump {
            Some(_) => (0..centres.len())
                .map(|k| ((k % 3) as f64 - 1.0) * 0.9)
                .collect(),
            None => vec![],
        };
        let k = Kriging {
            scales: [2.0, 1.0, 2.0],
            c_floor: floor,
            nugget: 1e-3,
            centres,
            weights,
            jump,
            phis,
        };
        let b = &q.model.blend;
        let d = ds[0];
        assert!(k.log_factor(b.asymptotes(10.0, 1.0, d), 10.0, 1.0, d).abs() > 1e-4);
        q.model.kriging = Some(k);
    }
    r
}

#[test]
fn formula_py_reproduces_the_rust_evaluation() {
    let mut r = with_lattice(report());
    // A point correction that fades beyond its cases (src/fit/support.rs; the fits give one to
    // lattice corrections, and point-257's are nested): the support of M in [10, 1000] at the
    // data's D, so that formula.py's `_fade` is checked on the taper and beyond it.
    let pm = &mut r.point.h_pm.as_mut().expect("point H_pm fitted").model;
    let blend = pm.blend.clone();
    let a_of = |m: f64, d: f64| Coordinates::new(blend.asymptotes(m, 0.0, d), d).a;
    pm.correction.support = Support::of(
        [0.1f64, 0.25, 0.5, 1.0]
            .iter()
            .flat_map(|&d| [10.0, 1000.0].map(|m| (d.ln(), a_of(m, d)))),
    );
    // The point H_c corner law's two corrections fade too (the point fits give them the
    // support of their cases), each beyond its own range: M in [10, 1000] and [3, 300].
    let c = &mut r.point.h_c.as_mut().expect("point H_c fitted").model;
    let blend = c.blend.clone();
    let a_of = |m: f64, d: f64| Coordinates::new(blend.asymptotes(m, 0.0, d), d).a;
    let support = |lo: f64, hi: f64| {
        Support::of(
            [0.1f64, 0.25, 0.5, 1.0]
                .iter()
                .flat_map(|&d| [lo, hi].map(|m| (d.ln(), a_of(m, d)))),
        )
    };
    let corner = c.corner.as_mut().expect("the point H_c corner law");
    corner.branch.support = support(10.0, 1000.0);
    corner.deficit.support = support(3.0, 300.0);
    let dir = std::env::temp_dir().join(format!("ehlmap-formula-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("formula.py"), formula_py(&r)).unwrap();
    // (M, L, D) inside and far outside the data, L = 0 included.
    let mut cases = vec![];
    for m in [
        0.01, 0.3, 1.0, 3.7, 20.0, 150.0, 1000.0, 1800.0, 2600.0, 3800.0, 3e4, 1e5,
    ] {
        for l in [0.0, 0.5, 4.0, 10.0, 25.0, 40.0] {
            for d in [0.01, 0.1, 0.15, 0.45, 1.0] {
                cases.push((m, l, d));
            }
        }
    }
    let fs = films(&r);
    assert_eq!(fs.len(), 6, "every film of both contacts fitted");
    let pm = &r.point.h_pm.as_ref().expect("point H_pm fitted").model;
    let support = pm.correction.support.as_ref().expect("the support set");
    let on_taper = cases.iter().filter(|&&(m, l, d)| {
        let z = Coordinates::new(pm.blend.asymptotes(m, l, d), d);
        let f = support.fade(z.a, z.ln_d);
        f > 0.0 && f < 1.0
    });
    assert!(on_taper.count() >= 3);
    // A width beyond the largest a of the cases at each D, the correction is 0: the formula is
    // its blend (times its kriging residual).
    assert!(!pm.correction.terms.is_empty());
    for d in [0.1f64, 0.5, 1.0] {
        let (_, hi) = support.range(d.ln());
        let beyond = (0..80)
            .map(|k| 10f64.powf(f64::from(k) / 10.0))
            .map(|m| pm.blend.asymptotes(m, 0.0, d))
            .find(|a| Coordinates::new(*a, d).a >= hi + FADE_WIDTH)
            .expect("M up to 1e8 passes the data's a");
        assert_eq!(pm.correction.log_factor(beyond, d), 0.0);
    }
    let mut input = String::new();
    let mut want = vec![];
    for (point, q) in &fs {
        for &(m, l, d) in &cases {
            let (dd, dpy) = if *point {
                (d, format!("{d:?}"))
            } else {
                (1.0, "None".to_string())
            };
            input.push_str(&format!("{m:?} {l:?} {dpy} {}\n", q.quantity));
            want.push(q.model.eval(m, l, dd));
        }
    }
    let script = "import sys\nsys.path.insert(0, sys.argv[1])\nfrom formula import H\n\
        for row in sys.stdin:\n    m, l, d, f = row.split()\n    \
        print(repr(H(float(m), float(l), None if d == 'None' else float(d), f)))\n";
    let mut child = Command::new("python3")
        .arg("-c")
        .arg(script)
        .arg(&dir)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("python3 is needed to test formula.py");
    child
        .stdin
        .take()
        .unwrap()
        .write_all(input.as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let got: Vec<f64> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|s| s.parse().unwrap())
        .collect();
    assert_eq!(got.len(), want.len());
    let mut worst = 0.0f64;
    for (g, w) in got.iter().zip(&want) {
        assert!(w.is_finite() && *w > 0.0, "Rust value {w}");
        worst = worst.max((g / w - 1.0).abs());
    }
    assert!(worst < 1e-12, "worst relative difference {worst:e}");
    // Some correction is in play (else this test would not cover it).
    assert!(fs.iter().any(|(_, q)| !q.model.correction.terms.is_empty()));
    // The point H_pm's elastic-isoviscous law has the exact D factor (so the cases above check
    // formula.py's elliptic integrals at five D).
    let pm = &r
        .point
        .h_pm
        .as_ref()
        .expect("point H_pm fitted")
        .model
        .blend;
    assert!(matches!(pm, Blend::Point(p) if p.ei_exact), "{pm:?}");
    // The point H_c holds the law too, with its approach factor (fitted to the data's H_c cases
    // at L = 0 and M >= 100; the H_pm cases there, where H_pm is resolved, are no more than its
    // 6 coefficients of two powers, and H_pm keeps g = 1; the third power needs anchors).
    let c = &r.point.h_c.as_ref().expect("point H_c fitted").model.blend;
    assert!(
        matches!(c, Blend::Point(p) if p.ei_exact && p.x[16..22].iter().all(|c| *c != 0.0)),
        "{c:?}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn held_out_errors_are_not_below_the_fitted_ones_and_choose_a_size() {
    let r = report();
    for (_, q) in films(&r) {
        let h = q.heldout.as_ref().expect("held-out errors computed");
        assert_eq!(h.folds, 5);
        assert_eq!(h.sizes[0].terms, 0, "the blend alone is scored");
        assert_eq!(h.joint[0].terms, 0, "the blend alone is scored jointly too");
        assert!(h.joint.len() >= 2 && h.joint.len() <= 5, "{:?}", h.joint);
        // The candidate kept is a joint one; its figures are its own unless a corner law or a
        // kriging residual was kept on top of it, and then lower.
        let plain = h
            .joint
            .iter()
            .find(|s| s.candidate == h.chosen.candidate)
            .expect("the candidate kept is a joint one");
        if q.corner.is_none() && q.kriging.is_none() {
            assert_eq!(plain, &h.chosen);
        } else {
            assert!(h.chosen.rms < plain.rms, "{:?} vs {plain:?}", h.chosen);
        }
        assert_eq!(q.model.correction.terms.len(), h.chosen.terms);
        let best = h.joint.iter().map(|s| s.rms).fold(f64::INFINITY, f64::min);
        assert!(h.chosen.rms <= 1.02 * best);
        // The joint candidates are the blend alone and the best sizes of the cheap scores.
        let mut cheap: Vec<_> = h.sizes.iter().collect();
        cheap.sort_by(|a, b| a.rms.total_cmp(&b.rms));
        for c in &h.joint {
            assert!(c.terms == 0 || cheap[..4].iter().any(|s| s.terms == c.terms));
        }
        // Held-out RMS is an out-of-sample figure: not below the in-sample RMS of the same
        // formula (the final fit uses every case).
        assert!(
            h.chosen.rms >= q.overall.rms * 0.999,
            "{}: held-out {} vs fitted {}",
            q.quantity,
            h.chosen.rms,
            q.overall.rms
        );
    }
}

#[test]
fn far_into_each_asymptotic_corner_the_formula_is_its_asymptote() {
    // The correction vanishes where one asymptote dominates: at every (M, L) of a wide log grid
    // whose coordinates put it deep in a corner (|c| > 20 and a < -20 or a > 200 isoviscous, |b| > 20
    // piezoviscous: each bracket's asymptotes e^20 apart), the corrected formula equals the blend
    // to 1e-3, and the blend there is its asymptote. The grid is wide because the crossovers are
    // slow powers (the point H_EP/H_RP goes like (L/M)^(1/12)); only the range where the
    // asymptotes are normal f64 numbers counts.
    let r = report();
    for (point, q) in films(&r) {
        let d = if point { 0.5 } else { 1.0 };
        let mut seen = [false; 4];
        for i in (-300..=300).step_by(2) {
            let m = 10f64.powi(i);
            for j in -1..=300 {
                let l = if j < 0 { 0.0 } else { 10f64.powi(j - 6) };
                let asym = q.model.blend.asymptotes(m, l, d);
                let n = if l > 0.0 { 4 } else { 2 };
                if !asym[..n].iter().all(|h| h.is_normal()) {
                    // Beyond the range of f64 (M^-2 underflows at M = 1e160).
                    continue;
                }
                let z = Coordinates::new(asym, d);
                // The elastic-isoviscous corner lies deeper: the correction's tail term decays
                // there only like e^(-a/TAIL) (the slow approach of the data to that limit).
                let corner = if z.c < -20.0 && (z.a < -20.0 || z.a > 25.0 * TAIL) {
                    usize::from(z.a > 0.0)
                } else if z.c > 20.0 && z.b.abs() > 20.0 {
                    2 + usize::from(z.b < 0.0)
                } else {
                    continue;
                };
                seen[corner] = true;
                let ratio = q.model.correction.log_factor(asym, d).exp();
                assert!(
                    (ratio - 1.0).abs() < 1e-3,
                    "{} at M = {m:e}, L = {l:e}: formula / blend = {ratio} ({z:?}, {:?})",
                    q.quantity,
                    q.model
                        .correction
                        .terms
                        .iter()
                        .map(|t| t.eval(&z))
                        .collect::<Vec<_>>()
                );
            }
        }
        // RI, EI, RP, EP: both isoviscous corners and at least one piezoviscous one (with the
        // fitted exponents of these small datasets the other may lie beyond the f64 range).
        assert!(
            seen[0] && seen[1] && (seen[2] || seen[3]),
            "{}: corners visited {seen:?}",
            q.quantity
        );
    }
}
