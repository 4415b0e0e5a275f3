//! The mixed-lubrication map of a sweep dataset: per smooth case (contact, M, L, D) and
//! roughness orientation gamma, the film ratios H_c/H_c_smooth and H_min/H_min_smooth and the
//! asperity share of the load against the film parameter Lambda = H_min/sigma, the Stribeck-like
//! map that designers read.
//!
//! Contract. Input: dataset rows ([`CaseRow`]). Rows with a roughness (`sigma` not null) that
//! converged, are valid and carry their smooth films make the points; other rough rows are
//! counted as left out, with the reason. Output: a [`MixedMap`] of curves, each sorted by
//! decreasing Lambda, and its Markdown ([`mixed_markdown`]). Pure: no files, no printing.

use crate::model::roughness::gamma_label;
use crate::store::results::{CaseRow, RowStatus};
use serde::Serialize;

/// One rough case of a curve.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MixedPoint {
    /// Composite RMS roughness, Moes film units.
    pub sigma: f64,
    /// H_min/sigma.
    pub lambda: f64,
    /// H_c over the smooth case's.
    pub h_c_ratio: f64,
    /// H_min over the smooth case's.
    pub h_min_ratio: f64,
    /// The share of the load the asperities carry.
    pub asperity_load_fraction: f64,
}

/// The rough cases of one smooth case and orientation.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MixedCurve {
    /// "line" or "point".
    pub contact: String,
    /// Moes M.
    pub m: f64,
    /// Moes L.
    pub l: f64,
    /// Ellipticity (point contacts).
    pub d: Option<f64>,
    /// Roughness orientation.
    pub gamma: f64,
    /// The points, by decreasing Lambda.
    pub points: Vec<MixedPoint>,
}

impl MixedCurve {
    /// A short label: `line M=100 L=10 gamma=1`.
    pub fn label(&self) -> String {
        let d = self.d.map_or(String::new(), |d| format!(" D={d}"));
        let gamma = gamma_label(self.gamma);
        format!(
            "{} M={} L={}{d} gamma={gamma}",
            self.contact, self.m, self.l
        )
    }
}

/// The map of a dataset.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct MixedMap {
    /// One curve per smooth case and orientation, in the order of (contact, M, L, D, gamma).
    pub curves: Vec<MixedCurve>,
    /// Rough rows left out, each with its case id and why.
    pub left_out: Vec<(String, String)>,
}

/// The map of `rows` (module docs).
pub fn mixed_map(rows: &[CaseRow]) -> MixedMap {
    let mut map = MixedMap::default();
    for r in rows.iter().filter(|r| r.sigma.is_some()) {
        let why = if r.status != RowStatus::Converged {
            Some(format!("status {}", r.status.as_str()))
        } else if !r.valid {
            Some("not valid".to_string())
        } else {
            None
        };
        let point = match (
            why,
            r.sigma,
            r.lambda_min,
            r.h_c,
            r.h_min,
            r.h_c_smooth,
            r.h_min_smooth,
            r.asperity_load_fraction,
        ) {
            (None, Some(s), Some(lam), Some(hc), Some(hm), Some(hcs), Some(hms), Some(f)) => {
                MixedPoint {
                    sigma: s,
                    lambda: lam,
                    h_c_ratio: hc / hcs,
                    h_min_ratio: hm / hms,
                    asperity_load_fraction: f,
                }
            }
            (Some(why), ..) => {
                map.left_out.push((r.case_id.clone(), why));
                continue;
            }
            _ => {
                map.left_out
                    .push((r.case_id.clone(), "no smooth film beside it".to_string()));
                continue;
            }
        };
        let key = |c: &MixedCurve| {
            c.contact == r.contact.as_str()
                && c.m == r.m
                && c.l == r.l
                && c.d == r.d
                && Some(c.gamma) == r.gamma
        };
        match map.curves.iter_mut().find(|c| key(c)) {
            Some(c) => c.points.push(point),
            None => map.curves.push(MixedCurve {
                contact: r.contact.as_str().to_string(),
                m: r.m,
                l: r.l,
                d: r.d,
                gamma: r.gamma.unwrap_or(1.0),
                points: vec![point],
            }),
        }
    }
    for c in &mut map.curves {
        c.points.sort_by(|a, b| b.lambda.total_cmp(&a.lambda));
    }
    map.curves.sort_by(|a, b| {
        (a.contact.as_str(), a.m, a.l, a.d.unwrap_or(0.0), a.gamma)
            .partial_cmp(&(b.contact.as_str(), b.m, b.l, b.d.unwrap_or(0.0), b.gamma))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    map
}

/// The map as Markdown: one table per curve (Lambda, sigma, the film ratios, the asperity
/// share), then the rows left out.
pub fn mixed_markdown(map: &MixedMap) -> String {
    let mut s = String::from("# Mixed lubrication: film and asperity load against Lambda\n\n");
    s += "Lambda = H_min/sigma; film ratios against the same case with smooth surfaces \
          (Patir-Cheng average flow, Greenwood-Tripp asperity contact).\n";
    if map.curves.is_empty() {
        s += "\nNo converged rough case in the data (give the sweep an axis sigma).\n";
    }
    for c in &map.curves {
        s += &format!("\n## {}\n\n", c.label());
        s += "| Lambda | sigma | H_c/H_c,smooth | H_min/H_min,smooth | asperity load |\n";
        s += "|---:|---:|---:|---:|---:|\n";
        for p in &c.points {
            s += &format!(
                "| {:.3} | {:.4} | {:.4} | {:.4} | {:.2e} |\n",
                p.lambda, p.sigma, p.h_c_ratio, p.h_min_ratio, p.asperity_load_fraction
            );
        }
    }
    if !map.left_out.is_empty() {
        s += &format!("\n## Left out ({} rows)\n\n", map.left_out.len());
        for (id, why) in &map.left_out {
            s += &format!("- {id}: {why}\n");
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::store::results::row::sample;

    fn rough(id: &str, sigma: f64, lambda: f64, hc: f64, share: f64) -> CaseRow {
        CaseRow {
            sigma: Some(sigma),
            gamma: Some(1.0),
            lambda_min: Some(lambda),
            h_c: Some(hc),
            h_min: Some(lambda * sigma),
            h_c_smooth: Some(4.0),
            h_min_smooth: Some(3.0),
            asperity_load_fraction: Some(share),
            ..sample(id)
        }
    }

    #[test]
    fn rows_become_curves_sorted_by_lambda_and_failures_are_named() {
        let mut failed = rough("03", 2.0, 1.5, 4.5, 1e-3);
        failed.status = RowStatus::MaxIterations;
        let smooth = CaseRow {
            sigma: None,
            ..sample("04")
        };
        let rows = [
            rough("01", 1.0, 3.2, 4.1, 0.0),
            rough("02", 4.0, 0.9, 4.8, 2e-3),
            failed,
            smooth,
        ];
        let map = mixed_map(&rows);
        assert_eq!(map.curves.len(), 1);
        let c = &map.curves[0];
        assert_eq!(c.points.len(), 2);
        assert!(c.points[0].lambda > c.points[1].lambda);
        assert_eq!(c.points[1].h_c_ratio, 4.8 / 4.0);
        assert_eq!(c.points[1].h_min_ratio, 0.9 * 4.0 / 3.0);
        assert_eq!(
            map.left_out,
            vec![("03".into(), "status max-iterations".into())]
        );
        let md = mixed_markdown(&map);
        assert!(
            md.contains("| 0.900 | 4.0000 | 1.2000 | 1.2000 | 2.00e-3 |"),
            "{md}"
        );
        assert!(md.contains("- 03: status max-iterations"));
    }
}
