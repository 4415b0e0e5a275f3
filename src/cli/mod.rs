//! The command line: a thin layer over the library. Bad input exits with code 2 and a one-line
//! message naming the bad value; a solve that fails numerically still prints its outputs with
//! its status (exit code 0: a failure is a result), so scripts read `status`.
//!
//! `--contact point --D d` solves a point contact: `--grid` counts points per direction, the
//! fields go to `--fields FILE.parquet`; `--method newton` is limited to
//! 33 x 33 points there, and `--profile` (line only) is an input error.

pub mod bench;
pub mod fit;
pub mod sweep;

use crate::model::case::{Elasticity, LineCase, Models, ParamError, PointCase};
use crate::model::lubricant::{Density, Viscosity};
use crate::solve::line::multigrid::CycleType;
use crate::solve::line::{solve_line, LineSolveParams, Method};
use crate::solve::point::{solve_point, PointSolveParams};
use crate::strategy::accuracy::solve_line_to_accuracy;
use crate::strategy::accuracy::solve_point_to_accuracy;
use crate::strategy::select::{solve_line_selected, solve_point_selected};
use clap::{Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

#[derive(Parser, Debug)]
#[command(
    name = "ehlmap",
    version,
    about = "Steady isothermal EHL by full multigrid"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Solve one contact and print its film thickness, pressure and convergence.
    Solve(SolveArgs),
    /// Run a sweep spec (TOML) into a Parquet dataset: resumable, shardable.
    Sweep(crate::cli::sweep::SweepArgs),
    /// Fit a Moes-style film formula to sweep datasets; report, fit.json and charts.
    Fit(crate::cli::fit::FitArgs),
    /// A dimensional case (SI units in a TOML file): groups, numerical solve, published formulas.
    Case(CaseArgs),
    /// Speed against accuracy of every method over a grid ladder (Parquet table and charts).
    Bench(crate::cli::bench::BenchArgs),
    /// Where methods fail: each method's status over an (M, L) map.
    Stability(crate::cli::bench::StabilityArgs),
    /// Charts: `regimes`, the regime map in Moes' (M, L) axes.
    Chart(crate::model::regimes::ChartArgs),
}

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub enum ContactArg {
    Line,
    Point,
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
    #[arg(long, value_parser = ["elastic", "rigid"], default_value = "elastic")]
    pub elasticity: String,
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
    /// Cycles allowed on the finest level (default 60 for line contacts, the point solver's
    /// default for point contacts).
    #[arg(long)]
    pub max_cycles: Option<usize>,
    /// Do not retry a failed solve with conservative settings.
    #[arg(long)]
    pub no_fallback: bool,
    /// Point contacts: relax the grid rows in parallel (zebra order) on this many threads
    /// (default: one thread, Gauss-Seidel row order).
    #[arg(long)]
    pub threads: Option<usize>,
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
/// `--max-cycles` default for line contacts.
const LINE_MAX_CYCLES: usize = 60;

#[derive(clap::Args, Debug)]
pub struct CaseArgs {
    /// The case file (TOML, SI units), e.g. sweeps/cases/example-7-1.toml.
    pub file: PathBuf,
    /// Print the report as JSON.
    #[arg(long)]
    pub json: bool,
    /// Only the groups and formulas, no numerical solve.
    #[arg(long)]
    pub no_solve: bool,
    /// Draw the pictures (PNG and SVG) of the solution into this directory.
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

/// Run `ehlmap case`.
pub fn run_case(a: &CaseArgs) -> Result<i32, InputError> {
    let path = a.file.display();
    let spec = crate::cases::read_case(&a.file).map_err(InputError)?;
    if a.plot.is_some() && a.no_solve {
        return Err(InputError("--plot needs a solve: drop --no-solve".into()));
    }
    let (r, fields) = spec
        .run(!a.no_solve, a.plot.is_some())
        .map_err(|e| InputError(format!("{path}: {e}")))?;
    if let (Some(dir), Some(o)) = (&a.plot, &r.numerical) {
        let stem = a
            .file
            .file_stem()
            .map_or("case".into(), |s| s.to_string_lossy());
        let files = match &fields {
            Some(crate::cases::CaseFields::Line(p)) => {
                crate::render::pictures::draw_line(dir, &stem, p, o)
            }
            Some(crate::cases::CaseFields::Point(f)) => {
                crate::render::pictures::draw_point(dir, &stem, f, o)
            }
            None => Err(format!("the solve returned no fields ({})", o.status)),
        };
        report_plot(files);
    }
    if a.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&r).expect("report serialises")
        );
    } else {
        print!("{}", crate::cases::summary(&r));
    }
    Ok(0)
}

/// Say which pictures were written (stderr), or why none were (a failed solve is a result).
fn report_plot(files: Result<Vec<PathBuf>, String>) {
    match files {
        Ok(f) => eprintln!(
            "ehlmap: --plot wrote {} files, e.g. {}",
            f.len(),
            f[0].display()
        ),
        Err(e) => eprintln!("ehlmap: --plot: no pictures: {e}"),
    }
}

/// An input error: printed as one line, exit code 2.
#[derive(Debug)]
pub struct InputError(pub String);

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
    let elasticity = if a.elasticity == "rigid" {
        Elasticity::Rigid
    } else {
        Elasticity::Elastic
    };
    Ok(Models {
        elasticity,
        viscosity,
        density,
    })
}

fn build_case(a: &SolveArgs) -> Result<LineCase, InputError> {
    let bad = |e: ParamError| InputError(e.to_string());
    if a.d.is_some() {
        return Err(InputError("--D applies to point contacts only".into()));
    }
    if a.fields.is_some() {
        return Err(InputError(
            "--fields applies to point contacts only (use --profile for line contacts)".into(),
        ));
    }
    grid_arg(a, LINE_GRID, "points")?;
    // Validate M and L first so that a bad M is named before model errors.
    let venner = LineCase::new(a.m, a.l).map_err(bad)?.venner();
    let models = build_models(a, venner.alpha_bar)?;
    LineCase::with_models(a.m, a.l, models).map_err(bad)
}

fn build_point_case(a: &SolveArgs) -> Result<PointCase, InputError> {
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

fn cycle_type(c: CycleArg) -> CycleType {
    match c {
        CycleArg::V => CycleType::V,
        CycleArg::W => CycleType::W,
    }
}

/// Run `ehlmap solve`; returns the process exit code.
pub fn run_solve(a: &SolveArgs) -> Result<i32, InputError> {
    if a.contact == ContactArg::Point {
        return run_solve_point(a);
    }
    let case = build_case(a)?;
    let grid = a.grid.unwrap_or(LINE_GRID.0);
    let mut p = LineSolveParams::default();
    p.mg.grid = grid;
    p.mg.max_cycles = a.max_cycles.unwrap_or(LINE_MAX_CYCLES);
    p.mg.cycle = cycle_type(a.cycle);
    p.fallback = !a.no_fallback;
    p.method = method_of(a.method);
    if p.method == Method::Newton && grid > 4097 {
        return Err(InputError(format!(
            "--method newton with --grid {grid}: the dense Jacobian needs O(N^2) memory and O(N^3) time; use at most 4097"
        )));
    }
    p.keep_profile = a.profile.is_some() || a.plot.is_some();
    let s = match a.accuracy {
        Some(t) if a.full_model => solve_line_to_accuracy(&case, &p, accuracy_arg(t)?, a.max_grid),
        Some(t) => solve_line_selected(&case, &p, accuracy_arg(t)?, a.max_grid).0,
        None => solve_line(&case, &p),
    };
    if let (Some(path), Some(prof)) = (&a.profile, &s.profile) {
        let meta = [
            ("contact", "line".to_string()),
            ("M", case.m.to_string()),
            ("L", case.l.to_string()),
            ("status", s.outputs.status.to_string()),
        ];
        crate::store::profile::write_profile(path, prof, &meta)
            .map_err(|e| InputError(format!("--profile: {e}")))?;
    }
    if let Some(dir) = &a.plot {
        let stem = format!("line-M{}-L{}", case.m, case.l);
        report_plot(match &s.profile {
            Some(prof) => crate::render::pictures::draw_line(dir, &stem, prof, &s.outputs),
            None => Err("the solve returned no profile".into()),
        });
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

fn method_of(m: MethodArg) -> Method {
    match m {
        MethodArg::Multigrid => Method::Multigrid,
        MethodArg::Newton => Method::Newton,
        MethodArg::Relax => Method::Relax,
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

/// `ehlmap solve --contact point`: same exit codes and JSON names as the line solve, plus `D`,
/// `k` and `Y_min`.
fn run_solve_point(a: &SolveArgs) -> Result<i32, InputError> {
    let case = build_point_case(a)?;
    let mut p = PointSolveParams::default();
    p.mg.grid = a.grid.unwrap_or(POINT_GRID.0);
    if let Some(n) = a.max_cycles {
        p.mg.max_cycles = n;
    }
    p.mg.cycle = cycle_type(a.cycle);
    p.method = method_of(a.method);
    p.fallback = !a.no_fallback;
    p.keep_fields = a.fields.is_some() || a.plot.is_some();
    let accuracy = a.accuracy.map(accuracy_arg).transpose()?;
    let run = |p: &PointSolveParams| match accuracy {
        // Point grids are per direction: at most 513 x 513 unless --max-grid is lower.
        Some(t) if a.full_model => solve_point_to_accuracy(&case, p, t, a.max_grid.min(513)),
        Some(t) => solve_point_selected(&case, p, t, a.max_grid.min(513)).0,
        None => solve_point(&case, p),
    };
    let s = match a.threads {
        Some(0) => return Err(InputError("--threads 0 is invalid: give 1 or more".into())),
        Some(n) => {
            p.mg.parallel = true;
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| InputError(format!("--threads {n}: {e}")))?;
            pool.install(|| run(&p))
        }
        None => run(&p),
    };
    if let Some(path) = &a.fields {
        match &s.fields {
            Some(f) => {
                let meta = [
                    ("contact", "point".to_string()),
                    ("M", case.m.to_string()),
                    ("L", case.l.to_string()),
                    ("D", case.d.to_string()),
                    ("k", case.ellipse().k.to_string()),
                    ("status", s.outputs.status.to_string()),
                ];
                crate::store::fields::write_fields(path, f, &meta)
                    .map_err(|e| InputError(format!("--fields: {e}")))?;
            }
            // A failed solve is a result (exit 0), but say why the file is missing.
            None => eprintln!(
                "ehlmap: --fields: the solve returned no fields ({}), {} not written",
                s.outputs.status,
                path.display()
            ),
        }
    }
    if let Some(dir) = &a.plot {
        let stem = format!("point-M{}-L{}-D{}", case.m, case.l, case.d);
        report_plot(match &s.fields {
            Some(f) => crate::render::pictures::draw_point(dir, &stem, f, &s.outputs),
            None => Err(format!(
                "the solve returned no fields ({})",
                s.outputs.status
            )),
        });
    }
    if a.json {
        println!(
            "{}",
            serde_json::to_string(&s.outputs).expect("outputs serialise")
        );
    } else {
        print!("{}", point_summary(&case, &s.outputs));
    }
    Ok(0)
}

fn point_summary(case: &PointCase, o: &crate::solve::solution::Outputs) -> String {
    let m = &case.models;
    let spike = o.spike.map_or("none".to_string(), |s| {
        format!("P = {:.4} at X = {:.4}", s.p, s.x)
    });
    let y_min = o.y_min.unwrap_or(f64::NAN);
    format!(
        "point contact  M = {}  L = {}  D = {}  (k = {:.6})  ({}, {}, {})\n\
         status         {}: {}\n\
         H_c            {:.6}   (film at X = Y = 0, Moes units)\n\
         H_c_pmax       {:.6}   (film at the pressure maximum)\n\
         H_min          {:.6}   at X = {:.4}, Y = {:.4}\n\
         P_max          {:.6}\n\
         spike          {}\n\
         H0             {:.6}\n\
         f Rx/b         {:.6e}\n\
         load error     {:.2e}\n\
         grid           {}, {} levels, {:.1} work units, {:.3} s\n",
        case.m,
        case.l,
        case.d,
        case.ellipse().k,
        m.elasticity,
        m.viscosity.name(),
        m.density.name(),
        o.status,
        o.reason,
        o.h_c,
        o.h_c_pmax,
        o.h_min,
        o.x_min,
        y_min,
        o.p_max,
        spike,
        o.h0,
        o.f,
        o.load_error,
        if o.model_used == crate::solve::solution::ModelUsed::SlenderLine.as_str() {
            format!("{} points (line solve)", o.grid)
        } else {
            format!("{} x {} points", o.grid, o.grid)
        },
        o.levels,
        o.work_units,
        o.wall_s
    ) + &model_line(o)
}

/// The model and error-estimate line of a summary (accuracy targets only).
fn model_line(o: &crate::solve::solution::Outputs) -> String {
    match o.error_estimate {
        Some(e) => format!(
            "model          {}, level {}, error estimate {e:.1e}\n",
            o.model_used,
            o.level.map_or("-".to_string(), |l| l.to_string())
        ),
        None if o.model_used != "full" => format!("model          {}\n", o.model_used),
        None => String::new(),
    }
}

fn summary(case: &LineCase, o: &crate::solve::solution::Outputs) -> String {
    let m = &case.models;
    let spike = o.spike.map_or("none".to_string(), |s| {
        format!("P = {:.4} at X = {:.4}", s.p, s.x)
    });
    format!(
        "line contact  M = {}  L = {}  ({}, {}, {})\n\
         status        {}: {}\n\
         H_c           {:.6}   (film at X = 0, Moes units)\n\
         H_c_pmax      {:.6}   (film at the pressure maximum)\n\
         H_min         {:.6}   at X = {:.4}\n\
         P_max         {:.6}\n\
         spike         {}\n\
         H0            {:.6}\n\
         f R/b         {:.6e}\n\
         load error    {:.2e}\n\
         grid          {} points, {} levels, {:.1} work units, {:.3} s\n",
        case.m,
        case.l,
        m.elasticity,
        m.viscosity.name(),
        m.density.name(),
        o.status,
        o.reason,
        o.h_c,
        o.h_c_pmax,
        o.h_min,
        o.x_min,
        o.p_max,
        spike,
        o.h0,
        o.f,
        o.load_error,
        o.grid,
        o.levels,
        o.work_units,
        o.wall_s
    ) + &model_line(o)
}
