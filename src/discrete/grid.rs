//! Grid geometry shared by line and point domains.

/// The interval `[x_in, x_out]` shifted to the nearest one of the same width on which, with `n0`
/// equal intervals, X = 0 is a node (not the first or last): returns the new `(x_in, x_out)`.
pub fn align_origin(x_in: f64, x_out: f64, n0: usize) -> (f64, f64) {
    let h0 = (x_out - x_in) / n0 as f64;
    let i0 = (-x_in / h0).round().clamp(1.0, n0 as f64 - 1.0);
    let x_in = -i0 * h0;
    (x_in, x_in + n0 as f64 * h0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn origin_is_an_interior_node_and_the_width_is_kept() {
        for (a, b, n) in [(-4.3, 1.7, 16), (-0.2, 9.0, 8), (-30.0, 0.01, 32)] {
            let (x_in, x_out) = align_origin(a, b, n);
            let h = (x_out - x_in) / n as f64;
            assert!(((x_out - x_in) - (b - a)).abs() < 1e-12);
            let i0 = -x_in / h;
            assert!((i0 - i0.round()).abs() < 1e-9 && i0 >= 1.0 && i0 <= n as f64 - 1.0);
        }
    }
}
