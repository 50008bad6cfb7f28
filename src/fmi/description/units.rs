//! `UnitDefinitions`: the units the variables use, with their SI base units and display units.

use std::io;

use super::xml::W;
use crate::fmi::variables::{ValueType, VariableTable};

/// Unit definitions: (name, base unit exponents and factor, display units (name, factor)).
struct UnitDef {
    name: &'static str,
    base: &'static [(&'static str, &'static str)],
    display: &'static [(&'static str, &'static str)],
}

const UNITS: [UnitDef; 17] = [
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
        name: "m/s2",
        base: &[("m", "1"), ("s", "-2")],
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
        name: "rad/s2",
        base: &[("s", "-2"), ("rad", "1")],
        display: &[],
    },
    UnitDef {
        name: "rad/s3",
        base: &[("s", "-3"), ("rad", "1")],
        display: &[],
    },
    UnitDef {
        name: "s",
        base: &[("s", "1")],
        display: &[],
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
        name: "kg.m2",
        base: &[("kg", "1"), ("m", "2")],
        display: &[],
    },
    UnitDef {
        name: "Hz",
        base: &[("s", "-1")],
        display: &[],
    },
];

pub(super) fn write_units(w: &mut W, table: &VariableTable) -> io::Result<()> {
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
