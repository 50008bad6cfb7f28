//! Inquire version, creation and destruction, initialization, and the modes this FMU does
//! not have (FMI 3.0, 2.3.1 to 2.3.6).

use std::ffi::{c_char, CString};
use std::panic::AssertUnwindSafe;
use std::ptr;

use super::super::component::{self, dispatch, CreateArgs};
use super::super::convert::strings;
use super::{
    fmi3Boolean, fmi3Float64, fmi3Instance, fmi3InstanceEnvironment,
    fmi3IntermediateUpdateCallback, fmi3LogMessageCallback, fmi3Status, fmi3String,
    fmi3ValueReference,
};
use crate::fmi::guard;
use crate::fmi::instance::{Instance, FMI2_CO_SIMULATION};
use crate::fmi::logging::LogSink;
use crate::fmi::standard::Standard;
use crate::fmi::state_machine::Call;
use crate::fmi::status::{FmiError, Status};

/// The importer's FMI 3.0 logger callback.
pub(super) struct Fmi3Sink {
    callback: fmi3LogMessageCallback,
    environment: fmi3InstanceEnvironment,
}

impl LogSink for Fmi3Sink {
    fn emit(&self, status: Status, category: &'static str, message: &str) {
        let message = CString::new(message.replace('\0', " ")).unwrap_or_default();
        let category = CString::new(category).unwrap_or_default();
        // SAFETY: the callback comes from the importer's fmi3InstantiateCoSimulation; both
        // strings are valid NUL-terminated strings that outlive the call (FMI 3.0: the
        // message is plain text, not a format).
        unsafe {
            (self.callback)(
                self.environment,
                status.code(),
                category.as_ptr(),
                message.as_ptr(),
            );
        }
    }
}

/// Log `message` as an error through a callback, for calls that never create an instance.
fn log_error(logger: Option<fmi3LogMessageCallback>, env: fmi3InstanceEnvironment, text: &str) {
    if let Some(callback) = logger {
        let sink = Fmi3Sink {
            callback,
            environment: env,
        };
        let _ = guard::catch(AssertUnwindSafe(|| {
            sink.emit(Status::Error, "logStatusError", text)
        }));
    }
}

#[no_mangle]
pub extern "C" fn fmi3GetVersion() -> *const c_char {
    c"3.0".as_ptr()
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetDebugLogging(
    instance: fmi3Instance,
    loggingOn: fmi3Boolean,
    nCategories: usize,
    categories: *const fmi3String,
) -> fmi3Status {
    unsafe {
        dispatch(Standard::Fmi3, instance, Call::SetDebugLogging, |i| {
            i.set_debug_logging(loggingOn, &strings(categories, nCategories, "categories")?)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3InstantiateModelExchange(
    _instanceName: fmi3String,
    _instantiationToken: fmi3String,
    _resourcePath: fmi3String,
    _visible: fmi3Boolean,
    _loggingOn: fmi3Boolean,
    instanceEnvironment: fmi3InstanceEnvironment,
    logMessage: Option<fmi3LogMessageCallback>,
) -> fmi3Instance {
    log_error(
        logMessage,
        instanceEnvironment,
        "fmi3InstantiateModelExchange: this FMU implements only Co-Simulation (use fmi3InstantiateCoSimulation)",
    );
    ptr::null_mut()
}

#[no_mangle]
pub unsafe extern "C" fn fmi3InstantiateCoSimulation(
    instanceName: fmi3String,
    instantiationToken: fmi3String,
    resourcePath: fmi3String,
    _visible: fmi3Boolean,
    loggingOn: fmi3Boolean,
    eventModeUsed: fmi3Boolean,
    _earlyReturnAllowed: fmi3Boolean,
    _requiredIntermediateVariables: *const fmi3ValueReference,
    nRequiredIntermediateVariables: usize,
    instanceEnvironment: fmi3InstanceEnvironment,
    logMessage: Option<fmi3LogMessageCallback>,
    _intermediateUpdate: fmi3IntermediateUpdateCallback,
) -> fmi3Instance {
    let refusal = if eventModeUsed {
        Some("eventModeUsed = true is not supported: this FMU declares hasEventMode=\"false\"; allowed false")
    } else if nRequiredIntermediateVariables > 0 {
        Some("nRequiredIntermediateVariables > 0 is not supported: this FMU declares providesIntermediateUpdate=\"false\"; allowed 0")
    } else {
        None
    };
    if let Some(reason) = refusal {
        log_error(
            logMessage,
            instanceEnvironment,
            &format!("fmi3InstantiateCoSimulation: {reason}"),
        );
        return ptr::null_mut();
    }
    let args = CreateArgs {
        standard: Standard::Fmi3,
        instance_name: instanceName,
        fmu_type: FMI2_CO_SIMULATION,
        token: instantiationToken,
        resource_location: resourcePath,
        logging_on: loggingOn,
    };
    // SAFETY: the strings are NULL or NUL-terminated (FMI 3.0).
    unsafe {
        component::create(args, |_| {
            logMessage.map(|callback| {
                Box::new(Fmi3Sink {
                    callback,
                    environment: instanceEnvironment,
                }) as Box<dyn LogSink>
            })
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3InstantiateScheduledExecution(
    _instanceName: fmi3String,
    _instantiationToken: fmi3String,
    _resourcePath: fmi3String,
    _visible: fmi3Boolean,
    _loggingOn: fmi3Boolean,
    instanceEnvironment: fmi3InstanceEnvironment,
    logMessage: Option<fmi3LogMessageCallback>,
    _clockUpdate: Option<unsafe extern "C" fn(fmi3InstanceEnvironment)>,
    _lockPreemption: Option<unsafe extern "C" fn()>,
    _unlockPreemption: Option<unsafe extern "C" fn()>,
) -> fmi3Instance {
    log_error(
        logMessage,
        instanceEnvironment,
        "fmi3InstantiateScheduledExecution: this FMU implements only Co-Simulation (use fmi3InstantiateCoSimulation)",
    );
    ptr::null_mut()
}

#[no_mangle]
pub unsafe extern "C" fn fmi3FreeInstance(instance: fmi3Instance) {
    unsafe { component::free(Standard::Fmi3, instance) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3EnterInitializationMode(
    instance: fmi3Instance,
    toleranceDefined: fmi3Boolean,
    tolerance: fmi3Float64,
    startTime: fmi3Float64,
    stopTimeDefined: fmi3Boolean,
    stopTime: fmi3Float64,
) -> fmi3Status {
    unsafe {
        dispatch(
            Standard::Fmi3,
            instance,
            Call::EnterInitializationMode,
            |i| {
                i.setup_experiment(
                    toleranceDefined.then_some(tolerance),
                    startTime,
                    stopTimeDefined.then_some(stopTime),
                )?;
                i.enter_initialization_mode()
            },
        )
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3ExitInitializationMode(instance: fmi3Instance) -> fmi3Status {
    unsafe {
        dispatch(
            Standard::Fmi3,
            instance,
            Call::ExitInitializationMode,
            Instance::exit_initialization_mode,
        )
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3Terminate(instance: fmi3Instance) -> fmi3Status {
    unsafe {
        dispatch(
            Standard::Fmi3,
            instance,
            Call::Terminate,
            Instance::terminate,
        )
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3Reset(instance: fmi3Instance) -> fmi3Status {
    unsafe { dispatch(Standard::Fmi3, instance, Call::Reset, Instance::reset) }
}

/// A function of a feature the FMU does not declare: `fmi3Error` with the reason.
pub(super) unsafe fn not_provided(
    instance: fmi3Instance,
    name: &'static str,
    why: &'static str,
) -> fmi3Status {
    unsafe {
        dispatch(Standard::Fmi3, instance, Call::NotProvided(name), |_| {
            Err(FmiError::rejected(format!(
                "not provided: {why}; nothing was done"
            )))
        })
    }
}

const NO_EVENT_MODE: &str = "this FMU declares hasEventMode=\"false\" (no events, no event mode)";
const NO_CONFIGURATION: &str =
    "this FMU has no structural parameters, so there is no configuration mode";
const NO_CLOCKS: &str = "this FMU has no clocks";

#[no_mangle]
pub unsafe extern "C" fn fmi3EnterEventMode(instance: fmi3Instance) -> fmi3Status {
    unsafe { not_provided(instance, "fmi3EnterEventMode", NO_EVENT_MODE) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3EnterConfigurationMode(instance: fmi3Instance) -> fmi3Status {
    unsafe { not_provided(instance, "fmi3EnterConfigurationMode", NO_CONFIGURATION) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3ExitConfigurationMode(instance: fmi3Instance) -> fmi3Status {
    unsafe { not_provided(instance, "fmi3ExitConfigurationMode", NO_CONFIGURATION) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3EvaluateDiscreteStates(instance: fmi3Instance) -> fmi3Status {
    unsafe { not_provided(instance, "fmi3EvaluateDiscreteStates", NO_EVENT_MODE) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3UpdateDiscreteStates(
    instance: fmi3Instance,
    _discreteStatesNeedUpdate: *mut fmi3Boolean,
    _terminateSimulation: *mut fmi3Boolean,
    _nominalsOfContinuousStatesChanged: *mut fmi3Boolean,
    _valuesOfContinuousStatesChanged: *mut fmi3Boolean,
    _nextEventTimeDefined: *mut fmi3Boolean,
    _nextEventTime: *mut fmi3Float64,
) -> fmi3Status {
    unsafe { not_provided(instance, "fmi3UpdateDiscreteStates", NO_EVENT_MODE) }
}

/// The clock functions: this FMU has no clocks.
macro_rules! no_clocks {
    ($($name:ident($($arg:ident: $ty:ty),*);)+) => {$(
        #[no_mangle]
        pub unsafe extern "C" fn $name(instance: fmi3Instance, $($arg: $ty),*) -> fmi3Status {
            $(let _ = $arg;)*
            unsafe { not_provided(instance, stringify!($name), NO_CLOCKS) }
        }
    )+};
}

no_clocks! {
    fmi3GetIntervalDecimal(vr: *const fmi3ValueReference, n: usize, intervals: *mut f64, qualifiers: *mut i32);
    fmi3GetIntervalFraction(vr: *const fmi3ValueReference, n: usize, counters: *mut u64, resolutions: *mut u64, qualifiers: *mut i32);
    fmi3GetShiftDecimal(vr: *const fmi3ValueReference, n: usize, shifts: *mut f64);
    fmi3GetShiftFraction(vr: *const fmi3ValueReference, n: usize, counters: *mut u64, resolutions: *mut u64);
    fmi3SetIntervalDecimal(vr: *const fmi3ValueReference, n: usize, intervals: *const f64);
    fmi3SetIntervalFraction(vr: *const fmi3ValueReference, n: usize, counters: *const u64, resolutions: *const u64);
    fmi3SetShiftDecimal(vr: *const fmi3ValueReference, n: usize, shifts: *const f64);
    fmi3SetShiftFraction(vr: *const fmi3ValueReference, n: usize, counters: *const u64, resolutions: *const u64);
}
