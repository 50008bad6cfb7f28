//! Step benchmarks: one internal step, one revolution at 150 rad/s, and the cost of
//! `fmi2DoStep` beyond `Simulation::advance` with the same communication step (the exported C
//! functions called in-process; default scene, NULL resource location, so the instance uses
//! the compiled-in default scene after checking the GUID).
//! `fmi2DoStep` at a 1e-5 s communication step (target: <= 1.5 us a call), without inputs and
//! with the crank angle and speed set before every call as an importer does.
//! Run: `cargo bench --bench step`.

use std::ffi::CString;
use std::ptr;

use criterion::{criterion_group, criterion_main, Criterion};
use flexrod::drive::{self, communication_grid, CrankDrive};
use flexrod::fmi::ffi::{self, fmi2CallbackFunctions};
use flexrod::fmi::ModelDescription;
use flexrod::{CrankInput, Scene, Simulation};
use std::hint::black_box;

const W: f64 = 150.0;

fn started(scene: &Scene) -> Simulation {
    let mut sim = Simulation::new(scene).unwrap();
    sim.start(
        0.0,
        CrankInput {
            angle: 0.0,
            speed: W,
            acceleration: 0.0,
            jerk: 0.0,
        },
        0.0,
    )
    .unwrap();
    sim
}

fn one_step(c: &mut Criterion) {
    let scene = Scene::benchmark();
    let h = scene.solver.step;
    let mut sim = started(&scene);
    // Constant speed: the input law of the start continues, no set_input needed.
    c.bench_function(
        "advance by one internal step (default scene, h 1e-4, outputs included)",
        |b| {
            b.iter(|| {
                sim.advance(black_box(h)).unwrap();
                black_box(sim.outputs().deflection_rel)
            })
        },
    );
    let mut fast = Scene::benchmark();
    fast.rod.modes = 3;
    fast.solver.step = 3e-4;
    fast.solver.method = flexrod::scene::SolverMethod::GeneralizedAlpha;
    let mut sim = started(&fast);
    c.bench_function(
        "advance by one internal step (generalized-alpha, 8 el, 3 modes, h 3e-4)",
        |b| {
            b.iter(|| {
                sim.advance(black_box(3e-4)).unwrap();
                black_box(sim.outputs().deflection_rel)
            })
        },
    );
}

fn one_revolution(c: &mut Criterion) {
    let scene = Scene::benchmark();
    let dt = 1e-4;
    let grid = communication_grid(
        0.0,
        dt,
        (2.0 * std::f64::consts::PI / W / dt).round() as usize,
    );
    let law = CrankDrive::Constant { speed: W };
    let mut sim = Simulation::new(&scene).unwrap();
    c.bench_function(
        "one revolution at 150 rad/s (default scene, outputs every 1e-4 s)",
        |b| {
            b.iter(|| {
                let record = drive::run(&mut sim, &law, 0.0, &grid).unwrap();
                black_box(record.peak_deflection_rel())
            })
        },
    );
}

fn do_step_overhead(c: &mut Criterion) {
    let scene = Scene::benchmark();
    let h = scene.experiment.step_size;
    let guid = CString::new(ModelDescription::for_scene(&scene).unwrap().guid).unwrap();
    let name = CString::new("bench").unwrap();
    let functions = fmi2CallbackFunctions {
        logger: None,
        allocate_memory: None,
        free_memory: None,
        step_finished: None,
        component_environment: ptr::null_mut(),
    };
    // SAFETY: valid NUL-terminated strings, a callback struct that outlives the instance,
    // NULL resource location (the default scene is used if the GUID matches).
    let comp = unsafe {
        ffi::fmi2Instantiate(
            name.as_ptr(),
            1,
            guid.as_ptr(),
            ptr::null(),
            &functions,
            0,
            0,
        )
    };
    assert!(!comp.is_null(), "fmi2Instantiate failed");
    unsafe {
        assert_eq!(ffi::fmi2SetupExperiment(comp, 0, 0.0, 0.0, 0, 0.0), 0);
        assert_eq!(ffi::fmi2EnterInitializationMode(comp), 0);
        assert_eq!(ffi::fmi2ExitInitializationMode(comp), 0);
    }
    let mut t = 0.0;
    c.bench_function("fmi2DoStep h 1e-4 (default scene)", |b| {
        b.iter(|| {
            // SAFETY: comp is a live instance in StepComplete; t is its current time.
            let status = unsafe { ffi::fmi2DoStep(comp, t, black_box(h), 1) };
            assert_eq!(status, 0);
            t += h;
        })
    });
    // SAFETY: comp came from fmi2Instantiate and is freed once.
    unsafe { ffi::fmi2FreeInstance(comp) };
    let mut sim = started(&scene);
    c.bench_function(
        "Simulation::advance h 1e-4 (default scene, same work as fmi2DoStep)",
        |b| {
            b.iter(|| {
                sim.advance(black_box(h)).unwrap();
                black_box(sim.outputs().deflection_rel)
            })
        },
    );
}

/// An instance of the default scene in StepComplete at t = 0.
fn instance() -> ffi::fmi2Component {
    let scene = Scene::benchmark();
    let guid = CString::new(ModelDescription::for_scene(&scene).unwrap().guid).unwrap();
    let name = CString::new("bench").unwrap();
    let functions = Box::leak(Box::new(fmi2CallbackFunctions {
        logger: None,
        allocate_memory: None,
        free_memory: None,
        step_finished: None,
        component_environment: ptr::null_mut(),
    }));
    // SAFETY: valid NUL-terminated strings, a callback struct that lives to the end of the
    // process, NULL resource location (the default scene is used if the GUID matches).
    let comp = unsafe {
        ffi::fmi2Instantiate(
            name.as_ptr(),
            1,
            guid.as_ptr(),
            ptr::null(),
            functions,
            0,
            0,
        )
    };
    assert!(!comp.is_null(), "fmi2Instantiate failed");
    // SAFETY: comp is a live instance.
    unsafe {
        assert_eq!(ffi::fmi2SetupExperiment(comp, 0, 0.0, 0.0, 0, 0.0), 0);
        assert_eq!(ffi::fmi2EnterInitializationMode(comp), 0);
        assert_eq!(ffi::fmi2ExitInitializationMode(comp), 0);
    }
    comp
}

/// `fmi2DoStep` at a 1e-5 s communication step, per call, in process.
fn do_step_1e5(c: &mut Criterion) {
    let h = 1e-5;
    let comp = instance();
    let mut t = 0.0;
    c.bench_function("fmi2DoStep h 1e-5 (default scene)", |b| {
        b.iter(|| {
            // SAFETY: comp is a live instance in StepComplete; t is its current time.
            let status = unsafe { ffi::fmi2DoStep(comp, t, black_box(h), 1) };
            assert_eq!(status, 0);
            t += h;
        })
    });
    // SAFETY: comp came from fmi2Instantiate and is freed once.
    unsafe { ffi::fmi2FreeInstance(comp) };
    let comp = instance();
    let mut t = 0.0;
    let vr = [1u32, 2];
    c.bench_function(
        "fmi2SetReal(crank.angle, crank.speed) + fmi2DoStep h 1e-5 (default scene)",
        |b| {
            b.iter(|| {
                let values = [W * t, W];
                // SAFETY: comp is live; vr and values hold two entries each.
                let status = unsafe {
                    ffi::fmi2SetReal(comp, vr.as_ptr(), 2, values.as_ptr());
                    ffi::fmi2DoStep(comp, t, black_box(h), 1)
                };
                assert_eq!(status, 0);
                t += h;
            })
        },
    );
    // SAFETY: comp came from fmi2Instantiate and is freed once.
    unsafe { ffi::fmi2FreeInstance(comp) };
}

criterion_group!(
    benches,
    one_step,
    one_revolution,
    do_step_overhead,
    do_step_1e5
);
criterion_main!(benches);
