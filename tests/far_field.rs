//! The asymptotic far field of point contacts (`PointDomainParams::far_field`,
//! src/discrete/point/far_field.rs): the film no longer depends on where the domain is cut.
//! References: the rigid circular contact's constants M^2 H_c = 35.5 and M^2 H_pm = 45.0
//! (known by extrapolating truncated domains enlarged 2, 4 and 8 times: issue 22), and, for the
//! elastic cases, the same solve on a domain twice as large at equal spacing.

use ehlmap::discrete::point::domain::PointDomainParams;
use ehlmap::fit::point_model::{nvm_ri_shape, ri_d_factor};
use ehlmap::limits::rigid_d_factor::ri_shape;
use ehlmap::limits::rigid_point::{C_RI_CENTRE, C_RI_PMAX};
use ehlmap::limits::rigid_rp::pi_law;
use ehlmap::model::case::{Elasticity, Models, PointCase};
use ehlmap::solve::film::Film;
use ehlmap::solve::params::Converge;
use ehlmap::solve::point::{solve_point, PointSolveParams};
use ehlmap::{solve, Case, SolveParams, Status};

/// A solve on `grid` points per direction, with or without the far field, on the default
/// domain scaled by `scale` (every extent of the domain rule).
fn run(case: &PointCase, grid: usize, far: bool, scale: f64) -> ehlmap::Outputs {
    run_with(case, grid, far, scale, Converge::Fast)
}

/// [`run`] with the stopping rule `converge` (tight for references).
fn run_with(
    case: &PointCase,
    grid: usize,
    far: bool,
    scale: f64,
    converge: Converge,
) -> ehlmap::Outputs {
    let mut p = PointSolveParams::default();
    p.mg.grid = grid;
    p.mg.converge = converge;
    p.mg.domain = PointDomainParams {
        far_field: far,
        ..p.mg.domain.scaled(scale)
    };
    let o = solve_point(case, &p).outputs;
    assert_eq!(
        o.status,
        Status::Converged,
        "{case:?} far {far} x{scale}: {}",
        o.reason
    );
    o
}

/// Tight far-field solves of `case` on the default domain (129^2) and on the domain doubled at
/// equal spacing (257^2; tight convergence: no algebraic error in the comparison), and the
/// relative changes of H_c and H_min between them (printed).
fn far_doubling(case: &PointCase) -> (ehlmap::Outputs, ehlmap::Outputs, f64, f64) {
    let a = run_with(case, 129, true, 1.0, Converge::Tight);
    let b = run_with(case, 257, true, 2.0, Converge::Tight);
    let (dc, dm) = (b.h_c / a.h_c - 1.0, b.h_min / a.h_min - 1.0);
    eprintln!(
        "M {} D {}: far field doubling H_c {dc:+.2e} H_min {dm:+.2e}",
        case.m, case.d
    );
    (a, b, dc, dm)
}

/// The first attempt (no fallback ladder) of an L = 0 case with `elasticity` on `grid` points per
/// direction, asserted converged; a minute's deadline turns a regression into a failure, not a
/// hang.
fn first_attempt(m: f64, d: f64, elasticity: Elasticity, grid: usize) -> ehlmap::Outputs {
    let models = Models {
        elasticity,
        ..Models::default()
    };
    let case = PointCase::with_models(m, 0.0, d, models).unwrap();
    let mut p = PointSolveParams::default();
    p.mg.grid = grid;
    p.fallback = false;
    p.mg.deadline = Some(std::time::Instant::now() + std::time::Duration::from_secs(60));
    let o = solve_point(&case, &p).outputs;
    assert_eq!(
        o.status,
        Status::Converged,
        "M = {m}, D = {d}: {}",
        o.reason
    );
    o
}

#[test]
fn rigid_circular_contact_meets_the_published_constants_in_one_solve() {
    let rigid = Models {
        elasticity: Elasticity::Rigid,
        ..Models::default()
    };
    let case = PointCase::with_models(1.0, 0.0, 1.0, rigid).unwrap();
    let o = run(&case, 257, true, 1.0);
    assert!((o.h_c - 35.5).abs() <= 0.3, "M^2 H_c = {}", o.h_c);
    assert!(
        (o.h_c_pmax - 45.0).abs() <= 0.4,
        "M^2 H_pm = {}",
        o.h_c_pmax
    );
    // The truncated domain of the same size is 30 % low.
    let cut = run(&case, 257, false, 1.0);
    assert!(cut.h_c < 0.75 * o.h_c, "{} vs {}", cut.h_c, o.h_c);
}

/// The rigid-isoviscous D factor (src/limits/rigid_d_factor.rs) against far-field solves at D
/// values that its shape was not fitted to (0.3, 0.03) and beyond them (0.003, near the exact
/// slender limit that fixes its exponent): Richardson over 257^2 and 513^2, tight convergence.
/// Measured 2026-11-29: -0.029, 0.029, 0.068 % (H_c) and -0.014, 0.011, 0.065 % (H_pm); the
/// solves lie 3.6 % (H_c) and 6.6 % (H_pm) below NVM's factor at D = 0.03. The same for the
/// rigid-piezoviscous factor pi(D) (src/limits/rigid_rp.rs), measured 2026-12-06: solver / law
/// 1.00019, 0.99972, 0.99938.
#[test]
fn rigid_d_factor_matches_far_field_solves_off_its_fitted_points() {
    let rigid = Models {
        elasticity: Elasticity::Rigid,
        ..Models::default()
    };
    for d in [0.3, 0.03, 0.003] {
        let case = PointCase::with_models(1.0, 0.0, d, rigid).unwrap();
        let [coarse, fine] = [257, 513].map(|g| run_with(&case, g, true, 1.0, Converge::Tight));
        let rich = |a: f64, b: f64| b + (b - a) / 3.0;
        for (film, c1, solver) in [
            (Film::Centre, C_RI_CENTRE, rich(coarse.h_c, fine.h_c)),
            (
                Film::PressureMax,
                C_RI_PMAX,
                rich(coarse.h_c_pmax, fine.h_c_pmax),
            ),
        ] {
            let ratio = solver / (c1 * ri_d_factor(ri_shape(film), d));
            assert!((ratio - 1.0).abs() < 2.5e-3, "D = {d} {film:?}: {ratio}");
            if d == 0.03 {
                let nvm = solver / (c1 * ri_d_factor(nvm_ri_shape(), d));
                assert!(nvm < 0.97, "NVM's factor is off here: {nvm}");
            }
        }
        // The rigid-piezoviscous D factor (src/limits/rigid_rp.rs) from the same solves:
        // pi(D) = (alpha_bar(M = 1, L = 1) P_max)^(2/3).
        let ab1 = PointCase::with_models(1.0, 1.0, d, rigid)
            .unwrap()
            .venner()
            .alpha_bar;
        let pi = |o: &ehlmap::Outputs| (ab1 * o.p_max).powf(2.0 / 3.0);
        let ratio = rich(pi(&coarse), pi(&fine)) / pi_law(d);
        println!("D = {d}: pi solver / law {ratio:.5}");
        assert!((ratio - 1.0).abs() < 2.5e-3, "D = {d} pi: {ratio}");
    }
}

/// Rigid-isoviscous circular contacts are one problem up to scale (the domain follows the
/// hydrodynamic length): M^2 H_c is the same at every M, and the tight solve converges at its
/// first attempt however small the pressures in Hertzian units (P of 1e-11 at M = 0.01). Before
/// the coarsest Newton solves took their tolerance relative to the pressure, M = 0.01 failed
/// every rung on 65^2 and M = 1e-3 ended max-iterations with M^2 H_c 5 % off.
#[test]
fn rigid_isoviscous_contacts_converge_alike_at_any_m() {
    let rigid = Models {
        elasticity: Elasticity::Rigid,
        ..Models::default()
    };
    let solve = |m: f64| {
        let case = PointCase::with_models(m, 0.0, 1.0, rigid).unwrap();
        let mut p = PointSolveParams::default();
        p.mg.grid = 65;
        p.mg.converge = Converge::Tight;
        let s = solve_point(&case, &p);
        let o = s.outputs;
        assert_eq!(o.status, Status::Converged, "M = {m}: {}", o.reason);
        assert!(!o.reason.contains("attempt"), "M = {m}: {}", o.reason);
        assert!(o.work_units < 500.0, "M = {m}: {} WU", o.work_units);
        m * m * o.h_c
    };
    let reference = solve(0.1);
    // 65^2 resolves the rigid constant 35.5 to a few per cent.
    assert!((reference - 35.5).abs() < 0.05 * 35.5, "{reference}");
    for m in [0.01, 1e-3, 1e-4] {
        let c = solve(m);
        assert!(
            (c / reference - 1.0).abs() < 1e-4,
            "M = {m}: {c} vs {reference}"
        );
    }
}

/// The same for slender rigid contacts under the default (fast) stopping rule: at D = 0.01 the
/// scales of the coarsest Newton rows spread with the film cubed (films of 1e10 Hertzian units at
/// M = 0.01), and without row equilibration its steps went wrong: on 33^2, M = 1 took 90 work
/// units and M = 0.01 1171 (fourteen cycles whose Newton solves all stalled), M = 0.01 at
/// D = 0.03 and M = 1e-3 at D = 0.1 ended max-iterations. Now every M takes the cycles and work
/// of M = 1, and M^2 H_c agrees to the algebraic error.
#[test]
fn rigid_slender_contacts_converge_alike_at_any_m() {
    for d in [0.01, 0.1] {
        let solve = |m: f64| {
            let o = first_attempt(m, d, Elasticity::Rigid, 33);
            (
                m * m * o.h_c,
                o.work_units,
                o.algebraic_error.unwrap_or(f64::NAN),
            )
        };
        let (reference, wu, err) = solve(1.0);
        for m in [0.01, 1e-3] {
            let (c, w, e) = solve(m);
            assert!(
                (c / reference - 1.0).abs() <= 2.0 * (err + e),
                "D = {d}, M = {m}: {c} vs {reference} (algebraic {e:.1e}, {err:.1e})"
            );
            assert!(
                w <= 1.5 * wu,
                "D = {d}, M = {m}: {w} WU against {wu} at M = 1"
            );
        }
    }
}

/// An elastic contact at M of 1e-3 or 1e-4 deforms by a negligible part of its film, so it is
/// the rigid contact: the same film to the algebraic error, at the same cost. Before the row
/// equilibration of the coarsest Newton, M = 1e-3, D = 0.1 did not finish on 33^2 or 65^2
/// within two minutes (the rigid model: 3339 WU, max-iterations on 33^2), and the default
/// solve with the full model diverged after 268 s with a negative film.
#[test]
fn elastic_contacts_at_tiny_m_solve_as_rigid_ones() {
    for (m, d) in [(1e-3, 0.1), (1e-4, 1.0)] {
        let solve = |elasticity| first_attempt(m, d, elasticity, 65);
        let (elastic, rigid) = (solve(Elasticity::Elastic), solve(Elasticity::Rigid));
        assert!(
            (elastic.h_c / rigid.h_c - 1.0).abs() < 1e-5,
            "M = {m}, D = {d}: {} vs {}",
            elastic.h_c,
            rigid.h_c
        );
        assert!(
            elastic.work_units <= 1.5 * rigid.work_units,
            "M = {m}, D = {d}: {} WU against {}",
            elastic.work_units,
            rigid.work_units
        );
    }
}

#[test]
fn doubling_the_domain_leaves_the_far_field_film_unchanged() {
    // L = 0 where the rigid-like pressure spreads far: the truncated domain's film rises by
    // 2-20 % when the domain doubles (docs/known-limits.md); with the far field it moves by
    // less than 0.3 %, and the next doubling far less (below), so the default domain is within
    // the 0.5 % of the unbounded one. Equal spacing: 129 points on the default domain,
    // 257 on the doubled one (cases whose extents are all set by the hydrodynamic length, so
    // they double exactly).
    for (m, d) in [(1.0, 1.0), (3.0, 0.25), (5.0, 1.0), (10.0, 0.25)] {
        let case = PointCase::new(m, 0.0, d).unwrap();
        let tight = |grid, scale| run_with(&case, grid, true, scale, Converge::Tight);
        let (a, b, dc, dm) = far_doubling(&case);
        assert!(dc.abs() < 3e-3 && dm.abs() < 3e-3, "M {m} D {d}: {dc} {dm}");
        if m == 5.0 {
            // The largest first change before the far film took the load's deformation
            // (measured 0.19 % and 0.27 %; since then -0.001 % and -0.019 %): the second
            // doubling moves the film by a tenth of it.
            let c = tight(513, 4.0);
            let (dc2, dm2) = (c.h_c / b.h_c - 1.0, c.h_min / b.h_min - 1.0);
            eprintln!("M {m} D {d}: second doubling H_c {dc2:+.2e} H_min {dm2:+.2e}");
            assert!(dc2.abs() < 5e-4 && dm2.abs() < 5e-4, "{dc2} {dm2}");
        }
        let (ta, tb) = (run(&case, 129, false, 1.0), run(&case, 257, false, 2.0));
        let cut = tb.h_c / ta.h_c - 1.0;
        assert!(
            cut > 0.02,
            "M {m} D {d}: the truncated domain moved by {cut} only"
        );
        // The far-field film lies above the truncated one by more than the first doubling
        // raises the latter: the bias that the later doublings would still add.
        assert!(a.h_c > tb.h_c, "M {m} D {d}: {} vs {}", a.h_c, tb.h_c);
    }
}

/// Elastic isoviscous contacts between the rigid-like and the Hertzian regime: the far film
/// carries the load's deformation coef W/R (src/discrete/point/far_field.rs). Without it their
/// films rose by 0.34 % / 0.63 % (H_c / H_min at (7.2, 0, 1)) and 0.35 % / 0.63 % (at
/// (20, 0, 0.25)) when the domain doubled at equal spacing (129^2 -> 257^2), above the 0.3 %
/// that the far field's truncation estimate assumes (src/discrete/point/domain.rs).
#[test]
fn the_far_film_carries_the_load_deformation() {
    for (m, d) in [(7.2, 1.0), (20.0, 0.25)] {
        let (_, _, dc, dm) = far_doubling(&PointCase::new(m, 0.0, d).unwrap());
        assert!(dc.abs() < 2e-3 && dm.abs() < 2e-3, "M {m} D {d}: {dc} {dm}");
    }
}

#[test]
fn the_far_field_costs_no_more_than_twice_the_truncated_domain() {
    // Work units are deterministic: the same on every machine.
    for m in [1.0, 3.0, 5.0, 10.0, 20.0, 100.0] {
        let case = PointCase::new(m, 0.0, 1.0).unwrap();
        let (far, cut) = (run(&case, 129, true, 1.0), run(&case, 129, false, 1.0));
        eprintln!(
            "M {m}: {:.1} WU against {:.1}",
            far.work_units, cut.work_units
        );
        assert!(
            far.work_units <= 2.0 * cut.work_units,
            "M {m}: {} WU against {}",
            far.work_units,
            cut.work_units
        );
    }
}

#[test]
fn with_the_far_field_the_default_target_is_met_at_m_10() {
    // Circular M = 10, L = 0: the truncated domain's estimate (3.9 %) breaks the 1 % target;
    // with the far field the estimate is the discretisation's and meets it.
    let case = Case::Point(PointCase::new(10.0, 0.0, 1.0).unwrap());
    // The library default (the far field is on by default).
    let params = SolveParams::default();
    assert!(params.point_domain.far_field);
    let s = solve(&case, &params);
    let o = &s.outputs;
    assert_eq!(o.status, Status::Converged, "{}", o.reason);
    assert_eq!(o.accuracy_met, Some(true), "{}", o.reason);
    assert!(o.error_estimate.unwrap() <= 0.01);
    assert!(!o.reason.contains("rigid-like"), "{}", o.reason);
    // Within its estimate of the far-field film on a finer grid.
    let fine = run(
        &PointCase::new(10.0, 0.0, 1.0).unwrap(),
        2 * (o.grid - 1) + 1,
        true,
        1.0,
    );
    let err = (o.h_c / fine.h_c - 1.0)
        .abs()
        .max((o.h_min / fine.h_min - 1.0).abs());
    assert!(
        err <= o.error_estimate.unwrap(),
        "{err} vs {:?}",
        o.error_estimate
    );
}

#[test]
fn the_fast_rule_stops_near_the_tight_solution_with_the_far_field() {
    // The fast stopping rule against the tight solution on the same grid (257^2), on the two
    // cases tests/point_contact.rs checks on the truncated domain. With the far field the
    // algebraic estimate is low by up to 2.5x here (measured 2026-11-26: (1, 0, 0.5) 9.4e-5
    // against 5.1e-5, (7.2, 20, 1) 6.9e-4 against 2.8e-4; the load carried by the far field
    // settles at about 0.7 per cycle while H_c hardly moves, docs/known-limits.md), so this
    // bound is 6x the estimate where the truncated domain's is 1x; both stay below 1e-3, a
    // tenth of the 1 % target. (Loosened from 3x on 2026-11-29, when the far film took the
    // load's deformation: (7.2, 20, 1) then stops 7.8e-4 from the tight solution against an
    // estimate of 2.2e-4, 3.5x; (1, 0, 0.5) 9.7e-5 against 9.3e-5. Loosened from 4x to 6x on
    // 2026-12-01, when a first attempt below L = 25 stopped freezing the band: (7.2, 20, 1)
    // then stops 7.4e-4 from the tight solution against an estimate of 1.4e-4, 5.3x.)
    for (m, l, d) in [(1.0, 0.0, 0.5), (7.2, 20.0, 1.0)] {
        let case = PointCase::new(m, l, d).unwrap();
        let fast = run(&case, 257, true, 1.0);
        let tight = run_with(&case, 257, true, 1.0, Converge::Tight);
        let alg = fast.algebraic_error.expect("an estimate");
        for (f, t) in [(fast.h_c, tight.h_c), (fast.h_min, tight.h_min)] {
            let e = (f / t - 1.0).abs();
            eprintln!("({m}, {l}, {d}): fast {f} tight {t}: {e:.1e}, estimate {alg:.1e}");
            assert!(e < 1e-3 && e <= 6.0 * alg, "{e} vs {alg}");
        }
    }
}

#[test]
fn a_spike_case_that_the_frozen_band_loses_converges_without_it() {
    // The nightly point sweep's M = 19.3, L = 20, D = 1 on 513^2: with the far field the
    // V cycles' residual grows from 2.4e-3 to 0.28 on the finest level (diverged) while the
    // coarse grids freeze the band along the cavitation boundary; the same cycles without the
    // band (the fast rule kept), the first attempt below L = 25, converge. Checks: the same
    // iteration run on for its whole cycle budget (algebraic error cap 1e-5) stays within the
    // answer's algebraic error estimate (measured: H_c 7.439478 against 7.439432, 6e-6,
    // estimate 6.1e-5), and H_c agrees with the truncated domain's (7.356) to within the far
    // field's effect at this M (about 1 %) and with the same case on a domain 1.25 times larger
    // (7.437). (The W cycles with the band, the rung that answered before this one existed,
    // give 7.438252: 1.6e-4 away, above their own estimate.)
    let case = PointCase::new(19.306977288832496, 20.0, 1.0).unwrap();
    let mut p = PointSolveParams::default();
    p.mg.grid = 513;
    let o = solve_point(&case, &p);
    assert_eq!(o.outputs.status, Status::Converged, "{}", o.outputs.reason);
    assert_eq!(o.attempt, 1, "{}", o.outputs.reason);
    assert!(
        (o.outputs.h_c / 7.437 - 1.0).abs() < 2e-3,
        "{}",
        o.outputs.h_c
    );
    let mut on = p;
    on.mg.max_algebraic = 1e-5;
    on.mg.freeze_band = Some(false);
    on.fallback = false;
    let r = solve_point(&case, &on).outputs;
    let alg = o.outputs.algebraic_error.expect("an estimate");
    for (a, b) in [(o.outputs.h_c, r.h_c), (o.outputs.h_min, r.h_min)] {
        let d = (a / b - 1.0).abs();
        eprintln!("unfrozen {a} run on {b}: {d:.1e}, estimate {alg:.1e}");
        assert!(d <= alg, "{a} vs {b}: {d:.1e} (estimate {alg:.1e})");
    }
}

/// Below alpha_bar = 5 the point coarse grids correct the outlet region up to the cavitation
/// boundary (the consistent residual restriction, no frozen nodes: docs/method.md, "The free
/// boundary on the coarse grids"). Isoviscous circular cases on 513^2 then converge in a few
/// cycles, and the stopping rule's algebraic error estimate bounds the distance of H_c and H_min
/// to the tightly converged answer on the same grid. With the frozen band, M = 20 took 47.6 work
/// units, and M = 2.68 stopped after 11.5 claiming 3.5e-5 with H_c 3.2e-4 off.
#[test]
fn isoviscous_cases_converge_in_few_cycles_with_an_honest_algebraic_error() {
    for (m, max_wu) in [(2.68269579528, 45.0), (20.0, 15.0)] {
        let case = PointCase::new(m, 0.0, 1.0).unwrap();
        let mut p = PointSolveParams::default();
        p.mg.grid = 513;
        p.fallback = false;
        let fast = solve_point(&case, &p);
        p.mg.converge = Converge::Tight;
        let tight = solve_point(&case, &p).outputs;
        let (o, info) = (&fast.outputs, &fast.info);
        assert_eq!(o.status, Status::Converged, "M = {m}: {}", o.reason);
        assert_eq!(tight.status, Status::Converged, "M = {m}: {}", tight.reason);
        let e_a = info.algebraic_error.expect("the fast rule's estimate");
        for (name, a, b) in [("H_c", o.h_c, tight.h_c), ("H_min", o.h_min, tight.h_min)] {
            let dev = (a / b - 1.0).abs();
            assert!(
                dev <= e_a,
                "M = {m}: {name} {a} vs tight {b}: {dev:.1e} > estimate {e_a:.1e}"
            );
        }
        assert!(
            o.work_units <= max_wu,
            "M = {m}: {} work units",
            o.work_units
        );
    }
}

/// Where the point coarse grids freeze the band along the cavitation boundary (alpha_bar >= 5),
/// a slow mode there can leave H_c and H_min almost unchanged over the first finest cycles and
/// move them later; the finest level's residual bound (`MgParams::residual_bound`,
/// docs/method.md "The algebraic error estimate and its residual bound") keeps the algebraic
/// error estimate above the true distance to the tightly converged answer. Without it (c = 0)
/// circular M = 1, L = 20 on 257^2 stopped after 12.7 work units claiming 1.6e-5 with H_c
/// 5.1e-4 off, and M = 3, L = 10 after 13.1 claiming 8.5e-5 with 5.8e-4 off: this test checks
/// both rules with the band frozen (`freeze_band` Some(true); a first attempt freezes it from
/// L = 25 on), and the default first attempt without the band, which takes the bound too.
#[test]
fn slow_modes_at_the_cavitation_boundary_stay_inside_the_algebraic_estimate() {
    for (m, l) in [(1.0, 20.0), (3.0, 10.0)] {
        let case = PointCase::new(m, l, 1.0).unwrap();
        let tight = run_with(&case, 257, true, 1.0, Converge::Tight);
        let dev = |o: &ehlmap::solve::solution::Solution| {
            let o = &o.outputs;
            (o.h_c / tight.h_c - 1.0)
                .abs()
                .max((o.h_min / tight.h_min - 1.0).abs())
        };
        let mut p = PointSolveParams::default();
        p.mg.grid = 257;
        p.fallback = false;
        for band in [None, Some(true)] {
            p.mg.freeze_band = band;
            let fast = solve_point(&case, &p);
            assert_eq!(
                fast.outputs.status,
                Status::Converged,
                "{}",
                fast.outputs.reason
            );
            let e_a = fast.info.algebraic_error.expect("the fast rule's estimate");
            assert!(
                dev(&fast) <= e_a,
                "M = {m}, L = {l}, band {band:?}: {:.1e} from the tight answer, estimate {e_a:.1e}",
                dev(&fast)
            );
        }
        p.mg.residual_bound = 0.0;
        let unbounded = solve_point(&case, &p);
        let e_0 = unbounded.info.algebraic_error.unwrap();
        assert!(
            dev(&unbounded) > 3.0 * e_0,
            "M = {m}, L = {l}: without the bound {:.1e} from the tight answer, estimate {e_0:.1e}",
            dev(&unbounded)
        );
    }
}
