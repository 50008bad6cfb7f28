//! Getting and setting variable values (FMI 2.0, 2.1.7). This FMU has no Boolean and no
//! String variables: those calls check their arguments and reject every value reference.

use super::component::dispatch;
use super::convert::{slice, slice_mut};
use super::{
    fmi2Boolean, fmi2Component, fmi2Integer, fmi2Real, fmi2Status, fmi2String, fmi2ValueReference,
};
use crate::fmi::standard::Standard;
use crate::fmi::state_machine::Call;
use crate::fmi::variables::Family;

#[no_mangle]
pub unsafe extern "C" fn fmi2GetReal(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Real,
) -> fmi2Status {
    unsafe {
        dispatch(Standard::Fmi2, c, Call::GetReal, |i| {
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
        dispatch(Standard::Fmi2, c, Call::GetInteger, |i| {
            i.get_integer(
                Family::Integer,
                slice(vr, nvr, "vr[]")?,
                slice_mut(value, nvr, "value[]")?,
            )
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
        dispatch(Standard::Fmi2, c, Call::GetBoolean, |i| {
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
        dispatch(Standard::Fmi2, c, Call::GetString, |i| {
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
        dispatch(Standard::Fmi2, c, Call::SetReal, |i| {
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
        dispatch(Standard::Fmi2, c, Call::SetInteger, |i| {
            i.set_integer(
                Family::Integer,
                slice(vr, nvr, "vr[]")?,
                slice(value, nvr, "value[]")?,
            )
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
        dispatch(Standard::Fmi2, c, Call::SetBoolean, |i| {
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
        dispatch(Standard::Fmi2, c, Call::SetString, |i| {
            slice(value, nvr, "value[]")?;
            i.no_variables_of(Family::String, slice(vr, nvr, "vr[]")?)
        })
    }
}
