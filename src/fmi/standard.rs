//! Which FMI standard an instance or a description follows: FMI 2.0 or FMI 3.0
//! Co-Simulation. One instance code ([`super::instance`]), one state machine
//! ([`super::state_machine`]) and one variable table (the model's, declared for the
//! standard's [`Interface`]) serve both; this enum selects the few things that differ:
//! function names in messages, the type families of the get/set functions, what the
//! interface offers (arrays, input derivatives, the independent variable `time`) and the XML
//! written.

use crate::cosimulation::Interface;

/// The FMI standard of an FMU, a description or an instance.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Standard {
    /// FMI 2.0 Co-Simulation (`fmi2*` functions, `fmiVersion="2.0"`).
    Fmi2,
    /// FMI 3.0 Co-Simulation (`fmi3*` functions, `fmiVersion="3.0"`).
    Fmi3,
}

impl Standard {
    /// The prefix of the C functions: `fmi2` or `fmi3`.
    pub fn prefix(self) -> &'static str {
        match self {
            Standard::Fmi2 => "fmi2",
            Standard::Fmi3 => "fmi3",
        }
    }

    /// `fmiVersion` of the description.
    pub fn version(self) -> &'static str {
        match self {
            Standard::Fmi2 => "2.0",
            Standard::Fmi3 => "3.0",
        }
    }

    /// What the description calls the identity check: `GUID` or `instantiationToken`.
    pub fn token_name(self) -> &'static str {
        match self {
            Standard::Fmi2 => "GUID",
            Standard::Fmi3 => "instantiationToken",
        }
    }

    /// What the standard offers the model's variable table, and its words in descriptions:
    /// FMI 2.0 has input derivatives and no arrays; FMI 3.0 Co-Simulation has arrays and the
    /// independent variable `time`, and no input derivatives.
    pub fn interface(self) -> Interface {
        match self {
            Standard::Fmi2 => Interface {
                name: "FMI 2.0",
                arrays: false,
                input_derivatives: true,
                independent_variable: false,
                refused_step: "fmi2Discard",
                failed_step: "fmi2Error",
            },
            Standard::Fmi3 => Interface {
                name: "FMI 3.0",
                arrays: true,
                input_derivatives: false,
                independent_variable: true,
                refused_step: "fmi3Discard",
                failed_step: "fmi3Error",
            },
        }
    }
}
