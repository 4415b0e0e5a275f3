//! The load balance: a safeguarded secant iteration for H0 on the scalar equation
//! G(H0) = h sum P(H0) - g = 0, where P(H0) is the pressure converged by multigrid cycles at fixed H0.
//!
//! G decreases with H0 (a wider gap carries less load). Each accepted evaluation narrows a
//! bracket [lo, hi] with G(lo) > 0 > G(hi); the next H0 is the secant step from the last two
//! evaluations, replaced by regula falsi when it leaves the bracket, and limited to `max_step`
//! (a fraction of the central film) while no bracket exists. The slope is carried from level to
//! level, so on the finest level one or two steps usually suffice. A secant slope from two
//! evaluations whose P had not settled can be near zero (G hardly changed over a small step of
//! H0) and would send the next step to the limit: a new slope is kept at least a
//! [`SLOPE_FLATTENING`]-th of the last one in magnitude (a steeper one, which shortens the step, is
//! taken as it is: high-L line contacts need it).

/// The largest factor by which one evaluation flattens the slope estimate.
pub const SLOPE_FLATTENING: f64 = 10.0;

/// State of the H0 iteration.
#[derive(Clone, Debug)]
pub struct LoadBalance {
    slope: f64,
    lo: Option<(f64, f64)>,
    hi: Option<(f64, f64)>,
    last: Option<(f64, f64)>,
    /// Evaluations made, and the one that set each bracket end.
    count: usize,
    lo_at: usize,
    hi_at: usize,
    /// Bracket ends older than this many evaluations are dropped (None: kept).
    memory: Option<usize>,
}

impl LoadBalance {
    /// Start with an estimate of dG/dH0 (negative).
    pub fn new(slope: f64) -> Self {
        LoadBalance {
            slope: if slope.is_finite() && slope < 0.0 {
                slope
            } else {
                -1.0
            },
            lo: None,
            hi: None,
            last: None,
            count: 0,
            lo_at: 0,
            hi_at: 0,
            memory: None,
        }
    }

    /// Drop bracket ends older than `evaluations` evaluations: for evaluations whose P has not
    /// settled at its H0 (one multigrid cycle each), where an old end may bracket a root that
    /// the settled G does not have, and the iteration would stall at that end.
    pub fn with_memory(mut self, evaluations: usize) -> Self {
        self.memory = Some(evaluations);
        self
    }

    /// Forget the bracket and the last point (a new grid level has a slightly different G).
    pub fn reset(&mut self) {
        self.lo = None;
        self.hi = None;
        self.last = None;
    }

    /// The current estimate of d(load)/dH0.
    pub fn slope(&self) -> f64 {
        self.slope
    }

    /// Record G at `h0` and return the next H0.
    pub fn next(&mut self, h0: f64, g: f64, max_step: f64) -> f64 {
        if let Some((h1, g1)) = self.last {
            let dh = h0 - h1;
            if dh.abs() > 1e-14 * (1.0 + h0.abs()) {
                let s = (g - g1) / dh;
                if s.is_finite() && s < 0.0 {
                    self.slope = s.min(self.slope / SLOPE_FLATTENING);
                }
            }
        }
        self.last = Some((h0, g));
        self.count += 1;
        if g > 0.0 {
            self.lo = Some((h0, g));
            self.lo_at = self.count;
        } else {
            self.hi = Some((h0, g));
            self.hi_at = self.count;
        }
        if let Some(mem) = self.memory {
            if self.count - self.lo_at >= mem {
                self.lo = None;
            }
            if self.count - self.hi_at >= mem {
                self.hi = None;
            }
        }
        let mut cand = h0 - g / self.slope;
        match (self.lo, self.hi) {
            (Some((hl, gl)), Some((hh, gh))) => {
                let (a, b) = (hl.min(hh), hl.max(hh));
                if !(cand > a && cand < b) {
                    cand = hl - gl * (hh - hl) / (gh - gl);
                    if !(cand > a && cand < b) {
                        cand = 0.5 * (a + b);
                    }
                }
            }
            _ => cand = h0 + (cand - h0).clamp(-max_step, max_step),
        }
        cand
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_root_of_decreasing_function() {
        // G(H0) = 1/H0 - 2 (rigid-like: load ~ 1/H0), root 0.5, bad initial slope.
        let g = |h: f64| 1.0 / h - 2.0;
        let mut lb = LoadBalance::new(-0.1);
        let mut h = 0.3;
        for _ in 0..30 {
            h = lb.next(h, g(h), 0.1);
        }
        assert!((h - 0.5).abs() < 1e-10, "{h}");
    }

    #[test]
    fn a_flat_secant_from_an_unsettled_evaluation_does_not_send_h0_to_its_limit() {
        // G barely changes over the first step (P had not settled at the new H0): the secant
        // slope, -2e-7, would ask for a step of 2.5e6, held only by the step limit of 100.
        let mut lb = LoadBalance::new(-1.0);
        let h1 = lb.next(1.0, 0.5, 100.0);
        assert_eq!(h1, 1.5);
        let h2 = lb.next(h1, 0.4999999, 100.0);
        // The slope flattens by SLOPE_FLATTENING at most: the step grows 10 times, no more.
        assert!(
            (h2 - (h1 + SLOPE_FLATTENING * 0.4999999)).abs() < 1e-12,
            "{h2}"
        );
        assert!((lb.slope() + 1.0 / SLOPE_FLATTENING).abs() < 1e-15);
        // A steeper secant is taken as it is.
        let h3 = lb.next(h2, -1e6, 100.0);
        let secant = (-1e6 - 0.4999999) / (h2 - h1);
        assert!((lb.slope() / secant - 1.0).abs() < 1e-12, "{}", lb.slope());
        assert!(h3 < h2);
    }

    #[test]
    fn a_stale_bracket_end_stalls_the_iteration_unless_it_is_forgotten() {
        // The first evaluation, at 0.6, comes from an unsettled P and has the wrong sign (G > 0
        // where the settled G(0.6) = -1/3 < 0): the bracket [0.6, ...] excludes the root 0.5.
        let g = |h: f64| 1.0 / h - 2.0;
        let run = |lb: &mut LoadBalance| {
            let mut h = lb.next(0.6, 0.1, 0.1);
            for _ in 0..40 {
                h = lb.next(h, g(h), 0.1);
            }
            h
        };
        let stalled = run(&mut LoadBalance::new(-1.0));
        assert!((stalled - 0.6).abs() < 1e-6, "{stalled}");
        let h = run(&mut LoadBalance::new(-1.0).with_memory(4));
        assert!((h - 0.5).abs() < 1e-10, "{h}");
    }
}
