//! The fit report: for each contact present in the data (line, point) fits three films ([`Film`]:
//! H_c at X = 0, H_pm at the pressure maximum, H_min), compares them and the published formulas
//! with the data, and checks each fitted asymptote against the solver's own limit solves
//! ([`crate::report::checks`]). Markdown rendering is in [`crate::report::markdown`].
//!
//! Why two central films: Moes' H_RI = 3/M is the rigid-isoviscous flux thickness, the film at
//! the pressure maximum; the film at X = 0 tends to 2.4475/M instead. Where the pressure peak
//! moves upstream (line, M < 3 with L > 0) the film at X = 0 is not monotone in M while the film
//! at the pressure maximum is, and the Moes form follows H_pm more closely (figures:
//! docs/validation.md, "Fit: the nightly sweeps"; docs/known-limits.md).
//!
//! Fitting (`staged`): stage 1 frees the asymptote laws from the published start; with
//! [`FULL_FIT_MIN_POINTS`] cases or more, stage 2 also frees the blend and is kept only when it is
//! physical, identified (every sigma finite) and fits better. Each contact's start models, free
//! sets, physical test and candidate corrections are its recipe (the private `recipe` module).
//!
//! Outputs: a [`FitReport`] (serialised as `fit.json`). A contact with fewer converged cases
//! than its model needs (free parameters + [`SPARE_CASES`]) is reported as "skipped: N cases,
//! need at least K"; [`fit_report`] fails only when no contact could be fitted.

pub mod checks;
mod corner;
pub mod decade;
mod digits;
mod forms;
pub mod formula_py;
mod kriging;
mod law;
pub mod markdown;
pub mod mixed;
mod recipe;
mod side_lobes;
mod support;
pub mod surrogate;

use crate::fit::correction::{Coordinates, Correction};
pub use crate::fit::dataset::{FitInput, FitPoint};
use crate::fit::error::FitError;
pub use crate::fit::fitted::{Blend, FittedModel, Param, QuantityFit};
use crate::fit::heldout::{joint_best, select, Refit, Selected};
use crate::fit::lsq::{fit, LsqFit, Sample};
use crate::fit::model::FilmModel;
use crate::fit::side::{SideChoice, SideLobe};
use crate::fit::stats::{d_table, err_stats, region_table, target_range, ErrStats, RegionStats};
use crate::limits::anchors::Anchor;
use crate::limits::jump::JumpTable;
use crate::model::formulas::{
    dowson_toyoda_line_hc_moes, hamrock_dowson_hc_moes, moes_line_hc, nvm_point_hc,
};
use crate::report::checks::{line_checks, point_checks, AsymptoteCheck};
use crate::report::law::{kept, Kept};
use crate::report::recipe::{
    anchor_samples, line_recipe, point_recipe, with_point_ei_limit, Recipe,
};
pub use crate::report::recipe::{
    A_EI_CENTRAL, A_EI_MIN, B_RP_CENTRAL, C_RI_CENTRAL, D_EP_CENTRAL, D_EP_MIN, LINE_RIDGES,
    MIN_CASES, POINT_RIDGES,
};
use crate::report::side_lobes::{composed, side_lobes};
pub use crate::solve::film::Film;
use serde::{Deserialize, Serialize};

/// Datasets with at least this many converged cases of a contact also fit the blending law (and,
/// for point contacts, the elastic M exponents and the H_EP law): low enough for the nightly
/// point sweep's fitted rows (docs/validation.md, "Earlier fit changes").
pub const FULL_FIT_MIN_POINTS: usize = 40;

/// The fit's targets: max error within [`MAX_ERROR_TARGET`] of the data, below the published
/// formulas' on the same film, asymptotes within [`ASYMPTOTE_TARGET`] of the limit solves.
pub const MAX_ERROR_TARGET: f64 = 0.02;
/// Largest relative gap between a fitted asymptote and the solver's limit solve (the target).
pub const ASYMPTOTE_TARGET: f64 = 0.01;

/// Extra cases required beyond the number of free parameters.
pub const SPARE_CASES: usize = 5;

fn h_c_name() -> String {
    Film::Centre.name().to_string()
}

/// A published formula on the same cases, against one film (`against`: H_c or H_pm), or why it
/// was skipped.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Published {
    /// The formula, e.g. "Moes 1992", "NVM 1994", "Dowson-Toyoda 1979", "Hamrock-Dowson 1977".
    pub name: String,
    /// The film it is compared with: "H_c" or "H_pm".
    #[serde(default = "h_c_name")]
    pub against: String,
    /// Relative errors formula/data - 1 over the cases that carry the film (None when skipped).
    pub overall: Option<ErrStats>,
    /// The same errors per region of the (M, L) plane (empty when skipped).
    pub regions: Vec<RegionStats>,
    /// Why the formula was not compared (e.g. it needs G and the dataset has none); None when
    /// compared.
    pub skipped: Option<String>,
}

/// The report of one contact.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ContactReport {
    /// "line" or "point".
    pub contact: String,
    /// Converged valid cases of this contact read for the fit.
    pub converged_cases: usize,
    /// Rows of this contact that failed ([`FitInput::failed_line`], [`FitInput::failed_point`]).
    pub failed_cases: usize,
    /// Why this contact was not fitted (None when fitted).
    pub skipped: Option<String>,
    /// The fit of the film at X = 0 (None when the contact or the film was skipped).
    pub h_c: Option<QuantityFit>,
    /// The film at the pressure maximum (None when the dataset does not carry it).
    #[serde(default)]
    pub h_pm: Option<QuantityFit>,
    /// The fit of the minimum film (None when the contact or the film was skipped).
    pub h_min: Option<QuantityFit>,
    /// Films not fitted because too few cases carry them (H_pm of older datasets).
    #[serde(default)]
    pub skipped_films: Vec<String>,
    /// The model families of the cases fitted ([`FitInput::line_families`]): a formula answers
    /// cases of its one family only.
    #[serde(default)]
    pub families: Vec<String>,
    /// The contact's published formulas on the same cases (line: Moes 1992, Dowson-Toyoda 1979;
    /// point: NVM 1994, Hamrock-Dowson 1977).
    pub published: Vec<Published>,
    /// Each fitted film's asymptotes against the solver's limit solves (empty when the limit
    /// solves were not run).
    pub asymptotes: Vec<AsymptoteCheck>,
}

/// Everything the report shows; `fit.json` is this, serialised ({"line": .., "point": ..}).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FitReport {
    /// The dataset directories read.
    pub datasets: Vec<String>,
    /// Rows left out as duplicates of a case id already read.
    pub duplicate_rows: usize,
    /// Rows left out, each with the reason (a Richardson or domain-truncation error estimate
    /// above [`MAX_ERROR_ESTIMATE`]).
    ///
    /// [`MAX_ERROR_ESTIMATE`]: crate::fit::dataset::MAX_ERROR_ESTIMATE
    pub excluded: Vec<String>,
    /// Rows used for one film only, with the reason.
    #[serde(default)]
    pub one_film: Vec<String>,
    /// The line-contact report (skipped when the data have too few line cases).
    pub line: ContactReport,
    /// The point-contact report (skipped when the data have too few point cases).
    pub point: ContactReport,
}

/// The samples of `film`: the cases that carry it.
fn samples(pts: &[FitPoint], film: Film) -> Vec<Sample> {
    pts.iter()
        .filter_map(|p| {
            p.film(film).map(|h| Sample {
                m: p.m,
                l: p.l,
                d: p.dd(),
                h,
            })
        })
        .collect()
}

/// [`stages`] from `start` as `r.pre` sets it from `data`. When `r.pre` would set the fitted
/// blend's held parameters differently (the point approach factor depends on the blend's r and
/// c_00), the stages run once more from the fitted blend with them set again.
fn staged<Mo: FilmModel>(
    data: &[Sample],
    start: &Mo,
    r: &Recipe<Mo>,
) -> Result<LsqFit<Mo>, FitError> {
    let anchors: Vec<Sample> = r.anchors.iter().map(|a| a.1).collect();
    let f = stages(data, &(r.pre)(start, data, &anchors), r)?;
    let again = (r.pre)(&f.model, data, &anchors);
    if again.x() == f.model.x() {
        return Ok(f);
    }
    Ok(stages(data, &again, r).unwrap_or(f))
}

/// Fit the `r.stage1` parameters from `start`; with at least [`FULL_FIT_MIN_POINTS`] samples
/// refit all of `r.stage2` from there and keep it when it stays physical, identified (every sigma
/// finite: J^T J not singular) and fits better (lower RMS log error). If it does not, try again
/// with the `r.late` parameters held at their start; the first kept try wins, else stage 1.
/// (Every rigid-piezoviscous law is held at the solver's limit, so none can run off when the
/// data hardly see it: docs/validation.md, "Earlier fit changes".)
fn stages<Mo: FilmModel>(
    data: &[Sample],
    start: &Mo,
    r: &Recipe<Mo>,
) -> Result<LsqFit<Mo>, FitError> {
    let mut f = fit(data, start, &r.stage1)?;
    if data.len() < FULL_FIT_MIN_POINTS || r.stage2.len() <= r.stage1.len() {
        return Ok(f);
    }
    let without = |out: &[usize]| -> Vec<usize> {
        r.stage2
            .iter()
            .copied()
            .filter(|k| !out.contains(k))
            .collect()
    };
    let mut tries = vec![r.stage2.clone()];
    if !r.late.is_empty() {
        tries.push(without(r.late));
    }
    for free in &tries {
        if let Ok(g) = fit(data, &f.model, free) {
            let identified = g.sigma.iter().all(|s| s.is_finite());
            if (r.physical)(&g.model) && identified && g.rms_log < f.rms_log {
                f = g;
                break;
            }
        }
    }
    Ok(f)
}

/// The fit of `film`: the blend `f` with its `correction`, the law kept on top of them with its
/// held-out errors (`law`), and for the point H_min through the centre line its side factor.
fn quantity<Mo: FilmModel>(
    film: Film,
    pts: &[FitPoint],
    f: LsqFit<Mo>,
    correction: Correction,
    law: Kept,
    side: Option<(SideLobe, SideChoice)>,
    r: &Recipe<Mo>,
) -> QuantityFit {
    let (names, wrap) = (r.names, r.wrap);
    let (lobe, choice) = side.unzip();
    let (corner, corner_choice) = law.corner.unzip();
    let (kriging, kriging_choice) = law.kriging.unzip();
    let model = FittedModel {
        blend: wrap(f.model.clone()),
        correction,
        side: lobe,
        corner,
        kriging,
    };
    let data: Vec<_> = pts
        .iter()
        .filter_map(|p| p.film(film).map(|h| (p, h)))
        .collect();
    let tuples: Vec<_> = data
        .iter()
        .map(|(p, h)| (p.m, p.l, model.eval(p.m, p.l, p.dd()), *h))
        .collect();
    let dts: Vec<_> = data
        .iter()
        .filter_map(|(p, h)| p.d.map(|d| (d, model.eval(p.m, p.l, d), *h)))
        .collect();
    QuantityFit {
        quantity: film.name().to_string(),
        params: names
            .iter()
            .zip(f.model.x().iter().zip(&f.sigma))
            .map(|(n, (v, s))| Param {
                name: n.to_string(),
                value: *v,
                sigma: *s,
            })
            .collect(),
        model,
        // Of the formula as fitted (blend, correction and any side-lobe factor), over the cases
        // that carry the film.
        rms_log: (tuples.iter().map(|t| (t.2 / t.3).ln().powi(2)).sum::<f64>()
            / tuples.len() as f64)
            .sqrt(),
        converged: f.converged,
        overall: err_stats(&tuples).expect("non-empty data"),
        regions: region_table(&tuples),
        per_d: d_table(&dts),
        within_target: target_range(&tuples, MAX_ERROR_TARGET),
        heldout: law.heldout,
        check: vec![],
        side: choice,
        corner: corner_choice,
        kriging: kriging_choice,
    }
}

/// A published formula against H_c and, when the data carry it, H_pm.
fn published(name: &str, pts: &[FitPoint], f: impl Fn(&FitPoint) -> f64) -> Vec<Published> {
    [Film::Centre, Film::PressureMax]
        .into_iter()
        .filter(|film| pts.iter().any(|p| p.film(*film).is_some()))
        .map(|film| {
            let t: Vec<_> = pts
                .iter()
                .filter_map(|p| p.film(film).map(|h| (p.m, p.l, f(p), h)))
                .collect();
            Published {
                name: name.to_string(),
                against: film.name().to_string(),
                overall: err_stats(&t),
                regions: region_table(&t),
                skipped: None,
            }
        })
        .collect()
}

fn needs_g(name: &str, pts: &[FitPoint], f: impl Fn(&FitPoint, f64) -> f64) -> Vec<Published> {
    if pts.iter().all(|p| p.g.is_some()) {
        published(name, pts, |p| f(p, p.g.expect("checked")))
    } else {
        vec![Published {
            name: name.to_string(),
            against: Film::Centre.name().to_string(),
            overall: None,
            regions: vec![],
            skipped: Some("skipped: dataset has no G".to_string()),
        }]
    }
}

fn skipped(contact: &str, n: usize, failed: usize, need: usize) -> ContactReport {
    ContactReport {
        contact: contact.to_string(),
        converged_cases: n,
        failed_cases: failed,
        skipped: Some(format!("skipped: {n} cases, need at least {need}")),
        ..ContactReport::default()
    }
}

/// The interior correction of the blend fitted in `f`: its size chosen by held-out error
/// ([`crate::fit::heldout`], the blend refitted per fold by [`staged`]), then blend and
/// correction fitted together on all of `data` ([`joint_best`], the parameters of the last stage
/// freed, from `f`'s blend and from each fold's): `f` takes the refitted blend and its sigmas.
/// Returns the correction and, when the cross-validation could be made, the selection (held-out
/// errors, each fold's blend and each fold's fitted formula); no correction when it could not.
fn corrected<Mo: FilmModel>(
    data: &[Sample],
    f: &mut LsqFit<Mo>,
    start: &Mo,
    r: &Recipe<Mo>,
) -> (Correction, Option<Selected<Mo>>) {
    let z: Vec<Coordinates> = data
        .iter()
        .map(|s| Coordinates::new(f.model.asymptotes(s.m, s.l, s.d), s.d))
        .collect();
    let bases = (r.bases)(&z, r.fades);
    let fit_blend = |train: &[Sample]| staged(train, start, r).ok().map(|f| f.model);
    let free = if data.len() >= FULL_FIT_MIN_POINTS {
        &r.stage2
    } else {
        &r.stage1
    };
    let refit = Refit {
        free,
        physical: &r.physical,
    };
    let Some(sel) = select(data, &bases, &fit_blend, &refit) else {
        return (Correction::default(), None);
    };
    let starts: Vec<&Mo> = std::iter::once(&f.model).chain(&sel.blends).collect();
    match joint_best(data, &starts, &bases[sel.heldout.chosen.candidate], &refit) {
        Some((b, c, sigma)) => {
            f.model = b;
            if let Some(sigma) = sigma {
                f.sigma = sigma;
            }
            (c, Some(sel))
        }
        None => (Correction::default(), Some(sel)),
    }
}

/// Fit each film the data carry (a film with fewer cases than the contact needs is left out and
/// named in `skipped_films`); returns the report without checks and published formulas, and the
/// fitted models for the checks.
fn fit_films<Mo: FilmModel>(
    r: &Recipe<Mo>,
    pts: &[FitPoint],
    failed: usize,
) -> Result<(ContactReport, Vec<(Film, Mo)>), FitError> {
    let need = (r.stage1.len() + SPARE_CASES).max(MIN_CASES);
    let mut report = ContactReport {
        contact: r.contact.to_string(),
        converged_cases: pts.len(),
        failed_cases: failed,
        ..ContactReport::default()
    };
    let mut models: Vec<(Film, Mo)> = vec![];
    // The H_pm correction, with its blend in `models`: the H_c corner law judges by it the cases
    // whose H_pm is not resolved.
    let mut pm_correction: Option<Correction> = None;
    // With a corner law H_c is fitted after H_pm, whose rigid law sets its rho.
    let order = if r.corner.is_some() {
        [Film::PressureMax, Film::Centre, Film::Minimum]
    } else {
        Film::ALL
    };
    for film in order {
        // The point H_min through the centre line: when the data carry it with side lobes and
        // the side-lobe factor can be cross-validated (else H_min is fitted directly).
        let side = (r.side_lobes && film == Film::Minimum)
            .then(|| side_lobes(pts, need))
            .flatten();
        let data = match &side {
            Some(s) => s.centre_line.clone(),
            None => samples(pts, film),
        };
        if data.len() < need {
            report.skipped_films.push(format!(
                "{}: {} of {} cases carry it, need at least {need}",
                film.name(),
                data.len(),
                pts.len()
            ));
            continue;
        }
        let start = (r.start)(film);
        let r = &r.for_film(film);
        let mut f = staged(&data, &start, r).map_err(|e| FitError::Film {
            contact: r.contact.to_string(),
            film: film.name(),
            source: Box::new(e),
        })?;
        let (correction, cv) = corrected(&data, &mut f, &start, r);
        let pm = models
            .iter()
            .find(|(g, _)| *g == Film::PressureMax)
            .map(|(_, m)| m)
            .zip(pm_correction.as_ref());
        let mut law = kept(film, pts, &data, (&f.model, &correction), cv, pm, r);
        if film == Film::PressureMax {
            pm_correction = Some(correction.clone());
        }
        let estimates: Vec<Option<f64>> = pts
            .iter()
            .filter(|p| p.film(film).is_some())
            .map(|p| p.estimate(film))
            .collect();
        let heldout = law.heldout.take();
        let side = match side {
            Some(s) => {
                law.heldout = composed(&s, heldout, pts);
                Some((s.lobe, s.choice))
            }
            None => {
                law.heldout = heldout.map(|h| h.with_estimates(&estimates));
                None
            }
        };
        models.push((film, f.model.clone()));
        let q = Some(quantity(film, pts, f, correction, law, side, r));
        match film {
            Film::Centre => report.h_c = q,
            Film::PressureMax => report.h_pm = q,
            Film::Minimum => report.h_min = q,
        }
    }
    models.sort_by_key(|(f, _)| Film::ALL.iter().position(|g| g == f));
    Ok((report, models))
}

fn line_report(
    pts: &[FitPoint],
    failed: usize,
    limit_solves: bool,
) -> Result<ContactReport, FitError> {
    let recipe = line_recipe();
    let need = (recipe.stage1.len() + SPARE_CASES).max(MIN_CASES);
    if pts.len() < need {
        return Ok(skipped("line", pts.len(), failed, need));
    }
    let (mut report, models) = fit_films(&recipe, pts, failed)?;
    if limit_solves {
        report.asymptotes = line_checks(&models, pts);
    }
    report.published = published("Moes 1992", pts, |p| moes_line_hc(p.m, p.l));
    report
        .published
        .extend(needs_g("Dowson-Toyoda 1979", pts, |p, g| {
            dowson_toyoda_line_hc_moes(p.m, p.l, g)
        }));
    Ok(report)
}

fn point_report(
    pts: &[FitPoint],
    failed: usize,
    limit_solves: bool,
    jump: Option<&JumpTable>,
    anchors: &[Anchor],
    ei_limit: bool,
) -> Result<ContactReport, FitError> {
    let mut recipe = point_recipe(pts);
    // Anchors pin the approach factor of every held EI law: with them H_c's is held too.
    if ei_limit || !anchors.is_empty() {
        recipe = with_point_ei_limit(recipe);
    }
    recipe.jump = jump.cloned();
    recipe.anchors = anchor_samples(anchors);
    let need = (recipe.stage1.len() + SPARE_CASES).max(MIN_CASES);
    if pts.len() < need {
        return Ok(skipped("point", pts.len(), failed, need));
    }
    let (mut report, models) = fit_films(&recipe, pts, failed)?;
    if limit_solves {
        let side = report.h_min.as_ref().and_then(|q| q.model.side.clone());
        report.asymptotes = point_checks(&models, side.as_ref(), pts);
        // The checks a decade beyond the data compare the solver with the whole formula.
        for a in &mut report.asymptotes {
            let fit = [&report.h_c, &report.h_pm, &report.h_min]
                .into_iter()
                .flatten()
                .find(|q| q.quantity == a.quantity);
            a.decade = a.decade.take().map(|b| match fit {
                Some(q) => {
                    let h = q.model.eval(b.m, 0.0, b.d);
                    b.with_formula(h)
                }
                None => b,
            });
        }
    }
    report.published = published("NVM 1994", pts, |p| nvm_point_hc(p.m, p.l, p.dd()));
    report
        .published
        .extend(needs_g("Hamrock-Dowson 1977", pts, |p, g| {
            hamrock_dowson_hc_moes(p.m, p.l, g, p.dd())
        }));
    Ok(report)
}

/// Each fitted film's errors on the check cases that carry it ([`QuantityFit::check`]).
fn add_checks(r: &mut ContactReport, checks: &[FitPoint]) {
    for (film, q) in [
        (Film::Centre, &mut r.h_c),
        (Film::PressureMax, &mut r.h_pm),
        (Film::Minimum, &mut r.h_min),
    ] {
        if let Some(q) = q {
            q.check = q.model.errors_on(checks, film);
        }
    }
}

/// Fit, compare and check each contact present. `limit_solves` runs the solver's limit cases.
/// Errors: no converged case at all, or no contact with enough cases (the message names each).
pub fn fit_report(input: &FitInput, limit_solves: bool) -> Result<FitReport, FitError> {
    if input.line.is_empty() && input.point.is_empty() {
        return Err(FitError::NoCases {
            datasets: input.datasets.join(", "),
            failed: input.failed_line + input.failed_point,
            excluded: input.excluded.len(),
        });
    }
    let mut line = line_report(&input.line, input.failed_line, limit_solves)?;
    let mut point = point_report(
        &input.point,
        input.failed_point,
        limit_solves,
        input.jump.as_ref(),
        &input.anchors,
        input.point_ei_limit,
    )?;
    line.families = input.line_families.clone();
    point.families = input.point_families.clone();
    add_checks(&mut line, &input.check_line);
    add_checks(&mut point, &input.check_point);
    if line.h_c.is_none() && point.h_c.is_none() {
        let why = |c: &ContactReport| c.skipped.clone().unwrap_or_default();
        return Err(FitError::TooFewCases {
            line: why(&line),
            point: why(&point),
        });
    }
    Ok(FitReport {
        datasets: input.datasets.clone(),
        duplicate_rows: input.duplicates,
        excluded: input.excluded.clone(),
        one_film: input.one_film.clone(),
        line,
        point,
    })
}
