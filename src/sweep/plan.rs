//! Expand a validated spec into cases, each with a stable id, ordered largest cost first, and
//! slice them into shards.
//!
//! The case id is the 64-bit FNV-1a hash of [`Case::canonical`], a string of every physical
//! parameter, model and numerical setting that can change a result (floats in Rust's shortest
//! round-trip `{:e}` form), printed as 16 hex digits. The sweep name, output settings and thread
//! count are not part of it. Shard `i/n` holds the cases whose mixed id is `i - 1` modulo `n`,
//! so the shards partition the sweep, and a case stays in its shard when the spec gains values.

use crate::model::case::{LineCase, Models, ParamError, PointCase};
use crate::model::lubricant::{Density, Viscosity};
use crate::model::roughness::Roughness;
use crate::sweep::spec::{Contact, ContactSpec, Numerics, SpecError, SweepSpec, ViscositySpec};
use std::collections::HashSet;
use std::fmt;

/// A shard argument that is not `i/n` with 1 <= i <= n.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct ShardError(pub String);

/// Version tag of the canonical string: bump it when the meaning of a setting changes.
const CANON_VERSION: &str = "ehlmap-case-v2";

/// One case to solve.
#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    /// Case id: FNV-1a of [`Case::canonical`].
    pub id: u64,
    /// Line or point.
    pub contact: Contact,
    /// Moes load parameter M.
    pub m: f64,
    /// Moes lubricant parameter L.
    pub l: f64,
    /// Ellipticity D = Rx/Ry (point contacts only).
    pub d: Option<f64>,
    /// The solver's models, with Roelands' z resolved for this case.
    pub models: Models,
    /// The ambient viscosity (Pa s) the Roelands z was derived from, when the spec gave eta0.
    pub eta0: Option<f64>,
    /// Numerical settings of the solve.
    pub numerics: Numerics,
    /// Relative cost estimate used to order the work (largest first).
    pub cost: f64,
}

/// 64-bit FNV-1a.
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h ^= b as u64;
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

/// The id as 16 lower-case hex digits.
pub fn id_hex(id: u64) -> String {
    format!("{id:016x}")
}

impl Case {
    /// The canonical description that the id hashes.
    pub fn canonical(&self) -> String {
        let n = &self.numerics;
        let visc = match self.models.viscosity {
            Viscosity::Barus => "barus".to_string(),
            Viscosity::Roelands { z, ph_pa } => format!("roelands(z={z:e},ph={ph_pa:e})"),
        };
        let dens = match self.models.density {
            Density::Incompressible => "incompressible".to_string(),
            Density::DowsonHigginson { ph_pa } => format!("dowson-higginson(ph={ph_pa:e})"),
        };
        let d = self.d.map_or("-".to_string(), |d| format!("{d:e}"));
        format!(
            "{CANON_VERSION};contact={};M={:e};L={:e};D={d};elasticity={};viscosity={visc};\
             density={dens};grid={};cycle={};converge={};max_cycles={};fallback={};tol_load={:e};\
             tol_h={:e};error_estimate={}",
            self.contact.as_str(),
            self.m,
            self.l,
            self.models.elasticity,
            n.grid,
            n.cycle.as_str(),
            n.converge.as_str(),
            n.max_cycles,
            n.fallback,
            n.tol_load,
            n.tol_h,
            n.error_estimate
        ) + &n
            .accuracy
            .map_or(String::new(), |a| format!(";accuracy={a:e}"))
            + if n.far_field { ";far_field=true" } else { "" }
            + &self
                .models
                .roughness
                .filter(|r| r.is_rough())
                .map_or(String::new(), |r| {
                    format!(
                        ";sigma={:e};gamma={:e};slide_roll={:e};vr1={:e};ebs={:e};sb={:e};phe={:e}",
                        r.sigma,
                        r.gamma,
                        r.slide_roll,
                        r.variance_ratio_1,
                        r.asperity.eta_beta_sigma,
                        r.asperity.sigma_over_beta,
                        r.ph_over_e
                    )
                })
    }

    /// The id as 16 lower-case hex digits (the `case_id` column).
    pub fn id_hex(&self) -> String {
        id_hex(self.id)
    }

    /// The same case at another M, with its own id (a warm-start neighbour).
    pub fn with_m(&self, m: f64) -> Case {
        let mut c = self.clone();
        c.m = m;
        c.id = fnv1a64(c.canonical().as_bytes());
        c
    }

    /// The line case to hand to the solver.
    pub fn line_case(&self) -> Result<LineCase, ParamError> {
        LineCase::with_models(self.m, self.l, self.models)
    }

    /// The case to hand to the solver, line or point.
    pub fn case(&self) -> Result<crate::model::case::Case, ParamError> {
        match self.contact {
            Contact::Line => self.line_case().map(crate::model::case::Case::Line),
            Contact::Point => self.point_case().map(crate::model::case::Case::Point),
        }
    }

    /// The point case to hand to the solver (an error when the case has no D).
    pub fn point_case(&self) -> Result<PointCase, ParamError> {
        let d = self.d.unwrap_or(f64::NAN);
        PointCase::with_models(self.m, self.l, d, self.models)
    }
}

impl fmt::Display for Case {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} {} M={} L={}",
            self.id_hex(),
            self.contact.as_str(),
            self.m,
            self.l
        )?;
        if let Some(d) = self.d {
            write!(f, " D={d}")?;
        }
        Ok(())
    }
}

/// Cost model, only its order matters (in units of about 10 us of one core, so that the line and
/// point costs of a mixed spec compare): linear in the grid, slowly growing with M, and steeply
/// growing at M ~ 1 with large L (measured at 2049 points: M = 1 costs 1.2 s at L <= 4, 2.5 s at
/// L = 12 and 19 s at L = 20, against 0.3-1.5 s elsewhere), so those start first.
fn cost(m: f64, l: f64, n: &Numerics) -> f64 {
    let low_m = ((l - 12.0) / 3.0).exp() / (m * m * m).max(1e-6);
    let base = n.grid as f64 * (1.0 + 0.1 * (1.0 + m).ln()) * (1.0 + low_m);
    if n.error_estimate {
        1.5 * base
    } else {
        base
    }
}

/// Point contacts: each solve costs about grid^2 log2(grid) (the FFT deformation product on
/// grid x grid nodes), growing slowly with M; the half-grid twin of `error_estimate` adds about a
/// quarter (129^2 nodes: about 1.2e5 units, 0.9 s; 2049 line points: 2.3e3 units, 21 ms).
fn point_cost(m: f64, n: &Numerics) -> f64 {
    let g = n.grid as f64;
    let base = g * g * g.log2() * (1.0 + 0.1 * (1.0 + m).ln());
    if n.error_estimate {
        1.25 * base
    } else {
        base
    }
}

/// Every case of the spec, largest cost first (ties by id), duplicates removed. Fails (naming the
/// spec key) when a combination of values is not a valid case.
pub fn plan(spec: &SweepSpec) -> Result<Vec<Case>, SpecError> {
    let mut cases = vec![];
    let mut seen = HashSet::new();
    for cs in &spec.contacts {
        let ds: Vec<Option<f64>> = match (cs.contact, &spec.d) {
            (Contact::Line, _) => vec![None],
            (Contact::Point, Some(d)) => d.iter().map(|&d| Some(d)).collect(),
            (Contact::Point, None) => {
                return Err(spec.error("axes.D", "missing: point contacts need the axis D"))
            }
        };
        // sigma = 0 is one smooth case whatever gamma: the duplicates go by their id.
        let roughness: Vec<Option<Roughness>> = spec
            .sigma
            .iter()
            .flat_map(|&s| {
                spec.gamma.iter().map(move |&g| {
                    (s > 0.0).then_some(Roughness {
                        sigma: s,
                        gamma: g,
                        ..spec.roughness
                    })
                })
            })
            .collect();
        for &m in &cs.m {
            for &l in &cs.l {
                for &d in &ds {
                    for &r in &roughness {
                        let c = plan_case(spec, cs, m, l, d, r)?;
                        if seen.insert(c.id) {
                            cases.push(c);
                        }
                    }
                }
            }
        }
    }
    cases.sort_by(|a, b| b.cost.total_cmp(&a.cost).then(a.id.cmp(&b.id)));
    Ok(cases)
}

/// The case of one (M, L, D) combination (D for point contacts only), with its id and cost.
fn plan_case(
    spec: &SweepSpec,
    cs: &ContactSpec,
    m: f64,
    l: f64,
    d: Option<f64>,
    roughness: Option<Roughness>,
) -> Result<Case, SpecError> {
    let at = match d {
        Some(d) => format!("at M = {m}, L = {l}, D = {d}"),
        None => format!("at M = {m}, L = {l}"),
    };
    let alpha_bar = match d {
        None => LineCase::new(m, l).map(|c| c.venner().alpha_bar),
        Some(d) => PointCase::new(m, l, d).map(|c| c.venner().alpha_bar),
    }
    .map_err(|e| spec.error("axes", e.to_string()))?;
    let (viscosity, eta0) = match spec.viscosity {
        ViscositySpec::Barus => (Viscosity::Barus, None),
        ViscositySpec::RoelandsZ { z, ph_pa } => (Viscosity::Roelands { z, ph_pa }, None),
        ViscositySpec::RoelandsEta0 { eta0, ph_pa } => (
            Viscosity::roelands_from_eta0(eta0, ph_pa, alpha_bar)
                .map_err(|e| spec.error("models.eta0", format!("{at}: {e}")))?,
            Some(eta0),
        ),
    };
    let models = Models {
        elasticity: spec.elasticity,
        viscosity,
        density: spec.density,
        roughness,
    };
    let mut c = Case {
        id: 0,
        contact: cs.contact,
        m,
        l,
        d,
        models,
        eta0,
        numerics: cs.numerics,
        // Rough surfaces: the fixed point's resumed solves and the smooth twin, about 3x.
        cost: match d {
            None => cost(m, l, &cs.numerics),
            Some(_) => point_cost(m, &cs.numerics),
        } * if roughness.is_some() { 3.0 } else { 1.0 },
    };
    match d {
        None => c.line_case().map(|_| ()),
        Some(_) => c.point_case().map(|_| ()),
    }
    .map_err(|e| spec.error("models", format!("{at}: {e}")))?;
    c.id = fnv1a64(c.canonical().as_bytes());
    Ok(c)
}

/// A deterministic slice `index/count` (1-based) of a sweep.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// Which slice, 1-based, `1 <= index <= count`.
    pub index: usize,
    /// Number of slices.
    pub count: usize,
}

impl Shard {
    /// The whole sweep, `1/1`.
    pub const WHOLE: Shard = Shard { index: 1, count: 1 };

    /// Parse `i/n` with 1 <= i <= n.
    pub fn parse(s: &str) -> Result<Shard, ShardError> {
        let (i, n) = s
            .split_once('/')
            .ok_or_else(|| ShardError(format!("--shard {s}: expected i/n, e.g. 1/4")))?;
        let i: usize = i
            .trim()
            .parse()
            .map_err(|_| ShardError(format!("--shard {s}: i is not a positive integer")))?;
        let n: usize = n
            .trim()
            .parse()
            .map_err(|_| ShardError(format!("--shard {s}: n is not a positive integer")))?;
        if n == 0 || i == 0 || i > n {
            return Err(ShardError(format!("--shard {s}: needs 1 <= i <= n")));
        }
        Ok(Shard { index: i, count: n })
    }

    /// Does this shard hold the case with this id?
    pub fn contains(&self, id: u64) -> bool {
        (mix(id) % self.count as u64) as usize == self.index - 1
    }

    /// File-name label, e.g. `2of4`.
    pub fn label(&self) -> String {
        format!("{}of{}", self.index, self.count)
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// SplitMix64 finaliser: spreads the FNV bits so that `id mod n` balances shards.
fn mix(mut x: u64) -> u64 {
    x ^= x >> 30;
    x = x.wrapping_mul(0xbf58_476d_1ce4_e5b9);
    x ^= x >> 27;
    x = x.wrapping_mul(0x94d0_49bb_1331_11eb);
    x ^ (x >> 31)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::spec::parse;

    #[test]
    fn fnv_reference_values() {
        assert_eq!(fnv1a64(b""), 0xcbf29ce484222325);
        assert_eq!(fnv1a64(b"a"), 0xaf63dc4c8601ec8c);
        assert_eq!(fnv1a64(b"foobar"), 0x85944171f73967e8);
    }

    #[test]
    fn ids_are_stable_and_shards_partition() {
        let text = "contact = \"line\"\n[axes]\nM = { from = 1, to = 1000, count = 16, scale = \"log\" }\nL = [0, 5, 10]\n";
        let spec = parse("t.toml", text, "t").unwrap();
        let cases = plan(&spec).unwrap();
        assert_eq!(cases.len(), 48);
        // The id depends on the physics and numerics only, not on the order of the axes.
        let text2 = "contact = \"line\"\n[axes]\nL = [10, 5, 0]\nM = { from = 1, to = 1000, count = 16, scale = \"log\" }\n";
        let mut a: Vec<u64> = cases.iter().map(|c| c.id).collect();
        let mut b: Vec<u64> = plan(&parse("u.toml", text2, "u").unwrap())
            .unwrap()
            .iter()
            .map(|c| c.id)
            .collect();
        a.sort();
        b.sort();
        assert_eq!(a, b);
        // A warm-start neighbour is the planned case at that M: same id as the plan gives it.
        let c10 = cases.iter().find(|c| c.m == 10.0 && c.l == 5.0).unwrap();
        let c1 = cases.iter().find(|c| c.m == 1.0 && c.l == 5.0).unwrap();
        assert_eq!(c10.with_m(1.0).id, c1.id);
        assert_eq!(
            c10.with_m(1.0),
            Case {
                cost: c10.cost,
                ..c1.clone()
            }
        );
        assert_eq!(c10.with_m(10.0).id, c10.id);
        // Pinned: a change here silently re-solves every stored dataset.
        let c = cases.iter().find(|c| c.m == 1.0 && c.l == 0.0).unwrap();
        assert_eq!(
            c.canonical(),
            "ehlmap-case-v2;contact=line;M=1e0;L=0e0;D=-;elasticity=elastic;viscosity=barus;\
             density=incompressible;grid=16385;cycle=v;converge=fast;max_cycles=60;fallback=true;\
             tol_load=1e-7;tol_h=1e-6;error_estimate=false;accuracy=1e-2"
        );
        assert_eq!(c.id_hex(), id_hex(fnv1a64(c.canonical().as_bytes())));
        // Largest cost first.
        assert!(cases.windows(2).all(|w| w[0].cost >= w[1].cost));
        assert_eq!(cases[0].m, 1000.0);
        let pos = |m: f64, l: f64| cases.iter().position(|c| c.m == m && c.l == l).unwrap();
        assert!(pos(1.0, 10.0) < pos(1.0, 0.0));
        for n in 1..5 {
            let mut total = 0;
            for i in 1..=n {
                let s = Shard { index: i, count: n };
                total += cases.iter().filter(|c| s.contains(c.id)).count();
            }
            assert_eq!(total, cases.len());
        }
        assert!(Shard::parse("0/2").is_err() && Shard::parse("3/2").is_err());
        assert_eq!(Shard::parse("2/3").unwrap(), Shard { index: 2, count: 3 });
    }

    #[test]
    fn point_cases_hash_d_and_cost_by_grid_squared() {
        let text = "contact = \"point\"\n[axes]\nM = [10, 100]\nL = [0, 10]\nD = [0.5, 1]\n";
        let spec = parse("p.toml", text, "p").unwrap();
        let cases = plan(&spec).unwrap();
        assert_eq!(cases.len(), 8);
        let ids: HashSet<u64> = cases.iter().map(|c| c.id).collect();
        assert_eq!(ids.len(), 8, "D is part of the id");
        assert!(cases
            .iter()
            .all(|c| c.contact == Contact::Point && c.d.is_some()));
        let c = cases
            .iter()
            .find(|c| c.m == 10.0 && c.l == 0.0 && c.d == Some(0.5))
            .unwrap();
        // Pinned like the line string above.
        assert_eq!(
            c.canonical(),
            "ehlmap-case-v2;contact=point;M=1e1;L=0e0;D=5e-1;elasticity=elastic;viscosity=barus;\
             density=incompressible;grid=1025;cycle=v;converge=fast;max_cycles=60;fallback=true;\
             tol_load=1e-7;tol_h=1e-6;error_estimate=false;accuracy=1e-2;far_field=true"
        );
        // The truncated domain keeps the ids it had before the far field existed.
        let truncated = parse(
            "p.toml",
            &format!("{text}[numerics]\nfar_field = false\n"),
            "p",
        )
        .unwrap();
        let t = plan(&truncated).unwrap();
        let t = t
            .iter()
            .find(|t| t.m == c.m && t.l == c.l && t.d == c.d)
            .unwrap();
        assert_eq!(
            t.canonical(),
            c.canonical().strip_suffix(";far_field=true").unwrap()
        );
        assert!(c.point_case().is_ok() && c.line_case().is_ok());
        assert!(cases.windows(2).all(|w| w[0].cost >= w[1].cost));
        assert!(cases[0].m == 100.0);
        // Doubling the grid costs about four times as much (grid^2 log grid).
        let on = |g: usize| {
            let spec = parse("p.toml", &format!("{text}[numerics]\ngrid = {g}\n"), "p").unwrap();
            plan(&spec).unwrap()[0].cost
        };
        let r = on(257) / on(129);
        assert!(r > 4.0 && r < 5.0, "{r}");
        // Roelands from eta0 derives z from the point-contact alpha_bar, per D.
        let roe = "contact = \"point\"\n[axes]\nM = [10]\nL = [10]\nD = [0.5, 1]\n\
                   [models]\nviscosity = \"roelands\"\neta0 = 0.05\nph = 1e9\n";
        let zs: Vec<f64> = plan(&parse("r.toml", roe, "r").unwrap())
            .unwrap()
            .iter()
            .map(|c| match c.models.viscosity {
                Viscosity::Roelands { z, .. } => z,
                Viscosity::Barus => f64::NAN,
            })
            .collect();
        assert_eq!(zs.len(), 2);
        assert!(
            zs.iter().all(|z| z.is_finite() && *z > 0.0) && zs[0] != zs[1],
            "{zs:?}"
        );
    }
}
