//! Relative-error statistics of a formula against numerical data: overall and per region of the
//! (M, L) plane (M decades x L bands), so a report shows where a formula is weak, and the M range
//! over which it meets a target ([`target_range`]), so it says where it can be trusted.

use serde::{Deserialize, Serialize};

/// Reads a number written by serde_json, where NaN is written as null: null reads as NaN (so
/// that fit.json reads back, [`ErrStats`] of a per-D table and unidentified sigmas included).
pub fn null_as_nan<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::NAN))
}

/// Error statistics of formula/data - 1 over a set of points.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ErrStats {
    /// Number of points (at least 1).
    pub n: usize,
    /// Largest |relative error|, signed value kept.
    pub max: f64,
    /// Root mean square of the relative errors.
    pub rms: f64,
    /// Mean of the signed relative errors (positive: the formula is above the data on average).
    pub mean: f64,
    /// Where the largest error is: its M (NaN in a per-D table, [`d_table`]).
    #[serde(deserialize_with = "null_as_nan")]
    pub worst_m: f64,
    /// Where the largest error is: its L (its D in a per-D table, [`d_table`]).
    #[serde(deserialize_with = "null_as_nan")]
    pub worst_l: f64,
}

/// Statistics of (M, L, formula, data) tuples, errors formula/data - 1; `None` when there are
/// none. On a tie in |error| the later tuple is named the worst.
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
    /// The region's label, e.g. "10 <= M < 100, 0 < L <= 10" or "D = 0.5".
    pub region: String,
    /// The statistics of the points in it.
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

/// Statistics per region of (M, L, formula, data) tuples: M bands with edges 10, 100, 1000
/// times L bands L = 0, 0 < L <= 10, L > 10, in increasing M then L; regions without points are
/// left out.
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

/// The M range over which a formula meets a target: every case with M in [`m_lo`, `m_hi`] (all
/// L, all D) has |formula/data - 1| <= `target`.
///
/// [`m_lo`]: TargetRange::m_lo
/// [`m_hi`]: TargetRange::m_hi
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TargetRange {
    /// The relative-error target met.
    pub target: f64,
    /// Smallest M of the range (an M value of the data).
    pub m_lo: f64,
    /// Largest M of the range (an M value of the data); at least `m_lo`.
    pub m_hi: f64,
    /// Cases in the range.
    pub n: usize,
    /// Cases in all (`n` <= `of`).
    pub of: usize,
}

/// The run of consecutive M values of the data (each with all its cases within `target`) that
/// holds the most cases; on a tie the higher M range (the elastic end, where formulas are used
/// most). None when no M value has all its cases within the target.
pub fn target_range(points: &[(f64, f64, f64, f64)], target: f64) -> Option<TargetRange> {
    let mut ms: Vec<f64> = points.iter().map(|p| p.0).collect();
    ms.sort_by(f64::total_cmp);
    ms.dedup();
    // (cases at this M, all of them within the target) per distinct M, in increasing M.
    let per_m: Vec<(usize, bool)> = ms
        .iter()
        .map(|&m| {
            let at: Vec<_> = points.iter().filter(|p| p.0 == m).collect();
            let ok = at
                .iter()
                .all(|&&(_, _, f, d)| (f / d - 1.0).abs() <= target);
            (at.len(), ok)
        })
        .collect();
    let mut best: Option<(usize, usize, usize)> = None; // (first, last, cases)
    let mut start = 0;
    let mut cases = 0;
    for (k, &(n, ok)) in per_m.iter().enumerate() {
        if !ok {
            start = k + 1;
            cases = 0;
            continue;
        }
        cases += n;
        if best.is_none_or(|(_, _, c)| cases >= c) {
            best = Some((start, k, cases));
        }
    }
    best.map(|(a, b, n)| TargetRange {
        target,
        m_lo: ms[a],
        m_hi: ms[b],
        n,
        of: points.len(),
    })
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

    /// Errors (formula/data - 1) of a made-up formula on a grid of M x L: a bad row at M = 2 and
    /// one at M = 500 split the range; the longer run between them (M = 5 .. 200) is kept.
    #[test]
    fn target_range_is_the_longest_run_of_m_values_within_the_target() {
        let ms = [1.0, 2.0, 5.0, 10.0, 50.0, 200.0, 500.0, 1000.0];
        let mut pts = vec![];
        for &m in &ms {
            for l in [0.0, 10.0] {
                let e = match (m, l) {
                    (2.0, 10.0) => 0.045,
                    (500.0, 0.0) => -0.021,
                    _ => 0.019,
                };
                pts.push((m, l, 1.0 + e, 1.0));
            }
        }
        let r = target_range(&pts, 0.02).unwrap();
        assert_eq!((r.m_lo, r.m_hi, r.n, r.of), (5.0, 200.0, 8, 16));
        // Everything within a looser target: the whole range.
        let r = target_range(&pts, 0.05).unwrap();
        assert_eq!((r.m_lo, r.m_hi, r.n), (1.0, 1000.0, 16));
        // Nothing within a tight one.
        assert!(target_range(&pts, 0.01).is_none());
        // A tie (one M value each side of the bad one) goes to the higher M.
        let two = [
            (1.0, 0.0, 1.0, 1.0),
            (2.0, 0.0, 1.5, 1.0),
            (3.0, 0.0, 1.0, 1.0),
        ];
        let r = target_range(&two, 0.02).unwrap();
        assert_eq!((r.m_lo, r.m_hi, r.n, r.of), (3.0, 3.0, 1, 3));
    }
}
