//! The deadline of a solve: an optional instant after which the solvers stop
//! (`MgParams::deadline`, `SolveParams::deadline`); an unconverged solve then ends with status
//! max-iterations and a reason naming the time limit.

use std::time::Instant;

/// Whether the instant `deadline` (if any) has passed.
pub fn past(deadline: Option<Instant>) -> bool {
    deadline.is_some_and(|d| Instant::now() >= d)
}
