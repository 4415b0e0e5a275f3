//! The two (log M, L) maps of a fit: the relative-error map of the data, and the contour map of
//! the fitted H_c(M, L) (log-spaced levels) with the regime boundaries RI = EI, RP = EP and
//! isoviscous bracket = piezoviscous bracket (the point blend's 3/2 and 8 powers, the line
//! fit's p and q) drawn as the zero contours of ln(H_a/H_b).
//! Contours by marching squares on a 160 x 120 grid in (ln M, L), linear interpolation on cell
//! edges (a saddle cell gives two segments).

use crate::render::style::{case_map, e, log_grid, Ctx, MapChart, Res};
use crate::report::Blend;
use plotters::coord::Shift;
use plotters::prelude::*;

/// Segments of the contour f = 0 of values `v[i][j]` on the grid (xs[i], ys[j]).
pub(crate) fn contour(xs: &[f64], ys: &[f64], v: &[Vec<f64>]) -> Vec<[(f64, f64); 2]> {
    let mut out = vec![];
    let cut = |a: (f64, f64, f64), b: (f64, f64, f64)| {
        // Point where the value crosses 0 on the edge a-b (x interpolated in ln x).
        let t = a.2 / (a.2 - b.2);
        (
            (a.0.ln() + t * (b.0.ln() - a.0.ln())).exp(),
            a.1 + t * (b.1 - a.1),
        )
    };
    for i in 0..xs.len() - 1 {
        for j in 0..ys.len() - 1 {
            let c = [
                (xs[i], ys[j], v[i][j]),
                (xs[i + 1], ys[j], v[i + 1][j]),
                (xs[i + 1], ys[j + 1], v[i + 1][j + 1]),
                (xs[i], ys[j + 1], v[i][j + 1]),
            ];
            if c.iter().any(|p| !p.2.is_finite()) {
                continue;
            }
            let hits: Vec<(f64, f64)> = (0..4)
                .filter_map(|k| {
                    let (a, b) = (c[k], c[(k + 1) % 4]);
                    ((a.2 < 0.0) != (b.2 < 0.0)).then(|| cut(a, b))
                })
                .collect();
            if hits.len() >= 2 {
                out.push([hits[0], hits[1]]);
            }
            if hits.len() == 4 {
                out.push([hits[2], hits[3]]);
            }
        }
    }
    out
}

pub(crate) fn error_map<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, c: &Ctx) -> Res {
    let pts = c.pts;
    let m_lo = pts.iter().map(|p| p.m).fold(f64::INFINITY, f64::min);
    let m_hi = pts.iter().map(|p| p.m).fold(0.0, f64::max);
    let l_hi = pts.iter().map(|p| p.l).fold(0.0, f64::max).max(1.0);
    let errs: Vec<f64> = pts
        .iter()
        .map(|p| c.model.eval(p.m, p.l, p.d.unwrap_or(1.0)) / p.h_c - 1.0)
        .collect();
    let emax = errs.iter().fold(1e-6f64, |a, v| a.max(v.abs()));
    let what = match c.model.blend {
        Blend::Line(_) => "line",
        Blend::Point(_) => "point, all D overlaid",
    };
    let caption = format!(
        "Fit error ({what}): red +, blue -, full colour = {:.2} %",
        100.0 * emax
    );
    let mut ch = case_map(root, &caption, 20, (m_lo, m_hi, l_hi))?;
    ch.draw_series(pts.iter().zip(&errs).map(|(p, &err)| {
        let t = (err.abs() / emax).clamp(0.0, 1.0);
        let col = if err >= 0.0 {
            RGBColor(255, (255.0 * (1.0 - t)) as u8, (255.0 * (1.0 - t)) as u8)
        } else {
            RGBColor((255.0 * (1.0 - t)) as u8, (255.0 * (1.0 - t)) as u8, 255)
        };
        EmptyElement::at((p.m, p.l))
            + Circle::new((0, 0), 7, col.filled())
            + Circle::new((0, 0), 7, BLACK.stroke_width(1))
    }))
    .map_err(e)?;
    Ok(())
}

/// A regime boundary: its name, colour and the function whose zero contour it is.
type Boundary<'a> = (&'static str, RGBColor, Box<dyn Fn(f64, f64) -> f64 + 'a>);

/// The sampling grid of the contours: 161 log-spaced M values by 121 L values from 0 to l_hi.
struct Grid {
    xs: Vec<f64>,
    ys: Vec<f64>,
}

impl Grid {
    fn new(m_lo: f64, m_hi: f64, l_hi: f64) -> Self {
        let xs = log_grid(m_lo, m_hi, 160);
        let ys: Vec<f64> = (0..=120).map(|j| l_hi * j as f64 / 120.0).collect();
        Grid { xs, ys }
    }

    /// The values of `f` on the grid, `[i][j]` at (xs[i], ys[j]).
    fn field(&self, f: &dyn Fn(f64, f64) -> f64) -> Vec<Vec<f64>> {
        self.xs
            .iter()
            .map(|&m| self.ys.iter().map(|&l| f(m, l)).collect())
            .collect()
    }
}

pub(crate) fn regime_map<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, c: &Ctx) -> Res {
    let pts = c.at_d();
    let m_lo = pts.iter().map(|p| p.m).fold(f64::INFINITY, f64::min) * 0.8;
    let m_hi = pts.iter().map(|p| p.m).fold(0.0, f64::max) * 1.25;
    let l_hi = pts.iter().map(|p| p.l).fold(0.0, f64::max).max(1.0);
    let mut ch = ChartBuilder::on(root)
        .caption(
            format!(
                "Fitted H_c(M, L): contours and regime boundaries{}",
                c.suffix()
            ),
            ("sans-serif", 19),
        )
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(48)
        .right_y_label_area_size(10)
        .build_cartesian_2d((m_lo..m_hi).log_scale(), 0.0..l_hi)
        .map_err(e)?;
    ch.configure_mesh()
        .x_desc("M")
        .y_desc("L")
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(e)?;
    let grid = Grid::new(m_lo, m_hi, l_hi);
    draw_hc_contours(&mut ch, &grid, c, m_hi, l_hi)?;
    draw_boundaries(&mut ch, &grid, &boundaries(c))?;
    ch.draw_series(
        pts.iter()
            .map(|p| Cross::new((p.m, p.l), 4, RGBColor(40, 40, 200).stroke_width(1))),
    )
    .map_err(e)?
    .label("solved cases")
    .legend(|(x, y)| Cross::new((x, y), 4, RGBColor(40, 40, 200).stroke_width(1)));
    ch.configure_series_labels()
        .position(SeriesLabelPosition::LowerRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(e)?;
    Ok(())
}

/// The H_c contour levels within (exp(hmin), exp(hmax)) of ln H_c field `h`: 1-1.5-2-3-5-7 per
/// decade.
fn hc_levels(h: &[Vec<f64>]) -> Vec<f64> {
    let (hmin, hmax) = h
        .iter()
        .flatten()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let mut levels = vec![];
    for dec in -4..4 {
        for f in [1.0, 1.5, 2.0, 3.0, 5.0, 7.0] {
            let lv = f * 10f64.powi(dec);
            if lv.ln() > hmin && lv.ln() < hmax {
                levels.push(lv);
            }
        }
    }
    levels
}

/// The fitted H_c as grey contours, each labelled at its segment nearest the top of the map.
fn draw_hc_contours<DB: DrawingBackend>(
    ch: &mut MapChart<DB>,
    grid: &Grid,
    c: &Ctx,
    m_hi: f64,
    l_hi: f64,
) -> Res {
    let h = grid.field(&|m, l| c.eval(m, l).ln());
    let levels = hc_levels(&h);
    let grey = RGBColor(110, 110, 110);
    for (k, &lv) in levels.iter().enumerate() {
        let v: Vec<Vec<f64>> = h
            .iter()
            .map(|r| r.iter().map(|x| x - lv.ln()).collect())
            .collect();
        let segs = contour(&grid.xs, &grid.ys, &v);
        let s = ch
            .draw_series(
                segs.iter()
                    .map(|s| PathElement::new(s.to_vec(), grey.stroke_width(1))),
            )
            .map_err(e)?;
        if k == 0 {
            s.label("H_c contours (1-1.5-2-3-5-7 per decade)")
                .legend(move |(x, y)| {
                    PathElement::new([(x, y), (x + 16, y)], grey.stroke_width(1))
                });
        }
        // Label at the segment nearest the top of the map.
        if let Some(top) = segs
            .iter()
            .max_by(|a, b| a[0].1.total_cmp(&b[0].1))
            .filter(|s| s[0].1 > 0.85 * l_hi || s[0].0 > 0.7 * m_hi)
        {
            ch.draw_series(std::iter::once(Text::new(
                format!("{lv}"),
                top[0],
                ("sans-serif", 13).into_font().color(&grey),
            )))
            .map_err(e)?;
        }
    }
    Ok(())
}

/// The regime boundaries of the fit: RI = EI, RP = EP and isoviscous = piezoviscous bracket.
fn boundaries<'a>(c: &'a Ctx) -> Vec<Boundary<'a>> {
    let a = |m: f64, l: f64| c.asymptotes(m, l);
    let (p, q) = match &c.model.blend {
        Blend::Line(x) => (x.x[7], x.x[8]),
        Blend::Point(_) => (1.5, 8.0),
    };
    vec![
        (
            "RI = EI",
            RGBColor(0, 0, 0),
            Box::new(move |m, l| (a(m, l)[0] / a(m, l)[1]).ln()),
        ),
        (
            "RP = EP",
            RGBColor(210, 30, 30),
            Box::new(move |m, l| (a(m, l)[2] / a(m, l)[3]).ln()),
        ),
        (
            "isoviscous = piezoviscous bracket",
            RGBColor(20, 140, 40),
            Box::new(move |m, l| {
                let h = a(m, l);
                let iso = (h[0].powf(p) + h[1].powf(p)).powf(1.0 / p);
                let piezo = (h[2].powf(-q) + h[3].powf(-q)).powf(-1.0 / q);
                (iso / piezo).ln()
            }),
        ),
    ]
}

/// Each boundary as the zero contour of its function over L > 0, in its colour.
fn draw_boundaries<DB: DrawingBackend>(
    ch: &mut MapChart<DB>,
    grid: &Grid,
    bounds: &[Boundary],
) -> Res {
    for (name, col, f) in bounds {
        let v = grid.field(&|m, l| if l > 0.0 { f(m, l) } else { f64::NAN });
        let segs = contour(&grid.xs, &grid.ys, &v);
        let col = *col;
        ch.draw_series(
            segs.iter()
                .map(|s| PathElement::new(s.to_vec(), col.stroke_width(3))),
        )
        .map_err(e)?
        .label(*name)
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], col.stroke_width(3)));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contour_of_a_plane_is_the_straight_line() {
        // f = L - 2 on x in [1, 100] (log), y in [0, 4]: the contour is y = 2 everywhere.
        let xs = log_grid(1.0, 100.0, 10);
        let ys: Vec<f64> = (0..=8).map(|j| j as f64 * 0.5 + 0.25).collect();
        let v: Vec<Vec<f64>> = xs
            .iter()
            .map(|_| ys.iter().map(|y| y - 2.0).collect())
            .collect();
        let segs = contour(&xs, &ys, &v);
        assert_eq!(segs.len(), 10);
        for s in segs {
            assert!((s[0].1 - 2.0).abs() < 1e-12 && (s[1].1 - 2.0).abs() < 1e-12);
        }
    }
}
