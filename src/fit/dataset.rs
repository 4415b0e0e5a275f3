//! Reading sweep datasets for the fit: every Parquet file of each directory, or a single Parquet
//! file (arrow-rs reader, any codec the build reads; a file of another layout is an error naming
//! the file and the missing column),
//! deduplicated by case id across directories, converged valid rows only, split by contact
//! (line / point; a mixed dataset gives both); failed rows and duplicates are counted for the
//! report. A film whose Richardson error estimate (H_c_err, H_min_err) exceeds
//! [`MAX_ERROR_ESTIMATE`] is left out of its film's fit as grid-unconverged (a fit to 2 % cannot
//! use data that are themselves uncertain by more; [`FitPoint::film`]); rows
//! where both exceed it are left out, each listed with its estimate in the report; rows used for
//! one film only are listed too (on the 513^2 nightly point sweep H_c is converged to 2 % at
//! M = 1000, D = 1, H_min at the exit constriction is not). So are point rows
//! whose domain-truncation error estimate (`PointDomain::truncation_error` of the row's own
//! domain rule: with the asymptotic far field at most 0.45 %; with P = 0 on the boundary
//! (`far_field` false, and every point row of files before schema 5) 2.5 times the change a
//! doubled domain makes, large for rigid-like cases at small M) exceeds the same limit. (Filtering on the
//! doubling change alone, `PointDomain::bias`, kept rows that are some 4 % low: on the nightly
//! point sweep at 257^2 the fit's max error was then 3.8 %, at M = 7.2, L = 5, D = 1, with the
//! fit above the data; with this filter 1.8 %.) The film at the pressure maximum (`H_c_pmax`,
//! fitted as H_pm) is left out where its own estimate (`H_c_pmax_err`, schema 6) exceeds the
//! limit (in older files without it, where H_c's or H_min's does), and where the pressure
//! maximum is not a converged quantity: where it is the outlet spike ([`spike_is_the_maximum`])
//! or where its own estimate (`P_max_err`) exceeds the limit ([`peak_is_unresolved`]). Under
//! Barus viscosity at high L the spike grows with every refinement (line M = 3.1, L = 20: P_max
//! 2.56, 3.00, 4.14, 5.97, 9.23, 10.8 on 513 ... 16385 points, the spike on the main maximum
//! near X = 0, so no second maximum is found), and the film under it is taken where the grid
//! puts the spike (there 9.6285 on 1025 points and 9.6167 on 16385, against H_c's 9.6433),
//! while the Richardson estimate of that film is 0.5 %.
//! Rows answered by a fitted formula (`model_used = "formula"`) are left out (listed). The model
//! families of the rows used are recorded per contact (a formula answers only its own family).
//! The datasets carry no G column, so `FitPoint::g` is None (formulas that need G are skipped by
//! the report).

use crate::discrete::point::domain::{PointDomain, PointDomainParams};
use crate::fit::error::FitError;
use crate::limits::anchors::Anchor;
use crate::limits::jump::JumpTable;
#[cfg(doc)]
use crate::model::case::Models;
use crate::model::case::{family, Contact, PointCase};
use crate::solve::film::Film;
use crate::solve::solution::ModelUsed;
use crate::store::results::{read_dataset, read_part, CaseRow, RowStatus};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::PathBuf;

/// Largest Richardson error estimate (H_c_err, H_min_err) of a film used by the fit.
pub const MAX_ERROR_ESTIMATE: f64 = 0.02;

/// One converged case of a dataset (`d` is None for line contacts, `g` = alpha E' when the
/// dataset carries it, `h_pm` the film at the pressure maximum when it does).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FitPoint {
    /// Moes' dimensionless load parameter M.
    pub m: f64,
    /// Moes' dimensionless lubricant parameter L.
    pub l: f64,
    /// Ellipticity D = Rx/Ry of a point contact; None for a line contact.
    pub d: Option<f64>,
    /// Dimensionless central film H_c (at X = 0, and Y = 0 for a point contact); positive.
    pub h_c: f64,
    /// Dimensionless minimum film H_min; positive.
    pub h_min: f64,
    /// Dimensionless material parameter G = alpha E' (None: the dataset does not carry it, as
    /// for every dataset read by [`load_fit_input`]).
    pub g: Option<f64>,
    /// Dimensionless film at the pressure maximum H_pm (the dataset's `H_c_pmax`; None when it
    /// is missing, not finite or not positive).
    #[serde(default)]
    pub h_pm: Option<f64>,
    /// Points per direction of the solve (the limit checks solve point cases on at least this).
    #[serde(default)]
    pub grid: Option<usize>,
    /// Richardson error estimate of H_c, relative (None: not estimated). A film whose estimate
    /// exceeds [`MAX_ERROR_ESTIMATE`] is left out of that film's fit
    /// ([`FitPoint::film`]); H_pm, which has no estimate of its own, needs both within it.
    #[serde(default)]
    pub h_c_err: Option<f64>,
    /// Richardson error estimate of H_min, relative (None: not estimated); see `h_c_err`.
    #[serde(default)]
    pub h_min_err: Option<f64>,
    /// Richardson error estimate of H_pm, relative (None: not estimated, as in files before
    /// schema 6; H_pm then needs H_c's and H_min's estimates within the limit).
    #[serde(default)]
    pub h_pm_err: Option<f64>,
    /// Dimensionless minimum film on the centre line Y = 0, H_min,cl (the dataset's `H_min_cl`,
    /// schema 7; None when missing, not finite or not positive): the point H_min law is its law
    /// times the side-lobe factor ([`crate::fit::side`]).
    #[serde(default)]
    pub h_min_cl: Option<f64>,
    /// Richardson error estimate of H_min,cl, relative (None: not estimated).
    #[serde(default)]
    pub h_min_cl_err: Option<f64>,
}

impl FitPoint {
    /// `film` of this case (None when the dataset does not carry it, or when its error
    /// estimate exceeds [`MAX_ERROR_ESTIMATE`]).
    pub fn film(&self, film: Film) -> Option<f64> {
        let p = self;
        let ok = |e: Option<f64>| e.is_none_or(|e| e <= MAX_ERROR_ESTIMATE);
        match film {
            Film::Centre => ok(p.h_c_err).then_some(p.h_c),
            Film::PressureMax => p.h_pm.filter(|_| match p.h_pm_err {
                Some(e) => ok(Some(e)),
                None => ok(p.h_c_err) && ok(p.h_min_err),
            }),
            Film::Minimum => ok(p.h_min_err).then_some(p.h_min),
        }
    }

    /// The relative error estimate of `film` at this case: H_c's, H_min's, H_pm's, and for
    /// H_pm without its own the larger of H_c's and H_min's (None where a film has none).
    pub fn estimate(&self, film: Film) -> Option<f64> {
        match film {
            Film::Centre => self.h_c_err,
            Film::PressureMax => self
                .h_pm_err
                .or_else(|| self.h_c_err.zip(self.h_min_err).map(|(a, b)| a.max(b))),
            Film::Minimum => self.h_min_err,
        }
    }

    /// H_min,cl of this case (None when the dataset does not carry it, or when its error
    /// estimate exceeds [`MAX_ERROR_ESTIMATE`]).
    pub fn centre_line_min(&self) -> Option<f64> {
        self.h_min_cl
            .filter(|_| self.h_min_cl_err.is_none_or(|e| e <= MAX_ERROR_ESTIMATE))
    }

    /// D, or 1 for a line contact.
    pub fn dd(&self) -> f64 {
        self.d.unwrap_or(1.0)
    }
}

/// What the fit reads: converged points per contact plus counts of what was left out.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct FitInput {
    /// The dataset directories read, in the order given.
    pub datasets: Vec<String>,
    /// The converged valid line-contact cases used by the fit (each has `d` None).
    pub line: Vec<FitPoint>,
    /// The converged valid point-contact cases used by the fit (each has `d` set).
    pub point: Vec<FitPoint>,
    /// Line rows not converged, not valid, or without a positive H_c and H_min.
    pub failed_line: usize,
    /// Point rows not converged, not valid, without a positive H_c and H_min, or without D.
    pub failed_point: usize,
    /// Rows whose case id was already read (the first row read of a case id is kept).
    pub duplicates: usize,
    /// Rows left out with the reason (e.g. an error estimate above the threshold).
    pub excluded: Vec<String>,
    /// Rows used for one film only (the other film's error estimate is above the threshold).
    #[serde(default)]
    pub one_film: Vec<String>,
    /// The model families ([`Models::family`]) of the line cases used, sorted, distinct.
    #[serde(default)]
    pub line_families: Vec<String>,
    /// The same for the point cases.
    #[serde(default)]
    pub point_families: Vec<String>,
    /// Line cases of the check set: evaluated against the formula, never fitted
    /// ([`FitInput::with_check`]).
    #[serde(default)]
    pub check_line: Vec<FitPoint>,
    /// Point cases of the check set.
    #[serde(default)]
    pub check_point: Vec<FitPoint>,
    /// Where the point H_c corner lies, from solves ([`crate::limits::jump`], `ehlmap fit
    /// --jump`): the point H_c kriging then also offers the corner coordinate. None: not given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub jump: Option<JumpTable>,
    /// The point approach factor's anchors, from solves ([`crate::limits::anchors`], `ehlmap fit
    /// --anchors`): the approach factor is fitted to them too. Empty: not given.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub anchors: Vec<Anchor>,
    /// Whether the point H_c elastic-isoviscous law is held at its limit as H_pm's always is:
    /// the line's carried over by the local inlet analysis ([`crate::limits::point_ei`]) times
    /// the approach factor fitted first ([`crate::fit::approach`]; `ehlmap fit
    /// --point-ei-limit`), instead of fitted. Anchors imply it ([`crate::report`]).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub point_ei_limit: bool,
}

impl FitInput {
    /// This input with the check set `check` (read like the data; its cases are only compared
    /// with the fitted formula; its rows left out are listed among `excluded`, marked "check
    /// set"). Errors: a check case that is also a data case (equal contact, M, L, D: it would
    /// not check anything), or a check set of other model families than the data's.
    pub fn with_check(mut self, check: FitInput) -> Result<FitInput, FitError> {
        for (contact, data, other) in [
            ("line", &self.line_families, &check.line_families),
            ("point", &self.point_families, &check.point_families),
        ] {
            if !other.is_empty() && !data.is_empty() && data != other {
                return Err(FitError::Dataset(format!(
                    "{}: the check set's {contact} cases are {} and the data's {}",
                    check.datasets.join(", "),
                    other.join(", "),
                    data.join(", ")
                )));
            }
        }
        let key = |p: &FitPoint| {
            let d = p.d.map(f64::to_bits);
            (p.m.to_bits(), p.l.to_bits(), d)
        };
        let data: std::collections::BTreeSet<_> =
            self.line.iter().chain(&self.point).map(key).collect();
        if let Some(p) = check
            .line
            .iter()
            .chain(&check.point)
            .find(|p| data.contains(&key(p)))
        {
            return Err(FitError::Dataset(format!(
                "{}: the check case M = {}, L = {}{} is also a data case",
                check.datasets.join(", "),
                p.m,
                p.l,
                p.d.map_or(String::new(), |d| format!(", D = {d}"))
            )));
        }
        self.check_line = check.line;
        self.check_point = check.point;
        let failed = check.failed_line + check.failed_point;
        self.excluded.extend(
            check
                .excluded
                .iter()
                .map(|e| format!("check set: {e}"))
                .chain((failed > 0).then(|| format!("check set: {failed} rows not converged"))),
        );
        Ok(self)
    }
}

/// Load the fit input from one or more dataset directories (module doc: which rows are kept,
/// left out or counted as failed).
///
/// Errors: a path that is neither a directory nor a file, or a dataset that cannot be read (the
/// message names the file).
pub fn load_fit_input(dirs: &[PathBuf]) -> Result<FitInput, FitError> {
    let mut by_id = BTreeMap::new();
    let mut duplicates = 0;
    for dir in dirs {
        let rows = if dir.is_dir() {
            read_dataset(dir)
        } else if dir.is_file() {
            read_part(dir).map(|p| p.rows)
        } else {
            return Err(FitError::Dataset(format!(
                "{}: not a dataset directory or Parquet file",
                dir.display()
            )));
        };
        for row in rows.map_err(|e| FitError::Dataset(e.to_string()))? {
            if by_id.contains_key(&row.case_id) {
                duplicates += 1;
            } else {
                by_id.insert(row.case_id.clone(), row);
            }
        }
    }
    let mut input = FitInput {
        datasets: dirs.iter().map(|d| d.display().to_string()).collect(),
        duplicates,
        ..FitInput::default()
    };
    for row in by_id.values() {
        if let Some(sigma) = row.sigma {
            // The formula is the smooth-surface film: rough rows are the mixed map's.
            input.excluded.push(format!(
                "{}: rough surfaces (sigma = {sigma}): see ehlmap mixed",
                row.case_id
            ));
            continue;
        }
        if row.model_used == ModelUsed::Formula {
            // A formula's answer is no datum for a formula.
            input.excluded.push(format!(
                "{}: answered by a fitted formula, not solved",
                row.case_id
            ));
            continue;
        }
        let ok = row.status == RowStatus::Converged && row.valid;
        let point = match (row.h_c, row.h_min) {
            (Some(h_c), Some(h_min)) if ok && h_c > 0.0 && h_min > 0.0 => Some(FitPoint {
                m: row.m,
                l: row.l,
                d: row.d,
                h_c,
                h_min,
                g: None,
                h_pm: row
                    .h_c_pmax
                    .filter(|v| v.is_finite() && *v > 0.0)
                    .filter(|_| !spike_is_the_maximum(row) && !peak_is_unresolved(row)),
                grid: row.grid.and_then(|g| usize::try_from(g).ok()),
                h_c_err: row.h_c_err,
                h_min_err: row.h_min_err,
                h_pm_err: row.h_c_pmax_err,
                h_min_cl: row.h_min_cl.filter(|v| v.is_finite() && *v > 0.0),
                h_min_cl_err: row.h_min_cl_err,
            }),
            _ => None,
        };
        let (err_c, err_min) = (row.h_c_err.unwrap_or(0.0), row.h_min_err.unwrap_or(0.0));
        let est = err_c.min(err_min);
        let truncation = domain_truncation(row);
        if point.is_some() && truncation > MAX_ERROR_ESTIMATE {
            input.excluded.push(format!(
                "{}: domain truncation error about {:.0} % > {:.0} % \
                 (rigid-like case, see src/discrete/point/domain.rs)",
                label(row),
                100.0 * truncation,
                100.0 * MAX_ERROR_ESTIMATE
            ));
            continue;
        }
        if point.is_some() && est > MAX_ERROR_ESTIMATE {
            input.excluded.push(format!(
                "{}: error estimates H_c {:.1} %, H_min {:.1} % > {:.0} %",
                label(row),
                100.0 * err_c,
                100.0 * err_min,
                100.0 * MAX_ERROR_ESTIMATE
            ));
            continue;
        }
        if point.is_some() && err_c.max(err_min) > MAX_ERROR_ESTIMATE {
            let (used, other, e) = if err_c > err_min {
                ("H_min", "H_c", err_c)
            } else {
                ("H_c", "H_min", err_min)
            };
            input.one_film.push(format!(
                "{}: {used} only ({other} error estimate {:.1} % > {:.0} %)",
                label(row),
                100.0 * e,
                100.0 * MAX_ERROR_ESTIMATE
            ));
        }
        let family = || family(row.elasticity, &row.viscosity, &row.density);
        match (row.contact, point) {
            (Contact::Line, Some(p)) => {
                input.line.push(p);
                input.line_families.push(family());
            }
            (Contact::Point, Some(p)) if p.d.is_some() => {
                input.point.push(p);
                input.point_families.push(family());
            }
            (Contact::Point, _) => input.failed_point += 1,
            (Contact::Line, None) => input.failed_line += 1,
        }
    }
    for f in [&mut input.line_families, &mut input.point_families] {
        f.sort();
        f.dedup();
    }
    Ok(input)
}

/// Whether the row's pressure maximum is its outlet spike (a second pressure maximum was found
/// and it is the largest).
pub fn spike_is_the_maximum(row: &CaseRow) -> bool {
    matches!((row.spike_p, row.p_max), (Some(s), Some(p)) if s >= p)
}

/// Whether the row's pressure maximum is not grid-converged: its Richardson estimate
/// (`P_max_err`, schema 6) exceeds [`MAX_ERROR_ESTIMATE`]. The maximum is then a spike whose
/// height the grid sets (Barus viscosity at high L, also where no second maximum is found, the
/// spike sitting on the main one), and where the film is taken under it is the grid's choice.
pub fn peak_is_unresolved(row: &CaseRow) -> bool {
    row.p_max_err.is_some_and(|e| e > MAX_ERROR_ESTIMATE)
}

/// "line M = .., L = .." or "point M = .., L = .., D = ..": a row in the report's lists.
fn label(row: &CaseRow) -> String {
    format!(
        "{} M = {:.4}, L = {}{}",
        row.contact,
        row.m,
        row.l,
        row.d.map_or(String::new(), |d| format!(", D = {d}"))
    )
}

/// The domain-truncation error estimate of a point row solved on a point grid (0 otherwise).
fn domain_truncation(row: &CaseRow) -> f64 {
    let Some(d) = row.d else { return 0.0 };
    if row.contact != Contact::Point || row.model_used == ModelUsed::SlenderLine {
        return 0.0;
    }
    let Ok(mut case) = PointCase::new(row.m, row.l, d) else {
        return 0.0;
    };
    case.models.elasticity = row.elasticity;
    let params = PointDomainParams {
        far_field: row.far_field,
        ..PointDomainParams::default()
    };
    PointDomain::of_case(&case, &params).truncation_error()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pt(m: f64, l: f64, d: Option<f64>) -> FitPoint {
        FitPoint {
            m,
            l,
            d,
            h_c: 1.0,
            h_min: 0.8,
            g: None,
            h_pm: None,
            grid: None,
            h_c_err: Some(1e-3),
            h_min_err: Some(1e-3),
            h_pm_err: None,
            h_min_cl: None,
            h_min_cl_err: None,
        }
    }

    #[test]
    fn a_check_set_must_be_new_cases_of_the_same_family() {
        let family = vec!["elastic barus incompressible".to_string()];
        let data = FitInput {
            datasets: vec!["data".into()],
            line: vec![pt(10.0, 2.0, None)],
            point: vec![pt(20.0, 0.0, Some(1.0))],
            line_families: family.clone(),
            point_families: family.clone(),
            ..FitInput::default()
        };
        // A line check case at the (M, L) of a point data case at D = 1 is a new case.
        let check = FitInput {
            datasets: vec!["check".into()],
            line: vec![pt(20.0, 0.0, None)],
            line_families: family.clone(),
            excluded: vec!["x: error estimates above 2 %".into()],
            failed_line: 2,
            ..FitInput::default()
        };
        let both = data.clone().with_check(check.clone()).unwrap();
        assert_eq!(both.check_line.len(), 1);
        assert_eq!(
            both.excluded,
            [
                "check set: x: error estimates above 2 %",
                "check set: 2 rows not converged"
            ]
        );
        // A data case again is no check.
        let again = FitInput {
            line: vec![pt(10.0, 2.0, None)],
            ..check.clone()
        };
        let e = data.clone().with_check(again).unwrap_err().to_string();
        assert!(e.contains("M = 10, L = 2 is also a data case"), "{e}");
        // Another family is no check of this formula.
        let other = FitInput {
            line_families: vec!["elastic roelands incompressible".into()],
            ..check
        };
        let e = data.with_check(other).unwrap_err().to_string();
        assert!(e.contains("roelands"), "{e}");
    }
}
