//! A warm run allocates nothing: the propagation loop works in the workspace's buffers.

// A counting global allocator needs `unsafe impl GlobalAlloc`; the library itself
// forbids unsafe code (see src/lib.rs).
#![allow(unsafe_code)]

use geotracks::mesh::io::read_mesh;
use geotracks::Sources;
use geotracks::{Density, Euclidean, Metric, Options, Solver, Source, Stop, Workspace};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

/// Counts allocations made by this test binary.
struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn allocations_of_warm_runs<M: Metric>(solver: &Solver<M>) -> usize {
    let mut ws = solver.workspace();
    // Full runs, and local ones (which clear only what they touched).
    // (Spot is about a unit across: this reaches a few percent of it.)
    let local = Stop::NONE.with_max_distance(0.1);
    let runs = |ws: &mut Workspace| {
        for s in [0, 1000, 2000] {
            solver.run(ws, &[s]).unwrap();
            solver
                .run(ws, Sources::from(&[Source::new(s)]).until(&local))
                .unwrap();
        }
    };
    // Warm up: the first runs size the buffers (and the queue's buckets).
    runs(&mut ws);
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    runs(&mut ws);
    ALLOCATIONS.load(Ordering::Relaxed) - before
}

#[test]
fn warm_runs_do_not_allocate() {
    let mesh = read_mesh(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/spot.obj")).unwrap();
    let solver = Solver::new(&mesh, Euclidean, &Options::DEFAULT).unwrap();
    assert_eq!(allocations_of_warm_runs(&solver), 0);
    let density = Density::constant(&mesh, 2.0).unwrap();
    let solver = Solver::new(&mesh, &density, &Options::DEFAULT).unwrap();
    assert_eq!(allocations_of_warm_runs(&solver), 0);
}
