//! Pictures of one solution (PNG and SVG via plotters, bundled DejaVu font of the fit charts).
//!
//! * `STEM-profile`: the centre-line (Y = 0) pressure P = p/p_h over X = x/b with the Hertz
//!   pressure `sqrt(1 - X^2)` (dashed; exact on the centre line of an elliptic contact too) and the
//!   pressure spike marked, and on rough surfaces the asperity pressure P_a (red, scaled by a
//!   power of 10 named in its label); below it the film H (Moes units) with H_c (X = 0) and H_min
//!   marked.
//! * point contacts also `STEM-film`: iso-lines of H (the horseshoe) by [`crate::render::contour`] at levels
//!   from H_min to 2.5 H_c, with the Hertz ellipse `X^2 + (Y/k)^2 = 1`, H_c and H_min marked;
//!   and `STEM-pressure`: a filled colour map of P/P_max (blue 0 to red 1) with the ellipse.

use crate::render::style::{e, series_legend, RenderError, Res};
use crate::solve::point::PointFields;
use crate::solve::solution::{Outputs, Profile};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// Draw with `f` on a PNG and an SVG backend: `dir/stem.png`, `dir/stem.svg`.
fn both(
    dir: &Path,
    stem: &str,
    size: (u32, u32),
    f: impl Fn(&DrawingArea<BitMapBackend, Shift>) -> Res,
    g: impl Fn(&DrawingArea<SVGBackend, Shift>) -> Res,
) -> Result<Vec<PathBuf>, RenderError> {
    std::fs::create_dir_all(dir).map_err(|x| format!("--plot {}: {x}", dir.display()))?;
    crate::render::style::both(&dir.join(stem), size, f, g)?;
    Ok(vec![
        dir.join(format!("{stem}.png")),
        dir.join(format!("{stem}.svg")),
    ])
}

/// Centre-line data: X, P, H and the outputs.
struct Line<'a> {
    x: &'a [f64],
    p: &'a [f64],
    h: &'a [f64],
    /// The asperity pressure (rough surfaces).
    pa: Option<&'a [f64]>,
    o: &'a Outputs,
    title: &'a str,
}

fn range(v: &[f64]) -> (f64, f64) {
    let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (lo, hi)
}

fn profile<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, l: &Line) -> Res {
    let (top, bottom) = root.split_vertically(330);
    // the far inlet carries no pressure: show at most 4 half-widths upstream
    let (x0, x1) = (l.x[0].max(-4.0), *l.x.last().unwrap_or(&1.0));
    let p_hi = l.o.p_max.max(1.0) * 1.1;
    let mut ch = ChartBuilder::on(&top)
        .caption(l.title, ("sans-serif", 20))
        .margin(10)
        .x_label_area_size(30)
        .y_label_area_size(60)
        .build_cartesian_2d(x0..x1, 0.0..p_hi)
        .map_err(e)?;
    ch.configure_mesh().y_desc("P = p/p_h").draw().map_err(e)?;
    ch.draw_series(LineSeries::new(
        l.x.iter()
            .zip(l.p)
            .filter(|(x, _)| **x >= x0)
            .map(|(a, b)| (*a, *b)),
        BLUE.stroke_width(2),
    ))
    .map_err(e)?
    .label("P (ehlmap)")
    .legend(|(x, y)| PathElement::new([(x, y), (x + 18, y)], BLUE.stroke_width(2)));
    let hertz: Vec<_> = (0..=200)
        .map(|i| {
            let x = -1.0 + 2.0 * i as f64 / 200.0;
            (x, (1.0 - x * x).max(0.0).sqrt())
        })
        .collect();
    ch.draw_series(DashedLineSeries::new(hertz, 6, 4, BLACK.stroke_width(1)))
        .map_err(e)?
        .label("Hertz")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 18, y)], BLACK.stroke_width(1)));
    if let Some(pa) = l.pa {
        // Scaled by a power of 10 so that its maximum reaches at least a tenth of the chart.
        let (_, top) = range(pa);
        if top > 0.0 {
            let k = (0.1 * p_hi / top).log10().ceil().max(0.0);
            let scale = 10f64.powf(k);
            ch.draw_series(LineSeries::new(
                l.x.iter()
                    .zip(pa)
                    .filter(|(x, _)| **x >= x0)
                    .map(|(a, b)| (*a, b * scale)),
                RED.stroke_width(2),
            ))
            .map_err(e)?
            .label(format!("P_a asperities x {scale:.0}"))
            .legend(|(x, y)| PathElement::new([(x, y), (x + 18, y)], RED.stroke_width(2)));
        }
    }
    if let Some(s) = l.o.spike {
        ch.draw_series([
            Circle::new((s.x, s.p), 6, RED.stroke_width(2)).into_dyn(),
            Text::new(
                format!("spike P = {:.3}", s.p),
                (s.x - 1.5, s.p * 1.06),
                ("sans-serif", 15).into_font().color(&RED),
            )
            .into_dyn(),
        ])
        .map_err(e)?;
    }
    series_legend(&mut ch, SeriesLabelPosition::UpperLeft)?;
    // film: show up to 4 H_c so the contact region is readable
    let (h_lo, h_all) = range(l.h);
    let h_hi = (4.0 * l.o.h_c).min(h_all).max(1.5 * l.o.h_c);
    let mut ch = ChartBuilder::on(&bottom)
        .margin(10)
        .x_label_area_size(36)
        .y_label_area_size(60)
        .build_cartesian_2d(x0..x1, (0.8 * h_lo).min(0.6 * l.o.h_min)..h_hi)
        .map_err(e)?;
    ch.configure_mesh()
        .x_desc("X = x/b (rolling direction)")
        .y_desc("H (Moes)")
        .draw()
        .map_err(e)?;
    ch.draw_series(LineSeries::new(
        l.x.iter()
            .zip(l.h)
            .filter(|(x, h)| **h <= h_hi && **x >= x0)
            .map(|(a, b)| (*a, *b)),
        GREEN.stroke_width(2),
    ))
    .map_err(e)?;
    marks(&mut ch, l.o, l.o.x_min)?;
    Ok(())
}

/// H_c at (0, y0 of the chart) and H_min at its position, with labels.
fn marks<DB: DrawingBackend>(
    ch: &mut ChartContext<
        DB,
        Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
    >,
    o: &Outputs,
    x_min: f64,
) -> Res {
    let font = ("sans-serif", 15).into_font();
    ch.draw_series([
        Circle::new((0.0, o.h_c), 5, BLACK.filled()).into_dyn(),
        Text::new(
            format!("H_c = {:.4}", o.h_c),
            (0.05, o.h_c * 1.2),
            font.clone(),
        )
        .into_dyn(),
        Cross::new((x_min, o.h_min), 6, RED.stroke_width(2)).into_dyn(),
        Text::new(
            format!("H_min = {:.4}", o.h_min),
            (x_min - 0.9, o.h_min * 0.95),
            font.color(&RED),
        )
        .into_dyn(),
    ])
    .map_err(e)?;
    Ok(())
}

/// `STEM-profile.{png,svg}` of a line solution.
pub fn draw_line(
    dir: &Path,
    stem: &str,
    prof: &Profile,
    o: &Outputs,
) -> Result<Vec<PathBuf>, RenderError> {
    let l = Line {
        x: &prof.x,
        p: &prof.p,
        h: &prof.h,
        pa: prof.p_asperity.as_deref(),
        o,
        title: "Line contact: centre-line pressure and film",
    };
    both(
        dir,
        &format!("{stem}-profile"),
        (900, 640),
        |r| profile(r, &l),
        |r| profile(r, &l),
    )
}

fn ellipse(k: f64) -> Vec<(f64, f64)> {
    (0..=240)
        .map(|i| {
            let t = 2.0 * std::f64::consts::PI * i as f64 / 240.0;
            (t.cos(), k * t.sin())
        })
        .collect()
}

/// Picture size keeping the X:Y aspect near 1 (plot area about 760 px wide).
fn map_size(f: &PointFields) -> (u32, u32) {
    let (x0, x1) = range(&f.x);
    let (y0, y1) = range(&f.y);
    let h = 760.0 * (y1 - y0) / (x1 - x0);
    (900, (h.clamp(300.0, 1400.0) + 120.0) as u32)
}

fn map_axes<'a, DB: DrawingBackend + 'a>(
    root: &'a DrawingArea<DB, Shift>,
    f: &PointFields,
    title: &str,
) -> Result<
    ChartContext<
        'a,
        DB,
        Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
    >,
    RenderError,
> {
    let (x0, x1) = range(&f.x);
    let (y0, y1) = range(&f.y);
    let mut ch = ChartBuilder::on(root)
        .caption(title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(50)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(e)?;
    ch.configure_mesh()
        .disable_mesh()
        .x_desc("X = x/b (rolling)")
        .y_desc("Y = y/b")
        .draw()
        .map_err(e)?;
    Ok(ch)
}

fn film_map<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    f: &PointFields,
    o: &Outputs,
) -> Res {
    let k = o.k.unwrap_or(1.0);
    let mut ch = map_axes(
        root,
        f,
        "Film H (Moes units): iso-lines; Hertz ellipse dashed",
    )?;
    // geometric levels, dense near the minimum where the horseshoe is
    let (lo, hi) = (o.h_min * 1.02, 2.5 * o.h_c);
    let n = 12;
    for i in 0..n {
        let c = lo * (hi / lo).powf(i as f64 / (n - 1) as f64);
        let col = HSLColor(0.7 * i as f64 / (n - 1) as f64, 0.9, 0.4);
        ch.draw_series(
            crate::render::contour::contour_segments(&f.x, &f.y, &f.h, c)
                .into_iter()
                .map(move |s| PathElement::new(s.to_vec(), col.stroke_width(2))),
        )
        .map_err(e)?;
    }
    ch.draw_series(DashedLineSeries::new(
        ellipse(k),
        6,
        4,
        BLACK.stroke_width(1),
    ))
    .map_err(e)?;
    let y_min = o.y_min.unwrap_or(0.0);
    let font = ("sans-serif", 15).into_font();
    ch.draw_series([
        Circle::new((0.0, 0.0), 5, BLACK.filled()).into_dyn(),
        Text::new(format!("H_c = {:.4}", o.h_c), (0.05, 0.1), font.clone()).into_dyn(),
        Cross::new((o.x_min, y_min), 7, RED.stroke_width(3)).into_dyn(),
        Text::new(
            format!("H_min = {:.4}", o.h_min),
            (o.x_min - 1.2, y_min + 0.15 * k),
            font.color(&RED),
        )
        .into_dyn(),
    ])
    .map_err(e)?;
    // the symmetric minimum on the other side
    ch.draw_series([Cross::new((o.x_min, -y_min), 7, RED.stroke_width(3))])
        .map_err(e)?;
    let levels = format!("levels {lo:.3} (red) .. {hi:.3} (violet), {n} geometric");
    ch.draw_series([Text::new(levels, (f.x[1], f.y[1]), font)])
        .map_err(e)?;
    Ok(())
}

fn pressure_map<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    f: &PointFields,
    o: &Outputs,
) -> Res {
    let k = o.k.unwrap_or(1.0);
    let mut ch = map_axes(
        root,
        f,
        &format!("Pressure P/P_max, P_max = {:.3} (blue 0, red 1)", o.p_max),
    )?;
    let nx = f.x.len();
    let pm = o.p_max.max(1e-300);
    let mut cells = Vec::new();
    for j in 0..f.y.len() - 1 {
        for i in 0..nx - 1 {
            let p = 0.25
                * (f.p[j * nx + i]
                    + f.p[j * nx + i + 1]
                    + f.p[(j + 1) * nx + i]
                    + f.p[(j + 1) * nx + i + 1]);
            let t = (p / pm).clamp(0.0, 1.0);
            if t > 0.02 {
                let col = HSLColor(0.66 * (1.0 - t), 0.85, 0.5);
                cells.push(Rectangle::new(
                    [(f.x[i], f.y[j]), (f.x[i + 1], f.y[j + 1])],
                    col.filled(),
                ));
            }
        }
    }
    ch.draw_series(cells).map_err(e)?;
    ch.draw_series(DashedLineSeries::new(
        ellipse(k),
        6,
        4,
        BLACK.stroke_width(1),
    ))
    .map_err(e)?;
    Ok(())
}

/// `STEM-profile`, `STEM-film` and `STEM-pressure` (PNG and SVG) of a point solution.
pub fn draw_point(
    dir: &Path,
    stem: &str,
    f: &PointFields,
    o: &Outputs,
) -> Result<Vec<PathBuf>, RenderError> {
    let nx = f.x.len();
    // centre line: the row nearest Y = 0
    let j0 = (0..f.y.len())
        .min_by(|a, b| f.y[*a].abs().total_cmp(&f.y[*b].abs()))
        .unwrap_or(0);
    let p = &f.p[j0 * nx..(j0 + 1) * nx];
    let h = &f.h[j0 * nx..(j0 + 1) * nx];
    let title = format!(
        "Point contact D = {:.4}: centre line Y = 0",
        o.d.unwrap_or(1.0)
    );
    let pa = f.p_asperity.as_ref().map(|pa| &pa[j0 * nx..(j0 + 1) * nx]);
    let l = Line {
        x: &f.x,
        p,
        h,
        pa,
        o,
        title: &title,
    };
    let mut files = both(
        dir,
        &format!("{stem}-profile"),
        (900, 640),
        |r| profile(r, &l),
        |r| profile(r, &l),
    )?;
    let size = map_size(f);
    files.extend(both(
        dir,
        &format!("{stem}-film"),
        size,
        |r| film_map(r, f, o),
        |r| film_map(r, f, o),
    )?);
    files.extend(both(
        dir,
        &format!("{stem}-pressure"),
        size,
        |r| pressure_map(r, f, o),
        |r| pressure_map(r, f, o),
    )?);
    Ok(files)
}
