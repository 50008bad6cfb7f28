//! Speed: the numbers of the README's speed fragment, measured in process on this
//! machine (medians of repeats; the machine's load shows in them, compare rows of one run):
//! - two revolutions of the default scene at 150 rad/s, outputs every 3e-4 s (`auto`: the
//!   exponential RK4(3), ETDRK4, on the closed-form minimal coordinates), and the same with
//!   `solver.method = "rk43"` (the classic pair) and `"dopri5"`;
//! - one right-hand side on the modal coordinates: the closed form (an intermediate stage, and a
//!   last stage with the frame angle and the multipliers) against the general partitioned
//!   evaluation (the path without the closed form);
//! - `fmi2DoStep` at a 1e-5 s communication step through the exported C functions, without
//!   inputs and with `fmi2SetReal` of the crank angle and speed before every call;
//! - the benchmark rod at 300 rad/s on the chain on its modes, two revolutions in one step;
//! - the accuracy of the default scene against the geometrically exact beam is in the
//!   `exact-beam` fragment (`cargo test --release --test geometric_reference`).
//!
//! `cargo run --release --example speed` prints the table; with `FLEXROD_BLESS=1` it also
//! writes `docs/generated/speed-minimal.md`.

use std::ffi::CString;
use std::hint::black_box;
use std::ptr;
use std::time::Instant;

use flexrod::drive::{self, communication_grid, CrankDrive};
use flexrod::fmi::ffi::{self, fmi2CallbackFunctions};
use flexrod::fmi::ModelDescription;
use flexrod::integrator::{GeneralPath, PartitionedRhs};
use flexrod::scene::SolverMethod;
use flexrod::{CrankInput, Scene, Simulation};

const W: f64 = 150.0;

fn median(mut x: Vec<f64>) -> f64 {
    x.sort_by(|a, b| a.total_cmp(b));
    x[x.len() / 2]
}

/// Median over `repeats` runs of the wall time `f` reports itself, s (after one warm-up run).
fn reported(repeats: usize, mut f: impl FnMut() -> std::time::Duration) -> f64 {
    f();
    median((0..repeats).map(|_| f().as_secs_f64()).collect())
}

/// Median wall time of `f` over `repeats` calls, s (after one warm-up call).
fn time(repeats: usize, mut f: impl FnMut()) -> f64 {
    f();
    median(
        (0..repeats)
            .map(|_| {
                let t = Instant::now();
                f();
                t.elapsed().as_secs_f64()
            })
            .collect(),
    )
}

/// Two revolutions at 150 rad/s, outputs every 3e-4 s: (ms, steps, right-hand sides, peak).
fn two_revolutions(scene: &Scene) -> (f64, u64, u64, f64) {
    let grid = communication_grid(0.0, 3e-4, 279);
    let law = CrankDrive::Constant { speed: W };
    let mut sim = Simulation::new(scene).unwrap();
    let mut peak = 0.0;
    let s = time(41, || {
        peak = drive::run(&mut sim, &law, 0.0, &grid)
            .unwrap()
            .peak_deflection_rel();
    });
    let stats = sim.stats();
    (s * 1e3, stats.steps, stats.newton_iterations, peak)
}

/// One right-hand side of the default scene, ns: closed form (intermediate, last stage), general.
fn right_hand_sides() -> [f64; 3] {
    let mut sim = Simulation::new(&Scene::benchmark()).unwrap();
    let input = CrankInput {
        angle: 0.3,
        speed: W,
        acceleration: 0.0,
        jerk: 0.0,
    };
    sim.start(0.0, input, 0.0).unwrap();
    let mech = sim.mechanism();
    let sys = mech.system(sim.state());
    let general = GeneralPath(&sys);
    let elastic: Vec<usize> = mech.rod.elastic_coordinates().unwrap().collect();
    let (z, zd, mut zdd) = ([1e-4, -2e-5, 1e-6], [1e-2, 1e-3, -1e-3], [0.0; 3]);
    let n = 20_000;
    let mut out = [0.0; 3];
    for (k, complete) in [(0, false), (1, true), (2, true)] {
        let system: &dyn flexrod::integrator::DaeSystem = if k == 2 { &general } else { &sys };
        let mut rhs = PartitionedRhs::new(system, elastic.clone());
        rhs.q.copy_from_slice(&sim.state().dae.q);
        out[k] =
            1e9 * time(31, || {
                for i in 0..n {
                    let t = black_box(1e-3 + 1e-9 * i as f64);
                    rhs.evaluate_stage(system, t, &z, &zd, &mut zdd, complete)
                        .unwrap();
                    if complete {
                        rhs.multipliers();
                    }
                }
            }) / n as f64;
    }
    out
}

/// `fmi2DoStep` at 1e-5 s in process, us a call: (no inputs, with `fmi2SetReal` of the crank),
/// of the default scene at 150 rad/s.
fn do_step() -> [f64; 2] {
    do_step_of(&Scene::benchmark(), None, W)
}

/// An instance of `scene`'s FMU in process, exported with its `resources/scene.toml` under
/// `resources` (a file: URI; `None`: the compiled-in default scene), with the Real values
/// `start` (value reference, value) set in initialization mode; freed on drop.
struct Instance {
    comp: ffi::fmi2Component,
    start: Vec<(u32, f64)>,
    // The strings and callbacks the instance was made with outlive it.
    _strings: [CString; 2],
    _resources: Option<CString>,
    _functions: Box<fmi2CallbackFunctions>,
}

impl Instance {
    fn new(scene: &Scene, resources: Option<&str>) -> Instance {
        Instance::with_start(scene, resources, &[])
    }

    fn with_start(scene: &Scene, resources: Option<&str>, start: &[(u32, f64)]) -> Instance {
        let resources = resources.map(|r| CString::new(r).unwrap());
        let location = resources.as_ref().map_or(ptr::null(), |r| r.as_ptr());
        let guid = CString::new(ModelDescription::for_scene(scene).unwrap().guid).unwrap();
        let name = CString::new("speed").unwrap();
        let functions = Box::new(fmi2CallbackFunctions {
            logger: None,
            allocate_memory: None,
            free_memory: None,
            step_finished: None,
            component_environment: ptr::null_mut(),
        });
        // SAFETY: valid NUL-terminated strings, a callback struct that outlives the instance,
        // a file: URI or NULL (the compiled-in default scene, GUID checked).
        let comp = unsafe {
            ffi::fmi2Instantiate(name.as_ptr(), 1, guid.as_ptr(), location, &*functions, 0, 0)
        };
        assert!(!comp.is_null());
        let instance = Instance {
            comp,
            start: start.to_vec(),
            _strings: [guid, name],
            _resources: resources,
            _functions: functions,
        };
        instance.initialize();
        instance
    }

    /// Experiment from t = 0, initialization mode entered, the start values set, and left: the
    /// instance at its start.
    fn initialize(&self) {
        // SAFETY: comp is a live instance in Instantiated; one reference and value per call.
        unsafe {
            assert_eq!(ffi::fmi2SetupExperiment(self.comp, 0, 0.0, 0.0, 0, 0.0), 0);
            assert_eq!(ffi::fmi2EnterInitializationMode(self.comp), 0);
            for (vr, value) in &self.start {
                assert_eq!(ffi::fmi2SetReal(self.comp, vr, 1, value), 0);
            }
            assert_eq!(ffi::fmi2ExitInitializationMode(self.comp), 0);
        }
    }

    /// Back to the start: `fmi2Reset`, then [`Instance::initialize`].
    fn restart(&self) {
        // SAFETY: comp is a live instance.
        assert_eq!(unsafe { ffi::fmi2Reset(self.comp) }, 0);
        self.initialize();
    }

    /// `fmi2DoStep(t, h)`: fmi2OK, or fmi2Warning (the error estimate passes the tolerance).
    fn do_step(&self, t: f64, h: f64) {
        // SAFETY: comp is live in StepComplete at time t.
        let status = unsafe { ffi::fmi2DoStep(self.comp, t, h, 1) };
        assert!(status == 0 || status == 1, "{status}");
    }
}

impl Drop for Instance {
    fn drop(&mut self) {
        // SAFETY: comp came from fmi2Instantiate and is freed once.
        unsafe { ffi::fmi2FreeInstance(self.comp) };
    }
}

/// As [`do_step`] for `scene` exported with its `resources/scene.toml` under `resources` (a
/// file: URI; `None`: the compiled-in default scene), crank at `w` rad/s.
fn do_step_of(scene: &Scene, resources: Option<&str>, w: f64) -> [f64; 2] {
    let h = 1e-5;
    let calls = 2000;
    let mut out = [0.0; 2];
    for (k, out) in out.iter_mut().enumerate() {
        let instance = Instance::new(scene, resources);
        let mut t = 0.0;
        let vr = [1u32, 2];
        let s = time(41, || {
            for _ in 0..calls {
                if k == 1 {
                    let values = [w * t, w];
                    // SAFETY: a live instance; two references and values.
                    let status =
                        unsafe { ffi::fmi2SetReal(instance.comp, vr.as_ptr(), 2, values.as_ptr()) };
                    assert_eq!(status, 0);
                }
                instance.do_step(t, h);
                t += h;
            }
        });
        *out = s * 1e6 / calls as f64;
    }
    out
}

/// One `fmi2DoStep` from the start to `t_end` s of `scene` exported as [`do_step_of`] does,
/// with the start values `start` ([`Instance`]), timed alone (median ms): before each,
/// `fmi2Reset` and the initialization, off the clock.
fn one_do_step_of(scene: &Scene, resources: Option<&str>, start: &[(u32, f64)], t_end: f64) -> f64 {
    let instance = Instance::with_start(scene, resources, start);
    1e3 * reported(41, || {
        instance.restart();
        let t = Instant::now();
        instance.do_step(0.0, t_end);
        t.elapsed()
    })
}

fn automotive() -> Scene {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/automotive_rod.toml");
    Scene::from_file(std::path::Path::new(path)).unwrap()
}

/// `scene` as an FMU's resources: `scene.toml` in a new folder `resources` under the temporary
/// directory (named `tag` and the process), removed on drop; its file: URI.
struct Resources(std::path::PathBuf);

impl Resources {
    fn new(scene: &Scene, tag: &str) -> Resources {
        let dir = std::env::temp_dir().join(format!("flexrod-speed-{tag}-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("resources")).unwrap();
        std::fs::write(dir.join("resources").join("scene.toml"), scene.to_toml()).unwrap();
        Resources(dir)
    }

    fn uri(&self) -> String {
        format!("file://{}", self.0.join("resources").display())
    }
}

impl Drop for Resources {
    fn drop(&mut self) {
        std::fs::remove_dir_all(&self.0).ok();
    }
}

/// The benchmark rod at 300 rad/s with the defaults (`rod.model = auto` takes the chain on its
/// modes; peak `|v_mid/L|` 0.07, where the FFR rod's linear field is 3.4 % off): two
/// revolutions from the undeformed start in one communication step (ms, steps, segments).
fn high_load_speed() -> (f64, u64, usize) {
    // The defaults with the crank at 300 rad/s from the start (in the FMU: crank.speed = 300
    // at initialization): `rod.model = auto` takes the chain on its modes.
    let w = 300.0;
    let t_end = 4.0 * std::f64::consts::PI / w;
    // The compiled-in default scene, crank.speed (value reference 2) set in initialization.
    let ms = one_do_step_of(&Scene::benchmark(), None, &[(2, w)], t_end);
    // The same run on `Simulation`: its steps and the segments `auto` took.
    let mut scene = Scene::benchmark();
    scene.experiment.crank_speed = w;
    let mut sim = Simulation::new(&scene).unwrap();
    drive::run(
        &mut sim,
        &CrankDrive::Constant { speed: w },
        0.0,
        &[0.0, t_end],
    )
    .unwrap();
    let built = &sim.mechanism().spec.rod;
    assert_eq!(built.model, flexrod::rod::RodModelKind::ModalSegments);
    (ms, sim.stats().steps, built.elements)
}

/// The automotive rod: two revolutions at 628.3 rad/s from the undeformed start in one
/// communication step (ms, steps, right-hand sides); the engine run of
/// `flexrod::drive::engine` (ramp to 6000 rpm, gas pulse, 60 ms: ms); `fmi2DoStep` at 1e-5 s
/// with the crank set before every call (us); with the gas pulse as a `[slider.gas_force]`
/// table, two revolutions in one communication step (ms), the engine run on its row grid, with
/// the crank set every 1e-3 s and rows every 1e-4 s and every 1e-3 s (ms), and the steps of
/// the two revolutions with the table.
fn automotive_speed() -> (f64, u64, u64, f64, f64, [f64; 4], u64) {
    let scene = automotive();
    let w = scene.experiment.crank_speed;
    let grid = [0.0, 4.0 * std::f64::consts::PI / w];
    // The scene's FMU: the instance reads `resources/scene.toml`.
    let resources = Resources::new(&scene, "automotive");
    let uri = resources.uri();
    // Two revolutions in one `fmi2DoStep` (the start, `fmi2ExitInitializationMode`, off the
    // clock); the same run on `Simulation` counts its steps.
    let ms = one_do_step_of(&scene, Some(&uri), &[], grid[1]);
    let mut sim = Simulation::new(&scene).unwrap();
    drive::run(&mut sim, &CrankDrive::Constant { speed: w }, 0.0, &grid).unwrap();
    let stats = sim.stats();
    // The engine runs' own wall time (`Simulation::new` excluded: the instance is built once).
    let engine = 1e3
        * reported(11, || {
            flexrod::drive::engine::EngineRun::automotive()
                .run(&scene)
                .unwrap()
                .1
        });
    // The gas pulse inside the model (`[slider.gas_force]`): two revolutions at full speed
    // with the pulse after the second top dead centre, in one communication step; the engine
    // run with the table on its 2e-5 s row grid.
    let setup = flexrod::drive::engine::EngineRun::automotive();
    let constant = flexrod::drive::engine::EngineRun {
        ramp: 0.0,
        stop: 0.02,
        firing_angle: 2.0 * std::f64::consts::PI + 15f64.to_radians(),
        ..setup
    };
    let mut with_gas = scene.clone();
    with_gas.slider.gas_force = Some(constant.gas_table());
    let gas_resources = Resources::new(&with_gas, "gas");
    let gas_ms = one_do_step_of(&with_gas, Some(&gas_resources.uri()), &[], grid[1]);
    let mut sim_gas = Simulation::new(&with_gas).unwrap();
    drive::run(&mut sim_gas, &CrankDrive::Constant { speed: w }, 0.0, &grid).unwrap();
    let gas_steps = sim_gas.stats().steps;
    let engine_table = 1e3
        * reported(11, || {
            setup.run_with_gas_table(&scene, setup.sample).unwrap().1
        });
    // As a master with input derivatives drives it: the crank set every 1e-3 s with its
    // acceleration and jerk, a row every 1e-4 s and every 1e-3 s (tests/automotive_reference.rs
    // checks it against the exact beam with rows every 2e-5 s).
    let engine_sparse = 1e3
        * reported(11, || {
            setup.run_with_sparse_input(&scene, 1e-3, 1e-4).unwrap().1
        });
    let engine_coarse = 1e3
        * reported(11, || {
            setup.run_with_sparse_input(&scene, 1e-3, 1e-3).unwrap().1
        });
    let [_, step] = do_step_of(&scene, Some(&uri), w);
    (
        ms,
        stats.steps,
        stats.newton_iterations,
        engine,
        step,
        [gas_ms, engine_table, engine_sparse, engine_coarse],
        gas_steps,
    )
}

fn main() {
    let (
        a_ms,
        a_steps,
        a_rhs,
        a_engine,
        a_step,
        [a_gas, a_engine_table, a_engine_sparse, a_engine_coarse],
        a_gas_steps,
    ) = automotive_speed();
    let (ms, steps, rhs, peak) = two_revolutions(&Scene::benchmark());
    let mut dopri = Scene::benchmark();
    dopri.solver.method = SolverMethod::Dopri5;
    let (ms_dp, steps_dp, rhs_dp, _) = two_revolutions(&dopri);
    let mut classic = Scene::benchmark();
    classic.solver.method = SolverMethod::Rk43;
    let (ms_c, steps_c, rhs_c, _) = two_revolutions(&classic);
    let [rhs_stage, rhs_last, rhs_general] = right_hand_sides();
    let [step, step_inputs] = do_step();
    let (high_ms, high_steps, high_segments) = high_load_speed();
    let simulated = 4.0 * std::f64::consts::PI / W;
    let text = format!(
        "<!-- written by `FLEXROD_BLESS=1 cargo run --release --example speed`: rerun it, do not edit -->
| measured in process (medians; `cargo run --release --example speed`) | value |
|---|---|
| two revolutions at 150 rad/s, default scene (`auto`: exponential RK4(3), ETDRK4, on minimal coordinates, tolerance 1e-3), outputs every 3e-4 s | {ms:.3} ms ({:.0} x real time); {steps} steps, {rhs} right-hand sides; peak v_mid/L {peak:.4e} |
| the same with `solver.method = \"rk43\"` (the classic RK4(3) pair) | {ms_c:.3} ms; {steps_c} steps, {rhs_c} right-hand sides |
| the same with `solver.method = \"dopri5\"` (Dormand-Prince on minimal coordinates) | {ms_dp:.3} ms; {steps_dp} steps, {rhs_dp} right-hand sides |
| one right-hand side on minimal coordinates: intermediate stage / last stage (frame angle, multipliers) | {rhs_stage:.0} ns / {rhs_last:.0} ns |
| one right-hand side by the general partitioned evaluation (no closed form) | {rhs_general:.0} ns |
| `fmi2DoStep` at a 1e-5 s communication step | {step:.2} us a call ({:.1} x real time) |
| `fmi2SetReal` (crank angle and speed) + `fmi2DoStep` at 1e-5 s | {step_inputs:.2} us a call |
| automotive rod (scenes/automotive_rod.toml: mass-loaded modes to 6 kHz, residual flexibility above, `auto`: exponential RK4(3), tolerance 1e-2), two revolutions at 628.3 rad/s from the undeformed start in one `fmi2DoStep` | {a_ms:.3} ms; {a_steps} steps, {a_rhs} right-hand sides |
| automotive rod, the engine run (ramp to 6000 rpm, gas pulse, 60 ms, 1e-5 s grid; here and below the instance built before the clock starts) | {a_engine:.2} ms |
| automotive rod, the engine run with the gas pulse as a `[slider.gas_force]` table (the crank on a 2e-5 s grid, a row at every point) | {a_engine_table:.2} ms |
| automotive rod, the engine run with the gas pulse as a table and the crank set every 1e-3 s (angle, speed, acceleration and jerk: `fmi2SetRealInputDerivatives`), a row every 1e-4 s | {a_engine_sparse:.2} ms ({:.0} x real time) |
| the same, a row every 1e-3 s (a 1 ms co-simulation step) | {a_engine_coarse:.2} ms ({:.0} x real time) |
| automotive rod, two revolutions at 628.3 rad/s with the gas pulse as a `[slider.gas_force]` table, in one `fmi2DoStep` | {a_gas:.2} ms; {a_gas_steps} steps |
| automotive rod, `fmi2SetReal` (crank angle and speed) + `fmi2DoStep` at 1e-5 s, 628.3 rad/s | {a_step:.2} us a call |
| benchmark rod at 300 rad/s (peak v_mid/L 0.07), the defaults (`rod.model = auto` takes the chain on its modes: {high_segments} segments for tolerance 1e-3, the band keeps 4 modes, shear by `auto`; exponential RK4(3)), two revolutions from the undeformed start in one `fmi2DoStep` | {high_ms:.2} ms; {high_steps} steps |
",
        simulated / (ms * 1e-3),
        1e-5 / (step * 1e-6),
        0.06 / (a_engine_sparse * 1e-3),
        0.06 / (a_engine_coarse * 1e-3),
    );
    print!("{text}");
    if std::env::var_os("FLEXROD_BLESS").is_some() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/docs/generated/speed-minimal.md"
        );
        std::fs::write(path, &text).unwrap();
        println!("wrote {path}");
    }
}
