//! The solver core is quiet: an observer receives every multigrid cycle (the FMG levels' and the
//! finest level's), changes nothing in the answer, and `ehlmap solve --trace` prints it.

use ehlmap::{solve, Case, CycleEvent, LineCase, Observer, PointCase, SolveParams, Status};
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};

static LINE_CYCLES: AtomicUsize = AtomicUsize::new(0);
static POINT_CYCLES: AtomicUsize = AtomicUsize::new(0);

fn count_line(e: &CycleEvent) {
    assert!(e.record.h_c.is_finite() && e.record.work_units > 0.0, "{e}");
    LINE_CYCLES.fetch_add(1, Ordering::SeqCst);
}

fn count_point(e: &CycleEvent) {
    assert!(e.record.h_c.is_finite() && e.record.work_units > 0.0, "{e}");
    POINT_CYCLES.fetch_add(1, Ordering::SeqCst);
}

fn check(case: Case, grid: usize, observer: Observer, seen: &AtomicUsize) {
    let params = SolveParams {
        grid: Some(grid),
        ..SolveParams::default()
    };
    let quiet = solve(&case, &params);
    let observed = solve(
        &case,
        &SolveParams {
            observer: Some(observer),
            ..params
        },
    );
    assert_eq!(quiet.outputs.status, Status::Converged);
    // The observer changes nothing: the same bits.
    assert_eq!(quiet.outputs.h_c.to_bits(), observed.outputs.h_c.to_bits());
    assert_eq!(
        quiet.outputs.h_min.to_bits(),
        observed.outputs.h_min.to_bits()
    );
    // Every finest-level cycle is in the history; the observer also sees the coarser FMG levels.
    let n = seen.load(Ordering::SeqCst);
    let finest = observed.info.history.len();
    assert!(
        finest > 0 && n > finest,
        "{n} cycles seen, {finest} on the finest level"
    );
}

#[test]
fn observer_sees_every_cycle_and_changes_nothing() {
    check(
        Case::Line(LineCase::new(20.0, 10.0).unwrap()),
        513,
        Observer(count_line),
        &LINE_CYCLES,
    );
    check(
        Case::Point(PointCase::new(20.0, 10.0, 1.0).unwrap()),
        65,
        Observer(count_point),
        &POINT_CYCLES,
    );
}

#[test]
fn solve_trace_prints_the_cycles() {
    let out = Command::new(env!("CARGO_BIN_EXE_ehlmap"))
        .args([
            "solve", "--M", "20", "--L", "10", "--grid", "513", "--trace", "--json",
        ])
        .output()
        .unwrap();
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    let lines: Vec<&str> = err.lines().filter(|l| l.starts_with("level ")).collect();
    assert!(lines.len() > 5, "{err}");
    assert!(lines
        .iter()
        .all(|l| l.contains(" res ") && l.contains(" hc ")));
    // Without --trace the solver prints nothing.
    let quiet = Command::new(env!("CARGO_BIN_EXE_ehlmap"))
        .args(["solve", "--M", "20", "--L", "10", "--grid", "513", "--json"])
        .output()
        .unwrap();
    assert!(
        quiet.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&quiet.stderr)
    );
}
