//! `modelDescription.xml`, written from the variable table, and the GUID derived from it.
//!
//! The GUID is the FNV-1a 128-bit hash of the description rendered with an all-zero GUID,
//! formatted `{8-4-4-4-12}`: the same scene and the same code give the same GUID, any change
//! of a variable, unit, start value or capability gives another.

//!
//! - this file: the description, its capabilities and GUID;
//! - [`xml`]: the FMI 2.0 XML, written element by element from the variable table;
//! - [`xml3`]: the FMI 3.0 XML from the FMI 3.0 table (`instantiationToken` takes the place
//!   of the GUID and is derived the same way);
//! - [`units`]: the unit definitions.

mod units;
mod xml;
mod xml3;

pub use xml3::CAPABILITIES_FMI3;

use std::io;

use crate::error::ModelError;
use crate::hash::fnv1a_128;
use crate::model::Scene;

use super::standard::Standard;
use super::variables::VariableTable;

/// The FMU's capability flags, written into `<CoSimulation>` (`docs/fmu.md`, "Capabilities").
pub const CAPABILITIES: [(&str, &str); 10] = [
    ("needsExecutionTool", "false"),
    ("canHandleVariableCommunicationStepSize", "true"),
    ("canInterpolateInputs", "true"),
    ("maxOutputDerivativeOrder", "0"),
    ("canRunAsynchronuously", "false"),
    ("canBeInstantiatedOnlyOncePerProcess", "false"),
    // The Rust allocator is used, never allocateMemory/freeMemory of the importer.
    ("canNotUseMemoryManagementFunctions", "true"),
    ("canGetAndSetFMUstate", "true"),
    ("canSerializeFMUstate", "true"),
    ("providesDirectionalDerivative", "false"),
];

/// A generated model description.
#[derive(Clone)]
pub struct ModelDescription {
    /// The XML text.
    pub xml: String,
    /// `{8-4-4-4-12}`: the GUID (FMI 2.0) or the `instantiationToken` (FMI 3.0).
    pub guid: String,
    /// The table the description was written from.
    pub table: VariableTable,
    /// The standard the description follows.
    pub standard: Standard,
}

impl ModelDescription {
    /// The FMI 2.0 description of `scene` (builds the model once to count the natural
    /// frequencies).
    pub fn for_scene(scene: &Scene) -> Result<ModelDescription, ModelError> {
        ModelDescription::for_standard(scene, Standard::Fmi2)
    }

    /// The FMI 3.0 description of `scene`.
    pub fn for_scene_fmi3(scene: &Scene) -> Result<ModelDescription, ModelError> {
        ModelDescription::for_standard(scene, Standard::Fmi3)
    }

    /// The description of `scene` in `standard`: the model's table declared for the
    /// standard's interface.
    pub fn for_standard(scene: &Scene, standard: Standard) -> Result<ModelDescription, ModelError> {
        let table = VariableTable::for_scene(scene, standard.interface())?;
        ModelDescription::new(scene, table, standard)
    }

    /// The description of `scene` with the given table, in `standard`.
    pub fn new(
        scene: &Scene,
        table: VariableTable,
        standard: Standard,
    ) -> Result<ModelDescription, ModelError> {
        // The scene's texts go into attributes: only characters XML 1.0 carries.
        scene.validate_texts()?;
        let render = match standard {
            Standard::Fmi2 => xml::render,
            Standard::Fmi3 => xml3::render,
        };
        let placeholder = "{00000000-0000-0000-0000-000000000000}";
        let unhashed = render(scene, &table, placeholder).map_err(write_error)?;
        let guid = guid_from_hash(fnv1a_128(unhashed.as_bytes()));
        let xml = render(scene, &table, &guid).map_err(write_error)?;
        Ok(ModelDescription {
            xml,
            guid,
            table,
            standard,
        })
    }

    /// The standard of the description.
    pub fn standard(&self) -> Standard {
        self.standard
    }
}

/// The `modelIdentifier` (file name of the binary) of a scene: its name.
pub fn model_identifier(scene: &Scene) -> &str {
    &scene.name
}

fn write_error(e: io::Error) -> ModelError {
    ModelError::State {
        message: format!("cannot write modelDescription.xml: {e}"),
    }
}

fn guid_from_hash(h: u128) -> String {
    let hex = format!("{h:032x}");
    format!(
        "{{{}-{}-{}-{}-{}}}",
        &hex[0..8],
        &hex[8..12],
        &hex[12..16],
        &hex[16..20],
        &hex[20..32]
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fmi2_table(scene: &Scene) -> VariableTable {
        VariableTable::for_interface(scene, 6, Standard::Fmi2.interface())
    }

    #[test]
    fn guid_format() {
        let g = guid_from_hash(0x0123456789abcdef0123456789abcdef);
        assert_eq!(g, "{01234567-89ab-cdef-0123-456789abcdef}");
    }

    #[test]
    fn description_depends_on_start_values() {
        let scene = Scene::benchmark();
        let a = ModelDescription::new(&scene, fmi2_table(&scene), Standard::Fmi2).unwrap();
        let mut other = scene.clone();
        other.rod.length = 0.31;
        let b = ModelDescription::new(&other, fmi2_table(&other), Standard::Fmi2).unwrap();
        assert_ne!(a.guid, b.guid);
        assert!(a.xml.contains(&a.guid));
        assert!(a.xml.contains("canSerializeFMUstate=\"true\""));
        assert_eq!(a.xml.matches("canRunAsynchronuously").count(), 1);
    }

    #[test]
    fn non_finite_values_are_not_written() {
        let mut scene = Scene::benchmark();
        scene.experiment.stop_time = f64::INFINITY;
        let e = ModelDescription::new(&scene, fmi2_table(&scene), Standard::Fmi2)
            .err()
            .expect("an infinite stop time is rejected");
        assert!(e.to_string().contains("not finite"), "{e}");
    }

    #[test]
    fn parameter_bounds_are_declared() {
        let scene = Scene::benchmark();
        let xml = ModelDescription::new(&scene, fmi2_table(&scene), Standard::Fmi2)
            .unwrap()
            .xml;
        assert!(
            xml.contains("<Real unit=\"m\" min=\"0.0\" start=\"0.3048\"/>"),
            "{xml}"
        );
        assert!(
            xml.contains("<Integer min=\"2\" max=\"128\" start=\"8\"/>"),
            "{xml}"
        );
    }
}
