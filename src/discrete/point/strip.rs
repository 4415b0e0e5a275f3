//! A band of a point level's rows, borrowed from the level (a strip): what the x-line smoother
//! ([`crate::solve::point::relax`]) and the Jacobian rows ([`crate::solve::point::jacobian`])
//! read and write. Rows j0..j0 + rows of the level's node fields, indexed in level coordinates:
//! node (i, j) of the level is entry (j - j0) nx + i of every field of the strip.
//!
//! A read-only strip ([`RowsRef`]) borrows the fields shared; a writable one ([`RowsMut`])
//! borrows P, H, eps, rho, eta lambda and the rough fields mutably (f, the frozen flags and the
//! kernel shared) and splits at a row into two writable strips
//! ([`RowsMut::split_at_row`]): the parallel smoother's blocks of rows, each relaxed in place on
//! its own thread with no copy of the level. Invariant: every field of a strip covers its rows
//! (the rough fields are empty on smooth surfaces, and sized by
//! [`crate::discrete::level::NodeFields::size_rough`] on rough ones before a writable strip is
//! taken).

use crate::discrete::level::{own_or, rough_at};
use crate::discrete::physics::Coefficients;
use crate::discrete::point::operator::{PointLevel, PointPhysics};
use crate::discrete::stencil::{flux_difference, upwind, wedge};
use std::ops::Deref;

/// Rows of a point level's node fields, `F` the borrow of the fields that a writable strip
/// changes (see the module docs).
pub struct Rows<'a, F> {
    /// Nodes along x.
    pub nx: usize,
    /// Rows of the whole level.
    pub level_ny: usize,
    /// The level row of the strip's first row.
    pub j0: usize,
    /// Grid spacing along x.
    pub hx: f64,
    /// Grid spacing along y.
    pub hy: f64,
    /// The level's whole kernel, K(dx, dy) at dy nx + dx.
    pub kernel: &'a [f64],
    /// FAS right-hand side of the Reynolds equation.
    pub f: &'a [f64],
    /// The frozen flags.
    pub frozen: &'a [bool],
    /// The pressure.
    pub p: F,
    /// The film.
    pub film: F,
    /// eps = rho H^3/(eta lambda).
    pub eps: F,
    /// The density.
    pub rho: F,
    /// eta lambda, the divisor of eps.
    pub divisor: F,
    /// eps along y (rough anisotropic surfaces; empty otherwise).
    pub eps_along_y: F,
    /// The wedge film q(H) (rough surfaces; empty otherwise).
    pub wfilm: F,
}

/// A read-only strip.
pub type RowsRef<'a> = Rows<'a, &'a [f64]>;

/// A writable strip.
pub type RowsMut<'a> = Rows<'a, &'a mut [f64]>;

impl<F: Deref<Target = [f64]>> Rows<'_, F> {
    /// Index of the level's node (i, j) in the strip's fields.
    #[inline]
    pub fn at(&self, i: usize, j: usize) -> usize {
        (j - self.j0) * self.nx + i
    }

    /// The Poiseuille coefficient along y ([`crate::discrete::level::NodeFields::eps_y`]).
    #[inline]
    pub fn eps_y(&self) -> &[f64] {
        own_or(&self.eps_along_y, &self.eps)
    }

    /// The film of the wedge term
    /// ([`crate::discrete::level::NodeFields::wedge_film`]).
    #[inline]
    pub fn wedge_film(&self) -> &[f64] {
        own_or(&self.wfilm, &self.film)
    }

    /// The discrete Reynolds operator L at the level's interior node (i, j) (module docs of
    /// [`crate::discrete::point::operator`]; -H for a dry contact), which reads rows j - 1..=j + 1.
    #[inline]
    pub fn reynolds(&self, phys: &PointPhysics, i: usize, j: usize) -> f64 {
        let c = self.at(i, j);
        if phys.dry {
            return -self.film[c];
        }
        let (e, p) = (&*self.eps, &*self.p);
        let pois = flux_difference(e, p, c, 1) / (self.hx * self.hx)
            + flux_difference(self.eps_y(), p, c, self.nx) / (self.hy * self.hy);
        let w = upwind(phys.second_order, i);
        pois - wedge(w, &self.rho, self.wedge_film(), c) / self.hx
    }

    /// The same strip, read-only.
    #[inline]
    pub fn as_ref(&self) -> RowsRef<'_> {
        Rows {
            nx: self.nx,
            level_ny: self.level_ny,
            j0: self.j0,
            hx: self.hx,
            hy: self.hy,
            kernel: self.kernel,
            f: self.f,
            frozen: self.frozen,
            p: &self.p,
            film: &self.film,
            eps: &self.eps,
            rho: &self.rho,
            divisor: &self.divisor,
            eps_along_y: &self.eps_along_y,
            wfilm: &self.wfilm,
        }
    }
}

impl<'a> RowsMut<'a> {
    /// The strip cut before the level row `j`: rows j0..j and j.. (j0 < j < the strip's end).
    pub fn split_at_row(self, j: usize) -> (RowsMut<'a>, RowsMut<'a>) {
        let k = (j - self.j0) * self.nx;
        let cut = |v: &'a mut [f64]| {
            if v.is_empty() {
                (Default::default(), Default::default())
            } else {
                v.split_at_mut(k)
            }
        };
        let (f, f2) = self.f.split_at(k);
        let (frozen, frozen2) = self.frozen.split_at(k);
        let (size, spacing) = ((self.nx, self.level_ny), (self.hx, self.hy));
        let fields = [
            self.p,
            self.film,
            self.eps,
            self.rho,
            self.divisor,
            self.eps_along_y,
            self.wfilm,
        ];
        let (mut heads, mut tails): ([&mut [f64]; 7], [&mut [f64]; 7]) = Default::default();
        for ((v, h), t) in fields.into_iter().zip(&mut heads).zip(&mut tails) {
            (*h, *t) = cut(v);
        }
        let head = Rows::whole(size, spacing, self.j0, (self.kernel, f, frozen), heads);
        let tail = Rows::whole(size, spacing, j, (self.kernel, f2, frozen2), tails);
        (head, tail)
    }

    /// The rough fields of node `c` from its H and eps
    /// ([`crate::discrete::level::NodeFields::refresh_rough_at`]; nothing on smooth surfaces).
    #[inline]
    pub fn refresh_rough_at(&mut self, law: &Coefficients, c: usize) {
        rough_at(law, self.film, self.eps, self.wfilm, self.eps_along_y, c);
    }
}

impl<'a, F> Rows<'a, F> {
    /// Rows from the level row `j0` of a level of `nx` x `ny` nodes spaced (hx, hy): its kernel,
    /// f and frozen flags, and its fields P, H, eps, rho, eta lambda, eps along y and wedge
    /// film, in order.
    fn whole(
        (nx, ny): (usize, usize),
        (hx, hy): (f64, f64),
        j0: usize,
        (kernel, f, frozen): (&'a [f64], &'a [f64], &'a [bool]),
        [p, film, eps, rho, divisor, eps_along_y, wfilm]: [F; 7],
    ) -> Self {
        Rows {
            nx,
            level_ny: ny,
            j0,
            hx,
            hy,
            kernel,
            f,
            frozen,
            p,
            film,
            eps,
            rho,
            divisor,
            eps_along_y,
            wfilm,
        }
    }
}

impl PointLevel {
    /// All rows of the level, read-only.
    pub fn rows(&self) -> RowsRef<'_> {
        let n = &self.nodes;
        Rows::whole(
            (self.nx, self.ny),
            (self.hx, self.hy),
            0,
            (&self.kernel, &n.f, &n.frozen),
            [
                &n.p,
                &n.film,
                &n.eps,
                &n.rho,
                &n.divisor,
                &n.eps_along_y,
                &n.wfilm,
            ],
        )
    }

    /// All rows of the level, writable (the rough fields sized first where `law` has them,
    /// [`crate::discrete::level::NodeFields::size_rough`]).
    pub fn rows_mut(&mut self, law: &Coefficients) -> RowsMut<'_> {
        self.nodes.size_rough(law);
        let n = &mut self.nodes;
        Rows::whole(
            (self.nx, self.ny),
            (self.hx, self.hy),
            0,
            (&self.kernel, &n.f, &n.frozen),
            [
                &mut n.p,
                &mut n.film,
                &mut n.eps,
                &mut n.rho,
                &mut n.divisor,
                &mut n.eps_along_y,
                &mut n.wfilm,
            ],
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn split_strips_index_the_level_nodes_they_cover() {
        let phys = PointPhysics::piezoviscous_compressible();
        let mut lv = PointLevel::new(&phys, -2.5, 1.5, 2.0, 16, 12);
        for (c, p) in lv.nodes.p.iter_mut().enumerate() {
            *p = c as f64;
        }
        let (nx, ny) = (lv.nx, lv.ny);
        let law = phys.coefficients();
        let (a, rest) = lv.rows_mut(&law).split_at_row(4);
        let (b, c) = rest.split_at_row(9);
        assert_eq!((a.j0, b.j0, c.j0), (0, 4, 9));
        assert_eq!(a.p.len(), 4 * nx);
        assert_eq!(b.p.len(), 5 * nx);
        assert_eq!(c.p.len(), (ny - 9) * nx);
        for (s, j) in [(&b, 5), (&c, 9), (&c, ny - 1)] {
            assert_eq!(s.p[s.at(3, j)], (j * nx + 3) as f64);
        }
        // Smooth surfaces: no rough fields to split.
        assert!(b.wfilm.is_empty() && b.eps_along_y.is_empty());
        let k = a.at(2, 1);
        a.p[k] = -1.0;
        assert_eq!(lv.p[nx + 2], -1.0);
    }
}
