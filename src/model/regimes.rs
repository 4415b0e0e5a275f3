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
pub const LOG_M: (f64, f64) = (-1.0, 4.0);
/// Largest L of the map.
pub const L_MAX: f64 = 25.0;

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
}
