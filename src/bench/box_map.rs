//! Where the default solve works: the box of cases that real machine elements span, each solved
//! as a user's default would be (the full model to the default 1 % accuracy target, the
//! accuracy ladder up to the largest grid, with its fallback ladder where the accuracy ladder
//! asks for the full effort), with a time limit per case. Each cell records the status, the
//! attempt of the fallback ladder that answered, the grid, the work units, the wall time and
//! whether the target was met.
//!
//! The box: line M in [0.01, 1e5] x L in [0, 40]; point M in [0.01, 3e4] x L in [0, 30] x
//! D in {1, 0.1, 0.01}; each with Barus viscosity and an incompressible lubricant, and with
//! Roelands viscosity and Dowson-Higginson density ([`model_sets`]). The cases run in parallel on the current
//! rayon pool, one solve per thread, and come back in the box's order. A cell that reaches
//! its time limit depends on the machine's speed (its reason says "time limit"); every other
//! cell does not.

use crate::model::case::{Case, LineCase, Models, PointCase};
use crate::model::lubricant::{Density, Viscosity};
use crate::strategy::solve_case::{solve, SolveParams};
use rayon::prelude::*;
use serde::Serialize;

/// One case of the box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoxCase {
    /// The case (its models included).
    pub case: Case,
    /// The panel of the map it belongs to ([`BoxCase::panel`]).
    pub panel: usize,
}

/// The Hertzian pressure of the box's Roelands and Dowson-Higginson models, Pa.
pub const BOX_PH_PA: f64 = 1e9;

/// The Roelands pressure-viscosity index of the box (a mineral oil).
pub const BOX_ROELANDS_Z: f64 = 0.6;

/// The models of the box and their names: (Barus, incompressible) and (Roelands with
/// [`BOX_ROELANDS_Z`], Dowson-Higginson), both at p_h = [`BOX_PH_PA`].
pub fn model_sets() -> [(Viscosity, Density, &'static str); 2] {
    [
        (Viscosity::Barus, Density::Incompressible, "Barus"),
        (
            Viscosity::Roelands {
                z: BOX_ROELANDS_Z,
                ph_pa: BOX_PH_PA,
            },
            Density::DowsonHigginson { ph_pa: BOX_PH_PA },
            "Roelands + DH",
        ),
    ]
}

/// The ellipticities of the point panels.
pub const POINT_D: [f64; 3] = [1.0, 0.1, 0.01];

/// The M and L values of one contact's box.
pub type Axes = (Vec<f64>, Vec<f64>);

/// The (M, L) values of the line and point boxes; `quick` gives the corners and the middle
/// only (for tests).
pub fn box_axes(quick: bool) -> (Axes, Axes) {
    if quick {
        return (
            (vec![0.01, 10.0, 1e5], vec![0.0, 40.0]),
            (vec![0.01, 10.0, 3e4], vec![0.0, 30.0]),
        );
    }
    (
        (
            vec![0.01, 0.1, 1.0, 10.0, 100.0, 1e3, 1e4, 1e5],
            vec![0.0, 10.0, 20.0, 30.0, 40.0],
        ),
        (
            vec![0.01, 0.1, 1.0, 10.0, 100.0, 1e3, 1e4, 3e4],
            vec![0.0, 10.0, 20.0, 30.0],
        ),
    )
}

/// The panel names, in panel order: per model set, the line panel then the point panels.
pub fn panel_names() -> Vec<String> {
    let mut names = vec![];
    for (_, _, models) in model_sets() {
        names.push(format!("line, {models}"));
        for d in POINT_D {
            names.push(format!("point D = {d}, {models}"));
        }
    }
    names
}

/// The cases of the box (`quick`: [`box_axes`]' small box), panel by panel.
pub fn box_cases(quick: bool) -> Vec<BoxCase> {
    let ((lm, ll), (pm, pl)) = box_axes(quick);
    let mut cases = vec![];
    let mut panel = 0;
    for (viscosity, density, _) in model_sets() {
        let models = Models {
            viscosity,
            density,
            ..Models::default()
        };
        for &m in &lm {
            for &l in &ll {
                let c = LineCase::with_models(m, l, models).expect("box values are valid");
                cases.push(BoxCase {
                    case: Case::Line(c),
                    panel,
                });
            }
        }
        panel += 1;
        for d in POINT_D {
            for &m in &pm {
                for &l in &pl {
                    let c = PointCase::with_models(m, l, d, models).expect("box values are valid");
                    cases.push(BoxCase {
                        case: Case::Point(c),
                        panel,
                    });
                }
            }
            panel += 1;
        }
    }
    cases
}

/// One cell of the box map.
#[derive(Clone, Debug, Serialize)]
pub struct BoxCell {
    /// The panel's name ([`panel_names`]).
    pub panel: String,
    /// "line" or "point".
    pub contact: String,
    /// Moes' load parameter M.
    pub m: f64,
    /// Moes' lubricant parameter L.
    pub l: f64,
    /// The ellipticity D (1 for line contacts, which have none).
    pub d: f64,
    /// The solve's status ("converged", "diverged", "stalled", "max-iterations",
    /// "under-resolved").
    pub status: String,
    /// The attempt of the fallback ladder (1-based) that answered on the last grid.
    pub attempt: usize,
    /// The last grid solved (points, per direction for point contacts).
    pub grid: usize,
    /// Work units of all grids and attempts.
    pub work_units: f64,
    /// Wall time of the case, s.
    pub wall_s: f64,
    /// Whether the 1 % target was met.
    pub accuracy_met: bool,
    /// The error estimate (relative), if any.
    pub error_estimate: Option<f64>,
    /// Whether the time limit ended the case.
    pub timed_out: bool,
    /// The solve's reason.
    pub reason: String,
}

/// Solve every case with the default target and `time_limit` seconds each (point contacts with
/// the asymptotic far field when `far_field`), in parallel on the current rayon pool; `log`
/// receives a line per finished case (in finishing order).
pub fn run_box(
    cases: &[BoxCase],
    time_limit: f64,
    far_field: bool,
    log: &(dyn Fn(&str) + Sync),
) -> Vec<BoxCell> {
    let names = panel_names();
    let done = std::sync::atomic::AtomicUsize::new(0);
    cases
        .par_iter()
        .with_max_len(1)
        .map(|bc| {
            let mut params = SolveParams {
                full_model: true,
                ..SolveParams::default()
            }
            .time_limit(Some(time_limit));
            params.point_domain.far_field = far_field;
            let s = solve(&bc.case, &params);
            let o = &s.outputs;
            let (contact, d) = match &bc.case {
                Case::Line(_) => ("line", 1.0),
                Case::Point(p) => ("point", p.d),
            };
            let cell = BoxCell {
                panel: names[bc.panel].clone(),
                contact: contact.to_string(),
                m: bc.case.m(),
                l: bc.case.l(),
                d,
                status: o.status.to_string(),
                attempt: s.attempt,
                grid: o.grid,
                work_units: o.work_units,
                wall_s: o.wall_s,
                accuracy_met: o.accuracy_met == Some(true),
                error_estimate: o.error_estimate,
                timed_out: o.reason.contains("time limit"),
                reason: o.reason.clone(),
            };
            let k = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            log(&format!(
                "[{k}/{}] {}: M = {}, L = {}: {} on {} points, attempt {}, {:.0} WU, {:.1} s",
                cases.len(),
                cell.panel,
                cell.m,
                cell.l,
                cell.status,
                cell.grid,
                cell.attempt,
                cell.work_units,
                cell.wall_s
            ));
            cell
        })
        .collect()
}

/// Per panel: (name, converged with the target met, converged, timed out, cases).
pub fn box_summary(cells: &[BoxCell]) -> Vec<(String, usize, usize, usize, usize)> {
    panel_names()
        .into_iter()
        .map(|name| {
            let of: Vec<&BoxCell> = cells.iter().filter(|c| c.panel == name).collect();
            let converged = of.iter().filter(|c| c.status == "converged").count();
            let met = of
                .iter()
                .filter(|c| c.status == "converged" && c.accuracy_met)
                .count();
            let timed = of.iter().filter(|c| c.timed_out).count();
            (name, met, converged, timed, of.len())
        })
        .filter(|r| r.4 > 0)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_box_spans_the_issue_ranges_panel_by_panel() {
        let cases = box_cases(false);
        assert_eq!(cases.len(), 2 * (8 * 5 + 3 * 8 * 4));
        assert_eq!(panel_names().len(), 8);
        let (mut m_lo, mut m_hi, mut l_hi) = (f64::INFINITY, 0.0f64, 0.0f64);
        for c in cases.iter().filter(|c| matches!(c.case, Case::Point(_))) {
            m_lo = m_lo.min(c.case.m());
            m_hi = m_hi.max(c.case.m());
            l_hi = l_hi.max(c.case.l());
        }
        assert_eq!((m_lo, m_hi, l_hi), (0.01, 3e4, 30.0));
        // Panels are contiguous and in order.
        assert!(cases.windows(2).all(|w| w[0].panel <= w[1].panel));
        assert_eq!(cases.last().unwrap().panel, 7);
    }
}
