//! Markdown rendering of a [`FitReport`]: one section per contact (fitted formula with
//! coefficients and uncertainties, error tables overall / per (M, L) region / per D, the
//! published formulas on the same cases, asymptote checks), or the reason it was skipped.

use crate::fit::correction::{Term, Transition, LATTICE};
use crate::fit::fitted::Blend;
use crate::fit::heldout::{worst_and_rms, SizeScore};
use crate::fit::stats::{ErrStats, RegionStats};
use crate::report::decade::decade_table;
use crate::report::digits::sig5;
use crate::report::forms::{point_form, LINE_FORM};
use crate::report::support::support_table;
use crate::report::{ContactReport, FitReport, QuantityFit, ASYMPTOTE_TARGET, MAX_ERROR_TARGET};
use std::fmt::Write;

fn pct(v: f64) -> String {
    format!("{:+.2} %", 100.0 * v)
}

fn stats_row(name: &str, s: &ErrStats) -> String {
    let at = if s.worst_m.is_nan() {
        String::new()
    } else {
        format!("M = {:.4}, L = {:.3}", s.worst_m, s.worst_l)
    };
    format!(
        "| {name} | {} | {} | {:.2} % | {} | {at} |\n",
        s.n,
        pct(s.max),
        100.0 * s.rms,
        pct(s.mean),
    )
}

fn table(md: &mut String, all: &ErrStats, rows: &[RegionStats]) {
    md.push_str("| region | n | max error | RMS | mean | worst at |\n|---|---|---|---|---|---|\n");
    md.push_str(&stats_row("all", all));
    for rg in rows {
        md.push_str(&stats_row(&rg.region, &rg.stats));
    }
    md.push('\n');
}

/// `v/W - k` with the sign of k folded in ("a/W + 9", "a/W", "a/W - 2").
fn shifted(v: &str, k: impl Into<f64>) -> String {
    let k: f64 = k.into();
    match k {
        k if k > 0.0 => format!("{v}/W - {k}"),
        k if k < 0.0 => format!("{v}/W + {}", -k),
        _ => format!("{v}/W"),
    }
}

fn term_name(t: &Term) -> String {
    let [i, j] = t.at;
    let bump = match t.transition {
        Transition::Isoviscous => "g(a)(1-w)".to_string(),
        Transition::Piezoviscous => "g(b) w".to_string(),
        Transition::Outer => "g(c)".to_string(),
        Transition::Tail => "t(a)(1-w)".to_string(),
        Transition::Shifted => format!("g({})(1-w)", shifted("a", i)),
        Transition::Cell => format!("g({}) g({})", shifted("a", i), shifted("c", j)),
    };
    let vars = ["a", "b", "c", "ln D", "w"];
    let mono: Vec<String> = vars
        .iter()
        .zip(t.powers)
        .filter(|(_, k)| *k > 0)
        .map(|(v, k)| {
            if k == 1 {
                v.to_string()
            } else {
                format!("{v}^{k}")
            }
        })
        .collect();
    if mono.is_empty() {
        bump
    } else {
        format!("{bump} {}", mono.join(" "))
    }
}

/// A candidate in the list of those tried: its number of terms, and its ridge weight if any.
fn short_name(s: &SizeScore) -> String {
    if s.ridge > 0.0 {
        format!(
            "{} (lattice W = {}, ridge {:.0e})",
            s.terms,
            LATTICE * 0.5f64.powi(i32::from(s.level)),
            s.ridge
        )
    } else {
        s.terms.to_string()
    }
}

/// The candidate kept, in words.
pub fn candidate_name(s: &SizeScore) -> String {
    if s.ridge > 0.0 {
        format!(
            "{} lattice terms (W = {}, ridge {:.0e})",
            s.terms,
            LATTICE * 0.5f64.powi(i32::from(s.level)),
            s.ridge
        )
    } else {
        format!("{} correction terms", s.terms)
    }
}

/// How the corner's bumps are taken times powers of ln D, in words ("" for none).
fn d_factors(powers: u8) -> String {
    match powers {
        0 => String::new(),
        1 => ", each also times ln D".to_string(),
        n => format!(", each also times (ln D)^1..{n}"),
    }
}

/// The formula kept for `q`, in words: its corner law ([`crate::fit::corner`]) or the
/// correction candidate `chosen`, and its kriging residual ([`crate::fit::kriging`]) if any.
fn kept_name(q: &QuantityFit, chosen: &SizeScore) -> String {
    let law = match &q.corner {
        Some(c) => format!(
            "its corner law: 2 x {} lattice terms (W = {}{}), ridges {:.0e} / {:.0e}",
            c.terms,
            c.width,
            d_factors(c.ln_d_powers),
            c.ridges[0],
            c.ridges[1]
        ),
        None => candidate_name(chosen),
    };
    match &q.kriging {
        Some(k) => {
            let [sa, sc, sd] = k.scales;
            let scales = match (&q.model.blend, k.jump_scale) {
                (Blend::Line(_), _) => format!("{sa} / {sc} in a / c"),
                (Blend::Point(_), None) => format!("{sa} / {sc} / {sd} in a / c / ln D"),
                (Blend::Point(_), Some(p)) => {
                    format!(
                        "{sa} / {sc} / {sd} / {p} in a / c / ln D / phi (the corner coordinate)"
                    )
                }
            };
            format!(
                "{law} and a kriging residual (Matern 5/2, scales {scales}, nugget {:.0e}; without it held out {:.2} % / {:.2} %)",
                k.nugget,
                100.0 * k.without_max,
                100.0 * k.without_rms
            )
        }
        None => law,
    }
}

fn heldout(md: &mut String, q: &QuantityFit) {
    let c = &q.model.correction;
    match &q.heldout {
        None => {
            let _ = writeln!(md, "Held-out errors: not computed (too few cases, or a fold's fit failed); no correction.\n");
        }
        Some(h) => {
            let base = &h.sizes[0];
            let _ = writeln!(
                md,
                "Held-out errors ({}-fold, each case predicted by a fit that never saw it): with {} max {}, RMS {:.2} % (worst at M = {:.4}, L = {:.3}, D = {}); the blend alone max {}, RMS {:.2} %. Tried (terms: RMS / max): {}.\n",
                h.folds,
                kept_name(q, &h.chosen),
                pct(h.chosen.max),
                100.0 * h.chosen.rms,
                h.chosen.worst.0,
                h.chosen.worst.1,
                h.chosen.worst.2,
                pct(base.max),
                100.0 * base.rms,
                h.sizes
                    .iter()
                    .map(|s| format!("{}: {:.2} / {:.1} %", short_name(s), 100.0 * s.rms, 100.0 * s.max.abs()))
                    .collect::<Vec<_>>()
                    .join(", ")
            );
        }
    }
    if !q.check.is_empty() {
        let errors: Vec<f64> = q.check.iter().map(|c| c.error).collect();
        let (worst, rms) = worst_and_rms(&errors);
        let w = &q.check[worst];
        let estimate = w.estimate.map_or(String::new(), |e| {
            format!(", its own error estimate {:.2} %", 100.0 * e)
        });
        let _ = writeln!(
            md,
            "Check set ({} cases of separate datasets, never fitted): max {}, RMS {:.2} % (worst at \
             M = {:.4}, L = {:.3}, D = {}{estimate}).\n",
            errors.len(),
            pct(errors[worst]),
            100.0 * rms,
            w.m,
            w.l,
            w.d
        );
    }
    if !c.terms.is_empty() {
        let _ = writeln!(md, "| correction term phi_k | c_k |\n|---|---|");
        for (t, k) in c.terms.iter().zip(&c.coef) {
            let _ = writeln!(md, "| {} | {} |", term_name(t), sig5(*k));
        }
        md.push('\n');
        support_table(md, c);
    }
}

/// The side-lobe factor of the point H_min (src/fit/side.rs), when it has one.
fn side_lobe(md: &mut String, q: &QuantityFit) {
    let (Some(s), Some(c)) = (&q.model.side, &q.side) else {
        return;
    };
    // The ramp in D, where the data reach slender contacts without side lobes.
    let (r_d, ramp_d) = s.ramp_d.map_or((String::new(), String::new()), |[a, b]| {
        (
            " r_D(D)".to_string(),
            format!(
                ", r_D(D) = (ln D - {}) / {} clamped to [0, 1] (no side lobe at D <= {})",
                sig5(a),
                sig5(b - a),
                sig5(a.exp())
            ),
        )
    });
    let _ = writeln!(
        md,
        "H_min = (the law above, fitted to the centre line's minimum H_min,cl) x exp(-max(0, g)), \
         g = r(M){r_d} sum c_k t_M^i t_D^j t_L^n, with t_M, t_D, t_L = ln M, ln D, ln(1 + L) mapped \
         onto [-1, 1] over ln M in [{}, {}], ln D in [{}, {}], ln(1 + L) in [{}, {}] and clamped \
         there, r(M) = {}{ramp_d}; the held-out errors above are of H_min (the candidates tried, of \
         H_min,cl). Degrees ({}, {}, {}), ridge {:e}, chosen by held-out error: ln F held out \
         RMS {:.2} %, max {}.\n",
        sig5(s.lo[0]),
        sig5(s.hi[0]),
        sig5(s.lo[1]),
        sig5(s.hi[1]),
        sig5(s.lo[2]),
        sig5(s.hi[2]),
        s.ramp.map_or("1".to_string(), |[a, b]| format!(
            "(ln M - {}) / {} clamped to [0, 1]",
            sig5(a),
            sig5(b - a)
        )),
        c.chosen.degrees[0],
        c.chosen.degrees[1],
        c.chosen.degrees[2],
        c.chosen.ridge,
        100.0 * c.rms,
        pct(c.max)
    );
    if let (Some(k), Some([rms, max])) = (&s.kriging, c.without) {
        let _ = writeln!(
            md,
            "With a kriging residual: g is replaced by max(0, g) - r(M){r_d} k, k the Matern 5/2 kriging of \
             the factor's log residuals over the cases with r(M){r_d} > 0 in (ln M, ln(1 + L), ln D) \
             clamped to the box (scales {} / {} / {}, nugget {:.0e}, {} centres); without it ln F \
             held out RMS {:.2} %, max {:.2} %.\n",
            k.scales[0],
            k.scales[1],
            k.scales[2],
            k.nugget,
            k.centres.len(),
            100.0 * rms,
            100.0 * max
        );
    }
    let _ = writeln!(md, "| (i, j, n) | c_k |\n|---|---|");
    for (p, k) in s.powers.iter().zip(&s.coef) {
        let _ = writeln!(md, "| ({}, {}, {}) | {} |", p[0], p[1], p[2], sig5(*k));
    }
    md.push('\n');
}

/// The corner law of H_c (src/fit/corner.rs), when it has one.
fn corner_law(md: &mut String, q: &QuantityFit) {
    let (Some(law), Some(c)) = (&q.model.corner, &q.corner) else {
        return;
    };
    let _ = writeln!(
        md,
        "H_c through its corner (where the film at X = 0 meets the film at the pressure maximum): \
         H_c = R exp(-rho (max(0, h) / rho)^{}), R = H_c,blend exp(rho r + C_R), h = rho r + C_h, \
         with H_c,blend the blend of this section, rho = ln(H_RI,pm / H_RI,c) at D = 1 = {}, \
         r = (1 - w)/(1 + e^a) + w/(1 + e^-b) in that blend's coordinates (1 in the rigid limits, \
         0 in the elastic ones), and C_R, C_h on the same {} lattice bumps (W = {}{}). C_R is fitted \
         to H_c where it follows H_pm (H_c >= {} H_pm: {} of {} cases) and held from below \
         elsewhere, C_h to the h of the data's deficit elsewhere and held from above where H_c \
         follows H_pm. The H_c asymptotes are the blend's above, exactly. The held-out errors \
         above are of this law (the candidates listed: of the smooth law, whose correction is \
         given here). Ridges (R / h) tried, held-out RMS / max: {}.\n",
        crate::fit::corner::DEFICIT_POWER,
        sig5(law.rho),
        c.terms,
        c.width,
        d_factors(c.ln_d_powers),
        crate::fit::corner::FOLLOWS,
        c.follows[0],
        c.follows[1],
        c.tried
            .iter()
            .map(|(r, rms, max)| format!(
                "{:.0e} / {:.0e}: {:.3} / {:.2} %",
                r[0],
                r[1],
                100.0 * rms,
                100.0 * max.abs()
            ))
            .collect::<Vec<_>>()
            .join(", ")
    );
    for (name, corr) in [("C_R", &law.branch), ("C_h", &law.deficit)] {
        let _ = writeln!(md, "| {name} term phi_k | c_k |\n|---|---|");
        for (t, k) in corr.terms.iter().zip(&corr.coef) {
            let _ = writeln!(md, "| {} | {} |", term_name(t), sig5(*k));
        }
        md.push('\n');
    }
}

fn quantity(md: &mut String, q: &QuantityFit) {
    let _ = writeln!(
        md,
        "### {} (LM converged: {}, RMS of log residuals {:.2e})\n",
        q.quantity, q.converged, q.rms_log
    );
    let _ = writeln!(md, "| parameter | value | 1 sigma |\n|---|---|---|");
    for p in &q.params {
        let _ = writeln!(md, "| {} | {} | {:.1e} |", p.name, sig5(p.value), p.sigma);
    }
    md.push('\n');
    if let Blend::Point(m) = &q.model.blend {
        let [a, p, e] = m.ri_shape.map(sig5);
        let _ = writeln!(
            md,
            "f_RI(D) = [(1 + {a} D^{p})/(1 + {a})]^({e}) / D (held).\n"
        );
        if let Some([a, p, e]) = m.rp_shape.map(|s| s.map(sig5)) {
            let _ = writeln!(
                md,
                "f_RP(D) = f_RI(D) D [(1 + {a} D^{p})/(1 + {a})]^({e}) (held).\n"
            );
        }
    }
    heldout(md, q);
    side_lobe(md, q);
    corner_law(md, q);
    table(md, &q.overall, &q.regions);
    if !q.per_d.is_empty() {
        let _ = writeln!(md, "Per ellipticity:\n");
        table(md, &q.overall, &q.per_d);
    }
}

/// One line per film: its max error against the target and the published formulas on the same
/// film, and how many of its asymptote checks are within their target.
fn summary(md: &mut String, c: &ContactReport) {
    let _ = writeln!(
        md,
        "### Summary
"
    );
    for q in [&c.h_c, &c.h_pm, &c.h_min].into_iter().flatten() {
        let max = q.overall.max.abs();
        let met = if max <= MAX_ERROR_TARGET {
            "met"
        } else {
            "not met"
        };
        let mut line = format!(
            "- {}: max error {:.2} % (target {:.0} %: {met})",
            q.quantity,
            100.0 * max,
            100.0 * MAX_ERROR_TARGET
        );
        if max > MAX_ERROR_TARGET {
            match &q.within_target {
                Some(r) => {
                    let _ = write!(
                        line,
                        ", met for M in [{:.4}, {:.4}] ({} of {} cases)",
                        r.m_lo, r.m_hi, r.n, r.of
                    );
                }
                None => line.push_str(", met at no M of the data"),
            }
        }
        if let Some(h) = &q.heldout {
            let _ = write!(
                line,
                "; held-out max {:.2} %, RMS {:.2} % ({})",
                100.0 * h.chosen.max.abs(),
                100.0 * h.chosen.rms,
                kept_name(q, &h.chosen)
            );
        }
        for p in c.published.iter().filter(|p| p.against == q.quantity) {
            if let Some(all) = &p.overall {
                let cmp = if max < all.max.abs() {
                    "fit better"
                } else {
                    "fit not better"
                };
                let _ = write!(line, "; {} {:.2} % ({cmp})", p.name, 100.0 * all.max.abs());
            }
        }
        let checks: Vec<_> = c
            .asymptotes
            .iter()
            .filter(|a| a.quantity == q.quantity)
            .collect();
        if !checks.is_empty() {
            let within: Vec<&str> = checks
                .iter()
                .filter(|a| a.ratio.is_some_and(|r| (r - 1.0).abs() <= ASYMPTOTE_TARGET))
                .map(|a| a.asymptote.as_str())
                .collect();
            let _ = write!(
                line,
                "; asymptotes within {:.0} % of the limit solves: {} of {}{}",
                100.0 * ASYMPTOTE_TARGET,
                within.len(),
                checks.len(),
                if within.is_empty() {
                    String::new()
                } else {
                    format!(" ({})", within.join(", "))
                }
            );
        }
        let _ = writeln!(md, "{line}.");
    }
    md.push('\n');
}

/// One table of every formula on the same cases: the fit in sample and held out, and each
/// published formula, by film (max |error| / RMS; "-" where a formula has no such film or was
/// skipped).
fn comparison(md: &mut String, c: &ContactReport) {
    let films = [&c.h_c, &c.h_pm, &c.h_min];
    let cell = |max: f64, rms: f64| format!("{:.2} % / {:.2} %", 100.0 * max.abs(), 100.0 * rms);
    let _ = writeln!(
        md,
        "### All formulas on the same cases (max |error| / RMS)\n\n| formula | H_c | H_pm | H_min |\n|---|---|---|---|"
    );
    let row = |name: &str, f: &dyn Fn(&QuantityFit) -> Option<String>| {
        let cells: Vec<String> = films
            .iter()
            .map(|q| q.as_ref().and_then(f).unwrap_or_else(|| "-".to_string()))
            .collect();
        format!("| {name} | {} |\n", cells.join(" | "))
    };
    md.push_str(&row("ehlmap fit", &|q| {
        Some(cell(q.overall.max, q.overall.rms))
    }));
    md.push_str(&row("ehlmap fit, held out", &|q| {
        q.heldout.as_ref().map(|h| cell(h.chosen.max, h.chosen.rms))
    }));
    let mut names: Vec<&str> = c.published.iter().map(|p| p.name.as_str()).collect();
    names.dedup();
    for name in names {
        let why = c
            .published
            .iter()
            .find(|p| p.name == name)
            .and_then(|p| p.skipped.as_deref());
        let label = why.map_or(name.to_string(), |w| format!("{name} ({w})"));
        md.push_str(&row(&label, &|q| {
            c.published
                .iter()
                .find(|p| p.name == name && p.against == q.quantity)
                .and_then(|p| p.overall.as_ref())
                .map(|s| cell(s.max, s.rms))
        }));
    }
    md.push('\n');
}

fn contact(md: &mut String, c: &ContactReport) {
    let _ = writeln!(md, "## {} contact\n", c.contact);
    if let Some(why) = &c.skipped {
        let _ = writeln!(md, "{why} (failed rows: {}).\n", c.failed_cases);
        return;
    }
    let _ = writeln!(
        md,
        "Converged cases fitted: {}; failed rows left out: {}.\n",
        c.converged_cases, c.failed_cases
    );
    let form = if c.contact == "line" {
        LINE_FORM.to_string()
    } else {
        point_form(c)
    };
    let _ = writeln!(md, "{form}\n");
    for why in &c.skipped_films {
        let _ = writeln!(md, "Not fitted: {why}.\n");
    }
    summary(md, c);
    comparison(md, c);
    for q in [&c.h_c, &c.h_pm, &c.h_min].into_iter().flatten() {
        quantity(md, q);
    }
    for p in &c.published {
        let _ = writeln!(md, "### {} on the same cases ({})\n", p.name, p.against);
        match (&p.overall, &p.skipped) {
            (Some(all), _) => table(md, all, &p.regions),
            (None, Some(why)) => {
                let _ = writeln!(md, "{why}.\n");
            }
            (None, None) => {}
        }
    }
    if !c.asymptotes.is_empty() {
        let _ = writeln!(
            md,
            "### Asymptotes against the solver's limit solves (the same film of the solve)\n"
        );
        let _ = writeln!(
            md,
            "| film | asymptote | fitted law | at | solver | asymptote | ratio | ratio toward the limit (M, domain scale, D or L: ratio) | note |\n|---|---|---|---|---|---|---|---|---|"
        );
        for a in &c.asymptotes {
            let d = a.d.map_or(String::new(), |d| format!(", D = {d}"));
            let grid = a.grid.map_or(String::new(), |g| format!(", {g} pts"));
            let trend: Vec<String> = a
                .trend
                .iter()
                .map(|(m, r)| match a.trend_over.as_str() {
                    "M" => format!("{m:.3}: {r:.4}"),
                    over => format!("{over} {m}: {r:.4}"),
                })
                .collect();
            let _ = writeln!(
                md,
                "| {} | {} | {} | M = {}, L = {}{d} ({}{grid}) | {} | {:.5} | {} | {} | {} |",
                a.quantity,
                a.asymptote,
                a.law,
                a.m,
                a.l,
                a.elasticity,
                a.solver.map_or("failed".into(), |v| format!("{v:.5}")),
                a.fitted,
                a.ratio.map_or("-".into(), |v| format!("{v:.4}")),
                trend.join(", ")
                    + &a.beyond.map_or(String::new(), |(l, r)| {
                        let r = r.map_or("solve failed".into(), |r| format!("{r:.4}"));
                        format!("; L = {l} (beyond the data): {r}")
                    }),
                a.note
            );
        }
        md.push('\n');
        decade_table(md, &c.asymptotes);
    }
}

/// Markdown of the report.
pub fn to_markdown(r: &FitReport) -> String {
    let mut md = String::new();
    let _ = writeln!(md, "# ehlmap film-thickness fit\n");
    let _ = writeln!(
        md,
        "Datasets: {}. Duplicate rows dropped: {}. A mixed dataset is fitted per contact.\n",
        r.datasets.join(", "),
        r.duplicate_rows
    );
    for e in &r.excluded {
        let _ = writeln!(md, "Excluded: {e}.");
    }
    for e in &r.one_film {
        let _ = writeln!(md, "Used for one film only: {e}.");
    }
    contact(&mut md, &r.line);
    contact(&mut md, &r.point);
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lattice_shifts_read_with_their_sign() {
        assert_eq!(shifted("a", -9i8), "a/W + 9");
        assert_eq!(shifted("c", 0i8), "c/W");
        assert_eq!(shifted("a", 2i8), "a/W - 2");
    }
}
