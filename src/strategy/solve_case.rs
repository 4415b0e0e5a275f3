//! One solve for both contacts: [`solve`] takes a [`Case`] (line or point) and one
//! [`SolveParams`], and returns a [`Solution`].
//!
//! Contract: by default (`accuracy = Some(`[`DEFAULT_ACCURACY`]`)`, no `grid`) the multigrid
//! solve refines the grid until the Richardson estimate of H_c and H_min meets the target (up to
//! `max_grid`), and unless `full_model` is set the cheapest verified model answers
//! ([`crate::strategy::select`]); a `formula` given answers first where it may
//! ([`crate::strategy::formula`]). With a fixed `grid` (or no target, or a baseline method) the
//! case is solved on that grid (or the contact's default) by the chosen method and, with
//! `estimate` (the default), once more on the half grid for the Richardson estimate
//! ([`crate::strategy::accuracy::add_half_grid_estimate`]). The fallback ladder runs when
//! `fallback` is set. Point answers add the domain-truncation estimate. Every solve ends with a status and a reason; numerical failure
//! is a result, never a panic. The shared controls here override the contact's defaults; what
//! they leave as `None` keeps the contact's own value (grid 2049 points for a line contact, 129
//! per direction for a point contact; 60 or 40 cycles on the finest level).

use crate::discrete::line::domain::DomainParams;
use crate::discrete::point::domain::PointDomainParams;
use crate::model::case::{Case, Contact};
use crate::solve::line::{solve_line, LineSolveParams};
use crate::solve::params::Method;
use crate::solve::params::{ContactParams, MgParams};
use crate::solve::params::{Converge, CycleType};
use crate::solve::point::{solve_point, PointSolveParams};
use crate::solve::solution::{Outputs, Solution};
use crate::solve::Observer;
use crate::strategy::accuracy::{
    add_half_grid_estimate, point_truncation, solve_line_to_accuracy, solve_point_to_accuracy,
    ESTIMATE_ORDER, POINT_ESTIMATE_ORDER,
};
use crate::strategy::formula::{formula_answer, FormulaRef};
use crate::strategy::select::{solve_line_selected, solve_point_selected};

/// The default target relative accuracy of H_c and H_min.
pub const DEFAULT_ACCURACY: f64 = 0.01;

/// Largest grid of the accuracy ladder by default for the relative accuracy `target`: points
/// (line) or points per direction (point). Point contacts stop at 1025^2 for targets of
/// [`DEFAULT_ACCURACY`] and looser, and may go on to 2049^2 (about 0.9 GB) for tighter ones:
/// where 1025^2 does not meet 1 % the case is a hard corner, and a 2049^2 attempt there costs
/// minutes, while a tighter target met on 1025^2 stops there anyway.
pub fn default_max_grid(contact: Contact, target: f64) -> usize {
    match contact {
        Contact::Line => 16385,
        Contact::Point if target < DEFAULT_ACCURACY => 2049,
        Contact::Point => 1025,
    }
}

/// The controls of one solve, shared by line and point contacts, plus each contact's domain
/// options. `Default` is the library's default solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolveParams {
    /// Full multigrid (default), or a baseline (dense Newton, single-grid relaxation).
    pub method: Method,
    /// A fixed finest grid (points, per direction for point contacts): no accuracy ladder.
    /// `None`: the ladder picks the grid when there is an accuracy target, else the contact's
    /// default grid.
    pub grid: Option<usize>,
    /// Multigrid cycle type.
    pub cycle: CycleType,
    /// The stopping rule: at the discretisation error (fast, default) or at the tolerances
    /// (tight, for references).
    pub converge: Converge,
    /// Cycles allowed on the finest level; `None`: the contact's default.
    pub max_cycles: Option<usize>,
    /// Convergence tolerance on the load error; `None`: the contact's default.
    pub tol_load: Option<f64>,
    /// Convergence tolerance on the relative change of H_c per cycle; `None`: the
    /// contact's default.
    pub tol_h: Option<f64>,
    /// Retry a failed solve with conservative settings (the fallback ladder).
    pub fallback: bool,
    /// Target relative accuracy of H_c and H_min: refine the grid until the estimate meets it
    /// (multigrid without a fixed `grid`; default [`DEFAULT_ACCURACY`]).
    pub accuracy: Option<f64>,
    /// On a fixed grid: also solve the half grid for the error estimate (default on).
    pub estimate: bool,
    /// With `accuracy`: the largest grid the ladder may use; `None`: [`default_max_grid`].
    pub max_grid: Option<usize>,
    /// With `accuracy`: always solve the full model (no model selection).
    pub full_model: bool,
    /// Return the line profile or the point fields.
    pub keep_fields: bool,
    /// Point contacts: relax blocks of rows in parallel on the current rayon pool
    /// ([`crate::solve::params::MgParams::parallel`]); off, one thread, the rows in order.
    pub parallel: bool,
    /// Receives every multigrid cycle (`ehlmap solve --trace` prints them).
    pub observer: Option<Observer>,
    /// Line contacts: the domain rule.
    pub line_domain: DomainParams,
    /// Point contacts: the domain rule.
    pub point_domain: PointDomainParams,
    /// Stop all work at this instant ([`MgParams::deadline`]): an unconverged solve then ends
    /// with status max-iterations, the accuracy ladder with the finest grid solved by then, its
    /// reason naming the time limit. `None` (default): no limit. See
    /// [`SolveParams::time_limit`].
    pub deadline: Option<std::time::Instant>,
    /// With `accuracy` and without `full_model`: a fitted film formula that answers the case
    /// where its held-out error map allows ([`crate::strategy::formula`]). `None` (default): none.
    pub formula: Option<FormulaRef>,
}

impl Default for SolveParams {
    fn default() -> Self {
        let line = LineSolveParams::default();
        SolveParams {
            method: line.method,
            grid: None,
            cycle: line.mg.cycle,
            converge: line.mg.converge,
            max_cycles: None,
            tol_load: None,
            tol_h: None,
            fallback: line.fallback,
            accuracy: Some(DEFAULT_ACCURACY),
            estimate: true,
            max_grid: None,
            full_model: false,
            keep_fields: false,
            parallel: false,
            observer: None,
            line_domain: line.mg.domain,
            point_domain: PointSolveParams::default().mg.domain,
            deadline: None,
            formula: None,
        }
    }
}

impl SolveParams {
    /// These parameters with a deadline `seconds` from now (`None`: no limit).
    pub fn time_limit(self, seconds: Option<f64>) -> Self {
        SolveParams {
            deadline: seconds
                .map(|t| std::time::Instant::now() + std::time::Duration::from_secs_f64(t)),
            ..self
        }
    }

    /// A contact's solve parameters: its defaults with these controls over them and `domain`.
    pub fn contact_params<D: Copy>(&self, domain: D) -> ContactParams<D>
    where
        MgParams<D>: Default,
    {
        let mut p = ContactParams {
            method: self.method,
            fallback: self.fallback,
            keep_fields: self.keep_fields,
            ..ContactParams::default()
        };
        p.mg.cycle = self.cycle;
        p.mg.converge = self.converge;
        p.mg.domain = domain;
        p.mg.observer = self.observer;
        p.mg.parallel = self.parallel;
        p.mg.deadline = self.deadline;
        if let Some(g) = self.grid {
            p.mg.grid = g;
        }
        if let Some(n) = self.max_cycles {
            p.mg.max_cycles = n;
        }
        if let Some(t) = self.tol_load {
            p.mg.tol_load = t;
        }
        if let Some(t) = self.tol_h {
            p.mg.tol_h = t;
        }
        p
    }

    /// The line solver's parameters.
    pub fn line_params(&self) -> LineSolveParams {
        self.contact_params(self.line_domain)
    }

    /// The point solver's parameters.
    pub fn point_params(&self) -> PointSolveParams {
        self.contact_params(self.point_domain)
    }
}

/// Solve a line or point case (see the module docs).
pub fn solve(case: &Case, params: &SolveParams) -> Solution {
    let Some(smooth_case) = smooth_twin(case) else {
        return solve_surfaces(case, params);
    };
    // Rough surfaces: the full model (no simplified model knows the roughness), and the same
    // case with smooth surfaces beside it.
    let formula = params.formula.is_some() && params.accuracy.is_some();
    let params = &SolveParams {
        full_model: true,
        ..*params
    };
    let smooth = solve_surfaces(
        &smooth_case,
        &SolveParams {
            keep_fields: false,
            ..*params
        },
    );
    let mut s = solve_rough_beside(case, params, &smooth.outputs);
    if formula {
        let note = "; formula not used: rough surfaces (the formula is the smooth film)";
        s.outputs.reason.push_str(note);
        s.info.reason.push_str(note);
    }
    s
}

/// Solve a case with rough surfaces by the full model, its mixed outputs carrying the films of
/// `smooth` (the same case with smooth surfaces, solved by the caller) when it converged.
pub fn solve_rough_beside(case: &Case, params: &SolveParams, smooth: &Outputs) -> Solution {
    let params = &SolveParams {
        full_model: true,
        ..*params
    };
    let mut s = solve_surfaces(case, params);
    if let Some(m) = s.outputs.mixed.as_mut() {
        let ok = smooth.status == crate::solve::Status::Converged;
        m.h_c_smooth = ok.then_some(smooth.h_c);
        m.h_min_smooth = ok.then_some(smooth.h_min);
    }
    s
}

/// The case with smooth surfaces, when `case` has rough ones.
pub fn smooth_twin(case: &Case) -> Option<Case> {
    case.models().roughness.filter(|r| r.is_rough())?;
    Some(case.with_roughness(None))
}

/// [`solve`] of the case's own surfaces, smooth or rough: by the formula where it answers, else
/// by a solve whose reason says why the formula did not answer.
fn solve_surfaces(case: &Case, params: &SolveParams) -> Solution {
    let ladder = params.method == Method::Multigrid && params.grid.is_none();
    let target = params.accuracy.filter(|_| ladder && !params.full_model);
    let Some((f, t)) = params.formula.zip(target) else {
        return solve_models(case, params);
    };
    match formula_answer(case, f.0, t) {
        Ok(s) => s,
        Err(why) => {
            let mut s = solve_models(case, params);
            let note = format!("; formula not used: {why}");
            s.outputs.reason.push_str(&note);
            s.info.reason.push_str(&note);
            s
        }
    }
}

/// [`solve_surfaces`] by a solve: the accuracy ladder with model selection, or a fixed grid.
fn solve_models(case: &Case, params: &SolveParams) -> Solution {
    let max_grid = params.max_grid.unwrap_or(default_max_grid(
        case.contact(),
        params.accuracy.unwrap_or(DEFAULT_ACCURACY),
    ));
    let ladder = params.method == Method::Multigrid && params.grid.is_none();
    match (case, params.accuracy.filter(|_| ladder)) {
        (_, None) => solve_fixed(case, params),
        (Case::Line(c), Some(t)) if params.full_model => {
            solve_line_to_accuracy(c, &params.line_params(), t, max_grid)
        }
        (Case::Point(c), Some(t)) if params.full_model => {
            solve_point_to_accuracy(c, &params.point_params(), t, max_grid)
        }
        (Case::Line(c), Some(t)) => solve_line_selected(c, &params.line_params(), t, max_grid).0,
        (Case::Point(c), Some(t)) => solve_point_selected(c, &params.point_params(), t, max_grid).0,
    }
}

/// One grid (`grid` or the contact's default), with [`estimate_fixed`] when `estimate` is set.
fn solve_fixed(case: &Case, params: &SolveParams) -> Solution {
    let mut s = solve_once(case, params);
    if params.estimate {
        estimate_fixed(case, params, &mut s);
    }
    s
}

/// One solve on `params`' grid (or the contact's default), no estimate.
fn solve_once(case: &Case, params: &SolveParams) -> Solution {
    match case {
        Case::Line(c) => solve_line(c, &params.line_params()),
        Case::Point(c) => solve_point(c, &params.point_params()),
    }
}

/// The error estimate of a solve `s` on a fixed grid: the half-grid Richardson estimate
/// ([`add_half_grid_estimate`], the half grid solved with `params`) plus, for a point contact,
/// the domain-truncation estimate.
pub fn estimate_fixed(case: &Case, params: &SolveParams, s: &mut Solution) {
    let order = match case {
        Case::Line(_) => ESTIMATE_ORDER,
        Case::Point(_) => POINT_ESTIMATE_ORDER,
    };
    add_half_grid_estimate(s, case.contact().grid_range().0, order, |g| {
        solve_once(
            case,
            &SolveParams {
                grid: Some(g),
                ..*params
            },
        )
    });
    if let Case::Point(c) = case {
        s.outputs
            .widen_errors(point_truncation(c, &params.point_params()));
    }
}
