//! Getting and setting variable values (FMI 3.0, 2.3.7): `Float64` (Real variables, arrays
//! included), `Int32` (Integer variables), `Int64` (Enumerations, as FMI 3.0 prescribes),
//! and the other types, of which this FMU has no variable: those check their arguments and
//! reject every value reference. `nValues` counts array elements.

use std::ffi::c_void;

use super::super::component::dispatch;
use super::super::convert::{slice, slice_mut};
use super::{fmi3Float64, fmi3Instance, fmi3Int32, fmi3Int64, fmi3Status, fmi3ValueReference};
use crate::fmi::standard::Standard;
use crate::fmi::state_machine::Call;
use crate::fmi::variables::Family;

#[no_mangle]
pub unsafe extern "C" fn fmi3GetFloat64(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *mut fmi3Float64,
    nValues: usize,
) -> fmi3Status {
    unsafe {
        dispatch(Standard::Fmi3, instance, Call::GetReal, |i| {
            i.get_real(
                slice(valueReferences, nValueReferences, "valueReferences[]")?,
                slice_mut(values, nValues, "values[]")?,
            )
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetFloat64(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *const fmi3Float64,
    nValues: usize,
) -> fmi3Status {
    unsafe {
        dispatch(Standard::Fmi3, instance, Call::SetReal, |i| {
            i.set_real(
                slice(valueReferences, nValueReferences, "valueReferences[]")?,
                slice(values, nValues, "values[]")?,
            )
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3GetInt32(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *mut fmi3Int32,
    nValues: usize,
) -> fmi3Status {
    unsafe {
        dispatch(Standard::Fmi3, instance, Call::GetInteger, |i| {
            i.get_integer(
                Family::Integer,
                slice(valueReferences, nValueReferences, "valueReferences[]")?,
                slice_mut(values, nValues, "values[]")?,
            )
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetInt32(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *const fmi3Int32,
    nValues: usize,
) -> fmi3Status {
    unsafe {
        dispatch(Standard::Fmi3, instance, Call::SetInteger, |i| {
            i.set_integer(
                Family::Integer,
                slice(valueReferences, nValueReferences, "valueReferences[]")?,
                slice(values, nValues, "values[]")?,
            )
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3GetInt64(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *mut fmi3Int64,
    nValues: usize,
) -> fmi3Status {
    unsafe {
        dispatch(Standard::Fmi3, instance, Call::GetInt64, |i| {
            i.get_integer(
                Family::Enumeration,
                slice(valueReferences, nValueReferences, "valueReferences[]")?,
                slice_mut(values, nValues, "values[]")?,
            )
        })
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetInt64(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *const fmi3Int64,
    nValues: usize,
) -> fmi3Status {
    unsafe {
        dispatch(Standard::Fmi3, instance, Call::SetInt64, |i| {
            i.set_integer(
                Family::Enumeration,
                slice(valueReferences, nValueReferences, "valueReferences[]")?,
                slice(values, nValues, "values[]")?,
            )
        })
    }
}

/// Get and set functions of the types this FMU has no variable of: the arrays are checked
/// (NULL only with length 0), then every value reference is rejected as unknown or of
/// another type. The value type does not matter for the check, so `c_void` stands for it.
macro_rules! no_variables {
    ($($get:ident, $set:ident, $ty:literal;)+) => {$(
        #[no_mangle]
        pub unsafe extern "C" fn $get(
            instance: fmi3Instance,
            valueReferences: *const fmi3ValueReference,
            nValueReferences: usize,
            values: *mut c_void,
            nValues: usize,
        ) -> fmi3Status {
            unsafe {
                dispatch(Standard::Fmi3, instance, Call::GetOther(stringify!($get)), |i| {
                    slice_mut(values.cast::<u8>(), nValues, "values[]")?;
                    i.no_variables_of(
                        Family::Other($ty),
                        slice(valueReferences, nValueReferences, "valueReferences[]")?,
                    )
                })
            }
        }

        #[no_mangle]
        pub unsafe extern "C" fn $set(
            instance: fmi3Instance,
            valueReferences: *const fmi3ValueReference,
            nValueReferences: usize,
            values: *const c_void,
            nValues: usize,
        ) -> fmi3Status {
            unsafe {
                dispatch(Standard::Fmi3, instance, Call::SetOther(stringify!($set)), |i| {
                    slice(values.cast::<u8>(), nValues, "values[]")?;
                    i.no_variables_of(
                        Family::Other($ty),
                        slice(valueReferences, nValueReferences, "valueReferences[]")?,
                    )
                })
            }
        }
    )+};
}

no_variables! {
    fmi3GetFloat32, fmi3SetFloat32, "Float32";
    fmi3GetInt8, fmi3SetInt8, "Int8";
    fmi3GetUInt8, fmi3SetUInt8, "UInt8";
    fmi3GetInt16, fmi3SetInt16, "Int16";
    fmi3GetUInt16, fmi3SetUInt16, "UInt16";
    fmi3GetUInt32, fmi3SetUInt32, "UInt32";
    fmi3GetUInt64, fmi3SetUInt64, "UInt64";
    fmi3GetBoolean, fmi3SetBoolean, "Boolean";
    fmi3GetString, fmi3SetString, "String";
}

#[no_mangle]
pub unsafe extern "C" fn fmi3GetBinary(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    valueSizes: *mut usize,
    values: *mut *const u8,
    nValues: usize,
) -> fmi3Status {
    unsafe {
        dispatch(
            Standard::Fmi3,
            instance,
            Call::GetOther("fmi3GetBinary"),
            |i| {
                slice_mut(valueSizes, nValues, "valueSizes[]")?;
                slice_mut(values, nValues, "values[]")?;
                i.no_variables_of(
                    Family::Other("Binary"),
                    slice(valueReferences, nValueReferences, "valueReferences[]")?,
                )
            },
        )
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetBinary(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    valueSizes: *const usize,
    values: *const *const u8,
    nValues: usize,
) -> fmi3Status {
    unsafe {
        dispatch(
            Standard::Fmi3,
            instance,
            Call::SetOther("fmi3SetBinary"),
            |i| {
                slice(valueSizes, nValues, "valueSizes[]")?;
                slice(values, nValues, "values[]")?;
                i.no_variables_of(
                    Family::Other("Binary"),
                    slice(valueReferences, nValueReferences, "valueReferences[]")?,
                )
            },
        )
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3GetClock(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *mut bool,
) -> fmi3Status {
    unsafe {
        dispatch(
            Standard::Fmi3,
            instance,
            Call::GetOther("fmi3GetClock"),
            |i| {
                slice_mut(values, nValueReferences, "values[]")?;
                i.no_variables_of(
                    Family::Other("Clock"),
                    slice(valueReferences, nValueReferences, "valueReferences[]")?,
                )
            },
        )
    }
}

#[no_mangle]
pub unsafe extern "C" fn fmi3SetClock(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *const bool,
) -> fmi3Status {
    unsafe {
        dispatch(
            Standard::Fmi3,
            instance,
            Call::SetOther("fmi3SetClock"),
            |i| {
                slice(values, nValueReferences, "values[]")?;
                i.no_variables_of(
                    Family::Other("Clock"),
                    slice(valueReferences, nValueReferences, "valueReferences[]")?,
                )
            },
        )
    }
}
