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

use crate::error::ModelError;

/// The whole scene.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Short identifier; also the FMU's `modelIdentifier` unless `[fmu] model_identifier` says otherwise.
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
}

/// The rod's state at the start time.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum StartDeflection {
    /// Undeformed, moving rigidly with the crank (physics.md, "Initial state").
    #[default]
    Undeformed,
    /// Deflected by the inertia loads of the start motion, with no elastic velocity or
    /// acceleration (FFR rod): no start transient at constant speed.
    QuasiStatic,
}

/// How the simulation starts.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct StartSpec {
    #[serde(default)]
    pub deflection: StartDeflection,
}

/// The crank A-B (massless; its motion is an input).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CrankSpec {
    /// Crank length r, m.
    pub length: f64,
}

/// Which rod model computes the connecting rod.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RodModelKind {
    /// Floating frame of reference with component modes (seeds 000 and 001).
    Ffr,
    /// Rigid segments joined by rotational springs (seed 002).
    Segments,
}

/// Reference conditions of the FFR rod (physics.md, "Rod model 1").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ReferenceKind {
    /// `u = v = 0` at B, `v = 0` at C; frame at B, x axis through C.
    SimplySupported,
    /// Free-free modes with the rigid-body modes removed; frame at the centre of mass.
    MeanAxis,
    /// All three coordinates of the middle node zero (needs an even number of elements).
    BodyFixedMid,
    /// All three coordinates of the B node zero (a cantilever from B).
    Cantilever,
}

/// Mass matrix of the beam element.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum MassKind {
    #[default]
    Consistent,
    Lumped,
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
    /// Cross-section area A, m^2.
    pub area: f64,
    /// Second moment of area I, m^4.
    pub area_moment: f64,
    /// Modal damping ratio (FFR) or joint damping ratio of the first bending mode (segments); 0 = undamped.
    #[serde(default)]
    pub damping_ratio: f64,
    /// Beam elements (FFR) or rigid segments (segments).
    pub elements: usize,
    /// Reference conditions (FFR only).
    #[serde(default = "default_reference")]
    pub reference: ReferenceKind,
    /// Retained modes (FFR only), lowest first.
    #[serde(default = "default_modes")]
    pub modes: usize,
    /// Consistent or lumped element mass (FFR only).
    #[serde(default)]
    pub mass: MassKind,
    /// Axial force acting on bending (geometric stiffness); physics.md, "What linear modes miss".
    #[serde(default = "default_true")]
    pub axial_stiffening: bool,
    /// Segments only: keep the axial springs E A / l (prismatic joints) between segments.
    #[serde(default)]
    pub axial_springs: bool,
}

/// The slider at C.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SliderSpec {
    /// Slider mass m_s, kg (0 allowed).
    #[serde(default)]
    pub mass: f64,
}

impl Default for SliderSpec {
    fn default() -> Self {
        SliderSpec { mass: 0.0 }
    }
}

/// The time integrator.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum SolverMethod {
    /// Implicit generalized-alpha on the index-3 DAE (stiff modes allowed).
    #[default]
    GeneralizedAlpha,
    /// Explicit fourth-order Runge-Kutta with coordinate projection (non-stiff scenes only:
    /// `2 pi f_max h < 2.78` for the highest retained frequency; the step is capped there).
    Rk4,
    /// RK4 if the scene's step is within its stability limit (`2 pi f_max h <= 2.5`), else
    /// generalized-alpha: the explicit path where it is stable, the implicit one when the rod is
    /// made stiff (more modes, the segment chain, a stiffer material).
    Auto,
}

/// Settings of the integrator (generalized-alpha, Arnold and Bruls 2007, or explicit RK4).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSpec {
    /// The integrator.
    #[serde(default)]
    pub method: SolverMethod,
    /// Largest internal step, s. Communication steps are split into equal sub-steps no larger than this.
    #[serde(default = "default_step")]
    pub step: f64,
    /// Spectral radius at infinity, in [0, 1]: 1 = no numerical damping, 0 = asymptotic annihilation.
    #[serde(default = "default_rho_inf")]
    pub rho_inf: f64,
    /// Newton tolerance on the scaled correction.
    #[serde(default = "default_newton_tol")]
    pub newton_tolerance: f64,
    /// Newton iterations before a step counts as failed.
    #[serde(default = "default_newton_iter")]
    pub max_newton_iterations: usize,
    /// How many times a failed step is halved before the step is reported as failed.
    #[serde(default = "default_halvings")]
    pub max_halvings: usize,
}

impl Default for SolverSpec {
    fn default() -> Self {
        SolverSpec {
            method: SolverMethod::GeneralizedAlpha,
            step: default_step(),
            rho_inf: default_rho_inf(),
            newton_tolerance: default_newton_tol(),
            max_newton_iterations: default_newton_iter(),
            max_halvings: default_halvings(),
        }
    }
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
}

impl Default for OutputSpec {
    fn default() -> Self {
        OutputSpec {
            slider: true,
            slider_force: true,
            pin_forces: true,
            crank_torque: true,
            frequencies: default_frequencies(),
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

impl Default for ExperimentSpec {
    fn default() -> Self {
        ExperimentSpec {
            start_time: 0.0,
            stop_time: 4.0 * std::f64::consts::PI / 150.0,
            step_size: 1e-4,
            crank_speed: 150.0,
        }
    }
}

fn default_reference() -> ReferenceKind {
    ReferenceKind::SimplySupported
}
fn default_modes() -> usize {
    4
}
fn default_true() -> bool {
    true
}
fn default_step() -> f64 {
    1e-4
}
fn default_rho_inf() -> f64 {
    0.8
}
fn default_newton_tol() -> f64 {
    1e-9
}
fn default_newton_iter() -> usize {
    8
}
fn default_halvings() -> usize {
    6
}
fn default_frequencies() -> usize {
    6
}

/// The default scene's TOML, compiled in (the benchmark rod of seed 001, 150 rad/s).
pub const DEFAULT_SCENE_TOML: &str = include_str!("../scenes/benchmark.toml");

impl Scene {
    /// Parse a scene from TOML text; `origin` names the file in error messages.
    pub fn from_toml_str(text: &str, origin: &str) -> Result<Scene, ModelError> {
        toml::from_str(text).map_err(|e| ModelError::Scene {
            origin: origin.to_string(),
            message: e.to_string().trim().to_string(),
        })
    }

    /// Read and parse a scene file.
    pub fn from_file(path: &Path) -> Result<Scene, ModelError> {
        let text = std::fs::read_to_string(path).map_err(|e| ModelError::Scene {
            origin: path.display().to_string(),
            message: format!("cannot read the file: {e}"),
        })?;
        Scene::from_toml_str(&text, &path.display().to_string())
    }

    /// The default scene: seed 001's benchmark rod at 150 rad/s.
    pub fn benchmark() -> Scene {
        Scene::from_toml_str(DEFAULT_SCENE_TOML, "scenes/benchmark.toml")
            .expect("the compiled-in default scene parses")
    }

    /// Write the scene back as TOML (the FMU ships its scene in `resources/scene.toml`).
    pub fn to_toml(&self) -> String {
        toml::to_string(self).expect("a scene always serializes")
    }
}
