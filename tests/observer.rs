//! The solver core is quiet: an observer receives every multigrid cycle (the FMG levels' and the
//! finest level's), changes nothing in the answer, and `ehlmap solve --trace` prints it.

use ehlmap::{solve, Case, CycleEvent, LineCase, Observer, PointCase, SolveParams, Status};
use std::sync::atomic::{AtomicUsize, Ordering};

mod common;
use common::ehlmap;

static LINE_CYCLES: AtomicUsize = AtomicUsize::new(0);
static POINT_CYCLES: AtomicUsize = AtomicUsize::new(0);

fn count_line(e: &CycleEvent) {
    assert!(e.record.h_c.is_finite() && e.record.work_units > 0.0, "{e}");
    // The level lies within the solve's grid (513 points, or 257 for the half-grid estimate),
    // every level of 2^k + 1 points.
    let pow = |n: usize| (n - 1).is_power_of_two();
    assert!(e.points <= e.finest_points && [257, 513].contains(&e.finest_points) && pow(e.points));
    LINE_CYCLES.fetch_add(1, Ordering::SeqCst);
}

fn count_point(e: &CycleEvent) {
    assert!(e.record.h_c.is_finite() && e.record.work_units > 0.0, "{e}");
    let pow = |n: usize| (n - 1).is_power_of_two();
    assert!(e.points <= e.finest_points && [33, 65].contains(&e.finest_points) && pow(e.points));
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
    let out = ehlmap(&[
        "solve", "--M", "20", "--L", "10", "--grid", "513", "--trace", "--json",
    ]);
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    let lines: Vec<&str> = err.lines().filter(|l| l.starts_with("level ")).collect();
    assert!(lines.len() > 5, "{err}");
    assert!(lines
        .iter()
        .all(|l| l.contains(" res ") && l.contains(" hc ")));
    // Without --trace the solver prints nothing.
    let quiet = ehlmap(&["solve", "--M", "20", "--L", "10", "--grid", "513", "--json"]);
    assert!(
        quiet.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&quiet.stderr)
    );
}

#[test]
fn solve_progress_says_where_a_long_solve_is_and_changes_nothing() {
    let run = |progress: &str| {
        let out = ehlmap(&[
            "solve",
            "--M",
            "20",
            "--L",
            "10",
            "--grid",
            "513",
            "--json",
            "--progress",
            progress,
        ]);
        assert!(out.status.success());
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        (
            json["H_c"].as_f64().unwrap(),
            String::from_utf8_lossy(&out.stderr).to_string(),
        )
    };
    // `log` prints from the first cycle, then at most every 10 s: a solve of well under 10 s
    // prints one line, naming the grid, the level and its cycle.
    let (h_log, err) = run("log");
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1, "{err}");
    let l = lines[0];
    assert!(
        l.starts_with("ehlmap solve: 0 s, grid 513, level ")
            && l.contains(" cycle 1: residual ")
            && l.contains(", H_c "),
        "{l}"
    );
    // `auto` waits 5 s before its first line, `none` prints nothing; the answer is the same.
    for p in ["auto", "none"] {
        let (h, err) = run(p);
        assert!(err.is_empty(), "{p}: {err}");
        assert_eq!(h.to_bits(), h_log.to_bits());
    }
}
