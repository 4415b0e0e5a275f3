//! Line-contact elastic deformation: the logarithmic kernel integrated exactly over each pressure
//! cell, and its Toeplitz product computed by FFT with zero padding (DC-FFT) in O(N log N).
//!
//! With P piecewise constant on cells [X_j - h/2, X_j + h/2], the deformation at node i is
//! W_i = -(1/pi) sum_j K_{|i-j|} P_j with
//! K_d = integral_{(d-1/2)h}^{(d+1/2)h} ln|u| du = [u ln|u| - u]_{(d-1/2)h}^{(d+1/2)h}.
//! The product is a symmetric Toeplitz one, embedded in a circulant of length 2(n-1) for n nodes
//! (the wrap point, offset n-1, carries the same K on both sides because K is even), so one real
//! FFT pair gives it exactly. [`direct_product`] is the O(N^2) oracle.

use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use std::f64::consts::PI;
use std::sync::Arc;

/// K_d for d = 0..n on a grid of spacing h.
pub fn log_kernel(n: usize, h: f64) -> Vec<f64> {
    let prim = |u: f64| if u == 0.0 { 0.0 } else { u * u.abs().ln() - u };
    (0..n)
        .map(|d| {
            let d = d as f64;
            prim((d + 0.5) * h) - prim((d - 0.5) * h)
        })
        .collect()
}

/// Reference O(N^2) deformation product W_i = -(1/pi) sum_j K_{|i-j|} P_j.
pub fn direct_product(kernel: &[f64], p: &[f64], out: &mut [f64]) {
    let n = p.len();
    for (i, o) in out.iter_mut().enumerate().take(n) {
        let mut s = 0.0;
        for (j, &pj) in p.iter().enumerate() {
            s += kernel[i.abs_diff(j)] * pj;
        }
        *o = -s / PI;
    }
}

/// A reusable plan for the fast deformation product on one grid: FFT plans, the transformed kernel
/// and all work buffers are made once, so [`DeformPlan1d::apply`] never allocates.
pub struct DeformPlan1d {
    n: usize,
    fwd: Arc<dyn RealToComplex<f64>>,
    inv: Arc<dyn ComplexToReal<f64>>,
    kernel_hat: Vec<Complex<f64>>,
    buf: Vec<f64>,
    spec: Vec<Complex<f64>>,
    scratch: Vec<Complex<f64>>,
}

impl DeformPlan1d {
    /// Plan for `kernel.len()` nodes (at least 2).
    pub fn new(kernel: &[f64]) -> Self {
        let n = kernel.len();
        assert!(n >= 2, "a deformation plan needs at least two nodes");
        let len = 2 * (n - 1);
        let mut planner = RealFftPlanner::<f64>::new();
        let fwd = planner.plan_fft_forward(len);
        let inv = planner.plan_fft_inverse(len);
        let mut circ = vec![0.0; len];
        for (d, &k) in kernel.iter().enumerate() {
            circ[d] = k;
            if d > 0 {
                circ[len - d] = k;
            }
        }
        let mut kernel_hat = fwd.make_output_vec();
        let mut scratch =
            vec![Complex::default(); fwd.get_scratch_len().max(inv.get_scratch_len())];
        fwd.process_with_scratch(&mut circ, &mut kernel_hat, &mut scratch)
            .expect("sizes fixed by the plan");
        // Fold the inverse FFT's factor len and the -1/pi of the film equation into the kernel.
        let scale = -1.0 / (PI * len as f64);
        for c in kernel_hat.iter_mut() {
            *c *= scale;
        }
        DeformPlan1d {
            n,
            spec: fwd.make_output_vec(),
            buf: vec![0.0; len],
            fwd,
            inv,
            kernel_hat,
            scratch,
        }
    }

    /// Nodes of the grid the plan multiplies on.
    pub fn nodes(&self) -> usize {
        self.n
    }

    /// out_i = -(1/pi) sum_j K_{|i-j|} p_j; `p` and `out` have the plan's node count.
    pub fn apply(&mut self, p: &[f64], out: &mut [f64]) {
        let n = self.n;
        assert!(
            p.len() == n && out.len() == n,
            "deformation plan size mismatch"
        );
        self.buf[..n].copy_from_slice(p);
        self.buf[n..].fill(0.0);
        self.fwd
            .process_with_scratch(&mut self.buf, &mut self.spec, &mut self.scratch)
            .expect("sizes fixed by the plan");
        for (s, k) in self.spec.iter_mut().zip(&self.kernel_hat) {
            *s *= *k;
        }
        // The imaginary parts of the first and last bins are zero for a real signal; clear rounding.
        self.spec[0].im = 0.0;
        let last = self.spec.len() - 1;
        self.spec[last].im = 0.0;
        self.inv
            .process_with_scratch(&mut self.spec, &mut self.buf, &mut self.scratch)
            .expect("sizes fixed by the plan");
        out.copy_from_slice(&self.buf[..n]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discrete::testing::{assert_agree, lcg, nodes};

    #[test]
    fn fft_product_equals_direct_product() {
        let mut seed = 42;
        for &n in &[2usize, 3, 17, 64, 129, 1000, 1025] {
            let h = 6.0 / (n as f64 - 1.0).max(1.0);
            let k = log_kernel(n, h);
            let p: Vec<f64> = (0..n).map(|_| lcg(&mut seed)).collect();
            let mut a = vec![0.0; n];
            let mut b = vec![0.0; n];
            direct_product(&k, &p, &mut a);
            DeformPlan1d::new(&k).apply(&p, &mut b);
            assert_agree(&a, &b, 1e-10, &format!("n={n}"));
        }
    }

    #[test]
    fn kernel_matches_quadrature() {
        // K_d against a fine midpoint rule of ln|u| (d >= 1, where the integrand is smooth).
        let h = 0.1;
        let k = log_kernel(5, h);
        for (d, &kd) in k.iter().enumerate().skip(1) {
            let m = 20000;
            let a = (d as f64 - 0.5) * h;
            let s: f64 = (0..m)
                .map(|q| (a + (q as f64 + 0.5) * h / m as f64).ln())
                .sum::<f64>()
                * h
                / m as f64;
            assert!((s - kd).abs() < 1e-9, "d={d}");
        }
        // d = 0 analytically: 2[(h/2) ln(h/2) - h/2].
        assert!((k[0] - 2.0 * (0.5 * h * (0.5 * h).ln() - 0.5 * h)).abs() < 1e-15);
    }

    #[test]
    fn hertz_pressure_gives_flat_film_in_contact() {
        // Exact: for P = sqrt(1 - X^2), X^2/2 - (1/pi) int P ln|X - X'| is constant on |X| < 1.
        let n = 2049;
        let (h, x) = nodes(-2.0, 2.0, n);
        let p: Vec<f64> = x.iter().map(|&x| (1.0 - x * x).max(0.0).sqrt()).collect();
        let mut w = vec![0.0; n];
        DeformPlan1d::new(&log_kernel(n, h)).apply(&p, &mut w);
        let g: Vec<f64> = (0..n).map(|i| x[i] * x[i] / 2.0 + w[i]).collect();
        let centre = g[n / 2];
        for i in 0..n {
            if x[i].abs() < 0.9 {
                assert!(
                    (g[i] - centre).abs() < 2e-4,
                    "X={} dev={}",
                    x[i],
                    g[i] - centre
                );
            }
        }
    }
}
