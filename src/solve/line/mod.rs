//! The line-contact solve as a library call: case + parameters in, outputs + info (+ profile) out.
//!
//! With `fallback` on (the default) a solve that does not converge is retried with more
//! conservative smoother settings, in this order, and the reason names the attempt that was kept:
//!
//! 1. the given parameters (line relaxation, distribution where xi < 100);
//! 2. the same with the tight stopping rule (when the given one is fast);
//! 3. more smoothing, V(4, 4) cycles (at L = 20 on 4097 points the V(2, 1) cycles of M = 103
//!    and 326 wandered for 60 cycles with residuals of order 1 while V(4, 4) converged in 570
//!    and 220 work units, to 0.1 % of the 2049-point film);
//! 4. the given cycles with the line under-relaxation lowered to 0.3 (steep piezoviscous spikes
//!    at L = 20 on fine grids);
//! 5. distributive line relaxation everywhere (xi threshold infinite): damps the smooth modes
//!    that the truncated kernel tail of the non-distributed rows amplifies at moderate xi;
//! 6. as 5, with W cycles and a coarsest grid twice as fine;
//! 7. the default smoother with twice the kernel band (at least 8 cells each side), the stopping
//!    rule as given: at L >= 12 on 16385 points the spike's fine-grid divergence depends on the
//!    band width in no regular way, and this rung rescues some cases that every rung above fails
//!    (M = 100, L = 12; M = 200, L = 16; M = 2000, L = 25; docs/known-limits.md).
//!
//! Where the physics have a piezoviscous spike (alpha_bar >= [`SPIKE_ALPHA_BAR`]) five rungs
//! come between the first and the second, each keeping the stopping rule as given: Newton
//! windows at the outlet spike on levels of 4097 points or more ([`spike`],
//! [`Rung::SpikeNewton`]; only on such grids), the coarse grids holding the spike's nodes fixed
//! ([`Rung::SpikeFrozen`]), Newton windows on every level at a lower threshold
//! ([`Rung::SpikeNewtonAll`]), and the frozen spike and the windows again with V(4, 4) cycles
//! ([`Rung::SpikeFrozenSmooth44`], [`Rung::SpikeNewtonSmooth44`], the latter only on grids of
//! 4097 points or more). At L >= 22 on 16385 points the outlet pressure falls
//! from its spike to nearly zero within a cell and the cycles stall there; which of these
//! settles it varies from case to case, and none changes a converged answer beyond its
//! algebraic error (docs/robustness.md, "Newton windows at the line spike").
//!
//! Where the case has no spike (alpha_bar < [`SPIKE_ALPHA_BAR`]) rungs 5 and 7 come second and
//! third, before rungs 2 to 4: the isoviscous and mildly piezoviscous cases whose first attempt
//! diverges on fine grids (M of about 5 to 200 at L <= 4 on 4097 points) fail rungs 2 to 4 and
//! converge on rung 5, with the same result to the bit as when it came fifth; the thin
//! isoviscous films above M of about 1e4 (M = 23100, L = 0 on 8193 and 16385 points) fail every
//! rung but 7 (docs/method.md, "Fallback ladder").
//!
//! Rungs 2 to 6 of the list above use the tight stopping rule.
//!
//! The best failed attempt (lowest final residual) is returned with its status if none converges.

pub mod jacobian;
pub mod multigrid;
pub mod relax;
pub mod spike;

use crate::discrete::line::domain::DomainParams;
use crate::model::case::{Elasticity, LineCase};
use crate::model::formulas::moes_line_hc;
use crate::solve::ladder::run_rungs;
use crate::solve::line::multigrid::{LineMgParams, LineMultigrid, WarmGuess};
use crate::solve::mixed::{set_mixed_outputs, solve_mixed, MixedState};
use crate::solve::multilevel::Seed;
use crate::solve::params::{ContactParams, Method, Rung, SPIKE_NEWTON};
use crate::solve::single_grid::solve_relax;
use crate::solve::solution::{line_outputs, Profile, Solution};
use crate::solve::SolveInfo;

/// The alpha_bar from which a line solve's ladder has the spike rungs (module doc).
pub const SPIKE_ALPHA_BAR: f64 = 5.0;

/// Parameters of a line solve.
pub type LineSolveParams = ContactParams<DomainParams>;

/// The fallback ladder of a case with a spike (module doc).
const LADDER: [Rung; 12] = [
    Rung::Default,
    Rung::SpikeNewton,
    Rung::SpikeFrozen,
    Rung::SpikeNewtonAll,
    Rung::SpikeFrozenSmooth44,
    Rung::SpikeNewtonSmooth44,
    Rung::Tight,
    Rung::Smooth44,
    Rung::Damped,
    Rung::Distributive,
    Rung::DistributiveWFiner,
    Rung::WideBand,
];

/// The ladder where the case has no spike (alpha_bar < [`SPIKE_ALPHA_BAR`]): the spike rungs
/// dropped, the distributive rung moved up to second and the wide band to third (module doc).
const UNSPIKED_LADDER: [Rung; 7] = [
    Rung::Default,
    Rung::Distributive,
    Rung::WideBand,
    Rung::Tight,
    Rung::Smooth44,
    Rung::Damped,
    Rung::DistributiveWFiner,
];

fn run(
    case: &LineCase,
    p: &LineMgParams,
    keep_fields: bool,
    guess: Option<&WarmGuess>,
    seed: Option<&Seed>,
) -> Solution {
    let mut mg = LineMultigrid::new(case, p);
    mg.seed = seed.cloned();
    if let Some(g) = guess {
        mg.set_guess(g.clone());
    }
    let (info, mixed) = solve_mixed(&mut mg);
    package(case, &mg, info, keep_fields, mixed.as_ref())
}

fn package(
    case: &LineCase,
    mg: &LineMultigrid,
    info: SolveInfo,
    keep_fields: bool,
    mixed: Option<&MixedState>,
) -> Solution {
    let fine = mg.levels.last().expect("levels");
    let ic = mg.domain.centre_index(fine.len() - 1);
    let hs = 8.0 * case.m / std::f64::consts::PI;
    let mut outputs = line_outputs(&fine.x, &fine.p, &fine.film, mg.h0, hs, ic, &info);
    set_mixed_outputs(
        &mut outputs,
        &case.models,
        mixed,
        fine.load(),
        std::f64::consts::PI / 2.0,
    );
    let profile = keep_fields.then(|| Profile {
        x: fine.x.clone(),
        p: fine.p.clone(),
        h: fine.film.iter().map(|v| v * hs).collect(),
        p_asperity: mixed.map(|m| m.asperity_pressure.clone()),
    });
    Solution {
        outputs,
        info,
        profile,
        attempt: 1,
        fields: None,
    }
}

/// The baselines run on one level: the finest grid itself.
fn single_level(p: &LineMgParams) -> LineMgParams {
    LineMgParams {
        coarse_intervals: Some((p.grid.max(17) - 1).next_power_of_two()),
        ..*p
    }
}

/// Solve a line contact. Never panics on a valid case; numerical failure is a status.
pub fn solve_line(case: &LineCase, params: &LineSolveParams) -> Solution {
    solve_line_from(case, params, None)
}

/// The warm-start guess for `case` from a solved neighbour (same models, another M or L;
/// its solution must carry its profile): the neighbour's P(X), and a central film scaled from
/// the neighbour's by the ratio of Moes' formula at the two cases.
pub fn warm_guess(case: &LineCase, neighbour: &LineCase, from: &Solution) -> Option<WarmGuess> {
    let prof = from.profile.as_ref()?;
    let ratio = moes_line_hc(case.m, case.l) / moes_line_hc(neighbour.m, neighbour.l);
    let centre_film = from.outputs.h_c * ratio / (8.0 * case.m / std::f64::consts::PI);
    (centre_film.is_finite() && centre_film > 0.0).then(|| WarmGuess {
        x: prof.x.clone(),
        p: prof.p.clone(),
        centre_film,
    })
}

/// [`solve_line`], every multigrid attempt starting its finest-level cycles from `guess` when
/// one is given (see [`warm_guess`]) instead of the FMG ascent.
pub fn solve_line_from(
    case: &LineCase,
    params: &LineSolveParams,
    guess: Option<&WarmGuess>,
) -> Solution {
    solve_line_with(case, params, guess, None)
}

/// [`solve_line`], the first multigrid attempt starting its FMG ascent from `seed` (a converged
/// solve of the case on a coarser grid of the same domain, [`Seed`]) where one of its levels is
/// the seed's grid; the fallback attempts start cold.
pub fn solve_line_seeded(
    case: &LineCase,
    params: &LineSolveParams,
    seed: Option<&Seed>,
) -> Solution {
    solve_line_with(case, params, None, seed)
}

fn solve_line_with(
    case: &LineCase,
    params: &LineSolveParams,
    guess: Option<&WarmGuess>,
    seed: Option<&Seed>,
) -> Solution {
    match params.method {
        Method::Multigrid => {}
        Method::Newton => {
            let mut p = single_level(&params.mg);
            p.newton_max_iter = p.newton_max_iter.max(200);
            return run(case, &p, params.keep_fields, None, None);
        }
        Method::Relax => {
            let mut mg = LineMultigrid::new(case, &single_level(&params.mg));
            let info = solve_relax(&mut mg, params.relax_max_sweeps, 10);
            return package(case, &mg, info, params.keep_fields, None);
        }
    }
    let mut seed = seed;
    let spiked =
        case.venner().alpha_bar >= SPIKE_ALPHA_BAR && case.models.elasticity == Elasticity::Elastic;
    let ladder: &[Rung] = if spiked { &LADDER } else { &UNSPIKED_LADDER };
    // The Newton windows need a grid of their size.
    let rungs: Vec<Rung> = ladder
        .iter()
        .copied()
        .filter(|r| {
            !matches!(r, Rung::SpikeNewton | Rung::SpikeNewtonSmooth44)
                || params.mg.grid >= SPIKE_NEWTON.min_points
        })
        .collect();
    run_rungs(&rungs, &params.mg, params.fallback, |p| {
        run(case, p, params.keep_fields, guess, seed.take())
    })
}
