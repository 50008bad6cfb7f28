//! The types a variable is made of: FMI 2.0 attributes (causality, variability, initial, type
//! and unit), start values, and where its value lives ([`Access`]).

use super::enumerations::EnumerationType;
use super::ValueReference;
use crate::fmi::standard::Standard;
use crate::mechanism::Outputs;
use crate::scene::Scene;

/// FMI causality (`Independent` only in FMI 3.0, for `time`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Causality {
    Independent,
    Input,
    Output,
    Parameter,
    CalculatedParameter,
}

impl Causality {
    pub fn as_str(self) -> &'static str {
        match self {
            Causality::Independent => "independent",
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
    /// Which get/set family serves this type: FMI 2.0 reads Enumerations with
    /// `fmi2GetInteger`, FMI 3.0 with `fmi3GetInt64`.
    pub fn family(self, standard: Standard) -> Family {
        match (self, standard) {
            (ValueType::Real { .. }, _) => Family::Real,
            (ValueType::Integer, _) | (ValueType::Enumeration(_), Standard::Fmi2) => {
                Family::Integer
            }
            (ValueType::Enumeration(_), Standard::Fmi3) => Family::Enumeration,
        }
    }
}

/// The get/set families (`fmi2GetReal` = `fmi3GetFloat64`, `fmi2GetInteger` = `fmi3GetInt32`,
/// FMI 3.0 Enumerations through `fmi3GetInt64`; `Other` names an FMI 3.0 type this FMU has
/// no variable of, e.g. `Float32`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Family {
    Real,
    Integer,
    Enumeration,
    Boolean,
    String,
    Other(&'static str),
}

impl Family {
    /// The type name in the functions of `standard`: `Real`/`Float64`, `Integer`/`Int32`, ...
    pub fn name(self, standard: Standard) -> &'static str {
        match (self, standard) {
            (Family::Real, Standard::Fmi2) => "Real",
            (Family::Real, Standard::Fmi3) => "Float64",
            (Family::Integer, Standard::Fmi2) => "Integer",
            (Family::Integer, Standard::Fmi3) => "Int32",
            (Family::Enumeration, Standard::Fmi2) => "Integer",
            (Family::Enumeration, Standard::Fmi3) => "Int64",
            (Family::Boolean, _) => "Boolean",
            (Family::String, _) => "String",
            (Family::Other(name), _) => name,
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
    /// FMI 3.0 only: the crank acceleration `alpha_k` of the input law (FMI 2.0 takes it as
    /// an input derivative instead).
    CrankAcceleration,
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
    /// FMI 3.0 `time`: the FMU's time.
    Time,
    /// FMI 3.0 array `rod.shape`: the transverse deflection at equally spaced points.
    Shape,
    /// FMI 3.0 array `rod.frequency`: the first `len` natural frequencies, Hz.
    Frequencies,
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
    /// FMI 3.0 arrays: the fixed number of elements (`<Dimension start="n"/>`); `None` for
    /// a scalar. FMI 2.0 tables have no arrays.
    pub dimension: Option<usize>,
}

impl Variable {
    /// Number of values the variable takes in a get/set call: 1, or the array's length.
    pub fn value_count(&self) -> usize {
        self.dimension.unwrap_or(1)
    }
}
