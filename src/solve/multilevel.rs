//! One FAS multigrid for both contacts: [`Multigrid<C>`] holds the levels and the state of a
//! solve, and runs the cycle, the coarsest-level solve, the cycle records and the FMG driver's
//! interface ([`Fas`]) once for line and point contacts; a [`Contact`] supplies what differs
//! between them: its level and physics types, the relaxation sweep, the restriction and the
//! interpolation of the correction, the start on the coarsest level, the FMG interpolation and
//! where X = 0 lies.
//!
//! A cycle on level l > 0: `pre` relaxations; the full residual r = f - L(P) (the
//! complementarity margin included on the cavitated set) is restricted and P injected
//! ([`Contact::restrict`]); the coarse load right-hand side is g_H = load_H(P^_H) + (g_h -
//! load_h); `gamma` coarse cycles (1: V, 2: W); the correction P_H - P^_H is interpolated, added
//! and projected on P >= 0 ([`Contact::correct`]); `post` relaxations. The coarsest level is
//! solved at fixed H0 by semi-smooth Newton, relaxed `coarse_sweeps` times instead when Newton
//! fails. Invariant: after every step each level's film and coefficients are up to date with its
//! P and the current H0.

use crate::solve::anderson::Anderson;
use crate::solve::fmg::{fmg_solve, Fas, FmgControl};
use crate::solve::fmg_fast::fmg_fast_solve;
use crate::solve::newton::{
    newton_solve, NewtonLevel, NewtonOutcome, NewtonParams, MULTIGRID_STALL_WINDOW,
};
use crate::solve::params::{Converge, FinerCoarsest, MgParams};
use crate::solve::phases::{Phase, PhaseTimes};
use crate::solve::{CycleRecord, Observer, SolveInfo};

/// The gain of [`Multigrid::relaxed_coarse_balance`]'s H0 update per unit load error.
pub const RELAXED_GAIN: f64 = 0.02;

/// The load error, in units of the load g, at which [`Multigrid::relaxed_coarse_balance`] gives
/// up.
pub const RUNAWAY_LOAD: f64 = 10.0;

/// Newton iterations allowed to a coarsest-level solve with the load equation after one has
/// failed (see [`Multigrid::coarse_solve`]).
pub const RETRY_NEWTON_ITERATIONS: usize = 8;

/// What the shared multigrid steps need from a grid level, beyond Newton's view of it.
pub trait GridLevel: NewtonLevel {
    /// Points per direction (the grid size a solve reports).
    fn points(&self) -> usize;
    /// The pressure P (Hertzian units) at every node.
    fn p(&self) -> &[f64];
    /// The film H (Hertzian units) at every node.
    fn film(&self) -> &[f64];
    /// The residual work buffer, one value per node.
    fn delta_mut(&mut self) -> &mut Vec<f64>;
    /// r = f - L at every node (0 on the boundary; with `active_only` also where P = 0).
    fn residual_into(&self, phys: &Self::Phys, active_only: bool, out: &mut [f64]);
    /// Set the right-hand side of the load equation.
    fn set_load_rhs(&mut self, g: f64);
    /// The node fields.
    fn nodes_mut(&mut self) -> &mut crate::discrete::level::NodeFields;
    /// The deformation by a pressure `field` on this level's nodes (film units), into `out`.
    fn deformation_of(&mut self, phys: &Self::Phys, field: &[f64], out: &mut [f64]);
    /// A finer level's nodal `fine_field` at this level's nodes (injection).
    fn inject_field(&self, fine: &Self, fine_field: &[f64]) -> Vec<f64>;
    /// The area of one cell: the load is cell_area x sum P.
    fn cell_area(&self) -> f64;
    /// Seconds this level has spent in deformation products so far
    /// ([`crate::solve::phases::PhaseTimes`]).
    fn deformation_seconds(&self) -> f64;
}

/// `impl GridLevel` for a level type with the fields `p`, `film`, `delta`, `g` and the methods
/// `residual` and `points` (both contacts' levels have them), with its physics type.
macro_rules! grid_level {
    ($level:ty, $phys:ty) => {
        impl $crate::solve::multilevel::GridLevel for $level {
            fn points(&self) -> usize {
                self.points()
            }
            fn p(&self) -> &[f64] {
                &self.p
            }
            fn film(&self) -> &[f64] {
                &self.film
            }
            fn delta_mut(&mut self) -> &mut Vec<f64> {
                &mut self.delta
            }
            fn residual_into(&self, phys: &$phys, active_only: bool, out: &mut [f64]) {
                self.residual(phys, active_only, out)
            }
            fn set_load_rhs(&mut self, g: f64) {
                self.g = g;
            }
            fn nodes_mut(&mut self) -> &mut $crate::discrete::level::NodeFields {
                &mut self.nodes
            }
            fn deformation_of(&mut self, phys: &$phys, field: &[f64], out: &mut [f64]) {
                self.deformation_of(phys, field, out)
            }
            fn inject_field(&self, fine: &Self, fine_field: &[f64]) -> Vec<f64> {
                self.inject_field(fine, fine_field)
            }
            fn cell_area(&self) -> f64 {
                self.cell_area()
            }
            fn deformation_seconds(&self) -> f64 {
                self.deform_seconds
            }
        }
    };
}
pub(crate) use grid_level;

/// Which coarse nodes a restriction holds fixed ([`Contact::restrict`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Freeze {
    /// The band along the cavitation boundary ([`Contact::frozen_band`]): coarse nodes whose
    /// fine neighbourhood touches the cavitated set.
    pub band: bool,
    /// Line contacts: also coarse nodes whose fine neighbourhood holds a pressurised node with
    /// |r| above this factor times the mean |r| of the pressurised nodes (the outlet spike,
    /// [`crate::solve::params::MgParams::spike_freeze`]).
    pub spike: Option<f64>,
}

/// What a contact supplies to [`Multigrid`]: the types of its levels, physics and domain, and
/// the steps that differ between line and point contacts.
pub trait Contact: Sized {
    /// A grid level (its `Phys` is the contact's discrete physics).
    type Level: GridLevel;
    /// The domain of the solve.
    type Domain: DomainRule;
    /// What the contact keeps besides: the smoother's work buffers, the finest grid's size for
    /// the work units, the line contact's warm-start guess.
    type Extra;
    /// The growth of the cycle budget per FMG level below the finest (see [`FmgControl`]).
    const COARSE_BUDGET_GROWTH: usize;
    /// Whether a damped cycle ([`Fas::damp_cycles`]) leaves the nodes that the cycle cavitated
    /// at P = 0 instead of damping them too. Damped, such a node keeps a fraction of its old
    /// pressure, shrinking cycle after cycle but never 0, and its cavitation margin counts in
    /// the residual (point contacts: a column of them next to the outlet stalled the residual
    /// of M = 19.3, L = 20, D = 0.1 on 513^2 while H_c had settled). Line contacts damp them:
    /// their damped cycles are the ones at the outlet spike, which needs the damping there
    /// (line M = 1000, L = 20 on 8193 points no longer converged at its first attempt).
    const KEEP_CAVITATED: bool;

    /// One relaxation sweep of level `l`; returns its cost in finest-grid work units.
    fn sweep(mg: &mut Multigrid<Self>, l: usize) -> f64;
    /// The cost in work units of `iterations` Newton iterations on the coarsest level.
    fn newton_cost(mg: &Multigrid<Self>, iterations: usize) -> f64;
    /// Inject P from `fine` into `coarse`, refresh the coarse film at `h0`, and set the coarse
    /// Reynolds right-hand side from the restricted residual `r` (frozen nodes marked as
    /// `freeze` says).
    fn restrict(
        coarse: &mut Self::Level,
        fine: &Self::Level,
        r: &[f64],
        phys: &Phys<Self>,
        h0: f64,
        freeze: Freeze,
    );
    /// Add the interpolated correction `coarse.p - p_hat` to `fine.p`, project on P >= 0 and
    /// refresh the fine film at `h0`.
    fn correct(
        coarse: &Self::Level,
        p_hat: &[f64],
        fine: &mut Self::Level,
        phys: &Phys<Self>,
        h0: f64,
    );
    /// Node index of X = 0 (Y = 0) on level `l`.
    fn centre_index(mg: &Multigrid<Self>, l: usize) -> usize;
    /// H_Moes / H_Venner.
    fn h_scale(mg: &Multigrid<Self>) -> f64;
    /// The central film estimate of the domain rule (Hertzian units).
    fn h_estimate(mg: &Multigrid<Self>) -> f64;
    /// The start on the coarsest level (see [`Fas::initialise`]).
    fn initialise(mg: &mut Multigrid<Self>);
    /// The full Newton solve of the coarsest level (see [`Fas::start_coarse`]).
    fn start_coarse(mg: &mut Multigrid<Self>, with_slope: bool) -> NewtonOutcome;
    /// Level `l - 1`'s P interpolated as level `l`'s start (see [`Fas::fmg_interpolate`]).
    fn fmg_interpolate(mg: &mut Multigrid<Self>, l: usize);
    /// Install a warm-start guess on level `l` (see [`Fas::install_guess`]).
    fn install_guess(_mg: &mut Multigrid<Self>, _l: usize) -> bool {
        false
    }
    /// Whether level `l`'s nodes are those of `seed` ([`Seed::matches`]).
    fn seed_matches(mg: &Multigrid<Self>, l: usize, seed: &Seed) -> bool;
    /// Whether the coarse grids freeze a band along the cavitation boundary (no coarse-grid
    /// correction there, so its error decays by relaxation alone).
    fn frozen_band(_mg: &Multigrid<Self>) -> bool {
        true
    }
    /// Whether the contact's slow modes sit at a pressure spike next to the cavitation
    /// boundary, where two cycles' changes of H_c and H_min do not see them (with or without a
    /// frozen band): the finest level's algebraic error estimate then takes the residual bound
    /// ([`crate::solve::params::MgParams::residual_bound`]).
    fn spiked_boundary(mg: &Multigrid<Self>) -> bool {
        Self::frozen_band(mg)
    }
}

/// A domain built by a rule with parameters [`DomainRule::Params`].
pub trait DomainRule {
    /// The rule's parameters.
    type Params: Copy + FinerCoarsest;
}

/// The domain rule's parameters of contact `C`.
pub type DomainParams<C> = <<C as Contact>::Domain as DomainRule>::Params;

/// The discrete physics of contact `C`.
pub type Phys<C> = <<C as Contact>::Level as NewtonLevel>::Phys;

/// The state of a multigrid solve of contact `C`: all levels (0 the coarsest), H0, counters.
pub struct Multigrid<C: Contact> {
    /// The discrete physics.
    pub phys: Phys<C>,
    /// The domain.
    pub domain: C::Domain,
    /// The levels, coarsest first.
    pub levels: Vec<C::Level>,
    /// The film constant H0 (Hertzian units).
    pub h0: f64,
    /// The multigrid settings.
    pub params: MgParams<DomainParams<C>>,
    /// Injected coarse pressures P^_H per level.
    pub(crate) p_hat: Vec<Vec<f64>>,
    /// Relaxation sweeps in finest-grid equivalents.
    pub work_units: f64,
    /// Where the time of the current solve went (`total` is set by the solve's info).
    pub phases: PhaseTimes,
    /// A timed step is running: the steps inside it are charged to its phase.
    timing: bool,
    /// Estimate of d(load)/dH0 from the coarsest level.
    pub(crate) load_slope: f64,
    /// The last coarsest-level solve with the load equation failed: the coarsest level was
    /// solved at fixed H0, and the driver moves H0 until a retry succeeds.
    pub(crate) coarse_load_failed: bool,
    /// The coarsest level's pressure before its Newton solve, restored when Newton fails (kept
    /// here so that the cycles do not allocate).
    coarse_backup: Vec<f64>,
    /// The scale of each finest-level cycle's change ([`Fas::damp_cycles`]), and the pressure
    /// before the cycle (allocated when damping starts).
    cycle_damping: f64,
    cycle_backup: Vec<f64>,
    /// The acceleration of the finest level's cycles ([`MgParams::anderson`]).
    anderson: Anderson,
    /// The contact's own state.
    pub(crate) extra: C::Extra,
    /// The finest level's state to resume the next solve from (see [`Resume`]).
    pub(crate) resume: Option<Resume>,
    /// The discretisation error of an earlier cold solve, for resumed solves
    /// ([`Fas::discretisation_hint`]).
    pub(crate) discretisation_hint: Option<f64>,
    /// A converged solution on one of the coarser levels to start the FMG ascent from
    /// ([`Fas::install_seed`]).
    pub(crate) seed: Option<Seed>,
}

pub use crate::solve::seed::Seed;

/// A finest-level state the next [`Multigrid::solve`] starts its finest cycles from, instead
/// of the FMG ascent (the mixed-lubrication re-solves: the previous solution under a changed
/// asperity load).
pub(crate) struct Resume {
    /// The finest level's pressure.
    pub p: Vec<f64>,
    /// H0.
    pub h0: f64,
    /// The finest level's load right-hand side.
    pub g: f64,
}

impl<C: Contact> Multigrid<C> {
    /// A solve's state over `levels` (coarsest first), H0 = 0.
    pub(crate) fn from_levels(
        phys: Phys<C>,
        domain: C::Domain,
        levels: Vec<C::Level>,
        params: &MgParams<DomainParams<C>>,
        extra: C::Extra,
    ) -> Self {
        let p_hat = levels.iter().map(|l| vec![0.0; l.p().len()]).collect();
        let coarse_backup = vec![0.0; levels[0].p().len()];
        Multigrid {
            phys,
            domain,
            levels,
            h0: 0.0,
            params: *params,
            p_hat,
            work_units: 0.0,
            phases: PhaseTimes::default(),
            timing: false,
            load_slope: -1.0,
            coarse_load_failed: false,
            coarse_backup,
            cycle_damping: 1.0,
            cycle_backup: vec![],
            anderson: Anderson::default(),
            extra,
            resume: None,
            discretisation_hint: None,
            seed: None,
        }
    }

    /// Put a solved state on level `l`: its pressure `p` (no FAS right-hand side, no frozen
    /// nodes) and H0, the film and coefficients refreshed (a resumed solve, a seed).
    fn install_state(&mut self, l: usize, p: &[f64], h0: f64) {
        let lv = &mut self.levels[l];
        lv.pressure().copy_from_slice(p);
        let nodes = lv.nodes_mut();
        nodes.f.fill(0.0);
        nodes.frozen.fill(false);
        lv.refresh(&self.phys, h0);
        self.h0 = h0;
    }

    /// One relaxation sweep on level `l`, counted in work units.
    pub fn relax_level(&mut self, l: usize) {
        let cost = self.timed(Phase::Relaxation, |mg| C::sweep(mg, l));
        self.work_units += cost;
    }

    /// The coarsest level's load balance by relaxation where its Newton solve has failed (the
    /// classic coarse-grid load balance): the film refreshed, then `sweeps` relaxation sweeps,
    /// each followed by H0 += [`RELAXED_GAIN`] (h sum P - g) and the film's refresh. Where the
    /// coupled iteration runs away (a load error that is not finite or above [`RUNAWAY_LOAD`]
    /// times g: point M = 3e4, L = 4.3, D = 0.01 reached H0 = inf and a NaN film), it stops and
    /// the state before its sweeps is restored, so that the cycles start from Newton's
    /// unconverged solve instead of a non-finite film.
    pub(crate) fn relaxed_coarse_balance(&mut self, sweeps: usize) {
        let (p_start, h0_start) = (self.levels[0].p().to_vec(), self.h0);
        self.levels[0].refresh(&self.phys, self.h0);
        for _ in 0..sweeps {
            self.relax_level(0);
            let lv = &mut self.levels[0];
            let (e, g) = (lv.load_sum() - lv.load_rhs(), lv.load_rhs());
            let h0 = self.h0 + RELAXED_GAIN * e;
            if !(h0.is_finite() && e.abs() <= RUNAWAY_LOAD * g.abs()) {
                lv.pressure().copy_from_slice(&p_start);
                self.h0 = h0_start;
                lv.refresh(&self.phys, self.h0);
                return;
            }
            self.h0 = h0;
            lv.refresh(&self.phys, self.h0);
        }
    }

    /// Run the step `f`, its time charged to `phase` and its levels' deformation products to
    /// the deformation ([`PhaseTimes::charge`]); inside another timed step, to that one's.
    pub(crate) fn timed<R>(&mut self, phase: Phase, f: impl FnOnce(&mut Self) -> R) -> R {
        if self.timing {
            return f(self);
        }
        self.timing = true;
        let deform = |mg: &Self| -> f64 { mg.levels.iter().map(|l| l.deformation_seconds()).sum() };
        let (start, d0) = (std::time::Instant::now(), deform(self));
        let r = f(self);
        let d = deform(self) - d0;
        self.phases.charge(phase, start, d);
        self.timing = false;
        r
    }

    /// Solve the coarsest level's FAS problem by Newton: for P and H0 with the load equation
    /// under fast convergence (the FAS load right-hand side carries the finer levels' load, so
    /// H0 converges with the cycles), for P at fixed H0 under tight convergence (the driver's
    /// secant step moves H0) or when that fails (then `coarse_load_failed` is set for the
    /// driver). If Newton fails at fixed H0 too, the pressure before it is restored and relaxed
    /// `coarse_sweeps` times. After a failed solve with the load equation each later one tries
    /// it again with at most [`RETRY_NEWTON_ITERATIONS`] iterations (Newton converges
    /// quadratically once the cycles have brought the level close); a success hands H0 back to
    /// the cycle. Under fast convergence each solve may stop once its residual has fallen by
    /// [`crate::solve::params::MgParams::coarse_rel_tol`].
    fn coarse_solve(&mut self) {
        self.timed(Phase::Coarsest, Self::coarse_solve_untimed)
    }

    /// [`Multigrid::coarse_solve`] without its timer.
    fn coarse_solve_untimed(&mut self) {
        self.coarse_backup.copy_from_slice(self.levels[0].p());
        let free = self.params.converge == Converge::Fast;
        for fix_h0 in if free {
            &[false, true][..]
        } else {
            &[true][..]
        } {
            let np = NewtonParams {
                fix_h0: *fix_h0,
                max_iter: if !*fix_h0 && self.coarse_load_failed {
                    RETRY_NEWTON_ITERATIONS
                } else {
                    NewtonParams::default().max_iter
                },
                stall_window: MULTIGRID_STALL_WINDOW,
                deadline: self.params.deadline,
                rel_tol: if free {
                    self.params.coarse_rel_tol
                } else {
                    0.0
                },
                load_rel_tol: self.params.coarse_load_rel_tol,
                ..NewtonParams::default()
            };
            let mut h0 = self.h0;
            let out = newton_solve(&mut self.levels[0], &self.phys, &mut h0, &np);
            self.work_units += C::newton_cost(self, out.iterations);
            if (out.converged || (!out.singular && out.residual < 1e-6 * out.unit))
                && h0.is_finite()
            {
                self.h0 = h0;
                if !*fix_h0 {
                    self.coarse_load_failed = false;
                }
                return;
            }
            self.coarse_load_failed |= free;
            let lv = &mut self.levels[0];
            lv.pressure().copy_from_slice(&self.coarse_backup);
            lv.refresh(&self.phys, self.h0);
        }
        for _ in 0..self.params.coarse_sweeps {
            self.relax_level(0);
        }
    }

    /// The coarse problem of level `l`: residual, injection, right-hand sides.
    fn restrict(&mut self, l: usize) {
        let freeze = Freeze {
            band: C::frozen_band(self),
            spike: self.params.spike_freeze,
        };
        // The full residual, cavitated nodes included: there it is the complementarity margin
        // (L - f < 0), which keeps the coarse problem strictly cavitated where the fine one is;
        // zeroing it would make P = 0 a degenerate coarse solution.
        let r = self.timed(Phase::Residual, |mg| {
            let fine = &mut mg.levels[l];
            let mut r = std::mem::take(fine.delta_mut());
            fine.residual_into(&mg.phys, false, &mut r);
            r
        });
        self.timed(Phase::Transfers, |mg| {
            let (lo, hi) = mg.levels.split_at_mut(l);
            let (coarse, fine) = (&mut lo[l - 1], &mut hi[0]);
            C::restrict(coarse, fine, &r, &mg.phys, mg.h0, freeze);
            coarse.set_load_rhs(coarse.load_sum() + (fine.load_rhs() - fine.load_sum()));
            mg.p_hat[l - 1].copy_from_slice(coarse.p());
        });
        *self.levels[l].delta_mut() = r;
    }

    /// One FAS cycle with level `l` as the finest (see the module docs).
    pub fn fas_cycle(&mut self, l: usize) {
        if l == 0 {
            self.coarse_solve();
            return;
        }
        for _ in 0..self.params.pre {
            self.relax_level(l);
        }
        self.restrict(l);
        for _ in 0..self.params.cycle.gamma() {
            self.fas_cycle(l - 1);
        }
        self.timed(Phase::Transfers, |mg| {
            let (lo, hi) = mg.levels.split_at_mut(l);
            C::correct(&lo[l - 1], &mg.p_hat[l - 1], &mut hi[0], &mg.phys, mg.h0);
        });
        for _ in 0..self.params.post {
            self.relax_level(l);
        }
    }

    /// Convergence measures of level `l` after a cycle: the mean |f - L| over the pressurised
    /// nodes, the relative load error, the central film (Moes units) and the work so far.
    pub fn record(&mut self, l: usize) -> CycleRecord {
        self.timed(Phase::Residual, |mg| mg.record_untimed(l))
    }

    /// [`Multigrid::record`] without its timer.
    fn record_untimed(&mut self, l: usize) -> CycleRecord {
        let ic = C::centre_index(self, l);
        let h_scale = C::h_scale(self);
        let fine = &mut self.levels[l];
        let mut r = std::mem::take(fine.delta_mut());
        fine.residual_into(&self.phys, true, &mut r);
        let active = fine.p().iter().filter(|&&p| p > 0.0).count().max(1);
        let residual = r.iter().map(|v| v.abs()).sum::<f64>() / active as f64;
        *fine.delta_mut() = r;
        let h_min = fine.film().iter().fold(f64::INFINITY, |a, &b| a.min(b));
        CycleRecord {
            residual,
            load_error: (fine.load_sum() - fine.load_rhs()) / fine.load_rhs(),
            h_c: fine.film()[ic] * h_scale,
            h_min: h_min * h_scale,
            work_units: self.work_units,
        }
    }

    /// Run FMG: to the discretisation error ([`crate::solve::fmg_fast::fmg_fast_solve`]) or
    /// to the tolerances ([`crate::solve::fmg::fmg_solve`]), as `params.converge` says.
    pub fn solve(&mut self) -> SolveInfo {
        self.anderson.reset();
        self.phases = PhaseTimes::default();
        match self.params.converge {
            Converge::Fast => fmg_fast_solve(self),
            Converge::Tight => fmg_solve(self),
        }
    }
}

impl<C: Contact> Fas for Multigrid<C> {
    fn control(&self) -> FmgControl {
        let mut c = self.params.control(C::COARSE_BUDGET_GROWTH);
        if !C::spiked_boundary(self) {
            c.residual_bound = 0.0;
        }
        c
    }
    fn top(&self) -> usize {
        self.levels.len() - 1
    }
    fn initialise(&mut self) {
        C::initialise(self)
    }
    fn start_coarse(&mut self, with_slope: bool) -> NewtonOutcome {
        self.timed(Phase::Coarsest, |mg| C::start_coarse(mg, with_slope))
    }
    fn load_slope(&self) -> f64 {
        self.load_slope
    }
    fn fmg_interpolate(&mut self, l: usize) {
        self.timed(Phase::Transfers, |mg| C::fmg_interpolate(mg, l))
    }
    fn relax(&mut self, l: usize) {
        self.relax_level(l)
    }
    fn cycle(&mut self, l: usize) {
        // The finest level's fast cycles with the Anderson step, where the coarse grids freeze
        // no band (there the slow mode is smooth and global, which the step extrapolates; at a
        // frozen band it is the spike or the cavitation boundary, which it does not), and not
        // once damping has started (a damped cycle is the conservative one).
        let accelerate =
            self.params.anderson && self.params.converge == Converge::Fast && !C::frozen_band(self);
        if accelerate && self.cycle_damping == 1.0 && l + 1 == self.levels.len() {
            self.anderson.begin(self.levels[l].p());
            self.fas_cycle(l);
            let lv = &mut self.levels[l];
            if self.anderson.mix(lv.pressure(), &mut self.h0) {
                lv.refresh(&self.phys, self.h0);
            }
            return;
        }
        if self.cycle_damping == 1.0 {
            return self.fas_cycle(l);
        }
        let beta = self.cycle_damping;
        let h0 = self.h0;
        self.cycle_backup.clear();
        self.cycle_backup.extend_from_slice(self.levels[l].p());
        self.fas_cycle(l);
        self.h0 = h0 + beta * (self.h0 - h0);
        let lv = &mut self.levels[l];
        // Where the contact says so, a node the cycle left cavitated stays so
        // ([`Contact::KEEP_CAVITATED`]).
        for (p, &old) in lv.pressure().iter_mut().zip(&self.cycle_backup) {
            if *p > 0.0 || !C::KEEP_CAVITATED {
                *p = old + beta * (*p - old);
            }
        }
        lv.refresh(&self.phys, self.h0);
    }
    fn damp_cycles(&mut self, beta: f64) {
        self.cycle_damping = beta;
    }
    fn record(&mut self, l: usize) -> CycleRecord {
        Multigrid::record(self, l)
    }
    fn h0(&self) -> f64 {
        self.h0
    }
    fn set_h0(&mut self, l: usize, h0: f64) {
        self.h0 = h0;
        self.levels[l].refresh(&self.phys, h0);
    }
    fn centre_film(&self, l: usize) -> f64 {
        self.levels[l].film()[C::centre_index(self, l)]
    }
    fn h_estimate(&self) -> f64 {
        C::h_estimate(self)
    }
    fn load_target(&self, l: usize) -> f64 {
        self.levels[l].load_rhs()
    }
    fn observer(&self) -> Option<Observer> {
        self.params.observer
    }
    fn install_guess(&mut self, l: usize) -> bool {
        if l + 1 == self.levels.len() {
            if let Some(r) = self.resume.take() {
                self.levels[l].set_load_rhs(r.g);
                self.install_state(l, &r.p, r.h0);
                return true;
            }
        }
        C::install_guess(self, l)
    }
    fn install_seed(&mut self) -> Option<usize> {
        let seed = self.seed.take()?;
        let top = self.levels.len() - 1;
        let l = (0..top).find(|&l| C::seed_matches(self, l, &seed))?;
        let h0 = seed.h0_moes / C::h_scale(self);
        self.install_state(l, &seed.p, h0);
        Some(l)
    }
    fn coarse_load_failed(&self) -> bool {
        self.coarse_load_failed
    }
    fn discretisation_hint(&self) -> Option<f64> {
        self.discretisation_hint
    }
    fn resuming(&self) -> bool {
        self.resume.is_some()
    }
    fn work_units(&self) -> f64 {
        self.work_units
    }
    fn phases(&self) -> PhaseTimes {
        self.phases
    }
    fn restart_acceleration(&mut self) {
        self.anderson.reset();
    }
    fn points(&self, l: usize) -> usize {
        self.levels[l].points()
    }
}
