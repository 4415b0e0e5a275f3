//! The fields every grid level holds, line or point contact: one value per node (row-major with
//! X fastest for point levels).

use crate::discrete::physics::Coefficients;

/// The unknowns, derived fields, right-hand sides and work buffers of a grid level. A level
/// dereferences to these, so `level.p` is its pressure.
#[derive(Clone, Debug)]
pub struct NodeFields {
    /// The pressure P (Hertzian units).
    pub p: Vec<f64>,
    /// The film H (Hertzian units).
    pub film: Vec<f64>,
    /// The Reynolds coefficient eps = rho H^3/(eta lambda).
    pub eps: Vec<f64>,
    /// The density rho (1 at ambient pressure).
    pub rho: Vec<f64>,
    /// eta(P) lambda, the divisor of eps, as last computed from P (for a film update at fixed P).
    pub divisor: Vec<f64>,
    /// FAS right-hand side of the Reynolds equation (zero on the finest level).
    pub f: Vec<f64>,
    /// Right-hand side of the load equation.
    pub g: f64,
    /// Nodes held fixed on a coarse level: those whose fine neighbourhood touches the cavitated
    /// set. Coarse corrections then never move the free boundary (the smoother does), which keeps
    /// the projected FAS cycle from fighting the fine smoother there (truncated multigrid).
    pub frozen: Vec<bool>,
    /// Work buffer (deformation).
    pub work: Vec<f64>,
    /// Work buffer (relaxation changes, residuals).
    pub delta: Vec<f64>,
    /// Rough anisotropic surfaces: eps along y, phi_y rho H^3/(eta lambda) (empty otherwise;
    /// see [`NodeFields::eps_y`]).
    pub eps_along_y: Vec<f64>,
    /// Rough surfaces: the wedge film q(H) (empty otherwise; see [`NodeFields::wedge_film`]).
    pub wfilm: Vec<f64>,
    /// Mixed lubrication: the deformation by the asperity pressure, added to the film (empty
    /// otherwise).
    pub asperity_gap: Vec<f64>,
}

impl NodeFields {
    /// `n` nodes with P = 0, rho = 1 and the load right-hand side `g`.
    pub fn new(n: usize, g: f64) -> Self {
        NodeFields {
            p: vec![0.0; n],
            film: vec![0.0; n],
            eps: vec![0.0; n],
            rho: vec![1.0; n],
            divisor: vec![1.0; n],
            f: vec![0.0; n],
            g,
            frozen: vec![false; n],
            work: vec![0.0; n],
            delta: vec![0.0; n],
            eps_along_y: vec![],
            wfilm: vec![],
            asperity_gap: vec![],
        }
    }

    /// The film of the wedge term: q(H) on rough surfaces, H itself on smooth ones.
    #[inline]
    pub fn wedge_film(&self) -> &[f64] {
        own_or(&self.wfilm, &self.film)
    }

    /// The Poiseuille coefficient along y: eps itself unless rough anisotropic surfaces give it
    /// its own flow factor.
    #[inline]
    pub fn eps_y(&self) -> &[f64] {
        own_or(&self.eps_along_y, &self.eps)
    }

    /// The rough fields (wedge film, eps along y) of every node from H and eps; nothing on
    /// smooth surfaces.
    pub fn refresh_rough(&mut self, law: &Coefficients) {
        if law.rough.is_none() {
            return;
        }
        for c in 0..self.film.len() {
            self.refresh_rough_at(law, c);
        }
    }

    /// Give the rough fields that `law` needs a value per node (zeros where new), so that they
    /// can be set node by node; nothing on smooth surfaces.
    pub fn size_rough(&mut self, law: &Coefficients) {
        let Some(r) = &law.rough else { return };
        let n = self.film.len();
        if self.wfilm.len() != n {
            self.wfilm.resize(n, 0.0);
        }
        if !r.isotropic() && self.eps_along_y.len() != n {
            self.eps_along_y.resize(n, 0.0);
        }
    }

    /// [`NodeFields::refresh_rough`] at node `c` alone (the rough fields sized first).
    #[inline]
    pub fn refresh_rough_at(&mut self, law: &Coefficients, c: usize) {
        self.size_rough(law);
        rough_at(
            law,
            &self.film,
            &self.eps,
            &mut self.wfilm,
            &mut self.eps_along_y,
            c,
        );
    }

    /// Recompute rho and eps from P and the current H by the coefficient law `law`.
    pub fn update_coefficients(&mut self, law: Coefficients) {
        law.update(
            &self.p,
            &self.film,
            &mut self.rho,
            &mut self.eps,
            &mut self.divisor,
        );
        self.refresh_rough(&law);
    }
}

/// A rough field where the surfaces have it (`own` holds values), else the smooth field it
/// stands for (`base`): the wedge film q(H) or H, eps along y or eps.
#[inline]
pub fn own_or<'a>(own: &'a [f64], base: &'a [f64]) -> &'a [f64] {
    if own.is_empty() {
        base
    } else {
        own
    }
}

/// The rough fields of node `c` from its film and eps: the wedge film q(H) into `wfilm` and,
/// for anisotropic roughness, eps phi_y/phi_x into `eps_along_y` (both sized to hold node `c`
/// where `law` needs them); nothing on smooth surfaces.
#[inline]
pub fn rough_at(
    law: &Coefficients,
    film: &[f64],
    eps: &[f64],
    wfilm: &mut [f64],
    eps_along_y: &mut [f64],
    c: usize,
) {
    let Some(r) = &law.rough else { return };
    wfilm[c] = r.wedge_film(film[c]);
    if !r.isotropic() {
        let (fx, fy) = r.factors(film[c]);
        eps_along_y[c] = eps[c] * fy / fx;
    }
}

/// `Deref` and `DerefMut` of a level type (with a field `nodes`) to its [`NodeFields`].
macro_rules! deref_nodes {
    ($level:ty) => {
        impl std::ops::Deref for $level {
            type Target = $crate::discrete::level::NodeFields;
            fn deref(&self) -> &Self::Target {
                &self.nodes
            }
        }
        impl std::ops::DerefMut for $level {
            fn deref_mut(&mut self) -> &mut Self::Target {
                &mut self.nodes
            }
        }
    };
}
pub(crate) use deref_nodes;
