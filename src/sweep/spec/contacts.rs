//! The contacts of a spec: `contact = "line"`, `"point"` or `["line", "point"]` (a mixed
//! spec), and the M and L axes of each, the spec's `[axes]` or a contact's own `[axes.line]` /
//! `[axes.point]`.

use super::ctx::{Ctx, Table, Value};
use super::error::SpecError;
use super::types::Contact;

/// One contact with its M and L axes.
pub(super) type ContactAxes = (Contact, Vec<f64>, Vec<f64>);

/// Why an M value is invalid, if it is.
pub(super) fn m_ok(x: f64) -> Option<&'static str> {
    (x <= 0.0).then_some("the load parameter must be > 0")
}

/// Why an L value is invalid, if it is.
pub(super) fn l_ok(x: f64) -> Option<&'static str> {
    (x < 0.0).then_some("the lubricant parameter must be >= 0")
}

/// `contact = "line"`, `"point"` or a list of both (a mixed spec).
pub(super) fn parse_contacts(cx: &Ctx, v: &Value) -> Result<Vec<Contact>, SpecError> {
    let one = |v: &Value| -> Result<Contact, SpecError> {
        Ok(match cx.choice(v, "contact", &["line", "point"])? {
            "line" => Contact::Line,
            _ => Contact::Point,
        })
    };
    let items = match v.get_ref().as_array() {
        None => return Ok(vec![one(v)?]),
        Some(a) => a,
    };
    let mut out = vec![];
    for item in items.iter() {
        let c = one(item)?;
        if out.contains(&c) {
            return Err(cx.err(
                &item.span(),
                "contact",
                format!("\"{}\" is listed twice", c.as_str()),
            ));
        }
        out.push(c);
    }
    if out.is_empty() {
        return Err(cx.err(
            &v.span(),
            "contact",
            "the list is empty: give \"line\", \"point\" or [\"line\", \"point\"]",
        ));
    }
    Ok(out)
}

/// Each contact with its (M, L) axes, in the order given: its own `[axes.<contact>]` values where
/// the spec gives them (M and L separately), else the spec's `m` and `l`.
pub(super) fn contact_axes(
    cx: &mut Ctx,
    axes: &Table,
    contacts: &[Contact],
    m: &[f64],
    l: &[f64],
) -> Result<Vec<ContactAxes>, SpecError> {
    for c in [Contact::Line, Contact::Point] {
        if let (Some(v), false) = (axes.get(c.as_str()), contacts.contains(&c)) {
            return Err(cx.err(
                &v.span(),
                &format!("axes.{}", c.as_str()),
                format!("the spec has no {} contacts", c.as_str()),
            ));
        }
    }
    let mut out = vec![];
    for &c in contacts {
        let (mut cm, mut cl) = (m.to_vec(), l.to_vec());
        if let Some(v) = axes.get(c.as_str()) {
            let key = format!("axes.{}", c.as_str());
            let t = cx.table(v, &key)?;
            cx.keys(t, &key, &["M", "L"])?;
            if let Some(v) = t.get("M") {
                cm = cx.axis(v, &format!("{key}.M"), &m_ok)?;
            }
            if let Some(v) = t.get("L") {
                cl = cx.axis(v, &format!("{key}.L"), &l_ok)?;
            }
        }
        out.push((c, cm, cl));
    }
    Ok(out)
}
