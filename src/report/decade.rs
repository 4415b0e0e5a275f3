//! The Markdown of the point elastic-isoviscous checks a decade of M beyond the data
//! ([`crate::limits::beyond`]): per film, the solver's film on each grid, its Richardson
//! extrapolation with the observed order and error bar, the whole formula there and their ratio,
//! judged against issue 24's 0.5 %.

use crate::report::checks::AsymptoteCheck;
use std::fmt::Write;

/// The bound a decade beyond the data (issue 24).
pub const DECADE_BOUND: f64 = 0.005;

/// The table of the rows that carry a decade-beyond check; nothing when none does.
pub fn decade_table(md: &mut String, rows: &[AsymptoteCheck]) {
    let rows: Vec<_> = rows
        .iter()
        .filter_map(|a| a.decade.as_ref().map(|b| (a, b)))
        .collect();
    let Some((_, first)) = rows.first() else {
        return;
    };
    let grids: Vec<String> = first.grids.iter().map(|g| format!("{g}^2")).collect();
    let _ = writeln!(
        md,
        "A decade beyond the data: the elastic-isoviscous case M = {}, L = 0, D = {} (ten times the \
         largest M of the data's L = 0 cases) solved on {} and extrapolated to zero spacing \
         (Richardson, the observed order; p = 2 where the grids show none), against the whole \
         formula there (bound {} %):\n",
        first.m,
        first.d,
        grids.join(", "),
        100.0 * DECADE_BOUND
    );
    let _ = writeln!(
        md,
        "| film | solver per grid | extrapolated | order | formula | solver / formula | within |\n|---|---|---|---|---|---|---|"
    );
    for (a, b) in rows {
        let films: Vec<String> = b
            .films
            .iter()
            .map(|f| f.map_or("failed".into(), |v| format!("{v:.5}")))
            .collect();
        let solver = match (b.solver, b.error_bar) {
            (Some(v), Some(e)) => format!("{v:.5} +- {e:.5}"),
            _ => "-".into(),
        };
        let within = match (b.ratio, b.error_bar.zip(b.solver)) {
            (Some(r), Some((e, v))) => {
                let yes = (r - 1.0).abs() <= DECADE_BOUND;
                format!(
                    "{} (bar {:.2} %)",
                    if yes { "yes" } else { "no" },
                    100.0 * e / v
                )
            }
            _ => "-".into(),
        };
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {} |",
            a.quantity,
            films.join(", "),
            solver,
            b.order.map_or("- (2 taken)".into(), |p| format!("{p:.2}")),
            b.formula.map_or("-".into(), |h| format!("{h:.5}")),
            b.ratio.map_or("-".into(), |r| format!("{r:.4}")),
            within
        );
    }
    md.push('\n');
}
