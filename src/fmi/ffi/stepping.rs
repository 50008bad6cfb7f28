//! Co-simulation: input and output derivatives, directional derivatives (not provided),
//! `fmi2DoStep`, `fmi2CancelStep` and the status queries (FMI 2.0, 2.1.9 and 4.2.2 to 4.2.4).

use std::ffi::c_int;

use super::component::dispatch;
use super::convert::{answer, out, slice};
use super::{
    fmi2Boolean, fmi2Component, fmi2Integer, fmi2Real, fmi2Status, fmi2String, fmi2ValueReference,
};
use crate::fmi::standard::Standard;
use crate::fmi::state_machine::Call;
use crate::fmi::status::{Status, StatusKind};

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
        dispatch(Standard::Fmi2, c, Call::GetDirectionalDerivative, |i| {
            i.get_directional_derivative()
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    order: *const fmi2Integer,
    value: *const fmi2Real,
) -> fmi2Status {
    unsafe {
        dispatch(Standard::Fmi2, c, Call::SetRealInputDerivatives, |i| {
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
        dispatch(Standard::Fmi2, c, Call::GetRealOutputDerivatives, |i| {
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
        dispatch(Standard::Fmi2, c, Call::DoStep, |i| {
            i.do_step(currentCommunicationPoint, communicationStepSize)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2CancelStep(c: fmi2Component) -> fmi2Status {
    // Always rejected by the call sequence: no step is ever in progress.
    unsafe { dispatch(Standard::Fmi2, c, Call::CancelStep, |_| Ok(Status::Ok)) }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2GetStatus(
    c: fmi2Component,
    s: c_int,
    value: *mut fmi2Status,
) -> fmi2Status {
    unsafe {
        dispatch(Standard::Fmi2, c, Call::GetStatus, |i| {
            answer(value, "value", || {
                Ok(i.get_status(StatusKind::from_code(s)?)?.code())
            })
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
        dispatch(Standard::Fmi2, c, Call::GetRealStatus, |i| {
            answer(value, "value", || {
                i.get_real_status(StatusKind::from_code(s)?)
            })
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
        dispatch(Standard::Fmi2, c, Call::GetIntegerStatus, |i| {
            answer(value, "value", || {
                i.get_integer_status(StatusKind::from_code(s)?)
            })
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
        dispatch(Standard::Fmi2, c, Call::GetBooleanStatus, |i| {
            answer(value, "value", || {
                Ok(fmi2Boolean::from(
                    i.get_boolean_status(StatusKind::from_code(s)?)?,
                ))
            })
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
        dispatch(Standard::Fmi2, c, Call::GetStringStatus, |i| {
            out(value, "value")?;
            i.get_string_status(StatusKind::from_code(s)?)
        })
    }
}
