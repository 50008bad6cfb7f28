//! The variable table: the one source of truth for the model's variables.
//!
//! The interface layer's description and its identity hash, its get/set dispatch, the packager's documentation page and reference CSV all read this table. Names,
//! units and signs are those of `docs/fmu.md`.
//!
//! Identifiers are fixed per variable (inputs 1.., outputs 10.., parameters 100..,
//! `rod.frequency[k]` = 200 + k), so a variable keeps its identifier when a scene leaves
//! others out. The table is declared for an [`Interface`]: what the importer's interface
//! offers (arrays, input derivatives, an independent variable) and its words in descriptions.
//!
//! - this file: the table and its lookups;
//! - [`types`]: what a variable is made of (causality, type and unit, [`Access`]);
//! - [`enumerations`]: the enumeration types, items from the core's name lists;
//! - [`list`]: the variable list itself (built with [`builder`]);
//! - [`interface`]: the variables that depend on the interface (the independent variable,
//!   the crank acceleration as an input, the arrays);
//! - [`ranges`]: the checks of Integer and Enumeration values at the set call.

mod builder;
pub mod enumerations;
mod interface;
mod list;
pub mod ranges;
pub mod types;

pub use crate::cosimulation::{
    Causality, Declaration, Declarations, Initial, InitialDependencies, Interface, Value,
    ValueType, Variability, VariableId,
};
pub use crate::cosimulation::{EnumerationItem, EnumerationType};
pub use enumerations::{ENUMERATION_TYPES, ROD_MODEL, ROD_REFERENCE};
pub use ranges::ELEMENTS_MAX;
pub use types::{Access, InputSlot, OutputGetter, Variable};

pub use interface::SHAPE_POINTS_MAX;

use crate::error::ModelError;
use crate::scene::Scene;
use crate::simulation::Simulation;

/// Identifier of `rod.frequency[1]` minus one.
pub const FREQUENCY_VR_BASE: VariableId = 200;

/// All variables of one model, in description order, with an index by identifier.
#[derive(Clone)]
pub struct VariableTable {
    variables: Vec<Variable>,
    /// The declarations of `variables`, in the same order: what an interface sees.
    declarations: Declarations,
}

impl VariableTable {
    /// The table of `scene` for `interface`, with K = min(`[outputs] frequencies`,
    /// frequencies that exist); builds the model once to count the frequencies. With
    /// arrays, `[outputs] shape_points` must be 0 or 2..=[`SHAPE_POINTS_MAX`].
    pub fn for_scene(scene: &Scene, interface: Interface) -> Result<VariableTable, ModelError> {
        if interface.arrays {
            interface::check_shape_points(scene)?;
        }
        let simulation = Simulation::new(scene)?;
        let k = scene
            .outputs
            .frequencies
            .min(simulation.frequencies_hz().len());
        Ok(VariableTable::for_interface(scene, k, interface))
    }

    /// The table from its variables in description order.
    pub(super) fn from_variables(variables: Vec<Variable>, interface: Interface) -> VariableTable {
        let declarations = Declarations::new(
            variables.iter().map(|v| v.declared.clone()).collect(),
            interface,
        );
        VariableTable {
            variables,
            declarations,
        }
    }

    /// The interface the table was declared for.
    pub fn interface(&self) -> Interface {
        self.declarations.interface()
    }

    /// The declarations (what an interface sees), in the same order as [`Self::variables`].
    pub fn declarations(&self) -> &Declarations {
        &self.declarations
    }

    /// All variables in description order.
    pub fn variables(&self) -> &[Variable] {
        &self.variables
    }

    /// The variable with this identifier.
    pub fn get(&self, vr: VariableId) -> Option<&Variable> {
        self.declarations.position(vr).map(|p| &self.variables[p])
    }

    /// 1-based index in the description's variable list (used by its model structure).
    pub fn index_of_name(&self, name: &str) -> Option<usize> {
        self.variables
            .iter()
            .position(|v| v.name == name)
            .map(|i| i + 1)
    }

    /// The variable with this name.
    pub fn by_name(&self, name: &str) -> Option<&Variable> {
        self.variables.iter().find(|v| v.name == name)
    }

    /// Number of frequencies declared: `rod.frequency[k]` scalars or the length of the
    /// array `rod.frequency`.
    pub fn frequency_count(&self) -> usize {
        self.variables
            .iter()
            .map(|v| match v.access {
                Access::Frequency(_) => 1,
                Access::Frequencies => v.value_count(),
                _ => 0,
            })
            .sum()
    }

    /// The outputs, in table order: (name, getter).
    pub fn outputs(&self) -> impl Iterator<Item = (&str, OutputGetter)> + '_ {
        self.variables.iter().filter_map(|v| match v.access {
            Access::Output(get) => Some((v.name.as_str(), get)),
            _ => None,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn value_references_unique_and_indexed() {
        let scene = Scene::benchmark();
        let table = VariableTable::new(&scene, 6);
        let mut vrs: Vec<_> = table
            .variables()
            .iter()
            .map(|v| v.value_reference)
            .collect();
        vrs.sort();
        vrs.dedup();
        assert_eq!(vrs.len(), table.variables().len());
        for v in table.variables() {
            assert_eq!(table.get(v.value_reference).unwrap().name, v.name);
        }
        assert!(table.get(9999).is_none());
        assert!(table.get(0).is_none());
        assert_eq!(
            table.by_name("rod.frequency[6]").unwrap().value_reference,
            206
        );
    }

    /// Every optional variable at once (a section table with stress outputs, the mechanism
    /// table, mass-loaded modes with a band, a gas-force table) in every combination of the
    /// interface's variables (arrays, independent variable, input derivatives): one variable a
    /// value reference (the builder asserts it).
    #[test]
    fn value_references_unique_with_every_optional_variable_and_interface() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/automotive_rod.toml");
        let mut scene = Scene::from_file(std::path::Path::new(path)).unwrap();
        scene.mechanism.gravity = [0.0, -9.81];
        scene.slider.gas_force = Some(crate::mechanism::gas_force::GasForceTable {
            cycle: 720.0,
            angle: vec![0.0, 10.0, 20.0],
            force: vec![0.0, -1e3, 0.0],
            scale: 1.0,
        });
        for arrays in [false, true] {
            for independent_variable in [false, true] {
                for input_derivatives in [false, true] {
                    let interface = Interface {
                        arrays,
                        independent_variable,
                        input_derivatives,
                        ..Interface::SCALARS
                    };
                    let table = VariableTable::for_interface(&scene, 6, interface);
                    for v in table.variables() {
                        assert_eq!(table.get(v.value_reference).unwrap().name, v.name);
                    }
                    assert!(table.by_name("slider.gas_force_scale").is_some());
                }
            }
        }
    }

    #[test]
    fn switched_off_variables_are_absent() {
        let mut scene = Scene::benchmark();
        scene.outputs.slider = false;
        scene.outputs.slider_force = false;
        scene.outputs.pin_forces = false;
        scene.outputs.crank_torque = false;
        let table = VariableTable::new(&scene, 2);
        for name in [
            "slider.position",
            "slider.force",
            "pinB.force_x",
            "crank.torque",
            "rod.frequency[3]",
        ] {
            assert!(table.by_name(name).is_none(), "{name}");
        }
        assert!(table.by_name("rod.deflection").is_some());
        assert!(table.by_name("slider.mass").is_some());
    }
}
