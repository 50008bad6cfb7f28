//! The variable table: the one source of truth for the FMU's variables.
//!
//! `modelDescription.xml`, the GUID, the get/set dispatch of the C ABI, the packager's
//! documentation page and the reference CSV of the packager all read this table. Names,
//! units and signs are those of `docs/fmu.md`.
//!
//! Value references are fixed per variable (inputs 1.., outputs 10.., parameters 100..,
//! `rod.frequency[k]` = 200 + k), so a variable keeps its reference when a scene leaves
//! others out.
//!
//! - this file: the table and its lookups;
//! - [`types`]: what a variable is made of (causality, type and unit, [`Access`]);
//! - [`enumerations`]: the enumeration types, items from the core's name lists;
//! - [`list`]: the variable list itself (built with [`builder`]);
//! - [`ranges`]: the checks of Integer and Enumeration values at the set call.

mod builder;
pub mod enumerations;
mod fmi3;
mod list;
pub mod ranges;
pub mod types;

pub use enumerations::{
    EnumerationItem, EnumerationType, ENUMERATION_TYPES, ROD_MODEL, ROD_REFERENCE,
};
pub use ranges::ELEMENTS_MAX;
pub use types::{
    Access, Causality, Family, Initial, InitialDependencies, InputSlot, OutputGetter, Value,
    ValueType, Variability, Variable,
};

pub use fmi3::SHAPE_POINTS_MAX;

use crate::error::ModelError;
use crate::fmi::standard::Standard;
use crate::scene::Scene;
use crate::simulation::Simulation;

/// `fmi2ValueReference`.
pub type ValueReference = u32;

/// Value reference of `rod.frequency[1]` minus one.
pub const FREQUENCY_VR_BASE: ValueReference = 200;

/// All variables of one FMU, in modelDescription.xml order, with an index by value reference.
#[derive(Clone)]
pub struct VariableTable {
    variables: Vec<Variable>,
    /// `by_vr[vr]` = position + 1 in `variables`, 0 if no variable has that reference.
    by_vr: Vec<u16>,
    standard: Standard,
}

impl VariableTable {
    /// The table of `scene`, with K = min(`[outputs] frequencies`, frequencies that exist);
    /// builds the model once to count the frequencies.
    pub fn for_scene(scene: &Scene) -> Result<VariableTable, ModelError> {
        let simulation = Simulation::new(scene)?;
        let k = scene
            .outputs
            .frequencies
            .min(simulation.frequencies_hz().len());
        Ok(VariableTable::new(scene, k))
    }

    /// The FMI 3.0 table of `scene` (see [`VariableTable::for_scene`]); `[outputs]
    /// shape_points` must be 0 or 2..=[`SHAPE_POINTS_MAX`].
    pub fn for_scene_fmi3(scene: &Scene) -> Result<VariableTable, ModelError> {
        fmi3::check_shape_points(scene)?;
        let simulation = Simulation::new(scene)?;
        let k = scene
            .outputs
            .frequencies
            .min(simulation.frequencies_hz().len());
        Ok(VariableTable::for_standard(scene, k, Standard::Fmi3))
    }

    /// The standard the table was built for.
    pub fn standard(&self) -> Standard {
        self.standard
    }

    /// All variables in modelDescription.xml order.
    pub fn variables(&self) -> &[Variable] {
        &self.variables
    }

    /// The variable with this value reference.
    pub fn get(&self, vr: ValueReference) -> Option<&Variable> {
        let position = *self.by_vr.get(vr as usize)?;
        (position > 0).then(|| &self.variables[position as usize - 1])
    }

    /// 1-based index in `ModelVariables` (used by `ModelStructure`).
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

    /// Number of frequencies declared: `rod.frequency[k]` scalars (FMI 2.0) or the length of
    /// the array `rod.frequency` (FMI 3.0).
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
