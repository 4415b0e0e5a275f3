//! The discrete point-contact problem on one grid level (Hertzian scaling X = x/b, Y = y/b,
//! P = p/p_h, H = h Rx/b^2; PHYSICS.md sections 2, 6b; the groups in [`crate::model::case::VennerPoint`]).
//!
//! Nodes (X_i, Y_j) = (X_in + i hx, -Y_half + j hy), stored row-major with X fastest (node (i, j)
//! at j nx + i); P = 0 on the boundary. At interior nodes
//!
//! L_ij = [ex_{i-1/2}(P_{i-1,j} - P_ij) + ex_{i+1/2}(P_{i+1,j} - P_ij)]/hx^2
//!      + [ey_{j-1/2}(P_{i,j-1} - P_ij) + ey_{j+1/2}(P_{i,j+1} - P_ij)]/hy^2 - D_x(rho H)_ij = f_ij
//!
//! with eps = rho H^3/(eta lambda), face values the means of the nodal ones, and D_x the upwind
//! difference along x (second order, (1.5 q_i - 2 q_{i-1} + 0.5 q_{i-2})/hx; first order at i = 1).
//! The film is H_ij = H0 + X_i^2/2 + D Y_j^2/2 + c sum K(|i-k|, |j-l|) P_kl with the exact cell
//! integrals of 1/r ([`crate::discrete::point::kernel`]) and c = (1+D)/(2 pi E) (2/pi^2 circular), the sum
//! dropped for rigid surfaces. The load equation is hx hy sum P = g (2 pi k/3 on the finest level).
//! A dry contact replaces L by -H.

use crate::discrete::level::{deref_nodes, NodeFields};
use crate::discrete::physics::Physics;
use crate::discrete::point::far_field::FarField;
use crate::discrete::point::kernel::{direct_product2d, kernel2d_on, DeformPlan2d};
use crate::discrete::rows::for_each_row;
use crate::model::case::PointCase;

/// The physics of a point case in Hertzian scaling, shared by all levels: the physics every
/// contact has ([`Physics`], which it dereferences to) and the ellipse's.
#[derive(Clone, Copy, Debug)]
pub struct PointPhysics {
    /// What every contact has.
    pub common: Physics,
    /// D = Rx/Ry: the curvature of the gap across the rolling direction.
    pub d: f64,
    /// k = a/b.
    pub k: f64,
    /// Coefficient of the deformation sum, (1+D)/(2 pi E).
    pub coef: f64,
    /// Load target 2 pi k/3.
    pub load: f64,
    /// H_Moes / H_Venner.
    pub h_scale: f64,
}

impl PointPhysics {
    /// The physics of M = 20, L = 10, D = 0.5 with Barus viscosity and Dowson-Higginson
    /// density (p_h = 0.5 GPa), for tests: every coefficient of the Reynolds operator varies
    /// with P.
    #[cfg(test)]
    pub(crate) fn piezoviscous_compressible() -> Self {
        use crate::model::case::{Models, PointCase};
        let models = Models {
            density: crate::model::lubricant::Density::DowsonHigginson { ph_pa: 0.5e9 },
            ..Default::default()
        };
        Self::from_case(&PointCase::with_models(20.0, 10.0, 0.5, models).expect("a valid case"))
    }

    /// The physics of a point case.
    pub fn from_case(case: &PointCase) -> Self {
        let v = case.venner();
        PointPhysics {
            common: Physics::of(&case.models, v.lambda, v.alpha_bar)
                .with_roughness(&case.models, v.h_scale),
            d: case.d,
            k: v.k,
            coef: v.film_coef,
            load: v.load,
            h_scale: v.h_scale,
        }
    }
}

impl std::ops::Deref for PointPhysics {
    type Target = Physics;
    fn deref(&self) -> &Physics {
        &self.common
    }
}

impl crate::discrete::physics::AsPhysics for PointPhysics {
    fn physics(&self) -> &Physics {
        &self.common
    }
    fn physics_mut(&mut self) -> &mut Physics {
        &mut self.common
    }
}

impl std::ops::DerefMut for PointPhysics {
    fn deref_mut(&mut self) -> &mut Physics {
        &mut self.common
    }
}

/// Nodes per rayon job in [`PointLevel::update_film_parallel`].
const PARALLEL_CHUNK: usize = 4096;

/// One grid level of a point contact: its grid, the rigid gap, the deformation kernel and the
/// node fields ([`NodeFields`], which the level dereferences to), row-major with X fastest.
pub struct PointLevel {
    /// Nodes along x.
    pub nx: usize,
    /// Nodes along y.
    pub ny: usize,
    /// Grid spacing along x (Hertzian units).
    pub hx: f64,
    /// Grid spacing along y (Hertzian units).
    pub hy: f64,
    /// Node coordinates X.
    pub x: Vec<f64>,
    /// Node coordinates Y.
    pub y: Vec<f64>,
    /// The node fields.
    pub nodes: NodeFields,
    /// K(dx, dy) at dy nx + dx.
    pub kernel: Vec<f64>,
    /// The FFT plan of the deformation product.
    deform: DeformPlan2d,
    /// The rigid gap X^2/2 + D Y^2/2.
    pub gap: Vec<f64>,
    /// Compute the deformation by the O(N^2) direct sum instead of the FFT (baseline).
    pub direct_deformation: bool,
    /// Seconds spent in this level's deformation products so far
    /// ([`crate::solve::phases::PhaseTimes::deformation`]).
    pub deform_seconds: f64,
    /// Compute the film, the coefficients and the residual on the rayon pool (the same values
    /// to the bit as the serial loops, whatever the number of threads).
    pub parallel: bool,
    /// Assemble the dense Newton Jacobian's rows on the rayon pool (a solve whose levels share
    /// the pool, whatever their size; never in a sweep's one-solve-per-thread pool, where a
    /// waiting thread would take up another case).
    pub parallel_jacobian: bool,
    /// The asymptotic far field ([`FarField`]): boundary values and the load beyond the domain
    /// from the r^-3 decay; `None`: P = 0 on the boundary.
    pub far: Option<FarField>,
    /// H0 of the last film update (the far field's rigid film).
    pub h0: f64,
}

deref_nodes!(PointLevel);

impl PointLevel {
    /// A level with `ix` x `iy` intervals on [x_in, x_out] x [-y_half, y_half], P = 0.
    pub fn new(
        phys: &PointPhysics,
        x_in: f64,
        x_out: f64,
        y_half: f64,
        ix: usize,
        iy: usize,
    ) -> Self {
        Self::new_on(phys, (x_in, x_out, y_half), ix, iy, false)
    }

    /// [`PointLevel::new`] on the domain `(x_in, x_out, y_half)`, made on the rayon pool and
    /// [`PointLevel::parallel`] where `parallel` (the same level to the bit).
    pub fn new_on(
        phys: &PointPhysics,
        (x_in, x_out, y_half): (f64, f64, f64),
        ix: usize,
        iy: usize,
        parallel: bool,
    ) -> Self {
        let (nx, ny) = (ix + 1, iy + 1);
        let hx = (x_out - x_in) / ix as f64;
        let hy = 2.0 * y_half / iy as f64;
        let x: Vec<f64> = (0..nx).map(|i| x_in + i as f64 * hx).collect();
        let y: Vec<f64> = (0..ny).map(|j| -y_half + j as f64 * hy).collect();
        let kernel = kernel2d_on(nx, ny, hx, hy, parallel);
        let mut gap = vec![0.0; nx * ny];
        for j in 0..ny {
            for i in 0..nx {
                gap[j * nx + i] = 0.5 * x[i] * x[i] + 0.5 * phys.d * y[j] * y[j];
            }
        }
        let n = nx * ny;
        PointLevel {
            nx,
            ny,
            hx,
            hy,
            x,
            y,
            nodes: NodeFields::new(n, phys.load),
            deform: DeformPlan2d::new_on(&kernel, nx, ny, parallel),
            kernel,
            gap,
            direct_deformation: false,
            deform_seconds: 0.0,
            parallel,
            parallel_jacobian: parallel,
            far: None,
            h0: 0.0,
        }
    }

    /// Use the asymptotic far field on this level ([`FarField`]) for the ellipticity `d`, with
    /// the coarsest grid's spacing `coarse` = (hx, hy) and the far deformation `deform`/R
    /// (`deform` = coef W; 0 for rigid surfaces).
    pub fn with_far_field(mut self, d: f64, coarse: (f64, f64), deform: f64) -> Self {
        self.far = Some(FarField::new(&self.x, &self.y, d, coarse, deform));
        self
    }

    /// Set the boundary values of the far field for H0 = `h0` (nothing without one), with their
    /// density and eta lambda.
    fn apply_far_field(&mut self, phys: &PointPhysics, h0: f64) {
        self.h0 = h0;
        let Some(far) = &self.far else { return };
        let nodes = &mut self.nodes;
        far.apply(&mut nodes.p, &self.gap, h0);
        let law = phys.coefficients();
        for b in far.boundary() {
            let r = b..b + 1;
            law.update(
                &nodes.p[r.clone()],
                &nodes.film[r.clone()],
                &mut nodes.rho[r.clone()],
                &mut nodes.eps[r.clone()],
                &mut nodes.divisor[r],
            );
        }
    }

    /// Points per direction (along x).
    pub fn points(&self) -> usize {
        self.nx
    }

    /// Nodes of the level, nx ny.
    pub fn len(&self) -> usize {
        self.p.len()
    }

    /// True for a level without nodes (never built by the solver).
    pub fn is_empty(&self) -> bool {
        self.p.is_empty()
    }

    /// Index of node (i, j).
    #[inline]
    pub fn at(&self, i: usize, j: usize) -> usize {
        j * self.nx + i
    }

    /// Whether node (i, j) is on the boundary.
    #[inline]
    pub fn boundary(&self, i: usize, j: usize) -> bool {
        i == 0 || j == 0 || i + 1 == self.nx || j + 1 == self.ny
    }

    /// The deformation sum c K*P (no H0, no gap) into `work` (the FFT product on the rayon pool
    /// for a `parallel` level), plus the asperity deformation in mixed lubrication.
    pub fn deformation(&mut self, phys: &PointPhysics) {
        if phys.elastic {
            let start = std::time::Instant::now();
            if self.direct_deformation {
                direct_product2d(
                    &self.kernel,
                    self.nx,
                    self.ny,
                    &self.nodes.p,
                    &mut self.nodes.work,
                );
            } else {
                let plan = &mut self.deform;
                if self.parallel {
                    plan.apply_parallel(&self.nodes.p, &mut self.nodes.work, phys.coef);
                } else {
                    plan.apply(&self.nodes.p, &mut self.nodes.work);
                }
            }
            if !self.parallel || self.direct_deformation {
                for w in &mut self.nodes.work {
                    *w *= phys.coef;
                }
            }
            self.deform_seconds += start.elapsed().as_secs_f64();
        } else {
            self.work.fill(0.0);
        }
        let nodes = &mut self.nodes;
        for (w, &a) in nodes.work.iter_mut().zip(&nodes.asperity_gap) {
            *w += a;
        }
    }

    /// The deformation c K*`field` (film units) by a pressure field on this level's nodes, into
    /// `out`: 0 for rigid surfaces.
    pub fn deformation_of(&mut self, phys: &PointPhysics, field: &[f64], out: &mut [f64]) {
        if !phys.elastic {
            out.fill(0.0);
            return;
        }
        let start = std::time::Instant::now();
        if self.direct_deformation {
            direct_product2d(&self.kernel, self.nx, self.ny, field, out);
        } else {
            self.deform.apply(field, out);
        }
        for w in out.iter_mut() {
            *w *= phys.coef;
        }
        self.deform_seconds += start.elapsed().as_secs_f64();
    }

    /// `fine_field` (on the nodes of a finer level of the same domain) at this level's nodes.
    pub fn inject_field(&self, fine: &PointLevel, fine_field: &[f64]) -> Vec<f64> {
        let step = (fine.nx - 1) / (self.nx - 1);
        let mut out = Vec::with_capacity(self.len());
        for j in 0..self.ny {
            for i in 0..self.nx {
                out.push(fine_field[fine.at(i * step, j * step)]);
            }
        }
        out
    }

    /// The area of one cell, hx hy (the load is cell_area x sum P).
    pub fn cell_area(&self) -> f64 {
        self.hx * self.hy
    }

    /// Recompute H (by the fast product), rho and eps from P and H0 (on the rayon pool when
    /// the level is `parallel`).
    pub fn update_film(&mut self, phys: &PointPhysics, h0: f64) {
        if self.parallel {
            return self.update_film_parallel(phys, h0, false);
        }
        self.film_only(phys, h0);
        self.update_coefficients(phys);
    }

    /// [`PointLevel::update_film`] (or, `fixed`, [`PointLevel::update_film_fixed_coefficients`])
    /// with the film and the coefficients computed on the rayon pool (and the deformation by
    /// [`PointLevel::deformation`]'s parallel product); the result is the same to the bit,
    /// whatever the number of threads.
    fn update_film_parallel(&mut self, phys: &PointPhysics, h0: f64, fixed: bool) {
        use rayon::prelude::*;
        self.apply_far_field(phys, h0);
        self.deformation(phys);
        let law = phys.coefficients();
        let nodes = &mut self.nodes;
        nodes
            .film
            .par_chunks_mut(PARALLEL_CHUNK)
            .zip(nodes.work.par_chunks(PARALLEL_CHUNK))
            .zip(self.gap.par_chunks(PARALLEL_CHUNK))
            .zip(nodes.p.par_chunks(PARALLEL_CHUNK))
            .zip(nodes.rho.par_chunks_mut(PARALLEL_CHUNK))
            .zip(nodes.eps.par_chunks_mut(PARALLEL_CHUNK))
            .zip(nodes.divisor.par_chunks_mut(PARALLEL_CHUNK))
            .for_each(|((((((film, work), gap), p), rho), eps), divisor)| {
                for ((f, &w), &g) in film.iter_mut().zip(work).zip(gap) {
                    *f = h0 + g + w;
                }
                if fixed {
                    for (k, e) in eps.iter_mut().enumerate() {
                        *e = law.eps_with(rho[k], film[k], divisor[k]);
                    }
                } else {
                    law.update(p, film, rho, eps, divisor);
                }
            });
        nodes.refresh_rough(&law);
    }

    /// Recompute H (by the fast product) from P and H0, nothing else.
    fn film_only(&mut self, phys: &PointPhysics, h0: f64) {
        self.apply_far_field(phys, h0);
        self.deformation(phys);
        for c in 0..self.len() {
            self.film[c] = h0 + self.gap[c] + self.work[c];
        }
    }

    /// Recompute H (by the fast product) and eps from P and H0, keeping rho and eta lambda
    /// (`divisor`): for a P whose rho and divisor are up to date (the smoother's rows have set
    /// them as they changed P); the result equals [`PointLevel::update_film`]'s.
    pub fn update_film_fixed_coefficients(&mut self, phys: &PointPhysics, h0: f64) {
        if self.parallel {
            return self.update_film_parallel(phys, h0, true);
        }
        self.film_only(phys, h0);
        let law = phys.coefficients();
        let nodes = &mut self.nodes;
        for ((e, &r), (&h, &d)) in nodes
            .eps
            .iter_mut()
            .zip(&nodes.rho)
            .zip(nodes.film.iter().zip(&nodes.divisor))
        {
            *e = law.eps_with(r, h, d);
        }
        nodes.refresh_rough(&law);
    }

    /// Recompute rho and eps from P and the current H.
    pub fn update_coefficients(&mut self, phys: &PointPhysics) {
        self.nodes.update_coefficients(phys.coefficients());
    }

    /// L at interior node (i, j) ([`crate::discrete::point::strip::Rows::reynolds`]).
    #[inline]
    pub fn reynolds(&self, phys: &PointPhysics, i: usize, j: usize) -> f64 {
        self.rows().reynolds(phys, i, j)
    }

    /// r = f - L at interior nodes, 0 on the boundary; with `active_only`, 0 also where P = 0.
    pub fn residual(&self, phys: &PointPhysics, active_only: bool, out: &mut [f64]) {
        for_each_row(self.parallel, &mut out[..self.len()], self.nx, |j, row| {
            self.residual_row(phys, active_only, j, row)
        });
    }

    /// [`PointLevel::residual`] of row j into `row` (nx values).
    fn residual_row(&self, phys: &PointPhysics, active_only: bool, j: usize, row: &mut [f64]) {
        let rows = self.rows();
        for (i, r) in row.iter_mut().enumerate() {
            let c = self.at(i, j);
            *r = if self.boundary(i, j) || (active_only && self.p[c] <= 0.0) {
                0.0
            } else {
                self.f[c] - rows.reynolds(phys, i, j)
            };
        }
    }

    /// hx hy sum P, with the far field's edge weights and tail beyond the domain when it has
    /// one.
    pub fn load(&self) -> f64 {
        let tail = self
            .far
            .as_ref()
            .map_or(0.0, |f| f.load_correction(&self.p, &self.gap, self.h0));
        self.hx * self.hy * self.p.iter().sum::<f64>() + tail
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discrete::testing::isoviscous_incompressible;

    #[test]
    fn rigid_reynolds_operator_is_second_order() {
        // P = exp(-X^2 - Y^2), H = 1 + X^2/2 + Y^2/2 (rigid, incompressible, lambda = 1, D = 1):
        // L = div(H^3 grad P) - dH/dX exactly; the discrete operator converges at second order.
        let phys = PointPhysics {
            common: Physics {
                lambda: 1.0,
                fluid: isoviscous_incompressible(),
                elastic: false,
                dry: false,
                second_order: true,
                rough: None,
                fluid_share: 1.0,
            },
            d: 1.0,
            k: 1.0,
            coef: 0.0,
            load: 1.0,
            h_scale: 1.0,
        };
        let exact = |x: f64, y: f64| {
            let hh = 1.0 + 0.5 * (x * x + y * y);
            let p = (-x * x - y * y).exp();
            let (px, py) = (-2.0 * x * p, -2.0 * y * p);
            let lap = (4.0 * (x * x + y * y) - 4.0) * p;
            3.0 * hh * hh * (x * px + y * py) + hh.powi(3) * lap - x
        };
        let mut errs = vec![];
        for n in [32usize, 64, 128] {
            let mut lv = PointLevel::new(&phys, -4.0, 4.0, 4.0, n, n);
            for j in 0..lv.ny {
                for i in 0..lv.nx {
                    let c = lv.at(i, j);
                    lv.p[c] = (-lv.x[i] * lv.x[i] - lv.y[j] * lv.y[j]).exp();
                }
            }
            lv.update_film(&phys, 1.0);
            // Node X = 1, Y = 0.5.
            let (i, j) = (n / 2 + n / 8, n / 2 + n / 16);
            errs.push((lv.reynolds(&phys, i, j) - exact(lv.x[i], lv.y[j])).abs());
        }
        let rate = (errs[1] / errs[2]).log2();
        assert!(rate > 1.8 && rate < 2.2, "rate {rate}, errs {errs:?}");
    }
}
