//! The C ABI: the 34 functions of FMI 2.0 Co-Simulation, and all `unsafe` code of the FMI
//! layer.
//!
//! Every function is a thin delegation: convert the C arguments (null checks, slices,
//! strings) and call one method of the safe [`Instance`] through [`Instance::run`], which
//! checks the call sequence, catches panics, logs failures and folds the status. An outer
//! [`guard::catch`] makes sure no panic (not even one while logging) unwinds into the host.
//!
//! The safety contract of each function is the FMI 2.0 standard's: `c` is NULL or a pointer
//! returned by `fmi2Instantiate` and not yet freed; arrays have the lengths passed with them;
//! strings are NUL-terminated. NULL pointers are detected and reported.
//!
//! FMU state handles are opaque integers (never dereferenced), looked up per instance, so a
//! stale or foreign handle gives an error (or a new handle where FMI allows one), not
//! undefined behaviour.
//!
//! Re-entrancy: an `fmi2Component` points to a [`Component`], which holds the [`Instance`] in
//! an `UnsafeCell` behind a busy flag. `&mut Instance` is created only by the call that set
//! the flag, so a logger callback that calls back into the same instance (or a second thread
//! calling it concurrently) never aliases it: such a nested call returns `fmi2Error` and is
//! reported through the logger.

#![allow(non_snake_case, non_camel_case_types)]
#![allow(clippy::missing_safety_doc)]
#![deny(unsafe_op_in_unsafe_fn)]

use std::borrow::Cow;
use std::cell::UnsafeCell;
use std::ffi::{c_char, c_int, c_uint, c_void, CStr, CString};
use std::panic::AssertUnwindSafe;
use std::ptr;
use std::sync::atomic::{AtomicBool, Ordering};

use super::guard;
use super::instance::{Instance, InstantiateArgs};
use super::logging::{printf_escape, LogSink, Logger};
use super::state_machine::Call;
use super::status::{FmiError, FmiResult, Status, StatusKind};
use super::variables::Family;

pub type fmi2Component = *mut c_void;
pub type fmi2ComponentEnvironment = *mut c_void;
pub type fmi2FMUstate = *mut c_void;
pub type fmi2ValueReference = c_uint;
pub type fmi2Real = f64;
pub type fmi2Integer = c_int;
pub type fmi2Boolean = c_int;
pub type fmi2Char = c_char;
pub type fmi2String = *const fmi2Char;
pub type fmi2Byte = c_char;
/// `fmi2Status` (a C enum).
pub type fmi2Status = c_int;

/// `fmi2CallbackLogger`: a printf-like variadic function.
pub type fmi2CallbackLogger = unsafe extern "C" fn(
    fmi2ComponentEnvironment,
    fmi2String,
    fmi2Status,
    fmi2String,
    fmi2String,
    ...
);

/// `fmi2CallbackFunctions`.
#[repr(C)]
pub struct fmi2CallbackFunctions {
    pub logger: Option<fmi2CallbackLogger>,
    pub allocate_memory: Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>,
    pub free_memory: Option<unsafe extern "C" fn(*mut c_void)>,
    pub step_finished: Option<unsafe extern "C" fn(fmi2ComponentEnvironment, fmi2Status)>,
    pub component_environment: fmi2ComponentEnvironment,
}

const ERROR: fmi2Status = Status::Error as fmi2Status;

/// The importer's logger callback.
#[derive(Clone)]
struct CallbackSink {
    callback: fmi2CallbackLogger,
    environment: fmi2ComponentEnvironment,
    instance_name: CString,
}

fn c_string(text: &str) -> CString {
    CString::new(text.replace('\0', " ")).unwrap_or_default()
}

impl LogSink for CallbackSink {
    fn emit(&self, status: Status, category: &'static str, message: &str) {
        let message = c_string(&printf_escape(message));
        let category = c_string(category);
        // SAFETY: the callback comes from the importer's fmi2CallbackFunctions; all string
        // arguments are valid NUL-terminated strings that outlive the call, and the message
        // has every '%' escaped, so the callback reads no variadic arguments.
        unsafe {
            (self.callback)(
                self.environment,
                self.instance_name.as_ptr(),
                status.code(),
                category.as_ptr(),
                message.as_ptr(),
            );
        }
    }
}

/// What an `fmi2Component` points to.
struct Component {
    /// Set while a call runs on `instance`.
    busy: AtomicBool,
    /// Set while a nested call is being reported (a logger that calls back on every
    /// message must not recurse without end).
    reporting: AtomicBool,
    /// The importer's logger, for reporting nested calls without touching `instance`.
    sink: Option<CallbackSink>,
    instance: UnsafeCell<Instance>,
}

impl Component {
    /// Report a call that arrived while another call on this instance was running.
    fn report_busy(&self, name: &str) {
        if self.reporting.swap(true, Ordering::Acquire) {
            return;
        }
        if let Some(sink) = &self.sink {
            let message = format!(
                "{name}: illegal call while another call on this instance is in progress (a re-entrant call from a callback, or concurrent calls from two threads); nothing was done"
            );
            let _ = guard::catch(AssertUnwindSafe(|| {
                sink.emit(Status::Error, "logStatusError", &message);
            }));
        }
        self.reporting.store(false, Ordering::Release);
    }
}

/// Clears the busy flag when the call ends (also if it unwinds).
struct Busy<'a>(&'a AtomicBool);

impl Drop for Busy<'_> {
    fn drop(&mut self) {
        self.0.store(false, Ordering::Release);
    }
}

// ------------------------------------------------------------------ argument conversion

/// `&[T]` from a C array; NULL is allowed only for n = 0.
unsafe fn slice<'a, T>(p: *const T, n: usize, what: &str) -> FmiResult<&'a [T]> {
    if n == 0 {
        return Ok(&[]);
    }
    if p.is_null() {
        return Err(FmiError::rejected(format!(
            "{what} is NULL but its length is {n}"
        )));
    }
    if n > isize::MAX as usize / std::mem::size_of::<T>().max(1) {
        return Err(FmiError::rejected(format!(
            "{what}: length {n} is too large"
        )));
    }
    // SAFETY: non-null, and the caller guarantees n readable elements (FMI 2.0).
    Ok(unsafe { std::slice::from_raw_parts(p, n) })
}

/// `&mut [T]` from a C array; NULL is allowed only for n = 0.
unsafe fn slice_mut<'a, T>(p: *mut T, n: usize, what: &str) -> FmiResult<&'a mut [T]> {
    if n == 0 {
        return Ok(&mut []);
    }
    if p.is_null() {
        return Err(FmiError::rejected(format!(
            "{what} is NULL but its length is {n}"
        )));
    }
    if n > isize::MAX as usize / std::mem::size_of::<T>().max(1) {
        return Err(FmiError::rejected(format!(
            "{what}: length {n} is too large"
        )));
    }
    // SAFETY: non-null, and the caller guarantees n writable elements (FMI 2.0).
    Ok(unsafe { std::slice::from_raw_parts_mut(p, n) })
}

/// `&mut T` from an output pointer.
unsafe fn out<'a, T>(p: *mut T, what: &str) -> FmiResult<&'a mut T> {
    // SAFETY: the caller guarantees p is NULL or points to a writable T.
    unsafe { p.as_mut() }.ok_or_else(|| FmiError::rejected(format!("{what} is NULL")))
}

/// Text from a C string, invalid UTF-8 replaced by U+FFFD; `None` for NULL.
unsafe fn lossy_text<'a>(p: *const c_char) -> Option<Cow<'a, str>> {
    if p.is_null() {
        return None;
    }
    // SAFETY: non-null, and the caller guarantees a NUL-terminated string.
    Some(unsafe { CStr::from_ptr(p) }.to_string_lossy())
}

/// `&str` from a C string; `None` for NULL.
unsafe fn text<'a>(p: *const c_char, what: &str) -> Result<Option<&'a str>, String> {
    if p.is_null() {
        return Ok(None);
    }
    // SAFETY: non-null, and the caller guarantees a NUL-terminated string.
    let s = unsafe { CStr::from_ptr(p) };
    s.to_str()
        .map(Some)
        .map_err(|_| format!("{what} is not valid UTF-8"))
}

fn handle_of(state: fmi2FMUstate) -> Option<usize> {
    (!state.is_null()).then(|| state.addr())
}

fn state_of(handle: usize) -> fmi2FMUstate {
    ptr::without_provenance_mut(handle)
}

/// Run `f` on the instance `c` as FMI call `call`.
unsafe fn dispatch(
    c: fmi2Component,
    call: Call,
    f: impl FnOnce(&mut Instance) -> FmiResult<Status>,
) -> fmi2Status {
    // SAFETY: c is NULL or a live pointer from fmi2Instantiate (FMI 2.0). Only a shared
    // reference is made here: a nested call may hold one at the same time.
    let Some(component) = (unsafe { c.cast::<Component>().as_ref() }) else {
        return ERROR;
    };
    if component.busy.swap(true, Ordering::Acquire) {
        component.report_busy(call.name());
        return ERROR;
    }
    let _busy = Busy(&component.busy);
    // SAFETY: this call set the busy flag, so no other `&mut Instance` exists until it is
    // cleared (when `_busy` drops, after the last use of `instance`).
    let instance = unsafe { &mut *component.instance.get() };
    match guard::catch(AssertUnwindSafe(|| instance.run(call, f).code())) {
        Ok(code) => code,
        Err(_) => {
            instance.enter_error_state();
            ERROR
        }
    }
}

// ------------------------------------------------------------------ inquire platform

#[no_mangle]
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    c"default".as_ptr()
}

#[no_mangle]
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    c"2.0".as_ptr()
}

// ------------------------------------------------------------------ creation and destruction

#[no_mangle]
pub unsafe extern "C" fn fmi2Instantiate(
    instanceName: fmi2String,
    fmuType: c_int,
    fmuGUID: fmi2String,
    fmuResourceLocation: fmi2String,
    functions: *const fmi2CallbackFunctions,
    _visible: fmi2Boolean,
    loggingOn: fmi2Boolean,
) -> fmi2Component {
    let created = guard::catch(AssertUnwindSafe(|| {
        // SAFETY: NULL or the importer's callback struct (FMI 2.0).
        let functions = unsafe { functions.as_ref() }?;
        // SAFETY (all three): NULL or NUL-terminated strings (FMI 2.0).
        let name = unsafe { lossy_text(instanceName) };
        let guid = unsafe { text(fmuGUID, "fmuGUID") };
        let location = unsafe { text(fmuResourceLocation, "fmuResourceLocation") };
        let sink = functions.logger.map(|callback| CallbackSink {
            callback,
            environment: functions.component_environment,
            instance_name: c_string(name.as_deref().unwrap_or("")),
        });
        let logger = Logger::new(
            sink.clone().map(|s| Box::new(s) as Box<dyn LogSink>),
            loggingOn != 0,
        );
        let args = match (&name, guid, location) {
            (Some(instance_name), Ok(Some(guid)), Ok(resource_location)) => InstantiateArgs {
                instance_name,
                fmu_type: fmuType,
                guid,
                resource_location,
            },
            (name, guid, location) => {
                let problem = if name.is_none() {
                    "instanceName is NULL".to_string()
                } else {
                    match guid {
                        Ok(None) => "fmuGUID is NULL".to_string(),
                        Err(e) => e,
                        Ok(Some(_)) => location.err().unwrap_or_default(),
                    }
                };
                logger.status(Status::Error, &format!("fmi2Instantiate: {problem}"));
                return None;
            }
        };
        let instance = Instance::instantiate(args, logger)?;
        Some(Component {
            busy: AtomicBool::new(false),
            reporting: AtomicBool::new(false),
            sink,
            instance: UnsafeCell::new(instance),
        })
    }));
    match created {
        Ok(Some(component)) => Box::into_raw(Box::new(component)).cast(),
        _ => ptr::null_mut(),
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2FreeInstance(c: fmi2Component) {
    // SAFETY: c is NULL or a live pointer from fmi2Instantiate (FMI 2.0).
    let Some(component) = (unsafe { c.cast::<Component>().as_ref() }) else {
        return;
    };
    if component.busy.swap(true, Ordering::Acquire) {
        // Freed from inside a callback of a running call: refuse rather than free memory
        // that call still uses.
        component.report_busy("fmi2FreeInstance");
        return;
    }
    // SAFETY: c came from Box::into_raw in fmi2Instantiate, no call is running on it (the busy
    // flag), and it is freed once (FMI 2.0).
    let component = unsafe { Box::from_raw(c.cast::<Component>()) };
    let _ = guard::catch(AssertUnwindSafe(move || drop(component)));
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetDebugLogging(
    c: fmi2Component,
    loggingOn: fmi2Boolean,
    nCategories: usize,
    categories: *const fmi2String,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::SetDebugLogging, |i| {
            let pointers = slice(categories, nCategories, "categories[]")?;
            let mut names = Vec::with_capacity(pointers.len());
            for (k, &p) in pointers.iter().enumerate() {
                match lossy_text(p) {
                    Some(name) => names.push(name),
                    None => return Err(FmiError::rejected(format!("categories[{k}] is NULL"))),
                }
            }
            let names: Vec<&str> = names.iter().map(|n| n.as_ref()).collect();
            i.set_debug_logging(loggingOn != 0, &names)
        })
    }
}

// ------------------------------------------------------------------ initialization

#[no_mangle]
pub unsafe extern "C" fn fmi2SetupExperiment(
    c: fmi2Component,
    toleranceDefined: fmi2Boolean,
    tolerance: fmi2Real,
    startTime: fmi2Real,
    stopTimeDefined: fmi2Boolean,
    stopTime: fmi2Real,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::SetupExperiment, |i| {
            i.setup_experiment(
                (toleranceDefined != 0).then_some(tolerance),
                startTime,
                (stopTimeDefined != 0).then_some(stopTime),
            )
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2EnterInitializationMode(c: fmi2Component) -> fmi2Status {
    unsafe {
        dispatch(
            c,
            Call::EnterInitializationMode,
            Instance::enter_initialization_mode,
        )
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2ExitInitializationMode(c: fmi2Component) -> fmi2Status {
    unsafe {
        dispatch(
            c,
            Call::ExitInitializationMode,
            Instance::exit_initialization_mode,
        )
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2Terminate(c: fmi2Component) -> fmi2Status {
    unsafe { dispatch(c, Call::Terminate, Instance::terminate) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2Reset(c: fmi2Component) -> fmi2Status {
    unsafe { dispatch(c, Call::Reset, Instance::reset) }
}

// ------------------------------------------------------------------ getters and setters

#[no_mangle]
pub unsafe extern "C" fn fmi2GetReal(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Real,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::GetReal, |i| {
            i.get_real(slice(vr, nvr, "vr[]")?, slice_mut(value, nvr, "value[]")?)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetInteger(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Integer,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::GetInteger, |i| {
            i.get_integer(slice(vr, nvr, "vr[]")?, slice_mut(value, nvr, "value[]")?)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetBoolean(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Boolean,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::GetBoolean, |i| {
            slice_mut(value, nvr, "value[]")?;
            i.no_variables_of(Family::Boolean, slice(vr, nvr, "vr[]")?)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetString(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2String,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::GetString, |i| {
            slice_mut(value, nvr, "value[]")?;
            i.no_variables_of(Family::String, slice(vr, nvr, "vr[]")?)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetReal(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Real,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::SetReal, |i| {
            i.set_real(slice(vr, nvr, "vr[]")?, slice(value, nvr, "value[]")?)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetInteger(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Integer,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::SetInteger, |i| {
            i.set_integer(slice(vr, nvr, "vr[]")?, slice(value, nvr, "value[]")?)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetBoolean(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Boolean,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::SetBoolean, |i| {
            slice(value, nvr, "value[]")?;
            i.no_variables_of(Family::Boolean, slice(vr, nvr, "vr[]")?)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetString(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2String,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::SetString, |i| {
            slice(value, nvr, "value[]")?;
            i.no_variables_of(Family::String, slice(vr, nvr, "vr[]")?)
        })
    }
}

// ------------------------------------------------------------------ FMU states

#[no_mangle]
pub unsafe extern "C" fn fmi2GetFMUstate(
    c: fmi2Component,
    FMUstate: *mut fmi2FMUstate,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::GetFMUstate, |i| {
            let slot = out(FMUstate, "FMUstate")?;
            *slot = state_of(i.get_fmu_state(handle_of(*slot))?);
            Ok(Status::Ok)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetFMUstate(c: fmi2Component, FMUstate: fmi2FMUstate) -> fmi2Status {
    unsafe {
        dispatch(c, Call::SetFMUstate, |i| {
            let handle =
                handle_of(FMUstate).ok_or_else(|| FmiError::rejected("FMUstate is NULL"))?;
            i.set_fmu_state(handle)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2FreeFMUstate(
    c: fmi2Component,
    FMUstate: *mut fmi2FMUstate,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::FreeFMUstate, |i| {
            let slot = out(FMUstate, "FMUstate")?;
            if let Some(handle) = handle_of(*slot) {
                i.free_fmu_state(handle)?;
                *slot = ptr::null_mut();
            }
            Ok(Status::Ok)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SerializedFMUstateSize(
    c: fmi2Component,
    FMUstate: fmi2FMUstate,
    size: *mut usize,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::SerializedFMUstateSize, |i| {
            let size = out(size, "size")?;
            let handle =
                handle_of(FMUstate).ok_or_else(|| FmiError::rejected("FMUstate is NULL"))?;
            *size = i.serialized_size(handle)?;
            Ok(Status::Ok)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SerializeFMUstate(
    c: fmi2Component,
    FMUstate: fmi2FMUstate,
    serializedState: *mut fmi2Byte,
    size: usize,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::SerializeFMUstate, |i| {
            let handle =
                handle_of(FMUstate).ok_or_else(|| FmiError::rejected("FMUstate is NULL"))?;
            let bytes = slice_mut(serializedState.cast::<u8>(), size, "serializedState[]")?;
            i.serialize_fmu_state(handle, bytes)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
    c: fmi2Component,
    serializedState: *const fmi2Byte,
    size: usize,
    FMUstate: *mut fmi2FMUstate,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::DeSerializeFMUstate, |i| {
            let bytes = slice(serializedState.cast::<u8>(), size, "serializedState[]")?;
            let slot = out(FMUstate, "FMUstate")?;
            *slot = state_of(i.deserialize_fmu_state(bytes, handle_of(*slot))?);
            Ok(Status::Ok)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetDirectionalDerivative(
    c: fmi2Component,
    _vUnknown_ref: *const fmi2ValueReference,
    _nUnknown: usize,
    _vKnown_ref: *const fmi2ValueReference,
    _nKnown: usize,
    _dvKnown: *const fmi2Real,
    _dvUnknown: *mut fmi2Real,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::GetDirectionalDerivative, |i| {
            i.get_directional_derivative()
        })
    }
}

// ------------------------------------------------------------------ co-simulation

#[no_mangle]
pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    order: *const fmi2Integer,
    value: *const fmi2Real,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::SetRealInputDerivatives, |i| {
            i.set_real_input_derivatives(
                slice(vr, nvr, "vr[]")?,
                slice(order, nvr, "order[]")?,
                slice(value, nvr, "value[]")?,
            )
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    _nvr: usize,
    _order: *const fmi2Integer,
    _value: *mut fmi2Real,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::GetRealOutputDerivatives, |i| {
            i.get_real_output_derivatives()
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2DoStep(
    c: fmi2Component,
    currentCommunicationPoint: fmi2Real,
    communicationStepSize: fmi2Real,
    _noSetFMUStatePriorToCurrentPoint: fmi2Boolean,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::DoStep, |i| {
            i.do_step(currentCommunicationPoint, communicationStepSize)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2CancelStep(c: fmi2Component) -> fmi2Status {
    // Always rejected by the call sequence: no step is ever in progress.
    unsafe { dispatch(c, Call::CancelStep, |_| Ok(Status::Ok)) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetStatus(
    c: fmi2Component,
    s: c_int,
    value: *mut fmi2Status,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::GetStatus, |i| {
            let value = out(value, "value")?;
            *value = i.get_status(StatusKind::from_code(s)?)?.code();
            Ok(Status::Ok)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealStatus(
    c: fmi2Component,
    s: c_int,
    value: *mut fmi2Real,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::GetRealStatus, |i| {
            let value = out(value, "value")?;
            *value = i.get_real_status(StatusKind::from_code(s)?)?;
            Ok(Status::Ok)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetIntegerStatus(
    c: fmi2Component,
    s: c_int,
    value: *mut fmi2Integer,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::GetIntegerStatus, |i| {
            let value = out(value, "value")?;
            *value = i.get_integer_status(StatusKind::from_code(s)?)?;
            Ok(Status::Ok)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetBooleanStatus(
    c: fmi2Component,
    s: c_int,
    value: *mut fmi2Boolean,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::GetBooleanStatus, |i| {
            let value = out(value, "value")?;
            *value = fmi2Boolean::from(i.get_boolean_status(StatusKind::from_code(s)?)?);
            Ok(Status::Ok)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetStringStatus(
    c: fmi2Component,
    s: c_int,
    value: *mut fmi2String,
) -> fmi2Status {
    unsafe {
        dispatch(c, Call::GetStringStatus, |i| {
            out(value, "value")?;
            i.get_string_status(StatusKind::from_code(s)?)
        })
    }
}
