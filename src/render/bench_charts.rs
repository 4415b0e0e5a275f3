//! The bench charts: error against time and time against grid size per method, and the
//! stability map (each method's outcome over an (M, L) map). They take plain series, not the
//! bench's rows.

use crate::render::style::{e, ensure_font, RenderError, COLORS};
use plotters::prelude::*;
use std::path::Path;

/// One series of a chart: its label and (x, y) points.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// The legend label (the method's name).
    pub label: String,
    /// The (x, y) points, in drawing order; both positive on the log-log charts.
    pub points: Vec<(f64, f64)>,
}

/// The error of H_c against wall time, one panel per case (`panels`: the case's name and one
/// series per method), log-log.
pub fn err_vs_time(path: &Path, panels: &[(String, Vec<Series>)]) -> Result<(), RenderError> {
    ensure_font();
    let root = BitMapBackend::new(path, (560 * panels.len() as u32, 480)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let areas = root.split_evenly((1, panels.len()));
    for (panel, (case, series)) in areas.iter().zip(panels) {
        let all = || series.iter().flat_map(|s| s.points.iter());
        let tmin = all().map(|p| p.0).fold(f64::INFINITY, f64::min).max(1e-5) * 0.5;
        let tmax = all().map(|p| p.0).fold(1e-4, f64::max) * 2.0;
        let emin = all().map(|p| p.1.max(1e-7)).fold(f64::INFINITY, f64::min) * 0.5;
        let emax = all().map(|p| p.1).fold(1e-6, f64::max) * 2.0;
        let mut ch = ChartBuilder::on(panel)
            .caption(format!("{case}: error of H_c vs time"), ("sans-serif", 18))
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
        for (k, s) in series.iter().enumerate() {
            let pts: Vec<(f64, f64)> = s.points.iter().map(|p| (p.0, p.1.max(1e-7))).collect();
            draw_series(&mut ch, &pts, &s.label, COLORS[k % COLORS.len()])?;
        }
        legend(&mut ch)?;
    }
    root.present().map_err(e)
}

type LogChart<'a> = ChartContext<'a, BitMapBackend<'a>, Cartesian2d<LogCoord<f64>, LogCoord<f64>>>;

fn draw_series(
    ch: &mut LogChart,
    pts: &[(f64, f64)],
    label: &str,
    c: RGBColor,
) -> Result<(), RenderError> {
    ch.draw_series(LineSeries::new(pts.to_vec(), c.stroke_width(2)))
        .map_err(e)?
        .label(label)
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], c.stroke_width(2)));
    ch.draw_series(pts.iter().map(|&p| Circle::new(p, 3, c.filled())))
        .map_err(e)?;
    Ok(())
}

fn legend(ch: &mut LogChart) -> Result<(), RenderError> {
    ch.configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(e)
}

/// Least-squares slope of log y against log x (NaN with fewer than two points; the points must
/// be positive).
pub fn slope(pts: &[(f64, f64)]) -> f64 {
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

/// Wall time against grid points, one series per method, log-log; returns each series' fitted
/// slope (time ~ N^slope), also shown in the legend.
pub fn time_vs_n(
    path: &Path,
    case: &str,
    series: &[Series],
) -> Result<Vec<(String, f64)>, RenderError> {
    ensure_font();
    let root = BitMapBackend::new(path, (760, 520)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let all = || series.iter().flat_map(|s| s.points.iter());
    let nmax = all().map(|p| p.0).fold(100.0, f64::max) * 1.5;
    let tmin = all().map(|p| p.1).fold(f64::INFINITY, f64::min).max(1e-5) * 0.5;
    let tmax = all().map(|p| p.1).fold(1e-4, f64::max) * 2.0;
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
    for (k, s) in series.iter().enumerate() {
        let sl = slope(&s.points);
        slopes.push((s.label.clone(), sl));
        let label = format!("{} (slope {sl:.2})", s.label);
        draw_series(&mut ch, &s.points, &label, COLORS[k % COLORS.len()])?;
    }
    legend(&mut ch)?;
    root.present().map_err(e)?;
    Ok(slopes)
}

/// How one cell of the stability map ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Converged on the first attempt.
    Converged,
    /// Converged through the fallback ladder.
    ConvergedFallback,
    /// The solve diverged.
    Diverged,
    /// The solve stalled: it stopped making progress before meeting its tolerances.
    Stalled,
    /// Converged, but far slower than the default multigrid.
    TooSlow,
    /// Converged, but its accuracy target was not met.
    TargetMissed,
    /// Anything else (max-iterations, a time limit, an under-resolved film).
    Other,
}

/// One cell of the stability map.
#[derive(Clone, Debug, PartialEq)]
pub struct MapCell {
    /// The method's name: the panel the cell is drawn in.
    pub method: String,
    /// Moes' load parameter M of the case.
    pub m: f64,
    /// Moes' lubricant parameter L of the case.
    pub l: f64,
    /// How the solve ended: the cell's colour.
    pub outcome: Outcome,
}

/// The stability map: one panel per method in `names` (two per row), each cell coloured by its
/// outcome, over the (M, L) values `ms`, `ls`.
pub fn stability_chart(
    path: &Path,
    names: &[String],
    cells: &[MapCell],
    ms: &[f64],
    ls: &[f64],
) -> Result<(), RenderError> {
    ensure_font();
    let rows = names.len().div_ceil(2).max(1);
    let root = BitMapBackend::new(path, (1000, 30 + 380 * rows as u32)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let body = root
        .titled(
            "green converged (light green: by the fallback ladder), purple converged but the \
             target missed, blue too slow, red diverged, orange stalled, grey max-iterations",
            ("sans-serif", 14),
        )
        .map_err(e)?;
    let panels = body.split_evenly((rows, 2));
    let (m0, m1) = (ms[0] * 0.7, ms[ms.len() - 1] * 1.4);
    let l1 = ls[ls.len() - 1].max(1.0) * 1.1;
    for (panel, name) in panels.iter().zip(names) {
        let mut ch = ChartBuilder::on(panel)
            .caption(name, ("sans-serif", 14))
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
            let col = match c.outcome {
                Outcome::Converged => RGBColor(44, 160, 44),
                Outcome::ConvergedFallback => RGBColor(140, 210, 120),
                Outcome::Diverged => RGBColor(214, 39, 40),
                Outcome::Stalled => RGBColor(255, 127, 14),
                Outcome::TooSlow => RGBColor(31, 119, 180),
                Outcome::TargetMissed => RGBColor(148, 103, 189),
                Outcome::Other => RGBColor(150, 150, 150),
            };
            Circle::new((c.m, c.l), 8, col.filled())
        }))
        .map_err(e)?;
    }
    root.present().map_err(e)
}
