//! The FMI 2.0 and FMI 3.0 Co-Simulation call sequence as data (one table for both: an FMI
//! 3.0 function shares the entry of the FMI 2.0 function with the same role; FMI 3.0's
//! `StepMode` is `StepComplete` here, and its `ConfigurationMode`, `EventMode` and
//! `IntermediateUpdateMode` are never entered, as the FMU declares no structural parameters,
//! no event mode and no intermediate update).
//!
//! Each function that takes an instance has a mask of the states it may be called in
//! (FMI 2.0.4, section 4.2.4, "State Machine of Calling Sequence from Master to Slave"; the
//! masks follow `modelica/Reference-FMUs`, `src/fmi2Functions.c`). The state `StepInProgress`
//! does not exist here: this FMU never returns `fmi2Pending` (`canRunAsynchronuously="false"`).
//!
//! `fmi2GetTypesPlatform`, `fmi2GetVersion` and `fmi2Instantiate` have no instance and so no
//! entry; `fmi2FreeInstance` is allowed in every state.

use super::standard::Standard;
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
    /// After initialization: the instance holds a simulation at a time within the experiment.
    pub fn is_stepping(self) -> bool {
        matches!(
            self,
            MachineState::StepComplete | MachineState::StepFailed | MachineState::Terminated
        )
    }

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
        /// Every FMI function that takes an instance: those of FMI 2.0 by their FMI 2.0 names
        /// (the FMI 3.0 function with the same role shares the variant, e.g. `DoStep` is
        /// `fmi2DoStep` and `fmi3DoStep`, `GetReal` is `fmi2GetReal` and `fmi3GetFloat64`),
        /// and the FMI 3.0 additions.
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub enum Call {
            $($call,)+
            /// `fmi3GetInt64` / `fmi3SetInt64` (FMI 3.0 Enumerations).
            GetInt64,
            SetInt64,
            /// A get function of a type this FMU has no variable of (e.g. `fmi3GetFloat32`).
            GetOther(&'static str),
            /// A set function of a type this FMU has no variable of.
            SetOther(&'static str),
            /// A function of an interface or capability this FMU does not declare (e.g.
            /// `fmi3EnterEventMode`): checked for the instance, then answered with an error.
            NotProvided(&'static str),
        }

        impl Call {
            /// The FMI 2.0 name, or the given name of the FMI 3.0-only calls.
            fn fmi2_name(self) -> &'static str {
                match self {
                    $(Call::$call => concat!("fmi2", stringify!($call)),)+
                    Call::GetInt64 => "fmi3GetInt64",
                    Call::SetInt64 => "fmi3SetInt64",
                    Call::GetOther(name) | Call::SetOther(name) | Call::NotProvided(name) => name,
                }
            }

            /// The same name with the `fmi3` prefix.
            fn fmi3_default_name(self) -> &'static str {
                match self {
                    $(Call::$call => concat!("fmi3", stringify!($call)),)+
                    other => other.fmi2_name(),
                }
            }

            fn allowed(self) -> u8 {
                match self {
                    $(Call::$call => $mask,)+
                    Call::GetInt64 | Call::GetOther(_) => READABLE,
                    Call::SetInt64 | Call::SetOther(_) => SETTABLE,
                    Call::NotProvided(_) => ANY,
                }
            }
        }
    };
}

impl Call {
    /// The C name in `standard`, e.g. `fmi2GetReal` or `fmi3GetFloat64`.
    pub fn name(self, standard: Standard) -> &'static str {
        match standard {
            Standard::Fmi2 => self.fmi2_name(),
            Standard::Fmi3 => match self {
                Call::GetReal => "fmi3GetFloat64",
                Call::GetInteger => "fmi3GetInt32",
                Call::SetReal => "fmi3SetFloat64",
                Call::SetInteger => "fmi3SetInt32",
                Call::GetFMUstate => "fmi3GetFMUState",
                Call::SetFMUstate => "fmi3SetFMUState",
                Call::FreeFMUstate => "fmi3FreeFMUState",
                Call::SerializedFMUstateSize => "fmi3SerializedFMUStateSize",
                Call::SerializeFMUstate => "fmi3SerializeFMUState",
                Call::DeSerializeFMUstate => "fmi3DeserializeFMUState",
                Call::GetRealOutputDerivatives => "fmi3GetOutputDerivatives",
                // FMI 3.0 passes tolerance, start and stop time to EnterInitializationMode.
                Call::SetupExperiment => "fmi3EnterInitializationMode",
                other => other.fmi3_default_name(),
            },
        }
    }
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
pub fn check(call: Call, state: MachineState, standard: Standard) -> Result<(), FmiError> {
    let mut allowed = call.allowed();
    // FMI 3.0 also allows the get functions in Instantiated (Reference-FMUs,
    // `src/fmi3Functions.c`, MASK_fmi3GetFloat32): parameters and inputs can be read before
    // initialization; outputs there report that the model is not initialized.
    if standard == Standard::Fmi3
        && matches!(
            call,
            Call::GetReal | Call::GetInteger | Call::GetInt64 | Call::GetOther(_)
        )
    {
        allowed |= INSTANTIATED;
    }
    if allowed & state.bit() != 0 {
        return Ok(());
    }
    let names: Vec<&str> = MachineState::ALL
        .into_iter()
        .filter(|s| allowed & s.bit() != 0)
        .map(MachineState::name)
        .collect();
    let allowed_text = if names.is_empty() {
        format!(
            "never (this FMU steps synchronously{})",
            match standard {
                Standard::Fmi2 => " and never returns fmi2Pending",
                Standard::Fmi3 => "",
            }
        )
    } else {
        names.join(", ")
    };
    Err(FmiError::rejected(format!(
        "illegal call sequence: {} is not allowed in state {}; allowed in: {allowed_text}",
        call.name(standard),
        state.name()
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn do_step_only_after_initialization() {
        assert!(check(Call::DoStep, MachineState::StepComplete, Standard::Fmi2).is_ok());
        let e = check(Call::DoStep, MachineState::Instantiated, Standard::Fmi2).unwrap_err();
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
            assert!(check(Call::CancelStep, s, Standard::Fmi2).is_err());
        }
    }

    #[test]
    fn free_reset_and_set_state_always_allowed() {
        for s in MachineState::ALL {
            assert!(check(Call::FreeInstance, s, Standard::Fmi2).is_ok());
            assert!(check(Call::Reset, s, Standard::Fmi2).is_ok());
            assert!(check(Call::SetFMUstate, s, Standard::Fmi2).is_ok());
            assert!(check(Call::GetFMUstate, s, Standard::Fmi2).is_ok());
            assert!(check(Call::SerializeFMUstate, s, Standard::Fmi2).is_ok());
        }
    }

    #[test]
    fn fmi3_names() {
        assert_eq!(Call::GetReal.name(Standard::Fmi3), "fmi3GetFloat64");
        assert_eq!(Call::DoStep.name(Standard::Fmi3), "fmi3DoStep");
        assert_eq!(Call::DoStep.name(Standard::Fmi2), "fmi2DoStep");
        assert_eq!(
            Call::DeSerializeFMUstate.name(Standard::Fmi3),
            "fmi3DeserializeFMUState"
        );
        let e = check(Call::DoStep, MachineState::Instantiated, Standard::Fmi3).unwrap_err();
        assert!(e.message.contains("fmi3DoStep"), "{}", e.message);
        assert!(check(Call::GetReal, MachineState::Instantiated, Standard::Fmi3).is_ok());
        assert!(check(Call::GetReal, MachineState::Instantiated, Standard::Fmi2).is_err());
    }

    #[test]
    fn codes_round_trip() {
        for s in MachineState::ALL {
            assert_eq!(MachineState::from_code(s.code()), Some(s));
        }
        assert_eq!(MachineState::from_code(200), None);
    }
}
