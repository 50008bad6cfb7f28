//! One FMU instance driven through the exported C functions, in process: instantiation with a
//! logger that counts the messages of this instance by status, the value references of the
//! default scene by role, and reading every value for the lockstep comparison.

use std::cell::Cell;
use std::ffi::{c_void, CString};
use std::ptr;

use flexrod::fmi::description::ModelDescription;
use flexrod::fmi::ffi::lifecycle::{fmi2FreeInstance, fmi2Instantiate};
use flexrod::fmi::ffi::values::{fmi2GetInteger, fmi2GetReal};
use flexrod::fmi::ffi::{
    fmi2CallbackFunctions, fmi2CallbackLogger, fmi2Component, fmi2ComponentEnvironment,
    fmi2FMUstate, fmi2Status, fmi2String,
};
use flexrod::fmi::standard::Standard;
use flexrod::fmi::variables::{Causality, Family, Value};
use flexrod::Scene;

pub const OK: fmi2Status = 0;
pub const WARNING: fmi2Status = 1;
pub const DISCARD: fmi2Status = 2;
pub const ERROR: fmi2Status = 3;

/// A parameter of the default scene with its start value (Real or Integer).
#[derive(Clone, Copy)]
pub struct Parameter {
    pub vr: u32,
    pub real: bool,
    pub start: f64,
}

/// The value references of the default scene, by role (from its variable table).
pub struct Vars {
    pub guid: CString,
    pub real_inputs: Vec<u32>,
    pub real_outputs: Vec<u32>,
    pub parameters: Vec<Parameter>,
    pub calculated: Vec<u32>,
    /// Every Real and every Integer, for the lockstep comparison.
    pub all_reals: Vec<u32>,
    pub all_integers: Vec<u32>,
    pub rod_model: u32,
    pub rod_elements: u32,
    pub rod_modes: u32,
    pub rod_policy: u32,
}

impl Vars {
    pub fn default_scene() -> Vars {
        let d = ModelDescription::for_scene(&Scene::benchmark()).expect("default scene");
        let vr_of = |name: &str| {
            d.table
                .by_name(name)
                .unwrap_or_else(|| panic!("{name} in the default scene"))
                .value_reference
        };
        let mut v = Vars {
            guid: CString::new(d.guid.clone()).unwrap(),
            real_inputs: vec![],
            real_outputs: vec![],
            parameters: vec![],
            calculated: vec![],
            all_reals: vec![],
            all_integers: vec![],
            rod_model: vr_of("rod.model"),
            rod_elements: vr_of("rod.elements"),
            rod_modes: vr_of("rod.modes"),
            rod_policy: vr_of("rod.deflection_policy"),
        };
        for x in d.table.variables() {
            let vr = x.value_reference;
            let real = Family::of(x.value_type, Standard::Fmi2) == Family::Real;
            if real {
                v.all_reals.push(vr);
            } else {
                v.all_integers.push(vr);
            }
            match x.causality {
                Causality::Input if real => v.real_inputs.push(vr),
                Causality::Output => v.real_outputs.push(vr),
                Causality::Parameter => v.parameters.push(Parameter {
                    vr,
                    real,
                    start: match x.start {
                        Some(Value::Real(r)) => r,
                        Some(Value::Integer(i)) => i as f64,
                        _ => 1.0,
                    },
                }),
                Causality::CalculatedParameter => v.calculated.push(vr),
                _ => {}
            }
        }
        v
    }

    /// Whether `vr` is a Real variable of the FMU.
    pub fn is_real(&self, vr: u32) -> bool {
        self.all_reals.contains(&vr)
    }

    pub fn is_integer(&self, vr: u32) -> bool {
        self.all_integers.contains(&vr)
    }
}

/// Messages one instance passed to its logger, by status (`fmi2OK` .. `fmi2Pending`).
#[derive(Default)]
pub struct Log {
    pub by_status: [Cell<u64>; 6],
    /// Messages that report a caught panic ("internal error").
    pub panics: Cell<u64>,
    /// The last error message.
    pub last_error: std::cell::RefCell<String>,
}

/// The logger: counts the messages by status in the [`Log`] the component environment points
/// to. FMI 2.0 declares it variadic; the FMU escapes every '%' of its messages and never passes
/// variadic arguments, and on x86-64 System V a variadic call reaches a fixed-arity function
/// with the same leading arguments unchanged.
unsafe extern "C" fn count_message(
    env: fmi2ComponentEnvironment,
    _name: fmi2String,
    status: fmi2Status,
    _category: fmi2String,
    message: fmi2String,
) {
    // SAFETY: env is the `Log` of the instance, alive as long as the instance (`Fmu` owns it).
    let Some(log) = (unsafe { env.cast::<Log>().as_ref() }) else {
        return;
    };
    let slot = &log.by_status[status.clamp(0, 5) as usize];
    slot.set(slot.get() + 1);
    if !message.is_null() {
        // SAFETY: the FMU passes a NUL-terminated string that outlives the call.
        let text = unsafe { std::ffi::CStr::from_ptr(message) }.to_string_lossy();
        if text.contains("panic") {
            log.panics.set(log.panics.get() + 1);
        }
        if status == ERROR {
            *log.last_error.borrow_mut() = text.into_owned();
        }
    }
}

/// Callbacks with the counting logger writing to `log` (no logger off x86-64 Linux).
pub fn callbacks(log: *const Log) -> fmi2CallbackFunctions {
    let logger = if cfg!(all(target_arch = "x86_64", target_os = "linux")) {
        type Fixed = unsafe extern "C" fn(
            fmi2ComponentEnvironment,
            fmi2String,
            fmi2Status,
            fmi2String,
            fmi2String,
        );
        // SAFETY: see `count_message`: the FMU calls it with exactly these five arguments.
        Some(unsafe { std::mem::transmute::<Fixed, fmi2CallbackLogger>(count_message as Fixed) })
    } else {
        None
    };
    fmi2CallbackFunctions {
        logger,
        allocate_memory: None,
        free_memory: None,
        step_finished: None,
        component_environment: log as *mut c_void,
    }
}

/// A live instance with its own message counts.
pub struct Fmu {
    pub c: fmi2Component,
    pub log: Box<Log>,
}

impl Fmu {
    pub fn new(vars: &Vars, name: &str) -> Fmu {
        let log = Box::<Log>::default();
        let cb = callbacks(&*log);
        let name = CString::new(name).unwrap();
        // SAFETY: valid strings and callbacks; the callbacks struct is copied by the FMU.
        let c = unsafe {
            fmi2Instantiate(name.as_ptr(), 1, vars.guid.as_ptr(), ptr::null(), &cb, 0, 0)
        };
        assert!(!c.is_null(), "the default scene instantiates");
        Fmu { c, log }
    }

    /// Error messages logged so far.
    pub fn errors_logged(&self) -> u64 {
        self.log.by_status[ERROR as usize].get()
    }

    /// Whether a logger is installed (the error-message check applies).
    pub fn has_logger(&self) -> bool {
        cfg!(all(target_arch = "x86_64", target_os = "linux"))
    }

    /// Every Real and Integer of the FMU, with the statuses of the two reads.
    pub fn snapshot(&self, vars: &Vars) -> Snapshot {
        let mut reals = vec![0.0; vars.all_reals.len()];
        let mut integers = vec![0; vars.all_integers.len()];
        // SAFETY: live instance, arrays of the length passed.
        let (sr, si) = unsafe {
            (
                fmi2GetReal(
                    self.c,
                    vars.all_reals.as_ptr(),
                    reals.len(),
                    reals.as_mut_ptr(),
                ),
                fmi2GetInteger(
                    self.c,
                    vars.all_integers.as_ptr(),
                    integers.len(),
                    integers.as_mut_ptr(),
                ),
            )
        };
        Snapshot {
            real_status: sr,
            reals,
            integer_status: si,
            integers,
        }
    }
}

impl Drop for Fmu {
    fn drop(&mut self) {
        // The FMU owns its states: fmi2FreeInstance frees them with the instance.
        // SAFETY: c came from fmi2Instantiate and is freed once.
        unsafe { fmi2FreeInstance(self.c) };
    }
}

/// Every value of an instance at one moment.
#[derive(Debug)]
pub struct Snapshot {
    pub real_status: fmi2Status,
    pub reals: Vec<f64>,
    pub integer_status: fmi2Status,
    pub integers: Vec<i32>,
}

impl Snapshot {
    /// Bit-for-bit equality (NaN included), statuses first.
    pub fn same_as(&self, other: &Snapshot) -> bool {
        self.real_status == other.real_status
            && self.integer_status == other.integer_status
            && (self.real_status != OK
                || self
                    .reals
                    .iter()
                    .zip(&other.reals)
                    .all(|(a, b)| a.to_bits() == b.to_bits()))
            && (self.integer_status != OK || self.integers == other.integers)
    }
}

/// A null FMU state.
pub fn null_state() -> fmi2FMUstate {
    ptr::null_mut()
}
