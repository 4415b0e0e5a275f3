//! `ehlmap solve`: one line or point case in Moes' parameters, solved by [`ehlmap::strategy::solve_case::solve`];
//! prints the readable summary or one JSON object (the [`Outputs`] fields), and writes the
//! profile, fields or pictures when asked. Bad input is an [`InputError`] (exit code 2) naming
//! the value; a solve that fails numerically is still printed with its status (exit code 0).

use crate::cli::error::InputError;
use crate::cli::output::report_plot;
use clap::ValueEnum;
use ehlmap::model::case::{Case, Elasticity, LineCase, Models, ParamError, PointCase};
use ehlmap::model::lubricant::{Density, Viscosity};
use ehlmap::render::style::RenderError;
use ehlmap::solve::params::Method;
use ehlmap::solve::params::{Converge, CycleType};
use ehlmap::solve::solution::{ModelUsed, Outputs, Solution};
use ehlmap::solve::{CycleEvent, Observer};
use ehlmap::strategy::solve_case::{solve, SolveParams};
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
    #[arg(long = "M")]
    pub m: f64,
    /// Moes lubricant parameter L >= 0.
    #[arg(long = "L", default_value_t = 0.0)]
    pub l: f64,
    /// Ellipticity D = Rx/Ry in (0, 1] (point contacts).
    #[arg(long = "D")]
    pub d: Option<f64>,
    #[arg(long, value_enum, default_value = "elastic")]
    pub elasticity: ElasticityArg,
    #[arg(long, value_enum, default_value = "barus")]
    pub viscosity: ViscosityArg,
    /// Roelands: ambient viscosity eta0 in Pa s (or give --z).
    #[arg(long)]
    pub eta0: Option<f64>,
    /// Roelands pressure-viscosity index z (or give --eta0).
    #[arg(long)]
    pub z: Option<f64>,
    /// Hertzian pressure p_h in Pa (Roelands and Dowson-Higginson need it).
    #[arg(long)]
    pub ph: Option<f64>,
    #[arg(long, value_enum, default_value = "incompressible")]
    pub density: DensityArg,
    /// Solver: full multigrid, or the baselines (dense Newton, single-grid relaxation).
    #[arg(long, value_enum, default_value = "multigrid")]
    pub method: MethodArg,
    /// Points of the finest grid (rounded up to 2^k n0 + 1): default 2049 for line contacts;
    /// per direction for point contacts, default 129, 17 to 2049.
    #[arg(long)]
    pub grid: Option<usize>,
    #[arg(long, value_enum, default_value = "v")]
    pub cycle: CycleArg,
    /// Stopping rule: at the discretisation error (fast) or at the tolerances (tight).
    #[arg(long, value_enum, default_value = "fast")]
    pub converge: ConvergeArg,
    /// Target relative accuracy of H_c and H_min: pick the cheapest adequate model (rigid,
    /// isoviscous, closed form; see --full-model) and refine the grid from 257 points until the
    /// Richardson estimate meets it (up to --max-grid); reports model_used, level,
    /// error_estimate and accuracy_met.
    #[arg(long)]
    pub accuracy: Option<f64>,
    /// With --accuracy: always solve the full model (no model selection).
    #[arg(long)]
    pub full_model: bool,
    /// Largest grid the accuracy target may use.
    #[arg(long, default_value_t = 16385)]
    pub max_grid: usize,
    /// Cycles allowed on the finest level (default: the contact's, 60 for line contacts, 40 for
    /// point contacts).
    #[arg(long)]
    pub max_cycles: Option<usize>,
    /// Do not retry a failed solve with conservative settings.
    #[arg(long)]
    pub no_fallback: bool,
    /// Point contacts: relax the grid rows in parallel (zebra order) on this many threads
    /// (default: one thread, Gauss-Seidel row order).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Print every multigrid cycle (level, cycle, residual, load error, H_c, work units) to
    /// stderr.
    #[arg(long)]
    pub trace: bool,
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
const LINE_GRID: (usize, usize, usize) = (2049, 33, (1 << 20) + 1);
/// The same for point contacts, points per direction.
const POINT_GRID: (usize, usize, usize) = (129, 17, 2049);
/// Point grids of the accuracy ladder are at most this per direction, whatever `--max-grid`.
const POINT_MAX_GRID: usize = 513;

/// `--grid` checked against `(default, min, max)`; `what` names the unit in messages.
fn grid_arg(
    a: &SolveArgs,
    (default, min, max): (usize, usize, usize),
    what: &str,
) -> Result<usize, InputError> {
    let g = a.grid.unwrap_or(default);
    if g < min {
        return Err(InputError(format!(
            "--grid {g} is too small: at least {min} {what}"
        )));
    }
    if g > max {
        return Err(InputError(format!(
            "--grid {g} is too large: at most {max} {what}"
        )));
    }
    Ok(g)
}

/// The models of the command line; `alpha_bar` of the case converts Roelands' eta0 into z.
fn build_models(a: &SolveArgs, alpha_bar: f64) -> Result<Models, InputError> {
    let bad = |e: ParamError| InputError(e.to_string());
    let need_ph = |what: &str| -> Result<f64, InputError> {
        a.ph.ok_or_else(|| InputError(format!("{what} needs the Hertzian pressure --ph (Pa)")))
    };
    let viscosity = match a.viscosity {
        ViscosityArg::Barus => {
            if a.eta0.is_some() || a.z.is_some() {
                return Err(InputError(
                    "--eta0 and --z apply to --viscosity roelands only".into(),
                ));
            }
            Viscosity::Barus
        }
        ViscosityArg::Roelands => {
            let ph = need_ph("--viscosity roelands")?;
            match (a.eta0, a.z) {
                (Some(eta0), None) => {
                    Viscosity::roelands_from_eta0(eta0, ph, alpha_bar).map_err(bad)?
                }
                (None, Some(z)) => {
                    let v = Viscosity::Roelands { z, ph_pa: ph };
                    v.validate().map_err(bad)?;
                    v
                }
                _ => {
                    return Err(InputError(
                        "--viscosity roelands needs exactly one of --eta0 (Pa s) or --z".into(),
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
    })
}

fn line_case(a: &SolveArgs) -> Result<LineCase, InputError> {
    let bad = |e: ParamError| InputError(e.to_string());
    if a.d.is_some() {
        return Err(InputError("--D applies to point contacts only".into()));
    }
    if a.fields.is_some() {
        return Err(InputError(
            "--fields applies to point contacts only (use --profile for line contacts)".into(),
        ));
    }
    let grid = grid_arg(a, LINE_GRID, "points")?;
    if a.method == MethodArg::Newton && grid > 4097 {
        return Err(InputError(format!(
            "--method newton with --grid {grid}: the dense Jacobian needs O(N^2) memory and O(N^3) time; use at most 4097"
        )));
    }
    // Validate M and L first so that a bad M is named before model errors.
    let venner = LineCase::new(a.m, a.l).map_err(bad)?.venner();
    let models = build_models(a, venner.alpha_bar)?;
    LineCase::with_models(a.m, a.l, models).map_err(bad)
}

fn point_case(a: &SolveArgs) -> Result<PointCase, InputError> {
    let bad = |e: ParamError| InputError(e.to_string());
    if a.method == MethodArg::Newton && a.grid.unwrap_or(POINT_GRID.0) > 33 {
        return Err(InputError(format!(
            "--method newton with a point contact on --grid {}: the dense 2D Jacobian costs O(N^3); use --grid 33 or less",
            a.grid.unwrap_or(POINT_GRID.0)
        )));
    }
    if a.profile.is_some() {
        return Err(InputError(
            "--profile applies to line contacts only (use --fields for point contacts)".into(),
        ));
    }
    let d = a.d.ok_or_else(|| {
        InputError("--contact point needs --D, the ellipticity Rx/Ry in (0, 1]".into())
    })?;
    grid_arg(a, POINT_GRID, "points per direction")?;
    // M, L and D before the models, so that a bad value is named first.
    let venner = PointCase::new(a.m, a.l, d).map_err(bad)?.venner();
    let models = build_models(a, venner.alpha_bar)?;
    PointCase::with_models(a.m, a.l, d, models).map_err(bad)
}

/// The case of the command line: a line contact, or a point contact with `--D`.
fn case_arg(a: &SolveArgs) -> Result<Case, InputError> {
    match a.contact {
        ContactArg::Line => line_case(a).map(Case::Line),
        ContactArg::Point => point_case(a).map(Case::Point),
    }
}

/// A valid --accuracy target.
fn accuracy_arg(t: f64) -> Result<f64, InputError> {
    if t.is_finite() && t > 0.0 && t < 1.0 {
        Ok(t)
    } else {
        Err(InputError(format!(
            "--accuracy {t} is invalid: give a relative accuracy in (0, 1), e.g. 0.005"
        )))
    }
}

/// The solve's parameters from the command line.
fn params_arg(a: &SolveArgs, case: &Case) -> Result<SolveParams, InputError> {
    let point = matches!(case, Case::Point(_));
    Ok(SolveParams {
        method: match a.method {
            MethodArg::Multigrid => Method::Multigrid,
            MethodArg::Newton => Method::Newton,
            MethodArg::Relax => Method::Relax,
        },
        grid: a.grid,
        cycle: match a.cycle {
            CycleArg::V => CycleType::V,
            CycleArg::W => CycleType::W,
        },
        converge: match a.converge {
            ConvergeArg::Fast => Converge::Fast,
            ConvergeArg::Tight => Converge::Tight,
        },
        max_cycles: a.max_cycles,
        fallback: !a.no_fallback,
        accuracy: a.accuracy.map(accuracy_arg).transpose()?,
        max_grid: Some(if point {
            a.max_grid.min(POINT_MAX_GRID)
        } else {
            a.max_grid
        }),
        full_model: a.full_model,
        keep_fields: a.profile.is_some() || a.fields.is_some() || a.plot.is_some(),
        parallel: point && a.threads.is_some(),
        observer: a.trace.then_some(Observer(print_cycle)),
        ..SolveParams::default()
    })
}

/// Print one multigrid cycle (`--trace`).
fn print_cycle(e: &CycleEvent) {
    eprintln!("{e}");
}

/// Solve on `--threads` threads when given (point contacts: parallel rows), else on this one.
fn solve_arg(a: &SolveArgs, case: &Case, p: &SolveParams) -> Result<Solution, InputError> {
    match a.threads {
        Some(0) => Err(InputError("--threads 0 is invalid: give 1 or more".into())),
        Some(n) if matches!(case, Case::Point(_)) => {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| InputError(format!("--threads {n}: {e}")))?;
            Ok(pool.install(|| solve(case, p)))
        }
        _ => Ok(solve(case, p)),
    }
}

/// The footer metadata of a profile or fields file.
fn file_meta(case: &Case, o: &Outputs) -> Vec<(&'static str, String)> {
    let mut meta = vec![
        ("contact", case.contact().to_string()),
        ("M", case.m().to_string()),
        ("L", case.l().to_string()),
    ];
    if let Case::Point(c) = case {
        meta.push(("D", c.d.to_string()));
        meta.push(("k", c.ellipse().k.to_string()));
    }
    meta.push(("status", o.status.to_string()));
    meta
}

/// `--profile` (line) or `--fields` (point): write the file, or say why there is none.
fn write_fields_arg(a: &SolveArgs, case: &Case, s: &Solution) -> Result<(), InputError> {
    let meta = file_meta(case, &s.outputs);
    match (&a.profile, &a.fields, &s.profile, &s.fields) {
        (Some(path), _, Some(prof), _) => ehlmap::store::profile::write_profile(path, prof, &meta)
            .map_err(|e| InputError(format!("--profile: {e}"))),
        (_, Some(path), _, Some(f)) => ehlmap::store::fields::write_fields(path, f, &meta)
            .map_err(|e| InputError(format!("--fields: {e}"))),
        (Some(path), ..) | (_, Some(path), ..) => {
            // A failed solve is a result (exit 0), but say why the file is missing.
            eprintln!(
                "ehlmap: the solve returned no profile or fields ({}), {} not written",
                s.outputs.status,
                path.display()
            );
            Ok(())
        }
        _ => Ok(()),
    }
}

/// `--plot DIR`: the pictures of the solution.
fn plot_arg(dir: &std::path::Path, case: &Case, s: &Solution) {
    let stem = match case {
        Case::Line(c) => format!("line-M{}-L{}", c.m, c.l),
        Case::Point(c) => format!("point-M{}-L{}-D{}", c.m, c.l, c.d),
    };
    report_plot(match (&s.profile, &s.fields) {
        (Some(prof), _) => ehlmap::render::pictures::draw_line(dir, &stem, prof, &s.outputs),
        (_, Some(f)) => ehlmap::render::pictures::draw_point(dir, &stem, f, &s.outputs),
        _ => Err(RenderError(format!(
            "the solve returned no profile or fields ({})",
            s.outputs.status
        ))),
    });
}

/// Run `ehlmap solve`; returns the process exit code.
pub fn run_solve(a: &SolveArgs) -> Result<i32, InputError> {
    let case = case_arg(a)?;
    let params = params_arg(a, &case)?;
    let s = solve_arg(a, &case, &params)?;
    write_fields_arg(a, &case, &s)?;
    if let Some(dir) = &a.plot {
        plot_arg(dir, &case, &s);
    }
    if a.json {
        println!(
            "{}",
            serde_json::to_string(&s.outputs).expect("outputs serialise")
        );
    } else {
        print!("{}", summary(&case, &s.outputs));
    }
    Ok(0)
}

/// The readable summary of a solve, line or point contact.
fn summary(case: &Case, o: &Outputs) -> String {
    let m = case.models();
    let head = match case {
        Case::Line(c) => format!("line contact  M = {}  L = {}", c.m, c.l),
        Case::Point(c) => format!(
            "point contact  M = {}  L = {}  D = {}  (k = {:.6})",
            c.m,
            c.l,
            c.d,
            c.ellipse().k
        ),
    };
    let spike = o.spike.map_or("none".to_string(), |s| {
        format!("P = {:.4} at X = {:.4}", s.p, s.x)
    });
    let (h_c_at, h_min_at, f_name) = match o.y_min {
        Some(y) => (
            "X = Y = 0",
            format!("X = {:.4}, Y = {y:.4}", o.x_min),
            "f Rx/b",
        ),
        None => ("X = 0", format!("X = {:.4}", o.x_min), "f R/b"),
    };
    let grid = match case {
        Case::Point(_) if o.model_used == ModelUsed::SlenderLine => {
            format!("{} points (line solve)", o.grid)
        }
        Case::Point(_) => format!("{} x {} points", o.grid, o.grid),
        Case::Line(_) => format!("{} points", o.grid),
    };
    let rows = [
        ("status", format!("{}: {}", o.status, o.reason)),
        (
            "H_c",
            format!("{:.6}   (film at {h_c_at}, Moes units)", o.h_c),
        ),
        (
            "H_c_pmax",
            format!("{:.6}   (film at the pressure maximum)", o.h_c_pmax),
        ),
        ("H_min", format!("{:.6}   at {h_min_at}", o.h_min)),
        ("P_max", format!("{:.6}", o.p_max)),
        ("spike", spike),
        ("H0", format!("{:.6}", o.h0)),
        (f_name, format!("{:.6e}", o.f)),
        ("load error", format!("{:.2e}", o.load_error)),
        (
            "grid",
            format!(
                "{grid}, {} levels, {:.1} work units, {:.3} s",
                o.levels, o.work_units, o.wall_s
            ),
        ),
    ];
    let mut out = format!(
        "{head}  ({}, {}, {})\n",
        m.elasticity,
        m.viscosity.name(),
        m.density.name()
    );
    for (name, value) in rows {
        out += &format!("{name:<15}{value}\n");
    }
    out + &model_line(o)
}

/// The model and error-estimate line of a summary (accuracy targets only).
fn model_line(o: &Outputs) -> String {
    match o.error_estimate {
        Some(e) => format!(
            "model          {}, level {}, error estimate {e:.1e}\n",
            o.model_used,
            o.level.map_or("-".to_string(), |l| l.to_string())
        ),
        None if o.model_used != ModelUsed::Full => format!("model          {}\n", o.model_used),
        None => String::new(),
    }
}
