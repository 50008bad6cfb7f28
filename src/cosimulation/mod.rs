//! The contract between a model and a co-simulation interface, in the words of the
//! co-simulation standards and of no one standard: the [`CoSimulationModel`] hooks an
//! interface drives, and what it needs to know of a model's variables and of the model
//! itself, nothing of where the values live. The FMI shell (`crate::fmi`) writes its
//! `modelDescription.xml` from the declarations and checks its get/set calls against them;
//! each model implements the hooks and keeps its own accessors.
//!
//! - `model.rs`: the hooks ([`CoSimulationModel`]), the step outcome and the opaque saved state;
//! - this file: the [`Interface`] a table is declared for, a variable's [`Declaration`], the
//!   [`Declarations`] of one model with their index by identifier, and the model's
//!   [`ModelInfo`] (names, default experiment, units and enumeration types);
//! - [`types`]: causality, variability, `initial`, the value types, start values and the
//!   initial dependencies;
//! - [`enumeration`]: enumeration types and their items;
//! - [`units`]: unit definitions (SI base units and display units) and the catalogue of the
//!   units this crate's models use.

pub mod enumeration;
pub mod experiment;
mod model;
pub mod types;
pub mod units;

pub use model::{CoSimulationModel, SavedState, StepOutcome};

pub use enumeration::{EnumerationItem, EnumerationType};
pub use types::{Causality, Initial, InitialDependencies, Value, ValueType, Variability};
pub use units::UnitDefinition;

/// The identifier of a variable in get/set calls (the interface's value reference).
pub type VariableId = u32;

/// What the interface a table is declared for offers, and its words in descriptions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Interface {
    /// Its name in descriptions (e.g. where a variable exists because of it).
    pub name: &'static str,
    /// Array variables; without them a model declares scalars only.
    pub arrays: bool,
    /// Derivatives of inputs set at communication points; without them a model that uses
    /// derivatives of its inputs declares them as inputs of their own.
    pub input_derivatives: bool,
    /// The independent variable `time` declared as a variable.
    pub independent_variable: bool,
    /// Its name for the outcome of a step refused with the state before it kept (the caller
    /// may restore a state and retry), and for a step that failed.
    pub refused_step: &'static str,
    pub failed_step: &'static str,
}

impl Interface {
    /// Scalars only, input derivatives, no independent variable, plain words (for tools
    /// that read names and identifiers).
    pub const SCALARS: Interface = Interface {
        name: "the interface",
        arrays: false,
        input_derivatives: true,
        independent_variable: false,
        refused_step: "refused",
        failed_step: "failed",
    };
}

/// One variable as an interface sees it.
#[derive(Clone, Debug, PartialEq)]
pub struct Declaration {
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
    /// Only for outputs and calculated parameters.
    pub initial_dependencies: InitialDependencies,
    /// Arrays: the fixed number of elements; `None` for a scalar.
    pub dimension: Option<usize>,
    /// The value is computed by the model (an output, a calculated parameter), so reading it
    /// needs the model built and started.
    pub computed: bool,
}

impl Declaration {
    /// A scalar of `causality` with the variability and `initial` it implies in this crate's
    /// models (inputs and outputs continuous, parameters fixed; `initial` exact for parameters,
    /// calculated for outputs and calculated parameters, none for inputs and the independent
    /// variable), no start value, bounds or initial dependencies.
    pub fn new(
        name: impl Into<String>,
        value_reference: VariableId,
        causality: Causality,
        value_type: ValueType,
        description: impl Into<String>,
    ) -> Declaration {
        let (variability, initial) = match causality {
            Causality::Independent | Causality::Input => (Variability::Continuous, None),
            Causality::Output => (Variability::Continuous, Some(Initial::Calculated)),
            Causality::Parameter => (Variability::Fixed, Some(Initial::Exact)),
            Causality::CalculatedParameter => (Variability::Fixed, Some(Initial::Calculated)),
        };
        Declaration {
            name: name.into(),
            value_reference,
            description: description.into(),
            causality,
            variability,
            initial,
            value_type,
            start: None,
            min: None,
            max: None,
            initial_dependencies: InitialDependencies::None,
            dimension: None,
            computed: false,
        }
    }

    /// Number of values the variable takes in a get/set call: 1, or the array's length.
    pub fn value_count(&self) -> usize {
        self.dimension.unwrap_or(1)
    }
}

/// All variables of one model, in description order, with an index by identifier.
#[derive(Clone, Debug, PartialEq)]
pub struct Declarations {
    variables: Vec<Declaration>,
    /// `by_vr[vr]` = position + 1 in `variables`, 0 if no variable has that identifier.
    by_vr: Vec<u16>,
    interface: Interface,
}

impl Declarations {
    /// The declarations in description order, for `interface`. Panics if two share an
    /// identifier (a programming error: tables are built from constants).
    pub fn new(variables: Vec<Declaration>, interface: Interface) -> Declarations {
        let by_vr = index_by_identifier(variables.iter().map(|v| (v.value_reference, &v.name)));
        Declarations {
            variables,
            by_vr,
            interface,
        }
    }

    /// The interface the declarations are for.
    pub fn interface(&self) -> Interface {
        self.interface
    }

    /// All variables in description order.
    pub fn variables(&self) -> &[Declaration] {
        &self.variables
    }

    /// The position (0-based) of the variable with this identifier.
    pub fn position(&self, vr: VariableId) -> Option<usize> {
        let position = *self.by_vr.get(vr as usize)?;
        (position > 0).then(|| position as usize - 1)
    }

    /// The variable with this identifier.
    pub fn get(&self, vr: VariableId) -> Option<&Declaration> {
        self.position(vr).map(|p| &self.variables[p])
    }

    /// The variable with this name.
    pub fn by_name(&self, name: &str) -> Option<&Declaration> {
        self.variables.iter().find(|v| v.name == name)
    }

    /// 1-based index in the description's variable list (used by its model structure).
    pub fn index_of_name(&self, name: &str) -> Option<usize> {
        self.variables
            .iter()
            .position(|v| v.name == name)
            .map(|i| i + 1)
    }
}

/// `index[vr]` = position + 1 of the variable with identifier `vr`, 0 for none. Panics if an
/// identifier is given twice.
pub fn index_by_identifier<'a>(
    identifiers: impl Iterator<Item = (VariableId, &'a String)> + Clone,
) -> Vec<u16> {
    let max_vr = identifiers.clone().map(|(vr, _)| vr).max().unwrap_or(0);
    let mut by_vr = vec![0u16; max_vr as usize + 1];
    for (i, (vr, name)) in identifiers.enumerate() {
        assert_eq!(
            by_vr[vr as usize], 0,
            "value reference {vr} given twice ({name})"
        );
        by_vr[vr as usize] = (i + 1) as u16;
    }
    by_vr
}

/// The experiment a model proposes (`DefaultExperiment`), s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DefaultExperiment {
    pub start_time: f64,
    pub stop_time: f64,
    pub step_size: f64,
}

/// What an interface needs to know of the model besides its variables.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelInfo {
    /// `modelName` and `modelIdentifier` (the file name of the binary).
    pub name: String,
    /// `description`.
    pub description: String,
    pub default_experiment: DefaultExperiment,
    /// The units its variables may use (the description lists those used).
    pub units: &'static [UnitDefinition],
    /// Its enumeration types, in `TypeDefinitions` order.
    pub enumeration_types: &'static [&'static EnumerationType],
}
