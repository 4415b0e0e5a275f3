//! Model selection: answer a case with the cheapest model that meets an accuracy target.
//!
//! Before solving, the case is placed in the (M, L) plane by the published blends, Moes 1992 for
//! line contacts and NVM 1994 for point contacts (`crate::model::formulas`). Their asymptotes give the
//! relative effect of what a simpler model neglects:
//! - elasticity: e_el = |H / H_rigid - 1|, with H_rigid the blend without its elastic asymptotes
//!   (H_EI -> 0, H_EP -> infinity, so s -> 3): `(H_RI^3 + H_RP^3)^(1/3)`;
//! - piezoviscosity: e_pv = |H / H(L = 0) - 1|.
//!
//! Screening: a simplification is a candidate when its estimated effect is below the target.
//! The blends are fits, and their *effects* can be off by an order of magnitude far from the
//! data they were fitted to (at M = 0.05, L = 5 Moes' blend puts the piezoviscous effect at
//! 1.5e-4; the solver measures 3.8e-3), so a candidate is then **verified**: the full and the
//! simplified model are solved on a coarse check grid (257 line points, 33^2 point nodes, a few
//! per cent of a fine solve; refined twice at most while the full check does not resolve the
//! film, status under-resolved) and the candidate is kept only when the measured change of H_c and
//! H_min is below `CHECK_FRACTION` times the target; the measured effect becomes the neglected
//! part of the error estimate. Otherwise the full model is solved. Where the full check itself
//! fails (the full model does not converge on the check grid), the screen is trusted with a
//! margin of `SCREEN_MARGIN`. The closed form is checked through its discrete twin
//! (rigid-isoviscous on the check grid). The models, cheapest first:
//! - `closed-form`: rigid and isoviscous line contact with incompressible lubricant: Martin's
//!   film with the Reynolds exit condition, exactly H_c = H_min = 2.4475/M at X = 0, and the
//!   flux thickness H(p_max) = 3/M; no solve at all.
//! - `rigid-isoviscous`, `rigid`: no deformation integral (H = H0 + X^2/2 ...);
//! - `isoviscous`: the case solved at L = 0 with Barus (viscosity 1 everywhere);
//! - `slender-line` (point contacts, small D): the line contact with the same Hertz half-width
//!   (`crate::strategy::slender`); not verified per case, since a point check precise enough to see its
//!   1-2 % gap costs more than the point solve it would save: its neglected effect is the gap
//!   bound of `crate::strategy::slender`, validated on a separate set in `tests/slender.rs`, and it is
//!   tried first, whenever that bound is below `CHECK_FRACTION` times the target;
//! - `full`: everything.
//!
//! The reported `error_estimate` of a simplified answer is the discretisation estimate plus the
//! neglected effect; the simplified model is therefore solved to the target less its neglected
//! effect ([`model_target`]), so that the sum meets the target. A simplified solve that fails
//! is retried with the full model (and says so).
//! Every simplification is checked against the full model in `tests/selection.rs` and
//! `tests/slender.rs`.

use crate::model::case::{Elasticity, LineCase, Models, PointCase};
use crate::model::formulas::{
    moes_line_asymptotes, moes_line_hc, nvm_point_asymptotes, nvm_point_hc,
};
use crate::model::lubricant::{Density, Viscosity};
use crate::solve::ladder::Attempt;
use crate::solve::line::{solve_line, LineSolveParams};
use crate::solve::point::{solve_point, PointSolveParams};
use crate::solve::solution::Solution;
use crate::solve::solution::{ModelUsed, Outputs};
use crate::solve::{SolveInfo, Status};
use crate::strategy::accuracy::solve_line_to_accuracy;
use crate::strategy::accuracy::solve_point_to_accuracy;
use crate::strategy::closed_form::closed_form_line;
use crate::strategy::slender;
use serde::{Deserialize, Serialize};

/// The check-grid solves stop with an algebraic error of at most this times the target (a
/// tenth of [`CHECK_FRACTION`]): the measured effect is the difference of two such solves, and
/// on the coarse check grid the fast rule's own cap (a tenth of a discretisation error of
/// several per cent, at most `max_algebraic` = 1e-2) would let their algebraic errors alone
/// exceed the limit (point M = 0.01, L = 20, D = 0.01, Roelands: two 33^2 solves of the full
/// model, converged to 5.6e-3 and 7.5e-3, differed by 0.8 %, the measured rigid-isoviscous
/// effect 1.0e-3).
pub const CHECK_ALGEBRAIC: f64 = CHECK_FRACTION / 10.0;

/// Points of the line check grid.
pub const CHECK_GRID_LINE: usize = 257;
/// Nodes per direction of the point check grid.
pub const CHECK_GRID_POINT: usize = 33;
/// A candidate is kept when its measured effect on the check grid is below this times the target.
pub const CHECK_FRACTION: f64 = 0.5;
/// When the full check solve fails (very small M), the screened effect times this margin must
/// be below the same limit, and is reported as the neglected effect.
pub const SCREEN_MARGIN: f64 = 10.0;

/// The choice for one case and the estimates it rests on.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Selection {
    /// The model chosen to answer the case.
    pub model: ModelUsed,
    /// Estimated relative effect of elasticity on H_c (from Moes 1992 or NVM 1994).
    pub elastic_effect: f64,
    /// Estimated relative effect of piezoviscosity on H_c (from Moes 1992 or NVM 1994).
    pub piezo_effect: f64,
    /// The effect of what the chosen model neglects: the screening estimate, replaced by the
    /// measured one once verified (0 for the full model).
    pub neglected: f64,
    /// The effect measured on the check grid, once verified.
    pub measured: Option<f64>,
}

/// Effects (elastic, piezoviscous) from Moes 1992 (line) or NVM 1994 (point, `Some(D)`).
pub fn effects(m: f64, l: f64, d: Option<f64>) -> (f64, f64) {
    let (full, iso, ri, rp) = match d {
        None => {
            let [ri, _, rp, _] = moes_line_asymptotes(m, l);
            (moes_line_hc(m, l), moes_line_hc(m, 0.0), ri, rp)
        }
        Some(d) => {
            let [ri, _, rp, _, _] = nvm_point_asymptotes(m, l, d);
            (nvm_point_hc(m, l, d), nvm_point_hc(m, 0.0, d), ri, rp)
        }
    };
    let rigid = if l > 0.0 {
        (ri.powi(3) + rp.powi(3)).cbrt()
    } else {
        ri
    };
    ((full / rigid - 1.0).abs(), (full / iso - 1.0).abs())
}

/// Screen: the cheapest model whose estimated neglected effects are below `target`. Only what the
/// case has can be switched off: a rigid case or an L = 0 case is "full" unless a further
/// simplification applies (a rigid, L = 0 line case with incompressible lubricant is the closed
/// form).
pub fn select(m: f64, l: f64, d: Option<f64>, models: &Models, target: f64) -> Selection {
    let (e_el, e_pv) = effects(m, l, d);
    let limit = target;
    // What switching a model off would neglect; a case that has it off already loses nothing.
    let has_el = models.elasticity != Elasticity::Rigid;
    let has_pv = l > 0.0;
    let el = if has_el { e_el } else { 0.0 };
    let pv = if has_pv { e_pv } else { 0.0 };
    let (drop_el, drop_pv) = if el + pv < limit {
        (has_el, has_pv)
    } else if el < limit {
        (has_el, false)
    } else {
        (false, has_pv && pv < limit)
    };
    let rigid_iso = (drop_el || !has_el) && (drop_pv || !has_pv);
    let closed = rigid_iso && d.is_none() && models.density == Density::Incompressible;
    let model = match (closed, drop_el, drop_pv) {
        (true, _, _) => ModelUsed::ClosedForm,
        (false, true, true) => ModelUsed::RigidIsoviscous,
        (false, true, false) => ModelUsed::Rigid,
        (false, false, true) => ModelUsed::Isoviscous,
        (false, false, false) => ModelUsed::Full,
    };
    let neglected = if drop_el { el } else { 0.0 } + if drop_pv { pv } else { 0.0 };
    Selection {
        model,
        elastic_effect: e_el,
        piezo_effect: e_pv,
        neglected,
        measured: None,
    }
}

/// The models and L of the simplified problem.
fn simplified(model: ModelUsed, l: f64, models: &Models) -> (f64, Models) {
    let mut mm = *models;
    let mut ll = l;
    if matches!(model, ModelUsed::Rigid | ModelUsed::RigidIsoviscous) {
        mm.elasticity = Elasticity::Rigid;
    }
    if matches!(model, ModelUsed::Isoviscous | ModelUsed::RigidIsoviscous) {
        ll = 0.0;
        mm.viscosity = Viscosity::Barus;
    }
    (ll, mm)
}

/// Mark a simplified answer: model, note, and the neglected effect added to the estimate.
fn annotate(o: &mut Outputs, info: &mut SolveInfo, sel: &Selection) {
    o.model_used = sel.model;
    if sel.model == ModelUsed::Full {
        return;
    }
    o.widen_errors(sel.neglected);
    let how = if sel.model == ModelUsed::SlenderLine {
        "the slender-contact gap bound"
    } else if sel.measured.is_some() {
        "measured on the check grid"
    } else {
        "screened x 10: the full check did not converge"
    };
    let solved_to = if sel.model == ModelUsed::ClosedForm {
        ""
    } else {
        ", its solve's target the target less it"
    };
    let note = format!(
        "; model {} (neglected effect {:.1e}, {how}{solved_to}; screened elastic {:.1e}, \
         piezoviscous {:.1e})",
        sel.model, sel.neglected, sel.elastic_effect, sel.piezo_effect
    );
    o.reason.push_str(&note);
    info.reason.push_str(&note);
}

/// The relative change of H_c and H_min (the larger) from `full` to `simple`, both converged.
fn measured_effect(full: &Outputs, simple: &Outputs) -> Option<f64> {
    let ok = full.status == Status::Converged && simple.status == Status::Converged;
    let rel = |a: f64, b: f64| (a / b - 1.0).abs();
    let e = rel(simple.h_c, full.h_c).max(rel(simple.h_min, full.h_min));
    (ok && e.is_finite()).then_some(e)
}

/// Verify a screened candidate with the check-grid solves (`check(model, grid)`, from `grid`,
/// refined twice at most while the full solve does not resolve the film); returns the kept
/// selection and the cost (work units, seconds) of the checks.
fn verify(
    sel: Selection,
    target: f64,
    grid: usize,
    check: impl Fn(ModelUsed, usize) -> Outputs,
) -> (Selection, f64, f64) {
    if sel.model == ModelUsed::Full {
        return (sel, 0.0, 0.0);
    }
    let (mut grid, mut spent) = (grid, (0.0, 0.0));
    let mut full = check(ModelUsed::Full, grid);
    for _ in 0..2 {
        if full.status != Status::UnderResolved {
            break;
        }
        spent = (spent.0 + full.work_units, spent.1 + full.wall_s);
        grid = 2 * (grid - 1) + 1;
        full = check(ModelUsed::Full, grid);
    }
    // The closed form is checked through its discrete twin, so that the coarse grid's
    // discretisation error cancels in the comparison.
    let twin = match sel.model {
        ModelUsed::ClosedForm => ModelUsed::RigidIsoviscous,
        m => m,
    };
    let simple = check(twin, grid);
    let cost = (
        spent.0 + full.work_units + simple.work_units,
        spent.1 + full.wall_s + simple.wall_s,
    );
    let limit = CHECK_FRACTION * target;
    let screened = sel.neglected * SCREEN_MARGIN;
    let measured = measured_effect(&full, &simple);
    let neglected = match measured {
        Some(e) => (e < limit).then_some(e),
        // The full check did not converge: trust the screen with a margin.
        None => (simple.status == Status::Converged && screened < limit).then_some(screened),
    };
    let sel = match neglected {
        Some(neglected) => Selection {
            neglected,
            measured,
            ..sel
        },
        None => Selection {
            model: ModelUsed::Full,
            neglected: 0.0,
            measured,
            ..sel
        },
    };
    (sel, cost.0, cost.1)
}

/// Finish a selected solve `s`: a simplified model that did not converge is replaced by the full
/// model (`full()`, noted in the reason); the answer is annotated with its model, and the cost
/// of the checks (`check` = work units, seconds) and of a failed simplified solve is added.
fn finish<S: Attempt>(
    mut s: S,
    sel: Selection,
    full: impl FnOnce() -> S,
    check: (f64, f64),
) -> (S, Selection) {
    let (mut wu, mut wall) = check;
    let sel = if sel.model != ModelUsed::Full && s.info().status != Status::Converged {
        wu += s.info().work_units;
        wall += s.info().wall_s;
        s = full();
        let note = format!(" ({} model did not converge; full model solved)", sel.model);
        let (info, o) = s.parts();
        o.reason.push_str(&note);
        info.reason.push_str(&note);
        Selection {
            model: ModelUsed::Full,
            neglected: 0.0,
            ..sel
        }
    } else {
        sel
    };
    let (info, o) = s.parts();
    annotate(o, info, &sel);
    o.work_units += wu;
    o.wall_s += wall;
    info.work_units += wu;
    info.wall_s += wall;
    (s, sel)
}

/// The target a simplified model's own solve must meet: what the neglected effect leaves of
/// `target`, so that the reported estimate (the solve's plus the neglected effect, [`annotate`])
/// stays within `target`. At least `(1 - CHECK_FRACTION) target`, since a model is kept only
/// while its neglected effect is below `CHECK_FRACTION` times the target.
pub fn model_target(target: f64, sel: &Selection) -> f64 {
    target - sel.neglected
}

/// Solve a line case with the cheapest verified model to `target` (refining up to `max_grid`);
/// a failed simplified solve is redone with the full model.
pub fn solve_line_selected(
    case: &LineCase,
    params: &LineSolveParams,
    target: f64,
    max_grid: usize,
) -> (Solution, Selection) {
    let screened = select(case.m, case.l, None, &case.models, target);
    let mut cp = *params;
    cp.keep_fields = false;
    let (sel, wu, wall) = verify(screened, target, CHECK_GRID_LINE, |model, grid| {
        let mut cp = cp;
        cp.mg.grid = grid;
        cp.mg.max_algebraic = cp.mg.max_algebraic.min(CHECK_ALGEBRAIC * target);
        solve_line_model(case, &cp, model)
    });
    let full = |p: &LineSolveParams| solve_line_to_accuracy(case, p, target, max_grid);
    let s = match sel.model {
        ModelUsed::Full => full(params),
        ModelUsed::ClosedForm => closed_form_line(case.m),
        model => {
            let (l, models) = simplified(model, case.l, &case.models);
            match LineCase::with_models(case.m, l, models) {
                Ok(simple) => {
                    solve_line_to_accuracy(&simple, params, model_target(target, &sel), max_grid)
                }
                Err(_) => full(params),
            }
        }
    };
    finish(s, sel, || full(params), (wu, wall))
}

/// [`solve_line_selected`] for point contacts (no closed form).
pub fn solve_point_selected(
    case: &PointCase,
    params: &PointSolveParams,
    target: f64,
    max_grid: usize,
) -> (Solution, Selection) {
    let screened = select(case.m, case.l, Some(case.d), &case.models, target);
    let full = |p: &PointSolveParams| solve_point_to_accuracy(case, p, target, max_grid);
    if let Some(bound) = slender::gap_bound(case).filter(|b| *b < CHECK_FRACTION * target) {
        let sel = Selection {
            model: ModelUsed::SlenderLine,
            neglected: bound,
            measured: None,
            ..screened
        };
        let lp = LineSolveParams {
            fallback: params.fallback,
            ..Default::default()
        };
        let lc = slender::equivalent_line(case);
        let line =
            solve_line_to_accuracy(&lc, &lp, model_target(target, &sel), slender::LINE_MAX_GRID);
        let s = slender::point_solution(case, line);
        return finish(s, sel, || full(params), (0.0, 0.0));
    }
    let mut cp = *params;
    cp.keep_fields = false;
    let (sel, wu, wall) = verify(screened, target, CHECK_GRID_POINT, |model, grid| {
        let mut cp = cp;
        cp.mg.grid = grid;
        cp.mg.max_algebraic = cp.mg.max_algebraic.min(CHECK_ALGEBRAIC * target);
        solve_point_model(case, &cp, model)
    });
    let s = match sel.model {
        ModelUsed::Full => full(params),
        model => {
            let (l, models) = simplified(model, case.l, &case.models);
            match PointCase::with_models(case.m, l, case.d, models) {
                Ok(simple) => {
                    solve_point_to_accuracy(&simple, params, model_target(target, &sel), max_grid)
                }
                Err(_) => full(params),
            }
        }
    };
    finish(s, sel, || full(params), (wu, wall))
}

/// Solve with a fixed model (no selection) on one grid: the reference the selection is checked
/// against.
pub fn solve_line_model(case: &LineCase, params: &LineSolveParams, model: ModelUsed) -> Outputs {
    if model == ModelUsed::ClosedForm {
        return closed_form_line(case.m).outputs;
    }
    let (l, models) = simplified(model, case.l, &case.models);
    match LineCase::with_models(case.m, l, models) {
        Ok(c) => solve_line(&c, params).outputs,
        Err(_) => solve_line(case, params).outputs,
    }
}

/// [`solve_line_model`] for point contacts.
pub fn solve_point_model(case: &PointCase, params: &PointSolveParams, model: ModelUsed) -> Outputs {
    if model == ModelUsed::SlenderLine {
        let lc = slender::equivalent_line(case);
        return slender::point_outputs(case, &solve_line(&lc, &LineSolveParams::default()).outputs);
    }
    let (l, models) = simplified(model, case.l, &case.models);
    match PointCase::with_models(case.m, l, case.d, models) {
        Ok(c) => solve_point(&c, params).outputs,
        Err(_) => solve_point(case, params).outputs,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn effects_vanish_in_their_limits_and_order_the_models() {
        // Deep rigid-isoviscous: both effects tiny; line -> closed form, point -> rigid (an
        // L = 0 case is isoviscous already), and rigid-isoviscous at small L > 0.
        let m = Models::default();
        let s = select(0.01, 0.0, None, &m, 0.01);
        assert_eq!(s.model, ModelUsed::ClosedForm, "{s:?}");
        assert!(s.elastic_effect < 1e-3 && s.piezo_effect == 0.0);
        let s = select(0.01, 0.0, Some(1.0), &m, 0.01);
        assert_eq!(s.model, ModelUsed::Rigid, "{s:?}");
        let s = select(0.01, 0.01, Some(1.0), &m, 0.01);
        assert_eq!(s.model, ModelUsed::RigidIsoviscous, "{s:?}");
        // Typical EHL: nothing can be dropped.
        let s = select(20.0, 10.0, None, &m, 0.01);
        assert_eq!(s.model, ModelUsed::Full);
        assert!(s.elastic_effect > 0.1 && s.piezo_effect > 0.3, "{s:?}");
        // Elastic but isoviscous at small L and large M.
        let s = select(100.0, 0.001, None, &m, 0.01);
        assert_eq!(s.model, ModelUsed::Isoviscous, "{s:?}");
        // Dowson-Higginson density rules out the closed form.
        let dh = Models {
            density: Density::DowsonHigginson { ph_pa: 1e9 },
            ..m
        };
        assert_eq!(select(0.01, 0.0, None, &dh, 0.01).model, ModelUsed::Rigid);
        // A rigid L = 0 case is the closed form; a rigid case with L > 0 only drops L.
        let rigid = Models {
            elasticity: Elasticity::Rigid,
            ..m
        };
        assert_eq!(
            select(50.0, 0.0, None, &rigid, 0.01).model,
            ModelUsed::ClosedForm
        );
        assert_eq!(
            select(0.01, 0.01, None, &rigid, 0.01).model,
            ModelUsed::ClosedForm
        );
        // The elastic effect grows with M; the piezoviscous one with L.
        let (a, _) = effects(0.1, 0.0, None);
        let (b, _) = effects(1.0, 0.0, None);
        let (_, c) = effects(10.0, 1.0, None);
        let (_, e) = effects(10.0, 5.0, None);
        assert!(a < b && c < e, "{a} {b} {c} {e}");
    }

    #[test]
    fn closed_form_is_martins_film() {
        let s = closed_form_line(0.01);
        assert!((s.outputs.h_c * 0.01 - 2.4475).abs() < 1e-12);
        assert_eq!(s.outputs.h_c, s.outputs.h_min);
        assert_eq!(s.outputs.model_used, "closed-form");
        assert!(s.outputs.error_estimate.unwrap() < 0.01);
        assert!(s.outputs.reason.contains("closed form"));
    }
}
