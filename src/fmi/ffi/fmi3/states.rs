//! FMU states: get, set, free, serialize and deserialize (FMI 3.0, 2.3.8), the same instance
//! methods as FMI 2.0's. Handles are opaque integers looked up per instance.

use super::super::component::dispatch;
use super::super::convert::{answer, clear_handle, handle, slice, slice_mut, store_handle};
use super::{fmi3Byte, fmi3FMUState, fmi3Instance, fmi3Status};
use crate::fmi::standard::Standard;
use crate::fmi::state_machine::Call;

#[no_mangle]
pub unsafe extern "C" fn fmi3GetFMUState(
    instance: fmi3Instance,
    FMUState: *mut fmi3FMUState,
) -> fmi3Status {
    unsafe {
        dispatch(Standard::Fmi3, instance, Call::GetFMUstate, |i| {
            store_handle(FMUState, |existing| i.get_fmu_state(existing))
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetFMUState(
    instance: fmi3Instance,
    FMUState: fmi3FMUState,
) -> fmi3Status {
    unsafe {
        dispatch(Standard::Fmi3, instance, Call::SetFMUstate, |i| {
            i.set_fmu_state(handle(FMUState)?)
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3FreeFMUState(
    instance: fmi3Instance,
    FMUState: *mut fmi3FMUState,
) -> fmi3Status {
    unsafe {
        dispatch(Standard::Fmi3, instance, Call::FreeFMUstate, |i| {
            clear_handle(FMUState, |h| i.free_fmu_state(h))
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SerializedFMUStateSize(
    instance: fmi3Instance,
    FMUState: fmi3FMUState,
    size: *mut usize,
) -> fmi3Status {
    unsafe {
        dispatch(
            Standard::Fmi3,
            instance,
            Call::SerializedFMUstateSize,
            |i| answer(size, "size", || i.serialized_size(handle(FMUState)?)),
        )
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SerializeFMUState(
    instance: fmi3Instance,
    FMUState: fmi3FMUState,
    serializedState: *mut fmi3Byte,
    size: usize,
) -> fmi3Status {
    unsafe {
        dispatch(Standard::Fmi3, instance, Call::SerializeFMUstate, |i| {
            i.serialize_fmu_state(
                handle(FMUState)?,
                slice_mut(serializedState, size, "serializedState[]")?,
            )
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3DeserializeFMUState(
    instance: fmi3Instance,
    serializedState: *const fmi3Byte,
    size: usize,
    FMUState: *mut fmi3FMUState,
) -> fmi3Status {
    unsafe {
        dispatch(Standard::Fmi3, instance, Call::DeSerializeFMUstate, |i| {
            let bytes = slice(serializedState, size, "serializedState[]")?;
            store_handle(FMUState, |existing| {
                i.deserialize_fmu_state(bytes, existing)
            })
        })
    }
}
