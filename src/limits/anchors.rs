//! The anchors of the point approach factor: the solver's elastic-isoviscous films half a decade
//! of M beyond the data, extrapolated to zero spacing, at each D of the data.
//!
//! The approach factor g of the point H_EI law ([`crate::fit::approach`]) is fitted to the data's
//! L = 0 cases, which stop at some M (1000 in the nightly data); beyond, g's powers of M
//! extrapolate, and a decade out that alone is 0.6-1.2 % off the solver (docs/validation.md,
//! "The approach factor cubic in ln D: tried and left"). The anchors are solves where the data
//! stop: at each D of the data's L = 0 cases at M >= `min_m`, the case ([`ANCHOR_FACTOR`] M_d,
//! 0, D), M_d the largest M of those cases at that D, solved on each of
//! [`crate::limits::beyond::BEYOND_GRIDS`] and extrapolated by
//! [`crate::limits::beyond::richardson`] (the films of the beyond check, half as far out).
//!
//! Inputs: the data's point cases (M, L, D) and `min_m`. Output: an [`Anchor`] per D ([`cases`]
//! then [`solve`]), each film None where a solve failed or no order was seen; an
//! [`AnchorFile`] stores them (`ehlmap fit --anchor-solves FILE`, read back with `--anchors
//! FILE`). Invariants: each anchor's solves are independent of the others and of the thread
//! count, so the anchors are too; an anchor is never data: it sets only the approach factor
//! (as data rows the interior correction's bumps rise past it: docs/validation.md).

use crate::limits::beyond::{BeyondSolves, BEYOND_GRIDS};
use crate::solve::film::Film;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// M of an anchor over the largest M of the data's L = 0 cases at its D: half a decade.
pub const ANCHOR_FACTOR: f64 = 3.1622776601683795;

/// The largest error bar (relative) of an anchor's film that is used: a film extrapolated with
/// a larger step is not a reference for a 0.5 % law.
pub const MAX_ERROR_BAR: f64 = 0.005;

/// One anchor: the case and its films extrapolated to zero spacing.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Anchor {
    /// M of the case.
    pub m: f64,
    /// D of the case (L = 0).
    pub d: f64,
    /// The central film H_c extrapolated (None: a solve failed).
    pub h_c: Option<f64>,
    /// Its error bar (the extrapolation's step).
    pub h_c_error_bar: Option<f64>,
    /// The film at the pressure maximum extrapolated.
    pub h_pm: Option<f64>,
    /// Its error bar.
    pub h_pm_error_bar: Option<f64>,
    /// Wall time of the three solves, seconds.
    pub wall_s: f64,
}

impl Anchor {
    /// The anchor's film `film` where it has one within [`MAX_ERROR_BAR`] (H_c and H_pm; H_min
    /// has no approach factor).
    pub fn film(&self, film: Film) -> Option<f64> {
        let (h, bar) = match film {
            Film::Centre => (self.h_c, self.h_c_error_bar),
            Film::PressureMax => (self.h_pm, self.h_pm_error_bar),
            Film::Minimum => (None, None),
        };
        let (h, bar) = (h?, bar?);
        (h > 0.0 && bar <= MAX_ERROR_BAR * h).then_some(h)
    }
}

/// The anchors as written by `ehlmap fit --anchor-solves`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AnchorFile {
    /// [`ANCHOR_FACTOR`].
    pub factor: f64,
    /// The grids of the solves.
    pub grids: Vec<usize>,
    /// One per D.
    pub anchors: Vec<Anchor>,
}

/// The anchor cases (M, D) of point cases (M, L, D): one per D of the L = 0 cases at M >=
/// `min_m`, at [`ANCHOR_FACTOR`] times the largest such M, in increasing D.
pub fn cases(data: &[(f64, f64, f64)], min_m: f64) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = vec![];
    let mut rows: Vec<(f64, f64)> = data
        .iter()
        .filter(|(m, l, _)| *l == 0.0 && *m >= min_m)
        .map(|(m, _, d)| (*d, *m))
        .collect();
    rows.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    for (d, m) in rows {
        match out.last_mut() {
            Some(last) if last.1 == d => last.0 = last.0.max(m),
            _ => out.push((m, d)),
        }
    }
    out.into_iter()
        .map(|(m, d)| (ANCHOR_FACTOR * m, d))
        .collect()
}

/// The anchors at `cases` ([`cases`]), solved in parallel; `progress(done, of)` after each.
pub fn solve(cases: &[(f64, f64)], progress: &(dyn Fn(usize, usize) + Sync)) -> AnchorFile {
    let done = std::sync::atomic::AtomicUsize::new(0);
    let anchors = cases
        .par_iter()
        .map(|&(m, d)| {
            let t = std::time::Instant::now();
            let s = BeyondSolves::at(m, d);
            let of = |film: Film| s.of(film);
            let (c, pm) = (of(Film::Centre), of(Film::PressureMax));
            let n = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            progress(n, cases.len());
            Anchor {
                m,
                d,
                h_c: c.solver,
                h_c_error_bar: c.error_bar,
                h_pm: pm.solver,
                h_pm_error_bar: pm.error_bar,
                wall_s: t.elapsed().as_secs_f64(),
            }
        })
        .collect();
    AnchorFile {
        factor: ANCHOR_FACTOR,
        grids: BEYOND_GRIDS.to_vec(),
        anchors,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_anchor_per_d_half_a_decade_beyond_its_largest_m() {
        let data = [
            (100.0, 0.0, 1.0),
            (1000.0, 0.0, 1.0),
            (5000.0, 5.0, 1.0),
            (300.0, 0.0, 0.1),
            (50.0, 0.0, 0.01),
            (700.0, 0.0, 0.1),
        ];
        let c = cases(&data, 100.0);
        assert_eq!(c.len(), 2, "{c:?}");
        assert_eq!(c[0].1, 0.1);
        assert!((c[0].0 / (700.0 * 10f64.sqrt()) - 1.0).abs() < 1e-15);
        assert!((c[1].0 / (1000.0 * 10f64.sqrt()) - 1.0).abs() < 1e-15);
    }

    #[test]
    fn a_film_with_a_wide_error_bar_or_a_failed_solve_is_not_used() {
        let a = Anchor {
            m: 3162.0,
            d: 0.1,
            h_c: Some(1.1),
            h_c_error_bar: Some(0.01),
            h_pm: Some(1.1),
            h_pm_error_bar: Some(0.001),
            wall_s: 1.0,
        };
        assert_eq!(a.film(Film::Centre), None);
        assert_eq!(a.film(Film::PressureMax), Some(1.1));
        assert_eq!(a.film(Film::Minimum), None);
        let failed = Anchor {
            h_pm: None,
            h_pm_error_bar: None,
            ..a
        };
        assert_eq!(failed.film(Film::PressureMax), None);
    }
}
