//! Relative-error statistics of a formula against numerical data: overall and per region of the
//! (M, L) plane (M decades x L bands), so a report shows where a formula is weak.

use serde::{Deserialize, Serialize};

/// Error statistics of formula/data - 1 over a set of points.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ErrStats {
    pub n: usize,
    /// Largest |relative error|, signed value kept.
    pub max: f64,
    pub rms: f64,
    pub mean: f64,
    /// Where the largest error is.
    pub worst_m: f64,
    pub worst_l: f64,
}

/// Statistics of (M, L, formula, data) tuples; `None` when there are none.
pub fn err_stats(points: &[(f64, f64, f64, f64)]) -> Option<ErrStats> {
    if points.is_empty() {
        return None;
    }
    let mut s = ErrStats {
        n: points.len(),
        max: 0.0,
        rms: 0.0,
        mean: 0.0,
        worst_m: f64::NAN,
        worst_l: f64::NAN,
    };
    for &(m, l, f, d) in points {
        let e = f / d - 1.0;
        s.rms += e * e;
        s.mean += e;
        if e.abs() >= s.max.abs() {
            s.max = e;
            s.worst_m = m;
            s.worst_l = l;
        }
    }
    s.rms = (s.rms / s.n as f64).sqrt();
    s.mean /= s.n as f64;
    Some(s)
}

/// One row of a region table.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RegionStats {
    pub region: String,
    pub stats: ErrStats,
}

const M_EDGES: [f64; 3] = [10.0, 100.0, 1000.0];

fn m_band(m: f64) -> usize {
    M_EDGES.iter().filter(|&&e| m >= e).count()
}

fn l_band(l: f64) -> usize {
    if l == 0.0 {
        0
    } else if l <= 10.0 {
        1
    } else {
        2
    }
}

fn band_name(mb: usize, lb: usize) -> String {
    let m = ["M < 10", "10 <= M < 100", "100 <= M < 1000", "M >= 1000"][mb];
    let l = ["L = 0", "0 < L <= 10", "L > 10"][lb];
    format!("{m}, {l}")
}

/// Statistics per region; regions without points are left out.
pub fn region_table(points: &[(f64, f64, f64, f64)]) -> Vec<RegionStats> {
    let mut out = vec![];
    for mb in 0..4 {
        for lb in 0..3 {
            let sel: Vec<_> = points
                .iter()
                .copied()
                .filter(|&(m, l, _, _)| m_band(m) == mb && l_band(l) == lb)
                .collect();
            if let Some(stats) = err_stats(&sel) {
                out.push(RegionStats {
                    region: band_name(mb, lb),
                    stats,
                });
            }
        }
    }
    out
}

/// Statistics per ellipticity D of (D, formula, data) tuples, in increasing D.
pub fn d_table(points: &[(f64, f64, f64)]) -> Vec<RegionStats> {
    let mut ds: Vec<f64> = points.iter().map(|p| p.0).collect();
    ds.sort_by(f64::total_cmp);
    ds.dedup();
    ds.iter()
        .filter_map(|&d| {
            let sel: Vec<_> = points
                .iter()
                .filter(|p| p.0 == d)
                .map(|&(d, f, h)| (f64::NAN, d, f, h))
                .collect();
            err_stats(&sel).map(|stats| RegionStats {
                region: format!("D = {d}"),
                stats,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statistics_of_known_errors() {
        let pts = [
            (1.0, 0.0, 1.1, 1.0),
            (50.0, 5.0, 0.95, 1.0),
            (2000.0, 20.0, 1.0, 1.0),
        ];
        let s = err_stats(&pts).unwrap();
        assert_eq!(s.n, 3);
        assert!((s.max - 0.1).abs() < 1e-12 && s.worst_m == 1.0);
        assert!((s.mean - 0.05 / 3.0).abs() < 1e-12);
        assert!((s.rms - ((0.01 + 0.0025) / 3.0f64).sqrt()).abs() < 1e-12);
        let t = region_table(&pts);
        assert_eq!(t.len(), 3);
        assert_eq!(t[0].region, "M < 10, L = 0");
    }
}
