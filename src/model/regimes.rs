//! The regime map in Moes' (M, L) axes (log M, L): which asymptote dominates the central film.
//!
//! Line contacts use Moes 1992's asymptotes ([`moes_line_asymptotes`]): `H_RI = 3/M`,
//! `H_EI = 2.621 M^-1/5`, `H_RP = 1.287 L^2/3`, `H_EP = 1.311 M^-1/8 L^3/4`; point contacts of
//! ellipticity D those of Nijenbanning-Venner-Moes 1994 ([`nvm_point_asymptotes`]), the elastic
//! isoviscous one combined with `H_00` as in the formula, `(H_EI^-4 + H_00^-4)^-1/4`. The
//! structure of both formulas is `max(iso, piezo)` with `iso = max(RI, EI)` and
//! `piezo = min(RP, EP)` (elasticity caps the piezoviscous rise): the regime is the asymptote
//! that gives that value. Boundaries are where two asymptotes are equal, e.g. RI/EI of a line
//! contact at `M = (3/2.621)^(5/4) = 1.184` for every L (the piezoviscous bracket does not win
//! at small L), RP/EP at `L = (1.287/1.311)^12 M^(3/2)`.

use crate::model::formulas::{moes_line_asymptotes, nvm_point_asymptotes, Regime};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// The dominant asymptote at (M, L): line contact (`d = None`) or point contact of ellipticity D.
pub fn regime(m: f64, l: f64, d: Option<f64>) -> Regime {
    let (ri, ei, rp, ep) = match d {
        None => {
            let [ri, ei, rp, ep] = moes_line_asymptotes(m, l);
            (ri, ei, rp, ep)
        }
        Some(d) => {
            let [ri, ei, rp, ep, h00] = nvm_point_asymptotes(m, l, d);
            (ri, (ei.powi(-4) + h00.powi(-4)).powf(-0.25), rp, ep)
        }
    };
    let (iso, iso_r) = if ei > ri {
        (ei, Regime::ElasticIsoviscous)
    } else {
        (ri, Regime::RigidIsoviscous)
    };
    let (piezo, piezo_r) = if ep < rp {
        (ep, Regime::ElasticPiezoviscous)
    } else {
        (rp, Regime::RigidPiezoviscous)
    };
    if l > 0.0 && piezo > iso {
        piezo_r
    } else {
        iso_r
    }
}

/// Short name: RI, EI, RP, EP.
pub fn short(r: Regime) -> &'static str {
    match r {
        Regime::RigidIsoviscous => "RI",
        Regime::ElasticIsoviscous => "EI",
        Regime::RigidPiezoviscous => "RP",
        Regime::ElasticPiezoviscous => "EP",
    }
}

/// Where the regime changes between `a` and `b` along a segment, by bisection (60 halvings).
fn bisect(mut a: (f64, f64), mut b: (f64, f64), d: Option<f64>) -> (f64, f64) {
    let ra = regime(10f64.powf(a.0), a.1, d);
    for _ in 0..60 {
        let mid = (0.5 * (a.0 + b.0), 0.5 * (a.1 + b.1));
        if regime(10f64.powf(mid.0), mid.1, d) == ra {
            a = mid;
        } else {
            b = mid;
        }
    }
    (0.5 * (a.0 + b.0), 0.5 * (a.1 + b.1))
}

/// The M of the RI/EI boundary at a given L, by bisection on the map between `m_lo` and `m_hi`.
pub fn ri_ei_boundary(l: f64, d: Option<f64>, m_lo: f64, m_hi: f64) -> Option<f64> {
    if regime(m_lo, l, d) != Regime::RigidIsoviscous
        || regime(m_hi, l, d) != Regime::ElasticIsoviscous
    {
        return None;
    }
    let (lm, _) = bisect((m_lo.log10(), l), (m_hi.log10(), l), d);
    Some(10f64.powf(lm))
}

/// Axis ranges of the map: log10 M and L.
const LOG_M: (f64, f64) = (-1.0, 4.0);
const L_MAX: f64 = 25.0;

/// Boundary points (log10 M, L) found along grid lines in both directions.
pub fn boundary_points(d: Option<f64>, n: usize) -> Vec<(f64, f64)> {
    let mut pts = Vec::new();
    let lm = |i: usize| LOG_M.0 + (LOG_M.1 - LOG_M.0) * i as f64 / n as f64;
    let ll = |j: usize| L_MAX * j as f64 / n as f64;
    let r = |p: (f64, f64)| regime(10f64.powf(p.0), p.1, d);
    for i in 0..=n {
        for j in 0..n {
            let (a, b) = ((lm(i), ll(j)), (lm(i), ll(j + 1)));
            if r(a) != r(b) {
                pts.push(bisect(a, b, d));
            }
            let (a, b) = ((lm(j), ll(i)), (lm(j + 1), ll(i)));
            if r(a) != r(b) {
                pts.push(bisect(a, b, d));
            }
        }
    }
    pts
}

fn e<T: std::fmt::Debug>(x: T) -> String {
    format!("{x:?}")
}

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
) -> Result<(), String> {
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
) -> Result<Vec<PathBuf>, String> {
    crate::render::charts::ensure_font();
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

/// `ehlmap chart regimes [--out DIR] [--case FILE.toml] [--D d]`.
#[derive(clap::Args, Debug)]
pub struct ChartArgs {
    /// Which chart (only `regimes`).
    #[arg(value_parser = ["regimes"])]
    pub what: String,
    /// Output directory.
    #[arg(long, default_value = "charts")]
    pub out: PathBuf,
    /// Mark this case (a case file) on the map; a point case sets D.
    #[arg(long)]
    pub case: Option<PathBuf>,
    /// A point contact of this ellipticity D = Rx/Ry in (0, 1] (default: line contact).
    #[arg(long = "D")]
    pub d: Option<f64>,
}

/// Run `ehlmap chart`.
pub fn run_chart(a: &ChartArgs) -> Result<i32, crate::cli::InputError> {
    use crate::cli::InputError;
    let mut d = a.d;
    if let Some(d) = d {
        if !(d > 0.0 && d <= 1.0) {
            return Err(InputError(format!("--D {d} is invalid: give D in (0, 1]")));
        }
    }
    let mut mark = None;
    if let Some(path) = &a.case {
        let spec = crate::cases::read_case(path).map_err(InputError)?;
        let r = spec
            .report(false)
            .map_err(|e| InputError(format!("{}: {e}", path.display())))?;
        if let Some(dc) = r.d {
            if d.is_some_and(|x| (x - dc).abs() > 1e-12 * dc) {
                return Err(InputError(format!(
                    "--D {} contradicts the case's D = {dc}",
                    d.unwrap_or(f64::NAN)
                )));
            }
            d = Some(dc);
        } else if d.is_some() {
            return Err(InputError(
                "--D with a line-contact --case: drop --D".into(),
            ));
        }
        let label = path
            .file_stem()
            .map_or("case".into(), |s| s.to_string_lossy().into_owned());
        mark = Some((
            r.m,
            r.l,
            format!("{label} ({})", short(regime(r.m, r.l, d))),
        ));
    }
    let files = write_regime_map(&a.out, d, mark.as_ref().map(|m| (m.0, m.1, m.2.as_str())))
        .map_err(|e| InputError(format!("chart regimes: {e}")))?;
    for f in files {
        println!("{}", f.display());
    }
    Ok(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_ri_ei_boundary_is_the_hand_crossing() {
        // 3/M = 2.621 M^-1/5  <=>  M^(4/5) = 3/2.621  <=>  M = (3/2.621)^(5/4) = 1.1840
        let hand = (3.0f64 / 2.621).powf(1.25);
        assert!((hand - 1.1840).abs() < 1e-3);
        for l in [0.0, 0.5] {
            let m = ri_ei_boundary(l, None, 0.1, 100.0).unwrap();
            assert!((m / hand - 1.0).abs() < 1e-9, "L = {l}: {m}");
        }
    }

    #[test]
    fn line_rp_ep_boundary_is_the_hand_crossing() {
        // 1.287 L^(2/3) = 1.311 M^(-1/8) L^(3/4)  <=>  L = (1.287/1.311)^12 M^(3/2); at M = 4:
        // L = 0.8011 x 8 = 6.41, inside the piezoviscous zone (H_RP = 4.44 > H_EI = 1.99). Below
        // it EP is the smaller piezoviscous asymptote (EP/RP grows like L^(1/12)), above it RP.
        let m = 4.0f64;
        let hand = (1.287f64 / 1.311).powi(12) * m.powf(1.5);
        assert!((hand - 6.41).abs() < 0.01, "{hand}");
        assert_eq!(regime(m, hand * 0.99, None), Regime::ElasticPiezoviscous);
        assert_eq!(regime(m, hand * 1.01, None), Regime::RigidPiezoviscous);
        // and the classic reference point M = 20, L = 10 is elastic-piezoviscous
        assert_eq!(regime(20.0, 10.0, None), Regime::ElasticPiezoviscous);
    }

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
