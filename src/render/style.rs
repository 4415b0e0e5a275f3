//! The style and drawing helpers shared by the chart modules: the bundled DejaVu Sans font
//! (registered once as "sans-serif" by [`ensure_font`], so nothing is needed from the system),
//! PNG plus SVG output of one drawing (`both`), the error type of drawing (`Res`, `e`), what a
//! fit chart draws (`Ctx`), the legend box (`series_legend`), the (log M, L) chart of data cases
//! (`case_map`), distinct values (`distinct`) and log-spaced sampling (`log_grid`); these are
//! crate-private.

use crate::model::formulas::{moes_line_hc, nvm_point_hc};
use crate::report::{Blend, FitPoint, FittedModel};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Once;

static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
static REGISTER: Once = Once::new();

/// Register the bundled font as "sans-serif" (once per process).
pub fn ensure_font() {
    REGISTER.call_once(|| {
        // The bundled font is a valid TrueType file; failure would only lose the labels.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

/// Why a chart or picture could not be drawn or written (plotters' error, or the file's).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct RenderError(pub String);

impl From<String> for RenderError {
    fn from(msg: String) -> Self {
        RenderError(msg)
    }
}

/// The result of a drawing step.
pub(crate) type Res = Result<(), RenderError>;

/// Series colours of the charts, in order.
pub const COLORS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
];

/// A drawing error (its `Debug` form).
pub(crate) fn e<T: std::fmt::Debug>(x: T) -> RenderError {
    RenderError(format!("{x:?}"))
}

/// Draw with `f` into `stem.png` and with `g` into `stem.svg` (shared by every chart module).
pub(crate) fn both(
    stem: &Path,
    size: (u32, u32),
    f: impl Fn(&DrawingArea<BitMapBackend, Shift>) -> Res,
    g: impl Fn(&DrawingArea<SVGBackend, Shift>) -> Res,
) -> Res {
    ensure_font();
    // Appended, not `with_extension`: a stem may hold a dot (`film-D0.5`).
    let png = PathBuf::from(format!("{}.png", stem.display()));
    let svg = PathBuf::from(format!("{}.svg", stem.display()));
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

/// What a chart draws: the points, the fitted model and the contact's published formula.
pub(crate) struct Ctx<'a> {
    /// The data points of the contact (all D for point contacts).
    pub pts: &'a [FitPoint],
    /// The fitted law of the film charted.
    pub model: &'a FittedModel,
    /// D at which curves and maps are drawn (1 for line contacts).
    pub d: f64,
}

impl Ctx<'_> {
    /// The contact's published central-film formula at (M, L, D): Moes 1992 (line) or NVM 1994
    /// (point).
    pub fn published(&self, m: f64, l: f64, d: f64) -> f64 {
        match self.model.blend {
            Blend::Line(_) => moes_line_hc(m, l),
            Blend::Point(_) => nvm_point_hc(m, l, d),
        }
    }
    /// The name of [`Ctx::published`]'s formula.
    pub fn published_name(&self) -> &'static str {
        match self.model.blend {
            Blend::Line(_) => "Moes 1992",
            Blend::Point(_) => "NVM 1994",
        }
    }
    /// The fitted film at (M, L) and the chart's D.
    pub fn eval(&self, m: f64, l: f64) -> f64 {
        self.model.eval(m, l, self.d)
    }
    /// The four asymptotes at (M, L) and the chart's D.
    pub fn asymptotes(&self, m: f64, l: f64) -> [f64; 4] {
        match &self.model.blend {
            Blend::Line(x) => x.asymptotes(m, l),
            Blend::Point(x) => x.asymptotes(m, l, self.d),
        }
    }
    /// The points at the chart's D.
    pub fn at_d(&self) -> Vec<FitPoint> {
        self.pts
            .iter()
            .filter(|p| p.d.is_none_or(|d| (d - self.d).abs() < 1e-9))
            .copied()
            .collect()
    }
    /// The title suffix naming the contact: empty for line contacts, ", point contact, D = .."
    /// for point contacts.
    pub fn suffix(&self) -> String {
        match self.model.blend {
            Blend::Line(_) => String::new(),
            Blend::Point(_) => format!(", point contact, D = {}", self.d),
        }
    }
}

/// Draw the series labels of `ch` at `position` on a translucent white box with a black border
/// (the legend of every chart that has one).
pub(crate) fn series_legend<'a, DB, CT>(
    ch: &mut ChartContext<'a, DB, CT>,
    position: SeriesLabelPosition,
) -> Res
where
    DB: DrawingBackend + 'a,
    CT: CoordTranslate,
{
    ch.configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(e)
}

/// The distinct values of `v` (equal within 1e-9 relative), sorted.
pub(crate) fn distinct(mut v: Vec<f64>) -> Vec<f64> {
    v.sort_by(f64::total_cmp);
    v.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * b.abs().max(1.0));
    v
}

/// A chart over log M by linear L.
pub(crate) type MapChart<'a, DB> = ChartContext<'a, DB, Cartesian2d<LogCoord<f64>, RangedCoordf64>>;

/// The chart of data cases over (log M, L) on `area`, padded around M in [m_lo, m_hi] and L in
/// [0, l_hi], with its mesh labelled M and L drawn (the fit's error map and validity map).
pub(crate) fn case_map<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    caption: &str,
    font: u32,
    (m_lo, m_hi, l_hi): (f64, f64, f64),
) -> Result<MapChart<'a, DB>, RenderError> {
    let mut ch = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", font))
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
    Ok(ch)
}

/// Log-spaced grid of n + 1 values from lo to hi.
pub(crate) fn log_grid(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    (0..=n)
        .map(|i| lo * (hi / lo).powf(i as f64 / n as f64))
        .collect()
}
