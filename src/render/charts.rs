//! Charts of a fit (PNG and SVG via plotters; text by ab_glyph with the bundled DejaVu Sans, so
//! nothing is needed from the system), per contact: parity plot (fit and the published formula),
//! H_c over M per L with the fitted formula and its four asymptotes (dashed), the relative-error
//! map over (log M, L), and the contour map of the fitted H_c(M, L) with the regime boundaries
//! (where two asymptotes cross) as contour lines of ln(H_a/H_b) = 0, by marching squares, and the
//! validity map of its held-out errors ([`crate::render::validity_map`]).
//! Point charts are drawn at D = 1 (curves, contours) or over all D (parity, error map).

use crate::fit::heldout::HeldOut;
use crate::render::charts_map::{error_map, regime_map};
use crate::render::style::{both, distinct, e, log_grid, series_legend, Ctx, RenderError, Res};
use crate::render::validity_map::validity_map;
use crate::report::{Blend, Film, FitPoint, FittedModel};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

fn parity<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, c: &Ctx) -> Res {
    let pts = c.pts;
    let lo = pts.iter().map(|p| p.h_c).fold(f64::INFINITY, f64::min) * 0.8;
    let hi = pts.iter().map(|p| p.h_c).fold(0.0, f64::max) * 1.25;
    let title = match c.model.blend {
        Blend::Line(_) => "Fitted formula vs numerics (H_c, line)",
        Blend::Point(_) => "Fitted formula vs numerics (H_c, point, all D)",
    };
    let mut ch = ChartBuilder::on(root)
        .caption(title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(56)
        .build_cartesian_2d((lo..hi).log_scale(), (lo..hi).log_scale())
        .map_err(e)?;
    ch.configure_mesh()
        .x_desc("H_c numerical")
        .y_desc("H_c formula")
        .draw()
        .map_err(e)?;
    ch.draw_series(LineSeries::new([(lo, lo), (hi, hi)], BLACK.stroke_width(1)))
        .map_err(e)?;
    let dd = |p: &FitPoint| p.d.unwrap_or(1.0);
    ch.draw_series(
        pts.iter()
            .map(|p| Circle::new((p.h_c, c.model.eval(p.m, p.l, dd(p))), 3, BLUE.filled())),
    )
    .map_err(e)?
    .label("fit")
    .legend(|(x, y)| Circle::new((x, y), 3, BLUE.filled()));
    ch.draw_series(pts.iter().map(|p| {
        Cross::new(
            (p.h_c, c.published(p.m, p.l, dd(p))),
            3,
            RED.stroke_width(1),
        )
    }))
    .map_err(e)?
    .label(c.published_name())
    .legend(|(x, y)| Cross::new((x, y), 3, RED.stroke_width(1)));
    series_legend(&mut ch, SeriesLabelPosition::UpperLeft)?;
    Ok(())
}

fn curves<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, c: &Ctx) -> Res {
    let pts = c.at_d();
    let m_lo = pts.iter().map(|p| p.m).fold(f64::INFINITY, f64::min) * 0.8;
    let m_hi = pts.iter().map(|p| p.m).fold(0.0, f64::max) * 1.25;
    let h_lo = pts.iter().map(|p| p.h_c).fold(f64::INFINITY, f64::min) * 0.6;
    let h_hi = pts.iter().map(|p| p.h_c).fold(0.0, f64::max) * 1.6;
    let ls = distinct(pts.iter().map(|p| p.l).collect());
    let areas = root.split_evenly((1, 2));
    let grid = log_grid(m_lo, m_hi, 120);
    let names = ["RI", "EI", "RP", "EP"];
    // Left panel: per L, fit (solid), data (dots), published (thin dotted); right panel: the
    // fitted formula with its four asymptotes (dashed) for the smallest and largest L.
    let mut ch = ChartBuilder::on(&areas[0])
        .caption(
            format!("H_c over M per L{}", c.suffix()),
            ("sans-serif", 18),
        )
        .margin(10)
        .x_label_area_size(36)
        .y_label_area_size(52)
        .build_cartesian_2d((m_lo..m_hi).log_scale(), (h_lo..h_hi).log_scale())
        .map_err(e)?;
    ch.configure_mesh()
        .x_desc("M")
        .y_desc("H_c (Moes units)")
        .draw()
        .map_err(e)?;
    for (k, &l) in ls.iter().enumerate() {
        let color = Palette99::pick(k).to_rgba();
        ch.draw_series(LineSeries::new(
            grid.iter().map(|&m| (m, c.eval(m, l))),
            color.stroke_width(2),
        ))
        .map_err(e)?
        .label(format!("L = {l}"))
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], color.stroke_width(2)));
        ch.draw_series(DashedLineSeries::new(
            grid.iter().map(|&m| (m, c.published(m, l, c.d))),
            2,
            4,
            color.stroke_width(1),
        ))
        .map_err(e)?;
        ch.draw_series(
            pts.iter()
                .filter(|p| (p.l - l).abs() <= 1e-9 * l.max(1.0))
                .map(|p| Circle::new((p.m, p.h_c), 4, color.filled())),
        )
        .map_err(e)?;
    }
    series_legend(&mut ch, SeriesLabelPosition::UpperRight)?;
    let mut ch = ChartBuilder::on(&areas[1])
        .caption(
            "fit (solid) and its asymptotes (dashed)",
            ("sans-serif", 18),
        )
        .margin(10)
        .x_label_area_size(36)
        .y_label_area_size(52)
        .build_cartesian_2d((m_lo..m_hi).log_scale(), (h_lo..h_hi).log_scale())
        .map_err(e)?;
    ch.configure_mesh().x_desc("M").draw().map_err(e)?;
    let colors = [BLACK, RED, GREEN, BLUE];
    let show: Vec<f64> = match (ls.first(), ls.last()) {
        (Some(&a), Some(&b)) if b > a && a == 0.0 => vec![b],
        (Some(&a), Some(&b)) if b > a => vec![a, b],
        (Some(&a), _) => vec![a],
        _ => vec![],
    };
    for &l in &show {
        ch.draw_series(LineSeries::new(
            grid.iter().map(|&m| (m, c.eval(m, l))),
            BLACK.stroke_width(2),
        ))
        .map_err(e)?;
        for (k, name) in names.iter().enumerate() {
            if l == 0.0 && k >= 2 {
                continue;
            }
            let col = colors[k];
            let s = ch
                .draw_series(DashedLineSeries::new(
                    grid.iter()
                        .map(|&m| (m, c.asymptotes(m, l)[k]))
                        .filter(|&(_, h)| h > h_lo && h < h_hi),
                    6,
                    4,
                    col.stroke_width(2),
                ))
                .map_err(e)?;
            if l == show[0] {
                s.label(format!("H_{name}")).legend(move |(x, y)| {
                    PathElement::new([(x, y), (x + 16, y)], col.stroke_width(2))
                });
            }
        }
    }
    // The L = 0 iso asymptotes as well, when L = 0 is in the data.
    if ls.first() == Some(&0.0) {
        ch.draw_series(LineSeries::new(
            grid.iter().map(|&m| (m, c.eval(m, 0.0))),
            RGBColor(120, 120, 120).stroke_width(2),
        ))
        .map_err(e)?
        .label("fit, L = 0")
        .legend(|(x, y)| {
            PathElement::new(
                [(x, y), (x + 16, y)],
                RGBColor(120, 120, 120).stroke_width(2),
            )
        });
    }
    series_legend(&mut ch, SeriesLabelPosition::UpperRight)?;
    Ok(())
}

/// Write the charts of one contact (PNG and SVG) into `dir`, file stems prefixed with `prefix`;
/// returns the stems.
pub fn write_charts(
    dir: &Path,
    prefix: &str,
    pts: &[FitPoint],
    model: &FittedModel,
    heldout: Option<&HeldOut>,
) -> Result<Vec<String>, RenderError> {
    // The charts show H_c: the cases whose H_c is within the fit's error limit.
    let pts: &[FitPoint] = &pts
        .iter()
        .filter(|p| p.film(Film::Centre).is_some())
        .copied()
        .collect::<Vec<_>>();
    if pts.is_empty() {
        return Ok(vec![]);
    }
    // Point charts at the largest D of the data (1, circular, in the sweeps).
    let d = pts.iter().filter_map(|p| p.d).fold(0.0f64, f64::max);
    let d = if d > 0.0 { d } else { 1.0 };
    let c = Ctx { pts, model, d };
    let mut stems = vec![];
    macro_rules! chart {
        ($name:literal, $draw:ident, $size:expr) => {
            let stem = format!("{prefix}{}", $name);
            both(&dir.join(&stem), $size, |r| $draw(r, &c), |r| $draw(r, &c))?;
            stems.push(stem);
        };
    }
    chart!("parity", parity, (900, 700));
    chart!("hc_vs_m", curves, (1400, 650));
    chart!("error_map", error_map, (900, 650));
    chart!("regime_map", regime_map, (1000, 700));
    if let Some(h) = heldout.filter(|h| !h.cases.is_empty()) {
        let point = matches!(model.blend, Blend::Point(_));
        let panels = if point {
            distinct(h.cases.iter().map(|c| c.d).collect()).len()
        } else {
            1
        };
        let size = (1100, 80 + 420 * panels.div_ceil(2) as u32);
        let (cases, film) = (&h.cases, Film::Centre.name());
        let stem = format!("{prefix}validity_map");
        both(
            &dir.join(&stem),
            size,
            |r| validity_map(r, cases, film, point),
            |r| validity_map(r, cases, film, point),
        )?;
        stems.push(stem);
    }
    Ok(stems)
}
