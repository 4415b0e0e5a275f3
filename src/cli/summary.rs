//! The readable summary of `ehlmap solve`: one line per output, with the status and its reason
//! first and the model and error estimate last.

use ehlmap::model::case::Case;
use ehlmap::model::error::num;
use ehlmap::solve::solution::{ModelUsed, Outputs};

/// The readable summary of a solve, line or point contact.
pub fn summary(case: &Case, o: &Outputs) -> String {
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
    let rows = [
        ("status", format!("{}: {}", o.status, o.reason)),
        (
            "H_c",
            format!("{:.6}   (film at {h_c_at}, Moes units)", o.h_c),
        ),
        (
            "H_c_pmax",
            format!("{:.6}   (film at the pressure maximum)", o.h_c_pmax),
        ),
        ("H_min", format!("{:.6}   at {h_min_at}", o.h_min)),
        ("P_max", format!("{:.6}", o.p_max)),
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
    let mut out = format!(
        "{head}  ({}, {}, {})\n",
        m.elasticity,
        m.viscosity.name(),
        m.density.name()
    );
    for (name, value) in rows {
        out += &format!("{name:<15}{value}\n");
    }
    out + &model_line(o)
}

/// The model and error-estimate line of a summary (accuracy targets only).
fn model_line(o: &Outputs) -> String {
    match o.error_estimate {
        Some(e) => format!(
            "model          {}, level {}, error estimate {e:.1e}\n",
            o.model_used,
            o.level.map_or("-".to_string(), |l| l.to_string())
        ),
        None if o.model_used != ModelUsed::Full => format!("model          {}\n", o.model_used),
        None => String::new(),
    }
}
