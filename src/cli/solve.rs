//! `ehlmap solve`: one line or point case in Moes' parameters, solved by [`ehlmap::strategy::solve_case::solve`];
//! prints the readable summary or one JSON object (the [`Outputs`] fields), and writes the
//! profile, fields or pictures when asked. Every option is checked before the solve
//! ([`crate::cli::solve_args`]); an output that cannot be written is an I/O error (exit code 1),
//! found before the solve where it can be. A solve that fails numerically is still printed with its
//! status (exit code 0).

use crate::cli::error::{io, CliError};
use crate::cli::limits::{check_memory, estimate, Solver};
use crate::cli::output::{check_file, note, out, outln, prepare_dir};
use crate::cli::solve_args::{
    case_arg, check_flags, params_arg, MethodArg, SolveArgs, LINE_GRID, POINT_GRID,
};
use ehlmap::model::case::{Case, Contact};
use ehlmap::model::error::num;
use ehlmap::solve::solution::{Outputs, Solution};
use ehlmap::strategy::solve_case::{default_max_grid, solve, SolveParams};

/// The solve's estimated memory against the memory there is (exit 2 naming the grid).
fn check_solve_memory(a: &SolveArgs, case: &Case, p: &SolveParams) -> Result<(), CliError> {
    let contact = case.contact();
    let (grid, flag) = match (p.accuracy, p.grid) {
        (Some(t), _) => {
            let g = p.max_grid.unwrap_or(default_max_grid(contact, t));
            (g, format!("--max-grid {g}"))
        }
        (None, Some(g)) => (g, format!("--grid {g}")),
        (None, None) => {
            let g = match contact {
                Contact::Line => LINE_GRID.0,
                Contact::Point => POINT_GRID.0,
            };
            (g, format!("the default grid {g}"))
        }
    };
    let solver = match a.method {
        MethodArg::Newton => Solver::Newton,
        _ => Solver::Multigrid,
    };
    check_memory(
        &flag,
        &format!("a {contact} solve on this grid"),
        estimate(contact, grid, solver),
    )
}

/// The output files and directory, checked (the directory created) before the solve.
fn check_outputs(a: &SolveArgs) -> Result<(), CliError> {
    if let Some(p) = &a.profile {
        check_file("--profile", p)?;
    }
    if let Some(p) = &a.fields {
        check_file("--fields", p)?;
    }
    if let Some(d) = &a.plot {
        prepare_dir("--plot", d)?;
    }
    Ok(())
}

/// Solve on `--threads` threads when given (point contacts: parallel rows), else on this one.
fn solve_arg(a: &SolveArgs, case: &Case, p: &SolveParams) -> Result<Solution, CliError> {
    match a.threads {
        Some(n) => {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| io(format!("--threads {n}: cannot start the threads: {e}")))?;
            Ok(pool.install(|| solve(case, p)))
        }
        None => Ok(solve(case, p)),
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

/// `--profile` (line) or `--fields` (point): write the file (an I/O error when it cannot be),
/// or say why there is none (a failed solve is a result).
fn write_fields_arg(a: &SolveArgs, case: &Case, s: &Solution) -> Result<(), CliError> {
    let meta = file_meta(case, &s.outputs);
    match (&a.profile, &a.fields, &s.profile, &s.fields) {
        (Some(path), _, Some(prof), _) => ehlmap::store::profile::write_profile(path, prof, &meta)
            .map_err(|e| io(format!("--profile {}: {e}", path.display()))),
        (_, Some(path), _, Some(f)) => ehlmap::store::fields::write_fields(path, f, &meta)
            .map_err(|e| io(format!("--fields {}: {e}", path.display()))),
        (Some(path), ..) | (_, Some(path), ..) => {
            note!(
                "ehlmap: the solve returned no profile or fields ({}), {} not written",
                s.outputs.status,
                path.display()
            );
            Ok(())
        }
        _ => Ok(()),
    }
}

/// `--plot DIR`: the pictures of the solution (an I/O error when they cannot be written; a
/// solve that returned no fields is a result, said on stderr).
fn plot_arg(dir: &std::path::Path, case: &Case, s: &Solution) -> Result<(), CliError> {
    let stem = match case {
        Case::Line(c) => format!("line-M{}-L{}", num(c.m), num(c.l)),
        Case::Point(c) => format!("point-M{}-L{}-D{}", num(c.m), num(c.l), num(c.d)),
    };
    let files = match (&s.profile, &s.fields) {
        (Some(prof), _) => ehlmap::render::pictures::draw_line(dir, &stem, prof, &s.outputs),
        (_, Some(f)) => ehlmap::render::pictures::draw_point(dir, &stem, f, &s.outputs),
        _ => {
            note!(
                "ehlmap: --plot: the solve returned no profile or fields ({}), no pictures",
                s.outputs.status
            );
            return Ok(());
        }
    };
    crate::cli::output::report_plot(dir, files)
}

/// The time split of the answering solve and its cost per work unit (`--trace`, stderr).
fn trace_phases(t: &ehlmap::solve::phases::PhaseTimes) {
    let per = t.per_work_unit();
    note!(
        "time split: {t}; {:.2} ms per work unit ({:.1} work units, {:.3} s)",
        1e3 * per.total,
        t.work_units,
        t.total
    );
}

/// Run `ehlmap solve`.
pub fn run_solve(a: &SolveArgs) -> Result<(), CliError> {
    check_flags(a)?;
    let case = case_arg(a)?;
    let params = params_arg(a, &case)?;
    check_solve_memory(a, &case, &params)?;
    check_outputs(a)?;
    crate::cli::solve_progress::start(a.progress);
    let s = solve_arg(a, &case, &params)?;
    if a.trace {
        trace_phases(&s.info.phases);
    }
    let written = write_fields_arg(a, &case, &s);
    let plotted = match &a.plot {
        Some(dir) => plot_arg(dir, &case, &s),
        None => Ok(()),
    };
    let printed = if a.json {
        outln!(
            "{}",
            serde_json::to_string(&s.outputs).expect("outputs serialise")
        )
    } else {
        out!(
            "{}",
            crate::cli::summary::summary(&case, &s.outputs, a.no_estimate)
        )
    };
    // The results are printed even when a file could not be written; the first error decides
    // the exit code.
    written.and(plotted).and(printed)
}
