//! Sweep specs: a TOML file parsed with spans and validated up front, so that every error names
//! the file, the line and the key (`sweeps/x.toml:7: axes.M: M = -1 is invalid: ...`).
//!
//! ```toml
//! name = "smoke"                 # dataset directory <out>/<name>/ (default: the file stem)
//! contact = "line"               # or "point" (needs the axis D), or ["line", "point"]
//! description = "free text"      # optional
//!
//! [axes]                         # each axis: a list, or a range table
//! M = [5, 20, 100, 500]
//! L = { from = 0, to = 10, count = 3 }                 # scale = "linear" (default) or "log"
//! # D = { from = 0.05, to = 1, count = 6, scale = "log" } (point contacts: required, in (0, 1])
//!
//! [models]                       # all optional; defaults shown
//! elasticity = "elastic"         # or "rigid"
//! viscosity = "barus"            # or "roelands": needs ph and exactly one of eta0, z
//! density = "incompressible"     # or "dowson-higginson": needs ph
//! # ph = 1.0e9                   # Hertzian pressure, Pa
//! # eta0 = 0.05                  # ambient viscosity, Pa s (Roelands z derived per case)
//! # z = 0.6                      # Roelands pressure-viscosity index
//!
//! [numerics]                     # all optional; defaults shown
//! grid = 2049                    # finest-grid points (the solver rounds up to 2^k n0 + 1), 33..=1048577;
//!                                # point contacts: per direction, default 129, 17..=2049
//! cycle = "v"                    # or "w"
//! max_cycles = 60
//! fallback = true
//! tol_load = 1e-7
//! tol_h = 1e-6
//! error_estimate = false         # true: also solve on the half grid, Richardson error columns
//! accuracy = 0.005               # optional: refine from 257 line points (33^2 point nodes) up
//!                                # to `grid` until the error estimate meets it
//! # [numerics.point]             # a mixed spec: overrides for one contact, same keys
//! # grid = 65
//!
//! [output]                       # all optional; defaults shown
//! dir = "outputs"                # relative to the working directory; --out overrides
//! batch = 32                     # flush to disk after this many finished cases ...
//! flush_seconds = 30             # ... or this long after the previous flush
//! ```

use crate::model::case::Elasticity;
use crate::model::lubricant::Density;
use std::collections::BTreeMap;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::de::DeTable;

mod axes;
mod contacts;
mod ctx;
mod error;
mod numerics;
#[cfg(test)]
mod tests;
mod types;

pub use axes::{canonical, expand_range, MAX_AXIS_VALUES};
use ctx::Ctx;
pub use error::SpecError;
pub use types::{Contact, ContactSpec, Numerics, OutputSpec, SweepSpec, ViscositySpec};

/// Largest number of cases one spec may expand to.
pub const MAX_CASES: usize = 1_000_000;

/// Read and validate a spec file.
pub fn load(path: &Path) -> Result<SweepSpec, SpecError> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| SpecError {
        file: file.clone(),
        line: 0,
        key: String::new(),
        message: format!("cannot read the spec: {e}"),
    })?;
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    parse(&file, &text, &stem)
}

/// Parse and validate a spec given as text. `file` names it in messages; `default_name` is the
/// dataset name when the spec has no `name`.
pub fn parse(file: &str, text: &str, default_name: &str) -> Result<SweepSpec, SpecError> {
    let mut cx = Ctx {
        file,
        text,
        lines: BTreeMap::new(),
    };
    let doc = DeTable::parse(text).map_err(|e| {
        let span = e.span().unwrap_or(0..0);
        let msg = e.message().lines().next().unwrap_or("invalid TOML").trim();
        cx.err(&span, "", format!("invalid TOML: {msg}"))
    })?;
    let root = doc.get_ref();
    cx.keys(
        root,
        "",
        &[
            "name",
            "contact",
            "description",
            "axes",
            "models",
            "numerics",
            "output",
        ],
    )?;
    let doc_span = 0..0;

    // name
    let name = match root.get("name") {
        Some(v) => cx.string(v, "name")?.to_string(),
        None => default_name.to_string(),
    };
    let name_ok = !name.is_empty()
        && !name.starts_with('.')
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "-_.".contains(c));
    if !name_ok {
        let span = root.get("name").map_or(doc_span.clone(), |v| v.span());
        return Err(cx.err(
            &span,
            "name",
            format!(
                "\"{name}\" is not a valid dataset name (letters, digits, '-', '_', '.'; not starting with '.')"
            ),
        ));
    }

    // contact
    let contact_v = root.get("contact").ok_or_else(|| {
        cx.err(
            &doc_span,
            "contact",
            "missing: give contact = \"line\" or \"point\"",
        )
    })?;
    let contacts = contacts::parse_contacts(&cx, contact_v)?;
    let description = match root.get("description") {
        Some(v) => Some(cx.string(v, "description")?.to_string()),
        None => None,
    };

    // axes
    let axes_v = root
        .get("axes")
        .ok_or_else(|| cx.err(&doc_span, "axes", "missing: an [axes] table with M and L"))?;
    let axes = cx.table(axes_v, "axes")?;
    cx.keys(axes, "axes", &["M", "L", "D", "line", "point"])?;
    let need = |k: &str| {
        axes.get(k).ok_or_else(|| {
            cx.err(
                &axes_v.span(),
                &format!("axes.{k}"),
                "missing: every sweep needs the axes M and L",
            )
        })
    };
    let (mv, lv) = (need("M")?, need("L")?);
    let m = cx.axis(mv, "axes.M", &contacts::m_ok)?;
    let l = cx.axis(lv, "axes.L", &contacts::l_ok)?;
    let axes_of = contacts::contact_axes(&mut cx, axes, &contacts, &m, &l)?;
    let d = match axes.get("D") {
        Some(dv) => Some(cx.axis(dv, "axes.D", &|x| {
            (!(x > 0.0 && x <= 1.0)).then_some("the ellipticity must be in (0, 1]")
        })?),
        None => None,
    };

    // models
    let mut elasticity = Elasticity::Elastic;
    let mut viscosity = ViscositySpec::Barus;
    let mut density = Density::Incompressible;
    if let Some(mv) = root.get("models") {
        let t = cx.table(mv, "models")?;
        cx.keys(
            t,
            "models",
            &["elasticity", "viscosity", "density", "ph", "eta0", "z"],
        )?;
        if let Some(v) = t.get("elasticity") {
            if cx.choice(v, "models.elasticity", &["elastic", "rigid"])? == "rigid" {
                elasticity = Elasticity::Rigid;
            }
        }
        let pos = |k: &str, why: &'static str| -> Result<Option<(f64, Range<usize>)>, SpecError> {
            match t.get(k) {
                None => Ok(None),
                Some(v) => {
                    let key = format!("models.{k}");
                    let x = cx.number(v, &key)?;
                    if x > 0.0 {
                        Ok(Some((x, v.span())))
                    } else {
                        Err(cx.err(&v.span(), &key, format!("{k} = {x} is invalid: {why}")))
                    }
                }
            }
        };
        let ph = pos("ph", "the Hertzian pressure must be > 0 (Pa)")?;
        let eta0 = pos("eta0", "the ambient viscosity must be > 0 (Pa s)")?;
        let z = pos("z", "the Roelands index must be > 0")?;
        let visc = match t.get("viscosity") {
            Some(v) => cx.choice(v, "models.viscosity", &["barus", "roelands"])?,
            None => "barus",
        };
        let dens = match t.get("density") {
            Some(v) => cx.choice(v, "models.density", &["incompressible", "dowson-higginson"])?,
            None => "incompressible",
        };
        let model_span = |k: &str| t.get(k).map_or(mv.span(), |v| v.span());
        let need_ph = |what: &str| {
            ph.as_ref().map(|p| p.0).ok_or_else(|| {
                cx.err(
                    &model_span(what),
                    &format!("models.{what}"),
                    "needs the Hertzian pressure models.ph (Pa)",
                )
            })
        };
        if visc == "roelands" {
            let ph_pa = need_ph("viscosity")?;
            viscosity = match (eta0, z) {
                (Some((eta0, span)), None) => {
                    if eta0.ln() + 9.67 <= 0.0 {
                        return Err(cx.err(
                            &span,
                            "models.eta0",
                            format!("eta0 = {eta0} is invalid: Roelands needs ln(eta0) + 9.67 > 0"),
                        ));
                    }
                    if l.contains(&0.0) {
                        return Err(cx.err(
                            &lv.span(),
                            "axes.L",
                            "L = 0 with Roelands from eta0 gives z = 0: use L > 0 or give models.z",
                        ));
                    }
                    ViscositySpec::RoelandsEta0 { eta0, ph_pa }
                }
                (None, Some((z, _))) => ViscositySpec::RoelandsZ { z, ph_pa },
                _ => {
                    return Err(cx.err(
                        &model_span("viscosity"),
                        "models.viscosity",
                        "roelands needs exactly one of models.eta0 (Pa s) or models.z",
                    ))
                }
            };
        } else {
            for (k, given) in [("eta0", eta0.is_some()), ("z", z.is_some())] {
                if given {
                    return Err(cx.err(
                        &model_span(k),
                        &format!("models.{k}"),
                        "applies to viscosity = \"roelands\" only",
                    ));
                }
            }
        }
        if dens == "dowson-higginson" {
            density = Density::DowsonHigginson {
                ph_pa: need_ph("density")?,
            };
        }
        if ph.is_some() && visc != "roelands" && dens != "dowson-higginson" {
            return Err(cx.err(
                &model_span("ph"),
                "models.ph",
                "is used only by viscosity = \"roelands\" and density = \"dowson-higginson\"",
            ));
        }
    }

    // numerics, per contact
    let contacts_numerics = numerics::parse(&mut cx, root, axes_of)?;

    // output
    let mut output = OutputSpec {
        dir: PathBuf::from("outputs"),
        batch: 32,
        flush_seconds: 30.0,
    };
    if let Some(ov) = root.get("output") {
        let t = cx.table(ov, "output")?;
        cx.keys(t, "output", &["dir", "batch", "flush_seconds"])?;
        if let Some(v) = t.get("dir") {
            let s = cx.string(v, "output.dir")?;
            if s.is_empty() {
                return Err(cx.err(&v.span(), "output.dir", "must not be empty"));
            }
            output.dir = PathBuf::from(s);
        }
        if let Some(v) = t.get("batch") {
            output.batch = cx.integer(v, "output.batch", 1, 1_000_000)? as usize;
        }
        if let Some(v) = t.get("flush_seconds") {
            let x = cx.number(v, "output.flush_seconds")?;
            if x <= 0.0 {
                return Err(cx.err(
                    &v.span(),
                    "output.flush_seconds",
                    format!("flush_seconds = {x} is invalid: must be > 0"),
                ));
            }
            output.flush_seconds = x;
        }
    }

    let n_d = d.as_ref().map_or(1, |d| d.len());
    let n_cases: usize = contacts_numerics
        .iter()
        .map(|c| c.m.len() * c.l.len() * if c.contact == Contact::Point { n_d } else { 1 })
        .sum();
    if n_cases > MAX_CASES {
        return Err(cx.err(
            &axes_v.span(),
            "axes",
            format!("{n_cases} cases: at most {MAX_CASES} per spec"),
        ));
    }

    // Contact-specific rules, after every value has been checked.
    if contacts.contains(&Contact::Point) && d.is_none() {
        return Err(cx.err(
            &axes_v.span(),
            "axes.D",
            "missing: contact = \"point\" needs the ellipticity axis D = Rx/Ry, values in (0, 1]",
        ));
    }
    if let (false, Some(dv)) = (contacts.contains(&Contact::Point), axes.get("D")) {
        return Err(cx.err(
            &dv.span(),
            "axes.D",
            "the ellipticity axis D applies to contact = \"point\" only",
        ));
    }

    Ok(SweepSpec {
        file: file.to_string(),
        text: text.to_string(),
        name,
        contacts: contacts_numerics,
        description,
        m,
        l,
        d,
        elasticity,
        viscosity,
        density,
        output,
        lines: cx.lines,
    })
}
