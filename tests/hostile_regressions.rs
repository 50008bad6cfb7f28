//! Values past the documented ranges at every boundary (serialized states, scene files, the
//! instance handle), each as a regression test. The cases that could crash or hang the
//! process run in a child process (this test binary re-executed with `FLEXROD_HOSTILE_CHILD`
//! naming the case), and the parent asserts a clean exit within a time bound.
//!
//! - a pre-initialization state whose scene carries `[solver] max_halvings = 100000` or
//!   `max_newton_iterations = 1e9` (checksum recomputed): refused by
//!   `fmi2DeSerializeFMUstate`; the same scene refused by `flexrod simulate`;
//! - the halving loop at `solver.max_halvings` = its maximum with every step failing: the
//!   step fails in bounded time;
//! - `fmi2FreeInstance` / `fmi3FreeInstance` twice, calls after it, a foreign pointer:
//!   `fmi2Error` / `fmi3Error`, no crash;
//! - inputs past their windows in a serialized state: refused;
//! - more `[[rod.section]]` stations than allowed: refused; the allowed maximum builds in
//!   bounded time;
//! - `[experiment]` step_size 0 and 1e-300, stop_time 1e300, start_time -inf: refused by the
//!   scene validation naming the key and its range.

mod common;
#[allow(dead_code)]
mod fuzz;

use std::ffi::c_void;
use std::path::Path;
use std::process::{Command, Stdio};
use std::ptr;
use std::time::{Duration, Instant};

use flexrod::fmi::description::ModelDescription;
use flexrod::fmi::ffi::fmi3::lifecycle::{
    fmi3ExitInitializationMode, fmi3FreeInstance, fmi3InstantiateCoSimulation,
};
use flexrod::fmi::ffi::fmi3::stepping::fmi3DoStep;
use flexrod::fmi::ffi::fmi3::values::fmi3GetFloat64;
use flexrod::fmi::ffi::lifecycle::*;
use flexrod::fmi::ffi::states::*;
use flexrod::fmi::ffi::stepping::*;
use flexrod::fmi::ffi::values::*;
use flexrod::hash::fnv1a_64;
use flexrod::scene::SolverMethod;
use flexrod::{CrankInput, Scene, Simulation};

use common::runs::{automotive_with, start_at};
use fuzz::fmu::{null_state, Fmu, Vars, ERROR, OK};

const CHILD: &str = "FLEXROD_HOSTILE_CHILD";

/// Whether this process is the child running `case`.
fn is_child(case: &str) -> bool {
    std::env::var(CHILD).is_ok_and(|c| c == case)
}

/// Re-run the test `test` of this binary as a child with `case` set; assert it exits cleanly
/// within `limit` (a child past it is killed and the test fails).
fn in_child(test: &str, case: &str, limit: Duration) {
    let exe = std::env::current_exe().expect("the test binary");
    let t0 = Instant::now();
    let mut child = Command::new(exe)
        .args([test, "--exact", "--nocapture", "--test-threads=1"])
        .env(CHILD, case)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the child starts");
    let status = common::child::wait_within(&mut child, limit, case);
    let output = child.wait_with_output().expect("the child's output");
    let took = t0.elapsed();
    println!(
        "{case}: child exited with {status} after {took:.2?}; its output:\n{}",
        String::from_utf8_lossy(&output.stdout)
    );
    assert!(
        status.success(),
        "{case}: child {status}\nstdout:\n{}\nstderr:\n{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
}

/// The serialized state of a fresh instance of the default scene (before initialization).
fn pre_initialization_state(f: &Fmu) -> Vec<u8> {
    let mut slot = null_state();
    // SAFETY: live instance, buffers of the lengths passed.
    unsafe {
        assert_eq!(fmi2GetFMUstate(f.c, &mut slot), OK);
        let mut size = 0;
        assert_eq!(fmi2SerializedFMUstateSize(f.c, slot, &mut size), OK);
        let mut bytes = vec![0u8; size];
        assert_eq!(
            fmi2SerializeFMUstate(f.c, slot, bytes.as_mut_ptr().cast(), size),
            OK
        );
        bytes
    }
}

/// The offset of the model's length (u64) in a serialized state: after the magic, the format
/// version, the GUID (u32 length + text), the machine state and last step status (u8 each),
/// the start time, the stop flag and the stop time (docs/fmu.md, "FMU states and
/// serialization").
fn model_length_at(bytes: &[u8]) -> usize {
    let guid = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    16 + guid + 1 + 1 + 8 + 1 + 8
}

/// `bytes` (a state without a simulation) with its scene text edited by `edit` and the length
/// and checksum recomputed: what a forger with the format at hand makes.
fn forged_scene(bytes: &[u8], edit: impl Fn(&str) -> String) -> Vec<u8> {
    let start = bytes
        .windows(8)
        .position(|w| w == b"name = \"")
        .expect("the scene text");
    let len = u32::from_le_bytes(bytes[start - 4..start].try_into().unwrap()) as usize;
    let text = std::str::from_utf8(&bytes[start..start + len]).unwrap();
    let edited = edit(text);
    assert_ne!(edited, text, "the edit applies");
    let mut out = bytes[..start - 4].to_vec();
    // The model's bytes are length-prefixed (u64) after the shell's header.
    let at = model_length_at(bytes);
    let model_len = u64::from_le_bytes(bytes[at..at + 8].try_into().unwrap()) as usize;
    let model_len = (model_len + edited.len() - len) as u64;
    out[at..at + 8].copy_from_slice(&model_len.to_le_bytes());
    out.extend_from_slice(&(edited.len() as u32).to_le_bytes());
    out.extend_from_slice(edited.as_bytes());
    out.extend_from_slice(&bytes[start + len..bytes.len() - 8]);
    let sum = fnv1a_64(&out);
    out.extend_from_slice(&sum.to_le_bytes());
    out
}

/// Deserialize `bytes` into a fresh instance: the status and the error logged.
fn deserialize(vars: &Vars, bytes: &[u8]) -> (i32, String, Fmu) {
    let target = Fmu::new(vars, "target");
    let mut slot = null_state();
    // SAFETY: live instance, valid buffer.
    let s =
        unsafe { fmi2DeSerializeFMUstate(target.c, bytes.as_ptr().cast(), bytes.len(), &mut slot) };
    if s == OK {
        // SAFETY: as above. Whatever the state holds, the steps must end cleanly.
        unsafe {
            fmi2SetFMUstate(target.c, slot);
            fmi2EnterInitializationMode(target.c);
            fmi2ExitInitializationMode(target.c);
            fmi2DoStep(target.c, 0.0, 1e-4, 0);
        }
    }
    let text = target.log.last_error.borrow().clone();
    (s, text, target)
}

/// The default scene's TOML with `[solver]` key `key` set to `value`.
fn scene_with_solver(key: &str, value: &str) -> String {
    let text = flexrod::scene::DEFAULT_SCENE_TOML;
    let edited = text.replacen("[solver]\n", &format!("[solver]\n{key} = {value}\n"), 1);
    assert_ne!(edited, text);
    edited
}

/// `flexrod simulate` on `scene_text`: exit success, stderr, seconds.
fn cli_simulate(scene_text: &str, name: &str) -> (bool, String, f64) {
    let dir = std::env::temp_dir().join(format!("flexrod-hostile-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, scene_text).unwrap();
    let t0 = Instant::now();
    let out = Command::new(env!("CARGO_BIN_EXE_flexrod"))
        .args(["simulate", path.to_str().unwrap()])
        .output()
        .expect("flexrod runs");
    let took = t0.elapsed().as_secs_f64();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    (out.status.success(), stderr, took)
}

fn forged_solver_case(key: &str, value: &str) {
    let vars = Vars::default_scene();
    let source = Fmu::new(&vars, "source");
    let bytes = pre_initialization_state(&source);
    let forged = forged_scene(&bytes, |text| {
        let line = text
            .lines()
            .find(|l| l.starts_with(&format!("{key} = ")))
            .expect("the key in the serialized scene");
        text.replacen(line, &format!("{key} = {value}"), 1)
    });
    let (status, text, _) = deserialize(&vars, &forged);
    println!("{key} = {value} in a forged state: status {status}: {text}");
    assert_eq!(status, ERROR, "{text}");
    assert!(
        text.contains(&format!("solver.{key}")) && text.contains("allowed"),
        "{text}"
    );
}

/// `max_halvings = 100000` in a forged pre-initialization state and in a scene file: refused
/// (run in a child: 100000 levels of halving, were they reached, would take the process down).
#[test]
fn huge_max_halvings_is_refused_in_states_and_scene_files() {
    if is_child("halvings") {
        forged_solver_case("max_halvings", "100000");
        let (ok, stderr, took) =
            cli_simulate(&scene_with_solver("max_halvings", "100000"), "halvings");
        println!("flexrod simulate, max_halvings = 100000: {took:.2} s: {stderr}");
        assert!(!ok && stderr.contains("solver.max_halvings") && stderr.contains("0..=20"));
        return;
    }
    in_child(
        "huge_max_halvings_is_refused_in_states_and_scene_files",
        "halvings",
        Duration::from_secs(60),
    );
}

/// `max_newton_iterations = 1e9` in a forged state and in a scene file: refused (run in a child
/// with a time limit: a billion Newton iterations in one step would run for minutes).
#[test]
fn huge_max_newton_iterations_is_refused_in_states_and_scene_files() {
    if is_child("newton") {
        forged_solver_case("max_newton_iterations", "1000000000");
        let (ok, stderr, took) = cli_simulate(
            &scene_with_solver("max_newton_iterations", "1000000000"),
            "newton",
        );
        println!("flexrod simulate, max_newton_iterations = 1e9: {took:.2} s: {stderr}");
        assert!(
            !ok && stderr.contains("solver.max_newton_iterations") && stderr.contains("1..=100")
        );
        return;
    }
    in_child(
        "huge_max_newton_iterations_is_refused_in_states_and_scene_files",
        "newton",
        Duration::from_secs(60),
    );
}

/// The halving loop at the largest `solver.max_halvings` with a step that always fails (a
/// Newton tolerance no iteration meets): the communication step fails with a message, in
/// bounded time, and nothing overflows.
#[test]
fn the_largest_max_halvings_fails_a_hopeless_step_in_bounded_time() {
    if is_child("halving-loop") {
        let mut scene = Scene::benchmark();
        scene.solver.method = SolverMethod::GeneralizedAlpha;
        scene.solver.newton_tolerance = 1e-300;
        scene.solver.max_newton_iterations = 1;
        scene.solver.max_halvings = flexrod::mechanism::spec::MAX_HALVINGS;
        let mut sim = Simulation::new(&scene).expect("in range");
        sim.start(
            0.0,
            CrankInput {
                angle: 0.0,
                speed: 150.0,
                acceleration: 0.0,
                jerk: 0.0,
            },
            0.0,
        )
        .unwrap();
        let t0 = Instant::now();
        let e = sim.advance(1e-3).expect_err("every step fails");
        println!(
            "max_halvings = {}: refused after {:.3} s: {e}",
            scene.solver.max_halvings,
            t0.elapsed().as_secs_f64()
        );
        assert_eq!(sim.time(), 0.0);
        return;
    }
    in_child(
        "the_largest_max_halvings_fails_a_hopeless_step_in_bounded_time",
        "halving-loop",
        Duration::from_secs(60),
    );
}

/// A second free, calls after the free and a foreign pointer: an error, no crash (FMI 2.0 and
/// FMI 3.0).
#[test]
fn freed_and_foreign_instances_give_an_error_not_a_crash() {
    if is_child("free") {
        let vars = Vars::default_scene();
        let log = fuzz::fmu::Log::default();
        let cb = fuzz::fmu::callbacks(&log);
        let mut local = [0u64; 64];
        let foreign = local.as_mut_ptr().cast::<c_void>();
        // SAFETY (FMI 2.0): every handle is the registry's business; arrays of the lengths passed.
        unsafe {
            let c = fmi2Instantiate(c"a".as_ptr(), 1, vars.guid.as_ptr(), ptr::null(), &cb, 0, 0);
            assert!(!c.is_null());
            assert_eq!(fmi2EnterInitializationMode(c), OK);
            assert_eq!(fmi2ExitInitializationMode(c), OK);
            assert_eq!(fmi2DoStep(c, 0.0, 1e-4, 0), OK);
            fmi2FreeInstance(c);
            fmi2FreeInstance(c);
            let mut x = [0.0; 4];
            for handle in [c, foreign] {
                assert_eq!(fmi2DoStep(handle, 1e-4, 1e-4, 0), ERROR);
                assert_eq!(
                    fmi2GetReal(handle, vars.real_outputs.as_ptr(), 4, x.as_mut_ptr()),
                    ERROR
                );
                assert_eq!(fmi2Terminate(handle), ERROR);
                let mut slot = null_state();
                assert_eq!(fmi2GetFMUstate(handle, &mut slot), ERROR);
                fmi2FreeInstance(handle);
            }
            // A new instance works after all that.
            let d = Fmu::new(&vars, "after");
            assert_eq!(fmi2EnterInitializationMode(d.c), OK);
        }
        // FMI 3.0.
        let d3 = ModelDescription::for_scene_fmi3(&Scene::benchmark()).unwrap();
        let token = std::ffi::CString::new(d3.guid.clone()).unwrap();
        let vr = d3.table.by_name("crank.torque").unwrap().value_reference;
        // SAFETY: as above.
        unsafe {
            let i = fmi3InstantiateCoSimulation(
                c"b".as_ptr(),
                token.as_ptr(),
                ptr::null(),
                false,
                false,
                false,
                false,
                ptr::null(),
                0,
                ptr::null_mut(),
                None,
                None,
            );
            assert!(!i.is_null());
            flexrod::fmi::ffi::fmi3::lifecycle::fmi3EnterInitializationMode(
                i, false, 0.0, 0.0, false, 0.0,
            );
            assert_eq!(fmi3ExitInitializationMode(i), OK);
            fmi3FreeInstance(i);
            fmi3FreeInstance(i);
            let (mut a, mut b, mut e) = (false, false, false);
            let mut last = 0.0;
            let mut x = 0.0;
            for handle in [i, foreign] {
                assert_eq!(
                    fmi3DoStep(handle, 0.0, 1e-4, false, &mut a, &mut b, &mut e, &mut last),
                    ERROR
                );
                assert_eq!(fmi3GetFloat64(handle, &vr, 1, &mut x, 1), ERROR);
                fmi3FreeInstance(handle);
            }
        }
        println!("double free, use after free, foreign pointer: fmi2Error / fmi3Error");
        return;
    }
    in_child(
        "freed_and_foreign_instances_give_an_error_not_a_crash",
        "free",
        Duration::from_secs(60),
    );
}

/// Inputs past their windows in a serialized state (valid checksum) are refused.
#[test]
fn inputs_past_their_windows_in_a_state_are_refused() {
    let vars = Vars::default_scene();
    let source = Fmu::new(&vars, "source");
    let bytes = pre_initialization_state(&source);
    // The inputs follow the model's length and its started flag.
    let inputs = model_length_at(&bytes) + 8 + 1;
    for (k, name) in ["crank.angle", "crank.speed", "slider.force"]
        .into_iter()
        .enumerate()
    {
        for x in [1e300_f64, -1e15] {
            let mut forged = bytes[..bytes.len() - 8].to_vec();
            let at = inputs + 8 * k;
            forged[at..at + 8].copy_from_slice(&x.to_le_bytes());
            let sum = fnv1a_64(&forged);
            forged.extend_from_slice(&sum.to_le_bytes());
            let (status, text, _) = deserialize(&vars, &forged);
            assert_eq!(status, ERROR, "{name} = {x:e}: {text}");
            assert!(
                text.contains(name) && text.contains("allowed |value| <="),
                "{text}"
            );
        }
    }
}

/// A scene with `[[rod.section]]` stations at equal spacing along the benchmark rod.
fn stations_scene(n: usize) -> String {
    let mut text: String = flexrod::scene::DEFAULT_SCENE_TOML
        .lines()
        .filter(|l| !l.starts_with("area"))
        .map(|l| format!("{l}\n"))
        .collect();
    let length = Scene::benchmark().rod.length;
    for k in 0..n {
        let s = length * k as f64 / (n - 1) as f64;
        text += &format!(
            "\n[[rod.section]]\nposition = {s:e}\narea = {:e}\narea_moment = {:e}\n",
            1e-4 * (1.0 + 0.1 * (k % 3) as f64),
            1e-9 * (1.0 + 0.1 * (k % 3) as f64)
        );
    }
    text
}

/// More stations than allowed are refused when the scene is read, naming the key and the
/// limit; the limit builds in bounded time.
#[test]
fn station_count_is_limited_and_the_limit_builds_in_bounded_time() {
    let max = flexrod::beam::section_table::MAX_STATIONS;
    let e = Scene::from_toml_str(&stations_scene(max + 1), "stations.toml")
        .expect_err("too many stations");
    let text = e.to_string();
    assert!(
        text.contains("rod.section") && text.contains(&format!("at most {max}")),
        "{text}"
    );
    let scene = Scene::from_toml_str(&stations_scene(max), "stations.toml").expect("in range");
    let t0 = Instant::now();
    let sim = Simulation::new(&scene);
    let took = t0.elapsed().as_secs_f64();
    println!(
        "{max} [[rod.section]] stations: built in {took:.3} s ({})",
        if sim.is_ok() { "ok" } else { "refused" }
    );
    sim.expect("the largest table builds");
    assert!(took < 5.0, "{took} s");
}

/// `[experiment]` values past their ranges: refused by the scene validation (file and CLI)
/// with the key and its range.
#[test]
fn experiment_values_past_their_ranges_are_refused() {
    let base = flexrod::scene::DEFAULT_SCENE_TOML;
    let cases = [
        (
            "step_size = 1e-4",
            "step_size = 0.0",
            "experiment.step_size",
        ),
        (
            "step_size = 1e-4",
            "step_size = 1e-300",
            "experiment.step_size",
        ),
        (
            "stop_time = 0.0838",
            "stop_time = 1e300",
            "experiment.stop_time",
        ),
        (
            "start_time = 0.0",
            "start_time = -inf",
            "experiment.start_time",
        ),
    ];
    for (from, to, key) in cases {
        let text = base.replacen(from, to, 1);
        assert_ne!(text, base, "{from}");
        let e = Scene::from_toml_str(&text, "x.toml")
            .expect_err(to)
            .to_string();
        assert!(e.contains(key) && e.contains("allowed"), "{to}: {e}");
        let (ok, stderr, took) = cli_simulate(&text, "experiment");
        println!(
            "{to}: flexrod simulate exits in {took:.2} s: {}",
            stderr.trim()
        );
        assert!(
            !ok && stderr.contains(key) && stderr.contains("allowed"),
            "{stderr}"
        );
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
    assert!(Path::new(env!("CARGO_BIN_EXE_flexrod")).exists());
}

/// A section-table scene declares no uniform `rod.area` / `rod.area_moment`; `rod.elements`
/// declares the least count that leaves the declared frequencies for the exported model, and
/// the set call refuses a value outside the declared range (what the initialization would
/// refuse later).
#[test]
fn declared_ranges_are_what_the_fmu_can_do() {
    use flexrod::model::{RodModel, VariableTable};
    use flexrod::scene::RodModelKind;
    let automotive = Scene::from_file(Path::new("scenes/automotive_rod.toml")).unwrap();
    let d = ModelDescription::for_scene(&automotive).unwrap();
    assert!(d.table.by_name("rod.area").is_none());
    assert!(d.table.by_name("rod.area_moment").is_none());
    assert!(!d.xml.contains("\"rod.area\""));
    let mut segments = Scene::benchmark();
    segments.rod.model = RodModelKind::Segments;
    segments.solver.method = SolverMethod::GeneralizedAlpha;
    for (scene, least) in [(Scene::benchmark(), 2), (segments, 7)] {
        let table = VariableTable::for_scene(&scene, flexrod::model::Interface::SCALARS).unwrap();
        assert_eq!(table.frequency_count(), 6);
        let v = table.by_name("rod.elements").unwrap();
        assert_eq!(
            v.min,
            Some(flexrod::model::variables::Value::Integer(least)),
            "{:?}",
            scene.rod.model
        );
        let vr = v.value_reference;
        let mut model = RodModel::with_table(scene.clone(), table.clone()).unwrap();
        let (_, text) = model.set_integers(&[(vr, least - 1)]).unwrap_err();
        assert!(text.contains(&format!("{least}..=128")), "{text}");
        model.set_integers(&[(vr, least)]).unwrap();
        model
            .ensure_started(0.0)
            .unwrap_or_else(|e| panic!("{:?} with {least}: {e}", scene.rod.model));
        println!(
            "{:?}: rod.elements declared min {least}, {} refused at the set call: {text}",
            scene.rod.model,
            least - 1
        );
    }
}

/// One communication step of a large model inside the declared ranges ends within the work
/// budget: the FFR rod with 115 elements and 344 modes, soft and heavy (many internal steps of
/// a costly model; or refused before it is built by the cost model), and the stiffest
/// 128-segment chain; each either completes or is refused at the work bound with the state
/// kept, in bounded time.
#[test]
fn large_models_inside_the_declared_ranges_take_bounded_time_per_step() {
    if is_child("large-models") {
        let mut ffr = Scene::benchmark();
        ffr.rod.elements = 115;
        ffr.rod.modes = 344;
        ffr.rod.youngs_modulus = 1e6;
        ffr.rod.density = 1e5;
        let mut segments = Scene::benchmark();
        segments.rod.model = flexrod::scene::RodModelKind::Segments;
        segments.rod.elements = 128;
        segments.solver.method = SolverMethod::GeneralizedAlpha;
        segments.rod.youngs_modulus = 1e17;
        segments.rod.density = 10.0;
        for (label, scene, h) in [("FFR 115/344", ffr, 1e-2), ("segments 128", segments, 0.1)] {
            let mut sim = match Simulation::new(&scene) {
                Ok(sim) => sim,
                // Refused before the build by the cost model (the FFR rod's axial coupling).
                Err(e @ flexrod::ModelError::TooCostly { .. }) => {
                    println!("{label}: {e}");
                    continue;
                }
                Err(e) => panic!("{label}: {e}"),
            };
            start_at(&mut sim, 150.0);
            let t0 = Instant::now();
            let r = sim.advance(h);
            let took = t0.elapsed().as_secs_f64();
            println!("{label}, h = {h} s: {took:.2} s, {r:?}");
            match r {
                Ok(_) => assert_eq!(sim.time(), h),
                Err(flexrod::ModelError::TooMuchWork { .. }) => assert_eq!(sim.time(), 0.0),
                Err(e) => panic!("{label}: {e}"),
            }
            assert!(took < 30.0, "{label}: {took} s");
        }
        return;
    }
    in_child(
        "large_models_inside_the_declared_ranges_take_bounded_time_per_step",
        "large-models",
        Duration::from_secs(90),
    );
}

/// `rod.error_estimate` is finite for every parameter set the FMU accepts: a shear area of
/// 1e-320 m^2 with shear off makes the estimate's shear share overflow, and the output must
/// still be a finite number under fmi2OK (the long fuzz mode's seed 40915 is such a case).
#[test]
fn the_error_estimate_is_finite_for_extreme_shear_parameters() {
    for (area, modulus) in [(1e-320, None), (1e-320, Some(1e4)), (1e-12, Some(1e4))] {
        let mut scene = Scene::benchmark();
        scene.rod.shear_deformation = flexrod::rod::PhysicsSwitch::Off;
        scene.rod.shear_area = Some(area);
        scene.rod.shear_modulus = modulus;
        // One communication step of 1 ms at 150 rad/s.
        let revolutions = 150.0 * 1e-3 / (2.0 * std::f64::consts::PI);
        let (_, sim) = flexrod::drive::run_constant(&scene, 150.0, 1e-3, revolutions).unwrap();
        let e = sim.outputs().error_estimate;
        assert!(e.is_finite() && e > 0.0, "A_s {area}, G {modulus:?}: {e}");
        assert!(e <= flexrod::rod::physics_choice::MAX_ERROR_ESTIMATE);
    }
}

/// A soft rod puts every mode into the automotive scene's 6 kHz band: 52 or 128 elements,
/// `mean_axis`, E = 7.95e6 Pa (all in range) retain about a hundred modes, half of them
/// axial, whose coupling (`na^2 n^2` terms per evaluation) made one 1e-4 s step take minutes.
/// The cost model refuses them before the build, naming the modes and the keys to change.
#[test]
fn a_soft_rod_with_every_mode_in_its_band_is_refused_before_it_is_built() {
    if is_child("soft-band") {
        for elements in [52, 128] {
            let t0 = Instant::now();
            let e = Simulation::new(&automotive_with(7.95e6, elements, "mean_axis"))
                .err()
                .unwrap_or_else(|| panic!("{elements} elements: built"));
            let took = t0.elapsed().as_secs_f64();
            println!("{elements} elements: refused after {took:.2} s: {e}");
            assert!(matches!(e, flexrod::ModelError::TooCostly { .. }), "{e}");
            let text = e.to_string();
            for needle in ["of them axial", "rod.mode_band_hz", "rod.axial_stiffening"] {
                assert!(text.contains(needle), "{text}");
            }
        }
        return;
    }
    in_child(
        "a_soft_rod_with_every_mode_in_its_band_is_refused_before_it_is_built",
        "soft-band",
        Duration::from_secs(60),
    );
}

/// The automotive scene with E = 1e5 Pa and `solver.tolerance` = 1.4e-6: the step that ran
/// 17 to 19 s before the budget refused it now ends within the budget, which counts what an
/// evaluation of this rod costs (its axial coupling): the evaluations it counts times their
/// cost stay within `WORK_BUDGET`.
#[test]
fn a_soft_rod_at_a_tight_tolerance_ends_its_step_within_the_budget() {
    use flexrod::mechanism::stepping::{evaluations_allowed, WORK_BUDGET};
    if is_child("soft-tight") {
        let mut scene = automotive_with(1e5, 8, "simply_supported");
        scene.solver.tolerance = 1.4e-6;
        let mut sim = match Simulation::new(&scene) {
            Ok(sim) => sim,
            Err(e) => panic!("in range and affordable: {e}"),
        };
        start_at(&mut sim, 628.3);
        let cost = sim.mechanism().evaluation_cost();
        assert!(cost > flexrod::rod::cost::dense_evaluation(sim.mechanism().work_coordinates()));
        let allowed = evaluations_allowed(cost);
        assert!(allowed as f64 * cost <= WORK_BUDGET);
        for h in [1e-4, 1e-3] {
            let t0 = Instant::now();
            let r = sim.advance(h);
            println!(
                "h = {h} s: {:.2} s, {allowed} evaluations of {cost:.3e} units allowed, {r:?}",
                t0.elapsed().as_secs_f64()
            );
            match r {
                Ok(_) => {}
                Err(flexrod::ModelError::TooMuchWork { .. }) => {}
                Err(e) => panic!("{e}"),
            }
        }
        return;
    }
    in_child(
        "a_soft_rod_at_a_tight_tolerance_ends_its_step_within_the_budget",
        "soft-tight",
        Duration::from_secs(60),
    );
}

/// A refused step of the default scene (a communication step of 1000 s, 1e5 internal steps
/// or the budget first) ends in bounded time: each evaluation of a small model is charged its
/// fixed overhead (`rod::cost::EVALUATION_OVERHEAD`), so the budget is not a count of
/// microsecond evaluations that runs for seconds.
#[test]
fn a_refused_step_of_a_small_model_ends_in_bounded_time() {
    if is_child("small-refused") {
        let mut sim = Simulation::new(&Scene::benchmark()).unwrap();
        start_at(&mut sim, 150.0);
        let t0 = Instant::now();
        let e = sim.advance(1000.0).expect_err("refused");
        println!("refused after {:.2} s: {e}", t0.elapsed().as_secs_f64());
        assert!(matches!(e, flexrod::ModelError::TooMuchWork { .. }), "{e}");
        assert_eq!(sim.time(), 0.0);
        return;
    }
    in_child(
        "a_refused_step_of_a_small_model_ends_in_bounded_time",
        "small-refused",
        Duration::from_secs(30),
    );
}

/// The largest FFR rod (128 elements, 384 bending modes) would hold about 620 MB of section
/// sampling per instance (`2 n^2` numbers at each of its 258 cuts): refused by the cost
/// model's memory limit, with the size named. With 192 modes it builds.
#[test]
fn the_largest_ffr_rod_is_refused_by_its_memory() {
    let mut scene = Scene::benchmark();
    scene.rod.model = flexrod::scene::RodModelKind::Ffr;
    scene.rod.elements = 128;
    scene.rod.modes = 384;
    scene.rod.youngs_modulus = 1e6;
    scene.rod.density = 1e5;
    let e = Simulation::new(&scene).err().expect("refused");
    let text = e.to_string();
    println!("{text}");
    assert!(matches!(e, flexrod::ModelError::TooCostly { .. }), "{text}");
    assert!(text.contains("MiB"), "{text}");
    scene.rod.modes = 192;
    if let Err(e) = Simulation::new(&scene) {
        panic!("{e}");
    }
}

/// An FFR rod whose bending stiffness is below what its eigenproblem resolves (100 m long,
/// radius of gyration 1e-11 m: every key in range) had natural frequencies of round-off (0 Hz
/// in `rod.frequency[1]`), and every step then failed. It is refused when the model is built,
/// naming `rod.area_moment` and the frequencies.
#[test]
fn a_rod_with_modes_of_round_off_is_refused_when_built() {
    let mut scene = Scene::benchmark();
    scene.rod.model = flexrod::scene::RodModelKind::Ffr;
    scene.rod.length = 100.0;
    scene.crank.length = 1.0;
    scene.rod.youngs_modulus = 1e5;
    scene.rod.density = 1e5;
    scene.rod.area = 1.0;
    scene.rod.area_moment = 1e-22;
    let e = Simulation::new(&scene).err().expect("refused");
    let text = e.to_string();
    println!("{text}");
    assert!(text.contains("rod.area_moment"), "{text}");
    assert!(text.contains("lowest retained natural frequency"), "{text}");
}

/// `rod.deflection_limit` reads the limit that applies: with `rod.model = auto` at a speed where
/// it takes the segment chain on its modes, the chain's 0.25 once the model is built (the
/// scene's default, the FFR rod's 0.05, before).
#[test]
fn the_deflection_limit_reads_the_limit_that_applies() {
    use flexrod::cosimulation::CoSimulationModel;
    use flexrod::model::{RodModel, VariableTable};
    use flexrod::scene::RodModelKind;
    let scene = Scene::benchmark();
    assert_eq!(scene.rod.model, RodModelKind::Auto);
    let table = VariableTable::for_scene(&scene, flexrod::model::Interface::SCALARS).unwrap();
    let vr = |name: &str| table.by_name(name).unwrap().value_reference;
    let (limit, speed) = (vr("rod.deflection_limit"), vr("crank.speed"));
    for (rad_per_s, applied) in [(150.0, 0.05), (400.0, 0.25)] {
        let mut model = RodModel::with_table(scene.clone(), table.clone()).unwrap();
        let read = |m: &RodModel| {
            let mut x = [0.0];
            CoSimulationModel::get_real(m, limit, &mut x, 0.0).unwrap();
            x[0]
        };
        CoSimulationModel::set_real(&mut model, speed, rad_per_s).unwrap();
        assert_eq!(read(&model), 0.05, "before the build");
        CoSimulationModel::ensure_started(&mut model, 0.0).unwrap();
        assert_eq!(
            read(&model),
            applied,
            "at {rad_per_s} rad/s: {}",
            model.start_summary()
        );
    }
}
