//! `modelDescription.xml`, written from a model's declarations and info, and the GUID
//! derived from it.
//!
//! The GUID is the FNV-1a 128-bit hash of the description rendered with an all-zero GUID,
//! formatted `{8-4-4-4-12}`: the same model and the same code give the same GUID, any change
//! of a variable, unit, start value or capability gives another.

//!
//! - this file: the description, its capabilities and GUID;
//! - [`xml`]: the FMI 2.0 XML, written element by element from the variable table;
//! - [`xml3`]: the FMI 3.0 XML from the FMI 3.0 table (`instantiationToken` takes the place
//!   of the GUID and is derived the same way);
//! - [`units`]: the unit definitions.

mod units;
mod writer;
mod xml;
mod xml3;

pub use xml3::CAPABILITIES_FMI3;

use std::io;

use crate::cosimulation::{CoSimulationModel, Declarations, ModelInfo};
use crate::error::ModelError;
use crate::hash::fnv1a_128;

use super::standard::Standard;

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
    /// The declarations the description was written from.
    pub table: Declarations,
    /// The model's names (`modelIdentifier`), default experiment, units and enumerations.
    pub info: ModelInfo,
    /// The standard the description follows.
    pub standard: Standard,
}

impl ModelDescription {
    /// The description of `model` (its variables declared for `standard`'s interface) in
    /// `standard`.
    pub fn of<M: CoSimulationModel + ?Sized>(
        model: &M,
        standard: Standard,
    ) -> Result<ModelDescription, ModelError> {
        let render = match standard {
            Standard::Fmi2 => xml::render,
            Standard::Fmi3 => xml3::render,
        };
        let (info, table) = (model.info(), model.declarations());
        let placeholder = "{00000000-0000-0000-0000-000000000000}";
        let unhashed = render(info, table, placeholder).map_err(write_error)?;
        let guid = guid_from_hash(fnv1a_128(unhashed.as_bytes()));
        let xml = render(info, table, &guid).map_err(write_error)?;
        Ok(ModelDescription {
            xml,
            guid,
            table: table.clone(),
            info: info.clone(),
            standard,
        })
    }

    /// The standard of the description.
    pub fn standard(&self) -> Standard {
        self.standard
    }
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

    #[test]
    fn guid_format() {
        let g = guid_from_hash(0x0123456789abcdef0123456789abcdef);
        assert_eq!(g, "{01234567-89ab-cdef-0123-456789abcdef}");
    }
}
