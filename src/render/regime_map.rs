//! The regime map chart in Moes' (M, L) axes: each asymptote's zone (from
//! [`crate::model::regimes`]) and an optional case marked, as PNG and SVG.

use crate::model::formulas::Regime;
use crate::model::regimes::{boundary_points, regime, short, LOG_M, L_MAX};
use crate::render::style::{e, ensure_font, RenderError};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

fn color(r: Regime) -> RGBColor {
    match r {
        Regime::RigidIsoviscous => RGBColor(255, 235, 200),
        Regime::ElasticIsoviscous => RGBColor(205, 235, 205),
        Regime::RigidPiezoviscous => RGBColor(210, 220, 255),
        Regime::ElasticPiezoviscous => RGBColor(245, 210, 235),
    }
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    d: Option<f64>,
    mark: Option<(f64, f64, &str)>,
) -> Result<(), RenderError> {
    let title = match d {
        None => "Regimes of a line contact (Moes 1992 asymptotes)".to_string(),
        Some(d) => format!("Regimes of a point contact, D = {d:.4} (NVM 1994 asymptotes)"),
    };
    let mut ch = ChartBuilder::on(root)
        .caption(title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(50)
        .build_cartesian_2d(LOG_M.0..LOG_M.1, 0.0..L_MAX)
        .map_err(e)?;
    ch.configure_mesh()
        .x_desc("log10 M")
        .y_desc("L")
        .draw()
        .map_err(e)?;
    let n = 120;
    let (dx, dy) = ((LOG_M.1 - LOG_M.0) / n as f64, L_MAX / n as f64);
    let mut cells = Vec::new();
    let mut sums = std::collections::HashMap::new();
    for i in 0..n {
        for j in 0..n {
            let (x, y) = (LOG_M.0 + dx * i as f64, dy * j as f64);
            let r = regime(10f64.powf(x + 0.5 * dx), y + 0.5 * dy, d);
            let s = sums.entry(short(r)).or_insert((0.0, 0.0, 0.0));
            *s = (s.0 + x, s.1 + y, s.2 + 1.0);
            cells.push(Rectangle::new(
                [(x, y), (x + dx, y + dy)],
                color(r).filled(),
            ));
        }
    }
    ch.draw_series(cells).map_err(e)?;
    ch.draw_series(
        boundary_points(d, 200)
            .into_iter()
            .map(|p| Circle::new(p, 1, BLACK.filled())),
    )
    .map_err(e)?;
    for (name, (sx, sy, c)) in sums {
        ch.draw_series([Text::new(
            name,
            (sx / c, sy / c),
            ("sans-serif", 26).into_font(),
        )])
        .map_err(e)?;
    }
    if let Some((m, l, label)) = mark {
        let p = (m.log10().clamp(LOG_M.0, LOG_M.1), l.min(L_MAX));
        let label = if l > L_MAX {
            format!("{label}: L = {l:.0}, above the chart")
        } else {
            label.to_string()
        };
        // the label goes left of the mark near the right edge
        // (about 8 px a character at size 16, 166 px a decade of M on the 900 px chart)
        let width = label.chars().count() as f64 * 8.0 / 166.0;
        let lx = if p.0 + 0.1 + width > LOG_M.1 {
            p.0 - 0.1 - width
        } else {
            p.0 + 0.08
        };
        ch.draw_series([
            Cross::new(p, 8, RED.stroke_width(3)).into_dyn(),
            Text::new(
                label,
                (lx, (p.1 + 0.4).min(L_MAX - 1.0)),
                ("sans-serif", 16).into_font().color(&RED),
            )
            .into_dyn(),
        ])
        .map_err(e)?;
    }
    Ok(())
}

/// Write `dir/regimes.png` and `dir/regimes.svg` (`regimes-D<d>` for a point contact), with an
/// optional case `(M, L, label)` marked.
pub fn write_regime_map(
    dir: &Path,
    d: Option<f64>,
    mark: Option<(f64, f64, &str)>,
) -> Result<Vec<PathBuf>, RenderError> {
    ensure_font();
    std::fs::create_dir_all(dir).map_err(|x| format!("--out {}: {x}", dir.display()))?;
    let stem = match d {
        None => "regimes".to_string(),
        Some(d) => format!("regimes-D{d:.4}"),
    };
    let png = dir.join(format!("{stem}.png"));
    let svg = dir.join(format!("{stem}.svg"));
    {
        let root = BitMapBackend::new(&png, (900, 700)).into_drawing_area();
        root.fill(&WHITE).map_err(e)?;
        draw(&root, d, mark)?;
        root.present().map_err(e)?;
    }
    {
        let root = SVGBackend::new(&svg, (900, 700)).into_drawing_area();
        root.fill(&WHITE).map_err(e)?;
        draw(&root, d, mark)?;
        root.present().map_err(e)?;
    }
    Ok(vec![png, svg])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chart_files_are_written() {
        let dir = std::env::temp_dir().join(format!("ehlmap-regimes-{}", std::process::id()));
        let files = write_regime_map(&dir, Some(0.5), Some((100.0, 10.0, "case"))).unwrap();
        for f in &files {
            assert!(std::fs::metadata(f).unwrap().len() > 5000, "{f:?}");
        }
        std::fs::remove_dir_all(&dir).ok();
    }
}
