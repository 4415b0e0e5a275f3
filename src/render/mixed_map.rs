//! The mixed-lubrication chart, one column per smooth case (contact, M, L, D) of a
//! [`MixedMap`]: on top the film ratio H_c/H_c,smooth (solid) and H_min/H_min,smooth (dashed)
//! against Lambda = H_min/sigma, below the asperity share of the load against Lambda; one colour
//! per roughness orientation gamma (log Lambda axes). At most [`COLUMNS`] cases per row.

use crate::model::roughness::{gamma_label, orientation};
use crate::render::style::{e, ensure_font, series_legend, RenderError, COLORS};
use crate::report::mixed::{MixedCurve, MixedMap};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// Cases per row of the chart.
pub const COLUMNS: usize = 3;
/// Asperity shares below this (none, or too small to matter) sit on the floor of the log axis.
const FLOOR: f64 = 1e-6;

/// Write the chart of `map` to `path` (PNG).
pub fn mixed_chart(path: &Path, map: &MixedMap) -> Result<(), RenderError> {
    ensure_font();
    // The smooth cases in the map's order, each with its curves (one per gamma).
    let mut cases: Vec<Vec<&MixedCurve>> = vec![];
    for c in &map.curves {
        match cases.last_mut() {
            Some(g) if same_case(g[0], c) => g.push(c),
            _ => cases.push(vec![c]),
        }
    }
    let cols = cases.len().clamp(1, COLUMNS);
    let rows = cases.len().div_ceil(COLUMNS).max(1);
    let root = BitMapBackend::new(path, (440 * cols as u32, 720 * rows as u32)).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    let areas = root.split_evenly((rows, cols));
    let pts = || map.curves.iter().flat_map(|c| c.points.iter());
    let lmin = pts()
        .map(|p| p.lambda)
        .fold(f64::INFINITY, f64::min)
        .max(1e-3)
        * 0.8;
    let lmax = pts().map(|p| p.lambda).fold(1e-2, f64::max) * 1.25;
    for (area, curves) in areas.iter().zip(&cases) {
        let (top, bottom) = area.split_vertically(380);
        film_panel(&top, curves, lmin..lmax)?;
        share_panel(&bottom, curves, lmin..lmax)?;
    }
    root.present().map_err(e)
}

fn same_case(a: &MixedCurve, b: &MixedCurve) -> bool {
    a.contact == b.contact && a.m == b.m && a.l == b.l && a.d == b.d
}

/// The case's name without the orientation.
fn case_name(c: &MixedCurve) -> String {
    let d = c.d.map_or(String::new(), |d| format!(" D={d}"));
    format!("{} M={} L={}{d}", c.contact, c.m, c.l)
}

fn orientation_label(gamma: f64) -> String {
    format!("gamma={} {}", gamma_label(gamma), orientation(gamma))
}

fn film_panel(
    area: &DrawingArea<BitMapBackend, Shift>,
    curves: &[&MixedCurve],
    lambda: std::ops::Range<f64>,
) -> Result<(), RenderError> {
    let all = || curves.iter().flat_map(|c| c.points.iter());
    let (rmin, rmax) = all()
        .flat_map(|p| [p.h_c_ratio, p.h_min_ratio])
        .fold((1.0f64, 1.0f64), |(a, b), v| (a.min(v), b.max(v)));
    let pad = 0.05 * (rmax - rmin).max(0.01);
    let mut ch = ChartBuilder::on(area)
        .caption(case_name(curves[0]), ("sans-serif", 17))
        .margin(10)
        .x_label_area_size(34)
        .y_label_area_size(50)
        .build_cartesian_2d(lambda.log_scale(), (rmin - pad)..(rmax + pad))
        .map_err(e)?;
    ch.configure_mesh()
        .x_desc("Lambda = H_min/sigma")
        .y_desc("H/H_smooth (H_c solid, H_min dashed)")
        .draw()
        .map_err(e)?;
    for (k, c) in curves.iter().enumerate() {
        let col = COLORS[k % COLORS.len()];
        let hc: Vec<(f64, f64)> = c.points.iter().map(|p| (p.lambda, p.h_c_ratio)).collect();
        let hm: Vec<(f64, f64)> = c.points.iter().map(|p| (p.lambda, p.h_min_ratio)).collect();
        ch.draw_series(LineSeries::new(hc.clone(), col.stroke_width(2)))
            .map_err(e)?
            .label(orientation_label(c.gamma))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], col.stroke_width(2)));
        ch.draw_series(hc.iter().map(|&p| Circle::new(p, 3, col.filled())))
            .map_err(e)?;
        ch.draw_series(DashedLineSeries::new(hm, 6, 4, col.stroke_width(1)))
            .map_err(e)?;
    }
    series_legend(&mut ch, SeriesLabelPosition::UpperRight)
}

fn share_panel(
    area: &DrawingArea<BitMapBackend, Shift>,
    curves: &[&MixedCurve],
    lambda: std::ops::Range<f64>,
) -> Result<(), RenderError> {
    let smax = curves
        .iter()
        .flat_map(|c| c.points.iter())
        .map(|p| p.asperity_load_fraction)
        .fold(1e-4, f64::max)
        * 2.0;
    let mut ch = ChartBuilder::on(area)
        .margin(10)
        .x_label_area_size(34)
        .y_label_area_size(50)
        .build_cartesian_2d(lambda.log_scale(), (FLOOR..smax).log_scale())
        .map_err(e)?;
    ch.configure_mesh()
        .x_desc("Lambda = H_min/sigma")
        .y_desc("asperity load / load")
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .draw()
        .map_err(e)?;
    for (k, c) in curves.iter().enumerate() {
        let col = COLORS[k % COLORS.len()];
        let s: Vec<(f64, f64)> = c
            .points
            .iter()
            .map(|p| (p.lambda, p.asperity_load_fraction.max(FLOOR)))
            .collect();
        ch.draw_series(LineSeries::new(s.clone(), col.stroke_width(2)))
            .map_err(e)?;
        ch.draw_series(s.iter().map(|&p| Circle::new(p, 3, col.filled())))
            .map_err(e)?;
    }
    Ok(())
}
