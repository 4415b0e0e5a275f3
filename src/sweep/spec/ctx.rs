//! Reading spec values with their positions: [`Ctx`] turns TOML values into numbers, strings,
//! choices and axes, and every error into a [`SpecError`] naming the file, line and key.

use super::axes::{canonical, expand_range, MAX_AXIS_VALUES};
use super::error::SpecError;
use std::collections::BTreeMap;
use std::ops::Range;
use toml::de::{DeTable, DeValue};
use toml::Spanned;

pub(super) struct Ctx<'a> {
    pub file: &'a str,
    pub text: &'a str,
    pub lines: BTreeMap<String, usize>,
}

pub(super) type Table<'i> = DeTable<'i>;
pub(super) type Value<'i> = Spanned<DeValue<'i>>;

impl Ctx<'_> {
    pub(super) fn line(&self, span: &Range<usize>) -> usize {
        let end = span.start.min(self.text.len());
        self.text.as_bytes()[..end]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
            + 1
    }

    pub(super) fn err(
        &self,
        span: &Range<usize>,
        key: &str,
        message: impl Into<String>,
    ) -> SpecError {
        SpecError {
            file: self.file.to_string(),
            line: self.line(span),
            key: key.to_string(),
            message: message.into(),
        }
    }

    /// Check that `t` has only `allowed` keys; record their lines.
    pub(super) fn keys(
        &mut self,
        t: &Table,
        prefix: &str,
        allowed: &[&str],
    ) -> Result<(), SpecError> {
        for (k, _) in t.iter() {
            let name = k.get_ref().as_ref();
            let path = join(prefix, name);
            if !allowed.contains(&name) {
                let want = allowed.join(", ");
                return Err(self.err(
                    &k.span(),
                    &path,
                    format!("unknown key (expected one of: {want})"),
                ));
            }
            let line = self.line(&k.span());
            self.lines.insert(path, line);
        }
        Ok(())
    }

    pub(super) fn number(&self, v: &Value, key: &str) -> Result<f64, SpecError> {
        let x = match v.get_ref() {
            DeValue::Integer(i) => i64::from_str_radix(i.as_str(), i.radix())
                .ok()
                .map(|n| n as f64),
            DeValue::Float(f) => f.as_str().parse::<f64>().ok(),
            other => {
                return Err(self.err(
                    &v.span(),
                    key,
                    format!("expected a number, found a {}", other.type_str()),
                ))
            }
        };
        match x {
            Some(x) if x.is_finite() => Ok(x),
            _ => Err(self.err(&v.span(), key, "the number must be finite")),
        }
    }

    pub(super) fn integer(
        &self,
        v: &Value,
        key: &str,
        min: i64,
        max: i64,
    ) -> Result<i64, SpecError> {
        let n = match v.get_ref() {
            DeValue::Integer(i) => i64::from_str_radix(i.as_str(), i.radix()).ok(),
            other => {
                return Err(self.err(
                    &v.span(),
                    key,
                    format!("expected an integer, found a {}", other.type_str()),
                ))
            }
        };
        match n {
            Some(n) if (min..=max).contains(&n) => Ok(n),
            _ => Err(self.err(
                &v.span(),
                key,
                format!("must be an integer from {min} to {max}"),
            )),
        }
    }

    pub(super) fn string<'v>(&self, v: &'v Value, key: &str) -> Result<&'v str, SpecError> {
        v.get_ref().as_str().ok_or_else(|| {
            self.err(
                &v.span(),
                key,
                format!("expected a string, found a {}", v.get_ref().type_str()),
            )
        })
    }

    pub(super) fn choice<'v>(
        &self,
        v: &'v Value,
        key: &str,
        options: &[&str],
    ) -> Result<&'v str, SpecError> {
        let s = self.string(v, key)?;
        if options.contains(&s) {
            Ok(s)
        } else {
            Err(self.err(
                &v.span(),
                key,
                format!("\"{s}\" is not one of: {}", options.join(", ")),
            ))
        }
    }

    pub(super) fn boolean(&self, v: &Value, key: &str) -> Result<bool, SpecError> {
        v.get_ref().as_bool().ok_or_else(|| {
            self.err(
                &v.span(),
                key,
                format!("expected true or false, found a {}", v.get_ref().type_str()),
            )
        })
    }

    pub(super) fn table<'v, 'i>(
        &self,
        v: &'v Value<'i>,
        key: &str,
    ) -> Result<&'v Table<'i>, SpecError> {
        v.get_ref().as_table().ok_or_else(|| {
            self.err(
                &v.span(),
                key,
                format!("expected a table, found a {}", v.get_ref().type_str()),
            )
        })
    }

    /// Expand one axis: a non-empty list of numbers or a range table. `check` validates each value
    /// (returns the reason when it is invalid).
    pub(super) fn axis(
        &mut self,
        v: &Value,
        key: &str,
        check: &dyn Fn(f64) -> Option<&'static str>,
    ) -> Result<Vec<f64>, SpecError> {
        let short = key.rsplit('.').next().unwrap_or(key);
        let bad = |ctx: &Ctx, span: &Range<usize>, x: f64, why: &str| {
            ctx.err(span, key, format!("{short} = {x} is invalid: {why}"))
        };
        let values = match v.get_ref() {
            DeValue::Array(a) => {
                if a.is_empty() {
                    return Err(self.err(&v.span(), key, "the axis is empty"));
                }
                if a.len() > MAX_AXIS_VALUES {
                    return Err(self.err(
                        &v.span(),
                        key,
                        format!("more than {MAX_AXIS_VALUES} values"),
                    ));
                }
                let mut out = Vec::with_capacity(a.len());
                for item in a.iter() {
                    let x = self.number(item, key)?;
                    if let Some(why) = check(x) {
                        return Err(bad(self, &item.span(), x, why));
                    }
                    out.push(canonical(x));
                }
                out
            }
            DeValue::Table(t) => {
                self.keys(t, key, &["from", "to", "count", "scale"])?;
                let get = |name: &str| {
                    t.get(name).ok_or_else(|| {
                        self.err(
                            &v.span(),
                            key,
                            format!("a range needs `from`, `to` and `count` (missing `{name}`)"),
                        )
                    })
                };
                let (fv, tv, cv) = (get("from")?, get("to")?, get("count")?);
                let from = self.number(fv, &join(key, "from"))?;
                let to = self.number(tv, &join(key, "to"))?;
                let count =
                    self.integer(cv, &join(key, "count"), 1, MAX_AXIS_VALUES as i64)? as usize;
                let log = match t.get("scale") {
                    None => false,
                    Some(s) => self.choice(s, &join(key, "scale"), &["linear", "log"])? == "log",
                };
                for (x, sv) in [(from, fv), (to, tv)] {
                    if let Some(why) = check(x) {
                        return Err(bad(self, &sv.span(), x, why));
                    }
                }
                if count == 1 && from != to {
                    return Err(self.err(
                        &cv.span(),
                        &join(key, "count"),
                        format!("count = 1 needs from = to (got {from} and {to})"),
                    ));
                }
                if count > 1 && from == to {
                    return Err(self.err(
                        &cv.span(),
                        &join(key, "count"),
                        format!("from = to = {from} with count = {count} repeats one value"),
                    ));
                }
                if log && (from <= 0.0 || to <= 0.0) {
                    return Err(self.err(
                        &v.span(),
                        &join(key, "scale"),
                        format!("a log range needs from > 0 and to > 0 (got {from} and {to})"),
                    ));
                }
                expand_range(from, to, count, log)
            }
            other => {
                return Err(self.err(
                    &v.span(),
                    key,
                    format!(
                        "expected a list of numbers or a range table {{ from, to, count, scale }}, found a {}",
                        other.type_str()
                    ),
                ))
            }
        };
        Ok(values)
    }
}

pub(super) fn join(prefix: &str, name: &str) -> String {
    if prefix.is_empty() {
        name.to_string()
    } else {
        format!("{prefix}.{name}")
    }
}
