//! The `[numerics]` table of a spec. Its keys apply to every contact of the spec (each starting
//! from [`Numerics::for_contact`]); a mixed spec (`contact = ["line", "point"]`) overrides them
//! for one contact in `[numerics.line]` or `[numerics.point]`, e.g. 2049 line points but 65^2
//! point nodes. Every value is checked against the contact it applies to (the grid range, the
//! half grid of `error_estimate`), and errors name the key that set it. A contact whose
//! numerics name no `grid` is solved to an accuracy target (`accuracy`, default 1 %) by the
//! ladder, up to its largest default grid (16385 line points, 1025 point nodes per direction).
//! `far_field` (point contacts only, default true) chooses the asymptotic far field on the
//! point domain's boundary or, with false, P = 0 there; in the `[numerics]` of a mixed spec it
//! applies to the point cases.

use super::contacts::ContactAxes;
use super::ctx::{join, Ctx, Table};
use super::error::SpecError;
use super::types::{Contact, ContactSpec, Numerics};
use crate::solve::params::{Converge, CycleType};
use crate::strategy::solve_case::{default_max_grid, DEFAULT_ACCURACY};
use std::ops::Range;

/// The settings a `[numerics]` table (or one of its per-contact tables) may hold.
const KEYS: [&str; 10] = [
    "grid",
    "cycle",
    "converge",
    "max_cycles",
    "fallback",
    "tol_load",
    "tol_h",
    "error_estimate",
    "accuracy",
    "far_field",
];

/// Each contact of the spec (with its M and L axes, in the order given) and its numerics.
pub(super) fn parse(
    cx: &mut Ctx,
    root: &Table,
    axes: Vec<ContactAxes>,
) -> Result<Vec<ContactSpec>, SpecError> {
    let contacts: Vec<Contact> = axes.iter().map(|a| a.0).collect();
    let table = match root.get("numerics") {
        Some(v) => Some((cx.table(v, "numerics")?, v.span())),
        None => None,
    };
    if let Some((t, _)) = table {
        let mut allowed = KEYS.to_vec();
        allowed.extend(["line", "point"]);
        cx.keys(t, "numerics", &allowed)?;
        if let (Some(v), false) = (t.get("far_field"), contacts.contains(&Contact::Point)) {
            return Err(cx.err(
                &v.span(),
                "numerics.far_field",
                "applies to point contacts only (the spec has none)",
            ));
        }
        if let Some(v) = t
            .get("line")
            .and_then(|l| l.get_ref().as_table())
            .and_then(|l| l.get("far_field"))
        {
            return Err(cx.err(
                &v.span(),
                "numerics.line.far_field",
                "applies to point contacts only",
            ));
        }
        for c in [Contact::Line, Contact::Point] {
            if let (Some(v), false) = (t.get(c.as_str()), contacts.contains(&c)) {
                return Err(cx.err(
                    &v.span(),
                    &join("numerics", c.as_str()),
                    format!(
                        "the spec has no {} contacts (contact = {:?})",
                        c.as_str(),
                        contacts.iter().map(|c| c.as_str()).collect::<Vec<_>>()
                    ),
                ));
            }
        }
    }
    let mut out = Vec::with_capacity(axes.len());
    for (contact, m, l) in axes {
        let mut n = Numerics::for_contact(contact);
        // The key that switched the error estimate on, for the half-grid check below.
        let mut estimate_key: Option<(Range<usize>, String)> = None;
        let mut grid_named = false;
        if let Some((t, _)) = table {
            apply(cx, t, "numerics", contact, &mut n, &mut estimate_key)?;
            grid_named |= t.get("grid").is_some();
            if let Some(v) = t.get(contact.as_str()) {
                let key = join("numerics", contact.as_str());
                let sub = cx.table(v, &key)?;
                cx.keys(sub, &key, &KEYS)?;
                apply(cx, sub, &key, contact, &mut n, &mut estimate_key)?;
                grid_named |= sub.get("grid").is_some();
            }
        }
        if !grid_named && n.accuracy.is_none() {
            // No grid named: the default accuracy target picks it, up to the ladder's largest.
            n.accuracy = Some(DEFAULT_ACCURACY);
            n.grid = default_max_grid(contact, DEFAULT_ACCURACY);
        } else if !grid_named {
            n.grid = default_max_grid(contact, n.accuracy.unwrap_or(DEFAULT_ACCURACY));
        }
        let grid_min = contact.grid_range().0;
        if let (true, Some((span, key))) = (n.error_estimate, &estimate_key) {
            if n.grid < 2 * grid_min - 1 {
                return Err(cx.err(
                    span,
                    key,
                    format!(
                        "needs grid >= {} for {} contacts (the half grid must have at least \
                         {grid_min} points)",
                        2 * grid_min - 1,
                        contact.as_str()
                    ),
                ));
            }
        }
        out.push(ContactSpec {
            contact,
            m,
            l,
            numerics: n,
        });
    }
    Ok(out)
}

/// Apply the settings of table `t` (at `prefix`) to `n`.
fn apply(
    cx: &mut Ctx,
    t: &Table,
    prefix: &str,
    contact: Contact,
    n: &mut Numerics,
    estimate_key: &mut Option<(Range<usize>, String)>,
) -> Result<(), SpecError> {
    let (grid_min, grid_max) = contact.grid_range();
    if let Some(v) = t.get("grid") {
        let key = join(prefix, "grid");
        n.grid = cx.integer(v, &key, grid_min as i64, grid_max as i64)? as usize;
    }
    if let Some(v) = t.get("cycle") {
        n.cycle = match cx.choice(v, &join(prefix, "cycle"), &["v", "w"])? {
            "v" => CycleType::V,
            _ => CycleType::W,
        };
    }
    if let Some(v) = t.get("converge") {
        n.converge = match cx.choice(v, &join(prefix, "converge"), &["fast", "tight"])? {
            "fast" => Converge::Fast,
            _ => Converge::Tight,
        };
    }
    if let Some(v) = t.get("max_cycles") {
        n.max_cycles = cx.integer(v, &join(prefix, "max_cycles"), 1, 100_000)? as usize;
    }
    if let Some(v) = t.get("fallback") {
        n.fallback = cx.boolean(v, &join(prefix, "fallback"))?;
    }
    for (k, slot) in [("tol_load", &mut n.tol_load), ("tol_h", &mut n.tol_h)] {
        if let Some(v) = t.get(k) {
            let key = join(prefix, k);
            let x = cx.number(v, &key)?;
            if !(x > 0.0 && x < 1.0) {
                return Err(cx.err(
                    &v.span(),
                    &key,
                    format!("{k} = {x} is invalid: must be in (0, 1)"),
                ));
            }
            *slot = x;
        }
    }
    if let Some(v) = t.get("accuracy") {
        let key = join(prefix, "accuracy");
        let x = cx.number(v, &key)?;
        if !(x > 0.0 && x < 1.0) {
            return Err(cx.err(
                &v.span(),
                &key,
                format!("accuracy = {x} is invalid: a relative accuracy in (0, 1), e.g. 0.005"),
            ));
        }
        n.accuracy = Some(x);
    }
    if let (Some(v), Contact::Point) = (t.get("far_field"), contact) {
        n.far_field = cx.boolean(v, &join(prefix, "far_field"))?;
    }
    if let Some(v) = t.get("error_estimate") {
        let key = join(prefix, "error_estimate");
        n.error_estimate = cx.boolean(v, &key)?;
        *estimate_key = Some((v.span(), key));
    }
    Ok(())
}
