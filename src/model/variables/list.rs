//! The variable list: every variable of the model, its value reference, unit, start value,
//! bounds and where its value lives. Names, units and signs are those of `docs/fmu.md`.

use super::builder::{real, Builder, DIMENSIONLESS, RAD, RAD_PER_S};
use super::enumerations::{self, PHYSICS_SWITCH, ROD_MODEL, ROD_REFERENCE};
use super::ranges::{
    element_count, non_negative, policy_code, set_axial_dynamics, set_model, set_policy,
    set_reference, set_shear_deformation, usize_to_i32, ELEMENTS_MAX,
};
use super::ranges::{loaded_modes_code, set_loaded_modes};
use super::types::{Access, InputSlot};
use super::{Interface, VariableId, VariableTable, FREQUENCY_VR_BASE};
use crate::cosimulation::{InitialDependencies, Value, ValueType};
use crate::scene::Scene;

/// Parameters the rod's natural frequencies depend on (names a scene does not declare are
/// left out of the description's dependencies): the rod, the model class the `auto` settings
/// choose (from the slider's mass and the tolerance too), the mass-loaded modes.
const FREQUENCY_KNOWNS: &[&str] = &[
    "crank.length",
    "crank.design_speed",
    "rod.length",
    "rod.youngs_modulus",
    "rod.density",
    "rod.area",
    "rod.area_moment",
    "rod.model",
    "rod.elements",
    "rod.reference",
    "rod.modes",
    "rod.model_index",
    "rod.reference_index",
    "rod.shear_modulus",
    "rod.shear_area",
    "rod.shear_deformation",
    "rod.shear_deformation_index",
    "rod.axial_dynamics",
    "rod.axial_dynamics_index",
    "rod.big_end.mass",
    "rod.big_end.inertia",
    "rod.small_end.mass",
    "rod.small_end.inertia",
    "rod.loaded_modes",
    "rod.mode_band_hz",
    "slider.mass",
    "solver.tolerance",
];

impl VariableTable {
    /// The table of `scene` for [`Interface::SCALARS`], with `n_frequencies` calculated
    /// parameters `rod.frequency[k]`.
    pub fn new(scene: &Scene, n_frequencies: usize) -> VariableTable {
        VariableTable::for_interface(scene, n_frequencies, Interface::SCALARS)
    }

    /// The table of `scene` for `interface`, with `n_frequencies` natural frequencies: the
    /// independent variable, `crank.acceleration`, the array `rod.shape` and the frequencies
    /// as one array `rod.frequency` as the interface calls for ([`super::interface`]).
    pub fn for_interface(
        scene: &Scene,
        n_frequencies: usize,
        interface: Interface,
    ) -> VariableTable {
        let mut b = Builder::new(scene, interface);
        inputs(&mut b);
        outputs(&mut b);
        section_outputs(&mut b);
        rod_parameters(&mut b, n_frequencies);
        mechanism_parameters(&mut b);
        real_rod_parameters(&mut b);
        mode_choice_parameters(&mut b);
        enumeration_twins(&mut b);
        solver_parameters(&mut b);
        let frequency_knowns = calculated_parameters(&mut b, n_frequencies);
        super::interface::add_variables(&mut b, interface, n_frequencies, frequency_knowns);
        b.finish()
    }
}

/// The inputs; start values from the default experiment.
fn inputs(b: &mut Builder<'_>) {
    let scene = b.scene;
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
        "Crank speed omega at the communication point (input derivatives: order 1 the crank acceleration, order 2 the crank jerk)");
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
}

/// The outputs of every scene.
fn outputs(b: &mut Builder<'_>) {
    let scene = b.scene;
    let out = &scene.outputs;
    use InitialDependencies as D;
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
    b.output(
        "rod.error_estimate",
        19,
        DIMENSIONLESS,
        |o| o.error_estimate,
        D::All,
        "Estimated error of v_mid / L relative to its peak so far, model and integration together: pointwise, after a start at speed of the forced motion and the amplitude (not the phase) of the vibration the start rings; one warning when it passes solver.tolerance",
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
}

/// The section forces and stress of real rods.
fn section_outputs(b: &mut Builder<'_>) {
    let scene = b.scene;
    let out = &scene.outputs;
    use InitialDependencies as D;
    // Real connecting rods (`docs/fmu.md`, "Real connecting rods"; value references
    // 130-149): section forces and stress, with `[outputs] stress = true`.
    if out.stress {
        b.output(
            "rod.axial_force_mid",
            130,
            real("N"),
            |o| o.section.axial_force_mid,
            D::All,
            "Axial force at the material midpoint, tension positive",
        );
        b.output(
            "rod.bending_moment_mid",
            131,
            real("N.m"),
            |o| o.section.bending_moment_mid,
            D::All,
            "Bending moment at the midpoint, positive when it bends the rod towards +v",
        );
        b.output(
            "rod.stress_max",
            132,
            real("Pa"),
            |o| o.section.stress_max,
            D::All,
            "Largest abs(N/A) + abs(M) c / I over the rod at this time",
        );
        b.output(
            "rod.stress_max_position",
            133,
            real("m"),
            |o| o.section.stress_max_position,
            D::All,
            "Where rod.stress_max occurs, distance from B",
        );
    }
}

/// The crank, rod and slider parameters.
fn rod_parameters(b: &mut Builder<'_>, n_frequencies: usize) {
    let scene = b.scene;
    // Parameters (fixed: settable until the end of initialization).
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
        "crank.design_speed",
        109,
        RAD_PER_S,
        |s| s.crank.design_speed,
        |s, v| s.crank.design_speed = v,
        "Highest crank speed |omega| of the run, rad/s, for which rod.model = auto chooses the rod model; 0 = |crank.speed| at initialization",
    );
    b.bounds(
        Some(Value::Real(0.0)),
        Some(Value::Real(crate::mechanism::DESIGN_SPEED_MAX)),
    );
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
    // A section table fixes the section: no uniform area or area moment.
    let uniform = scene.rod.section.is_empty();
    if uniform {
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
    }
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
        |s| enumerations::code(s.rod.model),
        set_model,
        "Rod model: ffr, segments, modal_segments, or auto (ffr, or modal_segments where the load at crank.design_speed calls for exact kinematics)",
    );
    b.integer_parameter(
        "rod.elements",
        111,
        ValueType::Integer,
        |s| usize_to_i32(s.rod.elements),
        |s, v| element_count(v).map(|n| s.rod.elements = n),
        "Beam elements (FFR) or rigid segments (segments, modal_segments)",
    );
    b.bounds(
        Some(Value::Integer(least_count(scene, n_frequencies))),
        Some(Value::Integer(ELEMENTS_MAX)),
    );
    b.integer_parameter(
        "rod.reference",
        112,
        ValueType::Enumeration(&ROD_REFERENCE),
        |s| enumerations::code(s.rod.reference),
        set_reference,
        "Reference conditions (FFR)",
    );
    // The retained modes: a count (`rod.modes`) or, in a scene with a mode band, every
    // mode up to a frequency (`rod.mode_band_hz`, below). A scene declares the one it
    // uses, so that no parameter is ignored.
    if scene.rod.mode_band_hz.is_none() {
        b.integer_parameter(
            "rod.modes",
            113,
            ValueType::Integer,
            |s| usize_to_i32(s.rod.modes),
            |s, v| non_negative(v).map(|n| s.rod.modes = n),
            "Retained modes (FFR), lowest first; with axial dynamics on (auto or on) the bending modes, the slider-rod axial mode in addition; modal_segments: at least this many bending modes (every one up to 20 times the first)",
        );
        b.bounds(Some(Value::Integer(0)), None);
    }
}

/// The slider line and gravity.
fn mechanism_parameters(b: &mut Builder<'_>) {
    let scene = b.scene;
    // Slider line and gravity (`docs/fmu.md`, "Real connecting rods"), in scenes with a
    // `[mechanism]` table.
    if !scene.mechanism.is_default() {
        b.real_parameter(
            "slider.offset",
            135,
            real("m"),
            |s| s.mechanism.slider_offset,
            |s, v| s.mechanism.slider_offset = v,
            "Slider line offset: the slider moves along y = slider.offset",
        );
        b.real_parameter(
            "gravity.x",
            136,
            real("m/s2"),
            |s| s.mechanism.gravity[0],
            |s, v| s.mechanism.gravity[0] = v,
            "Gravity, global x",
        );
        b.real_parameter(
            "gravity.y",
            137,
            real("m/s2"),
            |s| s.mechanism.gravity[1],
            |s, v| s.mechanism.gravity[1] = v,
            "Gravity, global y",
        );
    }

    if scene.slider.gas_force.is_some() {
        b.real_parameter(
            "slider.gas_force_scale",
            108,
            DIMENSIONLESS,
            |s| s.slider.gas_force.as_ref().map_or(1.0, |g| g.scale),
            |s, v| {
                if let Some(g) = s.slider.gas_force.as_mut() {
                    g.scale = v;
                }
            },
            "Factor on the scene's gas-force table [slider.gas_force] (force on the slider as a function of crank angle, in addition to slider.force), in [0, 100]",
        );
        b.bounds(
            Some(Value::Real(0.0)),
            Some(Value::Real(crate::mechanism::gas_force::MAX_SCALE)),
        );
    }
}

/// The shear deformation and the end bodies.
fn real_rod_parameters(b: &mut Builder<'_>) {
    // The rod's shear deformation and end bodies (`docs/fmu.md`, "Real connecting rods" and
    // "Model class and error estimate"), value references 138-142 and 145-149, in every
    // FMU: any rod can be entered with only physical parameters.
    b.real_parameter(
        "rod.shear_modulus",
        138,
        real("Pa"),
        |s| s.rod.shear_modulus.unwrap_or(s.rod.youngs_modulus / 2.6),
        |s, v| s.rod.shear_modulus = Some(v),
        "Shear modulus G, used where shear deformation is on (default E / 2.6)",
    );
    b.positive();
    // A section table gives the shear area per station.
    let uniform = b.scene.rod.section.is_empty();
    if uniform {
        b.real_parameter(
            "rod.shear_area",
            145,
            real("m2"),
            |s| s.rod.shear_area.unwrap_or(s.rod.area / 1.2),
            |s, v| s.rod.shear_area = Some(v),
            "Shear area A_s of the uniform rod, in (0, rod.area] (default A / 1.2, a rectangle)",
        );
        b.positive();
    }
    b.integer_parameter(
        "rod.shear_deformation",
        146,
        ValueType::Enumeration(&PHYSICS_SWITCH),
        |s| enumerations::code(s.rod.shear_deformation),
        set_shear_deformation,
        "Shear deformation and rotary inertia (Timoshenko): auto (on where their estimated effect on v_mid/L exceeds solver.tolerance), on or off",
    );
    b.integer_parameter(
        "rod.axial_dynamics",
        148,
        ValueType::Enumeration(&PHYSICS_SWITCH),
        |s| enumerations::code(s.rod.axial_dynamics),
        set_axial_dynamics,
        "Axial dynamics (the slider-rod axial mode): auto (on where it lies within 1.5 x the highest retained bending mode, or the masses at C reach the rod's), on or off",
    );
    b.real_parameter(
        "rod.big_end.mass",
        139,
        real("kg"),
        |s| s.rod.big_end.mass,
        |s, v| s.rod.big_end.mass = v,
        "Mass of the big end (rigid body at B)",
    );
    b.non_negative();
    b.real_parameter(
        "rod.big_end.inertia",
        140,
        real("kg.m2"),
        |s| s.rod.big_end.inertia,
        |s, v| s.rod.big_end.inertia = v,
        "Rotary inertia of the big end about B",
    );
    b.non_negative();
    b.real_parameter(
        "rod.small_end.mass",
        141,
        real("kg"),
        |s| s.rod.small_end.mass,
        |s, v| s.rod.small_end.mass = v,
        "Mass of the small end (rigid body at C)",
    );
    b.non_negative();
    b.real_parameter(
        "rod.small_end.inertia",
        142,
        real("kg.m2"),
        |s| s.rod.small_end.inertia,
        |s, v| s.rod.small_end.inertia = v,
        "Rotary inertia of the small end about C",
    );
    b.non_negative();
}

/// The modes chosen for the mechanism.
fn mode_choice_parameters(b: &mut Builder<'_>) {
    let scene = b.scene;
    // The modes chosen for the mechanism (`docs/fmu.md`, "Mode band and mass-loaded
    // modes"), value references 143-144, in scenes with `rod.loaded_modes` or
    // `rod.mode_band_hz`.
    let loaded_declared = scene.rod.loaded_modes || scene.rod.mode_band_hz.is_some();
    if loaded_declared {
        b.integer_parameter(
            "rod.loaded_modes",
            143,
            ValueType::Integer,
            loaded_modes_code,
            set_loaded_modes,
            "Mass-loaded modes (FFR): 1 = the slider's mass at C in the eigenproblem (the slider-rod axial mode is a mode; rod.frequency[k] are the loaded frequencies), 0 = free modes",
        );
        b.bounds(Some(Value::Integer(0)), Some(Value::Integer(1)));
    }
    if scene.rod.mode_band_hz.is_some() {
        b.real_parameter(
            "rod.mode_band_hz",
            144,
            real("Hz"),
            |s| s.rod.mode_band_hz.unwrap_or(f64::INFINITY),
            |s, v| s.rod.mode_band_hz = Some(v),
            "Mode band (FFR): every mode up to this frequency is retained, the bending modes above act as static corrections to rod.deflection; finite, > 0",
        );
        b.positive();
    }
}

/// The Integer twins of the Enumeration parameters.
fn enumeration_twins(b: &mut Builder<'_>) {
    // Integer twins of the Enumeration parameters: masters that ignore Enumeration
    // variables (libcosim, among others) can still switch the model and the reference
    // conditions. Same getter and setter as the Enumeration: one value, two names.
    b.integer_parameter(
        "rod.model_index",
        114,
        ValueType::Integer,
        |s| enumerations::code(s.rod.model),
        set_model,
        &ROD_MODEL.twin_description("rod.model"),
    );
    b.bounds(
        Some(Value::Integer(1)),
        Some(Value::Integer(ROD_MODEL.max_code())),
    );
    b.integer_parameter(
        "rod.reference_index",
        115,
        ValueType::Integer,
        |s| enumerations::code(s.rod.reference),
        set_reference,
        &ROD_REFERENCE.twin_description("rod.reference"),
    );
    b.bounds(
        Some(Value::Integer(1)),
        Some(Value::Integer(ROD_REFERENCE.max_code())),
    );

    for (name, vr, get, set) in [
        (
            "rod.shear_deformation",
            147,
            (|s: &Scene| enumerations::code(s.rod.shear_deformation)) as fn(&Scene) -> i32,
            set_shear_deformation as fn(&mut Scene, i32) -> Result<(), String>,
        ),
        (
            "rod.axial_dynamics",
            149,
            |s: &Scene| enumerations::code(s.rod.axial_dynamics),
            set_axial_dynamics,
        ),
    ] {
        b.integer_parameter(
            &format!("{name}_index"),
            vr,
            ValueType::Integer,
            get,
            set,
            &PHYSICS_SWITCH.twin_description(name),
        );
        b.bounds(
            Some(Value::Integer(1)),
            Some(Value::Integer(PHYSICS_SWITCH.max_code())),
        );
    }
}

/// The integrator's accuracy and the deflection policy.
fn solver_parameters(b: &mut Builder<'_>) {
    let interface = b.interface();
    // The integrator's accuracy: the error control chooses the internal steps.
    b.real_parameter(
        "solver.tolerance",
        116,
        DIMENSIONLESS,
        |s| s.solver.tolerance,
        |s, v| s.solver.tolerance = v,
        "Accuracy of the integration (solver.method auto or dopri5): pointwise error of the deflection relative to its peak, in [1e-10, 0.1]",
    );
    b.bounds(Some(Value::Real(1e-10)), Some(Value::Real(0.1)));

    // What a step beyond the small-deformation range does.
    b.real_parameter(
        "rod.deflection_limit",
        120,
        DIMENSIONLESS,
        |s| s.rod.deflection_limit(),
        |s, v| s.rod.deflection_limit = Some(v),
        "|v_mid/L| beyond which rod.deflection_policy applies, in (0, 1]; by default where the rod model is verified (ffr 0.05, segments and modal_segments 0.25)",
    );
    b.applied(|s| s.mechanism().spec.rod.deflection_limit());
    b.bounds(Some(Value::Real(0.0)), Some(Value::Real(1.0)));
    b.integer_parameter(
        "rod.deflection_policy",
        121,
        ValueType::Integer,
        |s| policy_code(s.rod.deflection_policy),
        set_policy,
        &format!(
            "What a step beyond rod.deflection_limit does: 1 = warn (one warning, continue), 2 = discard ({}, the state before the step kept; default), 3 = error ({}, the state before the step kept)",
            interface.refused_step, interface.failed_step
        ),
    );
    b.bounds(Some(Value::Integer(1)), Some(Value::Integer(3)));
}

/// The calculated parameters: the frequencies and the rod's mass.
fn calculated_parameters(b: &mut Builder<'_>, n_frequencies: usize) -> &'static [&'static str] {
    let interface = b.interface();
    use InitialDependencies as D;
    // Calculated parameters (with arrays: one array, see `interface`).
    let frequency_knowns = FREQUENCY_KNOWNS;
    let scalar_frequencies = if interface.arrays { 0 } else { n_frequencies };
    for k in 1..=scalar_frequencies {
        b.calculated_parameter(
            format!("rod.frequency[{k}]"),
            FREQUENCY_VR_BASE + k as VariableId,
            real("Hz"),
            Access::Frequency(k - 1),
            D::Named(frequency_knowns),
            format!(
                "Natural frequency {k} of the rod under its reference conditions (retained or not)"
            ),
        );
    }
    {
        b.calculated_parameter(
            "rod.mass".into(),
            134,
            real("kg"),
            Access::RodMass,
            D::Named(&[
                "rod.length",
                "rod.density",
                "rod.area",
                "rod.big_end.mass",
                "rod.small_end.mass",
            ]),
            "Mass of the rod with its end bodies".into(),
        );
    }
    frequency_knowns
}

/// The declared minimum of `rod.elements`: the least count that leaves `frequencies` natural
/// frequencies for the exported `rod.model` ([`crate::beam::mesh::least_elements`],
/// [`crate::rod::segments::least_segments`]), at least 1 and never above the exported count.
/// After `rod.model` is switched, the other model's least count is checked when the model is
/// built (it may differ: 7 segments against 2 elements for six frequencies).
fn least_count(scene: &Scene, frequencies: usize) -> i32 {
    let least = match scene.rod.model {
        // `auto` builds the FFR rod with `rod.elements`, or a chain of at least
        // `physics_choice::AUTO_SEGMENTS` segments (more than enough frequencies).
        crate::scene::RodModelKind::Ffr | crate::scene::RodModelKind::Auto => {
            crate::beam::mesh::least_elements(frequencies)
        }
        crate::scene::RodModelKind::Segments | crate::scene::RodModelKind::ModalSegments => {
            crate::rod::segments::least_segments(frequencies, scene.rod.axial_springs)
        }
    };
    usize_to_i32(least.clamp(1, scene.rod.elements.max(1)))
}
