//! The point-contact solve as a library call: case + parameters in, outputs + info (+ fields) out.
//!
//! Outputs use the line contact's names (PHYSICS.md section 7), evaluated on the finest grid:
//! `H_c` = H(0, 0); `H_c_pmax` the film at the pressure maximum on the centre line Y = 0; `H_min`
//! with `X_min`, `Y_min` (parabolic refinement in each direction); `P_max`; `spike` on the centre
//! line; `H0`; `f` the rolling traction integral (H/2) dP/dX dX dY over the load integral P dX dY
//! (Hertzian units); `load_error` against 2 pi k/3; plus `D` and `k`.
//!
//! With `fallback` on (the default) a solve that does not converge is retried, where the physics
//! have a band along the cavitation boundary ([`multigrid::freezes`]), with the other choice of
//! it (the first attempt freezes it from L = [`multigrid::FREEZE_MIN_L`] on,
//! [`multigrid::first_freezes`]); then with the line relaxation less damped
//! ([`crate::solve::params::LIGHT_DAMPING`] instead of 0.5), then with W cycles (the three with the stopping rule as given), then the line solver's
//! ladder: tight convergence, line under-relaxation 0.3, then distributive relaxation
//! everywhere, then that with W cycles. The reason names the attempt kept; the best failed
//! attempt is returned with its status if none converges. A thin isoviscous film without a seed
//! starts its FMG ascent from the Hertz pressure on the first level that resolves it
//! ([`start`]).

pub mod jacobian;
pub mod multigrid;
pub mod relax;
pub mod start;

use crate::discrete::point::domain::PointDomainParams;
use crate::discrete::point::domain::BIAS_CAUTION;
use crate::discrete::point::operator::PointPhysics;
use crate::model::case::PointCase;
use crate::solve::awake::KeepAwake;
use crate::solve::ladder::run_rungs;
use crate::solve::mixed::{set_mixed_outputs, solve_mixed, MixedState};
use crate::solve::multilevel::Seed;
use crate::solve::params::{ContactParams, Method, Rung};
pub use crate::solve::point::multigrid::PointMgParams;
use crate::solve::point::multigrid::PointMultigrid;
use crate::solve::single_grid::solve_relax;
use crate::solve::solution::grid_level;
pub use crate::solve::solution::PointFields;
use crate::solve::solution::{line_outputs, parabola_vertex, CentreLine, Outputs, Solution};
use crate::solve::SolveInfo;

/// Parameters of a point solve.
pub type PointSolveParams = ContactParams<PointDomainParams>;

/// The outputs of a finished solve (see the module docs).
pub fn point_outputs(mg: &PointMultigrid, info: &SolveInfo) -> Outputs {
    let top = mg.levels.len() - 1;
    let lv = &mg.levels[top];
    let hs = mg.phys.h_scale;
    let (nx, ny) = (lv.nx, lv.ny);
    let (ic, jc) = mg.domain.centre(nx - 1);
    let row = jc * nx..(jc + 1) * nx;
    let mut out = line_outputs(
        &lv.x,
        &lv.p[row.clone()],
        &lv.film[row],
        mg.h0,
        hs,
        ic,
        info,
    );
    // The centre row's minimum (line_outputs'), then the global minimum film over the
    // interior, refined by a parabola in each direction.
    out.centre_line = Some(CentreLine {
        h_min: out.h_min,
        x_min: out.x_min,
        h_min_err: None,
    });
    // Global minimum film over the interior, refined by a parabola in each direction.
    let mut cmin = lv.at(1, 1);
    for j in 1..ny - 1 {
        for i in 1..nx - 1 {
            let c = lv.at(i, j);
            if lv.film[c] < lv.film[cmin] {
                cmin = c;
            }
        }
    }
    let (i, j) = (cmin % nx, cmin / nx);
    let f = &lv.film;
    let (tx, vx) = parabola_vertex(f[cmin - 1], f[cmin], f[cmin + 1]);
    let (ty, vy) = parabola_vertex(f[cmin - nx], f[cmin], f[cmin + nx]);
    out.h_min = (vx + vy - f[cmin]) * hs;
    out.x_min = lv.x[i] + tx * lv.hx;
    out.y_min = Some(lv.y[j] + ty * lv.hy);
    let (mut pmax, mut cmax) = (0.0, 0);
    for (c, &p) in lv.p.iter().enumerate() {
        if p > pmax {
            pmax = p;
            cmax = c;
        }
    }
    if cmax % nx > 0 && cmax % nx + 1 < nx && cmax / nx > 0 && cmax / nx + 1 < ny {
        let p = &lv.p;
        let (_, px) = parabola_vertex(p[cmax - 1], p[cmax], p[cmax + 1]);
        let (_, py) = parabola_vertex(p[cmax - nx], p[cmax], p[cmax + nx]);
        pmax = px + py - p[cmax];
    }
    out.p_max = pmax;
    let load = lv.load();
    let mut traction = 0.0;
    for j in 0..ny {
        for i in 0..nx - 1 {
            let c = lv.at(i, j);
            traction += 0.25 * (f[c] + f[c + 1]) * (lv.p[c + 1] - lv.p[c]) * lv.hy;
        }
    }
    out.f = traction / load;
    out.load_error = (load - mg.phys.load) / mg.phys.load;
    out.d = Some(mg.phys.d);
    out.level = Some(grid_level(info.grid, 16));
    out.k = Some(mg.phys.k);
    let bias = mg.domain.bias();
    if bias >= BIAS_CAUTION {
        out.reason.push_str(&format!(
            "; caution: rigid-like case (w = {:.2}), H is biased low by the truncated domain \
             (doubling it raises H by about {:.0} %)",
            mg.domain.rigid_weight,
            100.0 * bias
        ));
    }
    out
}

fn run(case: &PointCase, p: &PointMgParams, keep_fields: bool, seed: Option<&Seed>) -> Solution {
    // Parallel rows fork and join the pool many times per work unit: its workers stay awake.
    let _awake = p.parallel.then(KeepAwake::start);
    let mut mg = PointMultigrid::new(case, p);
    mg.seed = seed.cloned().or_else(|| start::hertz_start(&mut mg));
    let (info, mixed) = solve_mixed(&mut mg);
    package(case, &mg, info, keep_fields, mixed.as_ref())
}

fn package(
    case: &PointCase,
    mg: &PointMultigrid,
    info: SolveInfo,
    keep_fields: bool,
    mixed: Option<&MixedState>,
) -> Solution {
    let mut outputs = point_outputs(mg, &info);
    let fine = mg.levels.last().expect("levels");
    set_mixed_outputs(&mut outputs, &case.models, mixed, fine.load(), mg.phys.load);
    let fields = keep_fields.then(|| {
        let lv = mg.levels.last().expect("levels");
        PointFields {
            x: lv.x.clone(),
            y: lv.y.clone(),
            p: lv.p.clone(),
            h: lv.film.iter().map(|v| v * mg.phys.h_scale).collect(),
            p_asperity: mixed.map(|m| m.asperity_pressure.clone()),
        }
    });
    Solution {
        outputs,
        info,
        fields,
        attempt: 1,
        profile: None,
    }
}

/// The fallback ladder (module doc).
const LADDER: [Rung; 9] = [
    Rung::Default,
    Rung::Unfrozen,
    Rung::Frozen,
    Rung::LightDamping,
    Rung::WCycles,
    Rung::Tight,
    Rung::Damped,
    Rung::Distributive,
    Rung::DistributiveW,
];

/// The baselines run on one level: the finest grid itself.
fn single_level(p: &PointMgParams) -> PointMgParams {
    let mut s = *p;
    s.domain.n0 = (p.grid.max(5) - 1).next_power_of_two();
    s
}

/// Solve a point contact. Never panics on a valid case; numerical failure is a status.
pub fn solve_point(case: &PointCase, params: &PointSolveParams) -> Solution {
    solve_point_seeded(case, params, None)
}

/// [`solve_point`], the first multigrid attempt starting its FMG ascent from `seed` (a converged
/// solve of the case on a coarser grid of the same domain, [`Seed`]) where one of its levels is
/// the seed's grid; the fallback attempts start cold.
pub fn solve_point_seeded(
    case: &PointCase,
    params: &PointSolveParams,
    seed: Option<&Seed>,
) -> Solution {
    match params.method {
        Method::Multigrid => {}
        Method::Newton => {
            let mut p = single_level(&params.mg);
            p.newton_max_iter = p.newton_max_iter.max(200);
            return run(case, &p, params.keep_fields, None);
        }
        Method::Relax => {
            let mut mg = PointMultigrid::new(case, &single_level(&params.mg));
            let info = solve_relax(&mut mg, params.relax_max_sweeps, 10);
            return package(case, &mg, info, params.keep_fields, None);
        }
    }
    let mut seed = seed;
    // Where the physics have no band (alpha_bar < 5) the ladder has no band rungs; where they
    // have one, the first attempt freezes it from L = FREEZE_MIN_L on, and of the rungs
    // `Unfrozen` and `Frozen` the one that repeats the first attempt is skipped by `run_rungs`.
    let mut mg = params.mg;
    let band = multigrid::freezes(&PointPhysics::from_case(case));
    mg.freeze_band = Some(band && mg.freeze_band.unwrap_or(multigrid::first_freezes(case)));
    let rungs: Vec<Rung> = LADDER
        .into_iter()
        .filter(|r| band || !matches!(r, Rung::Unfrozen | Rung::Frozen))
        .collect();
    run_rungs(&rungs, &mg, params.fallback, |p| {
        run(case, p, params.keep_fields, seed.take())
    })
}
