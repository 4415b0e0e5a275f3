//! Charts of a fit (PNG and SVG via plotters; text by ab_glyph with the bundled DejaVu Sans, so
//! nothing is needed from the system): parity plot, H_c over M per L with the fitted formula and
//! Moes 1992, and the relative-error map over (log M, L).

use crate::fit::model::LineModel;
use crate::fit::report::FitPoint;
use crate::formulas::moes_line_hc;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;
use std::sync::Once;

static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
static REGISTER: Once = Once::new();

pub(crate) fn ensure_font() {
    REGISTER.call_once(|| {
        // The bundled font is a valid TrueType file; failure would only lose the labels.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

type Res = Result<(), String>;

fn e<T: std::fmt::Debug>(x: T) -> String {
    format!("{x:?}")
}

/// Draw with `f` into `stem.png` and `stem.svg`.
fn both(
    stem: &Path,
    size: (u32, u32),
    f: impl Fn(&DrawingArea<BitMapBackend, Shift>) -> Res + Copy,
    g: impl Fn(&DrawingArea<SVGBackend, Shift>) -> Res,
) -> Res {
    ensure_font();
    let png = stem.with_extension("png");
    let svg = stem.with_extension("svg");
    {
        let root = BitMapBackend::new(&png, size).into_drawing_area();
        root.fill(&WHITE).map_err(e)?;
        f(&root)?;
        root.present().map_err(e)?;
    }
    let root = SVGBackend::new(&svg, size).into_drawing_area();
    root.fill(&WHITE).map_err(e)?;
    g(&root)?;
    root.present().map_err(e)?;
    Ok(())
}

fn parity<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    pts: &[FitPoint],
    model: &LineModel,
) -> Res {
    let lo = pts.iter().map(|p| p.h_c).fold(f64::INFINITY, f64::min) * 0.8;
    let hi = pts.iter().map(|p| p.h_c).fold(0.0, f64::max) * 1.25;
    let mut ch = ChartBuilder::on(root)
        .caption("Fitted formula vs numerics (H_c)", ("sans-serif", 22))
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
    ch.draw_series(
        pts.iter()
            .map(|p| Circle::new((p.h_c, model.eval(p.m, p.l)), 3, BLUE.filled())),
    )
    .map_err(e)?
    .label("fit")
    .legend(|(x, y)| Circle::new((x, y), 3, BLUE.filled()));
    ch.draw_series(
        pts.iter()
            .map(|p| Cross::new((p.h_c, moes_line_hc(p.m, p.l)), 3, RED.stroke_width(1))),
    )
    .map_err(e)?
    .label("Moes 1992")
    .legend(|(x, y)| Cross::new((x, y), 3, RED.stroke_width(1)));
    ch.configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(e)?;
    Ok(())
}

fn distinct(mut v: Vec<f64>) -> Vec<f64> {
    v.sort_by(|a, b| a.partial_cmp(b).expect("finite"));
    v.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * b.abs().max(1.0));
    v
}

fn curves<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    pts: &[FitPoint],
    model: &LineModel,
) -> Res {
    let m_lo = pts.iter().map(|p| p.m).fold(f64::INFINITY, f64::min);
    let m_hi = pts.iter().map(|p| p.m).fold(0.0, f64::max);
    let h_lo = pts.iter().map(|p| p.h_c).fold(f64::INFINITY, f64::min) * 0.7;
    let h_hi = pts.iter().map(|p| p.h_c).fold(0.0, f64::max) * 1.4;
    let mut ch = ChartBuilder::on(root)
        .caption(
            "H_c over M per L: numerics (dots), fit (lines), Moes 1992 (dashed)",
            ("sans-serif", 20),
        )
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(56)
        .build_cartesian_2d(
            (m_lo * 0.8..m_hi * 1.25).log_scale(),
            (h_lo..h_hi).log_scale(),
        )
        .map_err(e)?;
    ch.configure_mesh()
        .x_desc("M")
        .y_desc("H_c (Moes units)")
        .draw()
        .map_err(e)?;
    let ls = distinct(pts.iter().map(|p| p.l).collect());
    for (k, &l) in ls.iter().enumerate() {
        let color = Palette99::pick(k).to_rgba();
        let grid: Vec<f64> = (0..=80)
            .map(|i| m_lo * 0.8 * ((m_hi * 1.25) / (m_lo * 0.8)).powf(i as f64 / 80.0))
            .collect();
        ch.draw_series(LineSeries::new(
            grid.iter().map(|&m| (m, model.eval(m, l))),
            color.stroke_width(2),
        ))
        .map_err(e)?
        .label(format!("L = {l}"))
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], color.stroke_width(2)));
        ch.draw_series(DashedLineSeries::new(
            grid.iter().map(|&m| (m, moes_line_hc(m, l))),
            4,
            4,
            color.stroke_width(1),
        ))
        .map_err(e)?;
        ch.draw_series(
            pts.iter()
                .filter(|p| (p.l - l).abs() <= 1e-9 * l.max(1.0))
                .map(|p| Circle::new((p.m, p.h_c), 3, color.filled())),
        )
        .map_err(e)?;
    }
    ch.configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(e)?;
    Ok(())
}

fn error_map<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    pts: &[FitPoint],
    model: &LineModel,
) -> Res {
    let m_lo = pts.iter().map(|p| p.m).fold(f64::INFINITY, f64::min);
    let m_hi = pts.iter().map(|p| p.m).fold(0.0, f64::max);
    let l_hi = pts.iter().map(|p| p.l).fold(0.0, f64::max).max(1.0);
    let errs: Vec<f64> = pts
        .iter()
        .map(|p| model.eval(p.m, p.l) / p.h_c - 1.0)
        .collect();
    let emax = errs.iter().fold(1e-6f64, |a, v| a.max(v.abs()));
    let mut ch = ChartBuilder::on(root)
        .caption(
            format!(
                "Relative error of the fit (red +, blue -; full colour = {:.2} %)",
                100.0 * emax
            ),
            ("sans-serif", 20),
        )
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(48)
        .build_cartesian_2d(
            (m_lo * 0.8..m_hi * 1.25).log_scale(),
            -0.05 * l_hi..1.05 * l_hi,
        )
        .map_err(e)?;
    ch.configure_mesh()
        .x_desc("M")
        .y_desc("L")
        .draw()
        .map_err(e)?;
    ch.draw_series(pts.iter().zip(&errs).map(|(p, &err)| {
        let t = (err.abs() / emax).clamp(0.0, 1.0);
        let c = if err >= 0.0 {
            RGBColor(255, (255.0 * (1.0 - t)) as u8, (255.0 * (1.0 - t)) as u8)
        } else {
            RGBColor((255.0 * (1.0 - t)) as u8, (255.0 * (1.0 - t)) as u8, 255)
        };
        EmptyElement::at((p.m, p.l))
            + Circle::new((0, 0), 7, c.filled())
            + Circle::new((0, 0), 7, BLACK.stroke_width(1))
    }))
    .map_err(e)?;
    Ok(())
}

/// Where two asymptote laws of `model` cross, on a log-M grid at fixed L: the M values at which
/// f(M) changes sign.
fn crossings(ms: &[f64], f: impl Fn(f64) -> f64) -> Vec<f64> {
    let mut out = vec![];
    for w in ms.windows(2) {
        let (a, b) = (f(w[0]), f(w[1]));
        if a.is_finite() && b.is_finite() && a.signum() != b.signum() {
            // Log-linear interpolation of the sign change.
            let t = a / (a - b);
            out.push((w[0].ln() + t * (w[1].ln() - w[0].ln())).exp());
        }
    }
    out
}

/// A regime boundary: its name, colour and the (M, L) points found on it.
type Boundary = (&'static str, RGBColor, Vec<(f64, f64)>);

fn regime_map<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    pts: &[FitPoint],
    model: &LineModel,
) -> Res {
    let m_lo = pts.iter().map(|p| p.m).fold(f64::INFINITY, f64::min) * 0.8;
    let m_hi = pts.iter().map(|p| p.m).fold(0.0, f64::max) * 1.25;
    let l_hi = pts.iter().map(|p| p.l).fold(0.0, f64::max).max(1.0);
    let mut ch = ChartBuilder::on(root)
        .caption(
            "Fitted H_c(M, L) with regime boundaries (where two asymptotes cross)",
            ("sans-serif", 19),
        )
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(48)
        .build_cartesian_2d((m_lo..m_hi).log_scale(), 0.0..l_hi)
        .map_err(e)?;
    ch.configure_mesh()
        .x_desc("M")
        .y_desc("L")
        .draw()
        .map_err(e)?;
    // Filled map of log H_c on a 60 x 40 raster, light (thin film) to dark blue (thick film).
    let (nx, ny) = (60usize, 40usize);
    let mgrid: Vec<f64> = (0..=nx)
        .map(|i| m_lo * (m_hi / m_lo).powf(i as f64 / nx as f64))
        .collect();
    let lgrid: Vec<f64> = (0..=ny).map(|j| l_hi * j as f64 / ny as f64).collect();
    let (mut hmin, mut hmax) = (f64::INFINITY, 0.0f64);
    for &m in &mgrid {
        for &l in &lgrid {
            let h = model.eval(m, l);
            hmin = hmin.min(h);
            hmax = hmax.max(h);
        }
    }
    let shade = |h: f64| {
        let t = ((h.ln() - hmin.ln()) / (hmax.ln() - hmin.ln())).clamp(0.0, 1.0);
        RGBColor(
            (235.0 - 185.0 * t) as u8,
            (240.0 - 150.0 * t) as u8,
            (250.0 - 90.0 * t) as u8,
        )
    };
    ch.draw_series((0..nx).flat_map(|i| {
        let (mg, lg) = (&mgrid, &lgrid);
        (0..ny).map(move |j| {
            let h = model.eval((mg[i] * mg[i + 1]).sqrt(), 0.5 * (lg[j] + lg[j + 1]));
            Rectangle::new([(mg[i], lg[j]), (mg[i + 1], lg[j + 1])], shade(h).filled())
        })
    }))
    .map_err(e)?;
    // Boundaries: RI = EI (isoviscous), RP = EP (piezoviscous), iso bracket = piezo bracket.
    let fine: Vec<f64> = (0..=400)
        .map(|i| m_lo * (m_hi / m_lo).powf(i as f64 / 400.0))
        .collect();
    let (p, q) = (model.x[7], model.x[8]);
    let mut lines: Vec<Boundary> = vec![
        ("RI = EI", RGBColor(0, 0, 0), vec![]),
        ("RP = EP", RGBColor(200, 30, 30), vec![]),
        ("isoviscous = piezoviscous", RGBColor(30, 130, 30), vec![]),
    ];
    for &l in lgrid.iter().skip(1) {
        let a = |m: f64| model.asymptotes(m, l);
        for m in crossings(&fine, |m| a(m)[0].ln() - a(m)[1].ln()) {
            lines[0].2.push((m, l));
        }
        for m in crossings(&fine, |m| a(m)[2].ln() - a(m)[3].ln()) {
            lines[1].2.push((m, l));
        }
        let iso = |m: f64| (a(m)[0].powf(p) + a(m)[1].powf(p)).powf(1.0 / p);
        let piezo = |m: f64| (a(m)[2].powf(-q) + a(m)[3].powf(-q)).powf(-1.0 / q);
        for m in crossings(&fine, |m| iso(m).ln() - piezo(m).ln()) {
            lines[2].2.push((m, l));
        }
    }
    for (name, color, pts_line) in lines {
        if pts_line.is_empty() {
            continue;
        }
        ch.draw_series(
            pts_line
                .iter()
                .map(|&xy| Circle::new(xy, 2, color.filled())),
        )
        .map_err(e)?
        .label(name)
        .legend(move |(x, y)| Circle::new((x, y), 3, color.filled()));
    }
    ch.draw_series(
        pts.iter()
            .map(|p| Cross::new((p.m, p.l), 3, RGBColor(90, 90, 90).stroke_width(1))),
    )
    .map_err(e)?
    .label("solved cases")
    .legend(|(x, y)| Cross::new((x, y), 3, RGBColor(90, 90, 90).stroke_width(1)));
    ch.configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(e)?;
    Ok(())
}

/// Write parity, curves and error-map charts (PNG and SVG) into `dir`; returns the file stems.
pub fn write_charts(
    dir: &Path,
    pts: &[FitPoint],
    model: &LineModel,
) -> Result<Vec<String>, String> {
    if pts.is_empty() {
        return Ok(vec![]);
    }
    let size = (900, 650);
    let mut stems = vec![];
    // One chart function, drawn to both backends (their types differ, hence the macro).
    macro_rules! chart {
        ($name:literal, $draw:ident) => {
            both(
                &dir.join($name),
                size,
                |r| $draw(r, pts, model),
                |r| $draw(r, pts, model),
            )?;
            stems.push($name.to_string());
        };
    }
    chart!("parity", parity);
    chart!("hc_vs_m", curves);
    chart!("error_map", error_map);
    chart!("regime_map", regime_map);
    Ok(stems)
}
