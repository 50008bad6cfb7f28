//! What a scene says about the mechanism around the rod: the crank, the slider, the start and
//! the integrator settings.

use serde::{Deserialize, Serialize};

use crate::error::{require_positive, require_within, ModelError};

/// The crank A-B (massless; its motion is an input).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CrankSpec {
    /// Crank length r, m.
    pub length: f64,
    /// The highest crank speed `|omega|` the run reaches, rad/s, for which `rod.model = auto`
    /// chooses the rod model ([`crate::rod::physics_choice`], "Rod model"); 0: the crank speed
    /// at the start (a scene: `[experiment] crank_speed`; the FMU: `|crank.speed|` when the
    /// model is built, written here then).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub design_speed: f64,
}

/// The largest `crank.design_speed`, rad/s: the window of the crank speed input.
pub const DESIGN_SPEED_MAX: f64 = 1e4;

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

/// The slider at C.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SliderSpec {
    /// Slider mass m_s, kg (0 allowed).
    #[serde(default)]
    pub mass: f64,
    /// `[slider.gas_force]`: a force on the slider as a function of the crank angle
    /// ([`super::gas_force`]), in addition to the `slider.force` input.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gas_force: Option<super::gas_force::GasForceTable>,
}

impl Default for SliderSpec {
    fn default() -> Self {
        SliderSpec {
            mass: 0.0,
            gas_force: None,
        }
    }
}

/// The `[mechanism]` table of a scene: the slider line and gravity (docs/real-rods.md).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct MechanismTable {
    /// The slider moves along the line `y = slider_offset`, m (0: through the crank centre A).
    #[serde(default)]
    pub slider_offset: f64,
    /// Gravitational acceleration `[g_x, g_y]`, m/s^2, global frame (default none).
    #[serde(default)]
    pub gravity: [f64; 2],
}

impl MechanismTable {
    /// No offset, no gravity (the table is then left out of a written scene).
    pub fn is_default(&self) -> bool {
        *self == MechanismTable::default()
    }
}

/// The rod's state at the start time.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum StartDeflection {
    /// Undeformed, moving rigidly with the crank (docs/physics.md, "Initial state").
    #[default]
    Undeformed,
    /// Deflected by the inertia loads of the start motion, with no elastic velocity or
    /// acceleration (the rods with modal coordinates: FFR, the chain on its modes): no start
    /// transient at constant speed.
    QuasiStatic,
}

/// How the simulation starts.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct StartSpec {
    #[serde(default)]
    pub deflection: StartDeflection,
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
    /// Dormand-Prince 5(4) with error control on the mechanism's own degrees of freedom (the
    /// FFR rod's modal coordinates; frame and slider follow from the constraints): the
    /// internal step is chosen by `solver.tolerance`, independent of the communication step.
    Dopri5,
    /// The classic RK4 with an embedded third-order estimate and the same error control on the
    /// mechanism's own degrees of freedom (what `auto` takes where the exponential form does not
    /// apply).
    Rk43,
    /// The exponential form of the RK4(3) pair (ETDRK4 with each mode's oscillator exact) on
    /// the FFR rod's closed-form minimal coordinates, also where `auto` would not take it
    /// (free modes that move the pins: there it usually needs more steps than
    /// [`SolverMethod::Rk43`]).
    Exponential,
    /// Error-controlled and on the mechanism's own degrees of freedom: the exponential ETDRK4(3)
    /// form with the modal oscillators exact where the modes are the mechanism's own
    /// oscillators (they leave the pins in place, as simply supported bending modes, or carry
    /// the slider as mass-loaded modes, `rod.loaded_modes`), at any stiffness; else, where the
    /// retained modes allow an explicit step (`2.5 / w_max >= 5e-6 s`), [`SolverMethod::Rk43`];
    /// error-controlled generalized-alpha for stiffer rods of other modes and for the segment
    /// chain (`crate::mechanism::integrator_choice`).
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
    /// Accuracy the error control aims at (`dopri5`): the pointwise error of the rod's
    /// deflection, relative to its peak, over a run. In [1e-10, 0.1].
    #[serde(default = "default_tolerance")]
    pub tolerance: f64,
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
            tolerance: default_tolerance(),
        }
    }
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
fn default_tolerance() -> f64 {
    1e-3
}
fn default_halvings() -> usize {
    6
}

/// The ranges of the `[solver]` keys (each checked by [`SolverSpec::validate`]; docs/fmu.md,
/// "Input windows"): the internal step in s, the Newton tolerance, the iteration and halving
/// counts. They bound the work of one internal step: at most `max_newton_iterations` Newton
/// iterations, split at most `max_halvings` times.
pub const SOLVER_STEP_RANGE: (f64, f64) = (1e-9, 1e-2);
/// `solver.newton_tolerance`: any positive normal double up to 1e-2 (a tolerance Newton cannot
/// meet fails the step, bounded by the iteration count).
pub const NEWTON_TOLERANCE_RANGE: (f64, f64) = (f64::MIN_POSITIVE, 1e-2);
/// `solver.max_newton_iterations`.
pub const MAX_NEWTON_ITERATIONS: usize = 100;
/// `solver.max_halvings` (the halving loop's stack holds one more).
pub use super::stepping::MAX_HALVINGS;

impl SolverSpec {
    /// Check every `[solver]` key against its range (each error names the key and the range).
    pub fn validate(&self) -> Result<(), ModelError> {
        self.validate_settings()?;
        let tol = self.tolerance;
        // Below 1e-10 of the peak the error control asks for more than double precision can
        // give over a run (at 5e-324 every step would refuse at the work bound).
        if !(tol.is_finite() && (1e-10..=0.1).contains(&tol)) {
            return Err(ModelError::InvalidParameter {
                name: "solver.tolerance",
                value: tol,
                allowed: "[1e-10, 0.1]: the pointwise deflection error relative to its peak".into(),
            });
        }
        Ok(())
    }

    /// The `[solver]` keys an importer cannot set (all but `solver.tolerance`, an FMU
    /// parameter checked when the model is built): checked when a scene is read, from a file
    /// or from a serialized state, before anything uses them.
    pub fn validate_settings(&self) -> Result<(), ModelError> {
        let (low, high) = SOLVER_STEP_RANGE;
        require_within("solver.step", self.step, low, high, "s")?;
        let rho = self.rho_inf;
        if !(rho.is_finite() && (0.0..=1.0).contains(&rho)) {
            return Err(ModelError::InvalidParameter {
                name: "solver.rho_inf",
                value: rho,
                allowed: "[0, 1]".into(),
            });
        }
        let (low, high) = NEWTON_TOLERANCE_RANGE;
        require_within(
            "solver.newton_tolerance",
            self.newton_tolerance,
            low,
            high,
            "",
        )?;
        if !(1..=MAX_NEWTON_ITERATIONS).contains(&self.max_newton_iterations) {
            return Err(ModelError::InvalidInteger {
                name: "solver.max_newton_iterations",
                value: self.max_newton_iterations as i64,
                allowed: format!("an integer in 1..={MAX_NEWTON_ITERATIONS}"),
            });
        }
        if self.max_halvings > MAX_HALVINGS {
            return Err(ModelError::InvalidInteger {
                name: "solver.max_halvings",
                value: self.max_halvings as i64,
                allowed: format!(
                    "an integer in 0..={MAX_HALVINGS} (a failed step split into at most 2^{MAX_HALVINGS} pieces)"
                ),
            });
        }
        Ok(())
    }
}

/// Everything that defines the mechanism: the parts of a scene below the FMU's concerns.
#[derive(Clone, Debug, PartialEq)]
pub struct MechanismSpec {
    pub crank: CrankSpec,
    pub rod: crate::rod::RodSpec,
    pub slider: SliderSpec,
    pub solver: SolverSpec,
    pub start: StartSpec,
    /// Slider line offset and gravity.
    pub mechanism: MechanismTable,
    /// Recover the section forces and stress with the outputs (`[outputs] stress = true`).
    pub section_loads: bool,
}

impl MechanismSpec {
    /// The rod's `auto` settings resolved for this mechanism ([`crate::rod::physics_choice`]):
    /// the slider's mass, the tolerance, and the crank at its design speed.
    pub fn choose_physics(
        &self,
    ) -> Result<(crate::rod::RodSpec, crate::rod::PhysicsChoice), ModelError> {
        let operating_point = crate::rod::physics_choice::OperatingPoint {
            crank_length: self.crank.length,
            crank_speed: self.crank.design_speed,
        };
        crate::rod::physics_choice::choose(
            &self.rod,
            self.slider.mass,
            self.solver.tolerance,
            &operating_point,
        )
    }

    /// Check the parameters the rod models do not check themselves (each error names the
    /// parameter and its allowed range): crank shorter than the rod, damping and slider mass
    /// not negative, solver settings in range.
    pub fn validate(&self) -> Result<(), ModelError> {
        let rod = &self.rod;
        rod.validate()?;
        if self.section_loads {
            rod.require_fibre_distance()?;
        }
        require_positive("crank.length", self.crank.length)?;
        require_within(
            "crank.design_speed",
            self.crank.design_speed,
            0.0,
            DESIGN_SPEED_MAX,
            "rad/s (0: the crank speed at the start)",
        )?;
        if self.crank.length >= rod.length {
            return Err(ModelError::InvalidParameter {
                name: "crank.length",
                value: self.crank.length,
                allowed: format!(
                    "0 < crank.length < rod.length = {} m (a longer crank cannot turn the mechanism)",
                    rod.length
                ),
            });
        }
        require_within("rod.damping_ratio", rod.damping_ratio, 0.0, 100.0, "")?;
        require_within("slider.mass", self.slider.mass, 0.0, 1e6, "kg")?;
        if let Some(gas) = &self.slider.gas_force {
            gas.validate()?;
        }
        let offset = self.mechanism.slider_offset;
        if !(offset.is_finite() && self.crank.length + offset.abs() < rod.length) {
            return Err(ModelError::InvalidParameter {
                name: "mechanism.slider_offset",
                value: offset,
                allowed: format!(
                    "abs(mechanism.slider_offset) < rod.length - crank.length = {} m (else the crank cannot turn)",
                    rod.length - self.crank.length
                ),
            });
        }
        for (name, g) in [
            ("mechanism.gravity[0]", self.mechanism.gravity[0]),
            ("mechanism.gravity[1]", self.mechanism.gravity[1]),
        ] {
            if !g.is_finite() {
                return Err(ModelError::InvalidParameter {
                    name,
                    value: g,
                    allowed: "a finite acceleration, m/s2".into(),
                });
            }
        }
        self.solver.validate()?;
        Ok(())
    }
}
