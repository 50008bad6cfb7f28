//! `UnitDefinitions`: the model's units its variables use, with their SI base units and
//! display units.

use std::io;

use super::writer::W;
use crate::cosimulation::{Declarations, UnitDefinition, ValueType};

pub(super) fn write_units(
    w: &mut W,
    units: &[UnitDefinition],
    table: &Declarations,
) -> io::Result<()> {
    let used = |unit: &str| {
        table
            .variables()
            .iter()
            .any(|v| matches!(v.value_type, ValueType::Real { unit: Some(u), .. } if u == unit))
    };
    if !units.iter().any(|u| used(u.name)) {
        return Ok(());
    }
    w.create_element("UnitDefinitions")
        .write_inner_content(|w| {
            for unit in units.iter().filter(|u| used(u.name)) {
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
