//! The lubricant's side of the discrete Reynolds operator, written once for line and point
//! contacts (PHYSICS.md sections 2, 6b).
//!
//! Contract. Inputs: the viscosity and density models and alpha_bar = alpha p_h ([`Fluid`]), the
//! contact's lambda and whether it is dry (with the fluid, the [`Coefficients`] law), and nodal
//! values of the pressure P and the film H in Hertzian scaling. Outputs: the nodal density rho(P)
//! and the coefficient eps = rho H^3/(eta(P) lambda) of the Poiseuille terms, with H clipped at 0
//! (no flow through a closed gap) and eps = 0 for a dry contact; and the local derivatives of rho
//! and eps at fixed H ([`Fluid::dln_rho`], [`Fluid::dln_eps`]). Invariant: both contacts compute
//! rho and eps only through [`Coefficients::at`] (one node) or [`Coefficients::update`] (a whole
//! level, node by node in storage order), so equal P and H give bit-identical coefficients in
//! either contact.

use crate::discrete::roughness::RoughLaw;
use crate::model::case::{Elasticity, Models};
use crate::model::lubricant::{Density, Viscosity};

/// The lubricant in Hertzian scaling: its pressure-viscosity and pressure-density models.
#[derive(Clone, Copy, Debug)]
pub struct Fluid {
    /// eta(P)/eta0.
    pub viscosity: Viscosity,
    /// rho(P)/rho0.
    pub density: Density,
    /// alpha_bar = alpha p_h, the dimensionless pressure-viscosity coefficient.
    pub alpha_bar: f64,
}

impl Fluid {
    /// The lubricant of a case's models at the case's alpha_bar.
    pub fn new(models: &Models, alpha_bar: f64) -> Self {
        Fluid {
            viscosity: models.viscosity,
            density: models.density,
            alpha_bar,
        }
    }

    /// d ln(rho)/dP at pressure `p`.
    #[inline]
    pub fn dln_rho(&self, p: f64) -> f64 {
        self.density.dln_rho(p)
    }

    /// d ln(eps)/dP at fixed H: d ln(rho)/dP - d ln(eta)/dP.
    #[inline]
    pub fn dln_eps(&self, p: f64) -> f64 {
        self.density.dln_rho(p) - self.viscosity.dln_eta(p, self.alpha_bar)
    }
}

/// The coefficient law of a contact: rho and eps as functions of the nodal P and H.
#[derive(Clone, Copy, Debug)]
pub struct Coefficients {
    /// The lubricant.
    pub fluid: Fluid,
    /// The speed group lambda of the Hertzian scaling.
    pub lambda: f64,
    /// Dry contact: eps = 0.
    pub dry: bool,
    /// Rough surfaces: eps carries phi_x, and the level's rough fields follow H
    /// ([`crate::discrete::level::NodeFields::refresh_rough`]).
    pub rough: Option<RoughLaw>,
}

impl Coefficients {
    /// The law of a fluid at a contact's lambda, dry or not, smooth or rough.
    #[inline]
    pub fn new(fluid: Fluid, lambda: f64, dry: bool, rough: Option<RoughLaw>) -> Self {
        Coefficients {
            fluid,
            lambda,
            dry,
            rough,
        }
    }

    /// eta(P) lambda, the divisor of eps at one node.
    #[inline]
    pub fn divisor(&self, p: f64) -> f64 {
        self.fluid.viscosity.eta(p, self.fluid.alpha_bar) * self.lambda
    }

    /// eps = rho H^3/divisor at one node, H clipped at 0, with the node's [`Coefficients::divisor`]
    /// (for a film change at fixed P: no viscosity to evaluate), times phi_x(H) on rough
    /// surfaces; 0 when dry.
    #[inline]
    pub fn eps_with(&self, rho: f64, film: f64, divisor: f64) -> f64 {
        if self.dry {
            0.0
        } else {
            let hh = film.max(0.0);
            let e = rho * hh * hh * hh / divisor;
            match &self.rough {
                None => e,
                Some(r) => e * r.phi_x(film),
            }
        }
    }

    /// (rho, eps, divisor) at one node from its pressure and film.
    #[inline]
    pub fn at(&self, p: f64, film: f64) -> (f64, f64, f64) {
        let rho = self.fluid.density.rho(p);
        let divisor = self.divisor(p);
        (rho, self.eps_with(rho, film, divisor), divisor)
    }

    /// rho, eps and the divisor of eps at every node from P and H (all slices of one length).
    pub fn update(
        &self,
        p: &[f64],
        film: &[f64],
        rho: &mut [f64],
        eps: &mut [f64],
        divisor: &mut [f64],
    ) {
        for ((((&pc, &hc), r), e), d) in p.iter().zip(film).zip(rho).zip(eps).zip(divisor) {
            (*r, *e, *d) = self.at(pc, hc);
        }
    }
}

/// Access to the [`Physics`] every contact's physics holds (the line contact's is one).
pub trait AsPhysics {
    /// The shared physics.
    fn physics(&self) -> &Physics;
    /// The shared physics, to change.
    fn physics_mut(&mut self) -> &mut Physics;
}

impl AsPhysics for Physics {
    fn physics(&self) -> &Physics {
        self
    }
    fn physics_mut(&mut self) -> &mut Physics {
        self
    }
}

/// The physics every contact shares in Hertzian scaling, the same on all levels.
#[derive(Clone, Copy, Debug)]
pub struct Physics {
    /// The speed group lambda of the Reynolds coefficient eps = rho H^3/(eta lambda).
    pub lambda: f64,
    /// Viscosity and density models, alpha_bar.
    pub fluid: Fluid,
    /// Elastic surfaces (the film carries the deformation integral); false: rigid.
    pub elastic: bool,
    /// Dry contact: the Reynolds equation is switched off and replaced by the contact condition
    /// L = -H (so P >= 0, H >= 0, P H = 0: Hertz for a parabolic gap).
    pub dry: bool,
    /// Second-order upwind wedge term (default) or first order.
    pub second_order: bool,
    /// Rough surfaces (the average Reynolds equation); `None`: smooth.
    pub rough: Option<RoughLaw>,
    /// The share of the load the fluid carries (1; less in mixed lubrication, where the
    /// asperities carry the rest): the finest level's load equation is sum P = share x load.
    pub fluid_share: f64,
}

impl Physics {
    /// The physics of a lubricated case with `models`, lambda and alpha_bar: second-order
    /// upwinding, not dry.
    pub fn of(models: &Models, lambda: f64, alpha_bar: f64) -> Self {
        Physics {
            lambda,
            fluid: Fluid::new(models, alpha_bar),
            elastic: models.elasticity == Elasticity::Elastic,
            dry: false,
            second_order: true,
            rough: None,
            fluid_share: 1.0,
        }
    }

    /// The same physics with the rough surfaces of `models` (sigma in Moes units, H_Moes =
    /// `h_scale` H).
    pub fn with_roughness(self, models: &Models, h_scale: f64) -> Self {
        Physics {
            rough: RoughLaw::new(&models.roughness, h_scale),
            ..self
        }
    }

    /// The coefficient law rho(P), eps(P, H).
    #[inline]
    pub fn coefficients(&self) -> Coefficients {
        Coefficients::new(self.fluid, self.lambda, self.dry, self.rough)
    }
}
