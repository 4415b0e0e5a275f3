//! The hot loops never allocate (issue 21, "no allocation inside sweeps"): once a solve has
//! sized its scratch buffers, a relaxation sweep on any level and a full FAS cycle's smoothing,
//! transfers and residuals (everything but the coarsest level's dense Newton solve) allocate
//! nothing. Counted by a global allocator that counts the allocations of the thread under test
//! only (the other tests of this binary run beside it).

use ehlmap::model::case::{LineCase, PointCase};
use ehlmap::solve::line::multigrid::LineMultigrid;
use ehlmap::solve::line::LineSolveParams;
use ehlmap::solve::multilevel::{Contact, Multigrid};
use ehlmap::solve::point::multigrid::PointMultigrid;
use ehlmap::solve::point::PointSolveParams;
use ehlmap::solve::Status;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    /// Whether this thread's allocations are counted, and how many there were.
    static COUNTING: Cell<bool> = const { Cell::new(false) };
    static COUNT: Cell<usize> = const { Cell::new(0) };
}

fn note() {
    // try_with: the thread-locals may be gone while a thread shuts down.
    let _ = COUNTING.try_with(|on| {
        if on.get() {
            let _ = COUNT.try_with(|c| c.set(c.get() + 1));
        }
    });
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        note();
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        note();
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        note();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// The allocations `f` makes on this thread.
fn allocations(f: impl FnOnce()) -> usize {
    COUNT.with(|c| c.set(0));
    COUNTING.with(|on| on.set(true));
    f();
    COUNTING.with(|on| on.set(false));
    COUNT.with(|c| c.get())
}

#[test]
fn the_counter_sees_an_allocation() {
    // The oracle of the tests below: a Vec allocates once.
    let n = allocations(|| {
        let v = std::hint::black_box(vec![1u8; 100]);
        drop(v);
    });
    assert_eq!(n, 1);
}

/// Three sweeps on every level above the coarsest of a solved multigrid allocate nothing.
fn sweeps_allocate_nothing<C: Contact>(mut mg: Multigrid<C>, what: &str) {
    let info = mg.solve();
    assert_eq!(info.status, Status::Converged, "{what}: {}", info.reason);
    for l in 1..mg.levels.len() {
        let n = allocations(|| {
            for _ in 0..3 {
                mg.relax_level(l);
            }
        });
        assert_eq!(n, 0, "{what} level {l}: {n} allocations in three sweeps");
    }
}

#[test]
fn point_sweeps_allocate_nothing_after_the_first_solve() {
    let case = PointCase::new(20.0, 10.0, 1.0).expect("valid case");
    let mut p = PointSolveParams::default();
    p.mg.grid = 129;
    sweeps_allocate_nothing(PointMultigrid::new(&case, &p.mg), "point");
}

#[test]
fn line_sweeps_allocate_nothing_after_the_first_solve() {
    let case = LineCase::new(20.0, 10.0).expect("valid case");
    let mut p = LineSolveParams::default();
    p.mg.grid = 4097;
    sweeps_allocate_nothing(LineMultigrid::new(&case, &p.mg), "line");
}
