//! Inquire platform, creation and destruction, initialization (FMI 2.0, 2.1.4 to 2.1.6 and
//! 4.2.1).

use std::ffi::{c_char, c_int};

use super::component::{self, dispatch};
use super::convert::strings;
use super::{fmi2Boolean, fmi2CallbackFunctions, fmi2Component, fmi2Real, fmi2Status, fmi2String};
use crate::fmi::instance::Instance;
use crate::fmi::standard::Standard;
use crate::fmi::state_machine::Call;

#[no_mangle]
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    c"default".as_ptr()
}

#[no_mangle]
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    c"2.0".as_ptr()
}

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
    unsafe {
        component::instantiate(
            instanceName,
            fmuType,
            fmuGUID,
            fmuResourceLocation,
            functions,
            loggingOn,
        )
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2FreeInstance(c: fmi2Component) {
    unsafe { component::free(Standard::Fmi2, c) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetDebugLogging(
    c: fmi2Component,
    loggingOn: fmi2Boolean,
    nCategories: usize,
    categories: *const fmi2String,
) -> fmi2Status {
    unsafe {
        dispatch(Standard::Fmi2, c, Call::SetDebugLogging, |i| {
            i.set_debug_logging(
                loggingOn != 0,
                &strings(categories, nCategories, "categories")?,
            )
        })
    }
}

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
        dispatch(Standard::Fmi2, c, Call::SetupExperiment, |i| {
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
            Standard::Fmi2,
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
            Standard::Fmi2,
            c,
            Call::ExitInitializationMode,
            Instance::exit_initialization_mode,
        )
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2Terminate(c: fmi2Component) -> fmi2Status {
    unsafe { dispatch(Standard::Fmi2, c, Call::Terminate, Instance::terminate) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2Reset(c: fmi2Component) -> fmi2Status {
    unsafe { dispatch(Standard::Fmi2, c, Call::Reset, Instance::reset) }
}
