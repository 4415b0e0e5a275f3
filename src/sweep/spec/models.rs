//! The `[models]` table of a spec: elasticity, viscosity and density, defaults when absent
//! (elastic, Barus, incompressible). Roelands needs the Hertzian pressure `ph` and exactly one
//! of `eta0` (then ln(eta0) + 9.67 > 0 and no L = 0 on the L axis, as z is derived per case) or
//! `z`; Dowson-Higginson needs `ph`; `eta0`, `z` and `ph` are errors where no model uses them.
//! The rough surfaces of the cases with sigma > 0 take `slide_roll` (in [-2, 2], default 0),
//! `rough_surface` ("both", "1" or "2": which body carries the roughness, default both),
//! `ph_over_e` (in (0, 1), default 1 GPa on steel), `eta_beta_sigma` and `sigma_over_beta` (> 0,
//! defaults 0.04 and 1e-3); each is an error in a spec without such cases.

use super::ctx::{Ctx, Table};
use super::error::SpecError;
use super::types::ViscositySpec;
use crate::model::case::Elasticity;
use crate::model::lubricant::Density;
use crate::model::roughness::Roughness;
use std::ops::Range;

/// The models of a spec.
pub(super) struct Models {
    pub elasticity: Elasticity,
    pub viscosity: ViscositySpec,
    pub density: Density,
    /// The rough surfaces' inputs besides sigma and gamma (sigma 0 here: the axes give it).
    pub roughness: Roughness,
}

/// A positive number of the table and the span of its value.
type Given = Option<(f64, Range<usize>)>;

/// The `[models]` table with its positive numbers `ph`, `eta0` and `z`, where given.
struct ModelsTable<'t, 'i> {
    t: &'t Table<'i>,
    span: Range<usize>,
    ph: Given,
    eta0: Given,
    z: Given,
}

impl ModelsTable<'_, '_> {
    /// The span of key `k`, or the table's when it is absent.
    fn span_of(&self, k: &str) -> Range<usize> {
        self.t.get(k).map_or(self.span.clone(), |v| v.span())
    }

    /// `ph`, which model `what` needs.
    fn need_ph(&self, cx: &Ctx, what: &str) -> Result<f64, SpecError> {
        self.ph.as_ref().map(|p| p.0).ok_or_else(|| {
            cx.err(
                &self.span_of(what),
                &format!("models.{what}"),
                "needs the Hertzian pressure models.ph (Pa)",
            )
        })
    }
}

/// The `[models]` of `root`. `l` is the spec's L axis, given at `l_span`.
pub(super) fn parse(
    cx: &mut Ctx,
    root: &Table,
    l: &[f64],
    l_span: &Range<usize>,
    rough: bool,
) -> Result<Models, SpecError> {
    let mut models = Models {
        elasticity: Elasticity::Elastic,
        viscosity: ViscositySpec::Barus,
        density: Density::Incompressible,
        roughness: Roughness::isotropic(0.0),
    };
    let Some(mv) = root.get("models") else {
        return Ok(models);
    };
    let t = cx.table(mv, "models")?;
    cx.keys(
        t,
        "models",
        &[
            "elasticity",
            "viscosity",
            "density",
            "ph",
            "eta0",
            "z",
            "slide_roll",
            "rough_surface",
            "ph_over_e",
            "eta_beta_sigma",
            "sigma_over_beta",
        ],
    )?;
    models.roughness = roughness(cx, t, rough)?;
    if let Some(v) = t.get("elasticity") {
        if cx.choice(v, "models.elasticity", &["elastic", "rigid"])? == "rigid" {
            models.elasticity = Elasticity::Rigid;
        }
    }
    let mt = ModelsTable {
        t,
        span: mv.span(),
        ph: positive(cx, t, "ph", "the Hertzian pressure must be > 0 (Pa)")?,
        eta0: positive(cx, t, "eta0", "the ambient viscosity must be > 0 (Pa s)")?,
        z: positive(cx, t, "z", "the Roelands index must be > 0")?,
    };
    let visc = match t.get("viscosity") {
        Some(v) => cx.choice(v, "models.viscosity", &["barus", "roelands"])?,
        None => "barus",
    };
    let dens = match t.get("density") {
        Some(v) => cx.choice(v, "models.density", &["incompressible", "dowson-higginson"])?,
        None => "incompressible",
    };
    if visc == "roelands" {
        models.viscosity = roelands(cx, &mt, l, l_span)?;
    } else {
        only_with_roelands(cx, &mt)?;
    }
    if dens == "dowson-higginson" {
        models.density = Density::DowsonHigginson {
            ph_pa: mt.need_ph(cx, "density")?,
        };
    }
    if mt.ph.is_some() && visc != "roelands" && dens != "dowson-higginson" {
        return Err(cx.err(
            &mt.span_of("ph"),
            "models.ph",
            "is used only by viscosity = \"roelands\" and density = \"dowson-higginson\"",
        ));
    }
    Ok(models)
}

/// The rough surfaces' inputs of the `[models]` table `t` (module docs); `rough`: the spec has
/// cases with sigma > 0.
fn roughness(cx: &Ctx, t: &Table, rough: bool) -> Result<Roughness, SpecError> {
    let mut r = Roughness::isotropic(0.0);
    let keys = [
        "slide_roll",
        "rough_surface",
        "ph_over_e",
        "eta_beta_sigma",
        "sigma_over_beta",
    ];
    for k in keys {
        let Some(v) = t.get(k) else { continue };
        let key = format!("models.{k}");
        if !rough {
            return Err(cx.err(
                &v.span(),
                &key,
                "applies to rough surfaces only: give the axis sigma a value > 0",
            ));
        }
        if k == "rough_surface" {
            r.variance_ratio_1 = match cx.choice(v, &key, &["both", "1", "2"])? {
                "1" => 1.0,
                "2" => 0.0,
                _ => 0.5,
            };
            continue;
        }
        let x = cx.number(v, &key)?;
        let (ok, why) = match k {
            "slide_roll" => ((-2.0..=2.0).contains(&x), "must be in [-2, 2]"),
            "ph_over_e" => (x > 0.0 && x < 1.0, "must be in (0, 1)"),
            _ => (x > 0.0 && x.is_finite(), "must be > 0"),
        };
        if !ok {
            return Err(cx.err(&v.span(), &key, format!("{k} = {x} is invalid: {why}")));
        }
        match k {
            "slide_roll" => r.slide_roll = x,
            "ph_over_e" => r.ph_over_e = x,
            "eta_beta_sigma" => r.asperity.eta_beta_sigma = x,
            _ => r.asperity.sigma_over_beta = x,
        }
    }
    Ok(r)
}

/// The number `models.<k>` with its span when given; an error naming `why` unless it is > 0.
fn positive(cx: &Ctx, t: &Table, k: &str, why: &'static str) -> Result<Given, SpecError> {
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
}

/// `viscosity = "roelands"`: from `ph` and exactly one of `eta0` and `z`.
fn roelands(
    cx: &Ctx,
    mt: &ModelsTable,
    l: &[f64],
    l_span: &Range<usize>,
) -> Result<ViscositySpec, SpecError> {
    let ph_pa = mt.need_ph(cx, "viscosity")?;
    match (mt.eta0.clone(), mt.z.clone()) {
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
                    l_span,
                    "axes.L",
                    "L = 0 with Roelands from eta0 gives z = 0: use L > 0 or give models.z",
                ));
            }
            Ok(ViscositySpec::RoelandsEta0 { eta0, ph_pa })
        }
        (None, Some((z, _))) => Ok(ViscositySpec::RoelandsZ { z, ph_pa }),
        _ => Err(cx.err(
            &mt.span_of("viscosity"),
            "models.viscosity",
            "roelands needs exactly one of models.eta0 (Pa s) or models.z",
        )),
    }
}

/// `eta0` and `z` are errors unless the viscosity is Roelands.
fn only_with_roelands(cx: &Ctx, mt: &ModelsTable) -> Result<(), SpecError> {
    for (k, given) in [("eta0", mt.eta0.is_some()), ("z", mt.z.is_some())] {
        if given {
            return Err(cx.err(
                &mt.span_of(k),
                &format!("models.{k}"),
                "applies to viscosity = \"roelands\" only",
            ));
        }
    }
    Ok(())
}
