//! Point-contact elastic deformation: the Boussinesq kernel 1/r integrated exactly over each
//! rectangular pressure cell, and its two-level Toeplitz product computed by FFT with zero padding
//! (DC-FFT) in O(N log N).
//!
//! Grid: nx x ny nodes, spacings hx (along x, the rolling direction) and hy, stored row-major with
//! x fastest (node (i, k) at index k * nx + i). P is piecewise constant on the cell
//! [x_j - hx/2, x_j + hx/2] x [y_l - hy/2, y_l + hy/2], so the deformation integral at node (i, k)
//! is exactly sum_{j,l} K(|i-j|, |k-l|) P_{l,j} with
//! K(dx, dy) = integral over [dx hx - hx/2, dx hx + hx/2] x [dy hy - hy/2, dy hy + hy/2] of
//! 1/sqrt(x^2 + y^2) (Love 1929; Johnson, Contact Mechanics, 3.8), evaluated in closed form by
//! [`rect_integral`].
//!
//! **The physical coefficient is left to the caller**: nothing here multiplies by
//! (1+D)/(2 pi E) (elliptic, Hertzian units) or 2/pi^2 (circular). With it, the film is
//! H = H0 + X^2/2 + D Y^2/2 + coef * product (plus sign: the elastic displacement is positive and
//! largest under the load; for the Hertz pressure sqrt(1 - X^2 - Y^2) in circular Hertzian units
//! X^2/2 + Y^2/2 + (2/pi^2) * product = 1 inside the contact, see the tests).
//!
//! The product is a symmetric Toeplitz-block-Toeplitz one. It is embedded in a 2D circulant of size
//! 2(nx-1) x 2(ny-1): along x the circulant row is K_0, K_1, ..., K_{nx-1}, K_{nx-2}, ..., K_1, and
//! the wrap point (offset nx-1) carries the same K on both sides because K is even, so no offset
//! needed by the product is aliased and one FFT pair gives the discrete product exactly (to
//! rounding). A general (non-symmetric) kernel would need a period of at least 2n-1; the evenness
//! saves one point, and for the multigrid grids n = 2^k + 1 the period 2(n-1) = 2^(k+1) is a power
//! of two, the fastest FFT size (2n-1 = 2^(k+1) + 1 is awkward: 257 is prime, 1025 = 5^2 41).
//! Because the circulant is even in both directions its 2D DFT is real, so the transformed kernel
//! is stored as real numbers. [`direct_product2d`] is the O(N^2) oracle.
//!
//! The transform is real-to-complex along x (`realfft`, one row at a time, only the ny non-zero
//! rows) and complex along y (`rustfft` on the (2(nx-1)/2 + 1) columns of the half spectrum, stored
//! column by column so each column is contiguous; rows are moved in blocks to keep the transposes
//! cache friendly).

use crate::discrete::rows::for_each_row;
use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::{Fft, FftPlanner};
use std::sync::Arc;

/// Integral of 1/sqrt(x^2 + y^2) over the rectangle [x1, x2] x [y1, y2] (coordinates relative to
/// the field point; the rectangle may contain it: the singularity is integrable).
///
/// With F(x, y) = integral over [0, x] x [0, y] = x asinh(y/|x|) + y asinh(x/|y|) (each term 0 when
/// its prefactor is 0; F is odd in x and in y because 1/r is even), the integral is
/// F(x2, y2) - F(x1, y2) - F(x2, y1) + F(x1, y1). (The textbook form x asinh(y/x) + y asinh(x/y) is
/// only a primitive in the quadrant x, y > 0; the |.| make it valid in all four.)
pub fn rect_integral(x1: f64, x2: f64, y1: f64, y2: f64) -> f64 {
    corner(x2, y2) - corner(x1, y2) - corner(x2, y1) + corner(x1, y1)
}

fn corner(x: f64, y: f64) -> f64 {
    let t = |a: f64, b: f64| {
        if a == 0.0 {
            0.0
        } else {
            a * (b / a.abs()).asinh()
        }
    };
    t(x, y) + t(y, x)
}

/// K(dx, dy) for node offsets dx = 0..nx, dy = 0..ny on a grid of spacings hx, hy, stored at
/// dy * nx + dx. K is even in each offset, so these cover every pair of nodes.
///
/// Each cell's integral is [`rect_integral`]'s combination of its four corners; neighbouring
/// cells share corners, so the corner function is evaluated once per corner of the grid of cell
/// edges (x = (a - 1/2) hx, y = (b - 1/2) hy): a quarter of the `asinh` calls.
pub fn kernel2d(nx: usize, ny: usize, hx: f64, hy: f64) -> Vec<f64> {
    kernel2d_on(nx, ny, hx, hy, false)
}

/// [`kernel2d`], its rows computed on the rayon pool where `parallel` (the same values to the
/// bit).
pub fn kernel2d_on(nx: usize, ny: usize, hx: f64, hy: f64, parallel: bool) -> Vec<f64> {
    let w = nx + 1;
    let mut corners = vec![0.0; w * (ny + 1)];
    for_each_row(parallel, &mut corners, w, |b, row| {
        let y = (b as f64 - 0.5) * hy;
        for (a, v) in row.iter_mut().enumerate() {
            *v = corner((a as f64 - 0.5) * hx, y);
        }
    });
    let mut k = vec![0.0; nx * ny];
    for_each_row(parallel, &mut k, nx, |dy, row| {
        let (lo, hi) = (&corners[dy * w..][..w], &corners[(dy + 1) * w..][..w]);
        for (dx, v) in row.iter_mut().enumerate() {
            *v = hi[dx + 1] - hi[dx] - lo[dx + 1] + lo[dx];
        }
    });
    k
}

/// Reference O(N^2) product out[k*nx + i] = sum_{j,l} K(|i-j|, |k-l|) p[l*nx + j], with `kernel`
/// from [`kernel2d`] for the same nx, ny. No physical coefficient (see the module docs).
pub fn direct_product2d(kernel: &[f64], nx: usize, ny: usize, p: &[f64], out: &mut [f64]) {
    assert!(
        kernel.len() == nx * ny && p.len() == nx * ny && out.len() == nx * ny,
        "direct_product2d size mismatch"
    );
    for k in 0..ny {
        for i in 0..nx {
            let mut s = 0.0;
            for l in 0..ny {
                let krow = &kernel[k.abs_diff(l) * nx..][..nx];
                let prow = &p[l * nx..][..nx];
                for (j, &pj) in prow.iter().enumerate() {
                    s += krow[i.abs_diff(j)] * pj;
                }
            }
            out[k * nx + i] = s;
        }
    }
}

/// Rows moved together between the row transforms and the column-major spectrum.
const BLOCK: usize = 8;

/// Jobs per thread in the stages of [`DeformPlan2d::apply_parallel`] (each stage's rows or
/// columns cut into that many contiguous shares per thread).
const SHARES_PER_THREAD: usize = 4;

/// Unused bins after each column of the spectrum: the columns lie `my + COL_PAD` bins apart,
/// not a power of two (my = 2(ny - 1) often is), so that reading one bin of every column does
/// not map them all to the same few cache sets.
const COL_PAD: usize = 8;

/// What a column of the spectrum holds below its transformed rows: zeros (a product's input,
/// zero padded) or the even extension col[r] = col[my - r] (the kernel's circulant).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Below {
    Zero,
    Mirror,
}

impl Below {
    /// Fill `col[rows..]` (a whole column of my bins).
    fn fill(self, col: &mut [Complex<f64>], rows: usize) {
        match self {
            Below::Zero => col[rows..].fill(Complex::default()),
            Below::Mirror => {
                let my = col.len();
                for r in rows..my {
                    col[r] = col[my - r];
                }
            }
        }
    }
}

/// A reusable plan for the fast 2D deformation product on one grid: FFT plans, the transformed
/// kernel and all work buffers are made once, so [`DeformPlan2d::apply`] never allocates.
pub struct DeformPlan2d {
    nx: usize,
    ny: usize,
    /// Padded sizes 2(nx-1), 2(ny-1), and the half-spectrum width mx/2 + 1.
    mx: usize,
    my: usize,
    cx: usize,
    /// The column stride of the spectrum, my + [`COL_PAD`].
    cs: usize,
    row_fwd: Arc<dyn RealToComplex<f64>>,
    row_inv: Arc<dyn ComplexToReal<f64>>,
    col_fwd: Arc<dyn Fft<f64>>,
    col_inv: Arc<dyn Fft<f64>>,
    /// Real 2D DFT of the circulant kernel over mx * my (the inverse FFT's factor folded in),
    /// column-major like `spec`: bin (column c, row r) at c * cs + r (0 in the padding).
    kernel_hat: Vec<f64>,
    spec: Vec<Complex<f64>>,
    rows: Vec<f64>,
    rows_hat: Vec<Complex<f64>>,
    row_scratch: Vec<Complex<f64>>,
    col_scratch: Vec<Complex<f64>>,
    /// [`DeformPlan2d::apply_parallel`]: the row half-spectra (ny rows of cx bins, row-major)
    /// and one set of buffers per rayon job, made on its first call.
    row_spec: Vec<Complex<f64>>,
    jobs: Vec<FftJob>,
}

/// The buffers of one job of [`DeformPlan2d::apply_parallel`].
struct FftJob {
    row: Vec<f64>,
    hat: Vec<Complex<f64>>,
    scratch: Vec<Complex<f64>>,
}

impl DeformPlan2d {
    /// Plan for an nx x ny grid (each at least 2) with `kernel` from [`kernel2d`].
    pub fn new(kernel: &[f64], nx: usize, ny: usize) -> Self {
        Self::new_on(kernel, nx, ny, false)
    }

    /// [`DeformPlan2d::new`], the kernel's transform computed on the rayon pool where
    /// `parallel` (the same plan to the bit).
    pub fn new_on(kernel: &[f64], nx: usize, ny: usize, parallel: bool) -> Self {
        assert!(
            nx >= 2 && ny >= 2,
            "a 2D deformation plan needs at least two nodes per direction"
        );
        assert_eq!(kernel.len(), nx * ny, "kernel size does not match the grid");
        let (mx, my) = (2 * (nx - 1), 2 * (ny - 1));
        let cx = mx / 2 + 1;
        let cs = my + COL_PAD;
        let mut rplanner = RealFftPlanner::<f64>::new();
        let row_fwd = rplanner.plan_fft_forward(mx);
        let row_inv = rplanner.plan_fft_inverse(mx);
        let mut cplanner = FftPlanner::<f64>::new();
        let col_fwd = cplanner.plan_fft_forward(my);
        let col_inv = cplanner.plan_fft_inverse(my);
        let row_scratch =
            vec![Complex::default(); row_fwd.get_scratch_len().max(row_inv.get_scratch_len())];
        let col_scratch = vec![
            Complex::default();
            col_fwd
                .get_inplace_scratch_len()
                .max(col_inv.get_inplace_scratch_len())
        ];
        let mut plan = DeformPlan2d {
            nx,
            ny,
            mx,
            my,
            cx,
            cs,
            row_fwd,
            row_inv,
            col_fwd,
            col_inv,
            kernel_hat: Vec::new(),
            spec: vec![Complex::default(); cx * cs],
            rows: vec![0.0; BLOCK * mx],
            rows_hat: vec![Complex::default(); BLOCK * cx],
            row_scratch,
            col_scratch,
            row_spec: Vec::new(),
            jobs: Vec::new(),
        };
        // The even circulant extension of K over the full mx x my period: its rows r and my - r
        // are the same, so only the first ny are transformed (each extended along x to the
        // period), and each column is completed by the same symmetry before its transform.
        let wrap = |d: usize, n: usize, m: usize| if d < n { d } else { m - d };
        let mut ext = vec![0.0; mx * ny];
        for_each_row(parallel, &mut ext, mx, |r, row| {
            for (c, v) in row.iter_mut().enumerate() {
                *v = kernel[r * nx + wrap(c, nx, mx)];
            }
        });
        if parallel {
            plan.rows_forward_parallel(&ext, mx, ny);
            plan.columns_parallel(ny, Below::Mirror);
        } else {
            plan.forward(&ext, mx, ny, Below::Mirror);
        }
        let scale = 1.0 / (mx * my) as f64;
        plan.kernel_hat = plan.spec.iter().map(|z| z.re * scale).collect();
        plan
    }

    /// (nx, ny).
    pub fn nodes(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// The circulant (FFT) size per direction, (2(nx-1), 2(ny-1)).
    pub fn padded(&self) -> (usize, usize) {
        (self.mx, self.my)
    }

    /// out[k*nx + i] = sum_{j,l} K(|i-j|, |k-l|) p[l*nx + j] (exactly the product of
    /// [`direct_product2d`], no physical coefficient); `p` and `out` hold nx * ny values.
    pub fn apply(&mut self, p: &[f64], out: &mut [f64]) {
        let (nx, ny) = (self.nx, self.ny);
        assert!(
            p.len() == nx * ny && out.len() == nx * ny,
            "2D deformation plan size mismatch"
        );
        self.forward(p, nx, ny, Below::Zero);
        for (s, &k) in self.spec.iter_mut().zip(&self.kernel_hat) {
            *s *= k;
        }
        let (mx, my, cx, cs) = (self.mx, self.my, self.cx, self.cs);
        for col in self.spec.chunks_exact_mut(cs) {
            self.col_inv
                .process_with_scratch(&mut col[..my], &mut self.col_scratch);
        }
        for r0 in (0..ny).step_by(BLOCK) {
            let nb = BLOCK.min(ny - r0);
            for c in 0..cx {
                let col = &self.spec[c * cs + r0..][..nb];
                for (b, &z) in col.iter().enumerate() {
                    self.rows_hat[b * cx + c] = z;
                }
            }
            for b in 0..nb {
                let hat = &mut self.rows_hat[b * cx..][..cx];
                // Bins 0 and mx/2 of a real row are real: clear their imaginary rounding.
                hat[0].im = 0.0;
                hat[cx - 1].im = 0.0;
                let row = &mut self.rows[b * mx..][..mx];
                self.row_inv
                    .process_with_scratch(hat, row, &mut self.row_scratch)
                    .expect("sizes fixed by the plan");
                out[(r0 + b) * nx..][..nx].copy_from_slice(&row[..nx]);
            }
        }
    }

    /// [`DeformPlan2d::apply`] times `scale` on the rayon pool (each value of the product
    /// multiplied by `scale` once, as a caller scaling the product would): the row transforms,
    /// then each column's transform, kernel product and inverse, then the inverse row
    /// transforms, each stage split into one contiguous share per thread. Every row and column
    /// goes through the same transforms whatever the share, so the result does not depend on the
    /// number of threads.
    pub fn apply_parallel(&mut self, p: &[f64], out: &mut [f64], scale: f64) {
        use rayon::prelude::*;
        let (nx, ny, mx, cx, cs) = (self.nx, self.ny, self.mx, self.cx, self.cs);
        assert!(
            p.len() == nx * ny && out.len() == nx * ny,
            "2D deformation plan size mismatch"
        );
        self.rows_forward_parallel(p, nx, ny);
        self.columns_parallel(ny, Below::Zero);
        let rows_per = ny.div_ceil(self.jobs.len());
        let row_inv = &self.row_inv;
        let spec = &self.spec;
        out.par_chunks_mut(rows_per * nx)
            .zip(self.jobs.par_iter_mut())
            .enumerate()
            .for_each(|(b, (rows, job))| {
                // BLOCK rows at a time: each column's BLOCK bins are read at once.
                for (g, dst) in rows.chunks_mut(BLOCK * nx).enumerate() {
                    let (r0, ng) = (b * rows_per + g * BLOCK, dst.len() / nx);
                    for c in 0..cx {
                        for (k, &z) in spec[c * cs + r0..][..ng].iter().enumerate() {
                            job.hat[k * cx + c] = z;
                        }
                    }
                    for (hat, dst) in job.hat.chunks_exact_mut(cx).zip(dst.chunks_exact_mut(nx)) {
                        // Bins 0 and mx/2 of a real row are real: clear their imaginary rounding.
                        hat[0].im = 0.0;
                        hat[cx - 1].im = 0.0;
                        row_inv
                            .process_with_scratch(hat, &mut job.row[..mx], &mut job.scratch)
                            .expect("sizes fixed by the plan");
                        for (d, &v) in dst.iter_mut().zip(&job.row[..nx]) {
                            *d = v * scale;
                        }
                    }
                }
            });
    }

    /// One set of buffers per rayon job of the parallel stages (made once per thread count):
    /// [`SHARES_PER_THREAD`] jobs per thread of a pool of two or more, so that a thread that
    /// finishes its shares first takes over one of the other's.
    fn ensure_jobs(&mut self) {
        let threads = rayon::current_num_threads().max(1);
        let shares = if threads > 1 {
            threads * SHARES_PER_THREAD
        } else {
            1
        };
        if self.jobs.len() == shares {
            return;
        }
        let scratch_len = [
            self.row_fwd.get_scratch_len(),
            self.row_inv.get_scratch_len(),
            self.col_fwd.get_inplace_scratch_len(),
            self.col_inv.get_inplace_scratch_len(),
        ]
        .into_iter()
        .max()
        .unwrap_or(0);
        self.jobs = (0..shares)
            .map(|_| FftJob {
                row: vec![0.0; self.mx],
                hat: vec![Complex::default(); BLOCK * self.cx],
                scratch: vec![Complex::default(); scratch_len],
            })
            .collect();
    }

    /// The real transforms of `rows` rows of `width` values of `src` (zero padded to mx) into
    /// `row_spec` (rows of cx bins), one contiguous share of rows per rayon job.
    fn rows_forward_parallel(&mut self, src: &[f64], width: usize, rows: usize) {
        use rayon::prelude::*;
        self.ensure_jobs();
        let (mx, cx) = (self.mx, self.cx);
        self.row_spec.resize(rows * cx, Complex::default());
        let row_fwd = &self.row_fwd;
        let rows_per = rows.div_ceil(self.jobs.len());
        self.row_spec[..rows * cx]
            .par_chunks_mut(rows_per * cx)
            .zip(src.par_chunks(rows_per * width))
            .zip(self.jobs.par_iter_mut())
            .for_each(|((hats, src), job)| {
                let row = &mut job.row[..mx];
                for (hat, src) in hats.chunks_exact_mut(cx).zip(src.chunks_exact(width)) {
                    row[..width].copy_from_slice(src);
                    row[width..].fill(0.0);
                    row_fwd
                        .process_with_scratch(row, hat, &mut job.scratch)
                        .expect("sizes fixed by the plan");
                }
            });
    }

    /// The column stage of the parallel transforms: each column of the spectrum gathered from
    /// the first `rows` rows of `row_spec` and completed by `below`, transformed; for a product
    /// (zeros below), also multiplied by the kernel's transform and transformed back. One
    /// contiguous share of columns per rayon job.
    fn columns_parallel(&mut self, rows: usize, below: Below) {
        let product = below == Below::Zero;
        use rayon::prelude::*;
        let (my, cx, cs) = (self.my, self.cx, self.cs);
        let cols_per = cx.div_ceil(self.jobs.len());
        let (col_fwd, col_inv) = (&self.col_fwd, &self.col_inv);
        let (row_spec, kernel_hat) = (&self.row_spec, &self.kernel_hat);
        self.spec
            .par_chunks_mut(cols_per * cs)
            .zip(self.jobs.par_iter_mut())
            .enumerate()
            .for_each(|(b, (cols, job))| {
                // BLOCK columns at a time: each row's BLOCK half-spectrum bins are read at once.
                for (g, group) in cols.chunks_mut(BLOCK * cs).enumerate() {
                    let (c0, ng) = (b * cols_per + g * BLOCK, group.len() / cs);
                    for r in 0..rows {
                        for (k, &z) in row_spec[r * cx + c0..][..ng].iter().enumerate() {
                            group[k * cs + r] = z;
                        }
                    }
                    // Each step over the whole group before the next (faster than each
                    // column through all steps in turn).
                    for col in group.chunks_exact_mut(cs) {
                        let col = &mut col[..my];
                        below.fill(col, rows);
                        col_fwd.process_with_scratch(col, &mut job.scratch);
                    }
                    if !product {
                        continue;
                    }
                    for (k, col) in group.chunks_exact_mut(cs).enumerate() {
                        let kc = &kernel_hat[(c0 + k) * cs..][..my];
                        for (z, &kv) in col.iter_mut().zip(kc) {
                            *z *= kv;
                        }
                    }
                    for col in group.chunks_exact_mut(cs) {
                        col_inv.process_with_scratch(&mut col[..my], &mut job.scratch);
                    }
                }
            });
    }

    /// 2D forward DFT of `src` (`rows` rows of `width` values, zero padded to mx along x, each
    /// column completed to my by `below`) into `spec`.
    fn forward(&mut self, src: &[f64], width: usize, rows: usize, below: Below) {
        let (mx, my, cx, cs) = (self.mx, self.my, self.cx, self.cs);
        for r0 in (0..rows).step_by(BLOCK) {
            let nb = BLOCK.min(rows - r0);
            for b in 0..nb {
                let row = &mut self.rows[b * mx..][..mx];
                row[..width].copy_from_slice(&src[(r0 + b) * width..][..width]);
                row[width..].fill(0.0);
                self.row_fwd
                    .process_with_scratch(
                        row,
                        &mut self.rows_hat[b * cx..][..cx],
                        &mut self.row_scratch,
                    )
                    .expect("sizes fixed by the plan");
            }
            for c in 0..cx {
                let col = &mut self.spec[c * cs + r0..][..nb];
                for (b, z) in col.iter_mut().enumerate() {
                    *z = self.rows_hat[b * cx + c];
                }
            }
        }
        for col in self.spec.chunks_exact_mut(cs) {
            let col = &mut col[..my];
            below.fill(col, rows);
            self.col_fwd
                .process_with_scratch(col, &mut self.col_scratch);
        }
    }
}

#[cfg(test)]
mod tests;
