//! `ehlmap bench` and `ehlmap stability`: tables (Parquet), summaries (Markdown) and charts.

use crate::bench::selection;
use crate::bench::speed::{self, BenchCase, BenchRow, Reference};
use crate::bench::stability::{self, Cell};
use crate::bench::COLORS;
use crate::cli::error::InputError;
use crate::model::case::{LineCase, PointCase};
use crate::store::table::{write_table, Column};
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug)]
pub struct BenchArgs {
    /// Output directory for bench.parquet, bench.md and the charts.
    #[arg(long, default_value = "outputs/bench")]
    pub out: PathBuf,
    /// Timed repeats per point (median).
    #[arg(long, default_value_t = 3)]
    pub repeats: usize,
    /// Smaller ladder (257..2049 points, reference from 4097): about a minute.
    #[arg(long)]
    pub quick: bool,
    /// Instead of the speed ladder: solve every case of this sweep spec with the accuracy target
    /// (model selection, coarsest adequate grid) and with the full model on the spec's grid, and
    /// report the time saved (selection.md, selection.parquet).
    #[arg(long, value_name = "SPEC")]
    pub selection: Option<PathBuf>,
    /// Target relative accuracy for --selection.
    #[arg(long, default_value_t = 0.005)]
    pub accuracy: f64,
}

#[derive(clap::Args, Debug)]
pub struct StabilityArgs {
    #[arg(long, default_value = "outputs/stability")]
    pub out: PathBuf,
    /// Finest grid of the multigrid runs.
    #[arg(long, default_value_t = 1025)]
    pub grid: usize,
    /// A 5 x 3 map instead of 8 x 5.
    #[arg(long)]
    pub quick: bool,
    /// Map point contacts of this ellipticity D = Rx/Ry in (0, 1] instead of line contacts
    /// (`--grid` then counts points per direction; give e.g. 129).
    #[arg(long = "point-D")]
    pub point_d: Option<f64>,
}

fn e<T: std::fmt::Debug>(x: T) -> InputError {
    InputError(format!("{x:?}"))
}

fn err_vs_time(path: &Path, refs: &[Reference], rows: &[BenchRow]) -> Result<(), InputError> {
    crate::render::charts::ensure_font();
    let root = BitMapBackend::new(path, (560 * refs.len() as u32, 480)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let panels = root.split_evenly((1, refs.len()));
    for (panel, r) in panels.iter().zip(refs) {
        let sel: Vec<&BenchRow> = rows
            .iter()
            .filter(|x| x.case == r.case && x.status == "converged")
            .collect();
        let tmin = sel
            .iter()
            .map(|x| x.wall_s)
            .fold(f64::INFINITY, f64::min)
            .max(1e-5)
            * 0.5;
        let tmax = sel.iter().map(|x| x.wall_s).fold(1e-4, f64::max) * 2.0;
        let emin = sel
            .iter()
            .map(|x| x.err_h_c.max(1e-7))
            .fold(f64::INFINITY, f64::min)
            * 0.5;
        let emax = sel.iter().map(|x| x.err_h_c).fold(1e-6, f64::max) * 2.0;
        let mut ch = ChartBuilder::on(panel)
            .caption(
                format!("{}: error of H_c vs time", r.case),
                ("sans-serif", 18),
            )
            .margin(10)
            .x_label_area_size(36)
            .y_label_area_size(56)
            .build_cartesian_2d((tmin..tmax).log_scale(), (emin..emax).log_scale())
            .map_err(e)?;
        ch.configure_mesh()
            .x_desc("wall time (s)")
            .y_desc("|H_c/H_ref - 1|")
            .x_label_formatter(&|v| format!("{v:.2e}"))
            .y_label_formatter(&|v| format!("{v:.1e}"))
            .draw()
            .map_err(e)?;
        for (k, m) in speed::methods().iter().enumerate() {
            let pts: Vec<(f64, f64)> = sel
                .iter()
                .filter(|x| x.method == m.label)
                .map(|x| (x.wall_s, x.err_h_c.max(1e-7)))
                .collect();
            let c = COLORS[k % COLORS.len()];
            ch.draw_series(LineSeries::new(pts.clone(), c.stroke_width(2)))
                .map_err(e)?
                .label(m.label)
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], c.stroke_width(2)));
            ch.draw_series(pts.iter().map(|&p| Circle::new(p, 3, c.filled())))
                .map_err(e)?;
        }
        ch.configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(e)?;
    }
    root.present().map_err(e)
}

fn slope(pts: &[(f64, f64)]) -> f64 {
    let n = pts.len() as f64;
    if pts.len() < 2 {
        return f64::NAN;
    }
    let (sx, sy) = pts
        .iter()
        .fold((0.0, 0.0), |a, p| (a.0 + p.0.ln(), a.1 + p.1.ln()));
    let (mx, my) = (sx / n, sy / n);
    let num: f64 = pts.iter().map(|p| (p.0.ln() - mx) * (p.1.ln() - my)).sum();
    let den: f64 = pts.iter().map(|p| (p.0.ln() - mx).powi(2)).sum();
    num / den
}

fn time_vs_n(path: &Path, case: &str, rows: &[BenchRow]) -> Result<Vec<(String, f64)>, InputError> {
    crate::render::charts::ensure_font();
    let sel: Vec<&BenchRow> = rows
        .iter()
        .filter(|x| x.case == case && x.status == "converged")
        .collect();
    let root = BitMapBackend::new(path, (760, 520)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let nmax = sel.iter().map(|x| x.grid as f64).fold(100.0, f64::max) * 1.5;
    let tmin = sel
        .iter()
        .map(|x| x.wall_s)
        .fold(f64::INFINITY, f64::min)
        .max(1e-5)
        * 0.5;
    let tmax = sel.iter().map(|x| x.wall_s).fold(1e-4, f64::max) * 2.0;
    let mut ch = ChartBuilder::on(&root)
        .caption(
            format!("{case}: time vs grid points (fitted slopes in the legend)"),
            ("sans-serif", 18),
        )
        .margin(10)
        .x_label_area_size(36)
        .y_label_area_size(56)
        .build_cartesian_2d((150.0..nmax).log_scale(), (tmin..tmax).log_scale())
        .map_err(e)?;
    ch.configure_mesh()
        .x_desc("grid points N")
        .y_desc("wall time (s)")
        .draw()
        .map_err(e)?;
    let mut slopes = vec![];
    for (k, m) in speed::methods().iter().enumerate() {
        let pts: Vec<(f64, f64)> = sel
            .iter()
            .filter(|x| x.method == m.label)
            .map(|x| (x.grid as f64, x.wall_s))
            .collect();
        let s = slope(&pts);
        slopes.push((m.label.to_string(), s));
        let c = COLORS[k % COLORS.len()];
        ch.draw_series(LineSeries::new(pts.clone(), c.stroke_width(2)))
            .map_err(e)?
            .label(format!("{} (slope {s:.2})", m.label))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], c.stroke_width(2)));
        ch.draw_series(pts.iter().map(|&p| Circle::new(p, 3, c.filled())))
            .map_err(e)?;
    }
    ch.configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(e)?;
    root.present().map_err(e)?;
    Ok(slopes)
}

/// Run `ehlmap bench`.
pub fn run_bench(a: &BenchArgs) -> Result<i32, InputError> {
    std::fs::create_dir_all(&a.out)
        .map_err(|x| InputError(format!("--out {}: {x}", a.out.display())))?;
    if let Some(spec) = &a.selection {
        return run_selection(a, spec);
    }
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
    let mut log = |s: &str| eprintln!("{s}");
    let (mut refs, mut rows) = speed::run(&line_cases, &grids, a.repeats, ref_grid, &mut log);
    let (prefs, prows) = speed::run(&point_cases, &pgrids, a.repeats, pref, &mut log);
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
    .map_err(InputError)?;
    err_vs_time(&a.out.join("error_vs_time.png"), &refs, &rows)?;
    let mut md = String::from("# ehlmap bench (line and point contacts, one thread)\n\n");
    for r in &refs {
        let slopes = time_vs_n(
            &a.out.join(format!(
                "time_vs_n_{}.png",
                r.case.replace(['=', '.'], "").replace(' ', "_")
            )),
            &r.case,
            &rows,
        )?;
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
    std::fs::write(a.out.join("bench.md"), &md).map_err(|x| InputError(x.to_string()))?;
    println!("{md}");
    Ok(0)
}

fn stability_chart(path: &Path, cells: &[Cell], ms: &[f64], ls: &[f64]) -> Result<(), InputError> {
    crate::render::charts::ensure_font();
    let names: Vec<String> = stability::map_methods(1025)
        .iter()
        .map(|m| m.0.to_string())
        .collect();
    let root = BitMapBackend::new(path, (1000, 760)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let panels = root.split_evenly((2, 2));
    let (m0, m1) = (ms[0] * 0.7, ms[ms.len() - 1] * 1.4);
    let l1 = ls[ls.len() - 1].max(1.0) * 1.1;
    for (panel, name) in panels.iter().zip(&names) {
        let mut ch = ChartBuilder::on(panel)
            .caption(
                format!("{name}: green converged, blue too slow, red diverged, orange stalled, grey max-iter"),
                ("sans-serif", 13),
            )
            .margin(8)
            .x_label_area_size(30)
            .y_label_area_size(36)
            .build_cartesian_2d((m0..m1).log_scale(), -0.1 * l1..l1)
            .map_err(e)?;
        ch.configure_mesh()
            .x_desc("M")
            .y_desc("L")
            .draw()
            .map_err(e)?;
        ch.draw_series(cells.iter().filter(|c| &c.method == name).map(|c| {
            let col = match c.status.as_str() {
                "converged" if c.attempt <= 1 => RGBColor(44, 160, 44),
                "converged" => RGBColor(140, 210, 120),
                "diverged" => RGBColor(214, 39, 40),
                "stalled" => RGBColor(255, 127, 14),
                "too-slow" => RGBColor(31, 119, 180),
                _ => RGBColor(150, 150, 150),
            };
            Circle::new((c.m, c.l), 8, col.filled())
        }))
        .map_err(e)?;
    }
    root.present().map_err(e)
}

/// `ehlmap bench --selection SPEC`: the saving of model selection on a sweep spec.
fn run_selection(a: &BenchArgs, spec_path: &Path) -> Result<i32, InputError> {
    if !(a.accuracy > 0.0 && a.accuracy < 1.0) {
        return Err(InputError(format!(
            "--accuracy {} is invalid: a relative accuracy in (0, 1), e.g. 0.005",
            a.accuracy
        )));
    }
    let spec = crate::sweep::spec::load(spec_path).map_err(|x| InputError(x.to_string()))?;
    let cases = crate::sweep::plan::plan(&spec).map_err(|x| InputError(x.to_string()))?;
    eprintln!(
        "bench --selection: {} cases of {}, each solved with target {} and with the full model",
        cases.len(),
        spec_path.display(),
        a.accuracy
    );
    let pairs = selection::run(&cases, &spec.name, a.accuracy);
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
                pairs.iter().map(|p| p.full.contact.clone()).collect(),
            ),
            Column::F64("M", col_f(&|p| Some(p.full.m))),
            Column::F64("L", col_f(&|p| Some(p.full.l))),
            Column::F64("D", col_f(&|p| p.full.d)),
            Column::Str(
                "model_used",
                pairs
                    .iter()
                    .map(|p| p.selected.model_used.clone())
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
                pairs.iter().map(|p| p.selected.status.clone()).collect(),
            ),
            Column::Str(
                "status_full",
                pairs.iter().map(|p| p.full.status.clone()).collect(),
            ),
        ],
        &[
            ("spec", spec.text.clone()),
            ("accuracy", a.accuracy.to_string()),
        ],
    )
    .map_err(InputError)?;
    let md = selection::summary(&pairs, a.accuracy, &spec_path.display().to_string());
    std::fs::write(a.out.join("selection.md"), &md)
        .map_err(|x| InputError(format!("--out {}: {x}", a.out.display())))?;
    print!("{md}");
    Ok(0)
}

/// Run `ehlmap stability`.
pub fn run_stability(a: &StabilityArgs) -> Result<i32, InputError> {
    std::fs::create_dir_all(&a.out)
        .map_err(|x| InputError(format!("--out {}: {x}", a.out.display())))?;
    let (ms, ls): (Vec<f64>, Vec<f64>) = if a.quick {
        (vec![1.0, 10.0, 100.0, 500.0, 2000.0], vec![0.0, 10.0, 20.0])
    } else {
        (
            (0..8).map(|i| 2000f64.powf(i as f64 / 7.0)).collect(),
            vec![0.0, 5.0, 10.0, 15.0, 20.0],
        )
    };
    let mut log = |s: &str| eprintln!("{s}");
    let cells = match a.point_d {
        Some(d) if !(d > 0.0 && d <= 1.0) => {
            return Err(InputError(format!(
                "--point-D {d} is invalid: the ellipticity must be in (0, 1]"
            )))
        }
        Some(d) if !(17..=1025).contains(&a.grid) => {
            return Err(InputError(format!(
                "--grid {} with --point-D {d}: give 17 to 1025 points per direction",
                a.grid
            )))
        }
        Some(d) => stability::run_point(&ms, &ls, d, a.grid, &mut log),
        None => stability::run(&ms, &ls, a.grid, &mut log),
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
    .map_err(InputError)?;
    stability_chart(&a.out.join("stability.png"), &cells, &ms, &ls)?;
    let mut md = String::from("| method | converged | of |\n|---|---|---|\n");
    for (n, ok, all) in stability::summary(&cells) {
        let _ = writeln!(md, "| {n} | {ok} | {all} |");
    }
    std::fs::write(a.out.join("stability.md"), &md).map_err(|x| InputError(x.to_string()))?;
    println!("{md}");
    Ok(0)
}
