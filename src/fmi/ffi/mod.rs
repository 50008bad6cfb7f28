//! The C ABI: the 34 functions of FMI 2.0 Co-Simulation, the `fmi3*` functions ([`fmi3`]),
//! and all `unsafe` code of the FMI layer.
//!
//! Every function is a one-line delegation: convert the C arguments (null checks, slices,
//! strings; [`convert`]) and call one method of the safe [`Instance`] through
//! [`Instance::run`] ([`component::dispatch`]), which checks the call sequence, catches
//! panics, logs failures and folds the status. An outer [`guard::catch`] makes sure no panic
//! (not even one while logging) unwinds into the host.
//!
//! The safety contract of each function is the FMI 2.0 standard's for arrays (the lengths
//! passed with them) and strings (NUL-terminated); NULL pointers are detected and reported.
//! An `fmi2Component` / `fmi3Instance` is an opaque handle, never dereferenced: it is looked up
//! in a registry of the live instances ([`component`]), so a freed, foreign or NULL handle
//! gives an error (a free of one does nothing) rather than undefined behaviour.
//!
//! FMU state handles are opaque integers (never dereferenced), looked up per instance, so a
//! stale or foreign handle gives an error (or a new handle where FMI allows one), not
//! undefined behaviour.
//!
//! Re-entrancy: an `fmi2Component` points to a [`component::Component`], which holds the
//! [`Instance`] in an `UnsafeCell` behind a busy flag. `&mut Instance` is created only by the
//! call that set the flag, so a logger callback that calls back into the same instance (or a
//! second thread calling it concurrently) never aliases it: such a nested call returns
//! `fmi2Error` and is reported through the logger.
//!
//! FMI 3.0: [`fmi3`], the `fmi3*` functions in the same library, delegating to the same
//! instance code through the same [`component::dispatch`].
//!
//! Files: [`component`] (what `fmi2Component` points to, the logger callback, dispatch),
//! [`convert`] (C arguments to Rust), and the exported functions grouped as in the standard:
//! [`lifecycle`] (platform, creation, initialization), [`values`] (get and set), [`states`]
//! (FMU states), [`stepping`] (derivatives, `fmi2DoStep`, status).
//!
//! [`Instance`]: super::Instance
//! [`Instance::run`]: super::Instance::run
//! [`guard::catch`]: super::guard::catch

#![allow(non_snake_case, non_camel_case_types)]
#![allow(clippy::missing_safety_doc)]
#![deny(unsafe_op_in_unsafe_fn)]

pub mod component;
pub mod convert;
pub mod fmi3;
pub mod lifecycle;
pub mod states;
pub mod stepping;
pub mod values;

use std::ffi::{c_char, c_int, c_uint, c_void};

pub use lifecycle::*;
pub use states::*;
pub use stepping::*;
pub use values::*;

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
