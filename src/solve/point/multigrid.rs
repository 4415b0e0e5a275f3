//! Full multigrid (FAS) for the point contact: the line solver's design in 2D.
//!
//! Levels l = 0 (coarsest, n0 x n0 intervals) .. finest (n0 2^l per direction) on one domain
//! ([`crate::discrete::point::domain`]). A cycle on level l > 0: `pre` x-line relaxations
//! ([`crate::solve::point::relax`]); the residual is restricted by 9-point full weighting, at a
//! coarse node whose fine node is pressurised over the pressurised fine nodes only, at a cavitated
//! one with the complementarity margin of the cavitated fine nodes included; P is injected; the
//! coarse right-hand sides are f_H = L_H(P^_H) + R r and g_H = hx hy sum P^_H + (g_h - load_h);
//! `gamma` coarse cycles; the correction is interpolated bilinearly, added and projected on
//! P >= 0; `post` relaxations. With that restriction a converged fine solution is a fixed point of
//! the cycle (R r = 0 at pressurised coarse nodes, R r < 0 keeps the cavitated ones at P = 0), so
//! below alpha_bar = [`FREEZE_ALPHA_BAR`] no coarse node is frozen and the coarse grids correct
//! the outlet region up to the cavitation boundary; from it on (a pressure spike next to the
//! cavitation boundary, under-resolved on the coarse grids) coarse nodes whose fine 3 x 3
//! neighbourhood touches the cavitated set or a frozen node are frozen (docs/method.md, "The free
//! boundary on the coarse grids"), unless [`MgParams::freeze_band`] is off (the fallback
//! ladder's unfrozen rung).
//! The coarsest level is solved at fixed H0 by semi-smooth Newton on its ~(n0-1)^2 unknowns. FMG
//! (the driver in [`crate::solve::fmg`]) starts from the Hertz pressure with a full Newton solve
//! and interpolates each level's result to the next (cubic along each direction).

use crate::discrete::point::domain::PointDomain;
use crate::discrete::point::domain::PointDomainParams;
use crate::discrete::point::operator::{PointLevel, PointPhysics};
use crate::discrete::rows::for_each_row;
use crate::model::case::{Elasticity, PointCase};
use crate::solve::deadline::past;
use crate::solve::multilevel::{grid_level, Contact, DomainRule, Freeze, Multigrid, Seed};
use crate::solve::newton::{load_slope, newton_solve, NewtonOutcome, NewtonParams};
use crate::solve::params::{Converge, FinerCoarsest, MgParams};
use crate::solve::point::relax::{point_line_sweep, PointScratch};

/// The far field's reference points lie at least 1/FAR_FIELD_MAX_N0 of the domain inside.
const FAR_FIELD_MAX_N0: usize = 16;

/// With [`MgParams::parallel`], the levels of at least this many rows per direction relax
/// blocks of rows at once and compute their films and residuals on the rayon pool.
pub const PARALLEL_MIN_ROWS: usize = 65;

/// The point contact's [`MgParams::coarse_rel_tol`]: a V cycle contracts the finer residual by
/// 0.1-0.9, so solving the coarsest problem further than this only polishes a correction that
/// the next cycle revises (the coarse correction's own error is then at most a tenth of the
/// cycle's best contraction), provided H0 is solved further ([`POINT_COARSE_LOAD_REL_TOL`]).
/// Chosen against 1e-3, 3e-3, 5e-3 and 1e-1 on the benchmark cases and the nightly point
/// sweep (docs/performance.md, "The point cycles' coarsest Newton solve stopped at a relative
/// reduction" and "The coarsest solve's load equation").
pub const POINT_COARSE_REL_TOL: f64 = 1e-2;

/// The point contact's [`MgParams::coarse_load_rel_tol`]: the coarsest solve stops at
/// [`POINT_COARSE_REL_TOL`] only once the load equation's part of its residual has fallen by
/// this fraction of the norm's value at the start. Without it, low-M films (which follow H0
/// closely) took up to 33 % more work units on the nightly point sweep, its total 3.3 % more
/// than with 1e-3 throughout. One Newton iteration typically leaves the load part at 1e-3 to
/// 2e-3 of the starting norm, so 1e-3 often asks for a second iteration that 2e-3 does not:
/// the nightly sweep's total is the same (-0.03 %) with 2e-3, the benchmark grids cheaper; from
/// 3e-3 on a rigid-like case (M = 2.68, L = 20, D = 0.1) needs its second attempt
/// (docs/performance.md, "The coarsest solve's load equation").
pub const POINT_COARSE_LOAD_REL_TOL: f64 = 2e-3;

/// Under fast convergence, the coarsest level's first solve (from the Hertzian or rigid
/// guess) of a multigrid of two or more levels stops once its residual has fallen by this
/// (or at the absolute tolerance): the first coarse cycles solve that level again with the
/// finer levels' corrections, so a start polished further changes no answer (the same films
/// to 9 digits on the benchmark cases, docs/performance.md).
pub const POINT_START_REL_TOL: f64 = 1e-6;

/// Under fast convergence, the load slope dG/dH0 of the start (the load balance's fallback,
/// [`crate::solve::newton::load_slope`]) is solved at H0 + dh until its residual has fallen by
/// this: a finite-difference slope needs no more than three digits.
pub const POINT_SLOPE_REL_TOL: f64 = 1e-3;

/// Multigrid settings of a point solve.
pub type PointMgParams = MgParams<PointDomainParams>;

impl Default for MgParams<PointDomainParams> {
    /// The shared defaults with the finest cycles accelerated where alpha_bar < 5
    /// ([`MgParams::anderson`]) and the cycles' coarsest solves stopped at a reduction of
    /// [`POINT_COARSE_REL_TOL`] ([`POINT_COARSE_LOAD_REL_TOL`] for the load equation).
    fn default() -> Self {
        let mut p = MgParams::defaults(PointDomainParams::default(), 129, 40, 1e-6, 1e-5);
        p.anderson = true;
        p.coarse_rel_tol = POINT_COARSE_REL_TOL;
        p.coarse_load_rel_tol = POINT_COARSE_LOAD_REL_TOL;
        p
    }
}

impl FinerCoarsest for PointDomainParams {
    /// The point coarsest grid has a fixed interval count ([`PointDomainParams::n0`]) and no
    /// spacing limit: nothing to refine (no point rung asks for it).
    fn finer_coarsest(&mut self) {}
}

grid_level!(PointLevel, PointPhysics);

impl Multigrid<PointContact> {
    /// Build the levels for a case; the finest level has at least `params.grid` points per direction.
    pub fn new(case: &PointCase, params: &PointMgParams) -> Self {
        let mut phys = PointPhysics::from_case(case);
        phys.second_order = params.second_order;
        Self::with_physics(case, phys, params)
    }

    /// Levels for a case with the given physics (e.g. a dry contact).
    pub fn with_physics(case: &PointCase, phys: PointPhysics, params: &PointMgParams) -> Self {
        let rigid = case.models.elasticity == Elasticity::Rigid;
        let domain = PointDomain::for_case(
            case.m,
            case.l,
            case.d,
            phys.k,
            phys.h_scale,
            rigid,
            &params.domain,
        );
        let mut levels = vec![];
        // The far field's reference points one coarsest spacing inside, at most a sixteenth of
        // the domain: the single-level baselines (n0 = the finest grid's intervals) then solve
        // the discrete problem of the default hierarchy (n0 = 16).
        let far_spacing = params.domain.far_field.then(|| {
            let n_far = domain.n0.min(FAR_FIELD_MAX_N0) as f64;
            (
                (domain.x_out - domain.x_in) / n_far,
                2.0 * domain.y_half / n_far,
            )
        });
        let mut n = domain.n0;
        loop {
            // Parallel rows only where a level has enough rows to share.
            let parallel = params.parallel && n + 1 >= PARALLEL_MIN_ROWS;
            let extent = (domain.x_in, domain.x_out, domain.y_half);
            let mut lv = PointLevel::new_on(&phys, extent, n, n, parallel);
            lv.parallel_jacobian = params.parallel;
            if let Some(coarse) = far_spacing {
                // The load's deformation far from the contact: coef W / R (none when rigid).
                let deform = if rigid { 0.0 } else { phys.coef * phys.load };
                lv = lv.with_far_field(phys.d, coarse, deform);
            }
            lv.direct_deformation = params.direct_deformation;
            levels.push(lv);
            if n + 1 >= params.grid {
                break;
            }
            n *= 2;
        }
        let extra = PointExtra {
            fine_cells: (n * n) as f64,
            scratch: PointScratch::default(),
            first_freezes: first_freezes(case),
        };
        Multigrid::from_levels(phys, domain, levels, params, extra)
    }

    /// Index of X = Y = 0 on level l.
    pub fn centre_index(&self, l: usize) -> usize {
        let lv = &self.levels[l];
        let (i, j) = self.domain.centre(lv.nx - 1);
        lv.at(i, j)
    }
}

/// Cubic interpolation at the midpoint between v1 and v2 (linear next to the ends).
#[inline]
fn mid(v: &[f64], i: usize) -> f64 {
    if i >= 1 && i + 2 < v.len() {
        (-v[i - 1] + 9.0 * v[i] + 9.0 * v[i + 1] - v[i + 2]) / 16.0
    } else {
        0.5 * (v[i] + v[i + 1])
    }
}

impl Multigrid<PointContact> {}

/// The point contact's part of [`Multigrid`] (see [`crate::solve::multilevel::Contact`]).
pub struct PointContact;

/// The state of a point multigrid solve.
pub type PointMultigrid = Multigrid<PointContact>;

/// The dry (Hertzian) pressure sqrt(1 - X^2 - (Y/k)^2) at (X, Y), 0 outside the contact ellipse
/// (Hertzian units, peak 1, load 2 pi k / 3): the start of the FMG ascent on the coarsest level
/// and of [`crate::solve::point::start::hertz_start`].
pub fn hertz_pressure(x: f64, y: f64, k: f64) -> f64 {
    (1.0 - x.powi(2) - (y / k).powi(2)).max(0.0).sqrt()
}

/// What a point solve keeps besides the shared state.
pub struct PointExtra {
    /// Cells of the finest level (work units are sweeps of it).
    fine_cells: f64,
    /// The smoother's work buffers, shared by all levels.
    scratch: PointScratch,
    /// Whether the band is frozen where the parameters leave it to the case
    /// ([`first_freezes`]; [`crate::solve::params::MgParams::freeze_band`] None).
    first_freezes: bool,
}

/// The dimensionless pressure-viscosity coefficient alpha p_h from which a pressure spike sits
/// next to the cavitation boundary: coarse nodes next to the cavitated set may be frozen there
/// (module docs), and the fast rule's algebraic error estimate takes the residual bound
/// ([`crate::solve::multilevel::Contact::spiked_boundary`]). Below it the consistent
/// restriction alone converges faster (M = 20, L = 0, D = 1: 11 instead of 48 work units on
/// 513^2, 23 instead of 52 on 1025^2) and the cycles' changes measure the algebraic error.
/// Measured: docs/performance.md, "The free boundary on the point coarse grids".
pub const FREEZE_ALPHA_BAR: f64 = 5.0;

/// The Moes L from which a first attempt freezes the band (where alpha_bar >= [`FREEZE_ALPHA_BAR`]);
/// below it the first attempt corrects up to the cavitation boundary and the fallback ladder's
/// second rung freezes the band ([`crate::solve::params::Rung::Frozen`]), from it on the other
/// way round. Between the measured L = 20 (60 first attempts, M 19.3-5720, D 1 and 0.215, 257^2
/// and 513^2: 58 converge without the band, 55 with it, for 11 % fewer work units) and L = 30
/// (4 of 10 on 513^2 converge only with the band, 1 only without): docs/robustness.md, "The
/// band by L".
pub const FREEZE_MIN_L: f64 = 25.0;

/// Whether these physics have a spike next to the cavitation boundary (alpha_bar from
/// [`FREEZE_ALPHA_BAR`] on): the coarse grids may freeze the band along it, as the parameters
/// say ([`crate::solve::params::MgParams::freeze_band`]).
pub fn freezes(phys: &PointPhysics) -> bool {
    phys.fluid.alpha_bar >= FREEZE_ALPHA_BAR
}

/// Whether the first attempt at `case` freezes the band: alpha_bar >= [`FREEZE_ALPHA_BAR`] and
/// L >= [`FREEZE_MIN_L`].
pub fn first_freezes(case: &PointCase) -> bool {
    case.l >= FREEZE_MIN_L && freezes(&PointPhysics::from_case(case))
}

/// 9-point full weighting of the fine residual `r` at the interior coarse node (i, j), over the
/// pressurised fine nodes only where the coinciding fine node is pressurised (module docs).
fn full_weight(fine: &PointLevel, r: &[f64], i: usize, j: usize) -> f64 {
    let c = fine.at(2 * i, 2 * j);
    let nx = fine.nx;
    // At a pressurised coarse node the complementarity margins of cavitated fine nodes are left
    // out: they would push it towards cavitation even where the fine solution has converged.
    let active = fine.p[c] > 0.0;
    let v = |q: usize| {
        if active && fine.p[q] <= 0.0 {
            0.0
        } else {
            r[q]
        }
    };
    (4.0 * v(c)
        + 2.0 * (v(c - 1) + v(c + 1) + v(c - nx) + v(c + nx))
        + v(c - nx - 1)
        + v(c - nx + 1)
        + v(c + nx - 1)
        + v(c + nx + 1))
        / 16.0
}

impl DomainRule for PointDomain {
    type Params = PointDomainParams;
}

impl Contact for PointContact {
    type Level = PointLevel;
    type Domain = PointDomain;
    type Extra = PointExtra;
    fn sweep(mg: &mut PointMultigrid, l: usize) -> f64 {
        let lv = &mut mg.levels[l];
        point_line_sweep(lv, &mg.phys, mg.h0, &mg.params.relax, &mut mg.extra.scratch);
        ((lv.nx - 1) * (lv.ny - 1)) as f64 / mg.extra.fine_cells
    }

    /// A Newton iteration on level 0 counts as one sweep of level 0 per unknown row.
    fn newton_cost(mg: &PointMultigrid, iterations: usize) -> f64 {
        let lv = &mg.levels[0];
        (iterations * (lv.nx - 1)) as f64 * ((lv.nx - 1) * (lv.ny - 1)) as f64 / mg.extra.fine_cells
    }

    /// Injection of P and 9-point full weighting of the residual ([`full_weight`]); from
    /// alpha_bar = [`FREEZE_ALPHA_BAR`] on, frozen nodes where the fine 3 x 3 neighbourhood
    /// touches the cavitated set or a frozen node (module docs).
    fn restrict(
        coarse: &mut PointLevel,
        fine: &PointLevel,
        r: &[f64],
        phys: &PointPhysics,
        h0: f64,
        freeze: Freeze,
    ) {
        let freeze = freeze.band;
        for j in 0..coarse.ny {
            for i in 0..coarse.nx {
                let cc = coarse.at(i, j);
                coarse.p[cc] = fine.p[fine.at(2 * i, 2 * j)];
            }
        }
        coarse.update_film(phys, h0);
        // The rows of f and of the frozen marks from the coarse operator and the fine level
        // (taken out of `coarse` so that its rows can be filled in parallel).
        let (mut f, mut frozen) = (
            std::mem::take(&mut coarse.nodes.f),
            std::mem::take(&mut coarse.nodes.frozen),
        );
        let cl = &*coarse;
        let (nx, interior) = (fine.nx, |j: usize| j > 0 && j + 1 < cl.ny);
        for_each_row(cl.parallel, &mut frozen, cl.nx, |j, frozen| {
            if interior(j) {
                for (i, fr) in frozen.iter_mut().enumerate().take(cl.nx - 1).skip(1) {
                    let fc = fine.at(2 * i, 2 * j);
                    *fr = freeze
                        && [fc - nx, fc, fc + nx]
                            .iter()
                            .any(|&b| (b - 1..=b + 1).any(|q| fine.p[q] <= 0.0 || fine.frozen[q]));
                }
            }
        });
        for_each_row(cl.parallel, &mut f, cl.nx, |j, f| {
            f.fill(0.0);
            if interior(j) {
                let rows = cl.rows();
                for (i, v) in f.iter_mut().enumerate().take(cl.nx - 1).skip(1) {
                    *v = rows.reynolds(phys, i, j) + full_weight(fine, r, i, j);
                }
            }
        });
        coarse.nodes.f = f;
        coarse.nodes.frozen = frozen;
    }

    /// Bilinear interpolation of the correction.
    fn correct(
        coarse: &PointLevel,
        ph: &[f64],
        fine: &mut PointLevel,
        phys: &PointPhysics,
        h0: f64,
    ) {
        let e = |i: usize, j: usize| {
            let c = coarse.at(i, j);
            coarse.p[c] - ph[c]
        };
        let (nx, ny) = (fine.nx, fine.ny);
        for_each_row(fine.parallel, &mut fine.nodes.p, nx, |j, p| {
            if j == 0 || j + 1 == ny {
                return;
            }
            let (jc, jc1) = (j / 2, j.div_ceil(2));
            for (i, p) in p.iter_mut().enumerate().take(nx - 1).skip(1) {
                let (ic, ic1) = (i / 2, i.div_ceil(2));
                let v = 0.25 * (e(ic, jc) + e(ic1, jc) + e(ic, jc1) + e(ic1, jc1));
                *p = (*p + v).max(0.0);
            }
        });
        fine.update_film(phys, h0);
    }

    fn centre_index(mg: &PointMultigrid, l: usize) -> usize {
        mg.centre_index(l)
    }
    fn h_scale(mg: &PointMultigrid) -> f64 {
        mg.phys.h_scale
    }
    fn h_estimate(mg: &PointMultigrid) -> f64 {
        mg.domain.h_estimate
    }
    /// The Hertz ellipsoid sqrt(1 - X^2 - (Y/k)^2) (load 2 pi k/3) for elastic surfaces (in the dry
    /// limit one 1.5 times wider with the same load, so the solver has to find Hertz); for rigid
    /// ones, and where the rigid-isoviscous weight exceeds 1/2, a paraboloid of radius 1.5 l_h
    /// centred 0.5 l_h upstream, with the same load; H0 so that the central film equals the
    /// estimate.
    fn initialise(mg: &mut PointMultigrid) {
        let h_e = mg.domain.h_estimate;
        // Where the rigid-isoviscous regime dominates, the Hertz pressure is far from the answer
        // (and Newton from it can land on a spurious solution with a negative film).
        let rigid = !mg.phys.elastic || mg.domain.rigid_weight > 0.5;
        let dry = mg.phys.dry;
        let (k, load) = (mg.phys.k, mg.phys.load);
        let lh = (2.0 * h_e).sqrt();
        let lv = &mut mg.levels[0];
        for j in 0..lv.ny {
            for i in 0..lv.nx {
                let c = lv.at(i, j);
                lv.p[c] = if lv.boundary(i, j) {
                    0.0
                } else if dry {
                    // Wider than Hertz (the solver has to find Hertz), same load.
                    let (x, y) = (lv.x[i] / 1.5, lv.y[j] / (1.5 * k));
                    (1.0 - x * x - y * y).max(0.0).sqrt() / 2.25
                } else if rigid {
                    let r = 1.5 * lh;
                    let s2 = ((lv.x[i] + 0.5 * lh).powi(2) + lv.y[j].powi(2)) / (r * r);
                    // integral of (1 - s^2) over the disc of radius r: pi r^2 / 2.
                    load * 2.0 / (std::f64::consts::PI * r * r) * (1.0 - s2).max(0.0)
                } else {
                    hertz_pressure(lv.x[i], lv.y[j], k)
                };
            }
        }
        lv.update_film(&mg.phys, 0.0);
        let ic = mg.centre_index(0);
        let lv = &mut mg.levels[0];
        mg.h0 = h_e - lv.film[ic];
        lv.update_film(&mg.phys, mg.h0);
    }
    fn start_coarse(mg: &mut PointMultigrid, with_slope: bool) -> NewtonOutcome {
        let mut np = NewtonParams::coarsest_start(
            mg.params.newton_max_iter,
            mg.levels.len(),
            mg.params.deadline,
        );
        let fast = mg.params.converge == Converge::Fast && mg.levels.len() > 1;
        if fast {
            np.rel_tol = POINT_START_REL_TOL;
        }
        let lv = &mut mg.levels[0];
        lv.f.fill(0.0);
        lv.g = mg.phys.load * mg.phys.fluid_share;
        let out = newton_solve(lv, &mg.phys, &mut mg.h0, &np);
        mg.work_units += PointContact::newton_cost(mg, out.iterations);
        // (Not after the deadline: the solve stops at its first cycle anyway.)
        if !(out.converged || out.residual < 1e-6 * out.unit || past(mg.params.deadline)) {
            mg.relaxed_coarse_balance(20 * mg.params.coarse_sweeps);
        }
        if !with_slope {
            return out;
        }
        let ic = mg.centre_index(0);
        let lv = &mut mg.levels[0];
        let dh = 1e-3 * lv.film[ic].abs().max(1e-3 * mg.domain.h_estimate);
        let fallback = -lv.g / mg.domain.h_estimate;
        let rel_tol = if fast { POINT_SLOPE_REL_TOL } else { 0.0 };
        let (slope, iterations) = load_slope(lv, &mg.phys, mg.h0, dh, fallback, rel_tol);
        mg.load_slope = slope;
        mg.work_units += PointContact::newton_cost(mg, iterations);
        out
    }
    fn seed_matches(mg: &PointMultigrid, l: usize, seed: &Seed) -> bool {
        seed.matches(&mg.levels[l].x, &mg.levels[l].y)
    }
    fn frozen_band(mg: &PointMultigrid) -> bool {
        freezes(&mg.phys) && mg.params.freeze_band.unwrap_or(mg.extra.first_freezes)
    }
    fn spiked_boundary(mg: &PointMultigrid) -> bool {
        freezes(&mg.phys)
    }
    fn fmg_interpolate(mg: &mut PointMultigrid, l: usize) {
        let (lo, hi) = mg.levels.split_at_mut(l);
        let (coarse, fine) = (&lo[l - 1], &mut hi[0]);
        let (cnx, cny, fnx) = (coarse.nx, coarse.ny, fine.nx);
        // Even fine rows from the coarse rows (cubic along x), then odd rows along y.
        for jc in 0..cny {
            let row = &coarse.p[jc * cnx..(jc + 1) * cnx];
            let base = 2 * jc * fnx;
            for ic in 0..cnx {
                fine.p[base + 2 * ic] = row[ic];
                if ic + 1 < cnx {
                    fine.p[base + 2 * ic + 1] = mid(row, ic);
                }
            }
        }
        let mut col = vec![0.0; cny];
        for i in 0..fnx {
            for (jc, v) in col.iter_mut().enumerate() {
                *v = fine.p[2 * jc * fnx + i];
            }
            for jc in 0..cny - 1 {
                fine.p[(2 * jc + 1) * fnx + i] = mid(&col, jc);
            }
        }
        for j in 0..fine.ny {
            for i in 0..fnx {
                let c = fine.at(i, j);
                fine.p[c] = if fine.boundary(i, j) {
                    0.0
                } else {
                    fine.p[c].max(0.0)
                };
            }
        }
        fine.f.fill(0.0);
        fine.frozen.fill(false);
        fine.g = mg.phys.load * mg.phys.fluid_share;
        fine.update_film(&mg.phys, mg.h0);
    }

    const COARSE_BUDGET_GROWTH: usize = 2;
    const KEEP_CAVITATED: bool = true;
}
