//! `ehlmap bench` and `ehlmap stability`: tables (Parquet), summaries (Markdown) and charts.
//! Options are checked and the output directory created before the first solve: bad input
//! exits 2, an output that cannot be written 1.

use crate::cli::error::{input, io, CliError};
use crate::cli::limits::{check_memory, estimate, Solver};
use crate::cli::output::{note, out, outln, prepare_dir};
use crate::cli::solve_args::time_limit_arg;
use ehlmap::bench::box_map;
use ehlmap::bench::selection;
use ehlmap::bench::speed::{self, BenchCase, BenchRow};
use ehlmap::bench::stability::{self, Cell};
use ehlmap::model::case::Contact;
use ehlmap::model::case::{LineCase, PointCase};
use ehlmap::model::error::num;
use ehlmap::render::bench_charts::{self, MapCell, Outcome, Series};
use ehlmap::store::table::{write_table, Column};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct BenchArgs {
    /// Output directory for bench.parquet, bench.md and the charts.
    #[arg(long, default_value = "outputs/bench")]
    pub out: PathBuf,
    /// Timed repeats per point (median), 1 to 1000 (default 3); the speed ladder only.
    #[arg(long)]
    pub repeats: Option<usize>,
    /// Smaller ladder (line 257..2049 points, reference from 4097; point 33^2..129^2, reference
    /// from 257^2); the speed ladder only.
    #[arg(long)]
    pub quick: bool,
    /// Instead of the speed ladder: solve every case of this sweep spec with the accuracy target
    /// (model selection, coarsest adequate grid) and with the full model on the spec's grid, and
    /// report the time saved (selection.md, selection.parquet).
    #[arg(long, value_name = "SPEC")]
    pub selection: Option<PathBuf>,
    /// Target relative accuracy for --selection, in (0, 1) (default 0.005).
    #[arg(long, allow_hyphen_values = true)]
    pub accuracy: Option<f64>,
}

#[derive(clap::Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct StabilityArgs {
    /// Output directory for stability.parquet, stability.md and stability.png.
    #[arg(long, default_value = "outputs/stability")]
    pub out: PathBuf,
    /// Finest grid of the multigrid runs (default 1025): line 33 to 1048577 points; with
    /// --point-D 17 to 1025 per direction. Not with --box.
    #[arg(long)]
    pub grid: Option<usize>,
    /// A 5 x 3 map (M x L) instead of 8 x 5.
    #[arg(long)]
    pub quick: bool,
    /// Map point contacts of this ellipticity D = Rx/Ry in (0, 1] instead of line contacts
    /// (`--grid` then counts points per direction; give e.g. 129).
    #[arg(long = "point-D", allow_hyphen_values = true)]
    pub point_d: Option<f64>,
    /// Map the whole box instead, as a user's default solve would run it (the full model to the
    /// 1 % target, the accuracy and fallback ladders): line M 0.01-1e5 x L 0-40, point M
    /// 0.01-3e4 x L 0-30 x D 1, 0.1, 0.01, each with Barus/incompressible and Roelands/
    /// Dowson-Higginson; one case per thread (see --threads of the sweep runner: the rayon pool,
    /// RAYON_NUM_THREADS). With --quick the corners and the middle only.
    #[arg(long = "box")]
    pub box_map: bool,
    /// With --box: seconds each case may take (default 20); a case that reaches it ends with
    /// status max-iterations and says so.
    #[arg(long, allow_hyphen_values = true)]
    pub time_limit: Option<f64>,
    /// With --box: point contacts with P = 0 on the truncated domain's boundary instead of the
    /// asymptotic far field (`ehlmap solve --truncated-domain`).
    #[arg(long)]
    pub truncated_domain: bool,
}

/// The default --time-limit of `ehlmap stability --box`, s.
const BOX_TIME_LIMIT: f64 = 20.0;

/// Most timed repeats `--repeats` takes.
const MAX_REPEATS: usize = 1000;

/// Run `ehlmap bench`.
pub fn run_bench(a: &BenchArgs) -> Result<(), CliError> {
    if let Some(spec) = &a.selection {
        for (given, flag) in [(a.quick, "--quick"), (a.repeats.is_some(), "--repeats")] {
            if given {
                return Err(input(format!(
                    "{flag} applies to the speed ladder only, not to --selection"
                )));
            }
        }
        return run_selection(a, spec);
    }
    if let Some(t) = a.accuracy {
        return Err(input(format!(
            "--accuracy {} applies to --selection only (the speed ladder measures every accuracy)",
            num(t)
        )));
    }
    let repeats = a.repeats.unwrap_or(3);
    if !(1..=MAX_REPEATS).contains(&repeats) {
        return Err(input(format!(
            "--repeats {repeats} is invalid: give 1 to {MAX_REPEATS}"
        )));
    }
    prepare_dir("--out", &a.out)?;
    let line = |m: f64| BenchCase::Line(LineCase::new(m, 10.0).expect("valid"));
    let point = |m: f64, d: f64| BenchCase::Point(PointCase::new(m, 10.0, d).expect("valid"));
    let line_cases = [
        ("line M=20 L=10", line(20.0)),
        ("line M=200 L=10", line(200.0)),
    ];
    let point_cases = [
        ("circular M=20 L=10", point(20.0, 1.0)),
        ("circular M=200 L=10", point(200.0, 1.0)),
        ("elliptic D=0.25 M=100 L=10", point(100.0, 0.25)),
    ];
    let (grids, ref_grid, pgrids, pref): (Vec<usize>, usize, Vec<usize>, usize) = if a.quick {
        (vec![257, 513, 1025, 2049], 4097, vec![33, 65, 129], 257)
    } else {
        (
            vec![257, 513, 1025, 2049, 4097, 8193],
            16385,
            vec![33, 65, 129, 257],
            513,
        )
    };
    let mut log = |s: &str| note!("{s}");
    let (mut refs, mut rows) = speed::run(&line_cases, &grids, repeats, ref_grid, &mut log);
    let (prefs, prows) = speed::run(&point_cases, &pgrids, repeats, pref, &mut log);
    refs.extend(prefs);
    rows.extend(prows);
    write_table(
        &a.out.join("bench.parquet"),
        vec![
            Column::Str("case", rows.iter().map(|r| r.case.clone()).collect()),
            Column::Str("method", rows.iter().map(|r| r.method.clone()).collect()),
            Column::I64("grid", rows.iter().map(|r| r.grid as i64).collect()),
            Column::F64("wall_s", rows.iter().map(|r| r.wall_s).collect()),
            Column::F64("work_units", rows.iter().map(|r| r.work_units).collect()),
            Column::F64("H_c", rows.iter().map(|r| r.h_c).collect()),
            Column::F64("H_min", rows.iter().map(|r| r.h_min).collect()),
            Column::F64("err_H_c", rows.iter().map(|r| r.err_h_c).collect()),
            Column::F64("err_H_min", rows.iter().map(|r| r.err_h_min).collect()),
            Column::Str("status", rows.iter().map(|r| r.status.clone()).collect()),
        ],
        &[(
            "references",
            serde_json::to_string(&refs).expect("serialise"),
        )],
    )
    .map_err(|e| out_err(&a.out, &e))?;
    let panels: Vec<(String, Vec<Series>)> = refs
        .iter()
        .map(|r| {
            (
                r.case.clone(),
                method_series(&rows, &r.case, |x| (x.wall_s, x.err_h_c)),
            )
        })
        .collect();
    bench_charts::err_vs_time(&a.out.join("error_vs_time.png"), &panels)
        .map_err(|e| out_err(&a.out, &e))?;
    let mut md = String::from("# ehlmap bench (line and point contacts, one thread)\n\n");
    for r in &refs {
        let slopes = bench_charts::time_vs_n(
            &a.out.join(format!(
                "time_vs_n_{}.png",
                r.case.replace(['=', '.'], "").replace(' ', "_")
            )),
            &r.case,
            &method_series(&rows, &r.case, |x| (x.grid as f64, x.wall_s)),
        )
        .map_err(|e| out_err(&a.out, &e))?;
        let _ = writeln!(
            md,
            "{}: reference H_c {:.6}, H_min {:.6}; time ~ N^slope: {}\n",
            r.case,
            r.h_c,
            r.h_min,
            slopes
                .iter()
                .map(|(m, s)| format!("{m} {s:.2}"))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    let _ = writeln!(
        md,
        "| case | accuracy target | fastest method | grid | time |\n|---|---|---|---|---|"
    );
    for (c, t, best) in speed::pareto(&rows, &[1e-2, 1e-3, 1e-4]) {
        match best {
            Some(b) => {
                let _ = writeln!(
                    md,
                    "| {c} | {t:.0e} | {} | {} | {:.4} s |",
                    b.method, b.grid, b.wall_s
                );
            }
            None => {
                let _ = writeln!(md, "| {c} | {t:.0e} | none on this ladder | - | - |");
            }
        }
    }
    std::fs::write(a.out.join("bench.md"), &md).map_err(|e| out_err(&a.out, &e))?;
    outln!("{md}")
}

/// An output of `--out DIR` that could not be written: an I/O error naming the option.
fn out_err(dir: &Path, e: &dyn std::fmt::Display) -> CliError {
    io(format!("--out {}: {e}", dir.display()))
}

/// `ehlmap bench --selection SPEC`: the saving of model selection on a sweep spec.
fn run_selection(a: &BenchArgs, spec_path: &Path) -> Result<(), CliError> {
    let accuracy = a.accuracy.unwrap_or(0.005);
    if !(accuracy > 0.0 && accuracy < 1.0) {
        return Err(input(format!(
            "--accuracy {} is invalid: a relative accuracy in (0, 1), e.g. 0.005",
            num(accuracy)
        )));
    }
    let spec =
        ehlmap::sweep::spec::load(spec_path).map_err(|x| input(format!("--selection: {x}")))?;
    let cases = ehlmap::sweep::plan::plan(&spec).map_err(|x| input(format!("--selection: {x}")))?;
    for c in &spec.contacts {
        check_memory(
            &format!(
                "--selection {}: numerics.grid = {}",
                spec_path.display(),
                c.numerics.grid
            ),
            &format!("a {} solve on this grid", c.contact.as_str()),
            estimate(c.contact, c.numerics.grid, Solver::Multigrid),
        )?;
    }
    prepare_dir("--out", &a.out)?;
    note!(
        "bench --selection: {} cases of {}, each solved with target {} and with the full model",
        cases.len(),
        spec_path.display(),
        accuracy
    );
    let pairs = selection::run(&cases, &spec.name, accuracy);
    let col_f = |f: &dyn Fn(&selection::Pair) -> Option<f64>| -> Vec<f64> {
        pairs.iter().map(|p| f(p).unwrap_or(f64::NAN)).collect()
    };
    write_table(
        &a.out.join("selection.parquet"),
        vec![
            Column::Str(
                "case_id",
                pairs.iter().map(|p| p.full.case_id.clone()).collect(),
            ),
            Column::Str(
                "contact",
                pairs.iter().map(|p| p.full.contact.to_string()).collect(),
            ),
            Column::F64("M", col_f(&|p| Some(p.full.m))),
            Column::F64("L", col_f(&|p| Some(p.full.l))),
            Column::F64("D", col_f(&|p| p.full.d)),
            Column::Str(
                "model_used",
                pairs
                    .iter()
                    .map(|p| p.selected.model_used.to_string())
                    .collect(),
            ),
            Column::F64(
                "grid_selected",
                col_f(&|p| p.selected.grid.map(|g| g as f64)),
            ),
            Column::F64("grid_full", col_f(&|p| p.full.grid.map(|g| g as f64))),
            Column::F64("wall_s_selected", col_f(&|p| p.selected.wall_s)),
            Column::F64("wall_s_full", col_f(&|p| p.full.wall_s)),
            Column::F64("H_c_selected", col_f(&|p| p.selected.h_c)),
            Column::F64("H_c_full", col_f(&|p| p.full.h_c)),
            Column::F64("error_estimate", col_f(&|p| p.selected.error_estimate)),
            Column::F64("deviation", col_f(&selection::Pair::deviation)),
            Column::Str(
                "status_selected",
                pairs
                    .iter()
                    .map(|p| p.selected.status.to_string())
                    .collect(),
            ),
            Column::Str(
                "status_full",
                pairs.iter().map(|p| p.full.status.to_string()).collect(),
            ),
        ],
        &[
            ("spec", spec.text.clone()),
            ("accuracy", accuracy.to_string()),
        ],
    )
    .map_err(|e| out_err(&a.out, &e))?;
    let md = selection::summary(&pairs, accuracy, &spec_path.display().to_string());
    std::fs::write(a.out.join("selection.md"), &md).map_err(|e| out_err(&a.out, &e))?;
    out!("{md}")
}

/// Run `ehlmap stability`.
pub fn run_stability(a: &StabilityArgs) -> Result<(), CliError> {
    if a.box_map {
        return run_box(a);
    }
    if let Some(t) = a.time_limit {
        return Err(input(format!(
            "--time-limit {} applies to --box only",
            num(t)
        )));
    }
    if a.truncated_domain {
        return Err(input(
            "--truncated-domain applies to --box only (the method maps run the point solver's \
             default domain)",
        ));
    }
    let grid = a.grid.unwrap_or(1025);
    let (contact, (lo, hi)) = match a.point_d {
        Some(d) if !(d > 0.0 && d <= 1.0) => {
            return Err(input(format!(
                "--point-D {} is invalid: the ellipticity must be in (0, 1]",
                num(d)
            )))
        }
        Some(_) => (Contact::Point, (17, 1025)),
        None => (Contact::Line, Contact::Line.grid_range()),
    };
    if !(lo..=hi).contains(&grid) {
        return Err(input(match a.point_d {
            Some(d) => format!(
                "--grid {} with --point-D {}: give {lo} to {hi} points per direction",
                grid,
                num(d)
            ),
            None => format!(
                "--grid {} is invalid: give {lo} to {hi} points (line contacts)",
                grid
            ),
        }));
    }
    check_memory(
        &format!("--grid {}", grid),
        &format!("a {contact} solve on this grid"),
        estimate(contact, grid, Solver::Multigrid),
    )?;
    prepare_dir("--out", &a.out)?;
    let (ms, ls): (Vec<f64>, Vec<f64>) = if a.quick {
        (vec![1.0, 10.0, 100.0, 500.0, 2000.0], vec![0.0, 10.0, 20.0])
    } else {
        (
            (0..8).map(|i| 2000f64.powf(i as f64 / 7.0)).collect(),
            vec![0.0, 5.0, 10.0, 15.0, 20.0],
        )
    };
    let mut log = |s: &str| note!("{s}");
    let cells = match a.point_d {
        Some(d) => stability::run_point(&ms, &ls, d, grid, &mut log),
        None => stability::run(&ms, &ls, grid, &mut log),
    };
    write_table(
        &a.out.join("stability.parquet"),
        vec![
            Column::Str("method", cells.iter().map(|c| c.method.clone()).collect()),
            Column::F64("M", cells.iter().map(|c| c.m).collect()),
            Column::F64("L", cells.iter().map(|c| c.l).collect()),
            Column::I64("grid", cells.iter().map(|c| c.grid as i64).collect()),
            Column::Str("status", cells.iter().map(|c| c.status.clone()).collect()),
            Column::I64("attempt", cells.iter().map(|c| c.attempt as i64).collect()),
            Column::Str("reason", cells.iter().map(|c| c.reason.clone()).collect()),
            Column::F64("wall_s", cells.iter().map(|c| c.wall_s).collect()),
        ],
        &[],
    )
    .map_err(|e| out_err(&a.out, &e))?;
    let names: Vec<String> = stability::map_methods(1025)
        .iter()
        .map(|m| m.0.to_string())
        .collect();
    let map: Vec<MapCell> = cells.iter().map(map_cell).collect();
    bench_charts::stability_chart(&a.out.join("stability.png"), &names, &map, &ms, &ls)
        .map_err(|e| out_err(&a.out, &e))?;
    let mut md = String::from("| method | converged | of |\n|---|---|---|\n");
    for (n, ok, all) in stability::summary(&cells) {
        let _ = writeln!(md, "| {n} | {ok} | {all} |");
    }
    std::fs::write(a.out.join("stability.md"), &md).map_err(|e| out_err(&a.out, &e))?;
    outln!("{md}")
}

/// Run `ehlmap stability --box`.
fn run_box(a: &StabilityArgs) -> Result<(), CliError> {
    if let Some(d) = a.point_d {
        return Err(input(format!(
            "--point-D {} does not apply with --box (the box maps D = 1, 0.1 and 0.01)",
            num(d)
        )));
    }
    if let Some(g) = a.grid {
        return Err(input(format!(
            "--grid {g} does not apply with --box (the accuracy ladder picks each case's grid)"
        )));
    }
    let limit = match a.time_limit {
        None => BOX_TIME_LIMIT,
        Some(t) => time_limit_arg("--time-limit", t)?,
    };
    for contact in [Contact::Line, Contact::Point] {
        let g = ehlmap::strategy::solve_case::default_max_grid(
            contact,
            ehlmap::strategy::solve_case::DEFAULT_ACCURACY,
        );
        check_memory(
            &format!("--box ({contact} contacts up to {g} points)"),
            &format!("a {contact} solve on the largest grid"),
            estimate(contact, g, Solver::Multigrid),
        )?;
    }
    prepare_dir("--out", &a.out)?;
    let cases = box_map::box_cases(a.quick);
    note!(
        "stability --box: {} cases, at most {limit} s each, on {} threads",
        cases.len(),
        rayon::current_num_threads()
    );
    let cells = box_map::run_box(&cases, limit, !a.truncated_domain, &|s: &str| note!("{s}"));
    write_table(
        &a.out.join("stability.parquet"),
        vec![
            Column::Str("panel", cells.iter().map(|c| c.panel.clone()).collect()),
            Column::Str("contact", cells.iter().map(|c| c.contact.clone()).collect()),
            Column::F64("M", cells.iter().map(|c| c.m).collect()),
            Column::F64("L", cells.iter().map(|c| c.l).collect()),
            Column::F64("D", cells.iter().map(|c| c.d).collect()),
            Column::Str("status", cells.iter().map(|c| c.status.clone()).collect()),
            Column::I64("attempt", cells.iter().map(|c| c.attempt as i64).collect()),
            Column::I64("grid", cells.iter().map(|c| c.grid as i64).collect()),
            Column::F64("work_units", cells.iter().map(|c| c.work_units).collect()),
            Column::F64("wall_s", cells.iter().map(|c| c.wall_s).collect()),
            Column::Bool(
                "accuracy_met",
                cells.iter().map(|c| c.accuracy_met).collect(),
            ),
            Column::F64(
                "error_estimate",
                cells
                    .iter()
                    .map(|c| c.error_estimate.unwrap_or(f64::NAN))
                    .collect(),
            ),
            Column::Bool("timed_out", cells.iter().map(|c| c.timed_out).collect()),
            Column::Str("reason", cells.iter().map(|c| c.reason.clone()).collect()),
        ],
        &[],
    )
    .map_err(|e| out_err(&a.out, &e))?;
    let map: Vec<MapCell> = cells
        .iter()
        .map(|c| MapCell {
            method: c.panel.clone(),
            m: c.m,
            l: c.l,
            outcome: match (c.status.as_str(), c.accuracy_met, c.attempt) {
                ("converged", true, 1) => Outcome::Converged,
                ("converged", true, _) => Outcome::ConvergedFallback,
                ("converged", false, _) => Outcome::TargetMissed,
                ("diverged", ..) => Outcome::Diverged,
                ("stalled", ..) => Outcome::Stalled,
                _ => Outcome::Other,
            },
        })
        .collect();
    let ((lm, ll), (pm, pl)) = box_map::box_axes(a.quick);
    let ms: Vec<f64> = lm.iter().chain(&pm).copied().collect();
    let (m_lo, m_hi) = (
        ms.iter().copied().fold(f64::INFINITY, f64::min),
        ms.iter().copied().fold(0.0, f64::max),
    );
    let l_hi = ll.iter().chain(&pl).copied().fold(0.0, f64::max);
    bench_charts::stability_chart(
        &a.out.join("stability.png"),
        &box_map::panel_names(),
        &map,
        &[m_lo, m_hi],
        &[0.0, l_hi],
    )
    .map_err(|e| out_err(&a.out, &e))?;
    let far = if a.truncated_domain {
        ", point contacts on the truncated domain (P = 0 on its boundary)"
    } else {
        ""
    };
    let mut md = format!(
        "Default solve (full model, 1 % target{far}), at most {limit} s per case.\n\n\
         | panel | converged, target met | converged | time limit | cases |\n|---|---|---|---|---|\n"
    );
    for (name, met, ok, timed, all) in box_map::box_summary(&cells) {
        let _ = writeln!(md, "| {name} | {met} | {ok} | {timed} | {all} |");
    }
    md.push_str("\nCases not converged with the target met:\n\n| panel | M | L | status | grid | attempt | WU | s | reason |\n|---|---|---|---|---|---|---|---|---|\n");
    for c in cells
        .iter()
        .filter(|c| !(c.status == "converged" && c.accuracy_met))
    {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {:.0} | {:.1} | {} |",
            c.panel,
            num(c.m),
            num(c.l),
            c.status,
            c.grid,
            c.attempt,
            c.work_units,
            c.wall_s,
            c.reason.replace('|', "/")
        );
    }
    std::fs::write(a.out.join("stability.md"), &md).map_err(|e| out_err(&a.out, &e))?;
    outln!("{md}")
}

/// One series per method of the converged rows of `case`, points from `xy`.
fn method_series(rows: &[BenchRow], case: &str, xy: fn(&BenchRow) -> (f64, f64)) -> Vec<Series> {
    speed::methods()
        .iter()
        .map(|m| Series {
            label: m.label.to_string(),
            points: rows
                .iter()
                .filter(|x| x.case == case && x.status == "converged" && x.method == m.label)
                .map(xy)
                .collect(),
        })
        .collect()
}

/// A stability cell as the chart colours it.
fn map_cell(c: &Cell) -> MapCell {
    let outcome = match c.status.as_str() {
        "converged" if c.attempt <= 1 => Outcome::Converged,
        "converged" => Outcome::ConvergedFallback,
        "diverged" => Outcome::Diverged,
        "stalled" => Outcome::Stalled,
        "too-slow" => Outcome::TooSlow,
        _ => Outcome::Other,
    };
    MapCell {
        method: c.method.clone(),
        m: c.m,
        l: c.l,
        outcome,
    }
}
