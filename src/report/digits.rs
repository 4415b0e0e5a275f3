//! Numbers as the report prints them: coefficients to 5 significant digits, ready to copy.

/// `v` with 5 significant digits (scientific notation outside [1e-4, 1e6)).
pub fn sig5(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let e = v.abs().log10().floor() as i32;
    if !(-4..6).contains(&e) {
        return format!("{v:.4e}");
    }
    format!("{v:.*}", (4 - e).max(0) as usize)
}
