//! The readable summary of `ehlmap solve`: one line per output, with the status and its reason
//! first, H_c and H_min with their error bars (`4.485 +- 0.041`, digits to the error's second
//! significant figure), and the model and the accuracy, met or not in words, last.

use ehlmap::model::case::Case;
use ehlmap::model::error::num;
use ehlmap::model::roughness::orientation;
use ehlmap::solve::solution::{with_error, MixedOutputs, ModelUsed, Outputs};

/// The readable summary of a solve, line or point contact (`skipped_estimate`: the half-grid
/// estimate was not asked for).
pub fn summary(case: &Case, o: &Outputs, skipped_estimate: bool) -> String {
    let m = case.models();
    let head = match case {
        Case::Line(c) => format!("line contact  M = {}  L = {}", num(c.m), num(c.l)),
        Case::Point(c) => format!(
            "point contact  M = {}  L = {}  D = {}  (k = {:.6})",
            num(c.m),
            num(c.l),
            num(c.d),
            c.ellipse().k
        ),
    };
    let spike = o.spike.map_or("none".to_string(), |s| {
        format!("P = {:.4} at X = {:.4}", s.p, s.x)
    });
    let (h_c_at, h_min_at, f_name) = match o.y_min {
        Some(y) => (
            "X = Y = 0",
            format!("X = {:.4}, Y = {y:.4}", o.x_min),
            "f Rx/b",
        ),
        None => ("X = 0", format!("X = {:.4}", o.x_min), "f R/b"),
    };
    let grid = match case {
        Case::Point(_) if o.model_used == ModelUsed::SlenderLine => {
            format!("{} points (line solve)", o.grid)
        }
        Case::Point(_) => format!("{} x {} points", o.grid, o.grid),
        Case::Line(_) => format!("{} points", o.grid),
    };
    let formula = o.model_used == ModelUsed::Formula;
    let h_min_at = if formula {
        "(position not given by a formula)".to_string()
    } else {
        h_min_at
    };
    let mut rows = vec![
        ("status", format!("{}: {}", o.status, o.reason)),
        (
            "H_c",
            format!(
                "{}   (film at {h_c_at}, Moes units)",
                with_error(o.h_c, o.h_c_err)
            ),
        ),
        (
            "H_c_pmax",
            format!(
                "{}   (film at the pressure maximum)",
                estimated(o.h_c_pmax, o.h_c_pmax_err)
            ),
        ),
        (
            "H_min",
            format!("{}   at {h_min_at}", with_error(o.h_min, o.h_min_err)),
        ),
        ("P_max", estimated(o.p_max, o.p_max_err)),
        ("spike", spike),
        ("H0", format!("{:.6}", o.h0)),
        (f_name, format!("{:.6e}", o.f)),
        ("load error", format!("{:.2e}", o.load_error)),
        (
            "grid",
            format!(
                "{grid}, {} levels, {:.1} work units, {:.3} s",
                o.levels, o.work_units, o.wall_s
            ),
        ),
    ];
    if let Some(cl) = &o.centre_line {
        rows.insert(
            4,
            (
                "H_min, Y = 0",
                format!(
                    "{}   at X = {:.4} (the centre line's minimum)",
                    estimated(cl.h_min, cl.h_min_err),
                    cl.x_min
                ),
            ),
        );
    }
    let mut out = format!(
        "{head}  ({}, {}, {})\n",
        m.elasticity,
        m.viscosity.name(),
        m.density.name()
    );
    // A formula answer has films only: its other rows would all be NaN.
    let shown = if formula { &rows[..4] } else { &rows[..] };
    for (name, value) in shown {
        out += &format!("{name:<15}{value}\n");
    }
    if formula {
        out += &format!(
            "{:<15}none: answered by a fitted formula, no pressure or grid ({:.1e} s)\n",
            "solve", o.wall_s
        );
    }
    if let Some(x) = &o.mixed {
        out += &mixed_lines(x);
    }
    out + &model_line(o, skipped_estimate)
}

/// The mixed-lubrication lines of a summary: the roughness, the film parameters, the asperity
/// share of the load and the smooth case's films.
fn mixed_lines(x: &MixedOutputs) -> String {
    let orientation = orientation(x.gamma);
    let smooth = match (x.h_c_smooth, x.h_min_smooth) {
        (Some(c), Some(m)) => format!("H_c {c:.6}, H_min {m:.6}"),
        _ => "not converged".to_string(),
    };
    let mut s = format!(
        "{:<15}sigma {} (Moes units), gamma {} ({orientation}), slide-roll {}\n",
        "roughness",
        num(x.sigma),
        num(x.gamma),
        num(x.slide_roll)
    );
    s += &format!(
        "{:<15}Lambda = H_min/sigma {:.3}, H_c/sigma {:.3}\n",
        "film parameter", x.lambda_min, x.lambda_c
    );
    s += &format!(
        "{:<15}{:.3e} of the load (P_a max {:.3e}, {} fixed-point re-solves)\n",
        "asperities", x.asperity_load_fraction, x.p_asperity_max, x.mixed_iterations
    );
    s + &format!("{:<15}{smooth}\n", "smooth film")
}

/// The model and accuracy lines of a summary: which model answered, and whether the accuracy
/// target was met, in words.
fn model_line(o: &Outputs, skipped_estimate: bool) -> String {
    let level = o.level.map_or("-".to_string(), |l| l.to_string());
    let model = format!("model          {}, level {level}\n", o.model_used);
    let errs = match (o.h_c_err, o.h_min_err) {
        (Some(c), Some(m)) => format!(" (H_c {c:.1e}, H_min {m:.1e})"),
        _ => String::new(),
    };
    let accuracy = match (o.error_estimate, o.accuracy_met) {
        (Some(e), Some(true)) => format!("target met: error estimate {e:.1e}{errs}"),
        (Some(e), Some(false)) => {
            format!("target NOT met: error estimate {e:.1e}{errs} (see the status line for why)")
        }
        (Some(e), None) => {
            format!("error estimate {e:.1e}{errs} against the half grid (no target)")
        }
        (None, Some(_)) => "target NOT met: no error estimate (see the status line for why)".into(),
        (None, None) if skipped_estimate => "no error estimate (--no-estimate)".into(),
        (None, None) => "no error estimate (see the status line for why)".into(),
    };
    model + &format!("accuracy       {accuracy}\n")
}

/// `v +- e` where a film or P_max has an estimate `rel` (reported, not targeted), else `v`.
fn estimated(v: f64, rel: Option<f64>) -> String {
    rel.map_or(format!("{v:.6}"), |_| with_error(v, rel))
}
