//! Which FMI standard an instance or a description follows: FMI 2.0 or FMI 3.0
//! Co-Simulation. One instance code ([`super::instance`]), one state machine
//! ([`super::state_machine`]) and one variable table ([`super::variables`]) serve both; this
//! enum selects the few things that differ: function names in messages, the type families of
//! the get/set functions, the variables only FMI 3.0 has (arrays, `crank.acceleration`,
//! `time`) and the XML written.

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
}
