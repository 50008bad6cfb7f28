//! The FMI 2.0 Co-Simulation call sequence as data.
//!
//! Each function that takes an instance has a mask of the states it may be called in
//! (FMI 2.0.4, section 4.2.4, "State Machine of Calling Sequence from Master to Slave"; the
//! masks follow `modelica/Reference-FMUs`, `src/fmi2Functions.c`). The state `StepInProgress`
//! does not exist here: this FMU never returns `fmi2Pending` (`canRunAsynchronuously="false"`).
//!
//! `fmi2GetTypesPlatform`, `fmi2GetVersion` and `fmi2Instantiate` have no instance and so no
//! entry; `fmi2FreeInstance` is allowed in every state.

use super::status::FmiError;

/// The states of an instance.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MachineState {
    /// After `fmi2Instantiate` or `fmi2Reset`: parameters and inputs may be set.
    Instantiated,
    /// Between `fmi2EnterInitializationMode` and `fmi2ExitInitializationMode`.
    InitializationMode,
    /// Initialized, or the last `fmi2DoStep` succeeded: ready for the next step.
    StepComplete,
    /// The last `fmi2DoStep` returned `fmi2Discard`: the state from before the step is kept;
    /// restore a saved state (`fmi2SetFMUstate`), terminate or reset.
    StepFailed,
    /// After `fmi2Terminate`: outputs may still be read.
    Terminated,
    /// A call returned `fmi2Error` and the instance cannot continue (a failed initialization,
    /// an internal error). Reset, restore a state (`fmi2SetFMUstate`), read values or free
    /// the instance.
    Error,
}

impl MachineState {
    const ALL: [MachineState; 6] = [
        MachineState::Instantiated,
        MachineState::InitializationMode,
        MachineState::StepComplete,
        MachineState::StepFailed,
        MachineState::Terminated,
        MachineState::Error,
    ];

    const fn bit(self) -> u8 {
        1 << (self as u8)
    }

    /// Name used in messages (as in the FMI 2.0 state diagram).
    pub fn name(self) -> &'static str {
        match self {
            MachineState::Instantiated => "Instantiated",
            MachineState::InitializationMode => "InitializationMode",
            MachineState::StepComplete => "StepComplete",
            MachineState::StepFailed => "StepFailed",
            MachineState::Terminated => "Terminated",
            MachineState::Error => "Error",
        }
    }

    /// Stable code for serialized FMU states.
    pub fn code(self) -> u8 {
        self as u8
    }

    /// Decode [`MachineState::code`].
    pub fn from_code(code: u8) -> Option<MachineState> {
        MachineState::ALL.into_iter().find(|s| s.code() == code)
    }
}

const INSTANTIATED: u8 = MachineState::Instantiated.bit();
const INIT: u8 = MachineState::InitializationMode.bit();
const STEP_COMPLETE: u8 = MachineState::StepComplete.bit();
const STEP_FAILED: u8 = MachineState::StepFailed.bit();
const TERMINATED: u8 = MachineState::Terminated.bit();
const ERROR: u8 = MachineState::Error.bit();
const ANY: u8 = INSTANTIATED | INIT | STEP_COMPLETE | STEP_FAILED | TERMINATED | ERROR;
/// Where values can be read: from initialization mode on, also after an error.
const READABLE: u8 = INIT | STEP_COMPLETE | STEP_FAILED | TERMINATED | ERROR;
/// Where values can be set (which variables is checked per variable).
const SETTABLE: u8 = INSTANTIATED | INIT | STEP_COMPLETE;
/// Where the slave status can be inquired.
const STATUS: u8 = STEP_COMPLETE | STEP_FAILED | TERMINATED;
/// Where no call is possible (`fmi2CancelStep`: only while an asynchronous step runs).
const NEVER: u8 = 0;

macro_rules! calls {
    ($($call:ident => $mask:expr),+ $(,)?) => {
        /// Every FMI 2.0 function that takes an instance.
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub enum Call { $($call),+ }

        impl Call {
            /// The C name, e.g. `fmi2DoStep`.
            pub fn name(self) -> &'static str {
                match self { $(Call::$call => concat!("fmi2", stringify!($call))),+ }
            }

            fn allowed(self) -> u8 {
                match self { $(Call::$call => $mask),+ }
            }
        }
    };
}

calls! {
    SetDebugLogging => ANY,
    FreeInstance => ANY,
    SetupExperiment => INSTANTIATED,
    EnterInitializationMode => INSTANTIATED,
    ExitInitializationMode => INIT,
    Terminate => STEP_COMPLETE | STEP_FAILED,
    Reset => ANY,
    GetReal => READABLE,
    GetInteger => READABLE,
    GetBoolean => READABLE,
    GetString => READABLE,
    SetReal => SETTABLE,
    SetInteger => SETTABLE,
    SetBoolean => SETTABLE,
    SetString => SETTABLE,
    // As Reference-FMUs (MASK_fmi2FreeInstance): the state functions work in every state,
    // so an importer can restore a state saved before an error (fmi2SetFMUstate puts the
    // saved state machine state back).
    GetFMUstate => ANY,
    SetFMUstate => ANY,
    FreeFMUstate => ANY,
    SerializedFMUstateSize => ANY,
    SerializeFMUstate => ANY,
    DeSerializeFMUstate => ANY,
    GetDirectionalDerivative => READABLE,
    SetRealInputDerivatives => SETTABLE,
    GetRealOutputDerivatives => STEP_COMPLETE | STEP_FAILED | TERMINATED | ERROR,
    DoStep => STEP_COMPLETE,
    CancelStep => NEVER,
    GetStatus => STATUS,
    GetRealStatus => STATUS,
    GetIntegerStatus => STATUS,
    GetBooleanStatus => STATUS,
    GetStringStatus => STATUS,
}

/// Check that `call` is allowed in `state`; the error names the call, the state and the
/// states where the call is allowed.
pub fn check(call: Call, state: MachineState) -> Result<(), FmiError> {
    let allowed = call.allowed();
    if allowed & state.bit() != 0 {
        return Ok(());
    }
    let names: Vec<&str> = MachineState::ALL
        .into_iter()
        .filter(|s| allowed & s.bit() != 0)
        .map(MachineState::name)
        .collect();
    let allowed_text = if names.is_empty() {
        "never (this FMU steps synchronously and never returns fmi2Pending)".to_string()
    } else {
        names.join(", ")
    };
    Err(FmiError::rejected(format!(
        "illegal call sequence: {} is not allowed in state {}; allowed in: {allowed_text}",
        call.name(),
        state.name()
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn do_step_only_after_initialization() {
        assert!(check(Call::DoStep, MachineState::StepComplete).is_ok());
        let e = check(Call::DoStep, MachineState::Instantiated).unwrap_err();
        assert!(e.message.contains("fmi2DoStep"), "{}", e.message);
        assert!(e.message.contains("Instantiated"), "{}", e.message);
        assert!(
            e.message.contains("allowed in: StepComplete"),
            "{}",
            e.message
        );
        assert!(!e.instance_failed);
    }

    #[test]
    fn cancel_step_is_never_allowed() {
        for s in MachineState::ALL {
            assert!(check(Call::CancelStep, s).is_err());
        }
    }

    #[test]
    fn free_reset_and_set_state_always_allowed() {
        for s in MachineState::ALL {
            assert!(check(Call::FreeInstance, s).is_ok());
            assert!(check(Call::Reset, s).is_ok());
            assert!(check(Call::SetFMUstate, s).is_ok());
            assert!(check(Call::GetFMUstate, s).is_ok());
            assert!(check(Call::SerializeFMUstate, s).is_ok());
        }
    }

    #[test]
    fn codes_round_trip() {
        for s in MachineState::ALL {
            assert_eq!(MachineState::from_code(s.code()), Some(s));
        }
        assert_eq!(MachineState::from_code(200), None);
    }
}
