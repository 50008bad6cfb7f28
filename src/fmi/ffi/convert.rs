//! C arguments to Rust: arrays to slices (NULL allowed only for length 0), output pointers,
//! strings, and FMU state handles. All `unsafe` here relies on the FMI 2.0 contract that
//! pointers are NULL or valid for the lengths passed with them.

use std::borrow::Cow;
use std::ffi::{c_char, CStr};
use std::ptr;

use super::{fmi2FMUstate, fmi2String};
use crate::fmi::status::{FmiError, FmiResult, Status};

/// `&[T]` from a C array; NULL is allowed only for n = 0.
pub unsafe fn slice<'a, T>(p: *const T, n: usize, what: &str) -> FmiResult<&'a [T]> {
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
pub unsafe fn slice_mut<'a, T>(p: *mut T, n: usize, what: &str) -> FmiResult<&'a mut [T]> {
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
pub unsafe fn out<'a, T>(p: *mut T, what: &str) -> FmiResult<&'a mut T> {
    // SAFETY: the caller guarantees p is NULL or points to a writable T.
    unsafe { p.as_mut() }.ok_or_else(|| FmiError::rejected(format!("{what} is NULL")))
}

/// Text from a C string, invalid UTF-8 replaced by U+FFFD; `None` for NULL.
pub unsafe fn lossy_text<'a>(p: *const c_char) -> Option<Cow<'a, str>> {
    if p.is_null() {
        return None;
    }
    // SAFETY: non-null, and the caller guarantees a NUL-terminated string.
    Some(unsafe { CStr::from_ptr(p) }.to_string_lossy())
}

/// `&str` from a C string; `None` for NULL.
pub unsafe fn text<'a>(p: *const c_char, what: &str) -> Result<Option<&'a str>, String> {
    if p.is_null() {
        return Ok(None);
    }
    // SAFETY: non-null, and the caller guarantees a NUL-terminated string.
    let s = unsafe { CStr::from_ptr(p) };
    s.to_str()
        .map(Some)
        .map_err(|_| format!("{what} is not valid UTF-8"))
}

pub fn handle_of(state: fmi2FMUstate) -> Option<usize> {
    (!state.is_null()).then(|| state.addr())
}

pub fn state_of(handle: usize) -> fmi2FMUstate {
    ptr::without_provenance_mut(handle)
}

/// The strings of a C array of `n` strings; NULL entries are errors.
pub unsafe fn strings<'a>(
    p: *const fmi2String,
    n: usize,
    what: &str,
) -> FmiResult<Vec<Cow<'a, str>>> {
    // SAFETY: the caller guarantees n readable pointers (FMI 2.0).
    let pointers = unsafe { slice(p, n, &format!("{what}[]")) }?;
    let mut texts = Vec::with_capacity(pointers.len());
    for (k, &p) in pointers.iter().enumerate() {
        // SAFETY: each entry is NULL or a NUL-terminated string (FMI 2.0).
        match unsafe { lossy_text(p) } {
            Some(text) => texts.push(text),
            None => return Err(FmiError::rejected(format!("{what}[{k}] is NULL"))),
        }
    }
    Ok(texts)
}

/// The handle of a state passed by value; NULL is an error.
pub fn handle(state: fmi2FMUstate) -> FmiResult<usize> {
    handle_of(state).ok_or_else(|| FmiError::rejected("FMUstate is NULL"))
}

/// `*slot = f(handle in *slot)`: for the calls that hand out a state (`fmi2GetFMUstate`,
/// `fmi2DeSerializeFMUstate`), which may overwrite the state behind the handle passed in.
pub unsafe fn store_handle(
    slot: *mut fmi2FMUstate,
    f: impl FnOnce(Option<usize>) -> FmiResult<usize>,
) -> FmiResult<Status> {
    // SAFETY: the caller guarantees slot is NULL or writable.
    let slot = unsafe { out(slot, "FMUstate") }?;
    *slot = state_of(f(handle_of(*slot))?);
    Ok(Status::Ok)
}

/// `fmi2FreeFMUstate`: `f(handle in *slot)` and `*slot = NULL`; a NULL handle does nothing.
pub unsafe fn clear_handle(
    slot: *mut fmi2FMUstate,
    f: impl FnOnce(usize) -> FmiResult<Status>,
) -> FmiResult<Status> {
    // SAFETY: the caller guarantees slot is NULL or writable.
    let slot = unsafe { out(slot, "FMUstate") }?;
    if let Some(handle) = handle_of(*slot) {
        f(handle)?;
        *slot = ptr::null_mut();
    }
    Ok(Status::Ok)
}

/// `*p = f()` for the status queries and sizes; a NULL `p` is an error before `f` runs.
pub unsafe fn answer<T>(
    p: *mut T,
    what: &str,
    f: impl FnOnce() -> FmiResult<T>,
) -> FmiResult<Status> {
    // SAFETY: the caller guarantees p is NULL or writable.
    let value = unsafe { out(p, what) }?;
    *value = f()?;
    Ok(Status::Ok)
}
