//! `Simulation::advance` makes no heap allocation per call once warmed up: a counting global
//! allocator wraps the system allocator; after a first call, 1000 advances (and reading the
//! outputs) must not allocate. Checked for the default FFR scene, the segment rod and the
//! automotive rod with stress outputs.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use flexrod::scene::RodModelKind;
use flexrod::{CrankInput, Scene, Simulation};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);
/// Count only while a measurement is on (the test harness allocates on other threads).
static COUNTING: AtomicBool = AtomicBool::new(false);

thread_local! {
    static MEASURED_THREAD: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

fn counted() -> bool {
    COUNTING.load(Ordering::Relaxed) && MEASURED_THREAD.try_with(|c| c.get()).unwrap_or(false)
}

static IN_TRACE: AtomicBool = AtomicBool::new(false);

/// With FLEXROD_ALLOC_TRACE set, print where the first few counted allocations come from.
fn trace() {
    if ALLOCATIONS.load(Ordering::Relaxed) <= 5
        && std::env::var_os("FLEXROD_ALLOC_TRACE").is_some()
        && !IN_TRACE.swap(true, Ordering::SeqCst)
    {
        eprintln!(
            "allocation:\n{}",
            std::backtrace::Backtrace::force_capture()
        );
        IN_TRACE.store(false, Ordering::SeqCst);
    }
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if counted() && !IN_TRACE.load(Ordering::SeqCst) {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
            trace();
        }
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if counted() {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if counted() {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made by 1000 `set_input` + `advance` + `outputs` calls after a warm-up call.
fn allocations_per_1000_advances(scene: &Scene, h: f64) -> usize {
    let w = 150.0;
    let mut sim = Simulation::new(scene).unwrap();
    sim.start(
        0.0,
        CrankInput {
            angle: 0.0,
            speed: w,
            acceleration: 0.0,
            jerk: 0.0,
        },
        0.0,
    )
    .unwrap();
    sim.advance(h).unwrap();
    MEASURED_THREAD.with(|c| c.set(true));
    ALLOCATIONS.store(0, Ordering::SeqCst);
    COUNTING.store(true, Ordering::SeqCst);
    let mut peak: f64 = 0.0;
    for k in 1..=1000 {
        let t = k as f64 * h;
        sim.set_input(CrankInput {
            angle: w * t,
            speed: w,
            acceleration: 0.0,
            jerk: 0.0,
        })
        .unwrap();
        sim.advance(h).unwrap();
        peak = peak.max(sim.outputs().deflection_rel.abs());
    }
    COUNTING.store(false, Ordering::SeqCst);
    MEASURED_THREAD.with(|c| c.set(false));
    assert!(peak > 0.0);
    ALLOCATIONS.load(Ordering::SeqCst)
}

/// `Simulation::advance` makes no heap allocation after its first call: the backup copy of the
/// state reuses its buffers (`DaeState::clone_from`), the Newton and output workspaces are sized
/// once. Run with FLEXROD_ALLOC_TRACE=1 (without --release, for line numbers) to see where
/// allocations come from if this fails.
#[test]
fn advance_does_not_allocate() {
    let ffr = Scene::benchmark();
    // Communication step = 3 internal steps, so sub-stepping is exercised too.
    let a_ffr = allocations_per_1000_advances(&ffr, 3e-4);
    // A communication step far below the internal step: dense output (steps held ahead,
    // interpolated states).
    let a_dense = allocations_per_1000_advances(&ffr, 1e-5);
    let mut seg = Scene::benchmark();
    seg.rod.model = RodModelKind::Segments;
    seg.rod.elements = 16;
    let a_seg = allocations_per_1000_advances(&seg, 1e-4);
    // The automotive rod: section table, stress outputs (the section forces at every
    // communication point), mass-loaded modes and residual flexibility.
    let automotive = Scene::from_file(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenes/automotive_rod.toml"
    )))
    .unwrap();
    assert!(automotive.outputs.stress);
    let a_auto = allocations_per_1000_advances(&automotive, 1e-5);
    println!("allocations in 1000 advances after the first: FFR {a_ffr}, FFR at 1e-5 s (dense output) {a_dense}, segments {a_seg}, automotive with stress outputs {a_auto}");
    assert_eq!(a_ffr, 0);
    assert_eq!(a_dense, 0);
    assert_eq!(a_seg, 0);
    assert_eq!(a_auto, 0);
}
