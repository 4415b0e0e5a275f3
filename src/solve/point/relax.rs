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
use crate::discrete::point::strip::{RowsMut, RowsRef};
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
    /// The blocks and gaps of each parallel level relaxed so far ([`blocked_sweep`]).
    blocks: Vec<LevelBlocks>,
    /// The film correction: c dP of the relaxed row padded by `reach` zeros on both sides, and
    /// the kernel rows dy = 0, 1, 2 mirrored over -reach..=reach ([`mirror_kernel`]).
    scaled: Vec<f64>,
    film_kernel: [Vec<f64>; 3],
}

/// One sweep of x-line relaxation over all interior rows: Gauss-Seidel from row to row, or, on a
/// `parallel` level ([`PointLevel::parallel`]), the same in blocks of rows relaxed at once on the
/// current rayon pool ([`blocked_sweep`]; the result does not depend on the number of threads);
/// then H and eps refreshed by the FFT product.
pub fn point_line_sweep(
    lv: &mut PointLevel,
    phys: &PointPhysics,
    h0: f64,
    rp: &RelaxParams,
    s: &mut PointScratch,
) {
    let (nx, ny) = (lv.nx, lv.ny);
    let reach = 2 * (rp.band + 1);
    for (dy, m) in s.film_kernel.iter_mut().enumerate() {
        let row = lv.kernel.get(dy * nx..(dy + 1) * nx).unwrap_or(&[]);
        mirror_kernel(row, reach, m);
    }
    if lv.parallel {
        blocked_sweep(lv, phys, rp, reach, s);
    } else {
        let mut rows = lv.rows_mut(&phys.coefficients());
        for j in 1..ny - 1 {
            relax_row(&mut rows, phys, rp, j, reach, s);
        }
    }
    // Every changed row has set its rho and eta lambda: only H and eps are left to refresh.
    lv.update_film_fixed_coefficients(phys, h0);
}

/// Relax the level's row j of the strip `lv` (which holds rows j - 1..=j + 2, or up to the
/// level's last row): its changes ([`row_changes`], which read rows j - 1..=j + 1) added to P,
/// the film of rows j..=j+2 corrected ([`local_film_update`]).
fn relax_row(
    lv: &mut RowsMut,
    phys: &PointPhysics,
    rp: &RelaxParams,
    j: usize,
    reach: usize,
    s: &mut PointScratch,
) {
    row_changes(&lv.as_ref(), phys, rp, j, s);
    let (nx, c) = (lv.nx, lv.at(0, j));
    for (p, &d) in lv.p[c + 1..c + nx - 1].iter_mut().zip(&s.change[1..nx - 1]) {
        *p += d;
    }
    local_film_update(lv, phys, j, reach, s);
}

/// Interior rows per block of a parallel sweep ([`blocked_sweep`]), about.
pub const BLOCK_ROWS: usize = 64;

/// The blocks of one parallel level and the gaps between them ([`blocked_sweep`]).
struct LevelBlocks {
    nx: usize,
    ny: usize,
    blocks: Vec<Block>,
    gaps: Vec<Block>,
}

/// Rows lo..hi of a level relaxed in order, in place, with a row scratch of their own.
struct Block {
    lo: usize,
    hi: usize,
    scratch: PointScratch,
}

impl Block {
    fn new(lo: usize, hi: usize) -> Block {
        Block {
            lo,
            hi,
            scratch: PointScratch::default(),
        }
    }
}

/// The rows lo..hi of each block of a level of `ny` rows: the interior rows 1..ny - 1 cut into
/// an even number of blocks, 2 max(1, (ny - 2) / (2 [`BLOCK_ROWS`])) (two halves of equal work
/// on a contact symmetric in Y), of nearly equal size, [`BLOCK_GAP`] rows apart.
pub fn block_rows(ny: usize) -> Vec<(usize, usize)> {
    let interior = ny - 2;
    let count = 2 * (interior / (2 * BLOCK_ROWS)).max(1);
    let relaxed = interior - BLOCK_GAP * (count - 1);
    let mut lo = 1;
    (0..count)
        .map(|b| {
            let size = relaxed / count + usize::from(b < relaxed % count);
            let block = (lo, lo + size);
            lo += size + BLOCK_GAP;
            block
        })
        .collect()
}

/// Rows between two blocks of a parallel sweep: a relaxed row corrects the film of the next
/// two ([`local_film_update`]), and the row after those is the first that the next block's
/// equations read, so no block writes what another reads.
pub const BLOCK_GAP: usize = 3;

/// One sweep of a parallel level: Gauss-Seidel x-line relaxation in blocks of rows
/// ([`block_rows`]) relaxed at once on the rayon pool, then the rows between consecutive blocks
/// (the gaps), also at once ([`relax_at_once`]). No block reads a row that another writes
/// ([`BLOCK_GAP`]), and gaps lie more than [`BLOCK_GAP`] rows apart, so the sweep equals the
/// serial one taking the rows in the order: each block's rows, then each gap's (tested to the
/// bit). The blocks depend on the grid only: the result does not depend on the number of
/// threads.
fn blocked_sweep(
    lv: &mut PointLevel,
    phys: &PointPhysics,
    rp: &RelaxParams,
    reach: usize,
    s: &mut PointScratch,
) {
    let (nx, ny) = (lv.nx, lv.ny);
    let k = match s.blocks.iter().position(|b| b.nx == nx && b.ny == ny) {
        Some(k) => k,
        None => {
            let rows = block_rows(ny);
            let blocks = rows.iter().map(|&(lo, hi)| Block::new(lo, hi)).collect();
            let gaps = rows
                .windows(2)
                .map(|w| Block::new(w[0].1, w[1].0))
                .collect();
            s.blocks.push(LevelBlocks {
                nx,
                ny,
                blocks,
                gaps,
            });
            s.blocks.len() - 1
        }
    };
    let LevelBlocks { blocks, gaps, .. } = &mut s.blocks[k];
    let law = phys.coefficients();
    for set in [blocks, gaps] {
        for b in set.iter_mut() {
            for (d, m) in b.scratch.film_kernel.iter_mut().zip(&s.film_kernel) {
                d.clone_from(m);
            }
        }
        relax_at_once(lv.rows_mut(&law), phys, rp, reach, set);
    }
}

/// Relax the rows of each block of `set` (in row order, disjoint, at least [`BLOCK_GAP`] rows
/// apart) at once on the rayon pool, each in serial Gauss-Seidel order in place: the strip
/// `rows` is cut before the row under each block (block b gets rows lo_b - 1 up to the row
/// under the next block), and the halves are relaxed by `rayon::join`. A block reads its rows
/// lo - 1..=hi and writes rows lo..=hi + 1, all within its own strip.
fn relax_at_once(
    rows: RowsMut,
    phys: &PointPhysics,
    rp: &RelaxParams,
    reach: usize,
    set: &mut [Block],
) {
    match set {
        [] => {}
        [b] => {
            let mut rows = rows;
            for j in b.lo..b.hi {
                relax_row(&mut rows, phys, rp, j, reach, &mut b.scratch);
            }
        }
        _ => {
            let mid = set.len() / 2;
            let (head, tail) = rows.split_at_row(set[mid].lo - 1);
            let (first, second) = set.split_at_mut(mid);
            rayon::join(
                || relax_at_once(head, phys, rp, reach, first),
                || relax_at_once(tail, phys, rp, reach, second),
            );
        }
    }
}

/// The relaxation changes of row j (into `s.change`, indexed by i) from the current state.
fn row_changes(
    lv: &RowsRef,
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
    window.fill(lv.kernel, nx, (bw + 3).min(nx - 1));
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
            phys.dry || xi(lv.eps, lv.at(i, j), hx2) < rp.xi_threshold
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
    lv: &mut RowsMut,
    phys: &PointPhysics,
    j: usize,
    reach: usize,
    s: &mut PointScratch,
) {
    let (nx, ny) = (lv.nx, lv.level_ny);
    let law = phys.coefficients();
    let changed = if phys.elastic {
        scale_changes(&s.change, phys.coef, reach, &mut s.scaled)
    } else {
        None
    };
    for jj in j..(j + 3).min(ny - 1) {
        let dy = jj - j;
        if let Some((lo, hi)) = changed {
            let c = lv.at(0, jj);
            let film = &mut lv.film[c..c + nx];
            add_window(&mut film[lo..=hi], &s.scaled[lo..], &s.film_kernel[dy]);
        }
        if dy == 0 {
            // The relaxed row: P changed.
            for i in 1..nx - 1 {
                let c = lv.at(i, jj);
                (lv.rho[c], lv.eps[c], lv.divisor[c]) = law.at(lv.p[c], lv.film[c]);
                lv.refresh_rough_at(&law, c);
            }
        } else {
            // The rows after it: only H changed.
            for i in 1..nx - 1 {
                let c = lv.at(i, jj);
                lv.eps[c] = law.eps_with(lv.rho[c], lv.film[c], lv.divisor[c]);
                lv.refresh_rough_at(&law, c);
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
    fn blocks_cover_the_interior_rows_once_an_even_number_apart_by_the_gap() {
        for ny in [65usize, 66, 129, 257, 300, 513, 1025] {
            let blocks = block_rows(ny);
            assert_eq!(blocks.len() % 2, 0, "ny {ny}");
            assert_eq!(blocks[0].0, 1);
            assert_eq!(blocks[blocks.len() - 1].1, ny - 1);
            for w in blocks.windows(2) {
                assert_eq!(w[1].0 - w[0].1, BLOCK_GAP, "ny {ny}");
            }
            let sizes: Vec<usize> = blocks.iter().map(|(lo, hi)| hi - lo).collect();
            let (min, max) = (sizes.iter().min().unwrap(), sizes.iter().max().unwrap());
            assert!(max - min <= 1 && *min > BLOCK_GAP, "ny {ny}: {sizes:?}");
        }
        assert_eq!(block_rows(513).len(), 6);
        assert_eq!(block_rows(1025).len(), 14);
    }

    /// A point level of a piezoviscous, compressible case with a Hertzian pressure and its
    /// film: the state a sweep starts from.
    fn level(phys: &PointPhysics) -> PointLevel {
        let mut lv = PointLevel::new(phys, -2.5, 1.5, 2.0, 64, 140);
        for j in 1..lv.ny - 1 {
            for i in 1..lv.nx - 1 {
                let c = lv.at(i, j);
                let (x, y) = (lv.x[i], lv.y[j] / phys.k);
                lv.p[c] = (1.0 - x * x - y * y).max(0.0).sqrt() * (1.0 + 0.03 * x);
            }
        }
        lv.update_film(phys, -0.2);
        lv
    }

    #[test]
    fn the_parallel_sweep_is_the_serial_sweep_in_block_order_to_the_bit() {
        let phys = PointPhysics::piezoviscous_compressible();
        let rp = RelaxParams::default();
        let h0 = -0.2;
        // The oracle: the serial sweep's rows in the order each block, then the gaps.
        let mut serial = level(&phys);
        let blocks = block_rows(serial.ny);
        assert!(blocks.len() >= 2);
        let mut order: Vec<usize> = blocks.iter().flat_map(|&(lo, hi)| lo..hi).collect();
        order.extend(blocks.windows(2).flat_map(|w| w[0].1..w[1].0));
        let mut s = PointScratch::default();
        let reach = 2 * (rp.band + 1);
        for (dy, m) in s.film_kernel.iter_mut().enumerate() {
            mirror_kernel(&serial.kernel[dy * serial.nx..][..serial.nx], reach, m);
        }
        let law = phys.coefficients();
        for &j in &order {
            relax_row(&mut serial.rows_mut(&law), &phys, &rp, j, reach, &mut s);
        }
        serial.update_film_fixed_coefficients(&phys, h0);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        for threads in [1, 2, 3] {
            let mut par = level(&phys);
            par.parallel = true;
            let mut s = PointScratch::default();
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| {
                    // Twice: the second sweep reuses the blocks made by the first.
                    point_line_sweep(&mut par, &phys, h0, &rp, &mut s);
                    let p = par.p.clone();
                    let mut again = level(&phys);
                    again.parallel = true;
                    point_line_sweep(&mut again, &phys, h0, &rp, &mut s);
                    assert_eq!(bits(&again.p), bits(&p));
                });
            assert!(par.p != level(&phys).p, "the sweep changed nothing");
            assert_eq!(bits(&par.p), bits(&serial.p), "{threads} threads");
            assert_eq!(bits(&par.film), bits(&serial.film), "{threads} threads");
            assert_eq!(bits(&par.eps), bits(&serial.eps), "{threads} threads");
            assert_eq!(bits(&par.rho), bits(&serial.rho), "{threads} threads");
        }
    }

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
