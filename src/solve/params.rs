//! The settings of a solve, shared by line and point contacts: the method, the cycle type, the
//! multigrid settings ([`MgParams`]) and a contact's solve parameters ([`ContactParams`]), each
//! generic over the contact's domain rule; and the fallback ladder's rungs ([`Rung`]), the
//! conservative settings a failed attempt is retried with.

use crate::solve::fmg::FmgControl;
use crate::solve::relax::{RelaxParams, SpikeNewton};
use serde::{Deserialize, Serialize};

/// V or W cycles.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum CycleType {
    #[default]
    /// V cycles: one coarse-grid correction per level.
    V,
    /// W cycles: two coarse-grid corrections per level.
    W,
}

impl CycleType {
    /// The name stored in TOML and Parquet (`v`, `w`).
    pub fn as_str(&self) -> &'static str {
        match self {
            CycleType::V => "v",
            CycleType::W => "w",
        }
    }

    pub(crate) fn gamma(self) -> usize {
        match self {
            CycleType::V => 1,
            CycleType::W => 2,
        }
    }
}

impl std::str::FromStr for CycleType {
    type Err = crate::model::error::ParamError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        [CycleType::V, CycleType::W]
            .into_iter()
            .find(|c| c.as_str() == s)
            .ok_or_else(|| crate::model::error::ParamError::Unknown {
                what: "cycle",
                name: s.to_string(),
                expected: "v or w",
            })
    }
}

impl std::fmt::Display for CycleType {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// How far the finest level is converged.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Converge {
    /// To the discretisation error (default): full multigrid with a few cycles per level and
    /// the load balance inside the cycle (H0 solved on the coarsest level); on every level the
    /// cycles stop when the algebraic error estimate of H_c and H_min is below a tenth of the
    /// discretisation error estimate (the difference to the next coarser level's solution).
    #[default]
    Fast,
    /// To the tolerances (`tol_load`, `tol_h`): cycles until P settles, a secant step on H0 per
    /// settled state, the algebraic error driven far below the discretisation error (for
    /// references and tests).
    Tight,
}

impl Converge {
    /// The name on the command line and in TOML (`fast`, `tight`).
    pub fn as_str(&self) -> &'static str {
        match self {
            Converge::Fast => "fast",
            Converge::Tight => "tight",
        }
    }
}

impl std::str::FromStr for Converge {
    type Err = crate::model::error::ParamError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        [Converge::Fast, Converge::Tight]
            .into_iter()
            .find(|c| c.as_str() == s)
            .ok_or_else(|| crate::model::error::ParamError::Unknown {
                what: "convergence",
                name: s.to_string(),
                expected: "fast or tight",
            })
    }
}

impl std::fmt::Display for Converge {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Which solver.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Full multigrid (FAS), the default.
    #[default]
    Multigrid,
    /// Damped Newton-Raphson on the finest grid with a dense Jacobian (baseline; O(N^3)).
    Newton,
    /// The multigrid smoother alone on the finest grid (baseline).
    Relax,
}

impl Method {
    /// The name on the command line and in reports.
    pub fn as_str(&self) -> &'static str {
        match self {
            Method::Multigrid => "multigrid",
            Method::Newton => "newton",
            Method::Relax => "relax",
        }
    }
}

/// Multigrid settings of a solve, shared by line and point contacts; `D` is the contact's domain
/// rule ([`crate::discrete::line::domain::DomainParams`] or
/// [`crate::discrete::point::domain::PointDomainParams`]). `Default` (per contact) gives the
/// settings the stability map supports.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MgParams<D> {
    /// Points of the finest level (2^k n0 + 1 for the domain rule's n0; other values are rounded
    /// up to the next such size).
    pub grid: usize,
    /// V or W cycles.
    pub cycle: CycleType,
    /// Relaxations before the coarse-grid correction.
    pub pre: usize,
    /// Relaxations after the coarse-grid correction.
    pub post: usize,
    /// How far the finest level is converged (the stopping rule).
    pub converge: Converge,
    /// Cycles on each FMG level before moving to the next finer one (tight convergence: 4x
    /// this at most, growing on coarser levels; fast convergence: 2x this at most).
    pub fmg_cycles: usize,
    /// Cycles allowed on the finest level after FMG.
    pub max_cycles: usize,
    /// The smoother's constants.
    pub relax: RelaxParams,
    /// Damping of the secant load-balance step on H0 (`None`: 1).
    pub load_factor: Option<f64>,
    /// Relaxations of the coarsest level when its Newton solve fails.
    pub coarse_sweeps: usize,
    /// Converged when |load error| < tol_load and the relative change of H_c over a cycle is
    /// below tol_h.
    pub tol_load: f64,
    /// Converged when the relative change of H_c over a cycle is below this (and |load error| <
    /// tol_load).
    pub tol_h: f64,
    /// Load tolerance on the coarser FMG levels before moving up.
    pub tol_load_fmg: f64,
    /// Fast convergence: the largest algebraic error the finest level may stop with, however
    /// large its discretisation error estimate (default
    /// [`crate::solve::fmg_fast::MAX_ALGEBRAIC_ERROR`]; the accuracy ladder lowers it to a
    /// fraction of its target).
    pub max_algebraic: f64,
    /// Fast convergence: the factor c of the residual bound on the finest level's algebraic
    /// error, c 3 e_d r_k / r_0 (e_d the discretisation estimate, r_0 and r_k the residuals
    /// after its first and latest cycle; 0: none). Default
    /// [`crate::solve::fmg_fast::RESIDUAL_BOUND`]; the line contact takes
    /// [`crate::solve::line::multigrid::LINE_RESIDUAL_BOUND`].
    pub residual_bound: f64,
    /// Fast convergence: accelerate the finest level's cycles where the coarse grids freeze no
    /// band ([`crate::solve::multilevel::Contact::frozen_band`]) by Anderson acceleration of
    /// depth one ([`crate::solve::anderson`]; restarted after a cycle contracting the residual
    /// by less than [`crate::solve::fmg_fast::ACCELERATION_RESTART`]). On for point contacts
    /// (alpha_bar < 5), off for line contacts (docs/performance.md, "Anderson acceleration of
    /// the finest cycles").
    pub anderson: bool,
    /// Fast convergence: a cycle's coarsest-level Newton solve also stops once its scaled
    /// residual has fallen by this factor ([`crate::solve::newton::NewtonParams::rel_tol`]; 0:
    /// only at the absolute tolerance). Point contacts take
    /// [`crate::solve::point::multigrid::POINT_COARSE_REL_TOL`] = 1e-2, line contacts 0 (with a relative
    /// stop, line M = 1e4, L = 40 no longer converged on 16385 points; docs/performance.md).
    pub coarse_rel_tol: f64,
    /// Fast convergence, with `coarse_rel_tol`: that stop also needs the load equation's part
    /// of the residual below this fraction of the initial norm
    /// ([`crate::solve::newton::NewtonParams::load_rel_tol`]; infinite: no such condition).
    /// Point contacts take [`crate::solve::point::multigrid::POINT_COARSE_LOAD_REL_TOL`].
    pub coarse_load_rel_tol: f64,
    /// Point contacts: whether the coarse grids freeze the band along the cavitation boundary
    /// where the physics have one (alpha_bar >=
    /// [`crate::solve::point::multigrid::FREEZE_ALPHA_BAR`]): `None` (default) as the case
    /// says, from L = [`crate::solve::point::multigrid::FREEZE_MIN_L`] on
    /// ([`crate::solve::point::multigrid::first_freezes`]); `Some(b)` b (the [`Rung::Unfrozen`]
    /// and [`Rung::Frozen`] rungs). Line contacts always freeze it.
    pub freeze_band: Option<bool>,
    /// Line contacts: the coarse grids also hold fixed the nodes next to a pressurised fine node
    /// whose |r| exceeds this factor times the mean |r| (the outlet spike steeper than the grid,
    /// [`crate::solve::multilevel::Freeze::spike`]); `None` (default): no such nodes.
    pub spike_freeze: Option<f64>,
    /// The contact's domain rule.
    pub domain: D,
    /// Line contacts: override the coarsest grid's interval count (a power of two >= 8).
    pub coarse_intervals: Option<usize>,
    /// Second-order upwind wedge term (default) or first order.
    pub second_order: bool,
    /// Newton iterations allowed for the first coarsest-grid solve (and for the Newton method).
    pub newton_max_iter: usize,
    /// Deformation by the O(N^2) direct sum on every level instead of the FFT (baseline).
    pub direct_deformation: bool,
    /// Point contacts: relax blocks of rows at once on the current rayon pool, on levels of 65
    /// rows or more (Gauss-Seidel within each block, the rows between blocks after them:
    /// [`crate::solve::point::relax`]); the result does not depend on the number of threads.
    /// Off by default: a sweep already runs one solve per thread.
    pub parallel: bool,
    /// Receives every cycle of the solve.
    pub observer: Option<crate::solve::Observer>,
    /// Stop at this instant: the cycle running then is the last, the fallback and accuracy
    /// ladders try nothing further, and an unconverged solve ends with status max-iterations
    /// and a reason naming the time limit (`None`: no limit). A solve that meets its limit
    /// depends on the machine's speed; one that ends before it does not.
    pub deadline: Option<std::time::Instant>,
}

impl<D> MgParams<D> {
    /// The settings every contact defaults to, with the contact's domain rule, finest grid,
    /// cycle limit and tolerances: V(2, 1) cycles (the line contact's own default takes V(1, 1)),
    /// two cycles per FMG level, 20 coarse sweeps
    /// and 40 Newton iterations as fallbacks, second-order upwinding, the FFT deformation.
    pub fn defaults(domain: D, grid: usize, max_cycles: usize, tol_load: f64, tol_h: f64) -> Self {
        MgParams {
            grid,
            cycle: CycleType::V,
            pre: 2,
            post: 1,
            converge: Converge::Fast,
            fmg_cycles: 2,
            max_cycles,
            relax: RelaxParams::default(),
            load_factor: None,
            coarse_sweeps: 20,
            tol_load,
            tol_h,
            tol_load_fmg: 1e-4,
            max_algebraic: crate::solve::fmg_fast::MAX_ALGEBRAIC_ERROR,
            residual_bound: crate::solve::fmg_fast::RESIDUAL_BOUND,
            anderson: false,
            coarse_rel_tol: 0.0,
            coarse_load_rel_tol: f64::INFINITY,
            freeze_band: None,
            spike_freeze: None,
            domain,
            coarse_intervals: None,
            second_order: true,
            newton_max_iter: 40,
            direct_deformation: false,
            parallel: false,
            observer: None,
            deadline: None,
        }
    }

    /// The FMG driver's controls; a coarser level's cycle budget grows by
    /// `coarse_budget_growth` per level below the finest.
    pub fn control(&self, coarse_budget_growth: usize) -> FmgControl {
        FmgControl {
            fmg_cycles: self.fmg_cycles,
            max_cycles: self.max_cycles,
            tol_load: self.tol_load,
            tol_h: self.tol_h,
            tol_load_fmg: self.tol_load_fmg,
            max_algebraic: self.max_algebraic,
            residual_bound: self.residual_bound,
            load_factor: self.load_factor,
            coarse_budget_growth,
            deadline: self.deadline,
        }
    }
}

/// A domain rule whose coarsest grid can be made finer (a rung of the fallback ladder).
pub trait FinerCoarsest {
    /// Halve the coarsest grid's spacing.
    fn finer_coarsest(&mut self);
}

/// The line smoother's under-relaxation on the [`Rung::LightDamping`] rung (the point ladder's
/// second; the default is [`crate::solve::relax::RelaxParams`]' 0.5). Its rung's name states
/// this value.
pub const LIGHT_DAMPING: f64 = 0.8;

/// A rung of the fallback ladder: how an attempt changes the first attempt's settings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rung {
    /// The settings as given.
    Default,
    /// V(4, 4) cycles: four pre- and post-relaxations at least.
    Smooth44,
    /// W cycles with the default smoother, keeping the stopping rule as given (the one rung
    /// that does not converge tightly: a W cycle's coarse-grid corrections settle a pressure
    /// spike that V cycles with either rule leave oscillating).
    WCycles,
    /// The line smoother under-relaxed to 0.3 at most.
    Damped,
    /// The line smoother relaxed by [`LIGHT_DAMPING`] (less under-relaxed than the default),
    /// keeping the stopping rule as given.
    LightDamping,
    /// Distributive line relaxation at every node.
    Distributive,
    /// Distributive relaxation with W cycles.
    DistributiveW,
    /// Distributive relaxation with W cycles and a finer coarsest grid.
    DistributiveWFiner,
    /// The settings as given, converged tightly (the secant load balance between settled
    /// states instead of H0 solved inside the cycle).
    Tight,
    /// The default smoother with the kernel kept exactly over a band twice as wide (at least 8
    /// cells each side), keeping the stopping rule as given.
    WideBand,
    /// Point contacts: no band frozen along the cavitation boundary on the coarse grids
    /// ([`MgParams::freeze_band`]), keeping the stopping rule as given.
    Unfrozen,
    /// Point contacts: the band frozen along the cavitation boundary on the coarse grids (where
    /// the physics have one), keeping the stopping rule as given.
    Frozen,
    /// Line contacts: Newton windows at the outlet spike after each sweep on levels of 4097
    /// points or more ([`SPIKE_NEWTON`]), keeping the stopping rule as given.
    SpikeNewton,
    /// Line contacts: the coarse grids hold fixed the nodes next to the outlet spike
    /// ([`MgParams::spike_freeze`] = [`SPIKE_FREEZE`]), keeping the stopping rule as given.
    SpikeFrozen,
    /// Line contacts: Newton windows at a lower threshold on every level
    /// ([`SPIKE_NEWTON_ALL`]), keeping the stopping rule as given.
    SpikeNewtonAll,
    /// Line contacts: [`Rung::SpikeFrozen`] with V(4, 4) cycles.
    SpikeFrozenSmooth44,
    /// Line contacts: [`Rung::SpikeNewton`] with V(4, 4) cycles.
    SpikeNewtonSmooth44,
}

/// The Newton windows of [`Rung::SpikeNewton`]: nodes with |r| above 10 times the mean, up to 8
/// steps, on levels of 4097 points or more.
pub const SPIKE_NEWTON: SpikeNewton = SpikeNewton {
    factor: 10.0,
    iterations: 8,
    min_points: 4097,
};

/// The Newton windows of [`Rung::SpikeNewtonAll`]: nodes with |r| above 5 times the mean, up to
/// 8 steps, on every level.
pub const SPIKE_NEWTON_ALL: SpikeNewton = SpikeNewton {
    factor: 5.0,
    iterations: 8,
    min_points: 0,
};

/// The factor of [`Rung::SpikeFrozen`] ([`MgParams::spike_freeze`]).
pub const SPIKE_FREEZE: f64 = 10.0;

impl Rung {
    /// The name a solve's reason carries when this rung answered.
    pub fn name(self) -> &'static str {
        match self {
            Rung::Default => "default smoother",
            Rung::Smooth44 => "default smoother, V(4, 4) cycles",
            Rung::WCycles => "default smoother, W cycles",
            Rung::Damped => "default smoother, under-relaxation 0.3",
            Rung::LightDamping => "default smoother, under-relaxation 0.8",
            Rung::Distributive => "distributive line relaxation everywhere",
            Rung::DistributiveW => "distributive relaxation, W cycles",
            Rung::DistributiveWFiner => "distributive relaxation, W cycles, finer coarsest grid",
            Rung::Tight => "default smoother, tight convergence",
            Rung::WideBand => "default smoother, twice the kernel band",
            Rung::Unfrozen => "default smoother, no frozen band",
            Rung::Frozen => "default smoother, frozen band",
            Rung::SpikeNewton => "default smoother, Newton windows at the spike",
            Rung::SpikeFrozen => "default smoother, spike frozen on the coarse grids",
            Rung::SpikeNewtonAll => "default smoother, Newton windows on every level",
            Rung::SpikeFrozenSmooth44 => "spike frozen on the coarse grids, V(4, 4) cycles",
            Rung::SpikeNewtonSmooth44 => "Newton windows at the spike, V(4, 4) cycles",
        }
    }

    /// `p` changed as this rung says; every rung but the first, [`Rung::WCycles`],
    /// [`Rung::LightDamping`], [`Rung::WideBand`], [`Rung::Unfrozen`], [`Rung::Frozen`] and the
    /// five spike rungs converges tightly (the conservative load balance).
    pub fn apply<D: Copy + FinerCoarsest>(self, p: &MgParams<D>) -> MgParams<D> {
        let mut q = *p;
        if !matches!(
            self,
            Rung::Default
                | Rung::WCycles
                | Rung::WideBand
                | Rung::LightDamping
                | Rung::Unfrozen
                | Rung::Frozen
                | Rung::SpikeNewton
                | Rung::SpikeFrozen
                | Rung::SpikeNewtonAll
                | Rung::SpikeFrozenSmooth44
                | Rung::SpikeNewtonSmooth44
        ) {
            q.converge = Converge::Tight;
        }
        match self {
            Rung::Default => {}
            Rung::WCycles => q.cycle = CycleType::W,
            Rung::Tight => {}
            Rung::WideBand => q.relax.band = (2 * p.relax.band).max(8),
            // V(4, 4): below, with the spike rungs that take it too.
            Rung::Smooth44 => {}
            Rung::Damped => q.relax.omega_line = (0.6 * p.relax.omega_line).min(0.3),
            Rung::LightDamping => q.relax.omega_line = LIGHT_DAMPING,
            Rung::Unfrozen => q.freeze_band = Some(false),
            Rung::Frozen => q.freeze_band = Some(true),
            Rung::SpikeNewton | Rung::SpikeNewtonSmooth44 => {
                q.relax.spike_newton = Some(SPIKE_NEWTON)
            }
            Rung::SpikeFrozen | Rung::SpikeFrozenSmooth44 => q.spike_freeze = Some(SPIKE_FREEZE),
            Rung::SpikeNewtonAll => q.relax.spike_newton = Some(SPIKE_NEWTON_ALL),
            Rung::Distributive => q.relax.xi_threshold = f64::INFINITY,
            Rung::DistributiveW | Rung::DistributiveWFiner => {
                q.relax.xi_threshold = f64::INFINITY;
                q.cycle = CycleType::W;
                if self == Rung::DistributiveWFiner {
                    q.domain.finer_coarsest();
                }
            }
        }
        if matches!(
            self,
            Rung::Smooth44 | Rung::SpikeFrozenSmooth44 | Rung::SpikeNewtonSmooth44
        ) {
            q.pre = p.pre.max(4);
            q.post = p.post.max(4);
        }
        q
    }
}

/// Parameters of a solve of one contact; `Default` (per contact) is the library's default.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactParams<D> {
    /// Multigrid (default), or a baseline on the finest grid: the smoother alone (`Relax`) or
    /// dense semi-smooth Newton (`Newton`; its O(N^3) cost limits it to small grids).
    pub method: Method,
    /// Sweeps allowed to the single-grid relaxation baseline.
    pub relax_max_sweeps: usize,
    /// The multigrid settings.
    pub mg: MgParams<D>,
    /// Retry with conservative settings when the first attempt fails.
    pub fallback: bool,
    /// Return the finest-grid profile (line) or fields (point).
    pub keep_fields: bool,
}

impl<D> ContactParams<D>
where
    MgParams<D>: Default,
{
    /// The default method and ladder over the given multigrid settings.
    pub fn with_mg(mg: MgParams<D>) -> Self {
        ContactParams {
            method: Method::Multigrid,
            relax_max_sweeps: 20_000,
            mg,
            fallback: true,
            keep_fields: false,
        }
    }
}

impl<D> Default for ContactParams<D>
where
    MgParams<D>: Default,
{
    fn default() -> Self {
        ContactParams::with_mg(MgParams::default())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_lightly_damped_rung_sets_and_names_its_under_relaxation() {
        let p = MgParams::<crate::discrete::point::domain::PointDomainParams>::default();
        let q = Rung::LightDamping.apply(&p);
        assert_eq!(q.relax.omega_line, LIGHT_DAMPING);
        assert!(q.relax.omega_line > p.relax.omega_line);
        // The stopping rule and everything else as given.
        assert_eq!(q.converge, p.converge);
        assert_eq!(
            MgParams {
                relax: p.relax,
                ..q
            },
            p
        );
        let name = Rung::LightDamping.name();
        assert!(name.contains(&format!("{LIGHT_DAMPING}")), "{name}");
    }

    #[test]
    fn the_band_rungs_set_the_band_and_change_nothing_else() {
        let p = MgParams::<crate::discrete::point::domain::PointDomainParams>::default();
        assert_eq!(p.freeze_band, None);
        for (rung, band) in [(Rung::Unfrozen, false), (Rung::Frozen, true)] {
            let q = rung.apply(&p);
            assert_eq!(q.freeze_band, Some(band));
            assert_eq!(q.converge, p.converge);
            assert_eq!(
                MgParams {
                    freeze_band: None,
                    ..q
                },
                p
            );
        }
        assert_ne!(Rung::Frozen.name(), Rung::Unfrozen.name());
    }

    #[test]
    fn the_spike_rungs_set_their_spike_setting_and_change_nothing_else() {
        let p = MgParams::<crate::discrete::line::domain::DomainParams>::default();
        assert_eq!((p.relax.spike_newton, p.spike_freeze), (None, None));
        for rung in [
            Rung::SpikeNewton,
            Rung::SpikeFrozen,
            Rung::SpikeNewtonAll,
            Rung::SpikeFrozenSmooth44,
            Rung::SpikeNewtonSmooth44,
        ] {
            let q = rung.apply(&p);
            assert_eq!(q.converge, p.converge, "{rung:?}");
            let want = match rung {
                Rung::SpikeNewton | Rung::SpikeNewtonSmooth44 => (Some(SPIKE_NEWTON), None),
                Rung::SpikeFrozen | Rung::SpikeFrozenSmooth44 => (None, Some(SPIKE_FREEZE)),
                _ => (Some(SPIKE_NEWTON_ALL), None),
            };
            assert_eq!((q.relax.spike_newton, q.spike_freeze), want, "{rung:?}");
            let smooth = matches!(rung, Rung::SpikeFrozenSmooth44 | Rung::SpikeNewtonSmooth44);
            assert_eq!(
                (q.pre, q.post),
                if smooth { (4, 4) } else { (p.pre, p.post) }
            );
            let mut back = q;
            back.relax.spike_newton = None;
            back.spike_freeze = None;
            (back.pre, back.post) = (p.pre, p.post);
            assert_eq!(back, p, "{rung:?}");
        }
    }
}
