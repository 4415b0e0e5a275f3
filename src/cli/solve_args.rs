//! The command line of `ehlmap solve`: its options, and their checks before anything runs (a
//! value out of range, or an option the chosen contact or method would ignore, is bad input,
//! exit code 2, naming the option), turned into the [`Case`] and the [`SolveParams`] of the solve.

use crate::cli::error::{input, CliError};
use crate::cli::formula_arg::formula_arg;
use crate::cli::output::note;
use crate::cli::solve_progress::{self, SolveProgressArg};
use clap::ValueEnum;
use ehlmap::discrete::point::domain::PointDomainParams;
use ehlmap::model::asperity::AsperityParams;
use ehlmap::model::case::{Case, Contact, Elasticity, LineCase, Models, ParamError, PointCase};
use ehlmap::model::error::num;
use ehlmap::model::lubricant::{Density, Viscosity};
use ehlmap::model::roughness::Roughness;
use ehlmap::solve::params::Method;
use ehlmap::solve::params::{Converge, CycleType};
use ehlmap::solve::{CycleEvent, Observer};
use ehlmap::strategy::solve_case::{SolveParams, DEFAULT_ACCURACY};
use std::path::PathBuf;

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub enum ContactArg {
    Line,
    Point,
}

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub enum ElasticityArg {
    Elastic,
    Rigid,
}

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub enum ViscosityArg {
    Barus,
    Roelands,
}

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub enum DensityArg {
    Incompressible,
    DowsonHigginson,
}

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub enum RoughSurfaceArg {
    Both,
    #[value(name = "1")]
    One,
    #[value(name = "2")]
    Two,
}

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub enum MethodArg {
    Multigrid,
    Newton,
    Relax,
}

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub enum CycleArg {
    V,
    W,
}

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub enum ConvergeArg {
    /// Stop when the algebraic error is below a tenth of the discretisation error (default).
    Fast,
    /// Converge to the load and H_c tolerances (references, tests).
    Tight,
}

#[derive(clap::Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct SolveArgs {
    #[arg(long, value_enum, default_value = "line")]
    pub contact: ContactArg,
    /// Moes load parameter M > 0.
    #[arg(long = "M", allow_hyphen_values = true)]
    pub m: f64,
    /// Moes lubricant parameter L >= 0.
    #[arg(long = "L", default_value_t = 0.0, allow_hyphen_values = true)]
    pub l: f64,
    /// Ellipticity D = Rx/Ry in (0, 1] (point contacts; default 1, a circular contact).
    #[arg(long = "D", allow_hyphen_values = true)]
    pub d: Option<f64>,
    #[arg(long, value_enum, default_value = "elastic")]
    pub elasticity: ElasticityArg,
    #[arg(long, value_enum, default_value = "barus")]
    pub viscosity: ViscosityArg,
    /// Roelands: ambient viscosity eta0 in Pa s (or give --z).
    #[arg(long, allow_hyphen_values = true)]
    pub eta0: Option<f64>,
    /// Roelands pressure-viscosity index z (or give --eta0).
    #[arg(long, allow_hyphen_values = true)]
    pub z: Option<f64>,
    /// Hertzian pressure p_h in Pa (Roelands and Dowson-Higginson need it; an error otherwise).
    #[arg(long, allow_hyphen_values = true)]
    pub ph: Option<f64>,
    #[arg(long, value_enum, default_value = "incompressible")]
    pub density: DensityArg,
    /// Composite RMS roughness sigma = sqrt(Rq1^2 + Rq2^2) in Moes film units (the units of
    /// H_c): solves the Patir-Cheng average Reynolds equation with Greenwood-Tripp asperity
    /// contact, and the smooth case beside it; 0 (the default) is the smooth solver.
    #[arg(long, allow_hyphen_values = true)]
    pub sigma: Option<f64>,
    /// Roughness orientation gamma (Peklenik): 1 isotropic (default), < 1 transverse ridges,
    /// > 1 longitudinal; with --sigma.
    #[arg(long, allow_hyphen_values = true)]
    pub gamma: Option<f64>,
    /// Slide-to-roll ratio (u1 - u2)/u_m in [-2, 2] (default 0, pure rolling); with --sigma.
    #[arg(long, allow_hyphen_values = true)]
    pub slide_roll: Option<f64>,
    /// Which surface carries the roughness, for the shear flow: both (equally, default), 1 or 2
    /// (the surface moving at u1 or u2); with --sigma.
    #[arg(long, value_enum)]
    pub rough_surface: Option<RoughSurfaceArg>,
    /// p_h/E' in (0, 1) for the asperity pressure (default 1 GPa on steel, 0.004333); with
    /// --sigma.
    #[arg(long, allow_hyphen_values = true)]
    pub ph_over_e: Option<f64>,
    /// Greenwood-Tripp summit density x summit radius x sigma, eta_s beta sigma > 0 (default
    /// 0.04); with --sigma.
    #[arg(long, allow_hyphen_values = true)]
    pub eta_beta_sigma: Option<f64>,
    /// Greenwood-Tripp sigma over the summit radius, sigma/beta > 0 (default 1e-3); with --sigma.
    #[arg(long, allow_hyphen_values = true)]
    pub sigma_over_beta: Option<f64>,
    /// Solver: full multigrid, or the baselines (dense Newton, single-grid relaxation).
    #[arg(long, value_enum, default_value = "multigrid")]
    pub method: MethodArg,
    /// Fix the finest grid (rounded up to 2^k n0 + 1): 33 to 1048577 line points, 17 to 2049
    /// point nodes per direction. The half grid is solved too, for the error estimate (see
    /// --no-estimate). Without --grid the accuracy ladder picks the grid (--accuracy); the
    /// baseline methods use 2049 line points or 129 point nodes per direction.
    #[arg(long)]
    pub grid: Option<usize>,
    /// With --grid or a baseline method: skip the half-grid solve, so H_c_err, H_min_err and
    /// error_estimate are null (benchmarks only).
    #[arg(long)]
    pub no_estimate: bool,
    /// Multigrid cycle (default v); --method multigrid only.
    #[arg(long, value_enum)]
    pub cycle: Option<CycleArg>,
    /// Stopping rule (default fast): at a tenth of the discretisation error (fast) or at the
    /// load and H_c tolerances (tight); --method multigrid only.
    #[arg(long, value_enum)]
    pub converge: Option<ConvergeArg>,
    /// Target relative accuracy of H_c and H_min (default 0.01): pick the cheapest adequate
    /// model (rigid, isoviscous, closed form; see --full-model) and refine the grid from 257
    /// line points (33 point nodes per direction; a thin isoviscous point film from the first
    /// grid of its Hertzian start) until the Richardson estimate meets it (up
    /// to --max-grid); reports model_used, level, H_c_err, H_min_err, error_estimate and
    /// accuracy_met. --method multigrid only; not with --grid.
    #[arg(long, allow_hyphen_values = true)]
    pub accuracy: Option<f64>,
    /// Always solve the full model (no model selection; not with --grid).
    #[arg(long)]
    pub full_model: bool,
    /// The largest grid the accuracy ladder may use (default 16385 line points; point nodes per
    /// direction 1025 for targets of 1 % and looser, 2049 for tighter ones; line 513 to
    /// 1048577, point 65 to 2049; not with --grid).
    #[arg(long)]
    pub max_grid: Option<usize>,
    /// Cycles allowed on the finest level, 1 to 100000 (default: the contact's, 60 for line
    /// contacts, 40 for point contacts); --method multigrid only.
    #[arg(long)]
    pub max_cycles: Option<usize>,
    /// Do not retry a failed solve with conservative settings; --method multigrid only.
    #[arg(long)]
    pub no_fallback: bool,
    /// Point contacts: relax blocks of grid rows in parallel on this many threads, 1 to 4096
    /// (default: one thread, the rows in order); not with --method newton.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Point contacts: P = 0 on the domain's boundary (the classic references' truncated
    /// domain) instead of the default asymptotic far field (boundary values and the load beyond
    /// the domain from the r^-3 decay of the pressure); biases rigid-like cases (M below about
    /// 20) low, by about 18 % at M = 1.
    #[arg(long)]
    pub truncated_domain: bool,
    /// Stop solving after this many seconds: an unconverged solve ends with status
    /// max-iterations, the accuracy ladder with the finest grid solved by then; the reason says
    /// so. Default: no limit.
    #[arg(long, allow_hyphen_values = true)]
    pub time_limit: Option<f64>,
    /// A fit report (its fit.json, or the report directory) whose formula answers the case
    /// without a solve where its held-out error map is below half the accuracy target
    /// (model_used "formula"); else the case is solved and the reason says why not.
    #[arg(long)]
    pub formula: Option<PathBuf>,
    /// Print every multigrid cycle (level, cycle, residual, load error, H_c, work units) to
    /// stderr; --method multigrid only.
    #[arg(long)]
    pub trace: bool,
    /// Progress on stderr: auto, a line every 10 s once the solve has run for 5 s (quick
    /// solves print nothing); log, the same from the first cycle; none. --trace prints every
    /// cycle instead.
    #[arg(long, value_enum, default_value_t = SolveProgressArg::Auto)]
    pub progress: SolveProgressArg,
    /// Print one JSON object instead of the summary.
    #[arg(long)]
    pub json: bool,
    /// Write the X, P, H profile to this Parquet file (line contacts).
    #[arg(long)]
    pub profile: Option<PathBuf>,
    /// Write the X, Y, P, H fields, one row per node, to this Parquet file (point contacts).
    #[arg(long)]
    pub fields: Option<PathBuf>,
    /// Draw the pictures (PNG and SVG) into this directory.
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

/// Finest-grid default and range of `--grid` for line contacts.
pub(crate) const LINE_GRID: (usize, usize, usize) = (2049, 33, (1 << 20) + 1);
/// The same for point contacts, points per direction.
pub(crate) const POINT_GRID: (usize, usize, usize) = (129, 17, 2049);
/// `--max-grid` range: two grids of the ladder (257 then 513 line points, 33 then 65 point
/// nodes) up to the finest a line solve takes, or 2049 per direction for point contacts.
const LINE_MAX_GRID: (usize, usize) = (513, (1 << 20) + 1);
/// The same for point contacts.
const POINT_MAX_GRID: (usize, usize) = (65, 2049);
/// Most cycles `--max-cycles` takes (as a sweep spec's `max_cycles`).
const MAX_CYCLES: usize = 100_000;
/// Most threads `--threads` takes (as `ehlmap sweep --threads`).
const MAX_THREADS: usize = 4096;

/// `--grid` checked against `(default, min, max)`; `what` names the unit in messages.
fn grid_arg(
    a: &SolveArgs,
    (default, min, max): (usize, usize, usize),
    what: &str,
) -> Result<usize, CliError> {
    let g = a.grid.unwrap_or(default);
    if g < min {
        return Err(input(format!(
            "--grid {g} is too small: at least {min} {what}"
        )));
    }
    if g > max {
        return Err(input(format!(
            "--grid {g} is too large: at most {max} {what}"
        )));
    }
    Ok(g)
}

/// The options that only some methods, contacts or models use, checked before anything else:
/// an option the solve would ignore, or a count out of range, is bad input naming it.
pub(crate) fn check_flags(a: &SolveArgs) -> Result<(), CliError> {
    let method = match a.method {
        MethodArg::Multigrid => None,
        MethodArg::Newton => Some("newton"),
        MethodArg::Relax => Some("relax"),
    };
    if let Some(m) = method {
        for (given, flag) in [
            (a.cycle.is_some(), "--cycle"),
            (a.converge.is_some(), "--converge"),
            (a.max_cycles.is_some(), "--max-cycles"),
            (a.no_fallback, "--no-fallback"),
            (a.accuracy.is_some(), "--accuracy"),
            (a.trace, "--trace"),
            (a.sigma.is_some_and(|s| s != 0.0), "--sigma"),
        ] {
            if given {
                return Err(input(format!(
                    "{flag} applies to --method multigrid only (--method {m} ignores it)"
                )));
            }
        }
        if m == "newton" && a.threads.is_some() {
            return Err(input(
                "--threads applies to --method multigrid and relax only (the dense Newton solve runs on one thread)",
            ));
        }
    }
    // The accuracy ladder runs unless the grid is fixed or a baseline method is chosen.
    let fixed = match (a.grid, method) {
        (Some(g), _) => Some(format!("--grid {g}")),
        (None, Some(m)) => Some(format!("--method {m}")),
        (None, None) => None,
    };
    if let Some(why) = &fixed {
        for (given, flag) in [
            (a.accuracy.is_some(), "--accuracy"),
            (a.full_model, "--full-model"),
            (a.max_grid.is_some(), "--max-grid"),
            (a.formula.is_some(), "--formula"),
        ] {
            if given {
                return Err(input(format!(
                    "{flag} applies to the accuracy ladder, which {why} turns off (the solve \
                     uses one grid); drop {flag}, or drop --grid and let the ladder pick the grid"
                )));
            }
        }
    } else if a.no_estimate {
        return Err(input(
            "--no-estimate applies with --grid only (the accuracy ladder always estimates its error)",
        ));
    }
    if a.full_model && a.formula.is_some() {
        return Err(input(
            "--formula and --full-model exclude each other (the full model is always solved)",
        ));
    }
    if let Some(n) = a.max_cycles {
        if !(1..=MAX_CYCLES).contains(&n) {
            return Err(input(format!(
                "--max-cycles {n} is invalid: give 1 to {MAX_CYCLES}"
            )));
        }
    }
    if a.truncated_domain && a.contact == ContactArg::Line {
        return Err(input(
            "--truncated-domain applies to point contacts only (a line contact's domain has no \
             far field)",
        ));
    }
    if let Some(n) = a.threads {
        if !(1..=MAX_THREADS).contains(&n) {
            return Err(input(format!(
                "--threads {n} is invalid: give 1 to {MAX_THREADS}"
            )));
        }
        if a.contact == ContactArg::Line {
            return Err(input(format!(
                "--threads {n} applies to point contacts only (a line solve runs on one thread)"
            )));
        }
    }
    if a.ph.is_some()
        && a.viscosity == ViscosityArg::Barus
        && a.density == DensityArg::Incompressible
    {
        return Err(input(
            "--ph applies to --viscosity roelands and --density dowson-higginson only (Barus and incompressible do not use it)",
        ));
    }
    Ok(())
}

/// The rough surfaces of the command line: `None` without --sigma; the other roughness options
/// need it.
fn roughness(a: &SolveArgs) -> Result<Option<Roughness>, CliError> {
    let Some(sigma) = a.sigma else {
        for (given, name) in [
            (a.gamma.is_some(), "--gamma"),
            (a.slide_roll.is_some(), "--slide-roll"),
            (a.rough_surface.is_some(), "--rough-surface"),
            (a.ph_over_e.is_some(), "--ph-over-e"),
            (a.eta_beta_sigma.is_some(), "--eta-beta-sigma"),
            (a.sigma_over_beta.is_some(), "--sigma-over-beta"),
        ] {
            if given {
                return Err(input(format!("{name} needs --sigma (the RMS roughness)")));
            }
        }
        return Ok(None);
    };
    let base = Roughness::isotropic(sigma);
    let r = Roughness {
        gamma: a.gamma.unwrap_or(base.gamma),
        slide_roll: a.slide_roll.unwrap_or(base.slide_roll),
        variance_ratio_1: match a.rough_surface {
            None | Some(RoughSurfaceArg::Both) => 0.5,
            Some(RoughSurfaceArg::One) => 1.0,
            Some(RoughSurfaceArg::Two) => 0.0,
        },
        ph_over_e: a.ph_over_e.unwrap_or(base.ph_over_e),
        asperity: AsperityParams {
            eta_beta_sigma: a.eta_beta_sigma.unwrap_or(base.asperity.eta_beta_sigma),
            sigma_over_beta: a.sigma_over_beta.unwrap_or(base.asperity.sigma_over_beta),
        },
        ..base
    };
    // Every input of Roughness::validate is an option of the same name.
    r.validate().map_err(|e| match &e {
        ParamError::Invalid { name, .. } => input(format!("--{}: {e}", name.replace('_', "-"))),
        _ => input(e.to_string()),
    })?;
    Ok(r.is_rough().then_some(r))
}

/// The models of the command line; `alpha_bar` of the case converts Roelands' eta0 into z.
fn build_models(a: &SolveArgs, alpha_bar: f64) -> Result<Models, CliError> {
    let bad = |e: ParamError| input(e.to_string());
    let need_ph = |what: &str| -> Result<f64, CliError> {
        a.ph.ok_or_else(|| input(format!("{what} needs the Hertzian pressure --ph (Pa)")))
    };
    let viscosity = match a.viscosity {
        ViscosityArg::Barus => {
            if a.eta0.is_some() || a.z.is_some() {
                return Err(input("--eta0 and --z apply to --viscosity roelands only"));
            }
            Viscosity::Barus
        }
        ViscosityArg::Roelands => {
            let ph = need_ph("--viscosity roelands")?;
            match (a.eta0, a.z) {
                (Some(eta0), None) => match Viscosity::roelands_from_eta0(eta0, ph, alpha_bar) {
                    Ok(v) => v,
                    // eta0 and ph are valid, the z derived from them is not: with L = 0
                    // (alpha = 0) name L, the input that makes it zero.
                    Err(ParamError::Input(_)) if a.l == 0.0 => {
                        return Err(input(format!(
                            "--eta0 {} with L = 0: Roelands' z = alpha p0/(ln eta0 + 9.67) is 0 \
                             when alpha = 0; give L > 0, or --z",
                            num(eta0)
                        )))
                    }
                    Err(e) => return Err(bad(e)),
                },
                (None, Some(z)) => {
                    let v = Viscosity::Roelands { z, ph_pa: ph };
                    v.validate().map_err(bad)?;
                    v
                }
                _ => {
                    return Err(input(
                        "--viscosity roelands needs exactly one of --eta0 (Pa s) or --z",
                    ))
                }
            }
        }
    };
    let density = match a.density {
        DensityArg::Incompressible => Density::Incompressible,
        DensityArg::DowsonHigginson => Density::DowsonHigginson {
            ph_pa: need_ph("--density dowson-higginson")?,
        },
    };
    let elasticity = match a.elasticity {
        ElasticityArg::Elastic => Elasticity::Elastic,
        ElasticityArg::Rigid => Elasticity::Rigid,
    };
    Ok(Models {
        elasticity,
        viscosity,
        density,
        roughness: roughness(a)?,
    })
}

fn line_case(a: &SolveArgs) -> Result<LineCase, CliError> {
    let bad = |e: ParamError| input(e.to_string());
    if a.d.is_some() {
        return Err(input("--D applies to point contacts only"));
    }
    if a.fields.is_some() {
        return Err(input(
            "--fields applies to point contacts only (use --profile for line contacts)",
        ));
    }
    let grid = grid_arg(a, LINE_GRID, "points")?;
    if a.method == MethodArg::Newton && grid > 4097 {
        return Err(input(format!(
            "--method newton with --grid {grid}: the dense Jacobian needs O(N^2) memory and O(N^3) time; use at most 4097"
        )));
    }
    // Validate M and L first so that a bad M is named before model errors.
    let venner = LineCase::new(a.m, a.l).map_err(bad)?.venner();
    let models = build_models(a, venner.alpha_bar)?;
    LineCase::with_models(a.m, a.l, models).map_err(bad)
}

fn point_case(a: &SolveArgs) -> Result<PointCase, CliError> {
    let bad = |e: ParamError| input(e.to_string());
    if a.method == MethodArg::Newton && a.grid.unwrap_or(POINT_GRID.0) > 33 {
        return Err(input(format!(
            "--method newton with a point contact on --grid {}: the dense 2D Jacobian costs O(N^3); use --grid 33 or less",
            a.grid.unwrap_or(POINT_GRID.0)
        )));
    }
    if a.profile.is_some() {
        return Err(input(
            "--profile applies to line contacts only (use --fields for point contacts)",
        ));
    }
    // A point contact is a circular one unless --D says otherwise.
    let d = a.d.unwrap_or(1.0);
    grid_arg(a, POINT_GRID, "points per direction")?;
    // M, L and D before the models, so that a bad value is named first.
    let venner = PointCase::new(a.m, a.l, d).map_err(bad)?.venner();
    let models = build_models(a, venner.alpha_bar)?;
    PointCase::with_models(a.m, a.l, d, models).map_err(bad)
}

/// The case of the command line: a line contact, or a point contact with `--D`.
pub(crate) fn case_arg(a: &SolveArgs) -> Result<Case, CliError> {
    match a.contact {
        ContactArg::Line => line_case(a).map(Case::Line),
        ContactArg::Point => point_case(a).map(Case::Point),
    }
}

/// A valid --accuracy target.
fn accuracy_arg(t: f64) -> Result<f64, CliError> {
    if t.is_finite() && t > 0.0 && t < 1.0 {
        Ok(t)
    } else {
        Err(input(format!(
            "--accuracy {} is invalid: give a relative accuracy in (0, 1), e.g. 0.005",
            num(t)
        )))
    }
}

/// A valid time limit given by option `flag`: seconds, positive and finite.
pub(crate) fn time_limit_arg(flag: &str, t: f64) -> Result<f64, CliError> {
    if t.is_finite() && t > 0.0 {
        Ok(t)
    } else {
        Err(input(format!(
            "{flag} {} is invalid: give the seconds a solve may take, > 0",
            num(t)
        )))
    }
}

/// A valid --max-grid for the contact (with --accuracy).
fn max_grid_arg(g: usize, contact: Contact) -> Result<usize, CliError> {
    let ((lo, hi), what) = match contact {
        Contact::Line => (LINE_MAX_GRID, "points for line contacts"),
        Contact::Point => (POINT_MAX_GRID, "points per direction for point contacts"),
    };
    if g < lo {
        return Err(input(format!(
            "--max-grid {g} is too small: the accuracy ladder needs two grids, at least {lo} {what}"
        )));
    }
    if g > hi {
        return Err(input(format!(
            "--max-grid {g} is too large: at most {hi} {what}"
        )));
    }
    Ok(g)
}

/// The solve's parameters from the command line.
pub(crate) fn params_arg(a: &SolveArgs, case: &Case) -> Result<SolveParams, CliError> {
    let point = matches!(case, Case::Point(_));
    let time_limit = a
        .time_limit
        .map(|t| time_limit_arg("--time-limit", t))
        .transpose()?;
    Ok(SolveParams {
        method: match a.method {
            MethodArg::Multigrid => Method::Multigrid,
            MethodArg::Newton => Method::Newton,
            MethodArg::Relax => Method::Relax,
        },
        grid: a.grid,
        cycle: match a.cycle {
            Some(CycleArg::W) => CycleType::W,
            Some(CycleArg::V) | None => CycleType::V,
        },
        converge: match a.converge {
            Some(ConvergeArg::Tight) => Converge::Tight,
            Some(ConvergeArg::Fast) | None => Converge::Fast,
        },
        max_cycles: a.max_cycles,
        fallback: !a.no_fallback,
        accuracy: match (a.grid, a.method) {
            (None, MethodArg::Multigrid) => {
                Some(accuracy_arg(a.accuracy.unwrap_or(DEFAULT_ACCURACY))?)
            }
            _ => None,
        },
        estimate: !a.no_estimate,
        max_grid: a
            .max_grid
            .map(|g| max_grid_arg(g, case.contact()))
            .transpose()?,
        full_model: a.full_model,
        keep_fields: a.profile.is_some() || a.fields.is_some() || a.plot.is_some(),
        parallel: point && a.threads.is_some(),
        observer: if a.trace {
            Some(Observer(print_cycle))
        } else {
            solve_progress::observer(a.progress)
        },
        point_domain: PointDomainParams {
            far_field: !a.truncated_domain,
            ..PointDomainParams::default()
        },
        formula: a
            .formula
            .as_deref()
            .map(|p| formula_arg("--formula", p))
            .transpose()?,
        ..SolveParams::default()
    }
    .time_limit(time_limit))
}

/// Print one multigrid cycle (`--trace`).
fn print_cycle(e: &CycleEvent) {
    note!("{e}");
}
