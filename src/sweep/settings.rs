//! The settings that define a row beyond its (M, L, D): the models and each contact's numerics.
//! A dataset holds rows of one set of settings; a run whose spec would add rows of other
//! settings to it refuses to start (see [`crate::sweep::dataset`]).
//!
//! [`Settings`] is an ordered list of `key=value` pairs: `models.elasticity`,
//! `models.viscosity`, `models.z`, `models.eta0`, `models.ph`, `models.density`, then per contact
//! of the spec (line first) `<contact>.grid`, `.cycle`, `.converge`, `.max_cycles`, `.fallback`,
//! `.tol_load`, `.tol_h`, `.error_estimate` and `.accuracy` (and `point.far_field`; a footer
//! written before it existed reads as `false`, the truncated domain its rows had), and for a spec with rough cases
//! (an axis sigma with a value > 0) `models.slide_roll`, `models.variance_ratio_1`,
//! `models.ph_over_e`, `models.eta_beta_sigma`, `models.sigma_over_beta` (floats in Rust's shortest
//! round-trip `{:e}` form, `-` for a value not given). Not in it: the axes' values (adding axis
//! values only adds cases), the sweep's name, `[output]`, threads and shards. Its text is stored
//! in every part file's footer as `spec_settings`, its 64-bit FNV-1a hash as `spec_hash`.
//!
//! Two settings conflict on the keys both hold with different values: a spec that only adds a
//! contact (a point axis to a line dataset) does not conflict with the rows stored.
//! [`Settings::of_row`] reads the same keys back from a row's input columns, so that datasets
//! written before the footer held `spec_settings` (or re-saved without the footer) are checked
//! too.

use crate::model::lubricant::Density;
use crate::store::results::CaseRow;
use crate::sweep::plan::{fnv1a64, id_hex};
use crate::sweep::spec::{Contact, Numerics, SweepSpec, ViscositySpec};
use std::fmt;

/// The row-defining settings of a spec, a dataset part or a row (module docs).
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Settings {
    /// `(key, value)` in a fixed order.
    pub entries: Vec<(String, String)>,
}

/// One setting that differs: the key, the value here and the value there.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Difference {
    /// The setting, e.g. `line.grid`.
    pub key: String,
    /// Its value in the settings asked (`self` of [`Settings::conflicts`]).
    pub ours: String,
    /// Its value in the other settings.
    pub theirs: String,
}

fn float(x: f64) -> String {
    format!("{x:e}")
}

fn opt_float(x: Option<f64>) -> String {
    x.map_or("-".to_string(), float)
}

impl Settings {
    fn push(&mut self, key: impl Into<String>, value: impl Into<String>) {
        self.entries.push((key.into(), value.into()));
    }

    /// The six model settings.
    fn models(
        elasticity: &str,
        viscosity: &str,
        z: Option<f64>,
        eta0: Option<f64>,
        ph: Option<f64>,
        density: &str,
    ) -> Settings {
        let mut s = Settings::default();
        s.push("models.elasticity", elasticity);
        s.push("models.viscosity", viscosity);
        s.push("models.z", opt_float(z));
        s.push("models.eta0", opt_float(eta0));
        s.push("models.ph", opt_float(ph));
        s.push("models.density", density);
        s
    }

    /// The numerics of one contact.
    fn contact(&mut self, contact: Contact, n: &Numerics) {
        let c = contact.as_str();
        self.push(format!("{c}.grid"), n.grid.to_string());
        self.push(format!("{c}.cycle"), n.cycle.as_str());
        self.push(format!("{c}.converge"), n.converge.as_str());
        self.push(format!("{c}.max_cycles"), n.max_cycles.to_string());
        self.push(format!("{c}.fallback"), n.fallback.to_string());
        self.push(format!("{c}.tol_load"), float(n.tol_load));
        self.push(format!("{c}.tol_h"), float(n.tol_h));
        self.push(format!("{c}.error_estimate"), n.error_estimate.to_string());
        self.push(format!("{c}.accuracy"), opt_float(n.accuracy));
        if contact == Contact::Point {
            self.push("point.far_field", n.far_field.to_string());
        }
    }

    /// The settings of a validated spec: its models and the numerics of each of its contacts.
    pub fn of_spec(spec: &SweepSpec) -> Settings {
        let (viscosity, z, eta0, ph_v) = match spec.viscosity {
            ViscositySpec::Barus => ("barus", None, None, None),
            ViscositySpec::RoelandsZ { z, ph_pa } => ("roelands", Some(z), None, Some(ph_pa)),
            ViscositySpec::RoelandsEta0 { eta0, ph_pa } => {
                ("roelands", None, Some(eta0), Some(ph_pa))
            }
        };
        let ph_d = match spec.density {
            Density::Incompressible => None,
            Density::DowsonHigginson { ph_pa } => Some(ph_pa),
        };
        let mut s = Settings::models(
            spec.elasticity.as_str(),
            viscosity,
            z,
            eta0,
            ph_v.or(ph_d),
            spec.density.name(),
        );
        if spec.sigma.iter().any(|&x| x > 0.0) {
            let r = &spec.roughness;
            s.push("models.slide_roll", float(r.slide_roll));
            s.push("models.variance_ratio_1", float(r.variance_ratio_1));
            s.push("models.ph_over_e", float(r.ph_over_e));
            s.push("models.eta_beta_sigma", float(r.asperity.eta_beta_sigma));
            s.push("models.sigma_over_beta", float(r.asperity.sigma_over_beta));
        }
        for contact in [Contact::Line, Contact::Point] {
            if let Some(n) = spec.numerics(contact) {
                s.contact(contact, n);
            }
        }
        s
    }

    /// The settings a row was solved with, from its input columns (its contact's numerics
    /// only). Roelands' z is a setting only when the spec gave it: with `eta0` it is derived per
    /// case.
    pub fn of_row(row: &CaseRow) -> Settings {
        let z = if row.eta0.is_some() { None } else { row.z };
        let mut s = Settings::models(
            row.elasticity.as_str(),
            &row.viscosity,
            z,
            row.eta0,
            row.ph,
            &row.density,
        );
        let n = Numerics {
            grid: usize::try_from(row.grid_requested).unwrap_or(0),
            cycle: row.cycle,
            converge: row.converge,
            max_cycles: usize::try_from(row.max_cycles).unwrap_or(0),
            fallback: row.fallback,
            tol_load: row.tol_load,
            tol_h: row.tol_h,
            error_estimate: row.half_grid_estimate,
            accuracy: row.accuracy,
            far_field: row.far_field,
        };
        s.contact(row.contact, &n);
        s
    }

    /// Parse the text of [`fmt::Display`] (`key=value;key=value`); `None` when it is not one.
    pub fn parse(text: &str) -> Option<Settings> {
        let mut s = Settings::default();
        for kv in text.split(';').filter(|kv| !kv.is_empty()) {
            let (k, v) = kv.split_once('=')?;
            if k.is_empty() {
                return None;
            }
            s.push(k, v);
        }
        // Written before the point far field existed: those point rows had P = 0 on the
        // boundary.
        if s.get("point.grid").is_some() && s.get("point.far_field").is_none() {
            s.push("point.far_field", "false");
        }
        (!s.entries.is_empty()).then_some(s)
    }

    /// 16 hex digits: the 64-bit FNV-1a hash of the text (the footer's `spec_hash`).
    pub fn hash(&self) -> String {
        id_hex(fnv1a64(self.to_string().as_bytes()))
    }

    /// The value of `key`, when present.
    pub fn get(&self, key: &str) -> Option<&str> {
        self.entries
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }

    /// The keys both settings hold with different values, in this one's order (empty: the two
    /// may share a dataset).
    pub fn conflicts(&self, other: &Settings) -> Vec<Difference> {
        self.entries
            .iter()
            .filter_map(|(k, v)| {
                let theirs = other.get(k)?;
                (theirs != v).then(|| Difference {
                    key: k.clone(),
                    ours: v.clone(),
                    theirs: theirs.to_string(),
                })
            })
            .collect()
    }
}

impl fmt::Display for Settings {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, (k, v)) in self.entries.iter().enumerate() {
            if i > 0 {
                f.write_str(";")?;
            }
            write!(f, "{k}={v}")?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::plan::plan;
    use crate::sweep::row::input_row;
    use crate::sweep::spec::parse;

    const MIXED: &str = "contact = [\"line\", \"point\"]\n[axes]\nM = [10, 100]\nL = [2, 10]\n\
                         D = [0.5, 1]\n[numerics]\ntol_h = 1e-5\n[numerics.point]\ngrid = 65\n";

    /// Every row's settings are those of its spec: a spec's own rows never conflict with it.
    #[test]
    fn rows_carry_their_spec_settings() {
        let models = [
            "",
            "[models]\nviscosity = \"roelands\"\nz = 0.6\nph = 1e9\n",
            "[models]\nviscosity = \"roelands\"\neta0 = 0.05\nph = 1.2e9\ndensity = \"dowson-higginson\"\n",
            "[models]\nelasticity = \"rigid\"\ndensity = \"dowson-higginson\"\nph = 5e8\n",
        ];
        let numerics = [
            "",
            "[numerics.line]\naccuracy = 0.01\nerror_estimate = true\n",
            "far_field = false\n", // into MIXED's [numerics.point]
        ];
        for m in models {
            for n in numerics {
                let text = MIXED.replace("[numerics]", &format!("{m}[numerics]")) + n;
                let spec = parse("s.toml", &text, "s").unwrap();
                let settings = Settings::of_spec(&spec);
                assert_eq!(
                    Settings::parse(&settings.to_string()),
                    Some(settings.clone())
                );
                for c in plan(&spec).unwrap() {
                    let row = Settings::of_row(&input_row(&c, "s"));
                    assert_eq!(row.conflicts(&settings), vec![], "{text}");
                    let point = usize::from(c.contact == Contact::Point);
                    assert_eq!(row.entries.len(), 15 + point);
                    assert!(row.entries.iter().all(|e| settings.entries.contains(e)));
                }
            }
        }
    }

    #[test]
    fn numerics_conflict_axes_and_added_contacts_do_not() {
        let base = parse("s.toml", MIXED, "s").unwrap();
        let s = Settings::of_spec(&base);
        assert_eq!(s.entries.len(), 6 + 2 * 9 + 1);
        assert_eq!(s.get("point.grid"), Some("65"));
        assert_eq!(s.get("line.tol_h"), Some("1e-5"));
        // Pinned: a change here makes every stored dataset conflict with its own spec.
        assert_eq!(
            s.to_string(),
            "models.elasticity=elastic;models.viscosity=barus;models.z=-;models.eta0=-;\
             models.ph=-;models.density=incompressible;line.grid=16385;line.cycle=v;\
             line.converge=fast;line.max_cycles=60;line.fallback=true;line.tol_load=1e-7;\
             line.tol_h=1e-5;line.error_estimate=false;line.accuracy=1e-2;point.grid=65;\
             point.cycle=v;point.converge=fast;point.max_cycles=60;point.fallback=true;\
             point.tol_load=1e-7;point.tol_h=1e-5;point.error_estimate=false;point.accuracy=-;\
             point.far_field=true"
        );
        // A footer written before the far field existed: its point rows had P = 0 on the
        // boundary, a conflict with today's default.
        let old = s.to_string().replace(";point.far_field=true", "");
        let d = s.conflicts(&Settings::parse(&old).unwrap());
        assert_eq!(
            d,
            vec![Difference {
                key: "point.far_field".into(),
                ours: "true".into(),
                theirs: "false".into()
            }]
        );
        // Other axis values: same settings, same hash.
        let more = parse("s.toml", &MIXED.replace("[10, 100]", "[1, 10, 100]"), "s").unwrap();
        assert_eq!(Settings::of_spec(&more).hash(), s.hash());
        // A grid: a conflict naming the key and both values.
        let fine = parse("s.toml", &MIXED.replace("grid = 65", "grid = 129"), "s").unwrap();
        let d = Settings::of_spec(&fine).conflicts(&s);
        assert_eq!(
            d,
            vec![Difference {
                key: "point.grid".into(),
                ours: "129".into(),
                theirs: "65".into()
            }]
        );
        // A line-only dataset and a mixed spec of the same line settings share a dataset.
        let line = MIXED
            .replace("[\"line\", \"point\"]", "\"line\"")
            .replace("D = [0.5, 1]\n", "")
            .replace("[numerics.point]\ngrid = 65\n", "");
        let line = Settings::of_spec(&parse("l.toml", &line, "l").unwrap());
        assert!(line.conflicts(&s).is_empty() && s.conflicts(&line).is_empty());
        assert_ne!(line.hash(), s.hash());
        assert_eq!(Settings::parse("garbage"), None);
        assert_eq!(Settings::parse(""), None);
    }
}
