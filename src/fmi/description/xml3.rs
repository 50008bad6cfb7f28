//! The XML of the FMI 3.0 `modelDescription.xml` (FMI 3.0, 2.4: `fmiModelDescription` with
//! `instantiationToken`; `CoSimulation`; `UnitDefinitions`; `TypeDefinitions` with
//! `EnumerationType`; `LogCategories`; `DefaultExperiment`; `ModelVariables` as `Float64`,
//! `Int32` and `Enumeration` elements, arrays with `<Dimension start="n"/>`; `ModelStructure`
//! with `Output` and `InitialUnknown` by value reference), from the same variable table as
//! the FMI 2.0 description ([`super::xml`]).

use std::io;

use quick_xml::events::{BytesDecl, BytesText, Event};
use quick_xml::Writer;

use super::writer::W;
use super::xml::{named_error, value_text, write_default_experiment, write_type_definitions};
use crate::cosimulation::{
    Causality, Declarations, InitialDependencies, ModelInfo, Value, ValueType,
};
use crate::fmi::logging::LOG_CATEGORIES;
use crate::fmi::standard::Standard;

/// The attributes of `<CoSimulation>` (besides `modelIdentifier`); only what is implemented
/// and tested is claimed.
pub const CAPABILITIES_FMI3: [(&str, &str); 13] = [
    ("needsExecutionTool", "false"),
    ("canBeInstantiatedOnlyOncePerProcess", "false"),
    ("canGetAndSetFMUState", "true"),
    ("canSerializeFMUState", "true"),
    ("providesDirectionalDerivatives", "false"),
    ("providesAdjointDerivatives", "false"),
    ("providesPerElementDependencies", "false"),
    ("canHandleVariableCommunicationStepSize", "true"),
    ("maxOutputDerivativeOrder", "0"),
    // No intermediate update, no early return, no event mode: the scenes need none of them
    // (the crank law between communication points is fixed by inputs set at t_k).
    ("providesIntermediateUpdate", "false"),
    ("mightReturnEarlyFromDoStep", "false"),
    ("canReturnEarlyAfterIntermediateUpdate", "false"),
    ("hasEventMode", "false"),
];

pub(super) fn render(info: &ModelInfo, table: &Declarations, token: &str) -> io::Result<String> {
    let mut w = Writer::new_with_indent(Vec::new(), b' ', 2);
    w.write_event(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None)))?;
    let generation_tool = concat!("flexrod ", env!("CARGO_PKG_VERSION"));
    w.create_element("fmiModelDescription")
        .with_attributes([
            ("fmiVersion", "3.0"),
            ("modelName", info.name.as_str()),
            ("instantiationToken", token),
            ("description", info.description.as_str()),
            ("version", env!("CARGO_PKG_VERSION")),
            ("generationTool", generation_tool),
            ("variableNamingConvention", "structured"),
        ])
        .write_inner_content(|w| {
            let mut attributes = vec![("modelIdentifier", info.name.as_str())];
            attributes.extend(CAPABILITIES_FMI3);
            w.create_element("CoSimulation")
                .with_attributes(attributes)
                .write_empty()?;
            super::units::write_units(w, info.units, table)?;
            write_type_definitions(w, info.enumeration_types, Standard::Fmi3)?;
            write_log_categories(w)?;
            write_default_experiment(w, &info.default_experiment)?;
            write_model_variables(w, table)?;
            write_model_structure(w, table)
        })?;
    let mut bytes = w.into_inner();
    bytes.push(b'\n');
    String::from_utf8(bytes).map_err(|e| io::Error::new(io::ErrorKind::InvalidData, e))
}

/// The log categories, their descriptions with the FMI 3.0 status names.
fn write_log_categories(w: &mut W) -> io::Result<()> {
    w.create_element("LogCategories").write_inner_content(|w| {
        for (name, description) in LOG_CATEGORIES {
            let description = description.replace("fmi2", "fmi3");
            w.create_element("Category")
                .with_attributes([("name", name), ("description", description.as_str())])
                .write_empty()?;
        }
        Ok(())
    })?;
    Ok(())
}

fn write_model_variables(w: &mut W, table: &Declarations) -> io::Result<()> {
    w.create_element("ModelVariables")
        .write_inner_content(|w| {
            for v in table.variables() {
                let vr = v.value_reference.to_string();
                // Status names in descriptions are those of the standard's interface
                // (fmi3Discard, ...: `Standard::interface`).
                let description = &v.description;
                let mut attributes = vec![
                    ("name", v.name.as_str()),
                    ("valueReference", vr.as_str()),
                    ("description", description.as_str()),
                    ("causality", v.causality.as_str()),
                    ("variability", v.variability.as_str()),
                ];
                if let Some(initial) = v.initial {
                    attributes.push(("initial", initial.as_str()));
                }
                let (element, declared_type) = match v.value_type {
                    ValueType::Real { unit, display_unit } => {
                        if let Some(u) = unit {
                            attributes.push(("unit", u));
                        }
                        if let Some(d) = display_unit {
                            attributes.push(("displayUnit", d));
                        }
                        ("Float64", None)
                    }
                    ValueType::Integer => ("Int32", None),
                    ValueType::Enumeration(ty) => ("Enumeration", Some(ty.name)),
                };
                if let Some(ty) = declared_type {
                    attributes.push(("declaredType", ty));
                }
                let text = |value: Option<Value>| value.map(value_text).transpose();
                let start = text(v.start).map_err(|e| named_error(&v.name, "start", e))?;
                let min = text(v.min).map_err(|e| named_error(&v.name, "min", e))?;
                let max = text(v.max).map_err(|e| named_error(&v.name, "max", e))?;
                for (name, value) in [("min", &min), ("max", &max), ("start", &start)] {
                    if let Some(value) = value {
                        attributes.push((name, value.as_str()));
                    }
                }
                let element = w.create_element(element).with_attributes(attributes);
                match v.dimension {
                    None => {
                        element.write_empty()?;
                    }
                    Some(n) => {
                        let n = n.to_string();
                        element.write_inner_content(|w| {
                            w.create_element("Dimension")
                                .with_attribute(("start", n.as_str()))
                                .write_empty()?;
                            Ok(())
                        })?;
                    }
                }
            }
            Ok(())
        })?;
    Ok(())
}

fn write_model_structure(w: &mut W, table: &Declarations) -> io::Result<()> {
    let knowns: Vec<u32> = table
        .variables()
        .iter()
        .filter(|v| matches!(v.causality, Causality::Input | Causality::Parameter))
        .map(|v| v.value_reference)
        .collect();
    let list = |vrs: &[u32]| vrs.iter().map(u32::to_string).collect::<Vec<_>>().join(" ");
    let unknown = |w: &mut W, element: &str, vr: u32, dependencies: &str| -> io::Result<()> {
        let vr = vr.to_string();
        w.create_element(element)
            .with_attributes([
                ("valueReference", vr.as_str()),
                ("dependencies", dependencies),
            ])
            .write_empty()?;
        Ok(())
    };
    w.create_element("ModelStructure")
        .write_inner_content(|w| {
            w.write_event(Event::Comment(BytesText::new(
                " outputs refer to the end of the last step: no direct feedthrough ",
            )))?;
            for v in table.variables() {
                if v.causality == Causality::Output {
                    unknown(w, "Output", v.value_reference, "")?;
                }
            }
            for v in table.variables() {
                if !matches!(
                    v.causality,
                    Causality::Output | Causality::CalculatedParameter
                ) {
                    continue;
                }
                let dependencies = match v.initial_dependencies {
                    InitialDependencies::None => String::new(),
                    InitialDependencies::All => list(&knowns),
                    InitialDependencies::Named(names) => {
                        let mut vrs: Vec<u32> = names
                            .iter()
                            .filter_map(|n| table.by_name(n).map(|v| v.value_reference))
                            .collect();
                        vrs.sort_unstable();
                        list(&vrs)
                    }
                };
                unknown(w, "InitialUnknown", v.value_reference, &dependencies)?;
            }
            Ok(())
        })?;
    Ok(())
}
