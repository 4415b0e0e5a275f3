//! The current rayon pool kept awake for the span of one parallel solve ([`KeepAwake`]).
//!
//! A point solve with parallel rows ([`crate::solve::params::MgParams::parallel`]) forks and
//! joins the pool many times per work unit: each relaxation sweep, FFT product, film update,
//! residual and transfer of a parallel level is a region of tens to hundreds of microseconds.
//! Between regions an idle rayon worker goes to sleep within microseconds, and waking it takes
//! as long as a short region on a virtual machine (docs/performance.md has the measurement).
//!
//! Contract: while a [`KeepAwake`] lives, every other worker of the current pool, up to the
//! machine's cores less one, runs a job that executes pending pool work as soon as it appears
//! (`rayon::yield_now`) and spins otherwise; dropping the guard ends those jobs. Invariants:
//! - no result changes: which thread runs a piece of a parallel stage never does (the stages
//!   split their work by the grid alone);
//! - the calling thread is never occupied (its own copy of the job returns at once), so the
//!   solve cannot wait on itself;
//! - on a pool of one thread, or on a machine of one core, it does nothing.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Arc;

/// Guard that keeps the other workers of the current rayon pool spinning until it drops (see
/// the module docs).
#[must_use = "the workers are kept awake only while the guard lives"]
pub struct KeepAwake {
    stop: Option<Arc<AtomicBool>>,
}

impl KeepAwake {
    /// Occupy the other workers of the current pool (nothing on one thread or one core).
    pub fn start() -> Self {
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        let spinners = rayon::current_num_threads().min(cores).saturating_sub(1);
        if spinners == 0 {
            return KeepAwake { stop: None };
        }
        let stop = Arc::new(AtomicBool::new(false));
        let taken = Arc::new(AtomicUsize::new(0));
        let caller = rayon::current_thread_index();
        let flag = Arc::clone(&stop);
        rayon::spawn_broadcast(move |ctx| {
            if Some(ctx.index()) == caller || taken.fetch_add(1, Ordering::Relaxed) >= spinners {
                return;
            }
            while !flag.load(Ordering::Acquire) {
                if rayon::yield_now() != Some(rayon::Yield::Executed) {
                    std::hint::spin_loop();
                }
            }
        });
        KeepAwake { stop: Some(stop) }
    }

    /// Whether workers were occupied.
    pub fn active(&self) -> bool {
        self.stop.is_some()
    }
}

impl Drop for KeepAwake {
    fn drop(&mut self) {
        if let Some(stop) = &self.stop {
            stop.store(true, Ordering::Release);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pool(n: usize) -> rayon::ThreadPool {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .expect("a pool")
    }

    #[test]
    fn parallel_work_under_the_guard_gives_the_serial_result_and_ends() {
        // Sums of fixed chunks joined on the pool while the guard lives, many times: each
        // region completes (the guard neither starves nor blocks the pool) and equals the
        // serial sum to the bit; after the guard drops the pool is free for other work.
        use rayon::prelude::*;
        let v: Vec<f64> = (0..100_000)
            .map(|i| ((i * 7919) % 1000) as f64 * 0.1)
            .collect();
        let serial: Vec<f64> = v.chunks(1000).map(|c| c.iter().sum()).collect();
        let p = pool(2);
        p.install(|| {
            let awake = KeepAwake::start();
            let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
            assert_eq!(awake.active(), cores > 1);
            for _ in 0..200 {
                let par: Vec<f64> = v.par_chunks(1000).map(|c| c.iter().sum()).collect();
                assert_eq!(par, serial);
            }
        });
        let after: Vec<f64> = p.install(|| v.par_chunks(1000).map(|c| c.iter().sum()).collect());
        assert_eq!(after, serial);
    }

    #[test]
    fn a_one_thread_pool_is_left_alone() {
        pool(1).install(|| assert!(!KeepAwake::start().active()));
    }
}
