//! The attributes of a variable in the words of the co-simulation standards: causality,
//! variability, `initial`, the value type with its unit, start values and bounds, and which
//! knowns an unknown depends on during initialization.

use super::enumeration::EnumerationType;

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
