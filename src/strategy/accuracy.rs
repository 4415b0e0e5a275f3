//! Discretisation error estimates by Richardson extrapolation over grids refined by 2.
//!
//! For a quantity converging as Q_h = Q + C h^p, three grids (h, h/2, h/4) give the observed order
//! p = log2((Q_h - Q_{h/2})/(Q_{h/2} - Q_{h/4})) and the extrapolated value
//! Q* = Q_{h/4} + (Q_{h/4} - Q_{h/2})/(2^p - 1); two grids assume p = 2.

use serde::{Deserialize, Serialize};

/// Result of a Richardson extrapolation.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Richardson {
    /// Observed order (the assumed one for two grids).
    pub order: f64,
    /// Extrapolated value.
    pub extrapolated: f64,
    /// Estimated relative error of the finest value, |Q_fine - Q*| / |Q*|.
    pub error_estimate: f64,
}

/// Richardson from the values on grids h, h/2, h/4 (coarse to fine).
pub fn richardson3(coarse: f64, mid: f64, fine: f64) -> Richardson {
    let ratio = (coarse - mid) / (mid - fine);
    let order = if ratio.is_finite() && ratio > 1.0 {
        ratio.log2()
    } else {
        f64::NAN
    };
    let p = if order.is_finite() { order } else { 2.0 };
    let extrapolated = fine + (fine - mid) / (2f64.powf(p) - 1.0);
    Richardson {
        order,
        extrapolated,
        error_estimate: ((fine - extrapolated) / extrapolated).abs(),
    }
}

/// Richardson's estimate of the relative error of the fine value from grids h (`coarse`) and
/// h/2 (`fine`) for a quantity converging at `order`: |Q_h/2 - Q_h| / ((2^p - 1) |Q_h/2|).
pub fn relative_error(coarse: f64, fine: f64, order: f64) -> f64 {
    let factor = 1.0 / (2f64.powf(order) - 1.0);
    factor * ((fine - coarse) / fine).abs()
}

/// Richardson from two grids h, h/2 assuming second order.
pub fn richardson2(coarse: f64, fine: f64) -> Richardson {
    let extrapolated = fine + (fine - coarse) / 3.0;
    Richardson {
        order: 2.0,
        extrapolated,
        error_estimate: ((fine - extrapolated) / extrapolated).abs(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovers_order_and_limit() {
        let q = |h: f64| 5.0 + 0.7 * h * h + 0.01 * h * h * h;
        let r = richardson3(q(0.1), q(0.05), q(0.025));
        assert!((r.order - 2.0).abs() < 0.02, "{r:?}");
        assert!((r.extrapolated - 5.0).abs() < 1e-6);
        let r2 = richardson2(q(0.05), q(0.025));
        assert!((r2.extrapolated - 5.0).abs() < 1e-5);
    }
}
