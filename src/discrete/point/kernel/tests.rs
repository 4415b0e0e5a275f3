//! Tests of the point deformation kernel (`super`): the FFT product against the direct sum
//! (fixed seeds), the pool's plan and product against the serial ones to the bit, the kernel
//! against quadrature, and the flat film of the Hertz pressure.

use super::*;
use crate::discrete::testing::{assert_agree, lcg, nodes};
use std::f64::consts::PI;

#[test]
fn fft_product_equals_direct_product() {
    let mut seed = 7;
    for &(nx, ny) in &[
        (2usize, 2usize),
        (2, 7),
        (3, 5),
        (17, 9),
        (33, 65),
        (64, 31),
    ] {
        let (hx, hy) = (4.0 / (nx - 1) as f64, 3.0 / (ny - 1) as f64);
        let k = kernel2d(nx, ny, hx, hy);
        let mut plan = DeformPlan2d::new(&k, nx, ny);
        // Two fields through one plan: the work buffers must not leak between calls.
        for _ in 0..2 {
            let p: Vec<f64> = (0..nx * ny).map(|_| lcg(&mut seed) - 0.3).collect();
            let mut a = vec![0.0; nx * ny];
            let mut b = vec![0.0; nx * ny];
            direct_product2d(&k, nx, ny, &p, &mut a);
            plan.apply(&p, &mut b);
            assert_agree(&a, &b, 1e-10, &format!("{nx}x{ny}"));
            // The parallel product: the same to the bit on 1, 2 and 3 threads.
            let mut runs = vec![];
            for threads in [1, 2, 3] {
                let mut c = vec![0.0; nx * ny];
                rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap()
                    .install(|| plan.apply_parallel(&p, &mut c, 1.0));
                runs.push(c);
            }
            assert_agree(&a, &runs[0], 1e-10, &format!("parallel {nx}x{ny}"));
            assert!(
                runs.iter().all(|c| c == &runs[0]),
                "{nx}x{ny}: threads differ"
            );
        }
    }
}

#[test]
fn the_pool_makes_the_serial_kernel_plan_and_product_to_the_bit() {
    let mut seed = 11;
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    for &(nx, ny) in &[(2usize, 2usize), (3, 5), (17, 9), (33, 65), (64, 31)] {
        let (hx, hy) = (4.0 / (nx - 1) as f64, 3.0 / (ny - 1) as f64);
        let k = kernel2d(nx, ny, hx, hy);
        let mut plan = DeformPlan2d::new(&k, nx, ny);
        let p: Vec<f64> = (0..nx * ny).map(|_| lcg(&mut seed) - 0.3).collect();
        let mut serial = vec![0.0; nx * ny];
        plan.apply(&p, &mut serial);
        let scale = 0.2026;
        let scaled: Vec<f64> = serial.iter().map(|v| v * scale).collect();
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let (kp, mut pp) = pool.install(|| {
                let kp = kernel2d_on(nx, ny, hx, hy, true);
                let pp = DeformPlan2d::new_on(&kp, nx, ny, true);
                (kp, pp)
            });
            let what = format!("{nx}x{ny}, {threads} threads");
            assert_eq!(bits(&kp), bits(&k), "kernel, {what}");
            assert_eq!(bits(&pp.kernel_hat), bits(&plan.kernel_hat), "plan, {what}");
            let mut c = vec![0.0; nx * ny];
            pool.install(|| pp.apply_parallel(&p, &mut c, 1.0));
            assert_eq!(bits(&c), bits(&serial), "product, {what}");
            pool.install(|| pp.apply_parallel(&p, &mut c, scale));
            assert_eq!(bits(&c), bits(&scaled), "scaled product, {what}");
        }
    }
}

/// Integral of 1/r over [0, a] x [0, b] (a, b > 0) in polar coordinates about the corner:
/// int_0^t0 a/cos(t) dt + int_t0^{pi/2} b/sin(t) dt, t0 = atan(b/a), by composite Simpson.
fn quadrant_quad(a: f64, b: f64) -> f64 {
    let simpson = |f: &dyn Fn(f64) -> f64, lo: f64, hi: f64| {
        let m = 2000;
        let h = (hi - lo) / m as f64;
        let mut s = f(lo) + f(hi);
        for q in 1..m {
            s += f(lo + q as f64 * h) * if q % 2 == 1 { 4.0 } else { 2.0 };
        }
        s * h / 3.0
    };
    let t0 = (b / a).atan();
    simpson(&|t: f64| a / t.cos(), 0.0, t0) + simpson(&|t: f64| b / t.sin(), t0, PI / 2.0)
}

/// Integral of 1/r over a rectangle away from the origin: midpoint rule on m and 2m points per
/// direction, Richardson-extrapolated.
fn midpoint_quad(x1: f64, x2: f64, y1: f64, y2: f64) -> f64 {
    let mid = |m: usize| {
        let (dx, dy) = ((x2 - x1) / m as f64, (y2 - y1) / m as f64);
        let mut s = 0.0;
        for a in 0..m {
            let x = x1 + (a as f64 + 0.5) * dx;
            for b in 0..m {
                let y = y1 + (b as f64 + 0.5) * dy;
                s += 1.0 / (x * x + y * y).sqrt();
            }
        }
        s * dx * dy
    };
    let (c, f) = (mid(200), mid(400));
    (4.0 * f - c) / 3.0
}

#[test]
fn kernel_matches_quadrature() {
    let (hx, hy) = (0.1, 0.07);
    let (nx, ny) = (40, 40);
    let k = kernel2d(nx, ny, hx, hy);
    // Cells that do not contain the field point (the integrand is smooth on them).
    for &(dx, dy) in &[
        (1usize, 0usize),
        (0, 1),
        (1, 1),
        (2, 3),
        (5, 0),
        (0, 7),
        (39, 39),
    ] {
        let (xc, yc) = (dx as f64 * hx, dy as f64 * hy);
        let q = midpoint_quad(xc - hx / 2.0, xc + hx / 2.0, yc - hy / 2.0, yc + hy / 2.0);
        let kd = k[dy * nx + dx];
        assert!(
            (q - kd).abs() <= 1e-9 * kd,
            "K({dx},{dy}) = {kd} vs quadrature {q}"
        );
    }
    // The singular self cell: four corner quadrants, each by polar quadrature.
    let q0 = 4.0 * quadrant_quad(hx / 2.0, hy / 2.0);
    assert!((q0 - k[0]).abs() <= 1e-12 * k[0], "K(0,0) {} vs {q0}", k[0]);
    // Square self cell of side h: 8 (h/2) asinh(1) = 4 h ln(1 + sqrt 2).
    let h = 0.3;
    let sq = kernel2d(1, 1, h, h)[0];
    let exact = 4.0 * h * (1.0 + 2f64.sqrt()).ln();
    assert!((sq - exact).abs() <= 1e-15, "{sq} vs {exact}");
    // An off-centre rectangle around the field point (all four corners in different quadrants).
    let (x1, x2, y1, y2) = (-0.3, 0.7, -0.2, 0.5);
    let q = quadrant_quad(-x1, -y1)
        + quadrant_quad(x2, -y1)
        + quadrant_quad(-x1, y2)
        + quadrant_quad(x2, y2);
    let r = rect_integral(x1, x2, y1, y2);
    assert!((q - r).abs() <= 1e-12 * r, "{r} vs {q}");
    // Swapping the spacings transposes the kernel.
    let kt = kernel2d(ny, nx, hy, hx);
    for dy in 0..ny {
        for dx in 0..nx {
            assert!((k[dy * nx + dx] - kt[dx * ny + dy]).abs() <= 1e-15 * k[0]);
        }
    }
}

#[test]
fn hertz_pressure_gives_flat_film_in_contact() {
    // Circular contact in Hertzian units: a Boussinesq displacement (2/pi^2) int P/r under
    // P = sqrt(1 - R^2) equals 1 - R^2/2 for R <= 1, so X^2/2 + Y^2/2 + (2/pi^2) int P/r = 1.
    let n = 129;
    let (h, x) = nodes(-2.0, 2.0, n);
    let mut p = vec![0.0; n * n];
    for k in 0..n {
        for i in 0..n {
            p[k * n + i] = (1.0 - x[i] * x[i] - x[k] * x[k]).max(0.0).sqrt();
        }
    }
    let mut w = vec![0.0; n * n];
    DeformPlan2d::new(&kernel2d(n, n, h, h), n, n).apply(&p, &mut w);
    let coef = 2.0 / (PI * PI);
    let g = |i: usize, k: usize| x[i] * x[i] / 2.0 + x[k] * x[k] / 2.0 + coef * w[k * n + i];
    let centre = g(n / 2, n / 2);
    assert!((centre - 1.0).abs() < 1e-3, "constant {centre}, exact 1");
    let mut worst = 0.0f64;
    for k in 0..n {
        for i in 0..n {
            if x[i].hypot(x[k]) < 0.8 {
                worst = worst.max((g(i, k) - centre).abs());
            }
        }
    }
    // (1.4e-4 at n = 129, falling as h^2: 4.2e-4 at 65, 3.9e-5 at 257.)
    assert!(worst < 5e-4, "film not flat in contact: {worst}");
    // Outside the contact the gap opens: positive separation at R = 1.5.
    let i = (1.5 - x[0]) / h;
    assert!(g(i as usize, n / 2) - centre > 0.1);
}
