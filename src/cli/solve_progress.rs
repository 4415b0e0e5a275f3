//! Progress of one `ehlmap solve` on stderr: a line per multigrid cycle at most every
//! [`EVERY`], the first after the solve has run for [`FIRST`] ([`start`]), so that quick solves
//! print nothing and long ones (fine grids, the accuracy ladder, the fallback ladder) show
//! that they are alive and where they are:
//! `ehlmap solve: 12 s, grid 1025, level 513 cycle 4: residual 3.1e-3, load error 2.0e-5, H_c 4.85512`.
//! The solver calls [`print`] through an [`ehlmap::solve::Observer`] (a plain function, so
//! the state is one process-wide clock); observers never change a solve.

use crate::cli::output::note;
use clap::ValueEnum;
use ehlmap::solve::{CycleEvent, Observer};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// `ehlmap solve --progress`.
#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub enum SolveProgressArg {
    /// The first line once the solve has run for [`FIRST`].
    Auto,
    /// The first line at the first cycle.
    Log,
    None,
}

/// The least time between two progress lines.
pub const EVERY: Duration = Duration::from_secs(10);

/// How long a solve runs before `--progress auto` prints its first line.
pub const FIRST: Duration = Duration::from_secs(5);

/// The observer that reports `progress` (None for `none`).
pub fn observer(progress: SolveProgressArg) -> Option<Observer> {
    (progress != SolveProgressArg::None).then_some(Observer(print))
}

/// When the solve started and when the next line may be printed.
static CLOCK: Mutex<Option<(Instant, Duration)>> = Mutex::new(None);

/// Start the clock for `progress`: the first line may come once the solve has run for
/// [`FIRST`] (`auto`) or at once (`log`).
pub fn start(progress: SolveProgressArg) {
    let first = match progress {
        SolveProgressArg::Log => Duration::ZERO,
        _ => FIRST,
    };
    *CLOCK.lock().unwrap_or_else(|e| e.into_inner()) = Some((Instant::now(), first));
}

/// The progress line of a cycle seen `elapsed` after the start.
pub fn line(e: &CycleEvent, elapsed: Duration) -> String {
    let r = &e.record;
    format!(
        "ehlmap solve: {} s, grid {}, level {} cycle {}: residual {:.1e}, load error {:.1e}, H_c {:.6}",
        elapsed.as_secs(),
        e.finest_points,
        e.points,
        e.cycle + 1,
        r.residual,
        r.load_error,
        r.h_c
    )
}

/// The observer: print the cycle's line if the next line is due (nothing before [`start`]).
pub fn print(e: &CycleEvent) {
    let mut clock = CLOCK.lock().unwrap_or_else(|e| e.into_inner());
    let Some((t0, next)) = clock.as_mut() else {
        return;
    };
    let elapsed = t0.elapsed();
    if elapsed >= *next {
        *next = elapsed + EVERY;
        note!("{}", line(e, elapsed));
    }
}
