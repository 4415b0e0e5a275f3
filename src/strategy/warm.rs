//! Warm starts of line cases that fail cold.
//!
//! Contract: a line case whose cold solve (with its fallback ladder) does not converge is
//! continued in M. Its lower-M neighbours at the same L and numerics, M/2, M/4, ... (at most
//! [`WARM_DEPTH`] halvings), are solved cold until one converges; from that one the chain is
//! walked back up to M, each solve starting its finest-level cycles from the previous
//! solution's pressure ([`crate::solve::line::warm_guess`]). The neighbour chain is a
//! function of the case alone, never of what other tasks have finished, so results do not
//! depend on the thread count, the order of work or the shard split. The sweep row records the
//! case id of the neighbour at M/2 in `warm_start`; the cost of every solve is counted. The warm
//! result is kept only when it converged; otherwise the cold result stands.

use crate::model::case::LineCase;
use crate::solve::line::{solve_line, solve_line_from, warm_guess, LineSolveParams};
use crate::solve::solution::Solution;
use crate::solve::Status;

/// Most halvings of M tried for a converged neighbour.
pub const WARM_DEPTH: u32 = 2;

/// Try to rescue a failed cold solve of `case` (see the module docs). `spent` receives the work
/// units and seconds of every solve of the chain, whether it succeeds or not.
pub fn warm_start_line(
    case: &LineCase,
    params: &LineSolveParams,
    spent: &mut (f64, f64),
) -> Option<Solution> {
    let mut keep = *params;
    keep.keep_fields = true;
    let at = |k: u32| -> Option<LineCase> {
        LineCase::with_models(case.m / 2f64.powi(k as i32), case.l, case.models).ok()
    };
    let count = |s: &Solution, spent: &mut (f64, f64)| {
        spent.0 += s.info.work_units;
        spent.1 += s.info.wall_s;
    };
    // The first neighbour down the chain that converges cold.
    let mut found = None;
    for k in 1..=WARM_DEPTH {
        let lc = at(k)?;
        let s = solve_line(&lc, &keep);
        count(&s, spent);
        if s.info.status == Status::Converged {
            found = Some((k, lc, s));
            break;
        }
    }
    let (k0, mut prev_case, mut prev) = found?;
    for k in (0..k0).rev() {
        let lc = at(k)?;
        let guess = warm_guess(&lc, &prev_case, &prev)?;
        let mut s = solve_line_from(&lc, if k == 0 { params } else { &keep }, Some(&guess));
        count(&s, spent);
        if s.info.status != Status::Converged {
            return None;
        }
        if k == 0 {
            let note = format!(
                " (warm start from M = {} after the cold solve failed)",
                prev_case.m
            );
            s.info.reason.push_str(&note);
            s.outputs.reason.push_str(&note);
            return Some(s);
        }
        (prev_case, prev) = (lc, s);
    }
    None
}
