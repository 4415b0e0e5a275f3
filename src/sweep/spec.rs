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
//! # sigma = [0, 1, 2]            # rough surfaces: RMS roughness in Moes film units, >= 0
//! # gamma = [0.333, 1, 3]        # their orientation, > 0 (with sigma)
//!
//! [models]                       # all optional; defaults shown
//! elasticity = "elastic"         # or "rigid"
//! viscosity = "barus"            # or "roelands": needs ph and exactly one of eta0, z
//! density = "incompressible"     # or "dowson-higginson": needs ph
//! # ph = 1.0e9                   # Hertzian pressure, Pa
//! # eta0 = 0.05                  # ambient viscosity, Pa s (Roelands z derived per case)
//! # z = 0.6                      # Roelands pressure-viscosity index
//! # slide_roll = 0.0             # rough cases only: (u1 - u2)/u_m; also rough_surface,
//! #                              # ph_over_e, eta_beta_sigma, sigma_over_beta (models.rs)
//!
//! [numerics]                     # all optional; defaults shown
//! grid = 2049                    # a fixed finest grid (the solver rounds up to 2^k n0 + 1), 33..=1048577
//!                                # points; point contacts: per direction, 17..=2049. Not named: the
//!                                # accuracy target picks the grid, up to 16385 (point: 1025)
//! cycle = "v"                    # or "w"
//! converge = "fast"              # or "tight" (stopping rule, solve::params::Converge)
//! max_cycles = 60
//! fallback = true
//! tol_load = 1e-7
//! tol_h = 1e-6
//! error_estimate = false         # true: also solve on the half grid, Richardson error columns
//! accuracy = 0.005               # refine from 257 line points (33^2 point nodes) up to `grid`
//!                                # until the error estimate meets it; default 0.01 when no
//!                                # grid is named, none when one is
//! # [numerics.point]             # a mixed spec: overrides for one contact, same keys
//! # grid = 65
//!
//! [output]                       # all optional; defaults shown
//! dir = "outputs"                # relative to the working directory; --out overrides
//! batch = 32                     # flush to disk after this many finished cases ...
//! flush_seconds = 30             # ... or this long after the previous flush
//! ```

use std::collections::BTreeMap;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::de::DeTable;
use toml::Spanned;

mod axes;
mod contacts;
mod ctx;
mod error;
mod models;
mod numerics;
#[cfg(test)]
mod tests;
mod types;

pub use axes::{canonical, expand_range, MAX_AXIS_VALUES};
use contacts::ContactAxes;
use ctx::{Ctx, Table};
pub use error::SpecError;
pub use types::{Contact, ContactSpec, Numerics, OutputSpec, SweepSpec, ViscositySpec};

/// Largest number of cases one spec may expand to.
pub const MAX_CASES: usize = 1_000_000;

/// The keys of a spec's top level.
const ROOT_KEYS: [&str; 7] = [
    "name",
    "contact",
    "description",
    "axes",
    "models",
    "numerics",
    "output",
];

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
    let doc = parse_toml(&cx, text)?;
    let root = doc.get_ref();
    cx.keys(root, "", &ROOT_KEYS)?;
    let name = parse_name(&cx, root, default_name)?;
    let contacts = parse_contact(&cx, root)?;
    let description = match root.get("description") {
        Some(v) => Some(cx.string(v, "description")?.to_string()),
        None => None,
    };
    let axes = parse_axes(&mut cx, root, &contacts)?;
    let rough = axes.sigma.iter().any(|&s| s > 0.0);
    let models = models::parse(&mut cx, root, &axes.l, &axes.l_span, rough)?;
    let contacts_numerics = numerics::parse(&mut cx, root, axes.of_contact)?;
    let output = parse_output(&mut cx, root)?;
    check_case_count(
        &cx,
        &contacts_numerics,
        axes.d.as_deref(),
        axes.sigma.len() * axes.gamma.len(),
        &axes.span,
    )?;
    // Contact-specific rules, after every value has been checked.
    check_d_axis(&cx, &contacts, axes.d_span, &axes.span)?;
    Ok(SweepSpec {
        file: file.to_string(),
        text: text.to_string(),
        name,
        contacts: contacts_numerics,
        description,
        m: axes.m,
        l: axes.l,
        d: axes.d,
        sigma: axes.sigma,
        gamma: axes.gamma,
        roughness: models.roughness,
        elasticity: models.elasticity,
        viscosity: models.viscosity,
        density: models.density,
        output,
        lines: cx.lines,
    })
}

/// The TOML document of `text`; an error names the line of the first syntax error.
fn parse_toml<'i>(cx: &Ctx, text: &'i str) -> Result<Spanned<DeTable<'i>>, SpecError> {
    DeTable::parse(text).map_err(|e| {
        let span = e.span().unwrap_or(0..0);
        let msg = e.message().lines().next().unwrap_or("invalid TOML").trim();
        cx.err(&span, "", format!("invalid TOML: {msg}"))
    })
}

/// The dataset name: `name`, else `default_name`; letters, digits, '-', '_' and '.', not
/// starting with '.'.
fn parse_name(cx: &Ctx, root: &Table, default_name: &str) -> Result<String, SpecError> {
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
        let span = root.get("name").map_or(0..0, |v| v.span());
        return Err(cx.err(
            &span,
            "name",
            format!(
                "\"{name}\" is not a valid dataset name (letters, digits, '-', '_', '.'; not starting with '.')"
            ),
        ));
    }
    Ok(name)
}

/// The contacts of `contact`, which every spec gives.
fn parse_contact(cx: &Ctx, root: &Table) -> Result<Vec<Contact>, SpecError> {
    let contact_v = root.get("contact").ok_or_else(|| {
        cx.err(
            &(0..0),
            "contact",
            "missing: give contact = \"line\" or \"point\"",
        )
    })?;
    contacts::parse_contacts(cx, contact_v)
}

/// The `[axes]` of a spec: the values and where they are given.
struct Axes {
    m: Vec<f64>,
    l: Vec<f64>,
    d: Option<Vec<f64>>,
    /// The roughness axes (`[0]` and `[1]` when not given).
    sigma: Vec<f64>,
    gamma: Vec<f64>,
    /// Each contact with its own M and L axes.
    of_contact: Vec<ContactAxes>,
    /// The spans of the `[axes]` table, of `L` and of `D`.
    span: Range<usize>,
    l_span: Range<usize>,
    d_span: Option<Range<usize>>,
}

/// The `[axes]` table: M and L (required), each contact's own M and L, and D.
fn parse_axes(cx: &mut Ctx, root: &Table, contacts: &[Contact]) -> Result<Axes, SpecError> {
    let axes_v = root
        .get("axes")
        .ok_or_else(|| cx.err(&(0..0), "axes", "missing: an [axes] table with M and L"))?;
    let axes = cx.table(axes_v, "axes")?;
    cx.keys(
        axes,
        "axes",
        &["M", "L", "D", "sigma", "gamma", "line", "point"],
    )?;
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
    let of_contact = contacts::contact_axes(cx, axes, contacts, &m, &l)?;
    let d = match axes.get("D") {
        Some(dv) => Some(cx.axis(dv, "axes.D", &|x| {
            (!(x > 0.0 && x <= 1.0)).then_some("the ellipticity must be in (0, 1]")
        })?),
        None => None,
    };
    let sigma = match axes.get("sigma") {
        Some(v) => cx.axis(v, "axes.sigma", &|x| {
            (!x.is_finite() || x < 0.0)
                .then_some("the RMS roughness must be finite and >= 0 (Moes film units)")
        })?,
        None => vec![0.0],
    };
    let gamma = match axes.get("gamma") {
        Some(v) if axes.get("sigma").is_none() => {
            return Err(cx.err(
                &v.span(),
                "axes.gamma",
                "the roughness orientation needs the axis sigma",
            ))
        }
        Some(v) => cx.axis(v, "axes.gamma", &|x| {
            (!x.is_finite() || x <= 0.0)
                .then_some("the roughness orientation must be finite and > 0")
        })?,
        None => vec![1.0],
    };
    Ok(Axes {
        m,
        l,
        d,
        sigma,
        gamma,
        of_contact,
        span: axes_v.span(),
        l_span: lv.span(),
        d_span: axes.get("D").map(|dv| dv.span()),
    })
}

/// The `[output]` table, defaults where absent.
fn parse_output(cx: &mut Ctx, root: &Table) -> Result<OutputSpec, SpecError> {
    let mut output = OutputSpec {
        dir: PathBuf::from("outputs"),
        batch: 32,
        flush_seconds: 30.0,
    };
    let Some(ov) = root.get("output") else {
        return Ok(output);
    };
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
    Ok(output)
}

/// At most [`MAX_CASES`] cases over all contacts (point cases once per D value).
fn check_case_count(
    cx: &Ctx,
    contacts: &[ContactSpec],
    d: Option<&[f64]>,
    roughness: usize,
    axes_span: &Range<usize>,
) -> Result<(), SpecError> {
    let n_d = d.map_or(1, |d| d.len());
    let n_cases: usize = roughness
        * contacts
            .iter()
            .map(|c| c.m.len() * c.l.len() * if c.contact == Contact::Point { n_d } else { 1 })
            .sum::<usize>();
    if n_cases > MAX_CASES {
        return Err(cx.err(
            axes_span,
            "axes",
            format!("{n_cases} cases: at most {MAX_CASES} per spec"),
        ));
    }
    Ok(())
}

/// The axis D (given at `d_span`) is required by point contacts and an error without them.
fn check_d_axis(
    cx: &Ctx,
    contacts: &[Contact],
    d_span: Option<Range<usize>>,
    axes_span: &Range<usize>,
) -> Result<(), SpecError> {
    let point = contacts.contains(&Contact::Point);
    match (point, d_span) {
        (true, None) => Err(cx.err(
            axes_span,
            "axes.D",
            "missing: contact = \"point\" needs the ellipticity axis D = Rx/Ry, values in (0, 1]",
        )),
        (false, Some(span)) => Err(cx.err(
            &span,
            "axes.D",
            "the ellipticity axis D applies to contact = \"point\" only",
        )),
        _ => Ok(()),
    }
}
