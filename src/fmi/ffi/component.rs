//! What an `fmi2Component` (or an `fmi3Instance`) points to ([`Component`]: the instance behind a busy flag, and the
//! importer's logger), how a call reaches the instance ([`dispatch`]), and creating and
//! freeing components.

use std::cell::UnsafeCell;
use std::collections::BTreeMap;
use std::ffi::{c_int, CString};
use std::panic::AssertUnwindSafe;
use std::ptr;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, MutexGuard};

use super::convert::{lossy_text, text};
use super::{
    fmi2Boolean, fmi2CallbackFunctions, fmi2CallbackLogger, fmi2Component,
    fmi2ComponentEnvironment, fmi2Status, fmi2String,
};
use crate::fmi::guard;
use crate::fmi::instance::{instantiate_name, Instance, InstantiateArgs};
use crate::fmi::logging::{printf_escape, LogSink, Logger};
use crate::fmi::standard::Standard;
use crate::fmi::state_machine::Call;
use crate::fmi::status::{FmiResult, Status};

const ERROR: fmi2Status = Status::Error as fmi2Status;
/// The importer's FMI 2.0 logger callback.
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

/// What an `fmi2Component` or an `fmi3Instance` points to.
pub struct Component {
    /// Set while a call runs on `instance`.
    busy: AtomicBool,
    /// Set while a nested call is being reported (a logger that calls back on every
    /// message must not recurse without end).
    reporting: AtomicBool,
    /// The standard of the instance: only the functions of this standard accept its handle.
    standard: Standard,
    /// The importer's logger, for reporting nested calls without touching `instance`.
    sink: Option<Box<dyn LogSink>>,
    instance: UnsafeCell<Instance>,
}

impl Component {
    /// Report `message` through the importer's logger without touching the instance (a
    /// logger that calls back on every message does not recurse: a report during a report
    /// is dropped).
    fn report(&self, message: &str) {
        if self.reporting.swap(true, Ordering::Acquire) {
            return;
        }
        if let Some(sink) = &self.sink {
            let _ = guard::catch(AssertUnwindSafe(|| {
                sink.emit(Status::Error, "logStatusError", message);
            }));
        }
        self.reporting.store(false, Ordering::Release);
    }

    /// Report a call that arrived while another call on this instance was running.
    fn report_busy(&self, name: &str) {
        self.report(&format!(
            "{name}: illegal call while another call on this instance is in progress (a re-entrant call from a callback, or concurrent calls from two threads); nothing was done"
        ));
    }

    /// Report a call of one standard's function with an instance of the other standard.
    fn report_other_standard(&self, name: &str, called_as: Standard) {
        self.report(&format!(
            "{name}: the handle is an {} instance (created by {}), not an {} one: allowed an instance created by {}; nothing was done",
            self.standard.interface().name,
            instantiate_name(self.standard),
            called_as.interface().name,
            instantiate_name(called_as),
        ));
    }
}

/// The live components, by the handle given to the importer (FMI 2.0 and FMI 3.0 alike).
///
/// A handle is an opaque number, never dereferenced and never reused: every entry point looks
/// it up here, so a freed handle (a second `fmi2FreeInstance`, a call after it) or a foreign
/// pointer gets `fmi2Error` / `fmi3Error` (or nothing, for a free) instead of undefined
/// behaviour. The component stays in its box while it is registered; a call marks it busy
/// under the registry's lock, and a free removes it only when it is not busy, so no call ever
/// holds a component that is being freed.
struct Registry {
    next: usize,
    live: BTreeMap<usize, Registered>,
}

/// A registered component. The registry only moves the box between threads; the instance in
/// it is used only by the call that set its busy flag.
struct Registered(Box<Component>);

// SAFETY: see `Registered`: the component is reached only through `dispatch` and `free`, which
// serialize every use of its instance with the busy flag (set under the registry's lock); the
// logger callbacks it holds are the importer's, which FMI lets any thread call for its instance.
unsafe impl Send for Registered {}

static REGISTRY: Mutex<Registry> = Mutex::new(Registry {
    next: 0,
    live: BTreeMap::new(),
});

/// The registry, also after a panic elsewhere while it was locked (it holds no invariant a
/// panic can break: every change is one insert or one remove).
fn registry() -> MutexGuard<'static, Registry> {
    REGISTRY
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Handles are multiples of 16 from 16 on (they look like aligned pointers to a host that
/// prints them), never NULL and never reused.
const HANDLE_STRIDE: usize = 16;

fn register(component: Component) -> fmi2Component {
    let mut registry = registry();
    registry.next += 1;
    let handle = registry.next.wrapping_mul(HANDLE_STRIDE);
    registry
        .live
        .insert(handle, Registered(Box::new(component)));
    handle as fmi2Component
}

/// Why a handle cannot be used by a call.
enum Refused {
    /// Not a live handle (NULL, freed, foreign).
    Unknown,
    /// A live component with a call running on it (a nested or concurrent call).
    Busy(*const Component),
    /// A live component of the other standard, marked busy by this call (so that it is not
    /// freed while the refusal is reported); the caller clears the flag.
    OtherStandard(*const Component),
}

/// The registered component of handle `c`, marked busy, if it is an instance of `standard`.
fn acquire(standard: Standard, c: fmi2Component) -> Result<*const Component, Refused> {
    let registry = registry();
    let Some(Registered(component)) = registry.live.get(&(c as usize)) else {
        return Err(Refused::Unknown);
    };
    let component: *const Component = &**component;
    // SAFETY: registered, and it cannot be freed while the lock is held.
    let registered = unsafe { &*component };
    if registered.busy.swap(true, Ordering::Acquire) {
        return Err(Refused::Busy(component));
    }
    if registered.standard != standard {
        return Err(Refused::OtherStandard(component));
    }
    Ok(component)
}

/// Clears the busy flag when the call ends (also if it unwinds).
struct Busy<'a>(&'a AtomicBool);

impl Drop for Busy<'_> {
    fn drop(&mut self) {
        self.0.store(false, Ordering::Release);
    }
}

/// Run `f` on the instance `c` as FMI call `call` of `standard` (the standard of the calling
/// function: a handle of the other standard is refused without touching its instance).
pub unsafe fn dispatch(
    standard: Standard,
    c: fmi2Component,
    call: Call,
    f: impl FnOnce(&mut Instance) -> FmiResult<Status>,
) -> fmi2Status {
    let component = match acquire(standard, c) {
        Ok(component) => component,
        Err(Refused::Unknown) => return ERROR,
        Err(Refused::Busy(busy)) => {
            // SAFETY: registered and busy: the running call keeps it from being freed. Only a
            // shared reference is made: that call may hold one at the same time.
            let component = unsafe { &*busy };
            component.report_busy(call.name(standard));
            return ERROR;
        }
        Err(Refused::OtherStandard(other)) => {
            // SAFETY: registered and marked busy by this call, so `free` leaves it alone until
            // the flag is cleared (when `_busy` drops); the instance is not touched.
            let component = unsafe { &*other };
            let _busy = Busy(&component.busy);
            component.report_other_standard(call.name(standard), standard);
            return ERROR;
        }
    };
    // SAFETY: registered and marked busy by this call, so `free` leaves it alone until the
    // flag is cleared (when `_busy` drops, after the last use of `instance`).
    let component = unsafe { &*component };
    let _busy = Busy(&component.busy);
    let instance = unsafe { &mut *component.instance.get() };
    match guard::catch(AssertUnwindSafe(|| instance.run(call, f).code())) {
        Ok(code) => code,
        Err(_) => {
            instance.enter_error_state();
            ERROR
        }
    }
}

/// The C arguments of an instantiation, common to `fmi2Instantiate` and
/// `fmi3InstantiateCoSimulation`.
pub struct CreateArgs {
    pub standard: Standard,
    pub instance_name: fmi2String,
    /// `fmuType` (FMI 2.0) or [`FMI2_CO_SIMULATION`] (FMI 3.0).
    pub fmu_type: c_int,
    /// `fmuGUID` (FMI 2.0) or `instantiationToken` (FMI 3.0).
    pub token: fmi2String,
    /// `fmuResourceLocation` (FMI 2.0) or `resourcePath` (FMI 3.0).
    pub resource_location: fmi2String,
    pub logging_on: bool,
}

/// A new component, or NULL (the reason goes to the logger). `make_sink(instance name)`
/// wraps the importer's logger callback, if it gave one.
pub unsafe fn create(
    args: CreateArgs,
    make_sink: impl Fn(&str) -> Option<Box<dyn LogSink>>,
) -> fmi2Component {
    let standard = args.standard;
    let (token_name, location_name) = match standard {
        Standard::Fmi2 => ("fmuGUID", "fmuResourceLocation"),
        Standard::Fmi3 => ("instantiationToken", "resourcePath"),
    };
    let created = guard::catch(AssertUnwindSafe(|| {
        // SAFETY (all three): NULL or NUL-terminated strings (FMI 2.0, FMI 3.0).
        let name = unsafe { lossy_text(args.instance_name) };
        let guid = unsafe { text(args.token, token_name) };
        let location = unsafe { text(args.resource_location, location_name) };
        let sink_name = name.as_deref().unwrap_or("");
        let logger = Logger::new(make_sink(sink_name), args.logging_on);
        let instantiate_args = match (&name, guid, location) {
            (Some(instance_name), Ok(Some(guid)), Ok(resource_location)) => InstantiateArgs {
                standard,
                instance_name,
                fmu_type: args.fmu_type,
                guid,
                resource_location,
            },
            (name, guid, location) => {
                let problem = if name.is_none() {
                    "instanceName is NULL".to_string()
                } else {
                    match guid {
                        Ok(None) => format!("{token_name} is NULL"),
                        Err(e) => e,
                        Ok(Some(_)) => location.err().unwrap_or_default(),
                    }
                };
                logger.status(
                    Status::Error,
                    &format!("{}: {problem}", instantiate_name(standard)),
                );
                return None;
            }
        };
        let instance = Instance::instantiate(instantiate_args, logger)?;
        Some(Component {
            busy: AtomicBool::new(false),
            reporting: AtomicBool::new(false),
            standard,
            sink: make_sink(sink_name),
            instance: UnsafeCell::new(instance),
        })
    }));
    match created {
        Ok(Some(component)) => register(component),
        _ => ptr::null_mut(),
    }
}

/// `fmi2Instantiate`: a new component, or NULL (the reason goes to the logger).
pub unsafe fn instantiate(
    instanceName: fmi2String,
    fmuType: c_int,
    fmuGUID: fmi2String,
    fmuResourceLocation: fmi2String,
    functions: *const fmi2CallbackFunctions,
    loggingOn: fmi2Boolean,
) -> fmi2Component {
    // SAFETY: NULL or the importer's callback struct (FMI 2.0).
    let Ok(Some(functions)) = guard::catch(AssertUnwindSafe(|| unsafe { functions.as_ref() }))
    else {
        return ptr::null_mut();
    };
    let (logger, environment) = (functions.logger, functions.component_environment);
    let args = CreateArgs {
        standard: Standard::Fmi2,
        instance_name: instanceName,
        fmu_type: fmuType,
        token: fmuGUID,
        resource_location: fmuResourceLocation,
        logging_on: loggingOn != 0,
    };
    // SAFETY: the strings are NULL or NUL-terminated (FMI 2.0).
    unsafe {
        create(args, |name| {
            logger.map(|callback| {
                Box::new(CallbackSink {
                    callback,
                    environment,
                    instance_name: c_string(name),
                }) as Box<dyn LogSink>
            })
        })
    }
}

/// `fmi2FreeInstance` and `fmi3FreeInstance` (`standard` the one of the calling function). A
/// handle that is not live (NULL, freed already, foreign) is ignored; a component with a call
/// running (freed from inside a callback) or of the other standard is refused with a message.
pub unsafe fn free(standard: Standard, c: fmi2Component) {
    let name = match standard {
        Standard::Fmi2 => "fmi2FreeInstance",
        Standard::Fmi3 => "fmi3FreeInstance",
    };
    let removed = {
        let mut registry = registry();
        let handle = c as usize;
        match registry.live.get(&handle) {
            None => return,
            Some(Registered(component)) if component.busy.load(Ordering::Acquire) => {
                let component: *const Component = &**component;
                Err(Refused::Busy(component))
            }
            Some(Registered(component)) if component.standard != standard => {
                let component: *const Component = &**component;
                // SAFETY: registered, and it cannot be freed while the lock is held; marked
                // busy here so that it stays registered while the refusal is reported.
                unsafe { &*component }.busy.store(true, Ordering::Release);
                Err(Refused::OtherStandard(component))
            }
            Some(_) => Ok(registry.live.remove(&handle)),
        }
    };
    match removed {
        Err(Refused::Busy(busy)) => {
            // SAFETY: registered and busy: the running call keeps it from being freed.
            let component = unsafe { &*busy };
            component.report_busy(name);
        }
        Err(Refused::OtherStandard(other)) => {
            // SAFETY: registered and marked busy above; the flag is cleared when `_busy` drops.
            let component = unsafe { &*other };
            let _busy = Busy(&component.busy);
            component.report_other_standard(name, standard);
        }
        Err(Refused::Unknown) => {}
        Ok(component) => {
            // Dropped outside the registry's lock (the instance's drop may log).
            let _ = guard::catch(AssertUnwindSafe(move || drop(component)));
        }
    }
}
