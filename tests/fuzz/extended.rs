//! Generators beyond the call sequences of one FMI 2.0 instance pair, run once per sequence:
//!
//! - forged pre-initialization states: the scene text of a serialized state edited (a random
//!   `[solver]`, `[experiment]`, `[rod]` or `[crank]` key set to a random value, in range or not,
//!   or `[[rod.section]]` stations added), the checksum recomputed. Oracle: refused with
//!   `fmi2Error` and a message, or accepted and then every call ends within
//!   [`WALL_LIMIT`] with finite outputs;
//! - in-range extremes (1 sequence in [`EXTREMES_EVERY`]): the largest models and the most
//!   demanding in-range solver keys through fmi2SetInteger / fmi2SetReal and a forged state,
//!   one long communication step. Oracle: every call within [`WALL_LIMIT`];
//! - freed and foreign handles, FMI 2.0 and FMI 3.0: a second free, calls after the free, a
//!   pointer that never was an instance. Oracle: `fmi2Error` / `fmi3Error` from every call,
//!   no crash (a crash ends the whole run);
//! - FMI 3.0 sequences: random calls of the `fmi3*` entry points (instantiation, initialization
//!   with random times, set and get of the Float64 variables with abusive values, steps with
//!   random arguments, states saved, serialized and restored, terminate, reset). Oracle:
//!   statuses OK to Error, finite values with `fmi3OK`, no panic reported.

use std::cell::Cell;
use std::ffi::{c_void, CString};
use std::ptr;
use std::time::Instant;

use flexrod::fmi::description::ModelDescription;
use flexrod::fmi::ffi::fmi3::lifecycle::*;
use flexrod::fmi::ffi::fmi3::states::*;
use flexrod::fmi::ffi::fmi3::stepping::fmi3DoStep;
use flexrod::fmi::ffi::fmi3::values::{fmi3GetFloat64, fmi3SetFloat64};
use flexrod::fmi::ffi::fmi3::{fmi3FMUState, fmi3Instance, fmi3InstanceEnvironment, fmi3String};
use flexrod::fmi::ffi::lifecycle::*;
use flexrod::fmi::ffi::states::*;
use flexrod::fmi::ffi::stepping::*;
use flexrod::fmi::ffi::values::*;
use flexrod::fmi::standard::Standard;
use flexrod::fmi::variables::{Causality, Family};
use flexrod::hash::fnv1a_64;
use flexrod::Scene;

use super::fmu::{null_state, Fmu, Vars, ERROR, OK, WARNING};
use super::oracle::Violations;
use super::rng::Rng;

/// Longest a single call may take, s: the documented worst case (docs/fmu.md, "Time per
/// call": a few seconds) with a margin for a loaded machine.
pub const WALL_LIMIT: f64 = 30.0;

/// One sequence in this many also runs the in-range extremes (seconds each).
pub const EXTREMES_EVERY: u64 = 2000;

/// Counts of the extended generators.
#[derive(Default, Debug, Clone, Copy)]
pub struct Extended {
    pub forged_states: u64,
    pub forged_refused: u64,
    pub forged_calls_after: u64,
    pub extremes: u64,
    pub slowest_call: f64,
    pub stale_handle_calls: u64,
    pub fmi3_sequences: u64,
    pub fmi3_calls: u64,
}

impl Extended {
    pub fn add(&mut self, o: &Extended) {
        self.forged_states += o.forged_states;
        self.forged_refused += o.forged_refused;
        self.forged_calls_after += o.forged_calls_after;
        self.extremes += o.extremes;
        self.slowest_call = self.slowest_call.max(o.slowest_call);
        self.stale_handle_calls += o.stale_handle_calls;
        self.fmi3_sequences += o.fmi3_sequences;
        self.fmi3_calls += o.fmi3_calls;
    }
}

/// Run the extended generators of sequence `seq`.
pub fn run(seq: u64, vars: &Vars, ext: &mut Extended, v: &mut Violations) {
    let mut rng = Rng::new(0x3e_0000_0000 ^ seq.wrapping_mul(0x2545_f491_4f6c_dd1d));
    forged_state(&mut rng, vars, ext, v, seq, false);
    stale_handles(&mut rng, vars, ext, v);
    fmi3_sequence(&mut rng, ext, v, seq);
    if seq % EXTREMES_EVERY == EXTREMES_EVERY - 1 {
        forged_state(&mut rng, vars, ext, v, seq, true);
    }
}

/// Time `f`, record the slowest call, and flag one past [`WALL_LIMIT`].
fn timed<T>(ext: &mut Extended, v: &mut Violations, what: &str, f: impl FnOnce() -> T) -> T {
    let t0 = Instant::now();
    let r = f();
    let took = t0.elapsed().as_secs_f64();
    ext.slowest_call = ext.slowest_call.max(took);
    if took > WALL_LIMIT {
        v.add(format!("{what} took {took:.1} s, over {WALL_LIMIT} s"));
    }
    r
}

/// Keys of a serialized scene a forger edits, by table.
const KEYS: [(&str, &str); 16] = [
    ("solver", "max_halvings"),
    ("solver", "max_newton_iterations"),
    ("solver", "newton_tolerance"),
    ("solver", "step"),
    ("solver", "rho_inf"),
    ("solver", "tolerance"),
    ("solver", "method"),
    ("experiment", "start_time"),
    ("experiment", "stop_time"),
    ("experiment", "step_size"),
    ("experiment", "crank_speed"),
    ("rod", "elements"),
    ("rod", "modes"),
    ("rod", "youngs_modulus"),
    ("rod", "density"),
    ("crank", "length"),
];

/// Values a forger writes (TOML literals): out of every range, at the edges, in range.
const VALUES: [&str; 26] = [
    "0",
    "1",
    "-1",
    "6",
    "20",
    "21",
    "100",
    "101",
    "100000",
    "1000000000",
    "18446744073709551615",
    "0.0",
    "-0.0",
    "1e-300",
    "1e-9",
    "1e-4",
    "0.5",
    "1e300",
    "nan",
    "inf",
    "-inf",
    "1.5",
    "\"generalized_alpha\"",
    "\"rk4\"",
    "\"segments\"",
    "\"x\"",
];

/// In-range extremes: (table, key, value).
const EXTREMES: [(&str, &str, &str); 10] = [
    ("solver", "max_halvings", "20"),
    ("solver", "max_newton_iterations", "100"),
    ("solver", "newton_tolerance", "1e-300"),
    ("solver", "method", "\"generalized_alpha\""),
    ("solver", "step", "1e-9"),
    ("solver", "tolerance", "1e-10"),
    ("rod", "elements", "128"),
    ("rod", "modes", "384"),
    ("rod", "youngs_modulus", "1e5"),
    ("rod", "density", "1e5"),
];

/// `text` (a scene) with `key = value` in table `table`, the key's old line removed.
fn set_key(text: &str, table: &str, key: &str, value: &str) -> String {
    let header = format!("[{table}]");
    let mut out = String::new();
    let mut current = String::new();
    let prefix = format!("{key} = ");
    for line in text.lines() {
        let trimmed = line.trim();
        if trimmed.starts_with('[') {
            current = trimmed.to_string();
        }
        if current == header && trimmed.starts_with(&prefix) {
            continue;
        }
        out.push_str(line);
        out.push('\n');
        if trimmed == header {
            out.push_str(&format!("{prefix}{value}\n"));
        }
    }
    out
}

/// `n` stations of a tapered section along a rod of length `length`.
fn stations(n: usize, length: f64) -> String {
    let mut text = String::new();
    for k in 0..n {
        let s = length * k as f64 / (n.max(2) - 1) as f64;
        text += &format!(
            "\n[[rod.section]]\nposition = {s:e}\narea = {:e}\narea_moment = {:e}\n",
            3e-5 * (1.0 + 0.1 * (k % 3) as f64),
            8e-11 * (1.0 + 0.1 * (k % 3) as f64)
        );
    }
    text
}

/// A forged pre-initialization state (or, with `extremes`, one at the in-range extremes) into a
/// fresh instance; if accepted, initialization and a few steps, each timed.
fn forged_state(
    rng: &mut Rng,
    vars: &Vars,
    ext: &mut Extended,
    v: &mut Violations,
    seq: u64,
    extremes: bool,
) {
    let source = Fmu::new(vars, "source");
    // SAFETY (all calls): live instances, buffers of the lengths passed.
    let bytes = unsafe {
        if rng.one_in(3) {
            fmi2EnterInitializationMode(source.c);
        }
        let mut slot = null_state();
        if fmi2GetFMUstate(source.c, &mut slot) != OK {
            v.add(format!(
                "sequence {seq}: fmi2GetFMUstate before initialization refused"
            ));
            return;
        }
        let mut size = 0;
        fmi2SerializedFMUstateSize(source.c, slot, &mut size);
        let mut bytes = vec![0u8; size];
        fmi2SerializeFMUstate(source.c, slot, bytes.as_mut_ptr().cast(), size);
        bytes
    };
    let Some(start) = bytes.windows(8).position(|w| w == b"name = \"") else {
        v.add(format!(
            "sequence {seq}: no scene text in a serialized state"
        ));
        return;
    };
    let len = u32::from_le_bytes(bytes[start - 4..start].try_into().unwrap()) as usize;
    let mut text = String::from_utf8_lossy(&bytes[start..start + len]).into_owned();
    let length = Scene::benchmark().rod.length;
    if extremes {
        for _ in 0..1 + rng.below(4) {
            let (table, key, value) = rng.pick(&EXTREMES);
            text = set_key(&text, table, key, value);
        }
        if rng.one_in(2) {
            text = set_key(&text, "rod", "area", "0.0");
            text = set_key(&text, "rod", "area_moment", "0.0");
            text += &stations(flexrod::beam::section_table::MAX_STATIONS, length);
        }
        ext.extremes += 1;
    } else {
        for _ in 0..1 + rng.below(3) {
            let (table, key) = rng.pick(&KEYS);
            text = set_key(&text, table, key, rng.pick(&VALUES));
        }
        if rng.one_in(16) {
            let n = rng.pick(&[1, 2, 30, 257, 1000]);
            text = set_key(&text, "rod", "area", "0.0");
            text = set_key(&text, "rod", "area_moment", "0.0");
            text += &stations(n, length);
        }
    }
    let mut forged = bytes[..start - 4].to_vec();
    // The model's bytes are length-prefixed (u64) after the shell's header: magic, version,
    // GUID, machine state, last step status, start time, stop flag and stop time.
    let guid_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let model_len_at = 16 + guid_len + 1 + 1 + 8 + 1 + 8;
    let model_len = u64::from_le_bytes(bytes[model_len_at..model_len_at + 8].try_into().unwrap());
    let model_len = model_len as usize + text.len() - len;
    forged[model_len_at..model_len_at + 8].copy_from_slice(&(model_len as u64).to_le_bytes());
    forged.extend_from_slice(&(text.len() as u32).to_le_bytes());
    forged.extend_from_slice(text.as_bytes());
    forged.extend_from_slice(&bytes[start + len..bytes.len() - 8]);
    let sum = fnv1a_64(&forged);
    forged.extend_from_slice(&sum.to_le_bytes());
    ext.forged_states += 1;
    let target = Fmu::new(vars, "target");
    let mut slot = null_state();
    // SAFETY: live instance, valid buffer.
    let status = timed(ext, v, "fmi2DeSerializeFMUstate", || unsafe {
        fmi2DeSerializeFMUstate(target.c, forged.as_ptr().cast(), forged.len(), &mut slot)
    });
    if status != OK {
        ext.forged_refused += 1;
        if status != ERROR {
            v.add(format!(
                "sequence {seq}: a forged state answered {status}, allowed fmi2OK or fmi2Error"
            ));
        } else if target.has_logger() && target.log.last_error.borrow().is_empty() {
            v.add(format!(
                "sequence {seq}: a forged state refused without a message"
            ));
        }
        return;
    }
    // Accepted: whatever it holds, each call ends in bounded time with finite values.
    // SAFETY: live instance, buffers of the lengths passed.
    unsafe {
        let calls: [(&str, &dyn Fn() -> i32); 3] = [
            ("fmi2SetFMUstate", &|| fmi2SetFMUstate(target.c, slot)),
            ("fmi2EnterInitializationMode", &|| {
                fmi2EnterInitializationMode(target.c)
            }),
            ("fmi2ExitInitializationMode", &|| {
                fmi2ExitInitializationMode(target.c)
            }),
        ];
        for (name, call) in calls {
            timed(ext, v, name, call);
            ext.forged_calls_after += 1;
        }
        let mut t = 0.0;
        fmi2GetRealStatus(target.c, 2, &mut t);
        let steps = if extremes { 2 } else { 3 };
        for _ in 0..steps {
            let h = if extremes {
                rng.pick(&[1e-4, 1e-3, 1e-2])
            } else {
                1e-4
            };
            let s = timed(ext, v, "fmi2DoStep after a forged state", || {
                fmi2DoStep(target.c, t, h, 0)
            });
            ext.forged_calls_after += 1;
            let mut out = vec![0.0; vars.real_outputs.len()];
            let rs = fmi2GetReal(
                target.c,
                vars.real_outputs.as_ptr(),
                out.len(),
                out.as_mut_ptr(),
            );
            if s == OK || s == WARNING {
                t += h;
                v.check_values(rs, &out, &format!("sequence {seq}: forged state, outputs"));
            } else if !(0..=3).contains(&s) {
                v.add(format!("sequence {seq}: fmi2DoStep answered {s}"));
            }
        }
    }
}

/// Calls on handles that are not (or no longer) instances, FMI 2.0 and FMI 3.0.
fn stale_handles(rng: &mut Rng, vars: &Vars, ext: &mut Extended, v: &mut Violations) {
    let mut local = [0u64; 32];
    let foreign = local.as_mut_ptr().cast::<c_void>();
    // SAFETY: every handle goes through the registry; arrays of the lengths passed.
    unsafe {
        let fresh = Fmu::new(vars, "stale");
        let c = fresh.c;
        if rng.one_in(2) {
            fmi2EnterInitializationMode(c);
            fmi2ExitInitializationMode(c);
            fmi2DoStep(c, 0.0, 1e-4, 0);
        }
        // Freed here; `fresh` frees it again when it drops.
        fmi2FreeInstance(c);
        let handle = if rng.one_in(4) { foreign } else { c };
        for _ in 0..1 + rng.below(6) {
            let mut x = [0.0; 2];
            let mut slot = null_state();
            let s = match rng.below(8) {
                0 => fmi2DoStep(handle, 0.0, 1e-4, 0),
                1 => fmi2GetReal(handle, vars.real_outputs.as_ptr(), 2, x.as_mut_ptr()),
                2 => fmi2SetReal(handle, vars.real_inputs.as_ptr(), 1, x.as_ptr()),
                3 => fmi2GetFMUstate(handle, &mut slot),
                4 => fmi2Terminate(handle),
                5 => fmi2Reset(handle),
                6 => fmi2EnterInitializationMode(handle),
                _ => {
                    fmi2FreeInstance(handle);
                    ERROR
                }
            };
            ext.stale_handle_calls += 1;
            if s != ERROR {
                v.add(format!(
                    "a call on a freed or foreign FMI 2.0 handle answered {s}"
                ));
            }
        }
    }
    let f3 = Fmi3::new();
    let i = f3.instantiate();
    // SAFETY: as above.
    unsafe {
        fmi3FreeInstance(i);
        let handle = if rng.one_in(4) { foreign } else { i };
        for _ in 0..1 + rng.below(4) {
            let (mut a, mut b, mut e, mut last) = (false, false, false, 0.0);
            let mut x = 0.0;
            let s = match rng.below(4) {
                0 => fmi3DoStep(handle, 0.0, 1e-4, false, &mut a, &mut b, &mut e, &mut last),
                1 => fmi3GetFloat64(handle, &f3.outputs[0], 1, &mut x, 1),
                2 => fmi3Terminate(handle),
                _ => {
                    fmi3FreeInstance(handle);
                    ERROR
                }
            };
            ext.stale_handle_calls += 1;
            if s != ERROR {
                v.add(format!(
                    "a call on a freed or foreign FMI 3.0 handle answered {s}"
                ));
            }
        }
    }
}

/// Messages reported by an FMI 3.0 instance: the count of those naming a panic.
#[derive(Default)]
struct Log3 {
    panics: Cell<u64>,
}

unsafe extern "C" fn log3(
    env: fmi3InstanceEnvironment,
    _status: i32,
    _category: fmi3String,
    message: fmi3String,
) {
    // SAFETY: env is the `Log3` of the instance, alive as long as it (`Fmi3` owns it).
    let Some(log) = (unsafe { env.cast::<Log3>().as_ref() }) else {
        return;
    };
    if !message.is_null() {
        // SAFETY: a NUL-terminated string that outlives the call.
        let text = unsafe { std::ffi::CStr::from_ptr(message) }.to_string_lossy();
        if text.contains("panic") {
            log.panics.set(log.panics.get() + 1);
        }
    }
}

/// The FMI 3.0 description of the default scene and a logger.
struct Fmi3 {
    token: CString,
    inputs: Vec<u32>,
    outputs: Vec<u32>,
    log: Box<Log3>,
}

impl Fmi3 {
    fn new() -> Fmi3 {
        let d = ModelDescription::for_scene_fmi3(&Scene::benchmark()).expect("default scene");
        let mut inputs = Vec::new();
        let mut outputs = Vec::new();
        for x in d.table.variables() {
            if Family::of(x.value_type, Standard::Fmi3) != Family::Real || x.dimension.is_some() {
                continue;
            }
            match x.causality {
                Causality::Input => inputs.push(x.value_reference),
                Causality::Output => outputs.push(x.value_reference),
                _ => {}
            }
        }
        Fmi3 {
            token: CString::new(d.guid).unwrap(),
            inputs,
            outputs,
            log: Box::default(),
        }
    }

    fn instantiate(&self) -> fmi3Instance {
        // SAFETY: valid strings; the logger's environment outlives the instance.
        let i = unsafe {
            fmi3InstantiateCoSimulation(
                c"fuzz3".as_ptr(),
                self.token.as_ptr(),
                ptr::null(),
                false,
                true,
                false,
                false,
                ptr::null(),
                0,
                (&*self.log as *const Log3).cast_mut().cast(),
                Some(log3),
                None,
            )
        };
        assert!(!i.is_null(), "the default scene instantiates (FMI 3.0)");
        i
    }
}

/// A random sequence of FMI 3.0 calls on one instance.
fn fmi3_sequence(rng: &mut Rng, ext: &mut Extended, v: &mut Violations, seq: u64) {
    let f3 = Fmi3::new();
    let i = f3.instantiate();
    ext.fmi3_sequences += 1;
    let mut t = 0.0;
    let mut states: Vec<fmi3FMUState> = Vec::new();
    // SAFETY: live instance; arrays of the lengths passed; state handles are the FMU's.
    unsafe {
        for _ in 0..5 + rng.below(25) {
            ext.fmi3_calls += 1;
            let (name, s, values) = match rng.below(11) {
                0 => {
                    let start = if rng.one_in(4) {
                        rng.abusive_real()
                    } else {
                        0.0
                    };
                    let stop_defined = rng.one_in(2);
                    let s = fmi3EnterInitializationMode(i, false, 0.0, start, stop_defined, 1.0);
                    ("fmi3EnterInitializationMode", s, vec![])
                }
                1 => (
                    "fmi3ExitInitializationMode",
                    fmi3ExitInitializationMode(i),
                    vec![],
                ),
                2..=4 => {
                    let h = if rng.one_in(5) {
                        rng.abusive_real()
                    } else {
                        rng.pick(&[1e-4, 5e-4, 1e-3])
                    };
                    let now = if rng.one_in(5) { rng.abusive_real() } else { t };
                    let (mut a, mut b, mut e, mut last) = (false, false, false, 0.0);
                    let s = fmi3DoStep(i, now, h, false, &mut a, &mut b, &mut e, &mut last);
                    if s == OK || s == WARNING {
                        t = now + h;
                    }
                    ("fmi3DoStep", s, vec![])
                }
                5 | 6 => {
                    let mut out = vec![0.0; f3.outputs.len()];
                    let s = fmi3GetFloat64(
                        i,
                        f3.outputs.as_ptr(),
                        f3.outputs.len(),
                        out.as_mut_ptr(),
                        out.len(),
                    );
                    ("fmi3GetFloat64", s, out)
                }
                7 => {
                    let vr = rng.pick(&f3.inputs);
                    let x = if rng.one_in(2) {
                        rng.abusive_real()
                    } else {
                        rng.pick(&[0.0, 1.0, 150.0, -3.0])
                    };
                    ("fmi3SetFloat64", fmi3SetFloat64(i, &vr, 1, &x, 1), vec![])
                }
                8 => {
                    let mut st: fmi3FMUState = ptr::null_mut();
                    let s = fmi3GetFMUState(i, &mut st);
                    if s == OK {
                        states.push(st);
                    }
                    ("fmi3GetFMUState", s, vec![])
                }
                9 => {
                    let Some(&st) = states.last() else { continue };
                    let s = if rng.one_in(2) {
                        fmi3SetFMUState(i, st)
                    } else {
                        let mut size = 0;
                        let mut s = fmi3SerializedFMUStateSize(i, st, &mut size);
                        if s == OK {
                            let mut bytes = vec![0u8; size];
                            s = fmi3SerializeFMUState(i, st, bytes.as_mut_ptr(), size);
                            if s == OK {
                                let mut back: fmi3FMUState = ptr::null_mut();
                                s = fmi3DeserializeFMUState(i, bytes.as_ptr(), size, &mut back);
                                if s == OK {
                                    s = fmi3SetFMUState(i, back);
                                    states.push(back);
                                }
                            }
                        }
                        s
                    };
                    ("fmi3SetFMUState / serialize", s, vec![])
                }
                _ => {
                    if rng.one_in(2) {
                        ("fmi3Terminate", fmi3Terminate(i), vec![])
                    } else {
                        t = 0.0;
                        ("fmi3Reset", fmi3Reset(i), vec![])
                    }
                }
            };
            if !(0..=3).contains(&s) {
                v.add(format!("sequence {seq}: {name} answered {s}"));
            }
            v.check_values(s, &values, &format!("sequence {seq}: {name}"));
        }
        for st in states.iter_mut().rev() {
            fmi3FreeFMUState(i, st);
        }
        fmi3FreeInstance(i);
        fmi3FreeInstance(i);
    }
    if f3.log.panics.get() > 0 {
        v.add(format!("sequence {seq}: FMI 3.0 reported a panic"));
    }
}
