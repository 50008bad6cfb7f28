//! What a scene says about the rod: which model, its section, mesh and modes.

use serde::{Deserialize, Serialize};

use crate::beam::{EndBody, MassKind, RodDefinition, RodProperties, SectionStation, SectionTable};
use crate::error::ModelError;
use crate::modal::ReferenceKind;

/// Which rod model computes the connecting rod.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RodModelKind {
    /// Floating frame of reference with component modes (Agrawal and Shabana 1985).
    Ffr,
    /// Rigid segments joined by rotational springs (the finite segment method, Huston 1991).
    Segments,
    /// The segment chain on its rigid motions and `modes` lowest bending modes
    /// ([`crate::rod::segments::ModalSegmentRod`]): exact kinematics at large deflection, few
    /// coordinates.
    ModalSegments,
    /// The FFR rod or the chain on its modes, chosen for the load when the model is built
    /// ([`crate::rod::physics_choice`], "Rod model").
    Auto,
}

impl RodModelKind {
    /// Every variant, in the order of the FMU's enumeration items and Integer codes (1-based).
    pub const ALL: [RodModelKind; 4] = [
        RodModelKind::Ffr,
        RodModelKind::Segments,
        RodModelKind::ModalSegments,
        RodModelKind::Auto,
    ];

    /// The name used in scenes, the FMU's enumeration items and messages.
    pub fn name(self) -> &'static str {
        match self {
            RodModelKind::Ffr => "ffr",
            RodModelKind::Segments => "segments",
            RodModelKind::ModalSegments => "modal_segments",
            RodModelKind::Auto => "auto",
        }
    }

    /// The default `rod.deflection_limit` of the model: where it is verified
    /// ([`DEFAULT_DEFLECTION_LIMIT`], [`CHAIN_DEFLECTION_LIMIT`]; `auto` is resolved before a
    /// rod is built, its value here is the FFR rod's, the smaller one).
    pub fn deflection_limit(self) -> f64 {
        match self {
            RodModelKind::Ffr | RodModelKind::Auto => DEFAULT_DEFLECTION_LIMIT,
            RodModelKind::Segments | RodModelKind::ModalSegments => CHAIN_DEFLECTION_LIMIT,
        }
    }

    /// What the model's deflection limit stands for, and where to go beyond it (words for
    /// messages).
    pub fn validity(self) -> &'static str {
        match self {
            RodModelKind::Ffr | RodModelKind::Auto => "the small-deformation range of the FFR rod, linear in its modal coordinates; rod.model = modal_segments keeps the geometry exact to 0.25 (rod.model = auto takes it where crank.design_speed, or the crank speed at the start, calls for it)",
            RodModelKind::Segments | RodModelKind::ModalSegments => "the range where the segment chain is verified against the exact beam",
        }
    }

    /// The variant of a name (see [`Self::name`]).
    pub fn from_name(name: &str) -> Option<RodModelKind> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }
}

/// The connecting rod B-C.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RodSpec {
    pub model: RodModelKind,
    /// Rod length L, m.
    pub length: f64,
    /// Young's modulus E, Pa.
    pub youngs_modulus: f64,
    /// Density rho, kg/m^3.
    pub density: f64,
    /// Cross-section area A, m^2, of the uniform rod (left out, i.e. 0, with a section table).
    #[serde(default)]
    pub area: f64,
    /// Second moment of area I, m^4, of the uniform rod (left out, i.e. 0, with a section table).
    #[serde(default)]
    pub area_moment: f64,
    /// Station table `[[rod.section]]` of a rod whose section varies (empty = uniform rod).
    #[serde(default, rename = "section", skip_serializing_if = "Vec::is_empty")]
    pub section: Vec<SectionStation>,
    /// Timoshenko beam (shear flexibility and rotary inertia) instead of Euler-Bernoulli:
    /// `on`, `off`, or `auto` (default: on where it changes the outputs by more than
    /// `solver.tolerance`, [`crate::rod::physics_choice`]). `true` / `false` read as on / off.
    #[serde(default, skip_serializing_if = "PhysicsSwitch::is_auto")]
    pub shear_deformation: PhysicsSwitch,
    /// Shear modulus G, Pa (default E / 2.6); used where shear deformation is on.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shear_modulus: Option<f64>,
    /// Shear area A_s, m^2, of the uniform rod (default A / 1.2; a section table gives it per
    /// station).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shear_area: Option<f64>,
    /// Axial dynamics: the slider-rod axial mode among the retained modes, on mass-loaded modes
    /// (FFR), or the axial springs between segments (segments): `on`, `off`, or `auto`
    /// (default: on where that mode lies in the band the retained bending modes span,
    /// [`crate::rod::physics_choice`]). With `off` the scene's `axial_modes`, `loaded_modes`
    /// and `axial_springs` keys decide alone.
    #[serde(default, skip_serializing_if = "PhysicsSwitch::is_auto")]
    pub axial_dynamics: PhysicsSwitch,
    /// Rigid body attached at B (`[rod.big_end]`: mass kg, inertia kg m^2 about B).
    #[serde(default, skip_serializing_if = "EndBody::is_empty")]
    pub big_end: EndBody,
    /// Rigid body attached at C (`[rod.small_end]`: mass kg, inertia kg m^2 about C).
    #[serde(default, skip_serializing_if = "EndBody::is_empty")]
    pub small_end: EndBody,
    /// Modal damping ratio (FFR) or joint damping ratio of the first bending mode (segments); 0 = undamped.
    #[serde(default)]
    pub damping_ratio: f64,
    /// Beam elements (FFR) or rigid segments (segments).
    pub elements: usize,
    /// Reference conditions (FFR only).
    #[serde(default = "default_reference")]
    pub reference: ReferenceKind,
    /// Retained modes (FFR only), lowest first; where axial dynamics brings the axial mode in
    /// ([`Self::axial_in_addition`]), the number of bending modes.
    #[serde(default = "default_modes")]
    pub modes: usize,
    /// Least number of axial modes among the retained ones (FFR only): the lowest axial modes
    /// missing from the `modes` lowest are added. Absent (`"auto"`): 1 when the masses at C
    /// (slider and small end) reach [`AXIAL_MODE_MASS_RATIO`] times the rod's mass, else 0 (see
    /// [`Self::min_axial_modes`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axial_modes: Option<usize>,
    /// The axial modes come in addition to `modes` bending modes
    /// ([`crate::modal::ModeSelection::BendingWithAxial`]) instead of among the `modes` lowest:
    /// set where `axial_dynamics` (`auto` or `on`) brings the axial mode in, not read from a
    /// scene.
    #[serde(skip)]
    pub axial_in_addition: bool,
    /// Mass-loaded modes (FFR only): the slider's mass is added at C's axial coordinate in the
    /// eigenproblem (not in the dynamics), so that the retained modes include the slider-rod
    /// axial mode at its frequency in the mechanism ([`crate::modal::mass_loaded_modes`]).
    #[serde(default, skip_serializing_if = "is_false")]
    pub loaded_modes: bool,
    /// Keep every mode up to this frequency, Hz (FFR only), instead of the `modes` lowest:
    /// the band the mechanism's excitation and its quasi-static response need.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mode_band_hz: Option<f64>,
    /// Consistent or lumped element mass (FFR only).
    #[serde(default)]
    pub mass: MassKind,
    /// Axial force acting on bending (geometric stiffness); docs/physics.md, "What linear modes miss".
    #[serde(default = "default_true")]
    pub axial_stiffening: bool,
    /// Segments only: keep the axial springs E A / l (prismatic joints) between segments.
    #[serde(default)]
    pub axial_springs: bool,
    /// |v_mid / L| beyond which `deflection_policy` applies, in (0, 1]; absent: the model's
    /// own range ([`RodModelKind::deflection_limit`], read through [`Self::deflection_limit`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub deflection_limit: Option<f64>,
    /// What a step whose deflection exceeds `deflection_limit` does: "warn",
    /// "discard" (default) or "error".
    #[serde(default, skip_serializing_if = "DeflectionPolicy::is_default")]
    pub deflection_policy: DeflectionPolicy,
}

/// The FFR rod's `rod.deflection_limit`: the end of the small-deformation range of its field,
/// linear in the modal coordinates (3.4 % of the peak `v_mid` off the exact beam at a peak
/// `|v_mid / L|` of 0.07, tests/segments.rs `ffr_levels_off_at_300_rad_s`).
pub const DEFAULT_DEFLECTION_LIMIT: f64 = 0.05;

/// The segment chains' `rod.deflection_limit`: their kinematics are exact, and the chain on its
/// modes is measured within 0.1 % of the chain of 64 segments at a peak `|v_mid / L|` of 0.18
/// (450 rad/s, tests/modal_segments.rs); its straight-rod modes no longer assemble the
/// rod folded to 0.4 (600 rad/s).
pub const CHAIN_DEFLECTION_LIMIT: f64 = 0.25;

/// What a step does whose rod deflection |v_mid / L| exceeds `rod.deflection_limit`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DeflectionPolicy {
    /// One warning, then continue (results beyond the limit are not accurate).
    Warn,
    /// The step is refused and the state from before it kept, a refusal the caller can
    /// retry: the default, so that a master can react (restore a state, switch to the segment
    /// chain, stop) instead of receiving numbers past the small-deformation range with a
    /// warning most masters ignore.
    #[default]
    Discard,
    /// The step fails, the state from before it kept.
    Error,
}

impl DeflectionPolicy {
    /// Every policy, the mildest first.
    pub const ALL: [DeflectionPolicy; 3] = [
        DeflectionPolicy::Warn,
        DeflectionPolicy::Discard,
        DeflectionPolicy::Error,
    ];

    pub fn name(self) -> &'static str {
        match self {
            DeflectionPolicy::Warn => "warn",
            DeflectionPolicy::Discard => "discard",
            DeflectionPolicy::Error => "error",
        }
    }

    fn is_default(&self) -> bool {
        *self == DeflectionPolicy::default()
    }
}

/// A part of the physics a user can force on or off, or leave to the model (`auto`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PhysicsSwitch {
    /// Chosen at initialization from the rod's own numbers and `solver.tolerance`.
    #[default]
    Auto,
    On,
    Off,
}

impl PhysicsSwitch {
    /// Every setting, in the order of the FMU's enumeration items and Integer codes (1-based).
    pub const ALL: [PhysicsSwitch; 3] =
        [PhysicsSwitch::Auto, PhysicsSwitch::On, PhysicsSwitch::Off];

    /// The name in scenes, enumeration items and messages.
    pub fn name(self) -> &'static str {
        match self {
            PhysicsSwitch::Auto => "auto",
            PhysicsSwitch::On => "on",
            PhysicsSwitch::Off => "off",
        }
    }

    /// `On` for true, `Off` for false.
    pub fn from_bool(on: bool) -> PhysicsSwitch {
        if on {
            PhysicsSwitch::On
        } else {
            PhysicsSwitch::Off
        }
    }

    /// Whether the part is in (after [`crate::rod::physics_choice`] resolved `auto`; an
    /// unresolved `auto` counts as on).
    pub fn is_on(self) -> bool {
        self != PhysicsSwitch::Off
    }

    fn is_auto(&self) -> bool {
        *self == PhysicsSwitch::Auto
    }
}

impl<'de> Deserialize<'de> for PhysicsSwitch {
    /// `"auto"`, `"on"`, `"off"`, or a boolean (`true` = on, `false` = off).
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Raw {
            Flag(bool),
            Name(String),
        }
        match Raw::deserialize(d)? {
            Raw::Flag(b) => Ok(PhysicsSwitch::from_bool(b)),
            Raw::Name(name) => PhysicsSwitch::ALL
                .into_iter()
                .find(|k| k.name() == name)
                .ok_or_else(|| {
                    serde::de::Error::custom(format!(
                        "unknown setting {name:?}: expected \"auto\", \"on\", \"off\", true or false"
                    ))
                }),
        }
    }
}

/// With shear deformation in use (`on` or `auto`), the least shear area as a fraction of the
/// area, `A_s >= A / 100` (shear coefficients of real sections: 0.83 for a rectangle, about 0.5
/// for a thin tube, the web's share of an I-section 0.2 to 0.4), and the least shear modulus
/// as a fraction of Young's modulus, `G >= E / 1000` (isotropic: `E / 3` at least; fibre
/// composites about `E / 30`). Past them the shear stiffness `G A_s` is so small beside the
/// axial `E A` that double precision no longer resolves the rod's spectrum.
pub const SHEAR_FRACTIONS: (f64, f64) = (1e-2, 1e-3);

/// Default shear modulus as a fraction of Young's modulus, `G = E / 2.6` (isotropic, Poisson's
/// ratio 0.3: `G = E / (2 (1 + nu))`).
pub const DEFAULT_SHEAR_MODULUS_FACTOR: f64 = 1.0 / 2.6;

impl RodSpec {
    /// `rod.deflection_limit`: the scene's, else the model's own
    /// ([`RodModelKind::deflection_limit`]).
    pub fn deflection_limit(&self) -> f64 {
        self.deflection_limit
            .unwrap_or_else(|| self.model.deflection_limit())
    }

    /// The section properties of the uniform rod; with a section table, `area` and
    /// `area_moment` are the table's length means (an equivalent uniform rod, for messages and
    /// estimates; the models use [`Self::definition`]). A table that does not validate gives
    /// the spec's own (possibly 0) values, so that [`Self::validate`] names the station.
    pub fn properties(&self) -> RodProperties {
        let uniform = RodProperties {
            length: self.length,
            youngs_modulus: self.youngs_modulus,
            density: self.density,
            area: self.area,
            area_moment: self.area_moment,
        };
        if self.section.is_empty() {
            return uniform;
        }
        match SectionTable::new(self.length, &self.section) {
            Ok(t) => RodDefinition::with_table(uniform, t).properties,
            Err(_) => uniform,
        }
    }

    /// The shear modulus in use: `Some(G)` (given, or `E / 2.6`) with shear deformation on
    /// (or `auto`, not yet resolved).
    pub fn effective_shear_modulus(&self) -> Option<f64> {
        self.shear_deformation.is_on().then(|| {
            self.shear_modulus
                .unwrap_or(self.youngs_modulus * DEFAULT_SHEAR_MODULUS_FACTOR)
        })
    }

    /// The full rod (section table, shear, end bodies), validated: every error names the
    /// offending key (a station by its index and position).
    pub fn definition(&self) -> Result<RodDefinition, ModelError> {
        let mut def = if self.section.is_empty() {
            RodDefinition::uniform(self.properties())
        } else {
            if self.area != 0.0 || self.area_moment != 0.0 {
                let (name, value) = if self.area != 0.0 {
                    ("rod.area", self.area)
                } else {
                    ("rod.area_moment", self.area_moment)
                };
                return Err(ModelError::InvalidParameter {
                    name,
                    value,
                    allowed: "left out when [[rod.section]] stations are given (the table fixes the section)".into(),
                });
            }
            let table = SectionTable::new(self.length, &self.section)?;
            RodDefinition::with_table(self.properties(), table)
        };
        if let Some(a_s) = self.shear_area {
            if !self.section.is_empty() {
                return Err(ModelError::InvalidParameter {
                    name: "rod.shear_area",
                    value: a_s,
                    allowed: "left out when [[rod.section]] stations are given (each station carries its shear_area)".into(),
                });
            }
            let a = self.area;
            if !(a_s.is_finite() && a_s > 0.0 && a_s <= a) {
                return Err(ModelError::InvalidParameter {
                    name: "rod.shear_area",
                    value: a_s,
                    allowed: format!("in (0, rod.area] = (0, {a:e}] m2"),
                });
            }
        }
        if let Some(g) = self.shear_modulus {
            // Checked whether or not shear is in, so that a bad value is refused when set.
            crate::beam::definition::check_shear_modulus(g)?;
        }
        if self.shear_deformation.is_on() {
            self.check_shear_windows()?;
        }
        def.shear_modulus = self.effective_shear_modulus();
        def.uniform_shear_area = self.shear_area;
        def.big_end = self.big_end;
        def.small_end = self.small_end;
        def.validate()?;
        Ok(def)
    }

    /// With shear deformation in use: `rod.shear_area` (or each station's `shear_area`) in
    /// `[A / 100, A]` and `rod.shear_modulus` at least `E / 1000` ([`SHEAR_FRACTIONS`]).
    fn check_shear_windows(&self) -> Result<(), ModelError> {
        let (area_fraction, modulus_fraction) = SHEAR_FRACTIONS;
        let why = "with rod.shear_deformation on or auto";
        if let (Some(a_s), true) = (self.shear_area, self.section.is_empty()) {
            let a = self.area;
            if !(a_s >= area_fraction * a && a_s <= a) {
                return Err(ModelError::InvalidParameter {
                    name: "rod.shear_area",
                    value: a_s,
                    allowed: format!(
                        "[rod.area / 100, rod.area] = [{:e}, {a:e}] m2 {why} (a shear coefficient A_s / A of 0.01 to 1)",
                        area_fraction * a
                    ),
                });
            }
        }
        for (i, st) in self.section.iter().enumerate() {
            if let Some(a_s) = st.shear_area {
                if !(a_s >= area_fraction * st.area && a_s <= st.area) {
                    return Err(ModelError::InvalidParameter {
                        name: "rod.section.shear_area",
                        value: a_s,
                        allowed: format!(
                            "[area / 100, area] = [{:e}, {:e}] m2 {why} (station {i} of [[rod.section]], counted from 0, position {} m)",
                            area_fraction * st.area,
                            st.area,
                            st.position
                        ),
                    });
                }
            }
        }
        if let Some(g) = self.shear_modulus {
            let least = modulus_fraction * self.youngs_modulus;
            if !g.is_finite() || g < least {
                return Err(ModelError::InvalidParameter {
                    name: "rod.shear_modulus",
                    value: g,
                    allowed: format!("at least rod.youngs_modulus / 1000 = {least:e} Pa {why}"),
                });
            }
        }
        Ok(())
    }

    /// Check the rod's keys (see [`Self::definition`]).
    pub fn validate(&self) -> Result<(), ModelError> {
        if let Some(n) = self.axial_modes {
            if n > MAX_AXIAL_MODES {
                return Err(ModelError::InvalidInteger {
                    name: "rod.axial_modes",
                    value: n as i64,
                    allowed: format!("0..={MAX_AXIAL_MODES}, or absent for automatic"),
                });
            }
        }
        if let Some(band) = self.mode_band_hz {
            if !(band.is_finite() && band > 0.0) {
                return Err(ModelError::InvalidParameter {
                    name: "rod.mode_band_hz",
                    value: band,
                    allowed: "a frequency > 0 Hz, or absent (rod.modes lowest modes)".into(),
                });
            }
        }
        let l = self.deflection_limit();
        if !(l.is_finite() && l > 0.0 && l <= 1.0) {
            return Err(ModelError::InvalidParameter {
                name: "rod.deflection_limit",
                value: l,
                allowed: "a value in (0, 1] (|v_mid / L|)".into(),
            });
        }
        self.definition().map(|_| ())
    }

    /// Check that stress can be computed: every station gives `fibre_distance` (a section
    /// table is required for it, since the uniform keys have no fibre distance).
    pub fn require_fibre_distance(&self) -> Result<(), ModelError> {
        match &self.definition()?.table {
            Some(t) => t.require_fibre_distance(),
            None => Err(ModelError::InvalidParameter {
                name: "rod.section.fibre_distance",
                value: f64::NAN,
                allowed: "a [[rod.section]] table with fibre_distance at every station when stress is asked for".into(),
            }),
        }
    }

    /// Mass of the rod with its end bodies, kg (the FMU's calculated parameter `rod.mass`).
    pub fn total_mass(&self) -> Result<f64, ModelError> {
        Ok(self.definition()?.total_mass())
    }
}

fn is_false(b: &bool) -> bool {
    !*b
}

fn default_reference() -> ReferenceKind {
    ReferenceKind::SimplySupported
}
/// Most axial modes `rod.axial_modes` may ask for.
pub const MAX_AXIAL_MODES: usize = 8;

/// With `rod.axial_modes` absent, the first axial mode is kept when the masses at C (slider
/// and small end) reach this multiple of the rod's mass (end bodies included): a heavy piston,
/// whose axial mode with the rod carries sudden slider forces into the pin forces. The error
/// control with axial modes is established for such pistons only. Measured on the automotive
/// rod and the random parameter sets in docs/real-rods.md, "Modes chosen for the mechanism:
/// mass-loaded modes and the mode band".
pub const AXIAL_MODE_MASS_RATIO: f64 = 1.0;

impl RodSpec {
    /// The least number of axial modes to keep: `rod.axial_modes`, or automatically 1 when
    /// `slider_mass` plus the small end's mass is at least [`AXIAL_MODE_MASS_RATIO`] times
    /// [`Self::total_mass`], else 0.
    pub fn min_axial_modes(&self, slider_mass: f64) -> usize {
        self.axial_modes.unwrap_or_else(|| {
            let at_c = slider_mass + self.small_end.mass;
            // An invalid rod fails later, in its own validation.
            let rod = self.total_mass().unwrap_or(f64::INFINITY);
            usize::from(at_c > 0.0 && at_c >= AXIAL_MODE_MASS_RATIO * rod)
        })
    }
}

fn default_modes() -> usize {
    4
}
fn default_true() -> bool {
    true
}
