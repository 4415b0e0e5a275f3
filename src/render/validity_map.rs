//! The validity map of a fitted formula: each case of the data at (log M, L), one panel per D,
//! coloured by its held-out error ([`crate::fit::heldout`]: the formula fitted without the case's
//! fold): green within 1 %, orange within 2 %, red beyond. Where the formula may be trusted to
//! 1 % is where the map is green.

use crate::fit::heldout::CaseError;
use crate::render::style::{case_map, distinct, e, Res};
use plotters::coord::Shift;
use plotters::prelude::*;

/// Held-out error bands of the map: (upper bound of |error|, colour); the title names them.
const BANDS: [(f64, RGBColor); 3] = [
    (0.01, RGBColor(40, 160, 60)),
    (0.02, RGBColor(240, 150, 20)),
    (f64::INFINITY, RGBColor(210, 40, 40)),
];

fn band(err: f64) -> usize {
    BANDS
        .iter()
        .position(|(lim, _)| err.abs() <= *lim)
        .unwrap_or(2)
}

/// Draw the map of `cases` (of the film named `film`; one panel per D when `point`) on `root`.
pub(crate) fn validity_map<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    cases: &[CaseError],
    film: &str,
    point: bool,
) -> Res {
    let ds = if point {
        distinct(cases.iter().map(|c| c.d).collect())
    } else {
        vec![1.0]
    };
    let m_lo = cases.iter().map(|c| c.m).fold(f64::INFINITY, f64::min);
    let m_hi = cases.iter().map(|c| c.m).fold(0.0, f64::max);
    let l_hi = cases.iter().map(|c| c.l).fold(0.0, f64::max).max(1.0);
    let within = cases.iter().filter(|c| c.error.abs() <= 0.01).count();
    let title = format!(
        "Held-out error of the {film} formula ({}): {within} of {} cases within 1 % \
         (green; orange 1-2 %, red beyond)",
        if point { "point" } else { "line" },
        cases.len()
    );
    let root = root.titled(&title, ("sans-serif", 20)).map_err(e)?;
    let cols = ds.len().min(2);
    let rows = ds.len().div_ceil(cols);
    let panels = root.split_evenly((rows, cols));
    for (&d, area) in ds.iter().zip(panels.iter()) {
        let caption = if point {
            format!("D = {d}")
        } else {
            String::new()
        };
        let mut ch = case_map(area, &caption, 16, (m_lo, m_hi, l_hi))?;
        let here: Vec<&CaseError> = cases
            .iter()
            .filter(|c| !point || (c.d - d).abs() <= 1e-9 * d)
            .collect();
        ch.draw_series(here.iter().map(|c| {
            let col = BANDS[band(c.error)].1;
            EmptyElement::at((c.m, c.l))
                + Circle::new((0, 0), 6, col.filled())
                + Circle::new((0, 0), 6, BLACK.stroke_width(1))
        }))
        .map_err(e)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bands_split_at_one_and_two_percent() {
        assert_eq!(band(0.0099), 0);
        assert_eq!(band(-0.01), 0);
        assert_eq!(band(0.015), 1);
        assert_eq!(band(-0.02), 1);
        assert_eq!(band(0.0201), 2);
        assert_eq!(band(f64::NAN), 2);
    }
}
