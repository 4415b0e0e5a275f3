//! The line-contact solve as a library call: case + parameters in, outputs + info (+ profile) out.
//!
//! With `fallback` on (the default) a solve that does not converge is retried with more
//! conservative smoother settings, in this order, and the reason names the attempt that was kept:
//!
//! 1. the given parameters (line relaxation, distribution where xi < 100);
//! 2. the same with more smoothing, V(4, 4) cycles (at L = 20 on 4097 points the V(2, 1) cycles
//!    of M = 103 and 326 wandered for 60 cycles with residuals of order 1 while V(4, 4) converged
//!    in 570 and 220 work units, to 0.1 % of the 2049-point film);
//! 3. the given cycles with the line under-relaxation lowered to 0.3 (steep piezoviscous spikes
//!    at L = 20 on fine grids);
//! 4. distributive line relaxation everywhere (xi threshold infinite): damps the smooth modes
//!    that the truncated kernel tail of the non-distributed rows amplifies at moderate xi;
//! 5. as 4, with W cycles and a coarsest grid twice as fine.
//!
//! The best failed attempt (lowest final residual) is returned with its status if none converges.

pub mod jacobian;
pub mod multigrid;
pub mod relax;

use crate::model::case::LineCase;
use crate::model::formulas::moes_line_hc;
use crate::solve::ladder::run_ladder;
use crate::solve::line::multigrid::{CycleType, LineMgParams, LineMultigrid, WarmGuess};
use crate::solve::single_grid::solve_relax;
use crate::solve::solution::{line_outputs, Profile, Solution};
use crate::solve::SolveInfo;

/// Which solver.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
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
    pub fn as_str(&self) -> &'static str {
        match self {
            Method::Multigrid => "multigrid",
            Method::Newton => "newton",
            Method::Relax => "relax",
        }
    }
}

/// Parameters of a line solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineSolveParams {
    pub method: Method,
    /// Sweeps allowed to the single-grid relaxation baseline.
    pub relax_max_sweeps: usize,
    pub mg: LineMgParams,
    /// Retry with conservative settings when the first attempt fails.
    pub fallback: bool,
    /// Return the P(X), H(X) profile.
    pub keep_profile: bool,
}

impl Default for LineSolveParams {
    fn default() -> Self {
        LineSolveParams {
            method: Method::Multigrid,
            relax_max_sweeps: 20_000,
            mg: LineMgParams::default(),
            fallback: true,
            keep_profile: false,
        }
    }
}

/// The fallback ladder (module doc), each attempt with the name its reason carries.
fn attempts(p: &LineMgParams) -> Vec<(&'static str, LineMgParams)> {
    let mut smooth = *p;
    smooth.pre = p.pre.max(4);
    smooth.post = p.post.max(4);
    let mut damped = *p;
    damped.relax.omega_line = (0.6 * p.relax.omega_line).min(0.3);
    let mut a2 = *p;
    a2.relax.xi_threshold = f64::INFINITY;
    let mut a3 = a2;
    a3.cycle = CycleType::W;
    a3.domain.coarse_h_max *= 0.5;
    a3.domain.coarse_lh *= 0.5;
    vec![
        ("default smoother", *p),
        ("default smoother, V(4, 4) cycles", smooth),
        ("default smoother, under-relaxation 0.3", damped),
        ("distributive line relaxation everywhere", a2),
        ("distributive relaxation, W cycles, finer coarsest grid", a3),
    ]
}

fn run(
    case: &LineCase,
    p: &LineMgParams,
    keep_profile: bool,
    guess: Option<&WarmGuess>,
) -> Solution {
    let mut mg = LineMultigrid::new(case, p);
    if let Some(g) = guess {
        mg.set_guess(g.clone());
    }
    let info = mg.solve();
    package(case, &mg, info, keep_profile)
}

fn package(case: &LineCase, mg: &LineMultigrid, info: SolveInfo, keep_profile: bool) -> Solution {
    let fine = mg.levels.last().expect("levels");
    let ic = mg.domain.centre_index(fine.len() - 1);
    let hs = 8.0 * case.m / std::f64::consts::PI;
    let outputs = line_outputs(&fine.x, &fine.p, &fine.film, mg.h0, hs, ic, &info);
    let profile = keep_profile.then(|| Profile {
        x: fine.x.clone(),
        p: fine.p.clone(),
        h: fine.film.iter().map(|v| v * hs).collect(),
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
    match params.method {
        Method::Multigrid => {}
        Method::Newton => {
            let mut p = single_level(&params.mg);
            p.newton_max_iter = p.newton_max_iter.max(200);
            return run(case, &p, params.keep_profile, None);
        }
        Method::Relax => {
            let mut mg = LineMultigrid::new(case, &single_level(&params.mg));
            let info = solve_relax(&mut mg, params.relax_max_sweeps, 10);
            return package(case, &mg, info, params.keep_profile);
        }
    }
    let mut list = attempts(&params.mg);
    if !params.fallback {
        list.truncate(1);
    }
    let names: Vec<&str> = list.iter().map(|a| a.0).collect();
    run_ladder(&names, |k| {
        run(case, &list[k].1, params.keep_profile, guess)
    })
}
