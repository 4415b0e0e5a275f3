//! The fit report's formulas as a candidate model: [`FittedFormula`] implements
//! [`FilmFormula`] ([`crate::strategy::formula`]) from a [`FitReport`] (`fit.json`).
//!
//! Contract. A contact is usable when its three films (H_c, H_pm, H_min) were fitted with
//! held-out errors and its data are of one model family ([`ContactReport::families`]); a case is
//! answered when its models are that family and it lies inside the data: on each axis of the
//! data lattice (M, L, and D for point contacts) between two data values. The **held-out map**
//! at the case is, per film (H_c, H_min), the largest |relative error| of
//! - the formula at the corners of the data cell around it (2, 4 or 8 cases; one when the case
//!   is a data case), each predicted by a fit that did not see it (k-fold held-out errors);
//! - the formula at the check cases inside that cell ([`QuantityFit::check`]: separate datasets,
//!   never fitted; strictly between the corners on each axis where the case is between data
//!   values, and on an axis where the case is on a data value v, on v or in the cells on both
//!   sides of it, so that the answer does not jump at v). A case strictly
//!   inside a cell needs at least one: the folds leave the neighbours of a held-out case in the
//!   fit, so corner errors alone miss what the formula does between the data (nightly line data
//!   at L = 0 and 4 only: H_min 3 % off at L = 2, where the corners' held-out errors were
//!   0.3 %);
//! - the formula at the case against the data interpolated to it (ln H multilinear in (ln M, L,
//!   ln D) over the corners): large where the formula does between the data what neither the
//!   data nor a check case shows (smoke data at L = 0 and 2: H_c 12 % off at L = 0.5, with the
//!   check case at L = 1 within 2 %).
//!
//! Only cases of the default models (elastic, Barus, incompressible, smooth) are answered, from
//! data of that family: Roelands and Dowson-Higginson have parameters that the family name
//! omits. H_pm is given without a bound (as from a solve, the target is on H_c and H_min).
//! Each film's bound is [`MAP_SAFETY`] times its map plus the largest data error estimate of
//! those cases (the factor measured on points between the data and check cases:
//! docs/validation.md, "The formula as a model"). A corner missing from the map (a case that
//! failed or was left out) declines the case, as do a missing estimate, film or check case and a
//! family or position outside the data; the error says which.

use crate::fit::fitted::FittedModel;
use crate::fit::heldout::CaseError;
use crate::model::case::{Case, Models};
use crate::report::{ContactReport, FitReport, QuantityFit};
use crate::strategy::formula::{FilmFormula, FormulaFilms};
use std::collections::BTreeMap;

/// The bound of a film is this times its held-out map plus the data's estimate. Measured on
/// points between the data and check cases (the quarter points of the nightly cells, neither
/// data nor check cases; docs/validation.md): the true error reached 0.82 of the bound on 416
/// line cases and 0.74 on 128 point cases; without the interpolant term of the map, the map plus
/// the estimate alone was exceeded 1.9-fold.
pub const MAP_SAFETY: f64 = 2.0;

/// Relative tolerance when placing a case on a data axis value.
const ON_AXIS: f64 = 1e-9;

/// One film's formula and its held-out map.
#[derive(Clone, Debug)]
struct FilmMap {
    model: FittedModel,
    /// (held-out error, data estimate, data film) by the case's (M, L, D) bits.
    cases: BTreeMap<[u64; 3], (f64, Option<f64>, Option<f64>)>,
    /// The check cases.
    checks: Vec<CaseError>,
}

impl FilmMap {
    fn new(q: &QuantityFit) -> Option<FilmMap> {
        let h = q.heldout.as_ref().filter(|h| !h.cases.is_empty())?;
        let key = |c: &CaseError| [c.m.to_bits(), c.l.to_bits(), c.d.to_bits()];
        Some(FilmMap {
            model: q.model.clone(),
            cases: h
                .cases
                .iter()
                .map(|c| (key(c), (c.error, c.estimate, c.h)))
                .collect(),
            checks: q.check.clone(),
        })
    }

    /// (largest |error|, largest data estimate, check cases used) at `q` in `cell`: the corners'
    /// held-out errors, the errors of the check cases in the cell ([`Cell::checks`]) and the
    /// formula's departure from the corners' data interpolated to `q`; or why there is none: a
    /// corner without a held-out error, estimate or film, a check case without an estimate, no
    /// check case in a cell of more than one corner, or a term that is not finite.
    fn at(&self, q: [f64; 3], cell: &Cell, point: bool) -> Result<(f64, f64, usize), String> {
        let (mut err, mut est) = (0.0f64, 0.0f64);
        // ln H of the data, interpolated multilinearly in (ln M, L, ln D) over the corners.
        let mut ln_h = 0.0;
        for c in &cell.corners {
            let key = [c[0].to_bits(), c[1].to_bits(), c[2].to_bits()];
            let Some((e, Some(s), Some(h))) = self.cases.get(&key) else {
                return Err(format!(
                    "no held-out error, data estimate or data film at {} (a case that failed \
                     or was left out)",
                    place(*c, point)
                ));
            };
            err = err.max(e.abs());
            est = est.max(*s);
            ln_h += cell.weight(q, *c) * h.ln();
        }
        let mut checked = 0;
        for c in self.checks.iter().filter(|c| cell.checks([c.m, c.l, c.d])) {
            let Some(s) = c.estimate else {
                return Err(format!(
                    "no data estimate at the check case {}",
                    place([c.m, c.l, c.d], point)
                ));
            };
            err = err.max(c.error.abs());
            est = est.max(s);
            checked += 1;
        }
        // The formula's departure from the data's interpolant: large where the formula does
        // something between the data that neither the data nor the check cases show.
        let formula = self.model.eval(q[0], q[1], q[2]);
        let departure = (formula.ln() - ln_h).exp_m1().abs();
        if !(departure.is_finite() && err.is_finite() && est.is_finite()) {
            return Err(format!(
                "no finite error map: formula {formula}, departure {departure}, held-out {err}, \
                 estimate {est}"
            ));
        }
        err = err.max(departure);
        if cell.corners.len() > 1 && checked == 0 {
            let sets = if point {
                "sweeps/nightly-point-mid.toml and -cells.toml"
            } else {
                "sweeps/nightly-line-mid.toml and -cells.toml"
            };
            return Err(format!(
                "no check case between {} (fit with --check on datasets of the cells' \
                 midpoints and centres, e.g. {sets})",
                cell.describe(point)
            ));
        }
        Ok((err, est, checked))
    }
}

/// The data cell around a case: its corners, and where the check cases that count for it lie.
#[derive(Clone, Debug, PartialEq)]
struct Cell {
    /// Per axis, the data values bracketing the case (lo, hi), equal when it is on one.
    span: [(f64, f64); 3],
    /// The corners: every combination of the span's values.
    corners: Vec<[f64; 3]>,
    /// Per axis, the open interval a check case must lie in (tolerance [`ON_AXIS`]), and the
    /// axis value a check case may also equal: strictly between the two bracketing values; on
    /// an axis value v, between its neighbours (the cells on both sides), or on v itself.
    boxes: [(f64, f64, Option<f64>); 3],
}

impl Cell {
    /// Whether a check case at `x` counts for this cell.
    fn checks(&self, x: [f64; 3]) -> bool {
        x.iter().zip(&self.boxes).all(|(x, (a, b, on))| {
            let tol = |v: f64| ON_AXIS * v.abs().max(1e-300);
            let between = *x > a + tol(*a) && *x < b - tol(*b);
            between || on.is_some_and(|v| (x - v).abs() <= tol(v))
        })
    }

    /// The multilinear weight of `corner` at `q` in (ln M, L, ln D).
    fn weight(&self, q: [f64; 3], corner: [f64; 3]) -> f64 {
        let scale = [f64::ln, |x: f64| x, f64::ln];
        (0..3)
            .map(|k| {
                let (lo, hi) = self.span[k];
                if lo == hi {
                    return 1.0;
                }
                let t = (scale[k](q[k]) - scale[k](lo)) / (scale[k](hi) - scale[k](lo));
                if corner[k] == lo {
                    1.0 - t
                } else {
                    t
                }
            })
            .product()
    }

    /// "the 4 data cases around it (M 19.3-51.8, L 5-10, D 1)".
    fn describe(&self, point: bool) -> String {
        let range = |k: usize| match self.span[k] {
            (lo, hi) if lo == hi => sig3(lo),
            (lo, hi) => format!("{}-{}", sig3(lo), sig3(hi)),
        };
        let d = if point {
            format!(", D {}", range(2))
        } else {
            String::new()
        };
        let n = self.corners.len();
        let cases = if n == 1 { "case" } else { "cases" };
        format!(
            "the {n} data {cases} around it (M {}, L {}{d})",
            range(0),
            range(1)
        )
    }
}

/// One contact's films, family and data lattice.
#[derive(Clone, Debug)]
struct ContactFormula {
    family: String,
    /// H_c, H_pm, H_min.
    films: [FilmMap; 3],
    /// The distinct data values of M, L and D, sorted.
    axes: [Vec<f64>; 3],
}

impl ContactFormula {
    fn new(r: &ContactReport) -> Result<ContactFormula, String> {
        let film = |q: &Option<QuantityFit>, name: &str| {
            q.as_ref()
                .and_then(FilmMap::new)
                .ok_or_else(|| format!("no {name} formula with held-out errors"))
        };
        let films = [
            film(&r.h_c, "H_c")?,
            film(&r.h_pm, "H_pm")?,
            film(&r.h_min, "H_min")?,
        ];
        let family = match r.families.as_slice() {
            [f] => f.clone(),
            [] => return Err("the data's model family is not recorded".into()),
            many => return Err(format!("the data mix model families ({})", many.join(", "))),
        };
        let mut axes: [Vec<f64>; 3] = Default::default();
        for key in films[0].cases.keys() {
            for (axis, bits) in axes.iter_mut().zip(key) {
                axis.push(f64::from_bits(*bits));
            }
        }
        for a in &mut axes {
            a.sort_by(f64::total_cmp);
            a.dedup();
        }
        Ok(ContactFormula {
            family,
            films,
            axes,
        })
    }

    /// The data cell around `q` ([`Cell`]), or why the case lies outside the data.
    fn cell(&self, q: [f64; 3]) -> Result<Cell, String> {
        let names = ["M", "L", "D"];
        let mut span = [(0.0, 0.0); 3];
        let mut boxes = [(0.0, 0.0, None); 3];
        for (k, ((axis, x), name)) in self.axes.iter().zip(q).zip(names).enumerate() {
            let (lo, hi) = (axis[0], axis[axis.len() - 1]);
            if !x.is_finite() {
                return Err(format!("{name} = {x} is not a number"));
            }
            let near = |v: f64| (x - v).abs() <= ON_AXIS * v.abs().max(1e-300);
            if let Some(i) = axis.iter().position(|v| near(*v)) {
                let v = axis[i];
                span[k] = (v, v);
                let prev = if i > 0 { axis[i - 1] } else { v };
                let next = axis.get(i + 1).copied().unwrap_or(v);
                boxes[k] = (prev, next, Some(v));
            } else if x < lo || x > hi {
                return Err(format!("{name} = {x} outside the data ({lo} to {hi})"));
            } else {
                let i = axis.partition_point(|v| *v < x);
                span[k] = (axis[i - 1], axis[i]);
                boxes[k] = (axis[i - 1], axis[i], None);
            }
        }
        // Each axis contributes its one value, or both bracketing values.
        let values = |(lo, hi): (f64, f64)| if lo == hi { vec![lo] } else { vec![lo, hi] };
        let mut corners = vec![];
        for m in values(span[0]) {
            for l in values(span[1]) {
                for d in values(span[2]) {
                    corners.push([m, l, d]);
                }
            }
        }
        Ok(Cell {
            span,
            corners,
            boxes,
        })
    }
}

/// The formulas of a fit report with their held-out maps (see the module docs).
#[derive(Clone, Debug)]
pub struct FittedFormula {
    source: String,
    line: Result<ContactFormula, String>,
    point: Result<ContactFormula, String>,
}

impl FittedFormula {
    /// The formulas of `report` (read from `source`, named in every answer's reason); an error
    /// when neither contact is usable, saying why.
    pub fn from_report(report: &FitReport, source: &str) -> Result<FittedFormula, String> {
        let f = FittedFormula {
            source: source.to_string(),
            line: ContactFormula::new(&report.line),
            point: ContactFormula::new(&report.point),
        };
        match (&f.line, &f.point) {
            (Err(l), Err(p)) => Err(format!(
                "{source}: no usable formula: line: {l}; point: {p}"
            )),
            _ => Ok(f),
        }
    }
}

/// "M = .., L = .." (and ", D = .." for a point contact).
fn place(q: [f64; 3], point: bool) -> String {
    let d = if point {
        format!(", D = {}", q[2])
    } else {
        String::new()
    };
    format!("M = {}, L = {}{d}", q[0], q[1])
}

/// Three significant figures.
fn sig3(v: f64) -> String {
    format!("{}", format!("{v:.2e}").parse::<f64>().unwrap_or(v))
}

impl FilmFormula for FittedFormula {
    fn films(&self, case: &Case) -> Result<FormulaFilms, String> {
        let (c, d, point) = match case {
            Case::Line(_) => (&self.line, 1.0, false),
            Case::Point(p) => (&self.point, p.d, true),
        };
        let c = c
            .as_ref()
            .map_err(|e| format!("{} contact: {e}", case.contact()))?;
        // Equal (M, L, D) give equal films only for the default models: Roelands and
        // Dowson-Higginson have parameters (z, p_h) that the stored family name omits.
        let family = case.models().family();
        if case.models() != Models::default() || family != c.family {
            return Err(format!(
                "the formula answers elastic Barus incompressible smooth cases of data of that                  family; the case is {family}, the data {}",
                c.family
            ));
        }
        let (m, l) = (case.m(), case.l());
        let cell = c.cell([m, l, d])?;
        let [map_c, map_pm, map_min] = &c.films;
        let (err_c, est_c, n_c) = map_c.at([m, l, d], &cell, point)?;
        let (err_min, est_min, n_min) = map_min.at([m, l, d], &cell, point)?;
        let pm = map_pm.at([m, l, d], &cell, point).ok();
        let support = format!(
            "{} and {} check case(s) there",
            cell.describe(point),
            n_c.max(n_min)
        );
        Ok(FormulaFilms {
            h_c: map_c.model.eval(m, l, d),
            h_pm: map_pm.model.eval(m, l, d),
            h_min: map_min.model.eval(m, l, d),
            map: err_c.max(err_min),
            h_c_err: MAP_SAFETY * err_c + est_c,
            h_min_err: MAP_SAFETY * err_min + est_min,
            h_pm_err: pm.map(|(err, est, _)| MAP_SAFETY * err + est),
            support,
        })
    }

    fn source(&self) -> &str {
        &self.source
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::heldout::{HeldOut, SizeScore};

    fn score() -> SizeScore {
        SizeScore {
            terms: 0,
            ridge: 0.0,
            candidate: 0,
            level: 0,
            rms: 0.0,
            max: 0.0,
            worst: (0.0, 0.0, 0.0),
        }
    }

    fn moes() -> FittedModel {
        FittedModel {
            blend: crate::fit::fitted::Blend::Line(crate::fit::model::LineModel::moes()),
            correction: Default::default(),
            side: None,
            corner: None,
            kriging: None,
        }
    }

    /// A line report with Moes' formula whose held-out errors are 0.1 % x (index of M) + 0.01 %
    /// x L on a 3 x 2 lattice, the data films `scale` times the formula's, data estimates
    /// 0.2 %, the (M, L) = (100, 5) case missing from H_min; check cases at the centres of the two
    /// cells, 0.3 %.
    fn report(scale: f64) -> FitReport {
        let q = |skip: Option<(f64, f64)>| {
            let mut cases = vec![];
            for (i, m) in [10.0, 30.0, 100.0].into_iter().enumerate() {
                for l in [0.0, 5.0] {
                    if skip == Some((m, l)) {
                        continue;
                    }
                    cases.push(CaseError {
                        m,
                        l,
                        d: 1.0,
                        h: Some(scale * moes().eval(m, l, 1.0)),
                        error: -(0.001 * i as f64 + 0.0001 * l),
                        estimate: Some(0.002),
                    });
                }
            }
            Some(QuantityFit {
                heldout: Some(HeldOut {
                    folds: 5,
                    sizes: vec![],
                    joint: vec![],
                    chosen: score(),
                    cases,
                }),
                quantity: "H".into(),
                model: moes(),
                params: vec![],
                rms_log: 0.0,
                converged: true,
                overall: crate::fit::stats::ErrStats {
                    n: 1,
                    max: 0.0,
                    rms: 0.0,
                    mean: 0.0,
                    worst_m: 0.0,
                    worst_l: 0.0,
                },
                regions: vec![],
                per_d: vec![],
                within_target: None,
                side: None,
                corner: None,
                kriging: None,
                check: [20.0, 50.0]
                    .map(|m| CaseError {
                        m,
                        l: 2.5,
                        d: 1.0,
                        h: None,
                        error: 0.003,
                        estimate: Some(0.001),
                    })
                    .to_vec(),
            })
        };
        let line = ContactReport {
            contact: "line".into(),
            h_c: q(None),
            h_pm: q(None),
            h_min: q(Some((100.0, 5.0))),
            families: vec!["elastic barus incompressible".into()],
            ..ContactReport::default()
        };
        FitReport {
            datasets: vec![],
            duplicate_rows: 0,
            excluded: vec![],
            one_film: vec![],
            line,
            point: ContactReport::default(),
        }
    }

    #[test]
    fn the_map_is_the_worst_corner_of_the_cell_around_the_case() {
        let f = FittedFormula::from_report(&report(1.0), "fit.json").unwrap();
        let case = |m, l| Case::Line(crate::model::case::LineCase::new(m, l).unwrap());
        // Between M = 10 and 30, L = 0 and 5: corners i = 0, 1; worst 0.1 % + 0.05 %, the
        // check case (20, 2.5) at 0.3 %, and the formula's departure from the bilinear
        // interpolant of the data's ln H in (ln M, L).
        let a = f.films(&case(20.0, 2.0)).unwrap();
        let h = |m, l| moes().eval(m, l, 1.0).ln();
        let (t, u) = ((20.0f64 / 10.0).ln() / 3.0f64.ln(), 2.0 / 5.0);
        let interp = (1.0 - t) * (1.0 - u) * h(10.0, 0.0)
            + t * (1.0 - u) * h(30.0, 0.0)
            + (1.0 - t) * u * h(10.0, 5.0)
            + t * u * h(30.0, 5.0);
        let departure = (h(20.0, 2.0) - interp).exp_m1().abs();
        let map = departure.max(0.003);
        assert!((a.map - map).abs() < 1e-12, "{a:?} {departure}");
        assert!((a.h_c_err - (MAP_SAFETY * map + 0.002)).abs() < 1e-12);
        assert!(a.support.contains("1 check case"), "{}", a.support);
        assert!(a.support.contains("4 data cases") && a.support.contains("M 10-30"));
        // On a data case: that case's held-out error (the interpolant is the datum, which is the
        // formula) and the check cases of the cells around it (0.3 %).
        let a = f.films(&case(30.0, 0.0)).unwrap();
        assert!((a.map - 0.003).abs() < 1e-15, "{a:?}");
        assert!(a.support.contains("2 check case"), "{}", a.support);
        // Data 5 % above the formula everywhere: the departure is 1/1.05 - 1.
        let g = FittedFormula::from_report(&report(1.05), "fit.json").unwrap();
        let a = g.films(&case(30.0, 0.0)).unwrap();
        assert!((a.map - (1.0 - 1.0 / 1.05)).abs() < 1e-12, "{a:?}");
        assert!(a.support.contains("1 data case"), "{}", a.support);
        // On an axis value of M: 2 corners; the check cases of the cells on both sides of it
        // count (here the one at M = 20), so the answer does not jump at M = 10.
        let a = f.films(&case(10.0, 2.5)).unwrap();
        assert!(a.support.contains("2 data cases") && a.support.contains("1 check case"));
        let a = f.films(&case(30.0, 2.5)).unwrap();
        assert!(a.support.contains("2 check case"), "{}", a.support);
        // Without check cases, a case between data cases is declined.
        let mut r = report(1.0);
        r.line.h_c.as_mut().unwrap().check.clear();
        let g = FittedFormula::from_report(&r, "fit.json").unwrap();
        let e = g.films(&case(20.0, 2.0)).unwrap_err();
        assert!(
            e.contains("no check case between") && e.contains("nightly-line-mid"),
            "{e}"
        );
        assert!(g.films(&case(30.0, 0.0)).is_ok(), "a data case needs none");
        // A corner missing from H_min's map declines, naming it.
        let e = f.films(&case(50.0, 3.0)).unwrap_err();
        assert!(e.contains("M = 100, L = 5"), "{e}");
        // Outside the data.
        let e = f.films(&case(5.0, 3.0)).unwrap_err();
        assert!(e.contains("M = 5 outside the data (10 to 100)"), "{e}");
        let e = f.films(&case(20.0, 6.0)).unwrap_err();
        assert!(e.contains("L = 6 outside"), "{e}");
        // Another model family, and the point contact, are declined with the reason.
        let mut roelands = crate::model::case::LineCase::new(20.0, 2.0).unwrap();
        roelands.models.density = crate::model::lubricant::Density::DowsonHigginson { ph_pa: 1e9 };
        let e = f.films(&Case::Line(roelands)).unwrap_err();
        assert!(e.contains("dowson-higginson") && e.contains("Barus"), "{e}");
        let p = Case::Point(crate::model::case::PointCase::new(20.0, 2.0, 1.0).unwrap());
        let e = f.films(&p).unwrap_err();
        assert!(e.starts_with("point contact: no H_c formula"), "{e}");
    }

    #[test]
    fn a_report_without_usable_contacts_is_an_error() {
        let mut r = report(1.0);
        r.line
            .families
            .push("elastic roelands incompressible".into());
        let e = FittedFormula::from_report(&r, "x/fit.json").unwrap_err();
        assert!(
            e.contains("x/fit.json") && e.contains("mix model families"),
            "{e}"
        );
    }
}
