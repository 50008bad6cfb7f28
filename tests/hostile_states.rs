//! Hostile calls through the C API of both standards, each a regression test of a contract
//! line (docs/fmu.md, "Input windows" and "FMU states and serialization"):
//!
//! - `experiment_times_past_the_scene_ranges_are_refused`: a start time of 1e15 or 1e300, a
//!   stop time past 1e6 s or not after the start, at `fmi2SetupExperiment` and
//!   `fmi3EnterInitializationMode`: refused naming the value and the range, the instance usable;
//! - `state_fields_past_their_ranges_are_refused`: cached outputs of +-1e308 and a start time of
//!   1e300 in a serialized state (checksum recomputed): refused;
//! - `a_state_of_another_model_is_refused`: a state of the automotive rod with its GUID or
//!   token rewritten to the default scene's: refused, FMI 2.0 and FMI 3.0;
//! - `percent_signs_in_resource_folders_are_taken_as_they_are`: FMI 3.0 `resourcePath` is a
//!   path (folders `pct 100%`, `a%20b`), FMI 2.0 `fmuResourceLocation` a URI;
//! - `handles_of_the_other_standard_are_refused`: an FMI 2.0 handle in `fmi3*` functions and
//!   the reverse: refused through the logger, the instances continue bit for bit.

use std::cell::RefCell;
use std::ffi::{c_char, c_void, CStr, CString};
use std::path::{Path, PathBuf};
use std::ptr;

use flexrod::fmi::description::ModelDescription;
use flexrod::fmi::ffi::fmi3::lifecycle::*;
use flexrod::fmi::ffi::fmi3::states::*;
use flexrod::fmi::ffi::fmi3::stepping::fmi3DoStep;
use flexrod::fmi::ffi::fmi3::values::{fmi3GetFloat64, fmi3SetFloat64};
use flexrod::fmi::ffi::fmi3::{fmi3Instance, fmi3InstanceEnvironment, fmi3Status, fmi3String};
use flexrod::fmi::ffi::lifecycle::*;
use flexrod::fmi::ffi::states::*;
use flexrod::fmi::ffi::stepping::*;
use flexrod::fmi::ffi::values::*;
use flexrod::fmi::ffi::{
    fmi2CallbackFunctions, fmi2CallbackLogger, fmi2Component, fmi2ComponentEnvironment,
    fmi2FMUstate, fmi2Status, fmi2String,
};
use flexrod::hash::fnv1a_64;
use flexrod::Scene;

const OK: i32 = 0;
const ERROR: i32 = 3;

/// The messages an instance logged.
#[derive(Default)]
struct Log(RefCell<Vec<String>>);

impl Log {
    fn push(&self, message: *const c_char) {
        if !message.is_null() {
            // SAFETY: the FMU passes a NUL-terminated string that outlives the call.
            let text = unsafe { CStr::from_ptr(message) }.to_string_lossy();
            self.0.borrow_mut().push(text.into_owned());
        }
    }

    fn last(&self) -> String {
        self.0.borrow().last().cloned().unwrap_or_default()
    }

    fn count(&self) -> usize {
        self.0.borrow().len()
    }
}

/// FMI 2.0 declares the logger variadic; the FMU never passes variadic arguments (every `%`
/// escaped), and on x86-64 System V a variadic call reaches this fixed-arity function unchanged.
unsafe extern "C" fn log2(
    env: fmi2ComponentEnvironment,
    _name: fmi2String,
    _status: fmi2Status,
    _category: fmi2String,
    message: fmi2String,
) {
    // SAFETY: env is the instance's `Log`, alive as long as the instance.
    if let Some(log) = unsafe { env.cast::<Log>().as_ref() } {
        log.push(message);
    }
}

unsafe extern "C" fn log3(
    env: fmi3InstanceEnvironment,
    _status: fmi3Status,
    _category: fmi3String,
    message: fmi3String,
) {
    // SAFETY: as for `log2`.
    if let Some(log) = unsafe { env.cast::<Log>().as_ref() } {
        log.push(message);
    }
}

fn logs_here() -> bool {
    cfg!(all(target_arch = "x86_64", target_os = "linux"))
}

/// An FMI 2.0 instance of `scene` with resources at `location` (NULL: the compiled-in scene).
struct Fmi2 {
    c: fmi2Component,
    log: Box<Log>,
}

impl Fmi2 {
    fn new(scene: &Scene, location: Option<&str>) -> Option<Fmi2> {
        let guid = CString::new(ModelDescription::for_scene(scene).unwrap().guid).unwrap();
        let log = Box::<Log>::default();
        type Fixed = unsafe extern "C" fn(
            fmi2ComponentEnvironment,
            fmi2String,
            fmi2Status,
            fmi2String,
            fmi2String,
        );
        let logger = logs_here().then(|| {
            // SAFETY: see `log2`.
            unsafe { std::mem::transmute::<Fixed, fmi2CallbackLogger>(log2 as Fixed) }
        });
        let cb = fmi2CallbackFunctions {
            logger,
            allocate_memory: None,
            free_memory: None,
            step_finished: None,
            component_environment: (&*log as *const Log).cast_mut().cast::<c_void>(),
        };
        let location = location.map(|l| CString::new(l).unwrap());
        let location_ptr = location.as_ref().map_or(ptr::null(), |l| l.as_ptr());
        // SAFETY: valid strings and callbacks; the log outlives the instance.
        let c =
            unsafe { fmi2Instantiate(c"h2".as_ptr(), 1, guid.as_ptr(), location_ptr, &cb, 0, 0) };
        (!c.is_null()).then_some(Fmi2 { c, log })
    }

    fn start(&self, stop: f64) {
        // SAFETY: live instance.
        unsafe {
            assert_eq!(fmi2SetupExperiment(self.c, 0, 0.0, 0.0, 1, stop), OK);
            assert_eq!(fmi2EnterInitializationMode(self.c), OK);
            assert_eq!(fmi2ExitInitializationMode(self.c), OK);
        }
    }

    fn state_bytes(&self) -> Vec<u8> {
        let mut s: fmi2FMUstate = ptr::null_mut();
        // SAFETY: live instance, buffers of the lengths passed.
        unsafe {
            assert_eq!(fmi2GetFMUstate(self.c, &mut s), OK);
            let mut n = 0;
            assert_eq!(fmi2SerializedFMUstateSize(self.c, s, &mut n), OK);
            let mut bytes = vec![0u8; n];
            assert_eq!(
                fmi2SerializeFMUstate(self.c, s, bytes.as_mut_ptr().cast(), n),
                OK
            );
            bytes
        }
    }

    /// `fmi2DeSerializeFMUstate` of `bytes`: the status and the last message.
    fn load(&self, bytes: &[u8]) -> (i32, String) {
        let mut s: fmi2FMUstate = ptr::null_mut();
        // SAFETY: live instance, valid buffer.
        let status =
            unsafe { fmi2DeSerializeFMUstate(self.c, bytes.as_ptr().cast(), bytes.len(), &mut s) };
        (status, self.log.last())
    }

    fn reals(&self, vrs: &[u32]) -> (i32, Vec<f64>) {
        let mut out = vec![0.0; vrs.len()];
        // SAFETY: live instance, arrays of the length passed.
        let s = unsafe { fmi2GetReal(self.c, vrs.as_ptr(), vrs.len(), out.as_mut_ptr()) };
        (s, out)
    }
}

impl Drop for Fmi2 {
    fn drop(&mut self) {
        // SAFETY: from fmi2Instantiate, freed once.
        unsafe { fmi2FreeInstance(self.c) }
    }
}

/// An FMI 3.0 instance of `scene` with resources at `path` (NULL: the compiled-in scene).
struct Fmi3 {
    c: fmi3Instance,
    log: Box<Log>,
}

impl Fmi3 {
    fn new(scene: &Scene, path: Option<&str>) -> Option<Fmi3> {
        let token = CString::new(ModelDescription::for_scene_fmi3(scene).unwrap().guid).unwrap();
        let log = Box::<Log>::default();
        let path = path.map(|l| CString::new(l).unwrap());
        let path_ptr = path.as_ref().map_or(ptr::null(), |l| l.as_ptr());
        // SAFETY: valid strings; the log outlives the instance.
        let c = unsafe {
            fmi3InstantiateCoSimulation(
                c"h3".as_ptr(),
                token.as_ptr(),
                path_ptr,
                false,
                false,
                false,
                false,
                ptr::null(),
                0,
                (&*log as *const Log).cast_mut().cast(),
                Some(log3),
                None,
            )
        };
        (!c.is_null()).then_some(Fmi3 { c, log })
    }

    fn start(&self, stop: f64) {
        // SAFETY: live instance.
        unsafe {
            assert_eq!(
                fmi3EnterInitializationMode(self.c, false, 0.0, 0.0, true, stop),
                OK
            );
            assert_eq!(fmi3ExitInitializationMode(self.c), OK);
        }
    }

    fn step(&self, t: f64, h: f64) -> (i32, f64) {
        let (mut a, mut b, mut c) = (false, false, false);
        let mut last = f64::NAN;
        // SAFETY: live instance, valid out-arguments.
        let s = unsafe { fmi3DoStep(self.c, t, h, false, &mut a, &mut b, &mut c, &mut last) };
        (s, last)
    }

    fn state_bytes(&self) -> Vec<u8> {
        let mut s = ptr::null_mut();
        // SAFETY: live instance, buffers of the lengths passed.
        unsafe {
            assert_eq!(fmi3GetFMUState(self.c, &mut s), OK);
            let mut n = 0;
            assert_eq!(fmi3SerializedFMUStateSize(self.c, s, &mut n), OK);
            let mut bytes = vec![0u8; n];
            assert_eq!(fmi3SerializeFMUState(self.c, s, bytes.as_mut_ptr(), n), OK);
            bytes
        }
    }

    fn load(&self, bytes: &[u8]) -> (i32, String) {
        let mut s = ptr::null_mut();
        // SAFETY: live instance, valid buffer.
        let status =
            unsafe { fmi3DeserializeFMUState(self.c, bytes.as_ptr(), bytes.len(), &mut s) };
        (status, self.log.last())
    }

    fn reals(&self, vrs: &[u32]) -> (i32, Vec<f64>) {
        let mut out = vec![0.0; vrs.len()];
        // SAFETY: live instance, arrays of the length passed.
        let s =
            unsafe { fmi3GetFloat64(self.c, vrs.as_ptr(), vrs.len(), out.as_mut_ptr(), out.len()) };
        (s, out)
    }
}

impl Drop for Fmi3 {
    fn drop(&mut self) {
        // SAFETY: from fmi3InstantiateCoSimulation, freed once.
        unsafe { fmi3FreeInstance(self.c) }
    }
}

/// `bytes` with the checksum (the last 8 bytes) recomputed: what a forger does.
fn resealed(mut bytes: Vec<u8>) -> Vec<u8> {
    let n = bytes.len() - 8;
    let sum = fnv1a_64(&bytes[..n]);
    bytes[n..].copy_from_slice(&sum.to_le_bytes());
    bytes
}

/// The offset of the GUID's length field, and the GUID.
fn guid_at(bytes: &[u8]) -> (usize, String) {
    let at = 8 + 4;
    let n = u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
    (
        at,
        String::from_utf8(bytes[at + 4..at + 4 + n].to_vec()).unwrap(),
    )
}

/// `bytes` with the GUID replaced by `guid`, the checksum recomputed.
fn with_guid(bytes: &[u8], guid: &str) -> Vec<u8> {
    let (at, old) = guid_at(bytes);
    let mut out = bytes[..at].to_vec();
    out.extend_from_slice(&(guid.len() as u32).to_le_bytes());
    out.extend_from_slice(guid.as_bytes());
    out.extend_from_slice(&bytes[at + 4 + old.len()..]);
    resealed(out)
}

/// The offset of the start time (after the header, GUID and three flag bytes).
fn start_time_at(bytes: &[u8]) -> usize {
    let (at, guid) = guid_at(bytes);
    // After the token: the machine state and the last step status.
    at + 4 + guid.len() + 2
}

/// The offset of the simulation's first cached output (`rod.deflection`) in a serialized
/// state (docs/fmu.md, "FMU states and serialization"): after the shell's header, the model's
/// length, its started flag, inputs, scene text and simulation flag, the simulation's length
/// and fingerprint, twelve numbers (three times, two laws of four, the slider force).
fn first_output_at(bytes: &[u8]) -> usize {
    let (at, guid) = guid_at(bytes);
    let model = at + 4 + guid.len() + 1 + 1 + 8 + 1 + 8 + 8;
    let scene_at = model + 1 + 5 * 8 + 3;
    let scene_len = u32::from_le_bytes(bytes[scene_at..scene_at + 4].try_into().unwrap()) as usize;
    let simulation = scene_at + 4 + scene_len + 1 + 8;
    simulation + 8 + 12 * 8
}

fn put_f64(bytes: &mut [u8], at: usize, x: f64) {
    bytes[at..at + 8].copy_from_slice(&x.to_le_bytes());
}

/// A fresh folder under the target directory.
fn temp_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `<parent>/<folder>/resources/scene.toml` holding `scene`; the resources folder.
fn resources(parent: &Path, folder: &str, scene: &Scene) -> PathBuf {
    let dir = parent.join(folder).join("resources");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("scene.toml"), scene.to_toml()).unwrap();
    dir
}

fn automotive() -> Scene {
    Scene::from_file(Path::new("scenes/automotive_rod.toml")).unwrap()
}

fn vr(scene: &Scene, name: &str) -> u32 {
    let d = ModelDescription::for_scene(scene).unwrap();
    d.table.by_name(name).unwrap().value_reference
}

#[test]
fn experiment_times_past_the_scene_ranges_are_refused() {
    let scene = Scene::benchmark();
    let f = Fmi2::new(&scene, None).unwrap();
    let cases: [(f64, i32, f64, &str); 5] = [
        (1e15, 0, 0.0, "startTime"),
        (1e300, 0, 0.0, "startTime"),
        (-2e6, 0, 0.0, "startTime"),
        (0.0, 1, 2e6, "stopTime"),
        (0.5, 1, 0.5, "stopTime"),
    ];
    for (start, defined, stop, name) in cases {
        // SAFETY: live instance.
        let s = unsafe { fmi2SetupExperiment(f.c, 0, 0.0, start, defined, stop) };
        assert_eq!(s, ERROR, "start {start}, stop {stop}");
        let m = f.log.last();
        assert!(logs_here() || m.is_empty());
        if logs_here() {
            assert!(
                m.contains("fmi2SetupExperiment") && m.contains(name) && m.contains("1e6"),
                "{m}"
            );
        }
    }
    // The scene format refuses the same start time with the same check.
    let text =
        flexrod::scene::DEFAULT_SCENE_TOML.replacen("start_time = 0.0", "start_time = 1e15", 1);
    let e = Scene::from_toml_str(&text, "x.toml")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("experiment.start_time") && e.contains("1e6"),
        "{e}"
    );
    // The instance is still usable, and its time advances.
    f.start(0.01);
    let position = vr(&scene, "slider.position");
    let before = f.reals(&[position]).1[0];
    // SAFETY: live instance.
    assert_eq!(unsafe { fmi2DoStep(f.c, 0.0, 1e-3, 1) }, OK);
    assert_ne!(f.reals(&[position]).1[0], before);

    let g = Fmi3::new(&scene, None).unwrap();
    for (start, defined, stop, name) in cases {
        // SAFETY: live instance.
        let s = unsafe { fmi3EnterInitializationMode(g.c, false, 0.0, start, defined != 0, stop) };
        assert_eq!(s, ERROR, "start {start}, stop {stop}");
        let m = g.log.last();
        assert!(
            m.contains("fmi3EnterInitializationMode") && m.contains(name) && m.contains("1e6"),
            "{m}"
        );
    }
    g.start(0.01);
    let (s, t) = g.step(0.0, 1e-3);
    assert_eq!((s, t), (OK, 1e-3));
}

#[test]
fn state_fields_past_their_ranges_are_refused() {
    let scene = Scene::benchmark();
    let f = Fmi2::new(&scene, None).unwrap();
    f.start(0.01);
    // SAFETY: live instance.
    assert_eq!(unsafe { fmi2DoStep(f.c, 0.0, 1e-3, 1) }, OK);
    let bytes = f.state_bytes();
    let target = Fmi2::new(&scene, None).unwrap();
    assert_eq!(target.load(&bytes).0, OK, "the state as saved loads");
    let at = first_output_at(&bytes);
    // rod.deflection, pinB.force_x (the third output), slider.velocity (the ninth).
    for (k, x, name) in [
        (0, 1e308, "rod.deflection"),
        (2, -1e308, "pinB.force_x"),
        (8, 2e12, "slider.velocity"),
    ] {
        let mut forged = bytes.clone();
        put_f64(&mut forged, at + 8 * k, x);
        let (s, m) = target.load(&resealed(forged));
        assert_eq!(s, ERROR, "{name} = {x:e} accepted");
        if logs_here() {
            assert!(m.contains(name) && m.contains("1e12"), "{m}");
        }
    }
    // A state before initialization with a start time of 1e300.
    let fresh = Fmi2::new(&scene, None).unwrap();
    let mut pre = fresh.state_bytes();
    let at = start_time_at(&pre);
    assert_eq!(f64::from_le_bytes(pre[at..at + 8].try_into().unwrap()), 0.0);
    put_f64(&mut pre, at, 1e300);
    let (s, m) = target.load(&resealed(pre));
    assert_eq!(s, ERROR);
    if logs_here() {
        assert!(m.contains("start time") && m.contains("1e6"), "{m}");
    }
    // The target is untouched and usable.
    target.start(0.01);
    // SAFETY: live instance.
    assert_eq!(unsafe { fmi2DoStep(target.c, 0.0, 1e-3, 1) }, OK);
    let all = [vr(&scene, "rod.deflection"), vr(&scene, "pinB.force_x")];
    assert_eq!(target.reals(&all), f.reals(&all));
}

#[test]
fn a_state_of_another_model_is_refused() {
    let dir = temp_dir("hostile_states_models");
    let (auto, bench) = (automotive(), Scene::benchmark());
    let auto_dir = resources(&dir, "automotive", &auto);
    let bench_dir = resources(&dir, "benchmark", &bench);
    let uri = |p: &Path| format!("file://{}", p.display());
    // FMI 2.0.
    let a = Fmi2::new(&auto, Some(&uri(&auto_dir))).expect("the automotive rod instantiates");
    let b = Fmi2::new(&bench, Some(&uri(&bench_dir))).expect("the default scene instantiates");
    let bench_guid = ModelDescription::for_scene(&bench).unwrap().guid;
    let forged = with_guid(&a.state_bytes(), &bench_guid);
    let (s, m) = b.load(&forged);
    assert_eq!(
        s, ERROR,
        "a state of the automotive rod accepted by the default FMU"
    );
    if logs_here() {
        assert!(
            m.contains("this state belongs to another model") && m.contains("description"),
            "{m}"
        );
    }
    // Its own state with a declared parameter changed loads.
    let length = vr(&bench, "rod.length");
    // SAFETY: live instance.
    assert_eq!(unsafe { fmi2SetReal(b.c, &length, 1, &0.25) }, OK);
    let own = b.state_bytes();
    let c = Fmi2::new(&bench, Some(&uri(&bench_dir))).unwrap();
    assert_eq!(c.load(&own).0, OK, "{}", c.log.last());
    // FMI 3.0.
    let a3 = Fmi3::new(&auto, Some(&format!("{}/", auto_dir.display()))).unwrap();
    let b3 = Fmi3::new(&bench, Some(&format!("{}/", bench_dir.display()))).unwrap();
    let token = ModelDescription::for_scene_fmi3(&bench).unwrap().guid;
    let (s, m) = b3.load(&with_guid(&a3.state_bytes(), &token));
    assert_eq!(s, ERROR);
    assert!(m.contains("this state belongs to another model"), "{m}");
    b3.start(0.01);
    assert_eq!(b3.step(0.0, 1e-3).0, OK);
}

#[test]
fn percent_signs_in_resource_folders_are_taken_as_they_are() {
    let dir = temp_dir("hostile_states_percent");
    // The automotive rod: its GUID matches only if its scene is read from the folder (the
    // compiled-in default scene is another model).
    let auto = automotive();
    for folder in ["pct 100%", "a%20b"] {
        let res = resources(&dir, folder, &auto);
        let path = format!("{}/", res.display());
        let i = Fmi3::new(&auto, Some(&path));
        assert!(i.is_some(), "FMI 3.0 resourcePath {path}");
        // FMI 2.0: the URI of the same folder, percent-encoded.
        let encoded = res
            .display()
            .to_string()
            .replace('%', "%25")
            .replace(' ', "%20");
        let uri = format!("file://{encoded}");
        assert!(Fmi2::new(&auto, Some(&uri)).is_some(), "FMI 2.0 {uri}");
    }
}

#[test]
fn handles_of_the_other_standard_are_refused() {
    let scene = Scene::benchmark();
    let d3 = ModelDescription::for_scene_fmi3(&scene).unwrap();
    let torque2 = vr(&scene, "crank.torque");
    let torque3 = d3.table.by_name("crank.torque").unwrap().value_reference;
    let (f, f_ref) = (
        Fmi2::new(&scene, None).unwrap(),
        Fmi2::new(&scene, None).unwrap(),
    );
    let (g, g_ref) = (
        Fmi3::new(&scene, None).unwrap(),
        Fmi3::new(&scene, None).unwrap(),
    );
    for i in [&f, &f_ref] {
        i.start(0.01);
    }
    for i in [&g, &g_ref] {
        i.start(0.01);
    }
    let mut x = [0.0];
    let mut state = ptr::null_mut();
    // SAFETY: live instances of the other standard; valid arrays and out-arguments.
    let refused_by_fmi3: Vec<(&str, i32)> = unsafe {
        let (mut a, mut b, mut c, mut t) = (false, false, false, 0.0);
        vec![
            (
                "fmi3DoStep",
                fmi3DoStep(f.c, 0.0, 1e-3, false, &mut a, &mut b, &mut c, &mut t),
            ),
            (
                "fmi3GetFloat64",
                fmi3GetFloat64(f.c, &torque2, 1, x.as_mut_ptr(), 1),
            ),
            (
                "fmi3SetFloat64",
                fmi3SetFloat64(f.c, &torque2, 1, [1.0].as_ptr(), 1),
            ),
            ("fmi3GetFMUState", fmi3GetFMUState(f.c, &mut state)),
            ("fmi3Terminate", fmi3Terminate(f.c)),
            ("fmi3Reset", fmi3Reset(f.c)),
        ]
    };
    let before = f.log.count();
    // SAFETY: as above; a free of a handle of the other standard is refused.
    unsafe { fmi3FreeInstance(f.c) };
    if logs_here() {
        assert_eq!(f.log.count(), before + 1, "the refused free is reported");
        assert!(
            f.log.last().contains("fmi3FreeInstance"),
            "{}",
            f.log.last()
        );
    }
    for (k, (name, s)) in refused_by_fmi3.iter().enumerate() {
        assert_eq!(*s, ERROR, "{name} with an FMI 2.0 handle");
        if logs_here() {
            let m = &f.log.0.borrow()[k];
            assert!(m.starts_with(name) && m.contains("FMI 2.0 instance"), "{m}");
        }
    }
    let mut state2: fmi2FMUstate = ptr::null_mut();
    // SAFETY: as above.
    let refused_by_fmi2: Vec<(&str, i32)> = unsafe {
        vec![
            ("fmi2DoStep", fmi2DoStep(g.c, 0.0, 1e-3, 1)),
            ("fmi2GetReal", fmi2GetReal(g.c, &torque3, 1, x.as_mut_ptr())),
            ("fmi2SetReal", fmi2SetReal(g.c, &torque3, 1, [1.0].as_ptr())),
            ("fmi2GetFMUstate", fmi2GetFMUstate(g.c, &mut state2)),
            ("fmi2Terminate", fmi2Terminate(g.c)),
            ("fmi2Reset", fmi2Reset(g.c)),
        ]
    };
    // SAFETY: as above.
    unsafe { fmi2FreeInstance(g.c) };
    for (k, (name, s)) in refused_by_fmi2.iter().enumerate() {
        assert_eq!(*s, ERROR, "{name} with an FMI 3.0 handle");
        let m = &g.log.0.borrow()[k];
        assert!(m.starts_with(name) && m.contains("FMI 3.0 instance"), "{m}");
    }
    assert!(
        g.log.last().contains("fmi2FreeInstance"),
        "{}",
        g.log.last()
    );
    assert!(state.is_null() && state2.is_null());
    // Both continue bit for bit with the instances that never saw those calls.
    let mut t = 0.0;
    for _ in 0..5 {
        // SAFETY: live instances.
        unsafe {
            assert_eq!(fmi2DoStep(f.c, t, 1e-3, 1), OK);
            assert_eq!(fmi2DoStep(f_ref.c, t, 1e-3, 1), OK);
        }
        assert_eq!(g.step(t, 1e-3), g_ref.step(t, 1e-3));
        t += 1e-3;
        let (a, b) = (f.reals(&[torque2]), f_ref.reals(&[torque2]));
        assert_eq!(a.1[0].to_bits(), b.1[0].to_bits());
        let (a, b) = (g.reals(&[torque3]), g_ref.reals(&[torque3]));
        assert_eq!(a.1[0].to_bits(), b.1[0].to_bits());
    }
}
