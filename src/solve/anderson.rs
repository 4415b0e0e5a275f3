//! Anderson acceleration of depth one for the finest level's FAS cycles.
//!
//! The cycle is a fixed-point map x -> G(x) of the finest level's state x = (P, H0). After
//! cycle k, with f_k = G(x_k) - x_k and the differences df = f_k - f_(k-1),
//! dg = G(x_k) - G(x_(k-1)), the accelerated state is
//!
//! x_(k+1) = G(x_k) - gamma dg,  gamma = <df, f_k> / <df, df>
//!
//! (inner products over the pressures; H0 takes the same gamma), then P = max(P, 0) for the
//! cavitation condition. For a mode that contracts by rho per cycle gamma = rho / (rho - 1),
//! so the step extrapolates that mode to its limit (Aitken); a fixed point of the cycle is one
//! of the accelerated iteration. References: Walker & Ni, SIAM J. Numer. Anal. 49 (2011)
//! 1715 (the method); Washio & Oosterlee, ETNA 6 (1997) 271 (acceleration of nonlinear
//! multigrid). Memory: three vectors of the finest level's length, allocated at the first
//! cycle and reused; no allocation afterwards.

/// The history of the accelerated iteration: the state before the current cycle, the previous
/// cycle's f and G.
#[derive(Default)]
pub struct Anderson {
    /// The pressures before the current cycle ([`Anderson::begin`]), then their f.
    x: Vec<f64>,
    f_prev: Vec<f64>,
    g_prev: Vec<f64>,
    g_prev_h0: f64,
    has_prev: bool,
}

impl Anderson {
    /// Forget the history (a new solve, or a cycle that hardly contracted the residual).
    pub fn reset(&mut self) {
        self.has_prev = false;
    }

    /// Record the pressures before a cycle (H0 enters through G only: gamma is fitted on the
    /// pressures).
    pub fn begin(&mut self, p: &[f64]) {
        self.x.clear();
        self.x.extend_from_slice(p);
    }

    /// Replace the state (P, H0) after the cycle by the accelerated one. Returns false when it
    /// is left as it is (the first cycle after [`Anderson::reset`], or no usable step).
    pub fn mix(&mut self, p: &mut [f64], h0: &mut f64) -> bool {
        assert_eq!(p.len(), self.x.len(), "Anderson::begin was not called");
        // x becomes f = G(x) - x, and gamma's inner products are summed on the way.
        let (mut dd, mut df) = (0.0, 0.0);
        let prev = if self.has_prev { &self.f_prev[..] } else { &[] };
        for (i, (f, &g)) in self.x.iter_mut().zip(p.iter()).enumerate() {
            *f = g - *f;
            if let Some(&fp) = prev.get(i) {
                let d = *f - fp;
                dd += d * d;
                df += d * *f;
            }
        }
        let gamma = (self.has_prev && dd > 0.0)
            .then(|| df / dd)
            .filter(|g| g.is_finite());
        std::mem::swap(&mut self.x, &mut self.f_prev);
        self.has_prev = true;
        let prev_h0 = std::mem::replace(&mut self.g_prev_h0, *h0);
        let Some(gamma) = gamma else {
            // No step: G(x) is kept and becomes the previous G.
            self.g_prev.clear();
            self.g_prev.extend_from_slice(p);
            return false;
        };
        *h0 -= gamma * (*h0 - prev_h0);
        for (q, gp) in p.iter_mut().zip(self.g_prev.iter_mut()) {
            let g = *q;
            // A node the cycle left cavitated stays so: the step would revive it with a
            // fraction of its previous pressure, cycle after cycle.
            if g > 0.0 {
                *q = (g - gamma * (g - *gp)).max(0.0);
            }
            *gp = g;
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A linear fixed-point map x -> A x + b with two modes contracting by 0.9 and 0.2.
    fn g(x: &[f64]) -> Vec<f64> {
        vec![0.9 * x[0] + 1.0, 0.2 * x[1] + 2.0]
    }

    #[test]
    fn one_mode_is_extrapolated_to_its_limit_in_one_step() {
        // x -> 0.9 x + 1 has the fixed point 10; plain iteration from 0 needs about 130
        // steps to reach 1e-5, the accelerated one reaches it at the second cycle.
        let mut a = Anderson::default();
        let (mut x, mut h0) = (vec![0.0], 0.0);
        for _ in 0..2 {
            a.begin(&x);
            x[0] = 0.9 * x[0] + 1.0;
            h0 = 0.9 * h0 + 1.0;
            a.mix(&mut x, &mut h0);
        }
        assert!((x[0] - 10.0).abs() < 1e-12, "{}", x[0]);
        assert!((h0 - 10.0).abs() < 1e-12, "{h0}");
    }

    #[test]
    fn two_modes_converge_faster_than_the_plain_iteration_and_stay_non_negative() {
        // The slow mode (0.9) dominates the plain iteration: after 12 cycles its error is
        // 0.9^12 = 0.28 of the start. The accelerated iteration is a secant method on the
        // combined residual and converges to the fixed point (10, 2.5).
        let mut a = Anderson::default();
        let (mut x, mut plain, mut h0) = (vec![0.0, 0.0], vec![0.0, 0.0], 0.0);
        for _ in 0..12 {
            a.begin(&x);
            x = g(&x);
            a.mix(&mut x, &mut h0);
            plain = g(&plain);
            assert!(x.iter().all(|v| *v >= 0.0));
        }
        let err = |v: &[f64]| (v[0] - 10.0).abs().max((v[1] - 2.5).abs());
        assert!(err(&plain) > 2.0, "plain {}", err(&plain));
        assert!(err(&x) < 1e-3, "accelerated {}", err(&x));
    }

    #[test]
    fn a_reset_starts_the_history_again() {
        let mut a = Anderson::default();
        let (mut x, mut h0) = (vec![1.0], 0.0);
        a.begin(&x);
        x[0] = 2.0;
        assert!(!a.mix(&mut x, &mut h0), "the first cycle has no history");
        a.begin(&x);
        x[0] = 2.5;
        assert!(a.mix(&mut x, &mut h0));
        a.reset();
        a.begin(&x);
        x[0] = 4.0;
        assert!(!a.mix(&mut x, &mut h0));
        assert_eq!(x[0], 4.0);
    }
}
