//! The contract oracle: what the FMU must answer, written from the standard and docs/fmu.md,
//! not from the FMU's code.
//!
//! - The call sequence of FMI 2.0.4, section 4.2.4 (Co-Simulation state machine; the masks of
//!   `modelica/Reference-FMUs`, `src/fmi2Functions.c`, written out again here): a function
//!   called in a state that does not allow it returns `fmi2Error` and changes nothing.
//! - docs/fmu.md, "Errors and statuses": the calls rejected with `fmi2Error` (NULL where an
//!   array, string or output is needed, unknown value reference, wrong family, non-finite
//!   value, bad time or step, bad FMU state handle or bytes), each with a logged message, and
//!   never a non-finite value (or one of magnitude >= 1e12) with `fmi2OK`.
//! - The state the instance is in is modelled from the statuses of the legal calls and checked
//!   after each of them with [`probe`]: three calls without side effects whose accept/refuse
//!   pattern tells the states apart.

use flexrod::fmi::ffi::stepping::fmi2GetStatus;
use flexrod::fmi::ffi::values::{fmi2GetReal, fmi2SetReal};
use flexrod::fmi::ffi::{fmi2Component, fmi2Status};

use super::fmu::{DISCARD, ERROR, OK, WARNING};

/// The states of an instance (FMI 2.0.4, figure 8, without `stepInProgress`: the FMU never
/// returns `fmi2Pending`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum State {
    Instantiated,
    Init,
    StepComplete,
    StepFailed,
    Terminated,
    Error,
}

use State::*;

/// The fmi2 functions that take an instance (the other three, `fmi2GetTypesPlatform`,
/// `fmi2GetVersion` and `fmi2Instantiate`, are exercised on their own).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Func {
    FreeInstance,
    SetDebugLogging,
    SetupExperiment,
    EnterInitializationMode,
    ExitInitializationMode,
    Terminate,
    Reset,
    GetReal,
    GetInteger,
    GetBoolean,
    GetString,
    SetReal,
    SetInteger,
    SetBoolean,
    SetString,
    GetFMUstate,
    SetFMUstate,
    FreeFMUstate,
    SerializedFMUstateSize,
    SerializeFMUstate,
    DeSerializeFMUstate,
    GetDirectionalDerivative,
    SetRealInputDerivatives,
    GetRealOutputDerivatives,
    DoStep,
    CancelStep,
    GetStatus,
    GetRealStatus,
    GetIntegerStatus,
    GetBooleanStatus,
    GetStringStatus,
}

/// The functions that some state forbids (candidates for an illegal-order call).
pub const RESTRICTED: [Func; 22] = [
    Func::SetupExperiment,
    Func::EnterInitializationMode,
    Func::ExitInitializationMode,
    Func::Terminate,
    Func::GetReal,
    Func::GetInteger,
    Func::GetBoolean,
    Func::GetString,
    Func::SetReal,
    Func::SetInteger,
    Func::SetBoolean,
    Func::SetString,
    Func::GetDirectionalDerivative,
    Func::SetRealInputDerivatives,
    Func::GetRealOutputDerivatives,
    Func::DoStep,
    Func::CancelStep,
    Func::GetStatus,
    Func::GetRealStatus,
    Func::GetIntegerStatus,
    Func::GetBooleanStatus,
    Func::GetStringStatus,
];

/// Whether `f` may be called in state `s` (FMI 2.0.4, table of section 4.2.4; the FMU-state
/// functions in every state as docs/fmu.md says, to restore a state after an error).
pub fn allowed(f: Func, s: State) -> bool {
    use Func as F;
    let readable = s != Instantiated;
    let settable = matches!(s, Instantiated | Init | StepComplete);
    let status = matches!(s, StepComplete | StepFailed | Terminated);
    match f {
        F::FreeInstance | F::SetDebugLogging | F::Reset => true,
        F::SetupExperiment | F::EnterInitializationMode => s == Instantiated,
        F::ExitInitializationMode => s == Init,
        F::Terminate => matches!(s, StepComplete | StepFailed),
        F::GetReal | F::GetInteger | F::GetBoolean | F::GetString => readable,
        F::GetDirectionalDerivative => readable,
        F::SetReal | F::SetInteger | F::SetBoolean | F::SetString => settable,
        F::SetRealInputDerivatives => settable,
        F::GetRealOutputDerivatives => matches!(s, StepComplete | StepFailed | Terminated | Error),
        F::GetFMUstate
        | F::SetFMUstate
        | F::FreeFMUstate
        | F::SerializedFMUstateSize
        | F::SerializeFMUstate
        | F::DeSerializeFMUstate => true,
        F::DoStep => s == StepComplete,
        F::CancelStep => false,
        F::GetStatus
        | F::GetRealStatus
        | F::GetIntegerStatus
        | F::GetBooleanStatus
        | F::GetStringStatus => status,
    }
}

/// The state after a legal call `f` in state `s` answered `status` (FMI 2.0.4, section 4.2.4;
/// docs/fmu.md: a failed initialization or step enters `Error`, a discarded step `StepFailed`,
/// any other rejected call leaves the instance unchanged). `fmi2SetFMUstate` is handled by the
/// caller (the state saved with the handle).
pub fn after(f: Func, s: State, status: fmi2Status) -> State {
    let ok = status == OK || status == WARNING;
    match f {
        Func::EnterInitializationMode if ok => Init,
        Func::ExitInitializationMode if ok => StepComplete,
        Func::ExitInitializationMode if status == ERROR => Error,
        Func::DoStep if ok => StepComplete,
        Func::DoStep if status == DISCARD => StepFailed,
        // A legal step answered fmi2Error: the model failed or `rod.deflection_policy` = error
        // refused it (FMI 2.0: fmi2Error leaves only reset or a restored state), or it needed
        // more internal steps than the work bound or the crank law left an input window
        // (refused with the instance unchanged): the caller tells the two apart with the probe.
        Func::DoStep if status == ERROR => Error,
        Func::Terminate if ok => Terminated,
        Func::Reset if ok => Instantiated,
        _ => s,
    }
}

/// The accept (true) / refuse pattern of the three probe calls in state `s`:
/// `fmi2GetReal` with no values, `fmi2SetReal` with no values, `fmi2GetStatus(fmi2DoStepStatus)`.
pub fn signature(s: State) -> (bool, bool, bool) {
    (
        allowed(Func::GetReal, s),
        allowed(Func::SetReal, s),
        allowed(Func::GetStatus, s),
    )
}

/// The pattern the instance shows now (refusals are logged as errors by the instance).
pub fn probe(c: fmi2Component) -> (bool, bool, bool) {
    let mut status: fmi2Status = -1;
    let mut x = [0.0];
    let vr = [0u32];
    // SAFETY: live instance; zero-length arrays; `status` is writable.
    unsafe {
        (
            fmi2GetReal(c, vr.as_ptr(), 0, x.as_mut_ptr()) == OK,
            fmi2SetReal(c, vr.as_ptr(), 0, x.as_ptr()) == OK,
            fmi2GetStatus(c, 0, &mut status) == OK,
        )
    }
}

/// The outputs' magnitude bound of docs/fmu.md (`mechanism::MAX_OUTPUT_MAGNITUDE`).
pub const MAX_MAGNITUDE: f64 = 1e12;

/// Contract violations with their context (the first few are kept in full).
#[derive(Default)]
pub struct Violations {
    pub count: u64,
    pub first: Vec<String>,
}

impl Violations {
    pub fn add(&mut self, what: String) {
        self.count += 1;
        if self.first.len() < 20 {
            self.first.push(what);
        }
    }

    /// Values handed out with `fmi2OK` or `fmi2Warning` must be finite and below 1e12 in
    /// magnitude (frequencies and parameters included: all are physical quantities in SI).
    pub fn check_values(&mut self, status: fmi2Status, values: &[f64], what: &str) {
        if status == OK || status == WARNING {
            if let Some(x) = values
                .iter()
                .find(|x| !x.is_finite() || x.abs() >= MAX_MAGNITUDE)
            {
                self.add(format!("{what}: status {status} with the value {x}"));
            }
        }
    }
}
