//! The fit report: fits H_c and H_min, compares them and Moes 1992 with the data, checks each
//! fitted asymptote against the solver's own limit solves, and renders Markdown.

use crate::fit::lsq::{fit, Sample, ASYMPTOTES};
use crate::fit::model::{LineModel, PARAM_NAMES};
use crate::fit::stats::{err_stats, region_table, ErrStats, RegionStats};
use crate::formulas::moes_line_hc;
use crate::params::{Elasticity, LineCase, Models};
use crate::solver::line::{solve_line, LineSolveParams};
use crate::solver::Status;
use serde::{Deserialize, Serialize};
use std::fmt::Write;

/// The exact rigid-isoviscous constant of the film at X = 0 (Martin, Reynolds exit condition).
pub const C_RI_CENTRAL: f64 = 2.4475;

/// Datasets with at least this many converged cases also fit p, q and the s-law.
pub const FULL_FIT_MIN_POINTS: usize = 60;

/// One converged case of a dataset.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FitPoint {
    pub m: f64,
    pub l: f64,
    pub h_c: f64,
    pub h_min: f64,
}

/// What the fit reads: converged points plus counts of what was left out.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct FitInput {
    pub datasets: Vec<String>,
    pub points: Vec<FitPoint>,
    pub failed: usize,
    pub duplicates: usize,
}

/// A fitted parameter with its one-sigma uncertainty.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Param {
    pub name: String,
    pub value: f64,
    pub sigma: f64,
}

/// The fit of one quantity.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct QuantityFit {
    pub quantity: String,
    pub model: LineModel,
    pub params: Vec<Param>,
    pub rms_log: f64,
    pub converged: bool,
    pub overall: ErrStats,
    pub regions: Vec<RegionStats>,
}

/// One asymptote compared with a limit solve of the solver.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AsymptoteCheck {
    pub asymptote: String,
    pub law: String,
    pub m: f64,
    pub l: f64,
    pub elasticity: String,
    pub solver_h_c: Option<f64>,
    pub fitted: f64,
    /// solver / fitted asymptote (1 in the limit); None if the limit solve failed.
    pub ratio: Option<f64>,
    pub note: String,
}

/// Everything the report shows; `fit.json` is this, serialised.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FitReport {
    pub datasets: Vec<String>,
    pub converged_cases: usize,
    pub failed_cases: usize,
    pub duplicate_rows: usize,
    pub h_c: QuantityFit,
    pub h_min: QuantityFit,
    pub moes_1992: Option<ErrStats>,
    pub moes_1992_regions: Vec<RegionStats>,
    pub skipped: Vec<String>,
    pub asymptotes: Vec<AsymptoteCheck>,
}

fn fit_quantity(
    name: &str,
    pts: &[FitPoint],
    pick: impl Fn(&FitPoint) -> f64,
    scale: f64,
) -> Result<QuantityFit, String> {
    let data: Vec<Sample> = pts
        .iter()
        .map(|p| Sample {
            m: p.m,
            l: p.l,
            h: pick(p),
        })
        .collect();
    // Start from Moes with the elastic and piezoviscous asymptotes scaled (H_min ~ 3/4 H_c).
    let mut start = LineModel::moes();
    start.c_ri = C_RI_CENTRAL;
    for k in [0, 2, 4] {
        start.x[k] += f64::ln(scale);
    }
    let mut f = fit(&data, &start, &ASYMPTOTES).map_err(|e| format!("{name}: {e}"))?;
    // With enough data, free the blending powers and the s-law as well, starting from the
    // asymptote fit; keep the result only if it stays physical and fits better.
    if data.len() >= FULL_FIT_MIN_POINTS {
        let all: Vec<usize> = (0..f.model.x.len()).collect();
        if let Ok(g) = fit(&data, &f.model, &all) {
            let x = &g.model.x;
            let physical = x[7] > 0.5
                && x[8] > 0.5
                && x[9] > 0.5
                && x[11] > 0.0
                && x.iter().all(|v| v.abs() < 50.0);
            if physical && g.rms_log < f.rms_log {
                f = g;
            }
        }
    }
    let tuples: Vec<_> = data
        .iter()
        .map(|s| (s.m, s.l, f.model.eval(s.m, s.l), s.h))
        .collect();
    Ok(QuantityFit {
        quantity: name.to_string(),
        params: PARAM_NAMES
            .iter()
            .zip(f.model.x.iter().zip(&f.sigma))
            .map(|(n, (v, s))| Param {
                name: n.to_string(),
                value: *v,
                sigma: *s,
            })
            .collect(),
        model: f.model,
        rms_log: f.rms_log,
        converged: f.converged,
        overall: err_stats(&tuples).expect("non-empty data"),
        regions: region_table(&tuples),
    })
}

fn limit_solve(m: f64, l: f64, elasticity: Elasticity) -> Option<f64> {
    let case = LineCase::with_models(
        m,
        l,
        Models {
            elasticity,
            ..Models::default()
        },
    )
    .ok()?;
    let mut p = LineSolveParams::default();
    p.mg.grid = 4097;
    let s = solve_line(&case, &p);
    (s.outputs.status == Status::Converged).then_some(s.outputs.h_c)
}

fn checks(fit: &LineModel, pts: &[FitPoint]) -> Vec<AsymptoteCheck> {
    let m_max = pts.iter().map(|p| p.m).fold(0.0, f64::max);
    let l_max = pts.iter().map(|p| p.l).fold(0.0, f64::max);
    let x = &fit.x;
    let mut out = vec![];
    let mut push =
        |name: &str, law: String, m: f64, l: f64, el: Elasticity, idx: usize, note: &str| {
            let solver = limit_solve(m, l, el);
            let fitted = fit.asymptotes(m, l)[idx];
            out.push(AsymptoteCheck {
                asymptote: name.to_string(),
                law,
                m,
                l,
                elasticity: el.to_string(),
                solver_h_c: solver,
                fitted,
                ratio: solver.map(|s| s / fitted),
                note: note.to_string(),
            });
        };
    push(
        "rigid-isoviscous",
        format!("{C_RI_CENTRAL} M^-1 (exact, fixed)"),
        1.0,
        0.0,
        Elasticity::Rigid,
        0,
        "rigid solve, L = 0",
    );
    push(
        "elastic-isoviscous",
        format!("{:.4} M^{:.4}", x[0].exp(), x[1]),
        m_max,
        0.0,
        Elasticity::Elastic,
        1,
        "largest M of the data, L = 0",
    );
    if l_max > 0.0 {
        push(
            "rigid-piezoviscous",
            format!("{:.4} L^{:.4}", x[2].exp(), x[3]),
            10.0,
            l_max,
            Elasticity::Rigid,
            2,
            "rigid solve, largest L of the data (Barus rigid-piezoviscous solves may not exist)",
        );
        push(
            "elastic-piezoviscous",
            format!("{:.4} M^{:.4} L^{:.4}", x[4].exp(), x[5], x[6]),
            m_max,
            l_max,
            Elasticity::Elastic,
            3,
            "largest M and L of the data",
        );
    }
    out
}

/// Fit, compare and check. `limit_solves` runs the solver's limit cases (a few seconds).
pub fn fit_report(input: &FitInput, limit_solves: bool) -> Result<FitReport, String> {
    if input.points.is_empty() {
        return Err(format!(
            "no converged cases in {} ({} failed rows): nothing to fit",
            input.datasets.join(", "),
            input.failed
        ));
    }
    let h_c = fit_quantity("H_c", &input.points, |p| p.h_c, 1.0)?;
    let h_min = fit_quantity("H_min", &input.points, |p| p.h_min, 0.75)?;
    let moes: Vec<_> = input
        .points
        .iter()
        .map(|p| (p.m, p.l, moes_line_hc(p.m, p.l), p.h_c))
        .collect();
    Ok(FitReport {
        datasets: input.datasets.clone(),
        converged_cases: input.points.len(),
        failed_cases: input.failed,
        duplicate_rows: input.duplicates,
        asymptotes: if limit_solves { checks(&h_c.model, &input.points) } else { vec![] },
        h_c,
        h_min,
        moes_1992: err_stats(&moes),
        moes_1992_regions: region_table(&moes),
        skipped: vec![
            "Dowson-Toyoda 1979: needs G (and U, W' separately); a Moes-parameter sweep carries only M and L"
                .to_string(),
        ],
    })
}

fn pct(v: f64) -> String {
    format!("{:+.2} %", 100.0 * v)
}

fn stats_row(name: &str, s: &ErrStats) -> String {
    format!(
        "| {name} | {} | {} | {:.2} % | {} | M = {:.4}, L = {:.3} |\n",
        s.n,
        pct(s.max),
        100.0 * s.rms,
        pct(s.mean),
        s.worst_m,
        s.worst_l
    )
}

/// Markdown of the report.
pub fn to_markdown(r: &FitReport) -> String {
    let mut md = String::new();
    let _ = writeln!(md, "# ehlmap film-thickness fit (line contact)\n");
    let _ = writeln!(
        md,
        "Datasets: {}. Converged cases fitted: {}; failed rows left out: {}; duplicate rows dropped: {}.\n",
        r.datasets.join(", "),
        r.converged_cases,
        r.failed_cases,
        r.duplicate_rows
    );
    let _ = writeln!(
        md,
        "Formula (Moes units): H = [ (H_RI^p + H_EI^p)^(s/p) + (H_RP^-q + H_EP^-q)^(-s/q) ]^(1/s), \
         s = s0 + s1 exp(-s2 H_EI/H_RI), H_RI = 2.4475/M, H_EI = a M^alpha, H_RP = b L^beta, \
         H_EP = d M^gamma L^delta. The four asymptotes are fitted; p, q and the s-law start from Moes' \
         (p = 7/3, q = 7/2, s = 7/5 + 8/5 exp(-2 H_EI/H_RI)) and are fitted too when the dataset has \
         60 or more converged cases (a 1 sigma of 0 marks a parameter held fixed).\n"
    );
    for q in [&r.h_c, &r.h_min] {
        let _ = writeln!(
            md,
            "## {} (LM converged: {}, RMS of log residuals {:.2e})\n",
            q.quantity, q.converged, q.rms_log
        );
        let _ = writeln!(md, "| parameter | value | 1 sigma |\n|---|---|---|");
        for p in &q.params {
            let _ = writeln!(md, "| {} | {:.5} | {:.1e} |", p.name, p.value, p.sigma);
        }
        let _ = writeln!(
            md,
            "\n| region | n | max error | RMS | mean | worst at |\n|---|---|---|---|---|---|"
        );
        md.push_str(&stats_row("all", &q.overall));
        for rg in &q.regions {
            md.push_str(&stats_row(&rg.region, &rg.stats));
        }
        md.push('\n');
    }
    if let Some(m) = &r.moes_1992 {
        let _ = writeln!(md, "## Moes 1992 on the same cases (H_c)\n");
        let _ = writeln!(
            md,
            "| region | n | max error | RMS | mean | worst at |\n|---|---|---|---|---|---|"
        );
        md.push_str(&stats_row("all", m));
        for rg in &r.moes_1992_regions {
            md.push_str(&stats_row(&rg.region, &rg.stats));
        }
        md.push('\n');
    }
    if !r.asymptotes.is_empty() {
        let _ = writeln!(
            md,
            "## Asymptotes against the solver's limit solves (4097 points)\n"
        );
        let _ = writeln!(md, "| asymptote | fitted law | at | solver H_c | asymptote | ratio | note |\n|---|---|---|---|---|---|---|");
        for a in &r.asymptotes {
            let _ = writeln!(
                md,
                "| {} | {} | M = {}, L = {} ({}) | {} | {:.5} | {} | {} |",
                a.asymptote,
                a.law,
                a.m,
                a.l,
                a.elasticity,
                a.solver_h_c.map_or("failed".into(), |v| format!("{v:.5}")),
                a.fitted,
                a.ratio.map_or("-".into(), |v| format!("{v:.4}")),
                a.note
            );
        }
        md.push('\n');
    }
    for s in &r.skipped {
        let _ = writeln!(md, "Skipped: {s}.");
    }
    md
}
