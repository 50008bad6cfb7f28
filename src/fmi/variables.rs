//! The model's variable table ([`crate::model::variables`]) as the FMI layer reads it: the
//! model's types, and what only the standards have: value references and the type families of
//! their get/set functions.

pub use crate::cosimulation::{
    Causality, Declaration, Declarations, EnumerationType, Initial, InitialDependencies, Value,
    ValueType, Variability, VariableId,
};

use super::standard::Standard;

/// `fmi2ValueReference` / `fmi3ValueReference`: the model's variable identifier.
pub type ValueReference = VariableId;

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
    /// Which family serves a variable of type `ty`: FMI 2.0 reads Enumerations with
    /// `fmi2GetInteger`, FMI 3.0 with `fmi3GetInt64`.
    pub fn of(ty: ValueType, standard: Standard) -> Family {
        match (ty, standard) {
            (ValueType::Real { .. }, _) => Family::Real,
            (ValueType::Integer, _) | (ValueType::Enumeration(_), Standard::Fmi2) => {
                Family::Integer
            }
            (ValueType::Enumeration(_), Standard::Fmi3) => Family::Enumeration,
        }
    }

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
