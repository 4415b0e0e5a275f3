//! The baseline solvers (dense Newton-Raphson, single-grid relaxation) solve the same discrete
//! problem as the multigrid: on the same grid they must give the same answer.

use ehlmap::model::case::{Elasticity, LineCase, Models};
use ehlmap::solve::line::{solve_line, LineSolveParams};
use ehlmap::solve::params::{Converge, Method};
use ehlmap::solve::Status;

fn run(case: &LineCase, method: Method, grid: usize) -> ehlmap::solve::solution::Outputs {
    let mut p = LineSolveParams {
        method,
        ..Default::default()
    };
    p.mg.grid = grid;
    p.mg.tol_load = 1e-10;
    p.mg.tol_h = 1e-10;
    // The same discrete problem solved to the tolerances: tight convergence.
    p.mg.converge = Converge::Tight;
    solve_line(case, &p).outputs
}

#[test]
fn newton_and_multigrid_agree_on_the_same_grid() {
    let rigid = Models {
        elasticity: Elasticity::Rigid,
        ..Models::default()
    };
    for case in [
        LineCase::new(20.0, 10.0).unwrap(),
        LineCase::new(100.0, 5.0).unwrap(),
        LineCase::with_models(1.0, 0.0, rigid).unwrap(),
    ] {
        let mg = run(&case, Method::Multigrid, 513);
        let nt = run(&case, Method::Newton, 513);
        assert_eq!(mg.status, Status::Converged, "{}", mg.reason);
        assert_eq!(nt.status, Status::Converged, "{}", nt.reason);
        assert_eq!(mg.grid, nt.grid);
        let d = (mg.h_c / nt.h_c - 1.0).abs();
        assert!(
            d < 1e-6,
            "M={} L={}: multigrid {} newton {} ({d:.1e})",
            case.m,
            case.l,
            mg.h_c,
            nt.h_c
        );
        assert!((mg.h_min / nt.h_min - 1.0).abs() < 1e-5);
    }
}

#[test]
fn single_grid_relaxation_reaches_the_same_answer_slowly() {
    let case = LineCase::new(20.0, 5.0).unwrap();
    let mg = run(&case, Method::Multigrid, 1025);
    let rx = run(&case, Method::Relax, 1025);
    assert_eq!(rx.status, Status::Converged, "{}", rx.reason);
    assert!(
        (mg.h_c / rx.h_c - 1.0).abs() < 1e-5,
        "{} vs {}",
        mg.h_c,
        rx.h_c
    );
    // The smoother alone needs far more finest-grid sweeps than the multigrid's work units.
    assert!(
        rx.work_units > 3.0 * mg.work_units,
        "relax {} WU, multigrid {} WU",
        rx.work_units,
        mg.work_units
    );
}

#[test]
fn forced_divergence_of_the_baseline_is_reported() {
    let case = LineCase::new(20.0, 10.0).unwrap();
    let mut p = LineSolveParams {
        method: Method::Relax,
        relax_max_sweeps: 400,
        ..Default::default()
    };
    p.mg.grid = 257;
    p.mg.relax.omega_line = 3.0;
    let o = solve_line(&case, &p).outputs;
    assert_ne!(o.status, Status::Converged, "{}", o.reason);
}
