//! The values of an axis: at most [`MAX_AXIS_VALUES`] of them, each rounded by [`canonical`] so
//! that a value (and the id of its case) does not depend on how it was computed; a range expands
//! by [`expand_range`].

/// Largest number of values one axis may expand to.
pub const MAX_AXIS_VALUES: usize = 100_000;

/// Round to 12 significant digits, so that values computed from ranges (and their case ids) do
/// not depend on the last bits of `powf`.
pub fn canonical(x: f64) -> f64 {
    if x == 0.0 {
        return 0.0; // also turns -0 into 0
    }
    format!("{x:.11e}").parse().unwrap_or(x)
}

/// `count` values from `from` to `to` (both included), evenly spaced in x or in log x.
pub fn expand_range(from: f64, to: f64, count: usize, log: bool) -> Vec<f64> {
    if count == 1 {
        return vec![canonical(from)];
    }
    (0..count)
        .map(|i| {
            let t = i as f64 / (count - 1) as f64;
            let x = if i == 0 {
                from
            } else if i == count - 1 {
                to
            } else if log {
                from * (to / from).powf(t)
            } else {
                from + (to - from) * t
            };
            canonical(x)
        })
        .collect()
}
