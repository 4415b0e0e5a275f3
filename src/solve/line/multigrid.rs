//! Full multigrid (FAS) for the line contact (Venner & Lubrecht).
//!
//! Levels l = 0 (coarsest, n0 intervals) .. finest (n0 2^l intervals) on one domain chosen by
//! [`crate::discrete::line::domain`]. A cycle on level l (l > 0): `pre` relaxations; the residual
//! r = f - L(P), zeroed on the cavitated set P = 0, is restricted by full weighting; P is injected,
//! P^_H = P_h(2I); the coarse right-hand sides are f_H = L_H(P^_H) + R r and
//! g_H = h_H sum P^_H + (g_h - h_h sum P_h); `gamma` coarse cycles (1: V, 2: W); the correction
//! P_H - P^_H is interpolated linearly, added and projected on P >= 0; `post` relaxations.
//! The coarsest level is solved exactly at fixed H0 by semi-smooth Newton (relaxation only if
//! Newton fails); coarse nodes next to the cavitated set are held fixed. FMG starts with a full
//! Newton solve (load equation included) on the coarsest grid, interpolates each level's result
//! (cubic) as the next level's start, and predicts H0 there by extrapolating its last change.
//!
//! Load balance: on each level, cycles at fixed H0 until the load error has settled, then a
//! safeguarded secant step on H0 ([`crate::solve::load_balance::LoadBalance`]); the slope comes from the coarsest Newton and
//! is refined level by level.

use crate::discrete::line::domain::{DomainParams, LineDomain};
use crate::discrete::line::operator::{LineLevel, LinePhysics};
use crate::model::case::LineCase;
use crate::solve::deadline::past;
use crate::solve::line::relax::{relax, LineScratch};
use crate::solve::line::spike::residual_limit;
use crate::solve::multilevel::{grid_level, Contact, DomainRule, Freeze, Multigrid, Seed};
use crate::solve::newton::{load_slope, newton_solve, NewtonOutcome, NewtonParams};
use crate::solve::params::{FinerCoarsest, MgParams};
use std::f64::consts::PI;

/// Multigrid settings of a line solve.
pub type LineMgParams = MgParams<DomainParams>;

/// The line contact's [`crate::solve::relax::RelaxParams::relative_step`].
pub const LINE_RELATIVE_STEP: f64 = 0.25;

/// The line contact's [`MgParams::residual_bound`]: its algebraic error estimate needs a
/// tenth of the point contact's residual bound ([`crate::solve::fmg_fast::RESIDUAL_BOUND`]
/// has the measurement).
pub const LINE_RESIDUAL_BOUND: f64 = 0.1;

impl Default for MgParams<DomainParams> {
    /// The shared defaults with V(1, 1) cycles (on the line one pre-relaxation does what two
    /// did, for a third less work), a relative step limit of 1/4
    /// ([`crate::solve::relax::RelaxParams::relative_step`]) and the line's residual bound
    /// ([`LINE_RESIDUAL_BOUND`]).
    fn default() -> Self {
        let mut p = MgParams::defaults(DomainParams::default(), 2049, 60, 5e-7, 1e-6);
        p.pre = 1;
        p.relax.relative_step = LINE_RELATIVE_STEP;
        p.residual_bound = LINE_RESIDUAL_BOUND;
        p
    }
}

impl DomainRule for LineDomain {
    type Params = DomainParams;
}

impl FinerCoarsest for DomainParams {
    /// Halve the coarsest spacing's limits.
    fn finer_coarsest(&mut self) {
        self.coarse_h_max *= 0.5;
        self.coarse_lh *= 0.5;
    }
}

grid_level!(LineLevel, LinePhysics);

/// A solved neighbour's pressure profile (Hertzian X, P) and the central film (Hertzian units)
/// this case is expected to have, to start the finest-level cycles from.
#[derive(Clone, Debug, PartialEq)]
pub struct WarmGuess {
    /// Node coordinates X of the neighbour's profile.
    pub x: Vec<f64>,
    /// The neighbour's pressure P at those nodes.
    pub p: Vec<f64>,
    /// The central film this case is expected to have (Hertzian units).
    pub centre_film: f64,
}

impl WarmGuess {
    /// P at `x`, linear between the samples, zero outside them.
    fn p_at(&self, x: f64) -> f64 {
        let (xs, ps) = (&self.x, &self.p);
        if xs.len() < 2 || x <= xs[0] || x >= xs[xs.len() - 1] {
            return 0.0;
        }
        let j = xs.partition_point(|&v| v <= x).clamp(1, xs.len() - 1);
        let t = (x - xs[j - 1]) / (xs[j] - xs[j - 1]);
        ((1.0 - t) * ps[j - 1] + t * ps[j]).max(0.0)
    }
}

impl Multigrid<LineContact> {
    /// Build the levels for a case. The finest level has at least `params.grid` points.
    pub fn new(case: &LineCase, params: &LineMgParams) -> Self {
        let phys = LinePhysics {
            second_order: params.second_order,
            ..LinePhysics::from_case(case)
        };
        let max_int = (params.grid.max(17) - 1).next_power_of_two();
        let rigid = case.models.elasticity == crate::model::case::Elasticity::Rigid;
        let mut domain = LineDomain::for_case(case.m, case.l, rigid, &params.domain, max_int);
        if let Some(n0) = params.coarse_intervals {
            domain = LineDomain::aligned(
                domain.x_in,
                domain.x_out,
                n0.min(max_int),
                domain.h_estimate,
            );
        }
        let mut fine = domain.n0;
        while fine + 1 < params.grid {
            fine *= 2;
        }
        let mut levels = vec![];
        let mut n = domain.n0;
        while n <= fine {
            let mut lv = LineLevel::new(domain.x_in, domain.x_out, n);
            lv.direct_deformation = params.direct_deformation;
            levels.push(lv);
            n *= 2;
        }
        Multigrid::from_levels(
            phys,
            domain,
            levels,
            params,
            LineExtra {
                fine_intervals: fine,
                guess: None,
                scratch: LineScratch::default(),
            },
        )
    }

    /// Start the next [`LineMultigrid::solve`] from `guess` on the finest level instead of
    /// the FMG ascent.
    pub fn set_guess(&mut self, guess: WarmGuess) {
        self.extra.guess = Some(guess);
    }

    /// H_Moes / H_Venner.
    pub fn h_scale(&self) -> f64 {
        8.0 * PI.recip() * (3.0 * PI * PI / (8.0 * self.phys.lambda)).sqrt()
    }
}

/// The line contact's part of [`Multigrid`] (see [`crate::solve::multilevel::Contact`]).
pub struct LineContact;

/// The state of a line multigrid solve.
pub type LineMultigrid = Multigrid<LineContact>;

/// What a line solve keeps besides the shared state.
pub struct LineExtra {
    /// Intervals of the finest level (work units are sweeps of it).
    fine_intervals: usize,
    /// A warm-start guess for the finest level ([`LineMultigrid::set_guess`]).
    guess: Option<WarmGuess>,
    /// The smoother's work buffers, shared by all levels.
    scratch: LineScratch,
}

impl Contact for LineContact {
    type Level = LineLevel;
    type Domain = LineDomain;
    type Extra = LineExtra;
    fn sweep(mg: &mut LineMultigrid, l: usize) -> f64 {
        let cost = (mg.levels[l].len() - 1) as f64 / mg.extra.fine_intervals as f64;
        let scratch = &mut mg.extra.scratch;
        relax(
            &mut mg.levels[l],
            &mg.phys,
            mg.h0,
            &mg.params.relax,
            scratch,
        );
        cost
    }

    /// Each Newton iteration counts as n0 relaxations of level 0.
    fn newton_cost(mg: &LineMultigrid, iterations: usize) -> f64 {
        (iterations * mg.levels[0].len()) as f64 / mg.extra.fine_intervals as f64
    }

    /// Injection of P, full weighting of the residual.
    fn restrict(
        coarse: &mut LineLevel,
        fine: &LineLevel,
        r: &[f64],
        phys: &LinePhysics,
        h0: f64,
        freeze: Freeze,
    ) {
        let nc = coarse.len();
        for i in 0..nc {
            coarse.p[i] = fine.p[2 * i];
        }
        coarse.update_film(phys, h0);
        coarse.f[0] = 0.0;
        coarse.f[nc - 1] = 0.0;
        // A pressurised fine node with |r| above this (the outlet spike) freezes its coarse
        // neighbours too.
        let spike = freeze
            .spike
            .map_or(f64::INFINITY, |f| residual_limit(&fine.p, r, f));
        for i in 1..nc - 1 {
            coarse.frozen[i] = freeze.band
                && (2 * i - 1..=2 * i + 1)
                    .any(|k| fine.p[k] <= 0.0 || fine.frozen[k] || r[k].abs() > spike);
            let rr = 0.25 * r[2 * i - 1] + 0.5 * r[2 * i] + 0.25 * r[2 * i + 1];
            coarse.f[i] = coarse.reynolds(phys, i) + rr;
        }
    }

    /// Linear interpolation of the correction.
    fn correct(coarse: &LineLevel, ph: &[f64], fine: &mut LineLevel, phys: &LinePhysics, h0: f64) {
        let nc = coarse.len();
        for i in 0..nc {
            let e = coarse.p[i] - ph[i];
            fine.p[2 * i] += e;
            if i + 1 < nc {
                let e1 = coarse.p[i + 1] - ph[i + 1];
                fine.p[2 * i + 1] += 0.5 * (e + e1);
            }
        }
        let nf = fine.len();
        fine.p[0] = 0.0;
        fine.p[nf - 1] = 0.0;
        for p in fine.p.iter_mut() {
            *p = p.max(0.0);
        }
        fine.update_film(phys, h0);
    }

    fn centre_index(mg: &LineMultigrid, l: usize) -> usize {
        mg.domain.centre_index(mg.levels[l].len() - 1)
    }
    fn h_scale(mg: &LineMultigrid) -> f64 {
        mg.h_scale()
    }
    fn h_estimate(mg: &LineMultigrid) -> f64 {
        mg.domain.h_estimate
    }
    /// Start on the coarsest level: the Hertz pressure for elastic surfaces; for rigid ones a
    /// parabola over [-2.5, 0.5] l_h (the Martin pressure's extent, l_h = sqrt(2 H_e)); in the dry
    /// limit a wider parabola than Hertz, so that the solver has to find Hertz. All carry the load
    /// pi/2. H0 is chosen so that the central film equals the estimate H_e.
    fn initialise(mg: &mut LineMultigrid) {
        let dry = mg.phys.dry;
        let rigid = !mg.phys.elastic;
        let h_e = mg.domain.h_estimate;
        let half = 1.5 * (2.0 * h_e).sqrt();
        let lv = &mut mg.levels[0];
        for i in 0..lv.len() {
            let x = lv.x[i];
            lv.p[i] = if dry {
                PI / 4.0 * (1.0 - x * x / 2.25).max(0.0)
            } else if rigid {
                let s = (x + half / 1.5) / half;
                3.0 * PI / (8.0 * half) * (1.0 - s * s).max(0.0)
            } else {
                (1.0 - x * x).max(0.0).sqrt()
            };
        }
        let n = lv.len();
        lv.p[0] = 0.0;
        lv.p[n - 1] = 0.0;
        lv.update_film(&mg.phys, 0.0);
        let ic = mg.domain.centre_index(n - 1);
        mg.h0 = h_e - lv.film[ic];
        lv.update_film(&mg.phys, mg.h0);
    }
    /// Full Newton (with the load equation) on the coarsest level from the initial guess, then the
    /// slope dG/dH0 from a second fixed-H0 solve at a perturbed H0.
    fn start_coarse(mg: &mut LineMultigrid, with_slope: bool) -> NewtonOutcome {
        let np = NewtonParams::coarsest_start(
            mg.params.newton_max_iter,
            mg.levels.len(),
            mg.params.deadline,
        );
        let lv = &mut mg.levels[0];
        lv.f.fill(0.0);
        lv.g = PI / 2.0 * mg.phys.fluid_share;
        let out = newton_solve(lv, &mg.phys, &mut mg.h0, &np);
        let first = out;
        mg.work_units += (out.iterations * lv.len()) as f64 / mg.extra.fine_intervals as f64;
        // (Not after the deadline: the solve stops at its first cycle anyway.)
        if !(out.converged || out.residual < 1e-6 * out.unit || past(mg.params.deadline)) {
            mg.relaxed_coarse_balance(20 * mg.params.coarse_sweeps);
        }
        let lv = &mut mg.levels[0];
        if !with_slope {
            return out;
        }
        let ic = mg.domain.centre_index(lv.len() - 1);
        let dh = 1e-3 * lv.film[ic].abs().max(1e-3 * mg.domain.h_estimate);
        let fallback = -lv.g / mg.domain.h_estimate;
        mg.load_slope = load_slope(lv, &mg.phys, mg.h0, dh, fallback, 0.0).0;
        first
    }
    /// Cubic interpolation of level l-1's pressure as the start on level l (FMG).
    fn fmg_interpolate(mg: &mut LineMultigrid, l: usize) {
        let (lo, hi) = mg.levels.split_at_mut(l);
        let (coarse, fine) = (&lo[l - 1], &mut hi[0]);
        let nc = coarse.len();
        let pc = &coarse.p;
        for i in 0..nc {
            fine.p[2 * i] = pc[i];
            if i + 1 < nc {
                fine.p[2 * i + 1] = if i >= 1 && i + 2 < nc {
                    (-pc[i - 1] + 9.0 * pc[i] + 9.0 * pc[i + 1] - pc[i + 2]) / 16.0
                } else {
                    0.5 * (pc[i] + pc[i + 1])
                };
            }
        }
        for p in fine.p.iter_mut() {
            *p = p.max(0.0);
        }
        fine.f.fill(0.0);
        fine.frozen.fill(false);
        fine.g = PI / 2.0 * mg.phys.fluid_share;
        fine.update_film(&mg.phys, mg.h0);
    }
    /// Put the guess on level `l`: P interpolated onto its grid, H0 so that the central film is
    /// the guess's.
    fn install_guess(mg: &mut LineMultigrid, l: usize) -> bool {
        let Some(g) = mg.extra.guess.take() else {
            return false;
        };
        let lv = &mut mg.levels[l];
        let n = lv.len();
        for i in 0..n {
            lv.p[i] = if i == 0 || i + 1 == n {
                0.0
            } else {
                g.p_at(lv.x[i])
            };
        }
        lv.f.fill(0.0);
        lv.frozen.fill(false);
        lv.g = PI / 2.0 * mg.phys.fluid_share;
        lv.update_film(&mg.phys, 0.0);
        mg.h0 = g.centre_film - lv.film[mg.domain.centre_index(n - 1)];
        lv.update_film(&mg.phys, mg.h0);
        true
    }

    const COARSE_BUDGET_GROWTH: usize = 1;
    const KEEP_CAVITATED: bool = false;

    fn seed_matches(mg: &LineMultigrid, l: usize, seed: &Seed) -> bool {
        seed.matches(&mg.levels[l].x, &[])
    }
}
