//! The types a variable is made of: FMI 2.0 attributes (causality, variability, initial, type
//! and unit), start values, and where its value lives ([`Access`]).

use super::enumerations::EnumerationType;
use super::ValueReference;
use crate::mechanism::Outputs;
use crate::scene::Scene;

/// FMI 2.0 causality.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Causality {
    Input,
    Output,
    Parameter,
    CalculatedParameter,
}

impl Causality {
    pub fn as_str(self) -> &'static str {
        match self {
            Causality::Input => "input",
            Causality::Output => "output",
            Causality::Parameter => "parameter",
            Causality::CalculatedParameter => "calculatedParameter",
        }
    }
}

/// FMI 2.0 variability (only those used here).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Variability {
    Fixed,
    Continuous,
}

impl Variability {
    pub fn as_str(self) -> &'static str {
        match self {
            Variability::Fixed => "fixed",
            Variability::Continuous => "continuous",
        }
    }
}

/// FMI 2.0 `initial` (absent for inputs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Initial {
    Exact,
    Calculated,
}

impl Initial {
    pub fn as_str(self) -> &'static str {
        match self {
            Initial::Exact => "exact",
            Initial::Calculated => "calculated",
        }
    }
}

/// FMI 2.0 type of a variable, with its unit attributes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ValueType {
    Real {
        /// Unit (declared in `UnitDefinitions`); `None` for dimensionless.
        unit: Option<&'static str>,
        /// Display unit (deg for angles, rpm for speeds).
        display_unit: Option<&'static str>,
    },
    Integer,
    Enumeration(&'static EnumerationType),
}

impl ValueType {
    /// Which `fmi2Get*`/`fmi2Set*` family serves this type.
    pub fn family(self) -> Family {
        match self {
            ValueType::Real { .. } => Family::Real,
            ValueType::Integer | ValueType::Enumeration(_) => Family::Integer,
        }
    }
}

/// The `fmi2Get*`/`fmi2Set*` families.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Family {
    Real,
    Integer,
    Boolean,
    String,
}

impl Family {
    pub fn name(self) -> &'static str {
        match self {
            Family::Real => "Real",
            Family::Integer => "Integer",
            Family::Boolean => "Boolean",
            Family::String => "String",
        }
    }
}

/// A start value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    Real(f64),
    Integer(i32),
}

/// The inputs an instance stores between communication points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InputSlot {
    CrankAngle,
    CrankSpeed,
    SliderForce,
}

/// Reads one output from the simulation's outputs.
pub type OutputGetter = fn(&Outputs) -> f64;

/// Where a variable's value lives and how to read or write it.
#[derive(Clone, Copy)]
pub enum Access {
    /// An input kept by the instance.
    Input(InputSlot),
    /// An output of the simulation.
    Output(OutputGetter),
    /// A Real parameter stored in the instance's scene.
    RealParameter {
        get: fn(&Scene) -> f64,
        set: fn(&mut Scene, f64),
    },
    /// An Integer or Enumeration parameter stored in the instance's scene. `set` returns
    /// the allowed range when the value cannot be stored.
    IntegerParameter {
        get: fn(&Scene) -> i32,
        set: fn(&mut Scene, i32) -> Result<(), String>,
    },
    /// `rod.frequency[k]`: index k - 1 into `Simulation::frequencies_hz`.
    Frequency(usize),
    /// `rod.mass`: the rod with its end bodies, from the instance's scene.
    RodMass,
}

/// Which knowns an unknown depends on during initialization (`ModelStructure/InitialUnknowns`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InitialDependencies {
    /// Constant during initialization (e.g. the deflection of the undeformed rod).
    None,
    /// Every input and every parameter.
    All,
    /// The named inputs and parameters (names absent from the table are skipped).
    Named(&'static [&'static str]),
}

/// One scalar variable.
#[derive(Clone)]
pub struct Variable {
    pub name: String,
    pub value_reference: ValueReference,
    pub description: String,
    pub causality: Causality,
    pub variability: Variability,
    pub initial: Option<Initial>,
    pub value_type: ValueType,
    pub start: Option<Value>,
    /// `min` and `max` attributes (closed bounds; FMI 2.0 has no open ones).
    pub min: Option<Value>,
    pub max: Option<Value>,
    pub access: Access,
    /// Only for outputs and calculated parameters.
    pub initial_dependencies: InitialDependencies,
}
