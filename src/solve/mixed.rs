//! Mixed lubrication: the load shared between the fluid and the asperities (Greenwood-Tripp),
//! for both contacts, around the smooth multigrid solve.
//!
//! Contract. With rough surfaces ([`crate::discrete::roughness::RoughLaw`]) the film is
//! `H = H0 + gap + c K*(P + P_a)` and the load equation `area sum (P + P_a) = load`, where the
//! asperity pressure `P_a = A F_5/2(H/sigma)` is a local function of the film. [`solve_mixed`]
//! finds this by a damped fixed point on the finest grid: given `P_a`, the multigrid solves the
//! average Reynolds equation with the deformation of `P_a` added to every level's film (the
//! finest level's, injected) and the fluid's share of the load reduced by `area sum P_a`; then
//! `P_a <- P_a + omega (P_a(H) - P_a)`. It stops when `max |P_a(H) - P_a|` is below
//! [`MIXED_TOLERANCE`] (in units of p_h, so that a vanishing asperity load does not make the
//! test relative to nothing), after at most
//! [`MAX_MIXED_ITERATIONS`] re-solves; omega starts at 1/2 and halves whenever the fixed-point
//! residual grows. Where `H/sigma > 7` everywhere `P_a = 0` exactly and the single smooth-operator
//! solve is the answer. Outputs: the fluid solve's [`SolveInfo`] (work units and wall time of all
//! re-solves; status max-iterations with the reason when the fixed point did not converge), the
//! asperity pressure on the finest grid and its share of the load ([`MixedState`]).

use crate::discrete::physics::AsPhysics;
use crate::model::case::Models;
use crate::solve::multilevel::{Contact, GridLevel, Multigrid, Phys, Resume};
use crate::solve::newton::NewtonLevel;
use crate::solve::solution::{MixedOutputs, Outputs};
use crate::solve::{SolveInfo, Status};

/// Re-solves allowed to the fixed point of the asperity load.
pub const MAX_MIXED_ITERATIONS: usize = 60;
/// The fixed point's tolerance: `max |P_a(H) - P_a|` in units of p_h.
pub const MIXED_TOLERANCE: f64 = 1e-5;
/// The smallest share of the load left to the fluid; heavier asperity loads are reported as a
/// failure (the average flow model is not meant for them).
pub const MIN_FLUID_SHARE: f64 = 0.02;

/// The asperity side of a mixed solve on the finest grid.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MixedState {
    /// P_a = p_a/p_h at the finest grid's nodes (storage order of the level).
    pub asperity_pressure: Vec<f64>,
    /// area sum P_a over the load.
    pub asperity_load_fraction: f64,
    /// Re-solves of the fixed point (0: no asperity contact anywhere).
    pub iterations: usize,
    /// The last fixed-point residual max |P_a(H) - P_a| (units of p_h).
    pub residual: f64,
}

/// Fill the mixed outputs of a solve of a case with `models` (none when smooth): the film
/// parameters, the asperity share, and the load error of fluid (`fluid_load`, area sum P) and
/// asperities together against the full load `total_load`.
pub fn set_mixed_outputs(
    out: &mut Outputs,
    models: &Models,
    state: Option<&MixedState>,
    fluid_load: f64,
    total_load: f64,
) {
    let Some(r) = models.roughness.filter(|r| r.is_rough()) else {
        return;
    };
    let (fraction, pmax, iterations) = match state {
        Some(s) => (
            s.asperity_load_fraction,
            s.asperity_pressure.iter().fold(0.0f64, |a, &b| a.max(b)),
            s.iterations,
        ),
        None => (0.0, 0.0, 0),
    };
    out.load_error = (fluid_load + fraction * total_load - total_load) / total_load;
    out.mixed = Some(MixedOutputs {
        sigma: r.sigma,
        gamma: r.gamma,
        slide_roll: r.slide_roll,
        lambda_min: out.h_min / r.sigma,
        lambda_c: out.h_c / r.sigma,
        asperity_load_fraction: fraction,
        p_asperity_max: pmax,
        mixed_iterations: iterations,
        h_c_smooth: None,
        h_min_smooth: None,
    });
}

/// Solve a case with rough surfaces (module docs); `None` beside a smooth case's info.
pub fn solve_mixed<C: Contact>(mg: &mut Multigrid<C>) -> (SolveInfo, Option<MixedState>)
where
    Phys<C>: AsPhysics,
{
    let Some(law) = mg.phys.physics().rough else {
        return (mg.solve(), None);
    };
    let mut info = mg.solve();
    mg.discretisation_hint = info.discretisation_error;
    let top = mg.levels.len() - 1;
    let n = mg.levels[top].p().len();
    let area = mg.levels[top].cell_area();
    // The full load (the fluid's share is 1 on the first solve).
    let share0 = mg.phys.physics().fluid_share;
    let total = mg.levels[top].load_rhs() / share0;
    let mut state = MixedState {
        asperity_pressure: vec![0.0; n],
        ..MixedState::default()
    };
    let mut wall = info.wall_s;
    let mut omega = 0.5;
    let mut last_residual = f64::INFINITY;
    let mut target = vec![0.0; n];
    let mut gap = vec![0.0; n];
    loop {
        if info.status != Status::Converged {
            info.reason = format!(
                "{}; mixed lubrication: the fluid solve failed at fixed-point iteration {}",
                info.reason, state.iterations
            );
            break;
        }
        let fine = &mg.levels[top];
        let mut residual = 0.0f64;
        for ((t, &h), &pa) in target
            .iter_mut()
            .zip(fine.film())
            .zip(&state.asperity_pressure)
        {
            *t = law.asperity_pressure(h);
            residual = residual.max((*t - pa).abs());
        }
        state.residual = residual;
        if state.iterations == 0 && residual == 0.0 {
            break; // no asperity contact: the smooth-operator solve is the answer
        }
        if state.residual <= MIXED_TOLERANCE {
            break;
        }
        if state.iterations >= MAX_MIXED_ITERATIONS {
            info.status = Status::MaxIterations;
            info.reason = format!(
                "mixed lubrication: the asperity load did not settle in {} re-solves \
                 (fixed-point residual {:.1e}, tolerance {:.0e})",
                MAX_MIXED_ITERATIONS, state.residual, MIXED_TOLERANCE
            );
            break;
        }
        if residual > last_residual {
            omega *= 0.5;
        }
        last_residual = residual;
        // The fluid gives up to the asperities what they take at each node, so that the total
        // pressure, and with it the film and the load, stay as they were: the resumed solve
        // starts from a state off only in its Reynolds residual.
        let mut p_resume = mg.levels[top].p().to_vec();
        for ((pa, &t), p) in state
            .asperity_pressure
            .iter_mut()
            .zip(&target)
            .zip(&mut p_resume)
        {
            let step = omega * (t - *pa);
            *pa += step;
            *p = (*p - step).max(0.0);
        }
        let asperity_load = area * state.asperity_pressure.iter().sum::<f64>();
        state.asperity_load_fraction = asperity_load / total;
        let share = 1.0 - state.asperity_load_fraction;
        if share < MIN_FLUID_SHARE {
            info.status = Status::Diverged;
            info.reason = format!(
                "mixed lubrication: the asperities would carry {:.1} % of the load; the average \
                 flow model needs a fluid film (raise H/sigma)",
                100.0 * state.asperity_load_fraction
            );
            break;
        }
        mg.phys.physics_mut().fluid_share = share;
        mg.levels[top].deformation_of(&mg.phys, &state.asperity_pressure, &mut gap);
        for l in 0..top {
            let coarse = mg.levels[l].inject_field(&mg.levels[top], &gap);
            mg.levels[l].nodes_mut().asperity_gap = coarse;
        }
        mg.levels[top].nodes_mut().asperity_gap.clone_from(&gap);
        mg.resume = Some(Resume {
            p: p_resume,
            h0: mg.h0,
            g: total * share,
        });
        state.iterations += 1;
        info = mg.solve();
        wall += info.wall_s;
    }
    info.wall_s = wall;
    (info, Some(state))
}
