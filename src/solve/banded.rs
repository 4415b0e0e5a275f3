//! Gaussian elimination for banded systems (no pivoting), the line solver of the relaxation.
//!
//! Storage: row-major band, `a[i * (2 bw + 1) + (j + bw - i)]` holds A_ij for |i - j| <= bw.
//! The elimination fills nothing outside the band. Used only on the diagonally dominated line
//! systems of the smoother; a zero or non-finite pivot is reported, not divided by.

/// Solve A x = b in place (b becomes x). Returns false on a zero or non-finite pivot.
/// Half bandwidths 2 to 8 run a copy specialised at compile time (the smoothers' bands 1 to 7),
/// with the same operations in the same order: the results are identical.
pub fn solve_banded(a: &mut [f64], m: usize, bw: usize, b: &mut [f64]) -> bool {
    match bw {
        2 => solve_fixed::<2>(a, m, b),
        3 => solve_fixed::<3>(a, m, b),
        4 => solve_fixed::<4>(a, m, b),
        5 => solve_fixed::<5>(a, m, b),
        6 => solve_fixed::<6>(a, m, b),
        7 => solve_fixed::<7>(a, m, b),
        8 => solve_fixed::<8>(a, m, b),
        _ => solve_any(a, m, bw, b),
    }
}

/// [`solve_banded`] for any half bandwidth.
fn solve_any(a: &mut [f64], m: usize, bw: usize, b: &mut [f64]) -> bool {
    let w = 2 * bw + 1;
    debug_assert!(a.len() >= m * w && b.len() >= m);
    for k in 0..m {
        if !eliminate_tail(a, m, bw, b, k) {
            return false;
        }
    }
    for k in (0..m).rev() {
        substitute_tail(a, m, bw, b, k);
    }
    true
}

/// Elimination step k with bounds for rows near the end (the pivot row's band entries at and
/// right of the diagonal subtracted from the rows below it); false on a bad pivot.
#[inline]
fn eliminate_tail(a: &mut [f64], m: usize, bw: usize, b: &mut [f64], k: usize) -> bool {
    let w = 2 * bw + 1;
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
    true
}

/// Back substitution of row k with bounds for rows near the end.
#[inline]
fn substitute_tail(a: &[f64], m: usize, bw: usize, b: &mut [f64], k: usize) {
    let w = 2 * bw + 1;
    let mut s = b[k];
    for j in k + 1..(k + bw + 1).min(m) {
        s -= a[k * w + (j + bw - k)] * b[j];
    }
    b[k] = s / a[k * w + bw];
}

/// [`solve_any`] with the half bandwidth a constant: away from the last BW rows the loops have
/// fixed lengths and no bounds to test.
fn solve_fixed<const BW: usize>(a: &mut [f64], m: usize, b: &mut [f64]) -> bool {
    let w = 2 * BW + 1;
    debug_assert!(a.len() >= m * w && b.len() >= m);
    let mut pivot_row = [0.0f64; 9];
    let body = m.saturating_sub(BW);
    for k in 0..body {
        let piv = a[k * w + BW];
        if piv == 0.0 || !piv.is_finite() {
            return false;
        }
        pivot_row[..=BW].copy_from_slice(&a[k * w + BW..][..=BW]);
        let bk = b[k];
        for ii in 1..=BW {
            let base = (k + ii) * w + BW - ii;
            let f = a[base] / piv;
            if f == 0.0 {
                continue;
            }
            for (x, &pk) in a[base..][..=BW].iter_mut().zip(&pivot_row[..=BW]) {
                *x -= f * pk;
            }
            b[k + ii] -= f * bk;
        }
    }
    for k in body..m {
        if !eliminate_tail(a, m, BW, b, k) {
            return false;
        }
    }
    for k in (body..m).rev() {
        substitute_tail(a, m, BW, b, k);
    }
    for k in (0..body).rev() {
        let row = &a[k * w + BW..][..=BW];
        let mut s = b[k];
        for (&ak, &bj) in row[1..].iter().zip(&b[k + 1..][..BW]) {
            s -= ak * bj;
        }
        b[k] = s / row[0];
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

    #[test]
    fn specialised_bands_equal_the_general_elimination_to_the_bit() {
        let mut seed = 11u64;
        for bw in 1..=9 {
            for m in [1usize, 2, bw, bw + 1, 3 * bw + 2, 50] {
                let w = 2 * bw + 1;
                let mut a: Vec<f64> = (0..m * w)
                    .map(|_| crate::discrete::testing::lcg(&mut seed) - 0.5)
                    .collect();
                for i in 0..m {
                    a[i * w + bw] += 4.0 + bw as f64;
                }
                let b: Vec<f64> = (0..m)
                    .map(|_| crate::discrete::testing::lcg(&mut seed))
                    .collect();
                let (mut a1, mut b1) = (a.clone(), b.clone());
                let (mut a2, mut b2) = (a, b);
                assert!(solve_banded(&mut a1, m, bw, &mut b1));
                assert!(solve_any(&mut a2, m, bw, &mut b2));
                assert_eq!(b1, b2, "bw {bw}, m {m}");
            }
        }
    }
}
