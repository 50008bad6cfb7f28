//! A scene: everything that defines one exported FMU and one simulation.
//!
//! A scene is a TOML file (see `scenes/*.toml`). Unknown keys are rejected with an error
//! naming the key and the file. The FMU exposes the physical parameters of its scene as
//! FMI parameters (start values taken from here) and leaves out the variables the scene
//! switches off in `[outputs]`.
//!
//! Units are SI throughout: m, kg, s, N, Pa, rad.

use serde::{Deserialize, Serialize};
use std::path::Path;

use crate::error::{require_within, ModelError};

pub use crate::beam::MassKind;
pub use crate::mechanism::spec::{
    CrankSpec, MechanismSpec, MechanismTable, SliderSpec, SolverMethod, SolverSpec,
    StartDeflection, StartSpec,
};
pub use crate::modal::ReferenceKind;
pub use crate::rod::{DeflectionPolicy, RodModelKind, RodSpec};

/// The whole scene.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Short identifier; also the FMU's `modelIdentifier`.
    pub name: String,
    /// One line shown in modelDescription.xml and the documentation.
    #[serde(default)]
    pub description: String,
    pub crank: CrankSpec,
    pub rod: RodSpec,
    #[serde(default)]
    pub slider: SliderSpec,
    #[serde(default)]
    pub solver: SolverSpec,
    #[serde(default)]
    pub outputs: OutputSpec,
    #[serde(default)]
    pub experiment: ExperimentSpec,
    #[serde(default)]
    pub start: StartSpec,
    /// `[mechanism]`: slider line offset and gravity (left out when neither is used, so the
    /// scenes without it keep their fingerprint).
    #[serde(default, skip_serializing_if = "MechanismTable::is_default")]
    pub mechanism: MechanismTable,
}

/// Which optional variables the exported FMU declares.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// `slider.position`, `slider.velocity` outputs.
    #[serde(default = "default_true")]
    pub slider: bool,
    /// `slider.force` input.
    #[serde(default = "default_true")]
    pub slider_force: bool,
    /// `pinB.*`, `pinC.*` outputs.
    #[serde(default = "default_true")]
    pub pin_forces: bool,
    /// `crank.torque` output.
    #[serde(default = "default_true")]
    pub crank_torque: bool,
    /// How many `rod.frequency[k]` calculated parameters (capped at the number that exist).
    #[serde(default = "default_frequencies")]
    pub frequencies: usize,
    /// `rod.axial_force_mid`, `rod.bending_moment_mid`, `rod.stress_max`,
    /// `rod.stress_max_position` outputs (needs `fibre_distance` at every `[[rod.section]]`
    /// station). Left out of a written scene when false.
    #[serde(default, skip_serializing_if = "is_false")]
    pub stress: bool,
    /// FMI 3.0 only: number N of points of the `rod.shape` array output (0 = no such output,
    /// else 2..=1001). Left out of a written scene when it is the default.
    #[serde(
        default = "default_shape_points",
        skip_serializing_if = "is_default_shape_points"
    )]
    pub shape_points: usize,
}

fn default_shape_points() -> usize {
    11
}

fn is_default_shape_points(n: &usize) -> bool {
    *n == default_shape_points()
}

fn is_false(b: &bool) -> bool {
    !*b
}

impl Default for OutputSpec {
    fn default() -> Self {
        OutputSpec {
            slider: true,
            slider_force: true,
            pin_forces: true,
            crank_torque: true,
            frequencies: default_frequencies(),
            stress: false,
            shape_points: default_shape_points(),
        }
    }
}

/// The default experiment written to modelDescription.xml and used by the run command.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExperimentSpec {
    pub start_time: f64,
    pub stop_time: f64,
    /// Communication step, s.
    pub step_size: f64,
    /// Constant crank speed of the default experiment, rad/s.
    pub crank_speed: f64,
}

/// The window of the crank speed, rad/s: `[experiment] crank_speed` and the input
/// `crank.speed` (the crank law's [`crate::mechanism::crank::SPEED_WINDOW`]).
pub use crate::mechanism::crank::SPEED_WINDOW as CRANK_SPEED_WINDOW;

pub use crate::cosimulation::experiment::{check_experiment_times, EXPERIMENT_STEP_RANGE};
pub use crate::limits::EXPERIMENT_TIME_LIMIT;

/// The scene keys of the experiment's start and stop time.
pub const EXPERIMENT_TIME_KEYS: [&str; 2] = ["experiment.start_time", "experiment.stop_time"];

impl ExperimentSpec {
    /// Start and stop time as [`check_experiment_times`] checks them, the step in `[1e-9, 1]` s
    /// and not longer than the run, the crank speed within its input window. Each error names
    /// the value that is wrong.
    pub fn validate(&self) -> Result<(), ModelError> {
        check_experiment_times(self.start_time, Some(self.stop_time), EXPERIMENT_TIME_KEYS)?;
        let (low, high) = EXPERIMENT_STEP_RANGE;
        let span = self.stop_time - self.start_time;
        if !(self.step_size.is_finite()
            && self.step_size >= low
            && self.step_size <= high.min(span))
        {
            return Err(ModelError::InvalidParameter {
                name: "experiment.step_size",
                value: self.step_size,
                allowed: format!(
                    "a finite value in [{low:e}, {:e}] s (at most 1 s and at most stop_time - start_time)",
                    high.min(span)
                ),
            });
        }
        let window = CRANK_SPEED_WINDOW;
        require_within(
            "experiment.crank_speed",
            self.crank_speed,
            -window,
            window,
            "rad/s",
        )
    }
}

impl Default for ExperimentSpec {
    fn default() -> Self {
        ExperimentSpec {
            start_time: 0.0,
            // Two revolutions at 150 rad/s rounded to the 1e-4 s step grid (838 steps): fixed-step
            // masters need a stop time on the grid.
            stop_time: 0.0838,
            step_size: 1e-4,
            crank_speed: 150.0,
        }
    }
}

fn default_true() -> bool {
    true
}
fn default_frequencies() -> usize {
    6
}

/// The default scene's TOML, compiled in (the benchmark rod of the CDI parametric study,
/// 150 rad/s).
pub const DEFAULT_SCENE_TOML: &str = include_str!("../scenes/benchmark.toml");

impl Scene {
    /// Parse a scene from TOML text; `origin` names the file in error messages.
    /// The settings no importer can set are checked here ([`Scene::validate_settings`]); the
    /// physical parameters when the model is built.
    pub fn from_toml_str(text: &str, origin: &str) -> Result<Scene, ModelError> {
        // The parser's message quotes the offending line: each line cut to a bounded echo.
        let scene: Scene = toml::from_str(text).map_err(|e| ModelError::Scene {
            origin: origin.to_string(),
            message: crate::text::echo_lines(e.to_string().trim()),
        })?;
        scene.validate_settings().map_err(|e| ModelError::Scene {
            origin: origin.to_string(),
            message: e.to_string(),
        })?;
        Ok(scene)
    }

    /// Check the keys an importer cannot set against their ranges (docs/fmu.md, "Input
    /// windows"), before anything uses them: the `[solver]` settings but `solver.tolerance`
    /// ([`SolverSpec::validate_settings`]), the number of `[[rod.section]]` stations
    /// ([`crate::beam::MAX_STATIONS`]), the `[experiment]` and the texts written into
    /// modelDescription.xml ([`Scene::validate_texts`]). Each error names the key and its
    /// range.
    pub fn validate_settings(&self) -> Result<(), ModelError> {
        self.validate_texts()?;
        self.solver.validate_settings()?;
        crate::beam::section_table::check_station_count(self.rod.section.len())?;
        self.experiment.validate()
    }

    /// The scene's texts that modelDescription.xml carries (`name` as `modelName` and
    /// `modelIdentifier`, `description`; every other text there is the model's own) hold only
    /// characters an XML 1.0 attribute carries unchanged: no control character (U+0000 to
    /// U+001F, tab and line breaks included), no U+FFFE or U+FFFF. The error names the key,
    /// the character and its position.
    pub fn validate_texts(&self) -> Result<(), ModelError> {
        for (key, text) in [("name", &self.name), ("description", &self.description)] {
            if let Some((position, c)) = crate::text::first_non_xml_char(text) {
                return Err(ModelError::InvalidText {
                    key,
                    character: c,
                    position,
                    length: text.chars().count(),
                });
            }
        }
        Ok(())
    }

    /// Read and parse a scene file, at most [`crate::limits::SCENE_FILE_CAP`] bytes.
    pub fn from_file(path: &Path) -> Result<Scene, ModelError> {
        let cap = crate::limits::SCENE_FILE_CAP;
        let origin = crate::text::echo(&path.display().to_string());
        let text = crate::limits::read_text(path, cap, "the scene file").map_err(|message| {
            ModelError::Scene {
                origin: origin.clone(),
                message,
            }
        })?;
        Scene::from_toml_str(&text, &origin)
    }

    /// The default scene: the benchmark rod of the CDI parametric study at 150 rad/s.
    pub fn benchmark() -> Scene {
        Scene::from_toml_str(DEFAULT_SCENE_TOML, "scenes/benchmark.toml")
            .expect("the compiled-in default scene parses")
    }

    /// Where the scene gives no `[crank] design_speed`, take `|speed|` (rad/s) as the run's
    /// highest crank speed, the one `rod.model = auto` chooses for: it becomes the design speed,
    /// or for a start from rest (0) the experiment's crank speed the design speed falls back on.
    /// Returns the speed taken; `None` where the scene gives one or `|speed|` lies outside
    /// `[0, DESIGN_SPEED_MAX]`.
    pub fn take_design_speed(&mut self, speed: f64) -> Option<f64> {
        let speed = speed.abs();
        if self.crank.design_speed != 0.0
            || speed.is_nan()
            || speed > crate::mechanism::DESIGN_SPEED_MAX
        {
            return None;
        }
        if speed > 0.0 {
            self.crank.design_speed = speed;
        } else {
            self.experiment.crank_speed = 0.0;
        }
        Some(speed)
    }

    /// The mechanism this scene describes (what [`crate::mechanism::MechanismParts::new`]
    /// takes).
    pub fn mechanism_spec(&self) -> MechanismSpec {
        let mut crank = self.crank.clone();
        if crank.design_speed == 0.0 && self.experiment.crank_speed.is_finite() {
            crank.design_speed = self.experiment.crank_speed.abs();
        }
        MechanismSpec {
            crank,
            rod: self.rod.clone(),
            slider: self.slider.clone(),
            solver: self.solver.clone(),
            start: self.start.clone(),
            mechanism: self.mechanism.clone(),
            section_loads: self.outputs.stress,
        }
    }

    /// FNV-1a 64 of the model-defining part of the scene (without name, description, outputs
    /// and experiment): identifies the model of a serialized state.
    pub fn fingerprint(&self) -> u64 {
        let mut s = self.clone();
        s.name.clear();
        s.description.clear();
        s.outputs = Default::default();
        s.experiment = Default::default();
        crate::hash::fnv1a_64(s.to_toml().as_bytes())
    }

    /// Write the scene back as TOML (the FMU ships its scene in `resources/scene.toml`).
    pub fn to_toml(&self) -> String {
        toml::to_string(self).expect("a scene always serializes")
    }
}
