//! Fitted asymptotes against the solver's own limit solves. The solves are shared by the films
//! fitted (H_c, H_pm, H_min: [`Film`]); each film's law is compared with the same film of the
//! solve.
//!
//! * RI: rigid, L = 0 solve (line 4097 points, point 257 x 257); H_RI M (line) or H_RI M^2 (point)
//!   is exact for any M, so one solve at M = 1 gives the constant. A point solve's domain
//!   truncation biases it low by about 30 %, so the point row compares the extrapolation of solves
//!   on domains enlarged 1, 2, 4 times ([`crate::limits::rigid_point`]), its trend the ratio on each.
//!   When the point data go below the check's D, a second RI row checks the D factor: far-field
//!   rigid solves ([`crate::limits::rigid_d_factor`]) at the data's smallest D and a tenth of it,
//!   its trend the ratio at each D.
//! * EI: elastic, L = 0, at the largest M of the data; EP: elastic at the largest M and L. Both
//!   are also solved at 1/10 and 1/sqrt(10) of that M: the ratio's trend shows how far the data's
//!   extreme still is from the limit.
//! * RP: a rigid Barus solve converges only while the Barus pressure stays finite; the reduced
//!   pressure q = (1 - exp(-alpha p))/alpha obeys the isoviscous Reynolds equation, so the rigid
//!   Barus film is the rigid isoviscous film whose peak alpha q_max is below 1, and the
//!   rigid-piezoviscous limit (M -> infinity at fixed L) is where alpha q_max = 1 (the load is
//!   carried by an infinite pressure peak: no finite-grid solve reaches it; direct solves at
//!   L = 20 diverge from M = 1 up). Rigid isoviscous scaling gives alpha p_max = c L H^(-3/2), so
//!   H_RP = (c L)^(2/3) with c = alpha_bar(L = 1) P_max H_c^(3/2) from the solver's rigid L = 0
//!   solve; that is the "solver" value of the RP row.

use crate::fit::dataset::FitPoint;
use crate::fit::dataset::MAX_ERROR_ESTIMATE;
use crate::fit::model::LineModel;
use crate::fit::point_model::PointModel;
use crate::fit::side::SideLobe;
use crate::fit::stats::null_as_nan;
use crate::limits::beyond::{Beyond, BeyondSolves};
use crate::limits::line_ep::{LineEpLimit, EP_L, EP_M};
use crate::limits::rigid_d_factor::{FarFieldRigid, CHECK_GRIDS};
use crate::limits::rigid_point::{extrapolate, RigidPointSolves, DOMAIN_SCALES};
use crate::limits::solves::{
    largest_m_at, line_solve, point_alpha_bar_1, point_solve, LimitSolves, Solve, POINT_CHECK_GRID,
};
use crate::model::case::Elasticity;
use crate::solve::film::Film;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// One asymptote compared with a limit solve of the solver.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AsymptoteCheck {
    /// The film (H_c, H_pm, H_min; reports before H_pm checked H_c only).
    #[serde(default = "h_c_name")]
    pub quantity: String,
    /// The asymptote: "rigid-isoviscous", "elastic-isoviscous", "rigid-piezoviscous" or
    /// "elastic-piezoviscous".
    pub asymptote: String,
    /// The fitted law as text, with its coefficients (e.g. "2.4475 M^-1 (exact, fixed)").
    pub law: String,
    /// M of the limit solve: 1 (rigid-isoviscous), the largest M of the data's cases at the
    /// row's L (elastic rows), infinite (rigid-piezoviscous, the limit M -> infinity; null in
    /// fit.json, read back as NaN).
    #[serde(deserialize_with = "null_as_nan")]
    pub m: f64,
    /// L of the limit solve: 0 for the isoviscous rows, the largest L of the data otherwise.
    #[serde(deserialize_with = "null_as_nan")]
    pub l: f64,
    /// Ellipticity D of the point checks; None for line contacts.
    pub d: Option<f64>,
    /// "rigid" or "elastic": the elasticity of the limit solve.
    pub elasticity: String,
    /// Points per direction of the limit solve (None for a failed solve).
    #[serde(default)]
    pub grid: Option<usize>,
    /// The solver's value of the film.
    #[serde(alias = "solver_h_c")]
    pub solver: Option<f64>,
    /// The fitted asymptote at (M, L) (at M = 1 for the rigid-piezoviscous law, which does not
    /// depend on M).
    #[serde(deserialize_with = "null_as_nan")]
    pub fitted: f64,
    /// solver / fitted asymptote (1 in the limit); None if the limit solve failed.
    pub ratio: Option<f64>,
    /// How the solver value was obtained (which solves, or why it is biased).
    pub note: String,
    /// (M, solver / fitted asymptote) as M grows to the largest M of the data (elastic rows), or
    /// (domain scale, ratio) as the domain grows (point rigid row), or (D, ratio) as D falls
    /// (the D factors' rigid rows), or (L, ratio) as L grows (the line elastic-piezoviscous
    /// limit row): how the ratio approaches its limit.
    #[serde(default)]
    pub trend: Vec<(f64, f64)>,
    /// What the trend's first entry is: "M", "domain scale", "D" or "L" (the line
    /// elastic-piezoviscous limit row).
    #[serde(default = "m_name")]
    pub trend_over: String,
    /// Elastic-piezoviscous row: (L, solver / fitted law) at the largest M and twice the largest
    /// L of the data, beyond the swept range, where the EI law's share of the blend is smaller
    /// (it falls like L^-3/4): whether the ratio keeps approaching 1 past the data. The ratio is
    /// None when that solve failed.
    #[serde(default)]
    pub beyond: Option<(f64, Option<f64>)>,
    /// Point elastic-isoviscous rows: the solver a decade of M beyond the data (L = 0, three
    /// grids, Richardson-extrapolated) over the whole formula there ([`Beyond`]; issue 24 asks
    /// 0.5 %). None for the other rows, line contacts, reports fitted without limit solves and
    /// those written before it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub decade: Option<Beyond>,
}

fn m_name() -> String {
    "M".to_string()
}

fn h_c_name() -> String {
    Film::Centre.name().to_string()
}

/// The fitted laws of one film: their text and the four asymptotes [RI, EI, RP, EP] at (M, L).
struct Laws<'a> {
    text: [String; 4],
    notes: [&'a str; 4],
    at: &'a dyn Fn(f64, f64) -> [f64; 4],
}

/// The four checks of one film (RP and EP only when the data have L > 0).
fn film_checks(film: Film, s: &LimitSolves, d: Option<f64>, laws: Laws) -> Vec<AsymptoteCheck> {
    let rigid = s.rigid.as_ref().map(|(o, _)| o);
    let none: &[Solve] = &[];
    // (name, M, L, elasticity, the solve, the trend solves)
    let rows = [
        ("rigid-isoviscous", 1.0, 0.0, Elasticity::Rigid, rigid, none),
        (
            "elastic-isoviscous",
            s.m_ei,
            0.0,
            Elasticity::Elastic,
            LimitSolves::top(&s.ei),
            &s.ei[..],
        ),
        (
            "rigid-piezoviscous",
            f64::INFINITY,
            s.l_max,
            Elasticity::Rigid,
            rigid,
            none,
        ),
        (
            "elastic-piezoviscous",
            s.m_ep,
            s.l_max,
            Elasticity::Elastic,
            LimitSolves::top(&s.ep),
            &s.ep[..],
        ),
    ];
    let n = if s.l_max > 0.0 { 4 } else { 2 };
    rows.into_iter()
        .zip(laws.text)
        .zip(laws.notes)
        .enumerate()
        .take(n)
        .map(|(k, (((name, m, l, el, out, solves), law), note))| {
            // The rigid-piezoviscous law is evaluated at any finite M (it does not depend on M);
            // its solver value is the limit alpha q_max = 1 of the rigid solve, not its film.
            let fitted = (laws.at)(if m.is_finite() { m } else { 1.0 }, l)[k];
            let solver = if k == 2 {
                s.rp(film)
            } else {
                out.map(|o| film.of_outputs(o))
            };
            let trend = solves
                .iter()
                .filter_map(|(m, o)| {
                    o.as_ref()
                        .map(|o| (*m, film.of_outputs(o) / (laws.at)(*m, l)[k]))
                })
                .collect();
            AsymptoteCheck {
                quantity: film.name().to_string(),
                asymptote: name.to_string(),
                law,
                m,
                l,
                d,
                elasticity: el.to_string(),
                grid: out.map(|o| o.grid),
                solver,
                fitted,
                ratio: solver.map(|v| v / fitted),
                note: note.to_string(),
                trend,
                trend_over: m_name(),
                beyond: s.ep_beyond.as_ref().filter(|_| k == 3).map(|(l2, o)| {
                    let law = (laws.at)(s.m_ep, *l2)[3];
                    (*l2, o.as_ref().map(|o| film.of_outputs(o) / law))
                }),
                decade: None,
            }
        })
        .collect()
}

const RP_NOTE: &str =
    "limit alpha q_max = 1 from the rigid L = 0 solve (direct Barus solves diverge)";

/// The line checks (seven solves at 4097 points, or 2049 should 4097 fail; a few seconds) of
/// each fitted film; with L > 0 data also the elastic-piezoviscous limit itself
/// ([`LineEpLimit`]: three solves at M = 1e4 up to 65537 points, about 15 s).
pub fn line_checks(fits: &[(Film, LineModel)], pts: &[FitPoint]) -> Vec<AsymptoteCheck> {
    let cases: Vec<(f64, f64)> = pts.iter().map(|p| (p.m, p.l)).collect();
    let piezo = cases.iter().any(|c| c.1 > 0.0);
    let (s, ep) = rayon::join(
        || LimitSolves::new(&cases, line_solve(1.0, 0.0, Elasticity::Rigid), line_solve),
        || piezo.then(LineEpLimit::run),
    );
    let mut out = vec![];
    for (film, fit) in fits {
        let x = &fit.x;
        let laws = Laws {
            text: [
                format!("{} M^-1 (exact, fixed)", fit.c_ri),
                format!("{:.4} M^{:.4}", x[0].exp(), x[1]),
                format!("{:.4} L^{:.4}", x[2].exp(), x[3]),
                format!("{:.4} M^{:.4} L^{:.4}", x[4].exp(), x[5], x[6]),
            ],
            notes: [
                "rigid solve, L = 0",
                "largest M of the data's L = 0 cases",
                RP_NOTE,
                "largest L of the data and the largest M there (the RP and EI laws still \
                 contribute; also solved at twice that L, beyond the data)",
            ],
            at: &|m, l| fit.asymptotes(m, l),
        };
        out.extend(film_checks(*film, &s, None, laws));
        if let Some(ep) = &ep {
            out.push(ep_limit_row(*film, fit, ep));
        }
    }
    out
}

/// The elastic-piezoviscous row of the limit itself: the law's constant H_EP M^(1/8) L^(-3/4)
/// against the solver's c(L) = H M^(1/8) L^(-3/4) at M = [`EP_M`] extrapolated to L -> infinity
/// ([`LineEpLimit::limit`]); its trend the ratio at each L solved.
fn ep_limit_row(film: Film, fit: &LineModel, ep: &LineEpLimit) -> AsymptoteCheck {
    let x = &fit.x;
    let law = |l: f64| fit.asymptotes(EP_M, l)[3] * EP_M.powf(0.125) / l.powf(0.75);
    let fitted = law(EP_L[EP_L.len() - 1]);
    let solver = ep.limit(film);
    AsymptoteCheck {
        quantity: film.name().to_string(),
        asymptote: "elastic-piezoviscous".to_string(),
        law: format!(
            "{:.4} M^{:.4} L^{:.4} (its constant)",
            x[4].exp(),
            x[5],
            x[6]
        ),
        m: EP_M,
        l: f64::INFINITY,
        d: None,
        elasticity: "elastic".to_string(),
        grid: ep
            .solves
            .iter()
            .filter_map(|(_, o)| o.as_ref().map(|o| o.grid))
            .max(),
        solver,
        fitted,
        ratio: solver.map(|v| v / fitted),
        note: EP_LIMIT_NOTE.to_string(),
        trend: ep
            .constants(film)
            .into_iter()
            .map(|(l, c)| (l, c / law(l)))
            .collect(),
        trend_over: "L".to_string(),
        beyond: None,
        decade: None,
    }
}

const EP_LIMIT_NOTE: &str = "the limit L -> infinity of H M^(1/8) L^(-3/4) at M = 1e4: solves at \
     L = 20, 40, 80 (on 65537 points, each within 0.3 %), Aitken's extrapolation \
     (src/limits/line_ep.rs); solver and law are the constant d itself";

/// The point checks of each fitted film, at D = 1 (else the largest D of the data): seven
/// elastic solves at 257 x 257 points, or the data's finer grid, and the rigid solves on
/// enlarged domains (about 110 s of work at 257^2, 60 s on two cores; on the 513^2 nightly
/// data 10 min, most of it elastic L = 20 solves that run the whole fallback ladder and fail);
/// and the D factor's four far-field rigid solves (a few seconds) when the data have D < 1.
pub fn point_checks(
    fits: &[(Film, PointModel)],
    side: Option<&SideLobe>,
    pts: &[FitPoint],
) -> Vec<AsymptoteCheck> {
    // At D = 1 when the data have it (else their largest D), up to that D's largest M and L.
    let ds = pts.iter().filter_map(|p| p.d);
    let d = if ds.clone().any(|d| d == 1.0) {
        1.0
    } else {
        ds.fold(0.0, f64::max)
    };
    let at_d: Vec<FitPoint> = pts.iter().filter(|p| p.d == Some(d)).copied().collect();
    let grid = at_d
        .iter()
        .filter_map(|p| p.grid)
        .fold(POINT_CHECK_GRID, usize::max);
    // The enlarged-domain rigid solves (about 60 s for the 1025^2 one) beside the elastic ones;
    // their default-domain solve is the plain rigid solve of the rigid-piezoviscous row.
    // The D factor of H_RI: far-field rigid solves at the data's smallest D and a tenth of it
    // (when the data go below the check's D).
    let d_min = pts.iter().filter_map(|p| p.d).fold(d, f64::min);
    let slender = if d_min < d {
        vec![d_min, d_min / 10.0]
    } else {
        vec![]
    };
    // Beside them, the elastic-isoviscous solve a decade of M beyond the data's largest L = 0
    // case at d.
    let cases: Vec<(f64, f64)> = at_d.iter().map(|p| (p.m, p.l)).collect();
    let ((mut s, domains), (far, decade)) = rayon::join(
        || {
            rayon::join(
                || {
                    LimitSolves::new(&cases, None, |m, l, el| {
                        point_solve(m, l, d, el, grid, MAX_ERROR_ESTIMATE)
                    })
                },
                || RigidPointSolves::run(d),
            )
        },
        || {
            rayon::join(
                || {
                    slender
                        .par_iter()
                        .filter_map(|&d| FarFieldRigid::run(d))
                        .collect::<Vec<_>>()
                },
                || BeyondSolves::run(largest_m_at(&cases, 0.0), d),
            )
        },
    );
    let ab1 = point_alpha_bar_1(1.0, d, Elasticity::Rigid);
    s.rigid = domains
        .as_ref()
        .and_then(|r| r.default_domain())
        .zip(ab1)
        .map(|(o, ab1)| (o.clone(), ab1));
    let mut out = vec![];
    for (film, fit) in fits {
        let x = &fit.x;
        // H_min's asymptotes are the centre-line law's times the side-lobe factor (constant
        // beyond the data's box, 1 where there is no side lobe).
        let factor = |m: f64, l: f64, d: f64| match side {
            Some(s) if *film == Film::Minimum => s.factor(m, l, d),
            _ => 1.0,
        };
        let laws = Laws {
            text: [
                format!("{:.3} f_RI(D) D^{:.3} M^-2", x[0].exp(), x[1]),
                format!(
                    "{:.4} f_EI(D) D^{:.3} M^{:.4}{}",
                    x[2].exp(),
                    x[4],
                    x[3],
                    if fit.ei_exact {
                        " g(M, D) (exact f_EI, held at the line's limit; g -> 1 as M -> inf)"
                    } else {
                        ""
                    }
                ),
                format!(
                    "{:.4} f_RP(D) D^{:.3} L^{:.4}{}",
                    x[5].exp(),
                    x[7],
                    x[6],
                    if fit.rp_shape.is_some() {
                        " (held at the rigid limit)"
                    } else {
                        ""
                    }
                ),
                format!(
                    "{:.4} f_EP(D) D^{:.3} M^{:.4} L^{:.4}",
                    x[8].exp(),
                    x[11],
                    x[9],
                    x[10]
                ),
            ],
            notes: [
                RIGID_POINT_NOTE,
                "largest M of the data's L = 0 cases; trend solves with a domain-truncation \
                 error above 2 % are left out",
                RP_NOTE,
                "largest L of the data and the largest M there (the other laws still \
                 contribute; also solved at twice that L, beyond the data)",
            ],
            at: &|m, l| fit.asymptotes(m, l, d).map(|h| h * factor(m, l, d)),
        };
        let mut rows = film_checks(*film, &s, Some(d), laws);
        if let Some(row) = rows
            .iter_mut()
            .find(|r| r.asymptote == "elastic-isoviscous")
        {
            row.decade = Some(decade.of(*film));
        }
        match domains.as_ref().filter(|r| r.converged()) {
            Some(r) => {
                domain_limit(&mut rows[0], r, *film);
                if let (Some(row), Some(ab1)) = (rows.get_mut(2), ab1) {
                    domain_rp(row, r, *film, ab1);
                }
            }
            None => rows[0].note = RIGID_POINT_FAILED.to_string(),
        }
        if let Some(row) = d_factor_row(fit, *film, &far, &factor) {
            rows.insert(1, row);
        }
        let rp_at = rows
            .iter()
            .position(|r| r.asymptote == "rigid-piezoviscous");
        if let (Some(k), Some(row)) = (rp_at, rp_factor_row(fit, *film, &far, s.l_max)) {
            rows.insert(k + 1, row);
        }
        out.extend(rows);
    }
    out
}

/// The rigid-isoviscous row of the D factor: at the last of the far-field solves `far` (a tenth
/// of the data's smallest D, beyond the data), its trend the ratio at each D; None without
/// solves. A failed solve gives a row without a solver value.
fn d_factor_row(
    fit: &PointModel,
    film: Film,
    far: &[FarFieldRigid],
    factor: &dyn Fn(f64, f64, f64) -> f64,
) -> Option<AsymptoteCheck> {
    let [a, p, q] = fit.ri_shape;
    let law = format!(
        "{:.3} [(1 + {a:.5} D^{p:.5})/(1 + {a:.5})]^({q:.5}) D^{:.3} / D M^-2",
        fit.x[0].exp(),
        fit.x[1]
    );
    far_row(
        (film, "rigid-isoviscous", law, 1.0, 0.0),
        far,
        &|r| r.converged().then(|| r.constant(film)),
        &|d| fit.asymptotes(1.0, 0.0, d)[0] * factor(1.0, 0.0, d),
        D_FACTOR_NOTE,
    )
}

/// The rigid-piezoviscous row of the D factor at the largest L of the data: like
/// [`d_factor_row`], the solver's value pi(D) H_RI(1, D) L^(2/3) of the far-field solves
/// ([`FarFieldRigid::rp_constant`]); None without solves.
fn rp_factor_row(
    fit: &PointModel,
    film: Film,
    far: &[FarFieldRigid],
    l: f64,
) -> Option<AsymptoteCheck> {
    let x = &fit.x;
    let law = format!("{:.4} f_RP(D) D^{:.3} L^{:.4}", x[5].exp(), x[7], x[6]);
    let l23 = l.powf(2.0 / 3.0);
    far_row(
        (film, "rigid-piezoviscous", law, f64::INFINITY, l),
        far,
        &|r| {
            let ab1 = point_alpha_bar_1(1.0, r.d, Elasticity::Rigid)?;
            r.converged().then(|| r.rp_constant(film, ab1) * l23)
        },
        &|d| fit.asymptotes(1.0, l, d)[2],
        RP_FACTOR_NOTE,
    )
}

/// A D-factor row (film, asymptote, law text, M, L) at the last of the far-field solves `far`:
/// `solver` the solver's value of a solve, `law` the fitted law at D; its trend the ratio at each
/// D. None without solves.
fn far_row(
    (film, asymptote, law_text, m, l): (Film, &str, String, f64, f64),
    far: &[FarFieldRigid],
    solver: &dyn Fn(&FarFieldRigid) -> Option<f64>,
    law: &dyn Fn(f64) -> f64,
    note: &str,
) -> Option<AsymptoteCheck> {
    let last = far.last()?;
    let fitted = law(last.d);
    let value = solver(last);
    Some(AsymptoteCheck {
        quantity: film.name().to_string(),
        asymptote: asymptote.to_string(),
        law: law_text,
        m,
        l,
        d: Some(last.d),
        elasticity: "rigid".to_string(),
        grid: last.converged().then_some(CHECK_GRIDS[1]),
        solver: value,
        fitted,
        ratio: value.map(|v| v / fitted),
        note: note.to_string(),
        trend: far
            .iter()
            .filter_map(|r| solver(r).map(|v| (r.d, v / law(r.d))))
            .collect(),
        trend_over: "D".to_string(),
        beyond: None,
        decade: None,
    })
}

const RP_FACTOR_NOTE: &str = "the D factor: limit alpha q_max = 1 of the rigid solves, L = 0, \
     with the far field on 257^2 and 513^2 (tight, Richardson in the grid; \
     src/limits/rigid_rp.rs) at the data's smallest D and a tenth of it, beyond the data";

const D_FACTOR_NOTE: &str = "the D factor: rigid solves, L = 0, with the far field on 257^2 \
     and 513^2 (tight, Richardson in the grid; src/limits/rigid_d_factor.rs) at the data's \
     smallest D and a tenth of it, beyond the data";

const RIGID_POINT_NOTE: &str = "rigid solves, L = 0 (H M^2 is exact for any M) on the default \
     domain enlarged 1, 2, 4 times, extrapolated to an unbounded one (the pressure decays like \
     r^-3: H is low by about 1/R; src/limits/rigid_point.rs)";
const RIGID_POINT_FAILED: &str = "rigid solve, L = 0, default domain only (an enlarged-domain \
     solve did not converge): biased low by its truncation, about 30 %";

/// The rigid-piezoviscous row from the domain-enlarged solves: c = alpha_bar(L = 1) P_max
/// H^(3/2) on each domain (the default domain's is biased like its film), extrapolated in 1/R
/// like the film; the solver value is (c L)^(2/3), the trend the ratio on each domain.
fn domain_rp(row: &mut AsymptoteCheck, r: &RigidPointSolves, film: Film, ab1: f64) {
    let c = [0, 1, 2].map(|k| {
        let o = &r.solves[k].1;
        ab1 * o.p_max * film.of_outputs(o).powf(1.5)
    });
    let h_rp = |c: f64| (c * row.l).powf(2.0 / 3.0);
    let solver = h_rp(extrapolate(c));
    set_domain_row(row, r, solver, c.map(h_rp));
    row.note = RP_POINT_NOTE.to_string();
}

const RP_POINT_NOTE: &str = "limit alpha q_max = 1 from the rigid L = 0 solves on the default \
     domain enlarged 1, 2, 4 times, extrapolated to an unbounded one like the rigid-isoviscous \
     row (direct Barus solves diverge)";

/// The rigid-isoviscous row from the domain-enlarged solves: the solver value is their
/// extrapolation, the trend the ratio on each domain.
fn domain_limit(row: &mut AsymptoteCheck, r: &RigidPointSolves, film: Film) {
    set_domain_row(row, r, r.extrapolated(film), r.films(film));
}

/// A row whose solver value is the domain extrapolation `solver` of the values `per_domain` on
/// the [`DOMAIN_SCALES`] (its trend: the ratio on each domain).
fn set_domain_row(
    row: &mut AsymptoteCheck,
    r: &RigidPointSolves,
    solver: f64,
    per_domain: [f64; 3],
) {
    row.solver = Some(solver);
    row.ratio = Some(solver / row.fitted);
    row.grid = r.solves.last().map(|(_, o)| o.grid);
    row.trend = DOMAIN_SCALES
        .iter()
        .zip(per_domain)
        .map(|(s, h)| (*s, h / row.fitted))
        .collect();
    row.trend_over = "domain scale".to_string();
}
