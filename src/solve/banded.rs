//! Gaussian elimination for banded systems (no pivoting), the line solver of the relaxation.
//!
//! Storage: row-major band, `a[i * (2 bw + 1) + (j + bw - i)]` holds A_ij for |i - j| <= bw.
//! The elimination fills nothing outside the band. Used only on the diagonally dominated line
//! systems of the smoother; a zero or non-finite pivot is reported, not divided by.

/// Solve A x = b in place (b becomes x). Returns false on a zero or non-finite pivot.
pub fn solve_banded(a: &mut [f64], m: usize, bw: usize, b: &mut [f64]) -> bool {
    let w = 2 * bw + 1;
    debug_assert!(a.len() >= m * w && b.len() >= m);
    for k in 0..m {
        let piv = a[k * w + bw];
        if piv == 0.0 || !piv.is_finite() {
            return false;
        }
        for i in k + 1..(k + bw + 1).min(m) {
            let f = a[i * w + (k + bw - i)] / piv;
            if f == 0.0 {
                continue;
            }
            for j in k..(k + bw + 1).min(m) {
                a[i * w + (j + bw - i)] -= f * a[k * w + (j + bw - k)];
            }
            b[i] -= f * b[k];
        }
    }
    for k in (0..m).rev() {
        let mut s = b[k];
        for j in k + 1..(k + bw + 1).min(m) {
            s -= a[k * w + (j + bw - k)] * b[j];
        }
        b[k] = s / a[k * w + bw];
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_dense_solution() {
        // A diagonally dominant band matrix with a known solution.
        let (m, bw) = (40usize, 3usize);
        let w = 2 * bw + 1;
        let mut a = vec![0.0; m * w];
        let x: Vec<f64> = (0..m)
            .map(|i| (i as f64 * 0.7).sin() + 0.1 * i as f64)
            .collect();
        let entry = |i: usize, j: usize| {
            if i == j {
                10.0 + i as f64 * 0.01
            } else {
                1.0 / (1.0 + (i as f64 - j as f64).abs() + 0.3 * (i as f64))
            }
        };
        let mut b = vec![0.0; m];
        for i in 0..m {
            for j in i.saturating_sub(bw)..(i + bw + 1).min(m) {
                a[i * w + (j + bw - i)] = entry(i, j);
                b[i] += entry(i, j) * x[j];
            }
        }
        assert!(solve_banded(&mut a, m, bw, &mut b));
        for i in 0..m {
            assert!((b[i] - x[i]).abs() < 1e-12, "{i}: {} vs {}", b[i], x[i]);
        }
    }
}
