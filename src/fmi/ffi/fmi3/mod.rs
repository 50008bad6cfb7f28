//! The C ABI of FMI 3.0 Co-Simulation: the `fmi3*` functions, beside the `fmi2*` ones of the
//! parent module in the same library (the names do not clash).
//!
//! Every function is a one-line delegation to the SAME safe instance code as FMI 2.0,
//! through the same [`dispatch`](super::component::dispatch): call sequence (one state
//! machine for both standards), panic catching, busy flag against re-entrant calls, logging
//! and status folding are shared. What is specific to FMI 3.0 here: the signatures
//! (`fmi3Boolean` is a C `bool`; get/set take `nValues`, as arrays count their elements),
//! the logger callback (not variadic, no instance name), `fmi3InstantiateCoSimulation`,
//! `fmi3EnterInitializationMode` with the experiment, and `fmi3DoStep`'s out-arguments.
//!
//! The FMU declares Co-Simulation only, without event mode, intermediate update, early
//! return, clocks, configuration mode or derivatives: the functions of those features are
//! exported (importers resolve every symbol) and return `fmi3Error` with a message naming
//! what the FMU does not provide; `fmi3InstantiateModelExchange` and
//! `fmi3InstantiateScheduledExecution` return NULL, and the functions of those two interfaces
//! ([`interfaces`]) return `fmi3Error`.
//!
//! The safety contract of each function is the FMI 3.0 standard's for arrays (the lengths
//! passed with them) and strings (NUL-terminated); NULL pointers are detected and reported.
//! `instance` is an opaque handle looked up in the registry of live instances (as for FMI 2.0):
//! a freed, foreign or NULL one gives `fmi3Error`. Files: [`lifecycle`] (creation, initialization, unsupported modes), [`values`]
//! (get and set of every FMI 3.0 type), [`interfaces`] (Model Exchange and Scheduled
//! Execution), [`states`] (FMU states), [`stepping`] (`fmi3DoStep`,
//! derivatives).

pub mod interfaces;
pub mod lifecycle;
pub mod states;
pub mod stepping;
pub mod values;

use std::ffi::{c_char, c_int, c_uint, c_void};

pub use interfaces::*;
pub use lifecycle::*;
pub use states::*;
pub use stepping::*;
pub use values::*;

pub type fmi3Instance = *mut c_void;
pub type fmi3InstanceEnvironment = *mut c_void;
pub type fmi3FMUState = *mut c_void;
pub type fmi3ValueReference = c_uint;
pub type fmi3Float64 = f64;
pub type fmi3Int32 = i32;
pub type fmi3Int64 = i64;
/// `fmi3Boolean` is C99 `bool`.
pub type fmi3Boolean = bool;
pub type fmi3Char = c_char;
pub type fmi3String = *const fmi3Char;
pub type fmi3Byte = u8;
/// `fmi3Status` (a C enum: OK 0, Warning 1, Discard 2, Error 3, Fatal 4, the same codes as
/// FMI 2.0's first five).
pub type fmi3Status = c_int;

/// `fmi3LogMessageCallback`: not variadic, the message is plain text.
pub type fmi3LogMessageCallback =
    unsafe extern "C" fn(fmi3InstanceEnvironment, fmi3Status, fmi3String, fmi3String);

/// `fmi3IntermediateUpdateCallback` (never called: no intermediate update).
pub type fmi3IntermediateUpdateCallback = Option<
    unsafe extern "C" fn(
        fmi3InstanceEnvironment,
        fmi3Float64,
        fmi3Boolean,
        fmi3Boolean,
        fmi3Boolean,
        fmi3Boolean,
        *mut fmi3Boolean,
        *mut fmi3Float64,
    ),
>;
