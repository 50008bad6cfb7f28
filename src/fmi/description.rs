//! `modelDescription.xml`, written from the variable table, and the GUID derived from it.
//!
//! The GUID is the FNV-1a 128-bit hash of the description rendered with an all-zero GUID,
//! formatted `{8-4-4-4-12}`: the same scene and the same code give the same GUID, any change
//! of a variable, unit, start value or capability gives another.

use std::io;

use quick_xml::events::{BytesDecl, Event};
use quick_xml::Writer;

use super::logging::LOG_CATEGORIES;
use super::variables::{
    Causality, InitialDependencies, Value, ValueType, VariableTable, ROD_MODEL, ROD_REFERENCE,
};
use crate::error::ModelError;
use crate::scene::Scene;

/// The FMU's capability flags, written into `<CoSimulation>` (fmu-contract.md).
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

/// Unit definitions: (name, base unit exponents and factor, display units (name, factor)).
struct UnitDef {
    name: &'static str,
    base: &'static [(&'static str, &'static str)],
    display: &'static [(&'static str, &'static str)],
}

const UNITS: [UnitDef; 12] = [
    UnitDef {
        name: "m",
        base: &[("m", "1")],
        display: &[],
    },
    UnitDef {
        name: "m/s",
        base: &[("m", "1"), ("s", "-1")],
        display: &[],
    },
    UnitDef {
        name: "rad",
        base: &[("rad", "1")],
        display: &[("deg", "57.29577951308232")],
    },
    UnitDef {
        name: "rad/s",
        base: &[("s", "-1"), ("rad", "1")],
        display: &[("rpm", "9.549296585513721")],
    },
    UnitDef {
        name: "N",
        base: &[("kg", "1"), ("m", "1"), ("s", "-2")],
        display: &[],
    },
    UnitDef {
        name: "N.m",
        base: &[("kg", "1"), ("m", "2"), ("s", "-2")],
        display: &[],
    },
    UnitDef {
        name: "Pa",
        base: &[("kg", "1"), ("m", "-1"), ("s", "-2")],
        display: &[],
    },
    UnitDef {
        name: "kg",
        base: &[("kg", "1")],
        display: &[],
    },
    UnitDef {
        name: "kg/m3",
        base: &[("kg", "1"), ("m", "-3")],
        display: &[],
    },
    UnitDef {
        name: "m2",
        base: &[("m", "2")],
        display: &[],
    },
    UnitDef {
        name: "m4",
        base: &[("m", "4")],
        display: &[],
    },
    UnitDef {
        name: "Hz",
        base: &[("s", "-1")],
        display: &[],
    },
];

/// A generated model description.
#[derive(Clone)]
pub struct ModelDescription {
    /// The XML text.
    pub xml: String,
    /// `{8-4-4-4-12}`.
    pub guid: String,
    /// The table the description was written from.
    pub table: VariableTable,
}

impl ModelDescription {
    /// The description of `scene` (builds the model once to count the natural frequencies).
    pub fn for_scene(scene: &Scene) -> Result<ModelDescription, ModelError> {
        let table = VariableTable::for_scene(scene)?;
        ModelDescription::new(scene, table)
    }

    /// The description of `scene` with the given table.
    pub fn new(scene: &Scene, table: VariableTable) -> Result<ModelDescription, ModelError> {
        let placeholder = "{00000000-0000-0000-0000-000000000000}";
        let unhashed = render(scene, &table, placeholder).map_err(write_error)?;
        let guid = guid_from_hash(fnv1a_128(unhashed.as_bytes()));
        let xml = render(scene, &table, &guid).map_err(write_error)?;
        Ok(ModelDescription { xml, guid, table })
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

/// FNV-1a, 128 bits.
pub fn fnv1a_128(bytes: &[u8]) -> u128 {
    const OFFSET: u128 = 0x6c62_272e_07bb_0142_62b8_2175_6295_c58d;
    const PRIME: u128 = 0x0000_0000_0100_0000_0000_0000_0000_013b;
    bytes
        .iter()
        .fold(OFFSET, |h, &b| (h ^ u128::from(b)).wrapping_mul(PRIME))
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

/// Shortest text that reads back as the same f64. Non-finite values have no xs:double text
/// that importers accept (and are never valid start values or bounds here): an error.
fn real_text(x: f64) -> io::Result<String> {
    if x.is_finite() {
        Ok(format!("{x:?}"))
    } else {
        Err(io::Error::new(
            io::ErrorKind::InvalidData,
            format!("the value {x} is not finite and cannot be written into modelDescription.xml"),
        ))
    }
}

fn value_text(value: Value) -> io::Result<String> {
    match value {
        Value::Real(x) => real_text(x),
        Value::Integer(n) => Ok(n.to_string()),
    }
}

fn render(scene: &Scene, table: &VariableTable, guid: &str) -> io::Result<String> {
    let mut w = Writer::new_with_indent(Vec::new(), b' ', 2);
    w.write_event(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None)))?;
    let n_event_indicators = "0";
    let generation_tool = concat!("flexrod ", env!("CARGO_PKG_VERSION"));
    w.create_element("fmiModelDescription")
        .with_attributes([
            ("fmiVersion", "2.0"),
            ("modelName", scene.name.as_str()),
            ("guid", guid),
            ("description", scene.description.as_str()),
            ("version", env!("CARGO_PKG_VERSION")),
            ("generationTool", generation_tool),
            ("variableNamingConvention", "structured"),
            ("numberOfEventIndicators", n_event_indicators),
        ])
        .write_inner_content(|w| {
            write_co_simulation(w, scene)?;
            write_units(w, table)?;
            write_type_definitions(w)?;
            write_log_categories(w)?;
            write_default_experiment(w, scene)?;
            write_model_variables(w, table)?;
            write_model_structure(w, table)
        })?;
    let mut bytes = w.into_inner();
    bytes.push(b'\n');
    String::from_utf8(bytes).map_err(|e| io::Error::new(io::ErrorKind::InvalidData, e))
}

type W = Writer<Vec<u8>>;

fn named_error(name: &str, attribute: &str, e: io::Error) -> io::Error {
    io::Error::new(e.kind(), format!("{name}: {attribute}: {e}"))
}

fn write_co_simulation(w: &mut W, scene: &Scene) -> io::Result<()> {
    let mut attributes = vec![("modelIdentifier", model_identifier(scene))];
    attributes.extend(CAPABILITIES);
    w.create_element("CoSimulation")
        .with_attributes(attributes)
        .write_empty()?;
    Ok(())
}

fn write_units(w: &mut W, table: &VariableTable) -> io::Result<()> {
    let used = |unit: &str| {
        table
            .variables()
            .iter()
            .any(|v| matches!(v.value_type, ValueType::Real { unit: Some(u), .. } if u == unit))
    };
    w.create_element("UnitDefinitions")
        .write_inner_content(|w| {
            for unit in UNITS.iter().filter(|u| used(u.name)) {
                w.create_element("Unit")
                    .with_attribute(("name", unit.name))
                    .write_inner_content(|w| {
                        w.create_element("BaseUnit")
                            .with_attributes(unit.base.iter().copied())
                            .write_empty()?;
                        for (name, factor) in unit.display {
                            w.create_element("DisplayUnit")
                                .with_attributes([("name", *name), ("factor", *factor)])
                                .write_empty()?;
                        }
                        Ok(())
                    })?;
            }
            Ok(())
        })?;
    Ok(())
}

fn write_type_definitions(w: &mut W) -> io::Result<()> {
    w.create_element("TypeDefinitions")
        .write_inner_content(|w| {
            for ty in [&ROD_MODEL, &ROD_REFERENCE] {
                w.create_element("SimpleType")
                    .with_attributes([("name", ty.name), ("description", ty.description)])
                    .write_inner_content(|w| {
                        w.create_element("Enumeration").write_inner_content(|w| {
                            for (i, (name, description)) in ty.items.iter().enumerate() {
                                let value = (i + 1).to_string();
                                w.create_element("Item")
                                    .with_attributes([
                                        ("name", *name),
                                        ("value", value.as_str()),
                                        ("description", *description),
                                    ])
                                    .write_empty()?;
                            }
                            Ok(())
                        })?;
                        Ok(())
                    })?;
            }
            Ok(())
        })?;
    Ok(())
}

fn write_log_categories(w: &mut W) -> io::Result<()> {
    w.create_element("LogCategories").write_inner_content(|w| {
        for (name, description) in LOG_CATEGORIES {
            w.create_element("Category")
                .with_attributes([("name", name), ("description", description)])
                .write_empty()?;
        }
        Ok(())
    })?;
    Ok(())
}

fn write_default_experiment(w: &mut W, scene: &Scene) -> io::Result<()> {
    let e = &scene.experiment;
    let (start, stop, step) = (
        real_text(e.start_time)?,
        real_text(e.stop_time)?,
        real_text(e.step_size)?,
    );
    w.create_element("DefaultExperiment")
        .with_attributes([
            ("startTime", start.as_str()),
            ("stopTime", stop.as_str()),
            ("stepSize", step.as_str()),
        ])
        .write_empty()?;
    Ok(())
}

fn write_model_variables(w: &mut W, table: &VariableTable) -> io::Result<()> {
    w.create_element("ModelVariables")
        .write_inner_content(|w| {
            for (i, v) in table.variables().iter().enumerate() {
                w.write_event(Event::Comment(quick_xml::events::BytesText::new(&format!(
                    " index {} ",
                    i + 1
                ))))?;
                let vr = v.value_reference.to_string();
                let mut attributes = vec![
                    ("name", v.name.as_str()),
                    ("valueReference", vr.as_str()),
                    ("description", v.description.as_str()),
                    ("causality", v.causality.as_str()),
                    ("variability", v.variability.as_str()),
                ];
                if let Some(initial) = v.initial {
                    attributes.push(("initial", initial.as_str()));
                }
                let text = |value: Option<Value>| value.map(value_text).transpose();
                let start = text(v.start).map_err(|e| named_error(&v.name, "start", e))?;
                let min = text(v.min).map_err(|e| named_error(&v.name, "min", e))?;
                let max = text(v.max).map_err(|e| named_error(&v.name, "max", e))?;
                w.create_element("ScalarVariable")
                    .with_attributes(attributes)
                    .write_inner_content(|w| {
                        let (element, mut type_attributes) = match v.value_type {
                            ValueType::Real { unit, display_unit } => {
                                let mut a = Vec::new();
                                if let Some(u) = unit {
                                    a.push(("unit", u));
                                }
                                if let Some(d) = display_unit {
                                    a.push(("displayUnit", d));
                                }
                                ("Real", a)
                            }
                            ValueType::Integer => ("Integer", Vec::new()),
                            ValueType::Enumeration(ty) => {
                                ("Enumeration", vec![("declaredType", ty.name)])
                            }
                        };
                        if let Some(m) = &min {
                            type_attributes.push(("min", m.as_str()));
                        }
                        if let Some(m) = &max {
                            type_attributes.push(("max", m.as_str()));
                        }
                        if let Some(s) = &start {
                            type_attributes.push(("start", s.as_str()));
                        }
                        w.create_element(element)
                            .with_attributes(type_attributes)
                            .write_empty()?;
                        Ok(())
                    })?;
            }
            Ok(())
        })?;
    Ok(())
}

fn write_model_structure(w: &mut W, table: &VariableTable) -> io::Result<()> {
    let knowns: Vec<usize> = table
        .variables()
        .iter()
        .enumerate()
        .filter(|(_, v)| matches!(v.causality, Causality::Input | Causality::Parameter))
        .map(|(i, _)| i + 1)
        .collect();
    let list = |indices: &[usize]| {
        indices
            .iter()
            .map(usize::to_string)
            .collect::<Vec<_>>()
            .join(" ")
    };
    let unknown = |w: &mut W, index: usize, dependencies: &str| -> io::Result<()> {
        let index = index.to_string();
        w.create_element("Unknown")
            .with_attributes([("index", index.as_str()), ("dependencies", dependencies)])
            .write_empty()?;
        Ok(())
    };
    w.create_element("ModelStructure")
        .write_inner_content(|w| {
            // At communication points the outputs do not depend on the inputs set there:
            // they refer to the end of the last step (no direct feedthrough).
            w.create_element("Outputs").write_inner_content(|w| {
                for (i, v) in table.variables().iter().enumerate() {
                    if v.causality == Causality::Output {
                        unknown(w, i + 1, "")?;
                    }
                }
                Ok(())
            })?;
            w.create_element("InitialUnknowns")
                .write_inner_content(|w| {
                    for (i, v) in table.variables().iter().enumerate() {
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
                                let mut indices: Vec<usize> = names
                                    .iter()
                                    .filter_map(|n| table.index_of_name(n))
                                    .collect();
                                indices.sort_unstable();
                                list(&indices)
                            }
                        };
                        unknown(w, i + 1, &dependencies)?;
                    }
                    Ok(())
                })?;
            Ok(())
        })?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv_reference_values() {
        // FNV-1a 128 of "" is the offset basis; of "a" a published test vector.
        assert_eq!(fnv1a_128(b""), 0x6c62272e07bb014262b821756295c58d);
        assert_eq!(fnv1a_128(b"a"), 0xd228cb696f1a8caf78912b704e4a8964);
    }

    #[test]
    fn guid_format() {
        let g = guid_from_hash(0x0123456789abcdef0123456789abcdef);
        assert_eq!(g, "{01234567-89ab-cdef-0123-456789abcdef}");
    }

    #[test]
    fn description_depends_on_start_values() {
        let scene = Scene::benchmark();
        let a = ModelDescription::new(&scene, VariableTable::new(&scene, 6)).unwrap();
        let mut other = scene.clone();
        other.rod.length = 0.31;
        let b = ModelDescription::new(&other, VariableTable::new(&other, 6)).unwrap();
        assert_ne!(a.guid, b.guid);
        assert!(a.xml.contains(&a.guid));
        assert!(a.xml.contains("canSerializeFMUstate=\"true\""));
        assert_eq!(a.xml.matches("canRunAsynchronuously").count(), 1);
    }

    #[test]
    fn non_finite_values_are_not_written() {
        let mut scene = Scene::benchmark();
        scene.experiment.stop_time = f64::INFINITY;
        let e = ModelDescription::new(&scene, VariableTable::new(&scene, 6))
            .err()
            .expect("an infinite stop time is rejected");
        assert!(e.to_string().contains("not finite"), "{e}");
    }

    #[test]
    fn parameter_bounds_are_declared() {
        let scene = Scene::benchmark();
        let xml = ModelDescription::new(&scene, VariableTable::new(&scene, 6))
            .unwrap()
            .xml;
        assert!(
            xml.contains("<Real unit=\"m\" min=\"0.0\" start=\"0.3048\"/>"),
            "{xml}"
        );
        assert!(
            xml.contains("<Integer min=\"1\" max=\"4096\" start=\"8\"/>"),
            "{xml}"
        );
    }
}
