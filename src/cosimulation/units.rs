//! Unit definitions: SI base units and display units, as a model declares them.

/// A unit: its name, its SI base-unit exponents (`("kg", "1")`, ...) and its display units
/// (name, factor: display value = factor x value).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UnitDefinition {
    pub name: &'static str,
    pub base: &'static [(&'static str, &'static str)],
    pub display: &'static [(&'static str, &'static str)],
}

/// The units of this crate's models: lengths, speeds and accelerations of the slider and
/// the crank (angles displayed in deg, speeds in rpm), time, force, torque, a rotary loss
/// coefficient (torque per angular speed), stress, mass, density, section properties, rotary
/// inertia and frequency. A description lists the ones its variables use.
pub const SI_UNITS: &[UnitDefinition] = &[
    UnitDefinition {
        name: "m",
        base: &[("m", "1")],
        display: &[],
    },
    UnitDefinition {
        name: "m/s",
        base: &[("m", "1"), ("s", "-1")],
        display: &[],
    },
    UnitDefinition {
        name: "m/s2",
        base: &[("m", "1"), ("s", "-2")],
        display: &[],
    },
    UnitDefinition {
        name: "rad",
        base: &[("rad", "1")],
        display: &[("deg", "57.29577951308232")],
    },
    UnitDefinition {
        name: "rad/s",
        base: &[("s", "-1"), ("rad", "1")],
        display: &[("rpm", "9.549296585513721")],
    },
    UnitDefinition {
        name: "rad/s2",
        base: &[("s", "-2"), ("rad", "1")],
        display: &[],
    },
    UnitDefinition {
        name: "rad/s3",
        base: &[("s", "-3"), ("rad", "1")],
        display: &[],
    },
    UnitDefinition {
        name: "s",
        base: &[("s", "1")],
        display: &[],
    },
    UnitDefinition {
        name: "N",
        base: &[("kg", "1"), ("m", "1"), ("s", "-2")],
        display: &[],
    },
    UnitDefinition {
        name: "N.m",
        base: &[("kg", "1"), ("m", "2"), ("s", "-2")],
        display: &[],
    },
    UnitDefinition {
        name: "N.m.s",
        base: &[("kg", "1"), ("m", "2"), ("s", "-1")],
        display: &[],
    },
    UnitDefinition {
        name: "Pa",
        base: &[("kg", "1"), ("m", "-1"), ("s", "-2")],
        display: &[],
    },
    UnitDefinition {
        name: "kg",
        base: &[("kg", "1")],
        display: &[],
    },
    UnitDefinition {
        name: "kg/m3",
        base: &[("kg", "1"), ("m", "-3")],
        display: &[],
    },
    UnitDefinition {
        name: "m2",
        base: &[("m", "2")],
        display: &[],
    },
    UnitDefinition {
        name: "m4",
        base: &[("m", "4")],
        display: &[],
    },
    UnitDefinition {
        name: "kg.m2",
        base: &[("kg", "1"), ("m", "2")],
        display: &[],
    },
    UnitDefinition {
        name: "Hz",
        base: &[("s", "-1")],
        display: &[],
    },
];
