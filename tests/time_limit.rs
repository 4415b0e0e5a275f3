//! A time limit stops a solve as a result, never as a crash: the solve ends with status
//! max-iterations and a reason naming the limit, the fallback and accuracy ladders try nothing
//! further, and a limit that is not reached changes nothing (bit for bit). The checks count
//! work units and grids, not seconds, so they hold on any machine.

use ehlmap::{solve, Case, LineCase, PointCase, SolveParams, Status};
use std::process::Command;
use std::time::{Duration, Instant};

fn passed() -> SolveParams {
    SolveParams {
        deadline: Some(Instant::now()),
        ..SolveParams::default()
    }
}

#[test]
fn a_passed_deadline_stops_the_solve_after_one_cycle_with_its_reason() {
    // Point M = 200, L = 10 on 129^2: the full solve takes several finest-grid cycles.
    let case = Case::Point(PointCase::new(200.0, 10.0, 1.0).unwrap());
    let grid = SolveParams {
        grid: Some(129),
        estimate: false,
        ..SolveParams::default()
    };
    let full = solve(&case, &grid);
    assert_eq!(full.outputs.status, Status::Converged);
    let cut = solve(
        &case,
        &SolveParams {
            deadline: Some(Instant::now()),
            ..grid
        },
    );
    assert_eq!(cut.outputs.status, Status::MaxIterations);
    assert!(
        cut.outputs
            .reason
            .contains("time limit reached at cycle 1 of level 1"),
        "{}",
        cut.outputs.reason
    );
    // One attempt of the fallback ladder only, and a fraction of the full solve's work.
    assert_eq!(cut.attempt, 1);
    assert!(
        cut.outputs.work_units < 0.2 * full.outputs.work_units,
        "{} of {}",
        cut.outputs.work_units,
        full.outputs.work_units
    );
}

#[test]
fn the_accuracy_ladder_stops_at_the_deadline_and_says_so() {
    // The default 1 % target on a line case climbs from 257 points; a passed deadline stops it
    // on the first grid, with no estimate and the target reported as not met.
    let case = Case::Line(LineCase::new(1000.0, 20.0).unwrap());
    let s = solve(&case, &passed());
    assert_eq!(s.outputs.grid, 257);
    assert_eq!(s.outputs.accuracy_met, Some(false));
    assert!(
        s.outputs.reason.contains("time limit"),
        "{}",
        s.outputs.reason
    );
    assert!(s.outputs.error_estimate.is_none());
}

#[test]
fn a_deadline_not_reached_changes_nothing() {
    let later = Some(Instant::now() + Duration::from_secs(3600));
    for case in [
        Case::Line(LineCase::new(20.0, 10.0).unwrap()),
        Case::Point(PointCase::new(20.0, 10.0, 1.0).unwrap()),
    ] {
        let free = solve(&case, &SolveParams::default());
        let limited = solve(
            &case,
            &SolveParams {
                deadline: later,
                ..SolveParams::default()
            },
        );
        assert_eq!(free.outputs.status, Status::Converged);
        assert_eq!(free.outputs.h_c.to_bits(), limited.outputs.h_c.to_bits());
        assert_eq!(
            free.outputs.h_min.to_bits(),
            limited.outputs.h_min.to_bits()
        );
        assert_eq!(free.outputs.grid, limited.outputs.grid);
        assert_eq!(free.outputs.reason, limited.outputs.reason);
    }
}

#[test]
fn the_cli_reports_a_time_limit_as_a_status_not_an_error() {
    // A hard corner with a limit of a tenth of a second: exit 0, a JSON answer whose status
    // and reason say what happened.
    let out = Command::new(env!("CARGO_BIN_EXE_ehlmap"))
        .args([
            "solve",
            "--contact",
            "point",
            "--M",
            "30000",
            "--L",
            "10",
            "--time-limit",
            "0.1",
            "--json",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["status"], "max-iterations", "{v}");
    let reason = v["reason"].as_str().unwrap();
    assert!(reason.contains("time limit"), "{reason}");
    assert_eq!(v["accuracy_met"], false, "{v}");
}
