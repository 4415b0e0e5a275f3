//! Point contacts against independent references: the Hertz ellipsoid (dry limit), the classic
//! FMG code's grid-converged circular case (PHYSICS.md section 6), second-order grid convergence,
//! load conservation and P >= 0, and honest statuses on extreme input. On the classic
//! references' domain: P = 0 on its boundary ([`classic`]; the default far field has its own
//! tests in tests/far_field.rs).

use ehlmap::discrete::point::operator::PointPhysics;
use ehlmap::model::case::PointCase;
use ehlmap::solve::fmg::fmg_solve;
use ehlmap::solve::params::{Converge, Method};
use ehlmap::solve::point::multigrid::PointMultigrid;
use ehlmap::solve::point::{solve_point, PointMgParams, PointSolveParams};
use ehlmap::solve::Status;

/// The default multigrid settings on the truncated domain of the classic references.
fn classic() -> PointMgParams {
    let mut p = PointMgParams::default();
    p.domain.far_field = false;
    p
}

fn solve(m: f64, l: f64, d: f64, grid: usize) -> ehlmap::Solution {
    solve_with(m, l, d, grid, Converge::Fast)
}

fn solve_with(m: f64, l: f64, d: f64, grid: usize, converge: Converge) -> ehlmap::Solution {
    let case = PointCase::new(m, l, d).unwrap();
    let p = PointSolveParams {
        mg: PointMgParams {
            grid,
            converge,
            ..classic()
        },
        keep_fields: true,
        ..Default::default()
    };
    solve_point(&case, &p)
}

#[test]
fn dry_contact_gives_the_hertz_ellipsoid() {
    for d in [1.0, 0.5, 0.15] {
        let case = PointCase::new(100.0, 0.0, d).unwrap();
        let mut phys = PointPhysics::from_case(&case);
        phys.dry = true;
        let mut errs = vec![];
        let mut h0s = vec![];
        for grid in [33, 65] {
            let params = PointMgParams {
                grid,
                converge: Converge::Tight,
                ..Default::default()
            };
            let mut mg = PointMultigrid::with_physics(&case, phys, &params);
            let info = fmg_solve(&mut mg);
            assert_eq!(info.status, Status::Converged, "D={d}: {}", info.reason);
            let lv = mg.levels.last().unwrap();
            let k = phys.k;
            let mut err: f64 = 0.0;
            for j in 0..lv.ny {
                for i in 0..lv.nx {
                    let (x, y) = (lv.x[i], lv.y[j] / k);
                    // Away from the edge, where the square-root profile limits the accuracy.
                    if x * x + y * y < 0.8 {
                        let hertz = (1.0 - x * x - y * y).sqrt();
                        err = err.max((lv.p[lv.at(i, j)] - hertz).abs());
                    }
                }
            }
            errs.push(err);
            h0s.push(mg.h0);
        }
        // Inside the contact H = 0, so at its centre H0 = -c * integral sqrt(1 - X^2 - (Y/k)^2)/R
        // = -c pi F (b = 1): H0 = -(1 + D) F/(2 E) exactly (-1 for the circle).
        let el = case.ellipse();
        let exact = -(1.0 + d) * el.f / (2.0 * el.e);
        let rel: Vec<f64> = h0s.iter().map(|h| (h / exact - 1.0).abs()).collect();
        assert!(
            rel[1] < 2e-3 && rel[1] < rel[0],
            "D={d}: H0 {h0s:?} vs {exact}"
        );
        // Pointwise error is largest at the edge of the contact (a square-root profile), where
        // it falls like sqrt(h).
        assert!(errs[1] < 0.12, "D={d}: max |P - Hertz| {errs:?}");
        assert!(
            errs[1] < 0.85 * errs[0],
            "D={d}: no convergence to Hertz {errs:?}"
        );
    }
}

#[test]
fn circular_reference_case_and_second_order_convergence() {
    // Classic FMG code, 512^2 on [-4.5, 1.5] x [-3, 3]: H_c = 4.801, H_min = 2.960 (Moes units).
    // Converged to the tolerances (tight): the load balance to 2e-6 and the observed order.
    let sols: Vec<_> = [65, 129, 257]
        .iter()
        .map(|&g| solve_with(20.0, 10.0, 1.0, g, Converge::Tight))
        .collect();
    for s in &sols {
        assert_eq!(s.info.status, Status::Converged, "{}", s.info.reason);
        assert!(s.outputs.load_error.abs() < 2e-6);
        let f = s.fields.as_ref().unwrap();
        assert!(f.p.iter().all(|&p| p >= 0.0 && p.is_finite()));
    }
    let hc: Vec<f64> = sols.iter().map(|s| s.outputs.h_c).collect();
    let hm: Vec<f64> = sols.iter().map(|s| s.outputs.h_min).collect();
    let fine = &sols[2].outputs;
    assert!((fine.h_c / 4.80 - 1.0).abs() < 0.005, "H_c {hc:?}");
    assert!((fine.h_min / 2.96 - 1.0).abs() < 0.01, "H_min {hm:?}");
    let order = ((hc[1] - hc[0]) / (hc[2] - hc[1])).log2();
    assert!((order - 2.0).abs() < 0.3, "order {order}, H_c {hc:?}");
    let extrapolated = hc[2] + (hc[2] - hc[1]) / 3.0;
    assert!(
        (extrapolated / 4.801 - 1.0).abs() < 0.002,
        "Richardson {extrapolated}"
    );
    assert_eq!(fine.d, Some(1.0));
    assert_eq!(fine.k, Some(1.0));
    // The minimum film sits in the two side lobes, symmetric in Y, near the outlet.
    let y_min = fine.y_min.unwrap();
    assert!(y_min.abs() > 0.3 && fine.x_min > 0.0, "{fine:?}");
    // The default stopping rule (at a tenth of the discretisation error): the same reference
    // values, and within 0.1 % of the tight solution on the same grid, with the algebraic error
    // it reports bounding the difference.
    let fast = solve(20.0, 10.0, 1.0, 257).outputs;
    assert_eq!(fast.status, Status::Converged, "{}", fast.reason);
    assert!((fast.h_c / 4.80 - 1.0).abs() < 0.005, "H_c {}", fast.h_c);
    assert!(
        (fast.h_min / 2.96 - 1.0).abs() < 0.01,
        "H_min {}",
        fast.h_min
    );
    let alg = fast.algebraic_error.expect("an algebraic error estimate");
    for (f, t) in [(fast.h_c, fine.h_c), (fast.h_min, fine.h_min)] {
        let d = (f / t - 1.0).abs();
        assert!(
            d < 1e-3 && d <= alg,
            "fast {f} tight {t}: {d:.1e} (estimate {alg:.1e})"
        );
    }
}

/// The node minimum of the film on the row Y = 0 and its X: the slow oracle of `H_min_cl`.
fn centre_row_minimum(s: &ehlmap::Solution) -> (f64, f64) {
    let f = s.fields.as_ref().unwrap();
    let nx = f.x.len();
    let j =
        f.y.iter()
            .position(|y| y.abs() < 1e-12)
            .expect("a node row at Y = 0");
    (1..nx - 1)
        .map(|i| (f.h[j * nx + i], f.x[i]))
        .fold((f64::INFINITY, 0.0), |a, b| if b.0 < a.0 { b } else { a })
}

#[test]
fn the_centre_line_minimum_is_the_y_0_rows_and_a_branch_of_h_min() {
    // Circular M = 20, L = 10: the minimum is in the side lobes; the centre line's own minimum
    // (the exit constriction on Y = 0) is a thicker second branch, converging at second order.
    let sols: Vec<_> = [65, 129, 257]
        .iter()
        .map(|&g| solve(20.0, 10.0, 1.0, g))
        .collect();
    let mut cl = vec![];
    for s in &sols {
        let o = &s.outputs;
        assert_eq!(o.status, Status::Converged, "{}", o.reason);
        let c = o
            .centre_line
            .expect("a point solve reports the centre line");
        let (node, x_node) = centre_row_minimum(s);
        let f = s.fields.as_ref().unwrap();
        let hx = f.x[1] - f.x[0];
        // The parabola through the node minimum and its neighbours: at most the node value, by
        // far less than the film's variation over a cell, and within a cell of the node.
        assert!(
            c.h_min <= node && c.h_min > node * (1.0 - 1e-2),
            "{} {node}",
            c.h_min
        );
        assert!((c.x_min - x_node).abs() <= hx, "{} {x_node}", c.x_min);
        assert!(
            c.h_min > 1.1 * o.h_min,
            "side lobes: {} vs {}",
            c.h_min,
            o.h_min
        );
        assert!(o.y_min.unwrap().abs() > 0.3);
        cl.push(c.h_min);
    }
    let order = ((cl[1] - cl[0]) / (cl[2] - cl[1])).abs().log2();
    assert!(order > 1.4 && order < 2.6, "order {order}: {cl:?}");
    // A slender contact without side lobes (D = 0.1, L = 0): the minimum is on the centre line,
    // and the two are the same film.
    let s = solve(100.0, 0.0, 0.1, 129);
    let o = &s.outputs;
    assert_eq!(o.status, Status::Converged, "{}", o.reason);
    let c = o.centre_line.unwrap();
    // (The global minimum's parabola in Y puts it a hair off the row: 3.5e-5 here, a grid
    // spacing being 5e-2.)
    assert!(o.y_min.unwrap().abs() < 1e-3, "{:?}", o.y_min);
    assert!(
        (c.h_min / o.h_min - 1.0).abs() < 1e-9,
        "{} {}",
        c.h_min,
        o.h_min
    );
    assert!((c.x_min - o.x_min).abs() < 1e-9);
}

#[test]
fn extreme_inputs_end_with_a_status_and_no_nan() {
    // Corners of the required box M in [1, 2000], L in [0, 20], D in [0.05, 1], on a coarse
    // grid: each solve ends with a status and a reason; a converged one has finite outputs and
    // conserves the load.
    for (m, l, d) in [
        (1.0, 20.0, 0.05),
        (2000.0, 0.0, 1.0),
        (2000.0, 20.0, 0.05),
        (1.0, 0.0, 1.0),
    ] {
        for converge in [Converge::Fast, Converge::Tight] {
            let s = solve_with(m, l, d, 33, converge);
            let o = &s.outputs;
            assert!(!o.reason.is_empty());
            if o.status == Status::Converged {
                for v in [o.h_c, o.h_min, o.p_max, o.h0, o.f, o.load_error] {
                    assert!(v.is_finite(), "M={m} L={l} D={d}: {o:?}");
                }
                if converge == Converge::Tight {
                    assert!(o.load_error.abs() < 2e-6);
                } else {
                    // The load error is part of the reported algebraic error.
                    assert!(
                        2.0 * o.load_error.abs() <= o.algebraic_error.unwrap(),
                        "{o:?}"
                    );
                }
                if o.h_min <= 0.0 {
                    assert!(o.reason.contains("warning"), "{}", o.reason);
                }
            }
            let f = s.fields.as_ref().unwrap();
            assert!(f.p.iter().all(|p| p.is_finite() && *p >= 0.0));
        }
    }
}

#[test]
fn elliptic_films_follow_nvm_where_it_is_a_good_fit() {
    // NVM 1994 was fitted to 1990s numerics; in the elastic-piezoviscous band M in [10, 100],
    // L = 10 it is within a few per cent of converged solutions (measured: -4 % to +2 % on 129^2).
    for (m, d) in [(30.0, 0.5), (100.0, 0.25), (30.0, 1.0)] {
        let s = solve(m, 10.0, d, 129);
        assert_eq!(s.outputs.status, Status::Converged, "{}", s.outputs.reason);
        let nvm = ehlmap::model::formulas::nvm_point_hc(m, 10.0, d);
        let dev = s.outputs.h_c / nvm - 1.0;
        assert!(
            dev.abs() < 0.06,
            "M={m} D={d}: H_c {} vs NVM {nvm}",
            s.outputs.h_c
        );
        // The film at the pressure maximum and the minimum film sit below the central film.
        assert!(s.outputs.h_min < s.outputs.h_c);
    }
}

#[test]
fn parallel_rows_give_the_same_answer_whatever_the_thread_count() {
    // Blocks of rows relaxed at once on a rayon pool: the same discrete solution as the serial
    // row order (to the convergence tolerance), and bit-identical results for 1 and 2 threads.
    let case = PointCase::new(20.0, 10.0, 0.5).unwrap();
    let mut p = PointSolveParams::default();
    p.mg.converge = Converge::Tight;
    let serial = solve_point(&case, &p).outputs;
    p.mg.parallel = true;
    let run = |n: usize, p: &PointSolveParams| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .unwrap()
            .install(|| solve_point(&case, p).outputs)
    };
    let (one, two) = (run(1, &p), run(2, &p));
    assert_eq!(one.status, Status::Converged, "{}", one.reason);
    assert_eq!(one.h_c.to_bits(), two.h_c.to_bits());
    assert_eq!(one.h_min.to_bits(), two.h_min.to_bits());
    assert_eq!(one.work_units, two.work_units);
    assert!(
        (one.h_c / serial.h_c - 1.0).abs() < 1e-5,
        "{} vs {}",
        one.h_c,
        serial.h_c
    );
    assert!((one.h_min / serial.h_min - 1.0).abs() < 1e-5);
    // The default stopping rule is as reproducible, also with 3 threads (rows and FFT columns
    // split unevenly between the jobs).
    p.mg.converge = Converge::Fast;
    let (one, two, three) = (run(1, &p), run(2, &p), run(3, &p));
    assert_eq!(one.status, Status::Converged, "{}", one.reason);
    for other in [&two, &three] {
        assert_eq!(one.h_c.to_bits(), other.h_c.to_bits());
        assert_eq!(one.h_min.to_bits(), other.h_min.to_bits());
    }
}

#[test]
fn newton_relaxation_and_multigrid_solve_the_same_discrete_problem() {
    // Same discretisation, same answer: dense Newton and multigrid agree to 1e-6 on 33^2; the
    // smoother alone needs far more work than multigrid for the same answer.
    let case = PointCase::new(20.0, 10.0, 1.0).unwrap();
    let with = |method: Method| {
        let p = PointSolveParams {
            method,
            relax_max_sweeps: 3000,
            mg: PointMgParams {
                grid: 33,
                converge: Converge::Tight,
                ..classic()
            },
            ..Default::default()
        };
        solve_point(&case, &p).outputs
    };
    let (mg, newton, relax) = (
        with(Method::Multigrid),
        with(Method::Newton),
        with(Method::Relax),
    );
    assert_eq!(newton.status, Status::Converged, "{}", newton.reason);
    assert_eq!(mg.status, Status::Converged, "{}", mg.reason);
    assert!(
        (newton.h_c / mg.h_c - 1.0).abs() < 1e-6,
        "{} vs {}",
        newton.h_c,
        mg.h_c
    );
    assert!((newton.h_min / mg.h_min - 1.0).abs() < 1e-6);
    assert_eq!((newton.levels, relax.levels), (1, 1));
    assert!(
        relax.work_units > 5.0 * mg.work_units,
        "{} vs {}",
        relax.work_units,
        mg.work_units
    );
    assert!(
        (relax.h_c / mg.h_c - 1.0).abs() < 1e-3,
        "{} vs {}",
        relax.h_c,
        mg.h_c
    );
}

/// The domain-truncation bias law (`PointDomain::bias` = 0.25 w): doubling the inlet and side
/// extents raises H_c or H_min by about that much in rigid-like cases, and by almost nothing
/// in an elastic one.
#[test]
fn domain_bias_estimate_matches_a_doubled_domain() {
    use ehlmap::discrete::point::domain::PointDomain;
    for (m, d) in [(5.0, 1.0), (20.0, 0.25), (30.0, 1.0)] {
        let case = PointCase::new(m, 0.0, d).unwrap();
        let bias = PointDomain::of_case(&case, &classic().domain).bias();
        let solve = |f: f64| {
            let mut p = PointSolveParams {
                mg: classic(),
                ..Default::default()
            };
            p.mg.grid = 129;
            let dom = &mut p.mg.domain;
            dom.inlet_lh *= f;
            dom.inlet_elastic *= f;
            dom.side *= f;
            dom.side_lh *= f;
            let o = solve_point(&case, &p).outputs;
            assert_eq!(o.status, Status::Converged, "{}", o.reason);
            o
        };
        let (a, b) = (solve(1.0), solve(2.0));
        let rise = (b.h_c / a.h_c - 1.0).max(b.h_min / a.h_min - 1.0);
        println!("M={m} D={d}: rise {rise:.4}, bias estimate {bias:.4}");
        if bias >= 0.01 {
            assert!(
                rise > 0.6 * bias && rise < 1.2 * bias,
                "rise {rise}, bias {bias}"
            );
            assert!(
                a.reason.contains("caution: rigid-like case"),
                "{}",
                a.reason
            );
        } else {
            assert!(rise < 0.005, "M={m}: rise {rise}");
            assert!(!a.reason.contains("caution"), "{}", a.reason);
        }
    }
}

/// An accuracy-target solve of a rigid-like case adds the domain-truncation estimate to its
/// error estimate and says the target is not met when that breaks it.
#[test]
fn accuracy_target_counts_the_domain_truncation() {
    use ehlmap::discrete::point::domain::PointDomain;
    use ehlmap::strategy::accuracy::solve_point_to_accuracy;
    let case = PointCase::new(5.0, 0.0, 1.0).unwrap();
    let t = PointDomain::of_case(&case, &classic().domain).truncation_error();
    assert!(t > 0.2 && t < 0.3, "{t}");
    let truncated = PointSolveParams {
        mg: classic(),
        ..Default::default()
    };
    let o = solve_point_to_accuracy(&case, &truncated, 0.05, 65).outputs;
    assert_eq!(o.status, Status::Converged, "{}", o.reason);
    assert!(o.error_estimate.unwrap() >= t);
    assert_eq!(o.accuracy_met, Some(false), "{}", o.reason);
    assert!(
        o.reason.contains("domain-truncation estimate"),
        "{}",
        o.reason
    );
    // The default far field: its truncation estimate (at most 0.45 %) leaves the target met.
    let far = PointSolveParams::default();
    let tf = PointDomain::of_case(&case, &far.mg.domain).truncation_error();
    assert!(tf > 0.0 && tf <= 0.0045 + 1e-12, "{tf}");
    let o = solve_point_to_accuracy(&case, &far, 0.05, 65).outputs;
    assert_eq!(o.status, Status::Converged, "{}", o.reason);
    assert!(o.error_estimate.unwrap() >= tf);
    assert_eq!(o.accuracy_met, Some(true), "{}", o.reason);
    // An elastic case keeps its target: the truncation estimate is below 1e-3 there.
    let case = PointCase::new(30.0, 5.0, 1.0).unwrap();
    assert!(PointDomain::of_case(&case, &classic().domain).truncation_error() < 1e-3);
}

/// The fast rule converges at the first attempt (no fallback ladder) to the tight solution on
/// the same grid, within the algebraic error it reports and 1e-3, with the load balanced to 1e-4.
fn fast_matches_tight_at_the_first_attempt(m: f64, l: f64, d: f64, grid: usize) {
    let case = PointCase::new(m, l, d).unwrap();
    let fast = solve_point(
        &case,
        &PointSolveParams {
            mg: PointMgParams { grid, ..classic() },
            fallback: false,
            ..Default::default()
        },
    )
    .outputs;
    assert_eq!(fast.status, Status::Converged, "{}", fast.reason);
    let tight = solve_with(m, l, d, grid, Converge::Tight).outputs;
    assert_eq!(tight.status, Status::Converged, "{}", tight.reason);
    let alg = fast.algebraic_error.expect("an algebraic error estimate");
    for (f, t) in [(fast.h_c, tight.h_c), (fast.h_min, tight.h_min)] {
        let d = (f / t - 1.0).abs();
        assert!(
            d < 1e-3 && d <= alg,
            "fast {f} tight {t}: {d:.1e} (estimate {alg:.1e})"
        );
    }
    assert!(
        fast.load_error.abs() < 1e-4,
        "load error {}",
        fast.load_error
    );
}

#[test]
fn an_oscillating_high_l_case_converges_at_the_first_attempt() {
    // M = 7.2, L = 20, D = 1 on 257^2: the pressure spike makes the undamped cycles oscillate
    // with period two (H_c alternating by 0.2 %, the residual stalled at 2e-3); the fast rule
    // damps the cycles once it sees that.
    fast_matches_tight_at_the_first_attempt(7.2, 20.0, 1.0, 257);
}

#[test]
fn a_low_m_case_converges_at_the_first_attempt() {
    // M = 1, L = 0, D = 0.5 on 257^2: the coarsest grid's solve with the load equation fails at
    // the first cycles (its H0 is 2.5 where the finest level's is 81); retried at each later
    // cycle, it succeeds once the cycles have come close, and H0 moves with the cycle again.
    fast_matches_tight_at_the_first_attempt(1.0, 0.0, 0.5, 257);
}

/// Fixed-grid point solve parameters on `grid` with the rule `converge`, the fallback ladder
/// on or off and the cycle type `cycle`.
fn ladder_params(
    grid: usize,
    converge: Converge,
    fallback: bool,
    cycle: ehlmap::solve::params::CycleType,
) -> PointSolveParams {
    PointSolveParams {
        mg: PointMgParams {
            grid,
            converge,
            cycle,
            ..Default::default()
        },
        fallback,
        ..Default::default()
    }
}

#[test]
fn the_lightly_damped_rung_answers_where_the_first_attempt_fails() {
    // Circular M = 10, L = 30 on 257^2 (a spike case of issue 22's box): the first attempt does
    // not converge (measured 2026-11-28) and the ladder's lightly damped rung (the line
    // relaxation under-relaxed by 0.8 instead of 0.5) answers with the fast rule. Deliberately
    // tied to today's solver: if the first attempt learns to converge here, move the test to
    // another case. Independent check: the tight rule with W cycles on the same grid (converged
    // to 1e-6 in H_c; the tight V cycles do not converge in 200 cycles here) agrees within the
    // rung's algebraic error estimate (measured H_c 9.537887 against 9.536139: 1.8e-4, H_min
    // 3.2e-5, estimate 3.7e-4).
    use ehlmap::solve::params::CycleType;
    let case = PointCase::new(10.0, 30.0, 1.0).unwrap();
    let first = solve_point(
        &case,
        &ladder_params(257, Converge::Fast, false, CycleType::V),
    );
    assert_ne!(
        first.outputs.status,
        Status::Converged,
        "{}",
        first.outputs.reason
    );
    let laddered = solve_point(
        &case,
        &ladder_params(257, Converge::Fast, true, CycleType::V),
    );
    let o = &laddered.outputs;
    assert_eq!(o.status, Status::Converged, "{}", o.reason);
    assert!(o.reason.contains("under-relaxation 0.8"), "{}", o.reason);
    let tight = solve_point(
        &case,
        &ladder_params(257, Converge::Tight, false, CycleType::W),
    );
    let tight = tight.outputs;
    assert_eq!(tight.status, Status::Converged, "{}", tight.reason);
    let alg = o.algebraic_error.expect("an algebraic error estimate");
    for (a, b) in [(o.h_c, tight.h_c), (o.h_min, tight.h_min)] {
        let d = (a / b - 1.0).abs();
        assert!(
            d <= alg && d < 1e-3,
            "{a} vs tight {b}: {d:.1e} (estimate {alg:.1e})"
        );
    }
    assert!(o.load_error.abs() < 1e-4, "load error {}", o.load_error);
}

#[test]
fn a_rigid_film_at_held_h0_is_not_taken_for_converged() {
    // Rigid-isoviscous point contact M = 0.01, D = 0.0464 on 257^2 (a check solve of the model
    // selection in issue 22's point box): the coarsest solve with the load equation fails at
    // almost every cycle, so H0 moves only by the secant step between cycles, and a cycle at
    // held H0 leaves a rigid film unchanged to the bit. Taking that zero change for the
    // algebraic error, the lightly damped rung stopped 1.5e-3 from the tight answer claiming
    // 1.2e-5 (measured 2026-11-28 with the coarsest solves stopped at a reduction of 1e-2
    // without a separate condition on the load equation, the setting used here; with the
    // default condition the rung happens to stop elsewhere); a cycle at held H0 is now no
    // stopping point. Whatever rung answers, its answer is within its algebraic estimate (or
    // 1e-6 where the tight rung answers) of the tight rule's.
    use ehlmap::model::case::{Elasticity, Models};
    use ehlmap::solve::params::CycleType;
    let rigid = Models {
        elasticity: Elasticity::Rigid,
        ..Models::default()
    };
    let case = PointCase::with_models(0.01, 0.0, 0.0464158883361, rigid).unwrap();
    let mut params = ladder_params(257, Converge::Fast, true, CycleType::V);
    params.mg.coarse_load_rel_tol = f64::INFINITY;
    let laddered = solve_point(&case, &params);
    let o = &laddered.outputs;
    assert_eq!(o.status, Status::Converged, "{}", o.reason);
    let tight = solve_point(
        &case,
        &ladder_params(257, Converge::Tight, false, CycleType::V),
    );
    let tight = tight.outputs;
    assert_eq!(tight.status, Status::Converged, "{}", tight.reason);
    let alg = o.algebraic_error.unwrap_or(0.0).max(1e-6);
    for (a, b) in [(o.h_c, tight.h_c), (o.h_min, tight.h_min)] {
        let d = (a / b - 1.0).abs();
        assert!(
            d <= alg,
            "{a} vs tight {b}: {d:.1e} (estimate {alg:.1e}; {})",
            o.reason
        );
    }
}

#[test]
fn a_runaway_coarse_load_balance_leaves_finite_films() {
    // M = 3e4, L = 30/7, D = 0.01 on 65^2: the coarsest grid's Newton start fails, and its
    // relaxed load balance used to run away (H0 -> inf after about 200 sweeps, then a NaN film:
    // every rung of the fallback ladder ended at once with "non-finite residual or film on
    // level 1" and H_c = 0). The balance now stops where the load error passes 10 g and restores
    // Newton's state, so the cycles run on finite films (the grid is still too coarse to
    // converge: max-iterations, H_c about 2.2).
    let case = PointCase::new(3e4, 30.0 / 7.0, 0.01).unwrap();
    let mut p = PointSolveParams::default();
    p.mg.grid = 65;
    p.fallback = false;
    let s = solve_point(&case, &p);
    assert!(
        !s.outputs.reason.contains("non-finite"),
        "{}",
        s.outputs.reason
    );
    assert!(
        s.outputs.h_c.is_finite() && s.outputs.h_c > 0.0 && s.outputs.h_min.is_finite(),
        "H_c {} H_min {}",
        s.outputs.h_c,
        s.outputs.h_min
    );
}
