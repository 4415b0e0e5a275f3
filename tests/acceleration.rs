//! The Anderson step on the point contact's finest cycles (`MgParams::anderson`, on by default
//! for point contacts): the accelerated fast solve stops inside its algebraic error estimate
//! of the tightly converged answer on the same grid, for less work than the plain cycles where
//! the coarse grids freeze no band (alpha_bar < 5: the slow mode is a smooth one), and leaves
//! the cycles alone where they do.

use ehlmap::model::case::PointCase;
use ehlmap::solve::params::Converge;
use ehlmap::solve::point::{solve_point, PointSolveParams};
use ehlmap::Status;

fn solve(
    case: &PointCase,
    anderson: bool,
    converge: Converge,
) -> ehlmap::solve::solution::Solution {
    let mut p = PointSolveParams::default();
    p.mg.grid = 257;
    p.mg.converge = converge;
    p.mg.anderson = anderson;
    p.fallback = false;
    let s = solve_point(case, &p);
    assert_eq!(
        s.outputs.status,
        Status::Converged,
        "{case:?}: {}",
        s.outputs.reason
    );
    s
}

/// Measured on 257^2 (docs/performance.md, "Anderson acceleration of the finest cycles"):
/// M = 3, L = 0, D = 1 took 41.2 work units with the plain cycles and 20.3 accelerated; M = 1,
/// L = 20, D = 0.25 (alpha_bar 4.8) 29.9 and 17.4; M = 3, L = 10, D = 0.25 29.9 and 17.4.
#[test]
fn accelerated_cycles_stop_inside_their_estimate_for_less_work() {
    for (m, l, d) in [(3.0, 0.0, 1.0), (1.0, 20.0, 0.25), (3.0, 10.0, 0.25)] {
        let case = PointCase::new(m, l, d).unwrap();
        let tight = solve(&case, false, Converge::Tight).outputs;
        let plain = solve(&case, false, Converge::Fast);
        let fast = solve(&case, true, Converge::Fast);
        let o = &fast.outputs;
        let dev = (o.h_c / tight.h_c - 1.0)
            .abs()
            .max((o.h_min / tight.h_min - 1.0).abs());
        let e_a = fast.info.algebraic_error.expect("the fast rule's estimate");
        assert!(
            dev <= e_a,
            "M = {m}, L = {l}, D = {d}: {dev:.1e} from the tight answer, estimate {e_a:.1e}"
        );
        let (w1, w0) = (fast.info.work_units, plain.info.work_units);
        assert!(
            w1 < 0.75 * w0,
            "M = {m}, L = {l}, D = {d}: {w1:.1} work units accelerated against {w0:.1} plain"
        );
    }
}

/// The tight rule (references, the fallback ladder's conservative rungs) never takes the step,
/// nor does the fast rule where the coarse grids freeze a band (M = 19.3, L = 30, D = 0.215:
/// alpha_bar 53, and a first attempt freezes the band from L = 25 on): their answers do not
/// depend on the switch.
#[test]
fn the_tight_rule_and_frozen_band_cases_ignore_the_switch() {
    let case = PointCase::new(19.3, 30.0, 0.215).unwrap();
    for converge in [Converge::Tight, Converge::Fast] {
        let a = solve(&case, true, converge);
        let b = solve(&case, false, converge);
        assert_eq!(a.outputs.h_c, b.outputs.h_c, "{converge:?}");
        assert_eq!(a.info.work_units, b.info.work_units, "{converge:?}");
    }
}
