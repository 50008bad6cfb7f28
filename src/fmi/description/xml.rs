//! The XML of the FMI 2.0 `modelDescription.xml`, element by element, in the order FMI 2.0
//! prescribes (the FMI 3.0 one: [`super::xml3`], which shares the helpers here).

use std::io;

use quick_xml::events::{BytesDecl, Event};
use quick_xml::Writer;

use super::writer::W;
use super::CAPABILITIES;
use crate::cosimulation::{
    Causality, Declarations, DefaultExperiment, EnumerationType, InitialDependencies, ModelInfo,
    Value, ValueType,
};
use crate::fmi::logging::LOG_CATEGORIES;
use crate::fmi::standard::Standard;

/// Shortest text that reads back as the same f64. Non-finite values have no xs:double text
/// that importers accept (and are never valid start values or bounds here): an error.
pub(super) fn real_text(x: f64) -> io::Result<String> {
    if x.is_finite() {
        Ok(format!("{x:?}"))
    } else {
        Err(io::Error::new(
            io::ErrorKind::InvalidData,
            format!("the value {x} is not finite and cannot be written into modelDescription.xml"),
        ))
    }
}

pub(super) fn value_text(value: Value) -> io::Result<String> {
    match value {
        Value::Real(x) => real_text(x),
        Value::Integer(n) => Ok(n.to_string()),
    }
}

pub(super) fn render(info: &ModelInfo, table: &Declarations, guid: &str) -> io::Result<String> {
    let mut w = Writer::new_with_indent(Vec::new(), b' ', 2);
    w.write_event(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None)))?;
    let n_event_indicators = "0";
    let generation_tool = concat!("flexrod ", env!("CARGO_PKG_VERSION"));
    w.create_element("fmiModelDescription")
        .with_attributes([
            ("fmiVersion", "2.0"),
            ("modelName", info.name.as_str()),
            ("guid", guid),
            ("description", info.description.as_str()),
            ("version", env!("CARGO_PKG_VERSION")),
            ("generationTool", generation_tool),
            ("variableNamingConvention", "structured"),
            ("numberOfEventIndicators", n_event_indicators),
        ])
        .write_inner_content(|w| {
            write_co_simulation(w, info)?;
            super::units::write_units(w, info.units, table)?;
            write_type_definitions(w, info.enumeration_types, Standard::Fmi2)?;
            write_log_categories(w)?;
            write_default_experiment(w, &info.default_experiment)?;
            write_model_variables(w, table)?;
            write_model_structure(w, table)
        })?;
    let mut bytes = w.into_inner();
    bytes.push(b'\n');
    String::from_utf8(bytes).map_err(|e| io::Error::new(io::ErrorKind::InvalidData, e))
}

pub(super) fn named_error(name: &str, attribute: &str, e: io::Error) -> io::Error {
    io::Error::new(e.kind(), format!("{name}: {attribute}: {e}"))
}

fn write_co_simulation(w: &mut W, info: &ModelInfo) -> io::Result<()> {
    let mut attributes = vec![("modelIdentifier", info.name.as_str())];
    attributes.extend(CAPABILITIES);
    w.create_element("CoSimulation")
        .with_attributes(attributes)
        .write_empty()?;
    Ok(())
}

/// `TypeDefinitions`: the model's enumeration types (none: no element). FMI 2.0 writes each
/// as a `SimpleType` with an `Enumeration`, FMI 3.0 as an `EnumerationType`; the items are
/// numbered 1, 2, ... in order.
pub(super) fn write_type_definitions(
    w: &mut W,
    types: &[&EnumerationType],
    standard: Standard,
) -> io::Result<()> {
    if types.is_empty() {
        return Ok(());
    }
    w.create_element("TypeDefinitions")
        .write_inner_content(|w| {
            for ty in types {
                let attributes = [("name", ty.name), ("description", ty.description)];
                match standard {
                    Standard::Fmi2 => {
                        w.create_element("SimpleType")
                            .with_attributes(attributes)
                            .write_inner_content(|w| {
                                w.create_element("Enumeration")
                                    .write_inner_content(|w| write_items(w, ty))?;
                                Ok(())
                            })?;
                    }
                    Standard::Fmi3 => {
                        w.create_element("EnumerationType")
                            .with_attributes(attributes)
                            .write_inner_content(|w| write_items(w, ty))?;
                    }
                }
            }
            Ok(())
        })?;
    Ok(())
}

fn write_items(w: &mut W, ty: &EnumerationType) -> io::Result<()> {
    for (i, item) in ty.items().iter().enumerate() {
        let value = (i + 1).to_string();
        w.create_element("Item")
            .with_attributes([
                ("name", item.name),
                ("value", value.as_str()),
                ("description", item.description),
            ])
            .write_empty()?;
    }
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

pub(super) fn write_default_experiment(w: &mut W, e: &DefaultExperiment) -> io::Result<()> {
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

fn write_model_variables(w: &mut W, table: &Declarations) -> io::Result<()> {
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

fn write_model_structure(w: &mut W, table: &Declarations) -> io::Result<()> {
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
