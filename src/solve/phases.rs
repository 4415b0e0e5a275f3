//! Where the wall time of a multigrid solve goes: relaxation, the deformation product, residuals,
//! grid transfers and the coarsest level's Newton solves ([`PhaseTimes`]).
//!
//! Contract: every interval is measured by the multigrid driver around one step
//! ([`crate::solve::multilevel::Multigrid`]), and the deformation products that a step runs
//! (the film update after a sweep, a correction or a restriction; each level counts its own,
//! [`crate::solve::multilevel::GridLevel::deformation_seconds`]) are moved from that step's
//! phase to `deformation`, so the phases do not overlap: their sum is at most `total`, the
//! solve's wall time, and `other` is the rest (setting up the levels, kernels and FFT plans, the
//! Anderson step, the stopping rule). Timing never changes a result. The times are those of one
//! multigrid solve (in a fallback or accuracy ladder, the one that gave the answer: the info's
//! own work units and wall time add up every attempt). The split per work unit is what the
//! benchmarks report ([`PhaseTimes::per_work_unit`]).

use serde::{Deserialize, Serialize};
use std::fmt;
use std::time::Instant;

/// The phases of a multigrid solve, in seconds (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PhaseTimes {
    /// Relaxation sweeps (the line solves and the local film updates within them), without
    /// the deformation products they run.
    pub relaxation: f64,
    /// Deformation products c K*P (the FFT product, or the direct sum where asked for), with
    /// the coefficient and the film sum around them.
    pub deformation: f64,
    /// Residuals: the full residual before each restriction and the cycle records' residual.
    pub residual: f64,
    /// Grid transfers: injection and full weighting with the coarse operator (restriction),
    /// the interpolated correction, the FMG interpolation.
    pub transfers: f64,
    /// The coarsest level's Newton solves (the dense Jacobian and its LU).
    pub coarsest: f64,
    /// Wall time of the whole solve.
    pub total: f64,
    /// The solve's work units ([`crate::solve::SolveInfo::work_units`] of this one solve).
    pub work_units: f64,
}

/// One phase of [`PhaseTimes`] that a step is charged to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    /// [`PhaseTimes::relaxation`].
    Relaxation,
    /// [`PhaseTimes::residual`].
    Residual,
    /// [`PhaseTimes::transfers`].
    Transfers,
    /// [`PhaseTimes::coarsest`].
    Coarsest,
}

impl PhaseTimes {
    /// Charge a step that started at `start` to `phase`, less the deformation products it ran,
    /// `deform` seconds, which go to `deformation`.
    pub fn charge(&mut self, phase: Phase, start: Instant, deform: f64) {
        let own = (start.elapsed().as_secs_f64() - deform).max(0.0);
        self.deformation += deform;
        *match phase {
            Phase::Relaxation => &mut self.relaxation,
            Phase::Residual => &mut self.residual,
            Phase::Transfers => &mut self.transfers,
            Phase::Coarsest => &mut self.coarsest,
        } += own;
    }

    /// The measured phases' sum.
    pub fn measured(&self) -> f64 {
        self.relaxation + self.deformation + self.residual + self.transfers + self.coarsest
    }

    /// What the phases do not cover: `total` less their sum (0 when `total` is not set).
    pub fn other(&self) -> f64 {
        (self.total - self.measured()).max(0.0)
    }

    /// Every phase divided by the work units (seconds per work unit; `work_units` becomes 1);
    /// zeros for a solve without work.
    pub fn per_work_unit(&self) -> PhaseTimes {
        let s = if self.work_units > 0.0 {
            1.0 / self.work_units
        } else {
            0.0
        };
        PhaseTimes {
            relaxation: self.relaxation * s,
            deformation: self.deformation * s,
            residual: self.residual * s,
            transfers: self.transfers * s,
            coarsest: self.coarsest * s,
            total: self.total * s,
            work_units: self.work_units * s,
        }
    }
}

/// One line: each phase's share of the total, e.g. `relaxation 61 %, deformation 12 %, ...`.
impl fmt::Display for PhaseTimes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let t = self.total.max(self.measured()).max(1e-300);
        let pct = |v: f64| 100.0 * v / t;
        write!(
            f,
            "relaxation {:.0} %, deformation {:.0} %, residual {:.0} %, transfers {:.0} %, \
             coarsest {:.0} %, other {:.0} %",
            pct(self.relaxation),
            pct(self.deformation),
            pct(self.residual),
            pct(self.transfers),
            pct(self.coarsest),
            pct(self.other())
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_charged_step_moves_its_deformation_out_and_the_rest_is_other() {
        let mut t = PhaseTimes::default();
        let start = Instant::now();
        std::thread::sleep(std::time::Duration::from_millis(20));
        t.charge(Phase::Relaxation, start, 0.005);
        assert!(t.relaxation >= 0.015 && t.relaxation < 1.0, "{t:?}");
        assert_eq!(t.deformation, 0.005);
        // A step shorter than the deformation it claims is charged nothing (not negative).
        t.charge(Phase::Residual, Instant::now(), 10.0);
        assert_eq!(t.residual, 0.0);
        assert_eq!(t.deformation, 10.005);
        t.total = 20.0;
        assert!((t.other() - (20.0 - t.measured())).abs() < 1e-12);
        t.work_units = 4.0;
        let per = t.per_work_unit();
        assert_eq!((per.total, per.work_units), (5.0, 1.0));
        assert_eq!(PhaseTimes::default().per_work_unit(), PhaseTimes::default());
        let line = format!(
            "{}",
            PhaseTimes {
                relaxation: 3.0,
                deformation: 1.0,
                total: 5.0,
                ..Default::default()
            }
        );
        assert_eq!(
            line,
            "relaxation 60 %, deformation 20 %, residual 0 %, transfers 0 %, coarsest 0 %, other 20 %"
        );
    }
}
