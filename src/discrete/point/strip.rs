//! A point level's rows as a level of their own (a strip), for the parallel smoother's blocks
//! ([`crate::solve::point::relax`]): made once per block, filled from the level's rows before
//! each sweep ([`PointLevel::copy_rows_into`]) and copied back after it
//! ([`PointLevel::copy_rows_from`]). A strip has the level's spacing, the kernel rows it spans
//! and no deformation plan: its film is corrected locally, never recomputed.

use crate::discrete::level::NodeFields;
use crate::discrete::point::operator::PointLevel;

/// Values per field (each strip's `rows` times nx, summed) from which
/// [`PointLevel::copy_rows_from`] copies on the rayon pool: about a megabyte of the five main
/// fields, 0.1 ms of copying.
const PARALLEL_COPY_MIN: usize = 1 << 15;

/// A strip's place in its level and the rows it changed ([`PointLevel::copy_rows_from`]).
pub struct StripRows<'a> {
    /// The strip ([`PointLevel::strip`]).
    pub strip: &'a PointLevel,
    /// The level row of its first row.
    pub j0: usize,
    /// The level rows whose P it changed.
    pub p_rows: std::ops::Range<usize>,
    /// The level rows whose H, eps, rho, eta lambda and rough fields it changed.
    pub rows: std::ops::Range<usize>,
}

impl PointLevel {
    /// Rows j0..j0 + rows of this level as a level of their own, for the parallel smoother's
    /// blocks ([`crate::solve::point::relax`]): the same spacing, the kernel rows dy < rows (the
    /// kernel of the strip's grid), the gap of those rows, node fields sized but not filled
    /// ([`PointLevel::copy_rows_into`]); no deformation plan (a strip's film is corrected
    /// locally, never recomputed: its deformation product panics), no far field, not parallel.
    pub fn strip(&self, j0: usize, rows: usize) -> PointLevel {
        let nx = self.nx;
        PointLevel {
            nx,
            ny: rows,
            hx: self.hx,
            hy: self.hy,
            x: self.x.clone(),
            y: self.y[j0..j0 + rows].to_vec(),
            nodes: NodeFields::new(rows * nx, self.nodes.g),
            kernel: self.kernel[..rows * nx].to_vec(),
            deform: None,
            gap: self.gap[j0 * nx..(j0 + rows) * nx].to_vec(),
            direct_deformation: false,
            deform_seconds: 0.0,
            parallel: false,
            far: None,
            h0: self.h0,
        }
    }

    /// Copy the node fields of rows j0.. of this level (as many rows as `strip` has) into
    /// `strip`: P, f, the frozen flags, H, eps, rho, eta lambda and the rough and mixed fields
    /// where this level has them (no allocation once `strip` has held them).
    pub fn copy_rows_into(&self, j0: usize, strip: &mut PointLevel) {
        let r = j0 * self.nx..j0 * self.nx + strip.len();
        let (src, dst) = (&self.nodes, &mut strip.nodes);
        dst.p.copy_from_slice(&src.p[r.clone()]);
        dst.f.copy_from_slice(&src.f[r.clone()]);
        dst.frozen.copy_from_slice(&src.frozen[r.clone()]);
        dst.film.copy_from_slice(&src.film[r.clone()]);
        dst.eps.copy_from_slice(&src.eps[r.clone()]);
        dst.rho.copy_from_slice(&src.rho[r.clone()]);
        dst.divisor.copy_from_slice(&src.divisor[r.clone()]);
        dst.g = src.g;
        for (s, d) in [
            (&src.eps_along_y, &mut dst.eps_along_y),
            (&src.wfilm, &mut dst.wfilm),
            (&src.asperity_gap, &mut dst.asperity_gap),
        ] {
            d.clear();
            if !s.is_empty() {
                d.extend_from_slice(&s[r.clone()]);
            }
        }
        strip.h0 = self.h0;
    }

    /// Copy back what each strip of `strips` changed (`at(s)`: the strip, the level row j0 it
    /// was taken at, the level's rows `p_rows` whose P it changed, and the rows `rows` whose H,
    /// eps, rho, eta lambda and rough fields it changed; the ranges of different strips
    /// disjoint): the inverse of [`PointLevel::copy_rows_into`] over those rows, one field at a
    /// time on the rayon pool.
    pub fn copy_rows_from<S: Sync>(
        &mut self,
        strips: &[S],
        at: impl Fn(&S) -> StripRows<'_> + Sync,
    ) {
        use rayon::prelude::*;
        let (nx, n) = (self.nx, self.len());
        type Field = fn(&NodeFields) -> &Vec<f64>;
        let dst = &mut self.nodes;
        let fields: [(&mut Vec<f64>, Field, bool); 7] = [
            (&mut dst.p, |f| &f.p, true),
            (&mut dst.film, |f| &f.film, false),
            (&mut dst.eps, |f| &f.eps, false),
            (&mut dst.rho, |f| &f.rho, false),
            (&mut dst.divisor, |f| &f.divisor, false),
            (&mut dst.eps_along_y, |f| &f.eps_along_y, false),
            (&mut dst.wfilm, |f| &f.wfilm, false),
        ];
        let copy = |(d, field, is_p): (&mut Vec<f64>, Field, bool)| {
            for s in strips {
                let StripRows {
                    strip,
                    j0,
                    p_rows,
                    rows,
                } = at(s);
                let src = field(&strip.nodes);
                if src.is_empty() {
                    continue;
                }
                if d.len() < n {
                    d.resize(n, 0.0);
                }
                let rows = if is_p { p_rows } else { rows };
                let local = (rows.start - j0) * nx..(rows.end - j0) * nx;
                d[rows.start * nx..rows.end * nx].copy_from_slice(&src[local]);
            }
        };
        // On the pool only where the copy outweighs waking a thread (tens of microseconds).
        let values: usize = strips.iter().map(|s| at(s).rows.len() * nx).sum();
        if values >= PARALLEL_COPY_MIN {
            fields.into_par_iter().for_each(copy);
        } else {
            fields.into_iter().for_each(copy);
        }
    }
}
