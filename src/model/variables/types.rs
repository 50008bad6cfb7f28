//! The types a variable is made of: its attributes (causality, variability, initial, type and
//! unit, in the words of the co-simulation standards), start values, and where its value
//! lives ([`Access`]).

use super::enumerations::EnumerationType;
use super::VariableId;
use crate::mechanism::Outputs;
use crate::scene::Scene;

/// Causality (`Independent` only for the independent variable `time`).
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

/// Variability (only those used here).
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

/// `initial` (absent for inputs).
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

/// The type of a variable, with its unit attributes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ValueType {
    Real {
        /// Unit (declared in the unit definitions); `None` for dimensionless.
        unit: Option<&'static str>,
        /// Display unit (deg for angles, rpm for speeds).
        display_unit: Option<&'static str>,
    },
    Integer,
    Enumeration(&'static EnumerationType),
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
    /// The crank acceleration `alpha_k` of the input law, as an input of its own (for
    /// interfaces without input derivatives, see [`super::Interface`]).
    CrankAcceleration,
    /// The crank jerk `j_k` of the input law, as an input of its own (the same interfaces).
    CrankJerk,
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
    /// `time`, the independent variable: the model's time.
    Time,
    /// The array `rod.shape`: the transverse deflection at equally spaced points.
    Shape,
    /// The array `rod.frequency`: the first `len` natural frequencies, Hz.
    Frequencies,
}

/// Which knowns an unknown depends on during initialization (the description's initial
/// unknowns).
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
    pub value_reference: VariableId,
    pub description: String,
    pub causality: Causality,
    pub variability: Variability,
    pub initial: Option<Initial>,
    pub value_type: ValueType,
    pub start: Option<Value>,
    /// `min` and `max` attributes (closed bounds).
    pub min: Option<Value>,
    pub max: Option<Value>,
    pub access: Access,
    /// Only for outputs and calculated parameters.
    pub initial_dependencies: InitialDependencies,
    /// Arrays: the fixed number of elements; `None` for a scalar (tables declared without
    /// arrays have only scalars).
    pub dimension: Option<usize>,
}

impl Access {
    /// The value comes from the simulation (outputs, frequencies, the shape), which must be
    /// built and started to read it.
    pub fn needs_simulation(self) -> bool {
        matches!(
            self,
            Access::Output(_) | Access::Frequency(_) | Access::Frequencies | Access::Shape
        )
    }
}

impl Variable {
    /// Number of values the variable takes in a get/set call: 1, or the array's length.
    pub fn value_count(&self) -> usize {
        self.dimension.unwrap_or(1)
    }
}
