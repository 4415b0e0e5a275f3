//! The multigrid smoother for the point contact: x-line relaxation, row by row (Gauss-Seidel in
//! y), each row one banded solve of the exact Jacobian (kernel terms within `band` cells along x)
//! in distributed variables where xi is small.
//!
//! Row j: with the change of variables dP = D dQ along the row, where D distributes dQ_i as
//! (-1/2, 1, -1/2) at the nodes of the set J (pressurised with pressurised x-neighbours, and
//! xi = min(eps faces along x)/hx^2 below `xi_threshold`: the high-pressure zone where the
//! Poiseuille terms vanish and the wedge term's kernel dominates) and is the identity elsewhere,
//! solve (J_band D) dQ = f - L(P) (see [`crate::solve::point::jacobian`]). Cavitated nodes (Newton
//! point value P + r/J_ii <= 0) get dP = -P, frozen coarse nodes dP = 0. Then
//! P += omega dP (each change limited to min(1, 2/alpha_bar)), projected on P >= 0. The film of rows j to
//! j+2 (all that the next row's equations see) is corrected at once for the kernel within 2 band
//! cells along x, with rho, eps and eta lambda of row j from its new P and eps of rows j+1, j+2
//! from their stored eta lambda (their P did not change); after the sweep H is recomputed exactly
//! by the FFT product.
//!
//! The contact-independent steps of the banded row solve are the line smoother's
//! ([`crate::solve::line::relax`]: node kinds, distributed rows, the change of a node).

use crate::discrete::point::operator::{PointLevel, PointPhysics};
use crate::solve::banded::solve_banded;
use crate::solve::point::jacobian::{KernelWindow, PointJacRow, RowDerivatives};
use crate::solve::relax::{
    distributed, distributed_row, mirror_kernel, node_kind, pinned_row, relaxed, undistributed,
    viscosity_step_limit, xi, Kind, RelaxParams,
};

/// Work buffers of the point smoother, reused across rows, sweeps and levels.
#[derive(Default)]
pub struct PointScratch {
    rows: Vec<PointJacRow>,
    /// Boundary columns included (frozen).
    kind: Vec<Kind>,
    jset: Vec<bool>,
    a: Vec<f64>,
    rhs: Vec<f64>,
    /// Entries of one Jacobian row over the window, and the applied changes of the row.
    ent: Vec<f64>,
    /// The kernel near the diagonal, in order.
    window: KernelWindow,
    /// The nodal derivatives of the row.
    derivs: RowDerivatives,
    change: Vec<f64>,
    /// The changes of one colour in zebra order.
    zebra: Vec<f64>,
    /// One row scratch per zebra job (rayon thread).
    jobs: Vec<PointScratch>,
    /// The film correction: c dP of the relaxed row padded by `reach` zeros on both sides, and
    /// the kernel rows dy = 0, 1, 2 mirrored over -reach..=reach ([`mirror_kernel`]).
    scaled: Vec<f64>,
    film_kernel: [Vec<f64>; 3],
}

/// One sweep of x-line relaxation over all interior rows: Gauss-Seidel from row to row, or, on a
/// `parallel` level ([`PointLevel::parallel`]), zebra order (all odd rows from the same state, then all even rows; the rows of one
/// colour solved in parallel on the current rayon pool, the film updated by the FFT product between
/// the colours). Zebra results do not depend on the number of threads.
pub fn point_line_sweep(
    lv: &mut PointLevel,
    phys: &PointPhysics,
    h0: f64,
    rp: &RelaxParams,
    s: &mut PointScratch,
) {
    let (nx, ny) = (lv.nx, lv.ny);
    if lv.parallel {
        use rayon::prelude::*;
        // The changes of one colour, row after row, filled by one job per thread, each with its
        // own row scratch kept between sweeps (taken out of `s` so the jobs can borrow them).
        let mut zebra = std::mem::take(&mut s.zebra);
        let mut jobs = std::mem::take(&mut s.jobs);
        jobs.resize_with(rayon::current_num_threads().max(1), PointScratch::default);
        for first in [1usize, 2] {
            let count = (ny - 1 - first).div_ceil(2);
            // Every value is written by the jobs below: no clearing.
            zebra.resize(count * nx, 0.0);
            let per_job = count.div_ceil(jobs.len());
            {
                let lv = &*lv;
                zebra
                    .par_chunks_mut(per_job * nx)
                    .zip(jobs.par_iter_mut())
                    .enumerate()
                    .for_each(|(b, (block, rs))| {
                        for (k, out) in block.chunks_mut(nx).enumerate() {
                            row_changes(lv, phys, rp, first + 2 * (b * per_job + k), rs);
                            out.copy_from_slice(&rs.change);
                        }
                    });
            }
            // Row first + 2k of P is the first half of its chunk of two rows.
            lv.p[first * nx..]
                .par_chunks_mut(2 * nx)
                .zip(zebra.par_chunks(nx))
                .for_each(|(rows, ch)| {
                    for i in 1..nx - 1 {
                        rows[i] += ch[i];
                    }
                });
            lv.update_film(phys, h0);
        }
        s.zebra = zebra;
        s.jobs = jobs;
        return;
    }
    let reach = 2 * (rp.band + 1);
    for (dy, m) in s.film_kernel.iter_mut().enumerate() {
        let row = lv.kernel.get(dy * nx..(dy + 1) * nx).unwrap_or(&[]);
        mirror_kernel(row, reach, m);
    }
    for j in 1..ny - 1 {
        row_changes(lv, phys, rp, j, s);
        for i in 1..nx - 1 {
            let c = lv.at(i, j);
            lv.p[c] += s.change[i];
        }
        local_film_update(lv, phys, j, reach, s);
    }
    // Every changed row has set its rho and eta lambda: only H and eps are left to refresh.
    lv.update_film_fixed_coefficients(phys, h0);
}

/// The relaxation changes of row j (into `s.change`, indexed by i) from the current state.
fn row_changes(
    lv: &PointLevel,
    phys: &PointPhysics,
    rp: &RelaxParams,
    j: usize,
    s: &mut PointScratch,
) {
    let nx = lv.nx;
    let m = nx - 2;
    let bw = rp.band + 1;
    let w = 2 * bw + 1;
    let hx2 = lv.hx * lv.hx;
    // Each change is limited to one Hertz pressure, and to a viscosity change by e^2 (Barus):
    // far from the solution a full Newton change is not to be trusted.
    let max_dp = viscosity_step_limit(phys.fluid.alpha_bar).min(1.0);
    let PointScratch {
        rows,
        kind,
        jset,
        a,
        rhs,
        ent,
        change,
        window,
        derivs,
        ..
    } = s;
    window.fill(&lv.kernel, nx, (bw + 3).min(nx - 1));
    kind.clear();
    kind.resize(nx, Kind::Frozen);
    rhs.clear();
    rhs.resize(m, 0.0);
    // The residuals, and the kinds of the nodes that need no Jacobian row: frozen, or at P = 0
    // with r >= 0 (cavitated whatever its diagonal, see node_kind); the others marked Active
    // until their diagonal decides.
    let mut relaxed_nodes = nx..=0;
    for i in 1..nx - 1 {
        let c = lv.at(i, j);
        let r = lv.f[c] - lv.reynolds(phys, i, j);
        rhs[i - 1] = r;
        kind[i] = if lv.frozen[c] {
            Kind::Frozen
        } else if lv.p[c] <= 0.0 && r >= 0.0 {
            Kind::Cavitated
        } else {
            relaxed_nodes = (*relaxed_nodes.start()).min(i)..=i;
            Kind::Active
        };
    }
    // Their Jacobian rows read the nodal derivatives at i - 2..=i + 1.
    if !relaxed_nodes.is_empty() {
        let (first, last) = relaxed_nodes.into_inner();
        derivs.fill(
            lv,
            phys,
            j,
            first.saturating_sub(2)..=(last + 1).min(nx - 1),
        );
    }
    rows.clear();
    for i in 1..nx - 1 {
        if kind[i] == Kind::Active {
            let row = PointJacRow::in_row(lv, phys, i, j, derivs);
            let d = row.diagonal(window);
            kind[i] = node_kind(false, lv.p[lv.at(i, j)], rhs[i - 1], d);
            rows.push(row);
        } else {
            rows.push(PointJacRow::pinned(i, j));
        }
    }
    jset.clear();
    jset.extend((0..nx).map(|i| {
        distributed(kind, i, || {
            phys.dry || xi(&lv.eps, lv.at(i, j), hx2) < rp.xi_threshold
        })
    }));
    // Every row writes all its band entries (pinned_row, distributed_row): no clearing.
    a.resize(m * w, 0.0);
    ent.clear();
    ent.resize(nx, 0.0);
    for i in 1..nx - 1 {
        let row = i - 1;
        let a_row = &mut a[row * w..][..w];
        if kind[i] != Kind::Active {
            pinned_row(a_row, &mut rhs[row], bw, kind[i], lv.p[lv.at(i, j)]);
            continue;
        }
        let lo = i.saturating_sub(bw + 1).max(1);
        let hi = (i + bw + 1).min(nx - 2);
        rows[row].row_entries(window, lo, hi, ent);
        // distributed_row reads lo..=hi and 0 or nx - 1 beyond them (never written: 0).
        let ent = &*ent;
        distributed_row(a_row, i, bw, nx - 2, jset, |k| ent[k]);
    }
    let solved = solve_banded(a, m, bw, rhs) && rhs.iter().all(|v| v.is_finite());
    change.clear();
    change.resize(nx, 0.0);
    for i in 1..nx - 1 {
        let c = lv.at(i, j);
        let old = lv.p[c];
        let dp = if solved {
            undistributed(rhs, jset, i)
        } else {
            // A zero pivot: a damped point update from the diagonal alone.
            let d = rows[i - 1].diagonal(window);
            if d < 0.0 {
                (lv.f[c] - lv.reynolds(phys, i, j)) / d
            } else {
                0.0
            }
        };
        change[i] = relaxed(kind[i], old, rp.omega_line, dp, max_dp, rp.relative_step) - old;
    }
}

/// Correct the film (and rho, eps) of rows j..=j+2 for the pressure changes `s.change` on row j,
/// with the kernel kept within `reach` cells along x (`s.film_kernel` mirrored for this reach).
///
/// Node i of row j + dy gains c dP_k K(|i - k|, dy) for every interior k with |i - k| <= reach,
/// added one after the other with k ascending; the nodes are computed a block at a time
/// (the changes padded with zeros, whose terms add exact zeros to a non-zero film).
fn local_film_update(
    lv: &mut PointLevel,
    phys: &PointPhysics,
    j: usize,
    reach: usize,
    s: &mut PointScratch,
) {
    let (nx, ny) = (lv.nx, lv.ny);
    let law = phys.coefficients();
    let changed = if phys.elastic {
        scale_changes(&s.change, phys.coef, reach, &mut s.scaled)
    } else {
        None
    };
    for jj in j..(j + 3).min(ny - 1) {
        let dy = jj - j;
        if let Some((lo, hi)) = changed {
            let film = &mut lv.nodes.film[jj * nx..(jj + 1) * nx];
            add_window(&mut film[lo..=hi], &s.scaled[lo..], &s.film_kernel[dy]);
        }
        if dy == 0 {
            // The relaxed row: P changed.
            for i in 1..nx - 1 {
                let c = lv.at(i, jj);
                (lv.rho[c], lv.eps[c], lv.divisor[c]) = law.at(lv.p[c], lv.film[c]);
                lv.nodes.refresh_rough_at(&law, c);
            }
        } else {
            // The rows after it: only H changed.
            for i in 1..nx - 1 {
                let c = lv.at(i, jj);
                lv.eps[c] = law.eps_with(lv.rho[c], lv.film[c], lv.divisor[c]);
                lv.nodes.refresh_rough_at(&law, c);
            }
        }
    }
}

/// c dP (`coef` c, `change` dP over a row of nodes, 0 at both ends) into `scaled`, padded with
/// `reach` zeros on both sides; returns the interior nodes lo..=hi whose window of `reach`
/// holds a non-zero change (None: no change).
fn scale_changes(
    change: &[f64],
    coef: f64,
    reach: usize,
    scaled: &mut Vec<f64>,
) -> Option<(usize, usize)> {
    let nx = change.len();
    let first = (1..nx - 1).find(|&k| change[k] != 0.0)?;
    let last = (first..nx - 1).rev().find(|&k| change[k] != 0.0)?;
    scaled.clear();
    scaled.resize(nx + 2 * reach, 0.0);
    for (d, &dpk) in scaled[reach + 1..].iter_mut().zip(&change[1..nx - 1]) {
        *d = coef * dpk;
    }
    Some((
        first.saturating_sub(reach).max(1),
        (last + reach).min(nx - 2),
    ))
}

/// `out[t] += d[t + q] m[q]` for q = 0, 1, ..., m.len() - 1 in turn, for every t (`d` holds
/// out.len() + m.len() - 1 values at least): blocks of [`LANES`] consecutive outputs at once.
#[inline]
fn add_window(out: &mut [f64], d: &[f64], m: &[f64]) {
    let taps = m.len();
    for (b, block) in out.chunks_exact_mut(LANES).enumerate() {
        let mut acc = [0.0; LANES];
        acc.copy_from_slice(block);
        let d = &d[b * LANES..][..LANES + taps - 1];
        for (q, &mq) in m.iter().enumerate() {
            let dq = &d[q..q + LANES];
            for (a, &x) in acc.iter_mut().zip(dq) {
                *a += x * mq;
            }
        }
        block.copy_from_slice(&acc);
    }
    let done = out.len() - out.len() % LANES;
    for (t, o) in out.iter_mut().enumerate().skip(done) {
        for (&x, &mq) in d[t..t + taps].iter().zip(m) {
            *o += x * mq;
        }
    }
}

/// Outputs per block of [`add_window`].
const LANES: usize = 8;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discrete::testing::lcg;

    #[test]
    fn film_correction_equals_the_scatter_to_the_bit() {
        let mut seed = 5u64;
        for (nx, reach) in [(40usize, 10usize), (9, 10), (33, 4), (130, 10), (12, 3)] {
            let krow: Vec<f64> = (0..nx).map(|d| 1.0 / (1.0 + d as f64)).collect();
            let mut m = vec![];
            mirror_kernel(&krow, reach, &mut m);
            for zeros in [0.0, 0.5, 0.9] {
                let mut change = vec![0.0; nx];
                for c in &mut change[1..nx - 1] {
                    if lcg(&mut seed) >= zeros {
                        *c = lcg(&mut seed) - 0.5;
                    }
                }
                let film: Vec<f64> = (0..nx).map(|_| 0.1 + lcg(&mut seed)).collect();
                // The scatter, change by change.
                let mut want = film.clone();
                let coef = 0.2026;
                for (k, &dpk) in change.iter().enumerate().take(nx - 1).skip(1) {
                    if dpk == 0.0 {
                        continue;
                    }
                    let d = coef * dpk;
                    let (lo, hi) = (k.saturating_sub(reach).max(1), (k + reach).min(nx - 2));
                    for (f, &kv) in want[k..=hi].iter_mut().zip(&krow) {
                        *f += d * kv;
                    }
                    for (f, &kv) in want[lo..k].iter_mut().rev().zip(&krow[1..]) {
                        *f += d * kv;
                    }
                }
                let mut got = film.clone();
                let mut scaled = vec![];
                if let Some((lo, hi)) = scale_changes(&change, coef, reach, &mut scaled) {
                    add_window(&mut got[lo..=hi], &scaled[lo..], &m);
                }
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(
                    bits(&got),
                    bits(&want),
                    "nx {nx} reach {reach} zeros {zeros}"
                );
            }
        }
    }
}
