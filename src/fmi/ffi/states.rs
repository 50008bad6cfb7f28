//! FMU states: get, set, free, serialize and deserialize (FMI 2.0, 2.1.8). Handles are opaque
//! integers looked up per instance ([`super::convert::handle`]).

use super::component::dispatch;
use super::convert::{answer, clear_handle, handle, slice, slice_mut, store_handle};
use super::{fmi2Byte, fmi2Component, fmi2FMUstate, fmi2Status};
use crate::fmi::standard::Standard;
use crate::fmi::state_machine::Call;

#[no_mangle]
pub unsafe extern "C" fn fmi2GetFMUstate(
    c: fmi2Component,
    FMUstate: *mut fmi2FMUstate,
) -> fmi2Status {
    unsafe {
        dispatch(Standard::Fmi2, c, Call::GetFMUstate, |i| {
            store_handle(FMUstate, |existing| i.get_fmu_state(existing))
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2SetFMUstate(c: fmi2Component, FMUstate: fmi2FMUstate) -> fmi2Status {
    unsafe {
        dispatch(Standard::Fmi2, c, Call::SetFMUstate, |i| {
            i.set_fmu_state(handle(FMUstate)?)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi2FreeFMUstate(
    c: fmi2Component,
    FMUstate: *mut fmi2FMUstate,
) -> fmi2Status {
    unsafe {
        dispatch(Standard::Fmi2, c, Call::FreeFMUstate, |i| {
            clear_handle(FMUstate, |h| i.free_fmu_state(h))
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
        dispatch(Standard::Fmi2, c, Call::SerializedFMUstateSize, |i| {
            answer(size, "size", || i.serialized_size(handle(FMUstate)?))
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
        dispatch(Standard::Fmi2, c, Call::SerializeFMUstate, |i| {
            i.serialize_fmu_state(
                handle(FMUstate)?,
                slice_mut(serializedState.cast::<u8>(), size, "serializedState[]")?,
            )
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
        dispatch(Standard::Fmi2, c, Call::DeSerializeFMUstate, |i| {
            let bytes = slice(serializedState.cast::<u8>(), size, "serializedState[]")?;
            store_handle(FMUstate, |existing| {
                i.deserialize_fmu_state(bytes, existing)
            })
        })
    }
}
