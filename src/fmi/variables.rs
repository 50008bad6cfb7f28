//! The variable table: the one source of truth for the FMU's variables.
//!
//! `modelDescription.xml`, the GUID, the get/set dispatch of the C ABI, the packager's
//! documentation page and the reference CSV of the packager all read this table. Names,
//! units and signs are those of `fmu-contract.md`.
//!
//! Value references are fixed per variable (inputs 1.., outputs 10.., parameters 100..,
//! `rod.frequency[k]` = 200 + k), so a variable keeps its reference when a scene leaves
//! others out.

use crate::error::ModelError;
use crate::mechanism::Outputs;
use crate::scene::{ReferenceKind, RodModelKind, Scene};
use crate::simulation::Simulation;

/// `fmi2ValueReference`.
pub type ValueReference = u32;

/// Value reference of `rod.frequency[1]` minus one.
pub const FREQUENCY_VR_BASE: ValueReference = 200;

/// FMI 2.0 causality.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Causality {
    Input,
    Output,
    Parameter,
    CalculatedParameter,
}

impl Causality {
    pub fn as_str(self) -> &'static str {
        match self {
            Causality::Input => "input",
            Causality::Output => "output",
            Causality::Parameter => "parameter",
            Causality::CalculatedParameter => "calculatedParameter",
        }
    }
}

/// FMI 2.0 variability (only those used here).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Variability {
    Fixed,
    Continuous,
}

impl Variability {
    pub fn as_str(self) -> &'static str {
        match self {
            Variability::Fixed => "fixed",
            Variability::Continuous => "continuous",
        }
    }
}

/// FMI 2.0 `initial` (absent for inputs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Initial {
    Exact,
    Calculated,
}

impl Initial {
    pub fn as_str(self) -> &'static str {
        match self {
            Initial::Exact => "exact",
            Initial::Calculated => "calculated",
        }
    }
}

/// An enumeration type: its items are numbered 1, 2, ... in this order.
#[derive(Debug, PartialEq, Eq)]
pub struct EnumerationType {
    pub name: &'static str,
    pub description: &'static str,
    /// (item name, item description).
    pub items: &'static [(&'static str, &'static str)],
}

impl EnumerationType {
    /// "1 (ffr), 2 (segments)", for messages.
    pub fn allowed_text(&self) -> String {
        let items: Vec<String> = self
            .items
            .iter()
            .enumerate()
            .map(|(i, (name, _))| format!("{} ({name})", i + 1))
            .collect();
        items.join(", ")
    }
}

/// `rod.model`.
pub static ROD_MODEL: EnumerationType = EnumerationType {
    name: "RodModel",
    description: "Which model computes the connecting rod",
    items: &[
        ("ffr", "Floating frame of reference with component modes"),
        (
            "segments",
            "Rigid segments joined by rotational springs (finite segment method)",
        ),
    ],
};

/// `rod.reference`.
pub static ROD_REFERENCE: EnumerationType = EnumerationType {
    name: "RodReference",
    description: "Reference conditions of the FFR rod",
    items: &[
        (
            "simply_supported",
            "u = v = 0 at B, v = 0 at C; frame at B, x axis through C",
        ),
        (
            "mean_axis",
            "Free-free modes without the rigid-body modes; frame at the centre of mass",
        ),
        (
            "body_fixed_mid",
            "All coordinates of the middle node zero (even number of elements)",
        ),
        ("cantilever", "All coordinates of the B node zero"),
    ],
};

/// FMI 2.0 type of a variable, with its unit attributes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ValueType {
    Real {
        /// Unit (declared in `UnitDefinitions`); `None` for dimensionless.
        unit: Option<&'static str>,
        /// Display unit (deg for angles, rpm for speeds).
        display_unit: Option<&'static str>,
    },
    Integer,
    Enumeration(&'static EnumerationType),
}

impl ValueType {
    /// Which `fmi2Get*`/`fmi2Set*` family serves this type.
    pub fn family(self) -> Family {
        match self {
            ValueType::Real { .. } => Family::Real,
            ValueType::Integer | ValueType::Enumeration(_) => Family::Integer,
        }
    }
}

/// The `fmi2Get*`/`fmi2Set*` families.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Family {
    Real,
    Integer,
    Boolean,
    String,
}

impl Family {
    pub fn name(self) -> &'static str {
        match self {
            Family::Real => "Real",
            Family::Integer => "Integer",
            Family::Boolean => "Boolean",
            Family::String => "String",
        }
    }
}

/// A start value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    Real(f64),
    Integer(i32),
}

/// The inputs an instance stores between communication points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InputSlot {
    CrankAngle,
    CrankSpeed,
    SliderForce,
}

/// Reads one output from the simulation's outputs.
pub type OutputGetter = fn(&Outputs) -> f64;

/// Where a variable's value lives and how to read or write it.
#[derive(Clone, Copy)]
pub enum Access {
    /// An input kept by the instance.
    Input(InputSlot),
    /// An output of the simulation.
    Output(OutputGetter),
    /// A Real parameter stored in the instance's scene.
    RealParameter {
        get: fn(&Scene) -> f64,
        set: fn(&mut Scene, f64),
    },
    /// An Integer or Enumeration parameter stored in the instance's scene. `set` returns
    /// the allowed range when the value cannot be stored.
    IntegerParameter {
        get: fn(&Scene) -> i32,
        set: fn(&mut Scene, i32) -> Result<(), String>,
    },
    /// `rod.frequency[k]`: index k - 1 into `Simulation::frequencies_hz`.
    Frequency(usize),
}

/// Which knowns an unknown depends on during initialization (`ModelStructure/InitialUnknowns`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InitialDependencies {
    /// Constant during initialization (e.g. the deflection of the undeformed rod).
    None,
    /// Every input and every parameter.
    All,
    /// The named inputs and parameters (names absent from the table are skipped).
    Named(&'static [&'static str]),
}

/// One scalar variable.
#[derive(Clone)]
pub struct Variable {
    pub name: String,
    pub value_reference: ValueReference,
    pub description: String,
    pub causality: Causality,
    pub variability: Variability,
    pub initial: Option<Initial>,
    pub value_type: ValueType,
    pub start: Option<Value>,
    /// `min` and `max` attributes (closed bounds; FMI 2.0 has no open ones).
    pub min: Option<Value>,
    pub max: Option<Value>,
    pub access: Access,
    /// Only for outputs and calculated parameters.
    pub initial_dependencies: InitialDependencies,
}

/// All variables of one FMU, in modelDescription.xml order, with an index by value reference.
#[derive(Clone)]
pub struct VariableTable {
    variables: Vec<Variable>,
    /// `by_vr[vr]` = position + 1 in `variables`, 0 if no variable has that reference.
    by_vr: Vec<u16>,
}

const RAD: ValueType = ValueType::Real {
    unit: Some("rad"),
    display_unit: Some("deg"),
};
const RAD_PER_S: ValueType = ValueType::Real {
    unit: Some("rad/s"),
    display_unit: Some("rpm"),
};

const fn real(unit: &'static str) -> ValueType {
    ValueType::Real {
        unit: Some(unit),
        display_unit: None,
    }
}

const DIMENSIONLESS: ValueType = ValueType::Real {
    unit: None,
    display_unit: None,
};

/// Parameters the rod's natural frequencies depend on.
const FREQUENCY_KNOWNS: &[&str] = &[
    "rod.length",
    "rod.youngs_modulus",
    "rod.density",
    "rod.area",
    "rod.area_moment",
    "rod.model",
    "rod.elements",
    "rod.reference",
];

fn usize_to_i32(n: usize) -> i32 {
    i32::try_from(n).unwrap_or(i32::MAX)
}

fn non_negative(value: i32) -> Result<usize, String> {
    usize::try_from(value).map_err(|_| "an integer >= 0".to_string())
}

/// `rod.elements`: the core's mesh takes 1..=ELEMENTS_MAX elements.
pub const ELEMENTS_MAX: i32 = 4096;

fn element_count(value: i32) -> Result<usize, String> {
    if (1..=ELEMENTS_MAX).contains(&value) {
        non_negative(value)
    } else {
        Err(format!("an integer in 1..={ELEMENTS_MAX}"))
    }
}

fn model_index(kind: RodModelKind) -> i32 {
    match kind {
        RodModelKind::Ffr => 1,
        RodModelKind::Segments => 2,
    }
}

fn reference_index(kind: ReferenceKind) -> i32 {
    match kind {
        ReferenceKind::SimplySupported => 1,
        ReferenceKind::MeanAxis => 2,
        ReferenceKind::BodyFixedMid => 3,
        ReferenceKind::Cantilever => 4,
    }
}

fn set_model(scene: &mut Scene, value: i32) -> Result<(), String> {
    scene.rod.model = match value {
        1 => RodModelKind::Ffr,
        2 => RodModelKind::Segments,
        _ => return Err(ROD_MODEL.allowed_text()),
    };
    Ok(())
}

fn set_reference(scene: &mut Scene, value: i32) -> Result<(), String> {
    scene.rod.reference = match value {
        1 => ReferenceKind::SimplySupported,
        2 => ReferenceKind::MeanAxis,
        3 => ReferenceKind::BodyFixedMid,
        4 => ReferenceKind::Cantilever,
        _ => return Err(ROD_REFERENCE.allowed_text()),
    };
    Ok(())
}

struct Builder<'a> {
    scene: &'a Scene,
    variables: Vec<Variable>,
}

impl Builder<'_> {
    /// `min`/`max` of the variable added last.
    fn bounds(&mut self, min: Option<Value>, max: Option<Value>) {
        if let Some(v) = self.variables.last_mut() {
            v.min = min;
            v.max = max;
        }
    }

    /// `min="0"` on a Real parameter that must be positive: FMI 2.0 has no open bound, so 0
    /// itself passes the declared range and is rejected at initialization (`fmi2Error` at
    /// `fmi2ExitInitializationMode` naming the parameter).
    fn positive(&mut self) {
        self.bounds(Some(Value::Real(0.0)), None);
    }

    /// `min="0"`: zero allowed.
    fn non_negative(&mut self) {
        self.bounds(Some(Value::Real(0.0)), None);
    }

    fn input(
        &mut self,
        name: &str,
        vr: ValueReference,
        ty: ValueType,
        start: f64,
        slot: InputSlot,
        description: &str,
    ) {
        self.variables.push(Variable {
            name: name.into(),
            value_reference: vr,
            description: description.into(),
            causality: Causality::Input,
            variability: Variability::Continuous,
            initial: None,
            value_type: ty,
            start: Some(Value::Real(start)),
            min: None,
            max: None,
            access: Access::Input(slot),
            initial_dependencies: InitialDependencies::None,
        });
    }

    fn output(
        &mut self,
        name: &str,
        vr: ValueReference,
        ty: ValueType,
        get: OutputGetter,
        deps: InitialDependencies,
        description: &str,
    ) {
        self.variables.push(Variable {
            name: name.into(),
            value_reference: vr,
            description: description.into(),
            causality: Causality::Output,
            variability: Variability::Continuous,
            initial: Some(Initial::Calculated),
            value_type: ty,
            start: None,
            min: None,
            max: None,
            access: Access::Output(get),
            initial_dependencies: deps,
        });
    }

    fn real_parameter(
        &mut self,
        name: &str,
        vr: ValueReference,
        ty: ValueType,
        get: fn(&Scene) -> f64,
        set: fn(&mut Scene, f64),
        description: &str,
    ) {
        self.variables.push(Variable {
            name: name.into(),
            value_reference: vr,
            description: description.into(),
            causality: Causality::Parameter,
            variability: Variability::Fixed,
            initial: Some(Initial::Exact),
            value_type: ty,
            start: Some(Value::Real(get(self.scene))),
            min: None,
            max: None,
            access: Access::RealParameter { get, set },
            initial_dependencies: InitialDependencies::None,
        });
    }

    fn integer_parameter(
        &mut self,
        name: &str,
        vr: ValueReference,
        ty: ValueType,
        get: fn(&Scene) -> i32,
        set: fn(&mut Scene, i32) -> Result<(), String>,
        description: &str,
    ) {
        self.variables.push(Variable {
            name: name.into(),
            value_reference: vr,
            description: description.into(),
            causality: Causality::Parameter,
            variability: Variability::Fixed,
            initial: Some(Initial::Exact),
            value_type: ty,
            start: Some(Value::Integer(get(self.scene))),
            min: None,
            max: None,
            access: Access::IntegerParameter { get, set },
            initial_dependencies: InitialDependencies::None,
        });
    }
}

impl VariableTable {
    /// The table of `scene`, with `n_frequencies` calculated parameters `rod.frequency[k]`.
    pub fn new(scene: &Scene, n_frequencies: usize) -> VariableTable {
        use InitialDependencies as D;
        let mut b = Builder {
            scene,
            variables: Vec::new(),
        };
        let exp = &scene.experiment;
        let out = &scene.outputs;

        // Inputs. Start values: the default experiment (constant crank speed from t = start).
        b.input(
            "crank.angle",
            1,
            RAD,
            exp.crank_speed * exp.start_time,
            InputSlot::CrankAngle,
            "Crank angle theta at the communication point",
        );
        b.input("crank.speed", 2, RAD_PER_S, exp.crank_speed, InputSlot::CrankSpeed,
            "Crank speed omega at the communication point (order-1 input derivative: crank acceleration)");
        if out.slider_force {
            b.input(
                "slider.force",
                3,
                real("N"),
                0.0,
                InputSlot::SliderForce,
                "External force on the slider along +x",
            );
        }

        // Outputs. No direct feedthrough: outputs refer to the end of the last step.
        b.output(
            "rod.deflection",
            10,
            real("m"),
            |o| o.deflection,
            D::None,
            "Midpoint deflection v_mid from the chord B->C, positive to the left of B->C",
        );
        b.output(
            "rod.deflection_rel",
            11,
            DIMENSIONLESS,
            |o| o.deflection_rel,
            D::None,
            "v_mid / L",
        );
        if out.pin_forces {
            b.output(
                "pinB.force_x",
                12,
                real("N"),
                |o| o.pin_b_force[0],
                D::All,
                "Force of the rod on the crank pin B, global x",
            );
            b.output(
                "pinB.force_y",
                13,
                real("N"),
                |o| o.pin_b_force[1],
                D::All,
                "Force of the rod on the crank pin B, global y",
            );
            b.output(
                "pinC.force_x",
                14,
                real("N"),
                |o| o.pin_c_force[0],
                D::All,
                "Force of the rod on the slider at C, global x",
            );
            b.output(
                "pinC.force_y",
                15,
                real("N"),
                |o| o.pin_c_force[1],
                D::All,
                "Force of the rod on the slider at C, global y",
            );
        }
        if out.crank_torque {
            b.output(
                "crank.torque",
                16,
                real("N.m"),
                |o| o.crank_torque,
                D::All,
                "Drive torque about A that imposes the crank motion (massless crank)",
            );
        }
        if out.slider {
            b.output(
                "slider.position",
                17,
                real("m"),
                |o| o.slider_position,
                D::Named(&["crank.angle", "crank.length", "rod.length"]),
                "Slider position x_C",
            );
            b.output(
                "slider.velocity",
                18,
                real("m/s"),
                |o| o.slider_velocity,
                D::Named(&["crank.angle", "crank.speed", "crank.length", "rod.length"]),
                "Slider velocity",
            );
        }

        // Parameters (fixed: settable until fmi2ExitInitializationMode).
        b.real_parameter(
            "crank.length",
            100,
            real("m"),
            |s| s.crank.length,
            |s, v| s.crank.length = v,
            "Crank length r",
        );
        b.positive();
        b.real_parameter(
            "rod.length",
            101,
            real("m"),
            |s| s.rod.length,
            |s, v| s.rod.length = v,
            "Rod length L",
        );
        b.positive();
        b.real_parameter(
            "rod.youngs_modulus",
            102,
            real("Pa"),
            |s| s.rod.youngs_modulus,
            |s, v| s.rod.youngs_modulus = v,
            "Young's modulus E",
        );
        b.positive();
        b.real_parameter(
            "rod.density",
            103,
            real("kg/m3"),
            |s| s.rod.density,
            |s, v| s.rod.density = v,
            "Density rho",
        );
        b.positive();
        b.real_parameter(
            "rod.area",
            104,
            real("m2"),
            |s| s.rod.area,
            |s, v| s.rod.area = v,
            "Cross-section area A",
        );
        b.positive();
        b.real_parameter(
            "rod.area_moment",
            105,
            real("m4"),
            |s| s.rod.area_moment,
            |s, v| s.rod.area_moment = v,
            "Second moment of area I",
        );
        b.positive();
        b.real_parameter(
            "rod.damping_ratio",
            106,
            DIMENSIONLESS,
            |s| s.rod.damping_ratio,
            |s, v| s.rod.damping_ratio = v,
            "Modal damping ratio (0 = undamped)",
        );
        b.non_negative();
        b.real_parameter(
            "slider.mass",
            107,
            real("kg"),
            |s| s.slider.mass,
            |s, v| s.slider.mass = v,
            "Slider mass m_s (0 allowed)",
        );
        b.non_negative();
        b.integer_parameter(
            "rod.model",
            110,
            ValueType::Enumeration(&ROD_MODEL),
            |s| model_index(s.rod.model),
            set_model,
            "Rod model: ffr or segments",
        );
        b.integer_parameter(
            "rod.elements",
            111,
            ValueType::Integer,
            |s| usize_to_i32(s.rod.elements),
            |s, v| element_count(v).map(|n| s.rod.elements = n),
            "Beam elements (FFR) or rigid segments (segments)",
        );
        b.bounds(Some(Value::Integer(1)), Some(Value::Integer(ELEMENTS_MAX)));
        b.integer_parameter(
            "rod.reference",
            112,
            ValueType::Enumeration(&ROD_REFERENCE),
            |s| reference_index(s.rod.reference),
            set_reference,
            "Reference conditions (FFR)",
        );
        b.integer_parameter(
            "rod.modes",
            113,
            ValueType::Integer,
            |s| usize_to_i32(s.rod.modes),
            |s, v| non_negative(v).map(|n| s.rod.modes = n),
            "Retained modes (FFR), lowest first",
        );
        b.bounds(Some(Value::Integer(0)), None);

        // Calculated parameters.
        for k in 1..=n_frequencies {
            b.variables.push(Variable {
                name: format!("rod.frequency[{k}]"),
                value_reference: FREQUENCY_VR_BASE + k as ValueReference,
                description: format!(
                    "Natural frequency {k} of the rod under its reference conditions (retained or not)"
                ),
                causality: Causality::CalculatedParameter,
                variability: Variability::Fixed,
                initial: Some(Initial::Calculated),
                value_type: real("Hz"),
                start: None,
                min: None,
                max: None,
                access: Access::Frequency(k - 1),
                initial_dependencies: D::Named(FREQUENCY_KNOWNS),
            });
        }

        let max_vr = b
            .variables
            .iter()
            .map(|v| v.value_reference)
            .max()
            .unwrap_or(0);
        let mut by_vr = vec![0u16; max_vr as usize + 1];
        for (i, v) in b.variables.iter().enumerate() {
            by_vr[v.value_reference as usize] = (i + 1) as u16;
        }
        VariableTable {
            variables: b.variables,
            by_vr,
        }
    }

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

    /// Number of `rod.frequency[k]` variables.
    pub fn frequency_count(&self) -> usize {
        self.variables
            .iter()
            .filter(|v| matches!(v.access, Access::Frequency(_)))
            .count()
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

    #[test]
    fn enumeration_setters_check_items() {
        let mut scene = Scene::benchmark();
        assert!(set_model(&mut scene, 2).is_ok());
        assert_eq!(scene.rod.model, RodModelKind::Segments);
        assert_eq!(
            set_model(&mut scene, 3).unwrap_err(),
            "1 (ffr), 2 (segments)"
        );
        assert!(set_reference(&mut scene, 0).is_err());
    }
}
