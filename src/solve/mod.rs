//! Solvers and what every solve returns: a [`Status`] with a reason, the convergence history and
//! the cost (work units, wall time). Numerical failure is a result, never a panic.

pub mod anderson;
pub mod awake;
pub mod banded;
pub mod deadline;
pub mod film;
pub mod fmg;
pub mod fmg_fast;
pub mod ladder;
pub mod line;
pub mod load_balance;
pub mod mixed;
pub mod multilevel;
pub mod newton;
pub mod params;
pub mod phases;
pub mod point;
pub mod relax;
pub mod seed;
pub mod single_grid;
pub mod solution;

use serde::{Deserialize, Serialize};
use std::fmt;

/// How a solve ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Status {
    /// The load error and the relative change of H_c per cycle are below the tolerances.
    Converged,
    /// A non-finite residual, film or H0, the finest residual grown by 1e4 over its smallest, a
    /// load error above 10, or a singular Newton system.
    Diverged,
    /// The load error is stuck above the tolerance: H_c no longer moves between load-balance
    /// steps on H0.
    Stalled,
    /// The cycle, sweep or Newton iteration limit was reached first.
    MaxIterations,
    /// The iterations converged, but to a film H_c or H_min <= 0 (or not a number): the grid
    /// does not resolve the case, so the answer is not one (refine the grid).
    UnderResolved,
}

impl Status {
    /// The name in JSON and Parquet: converged, diverged, stalled, max-iterations,
    /// under-resolved.
    pub fn as_str(&self) -> &'static str {
        match self {
            Status::Converged => "converged",
            Status::Diverged => "diverged",
            Status::Stalled => "stalled",
            Status::MaxIterations => "max-iterations",
            Status::UnderResolved => "under-resolved",
        }
    }
}

impl fmt::Display for Status {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// One multigrid cycle on the finest level, as seen after it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CycleRecord {
    /// Mean |f - L(P)| over the pressurised nodes of the finest level.
    pub residual: f64,
    /// (h sum P - target)/target.
    pub load_error: f64,
    /// Central film (Moes units) after the cycle.
    pub h_c: f64,
    /// Smallest nodal film (Moes units) after the cycle.
    pub h_min: f64,
    /// Cumulative work units.
    pub work_units: f64,
}

/// Convergence information returned with every solve.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SolveInfo {
    /// How the solve ended.
    pub status: Status,
    /// Why, in words; after a fallback or a failed ladder, also which attempt answered.
    pub reason: String,
    /// One record per cycle on the finest level.
    pub history: Vec<CycleRecord>,
    /// Relaxation sweeps in finest-grid equivalents.
    pub work_units: f64,
    /// Wall time of the solve (s), all attempts included.
    pub wall_s: f64,
    /// Points of the finest level.
    pub grid: usize,
    /// Levels of the multigrid hierarchy.
    pub levels: usize,
    /// Fast convergence: the estimated relative algebraic error of H_c and H_min (the larger)
    /// left on the finest level when the cycles stopped (see [`crate::solve::fmg`]).
    pub algebraic_error: Option<f64>,
    /// Fast convergence: the relative discretisation error of H_c and H_min (the larger)
    /// estimated from the finest level and the next coarser one, |Q_h - Q_2h| / (3 |Q_h|).
    pub discretisation_error: Option<f64>,
    /// Where the wall time of the multigrid solve that gave the answer went
    /// ([`phases::PhaseTimes`]; zeros for an answer without a multigrid solve).
    #[serde(default)]
    pub phases: phases::PhaseTimes,
}

/// One multigrid cycle as an observer sees it: the FMG level (0 the coarsest), the cycle's index
/// on that level, its record, the film constant after it and the grid sizes. Its `Display` is
/// one line of `ehlmap solve --trace`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CycleEvent {
    /// The FMG level (0 the coarsest).
    pub level: usize,
    /// The cycle's index on that level.
    pub cycle: usize,
    /// The cycle's record.
    pub record: CycleRecord,
    /// The film constant H0 after the cycle (Hertzian units).
    pub h0: f64,
    /// Points per direction of the cycle's level.
    pub points: usize,
    /// Points per direction of the solve's finest level (its grid).
    pub finest_points: usize,
}

impl fmt::Display for CycleEvent {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let r = &self.record;
        write!(
            f,
            "level {} cycle {} res {:.3e} load {:.3e} hc {:.7} hmin {:.7} wu {:.1} h0 {:.8}",
            self.level, self.cycle, r.residual, r.load_error, r.h_c, r.h_min, r.work_units, self.h0
        )
    }
}

/// A callback that receives every multigrid cycle of a solve (the solver itself never prints).
/// A plain function, so that solver parameters stay `Copy`. Observers never change a solve, so
/// any two compare equal.
#[derive(Clone, Copy)]
pub struct Observer(pub fn(&CycleEvent));

impl Observer {
    /// Tell the observer about one cycle.
    pub fn notify(&self, event: &CycleEvent) {
        (self.0)(event)
    }
}

impl PartialEq for Observer {
    fn eq(&self, _: &Observer) -> bool {
        true
    }
}

impl fmt::Debug for Observer {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("Observer")
    }
}
