//! The simulation facade: one slider-crank with a flexible rod, driven by crank inputs.
//!
//! This is the whole surface the model's self-description (`model`, and through it the FMI
//! layer) and the command-line tools use. It knows nothing of FMI: times in s, angles in rad,
//! forces in N.
//!
//! Input law between communication points (docs/fmu.md, "Behaviour"):
//! `theta(t_k + s) = theta_k + omega_k s + alpha_k s^2 / 2 + j_k s^3 / 6`,
//! `omega(t_k + s) = omega_k + alpha_k s + j_k s^2 / 2`.

use crate::error::ModelError;
use crate::mechanism::crank;
use crate::mechanism::{integrator_choice, Mechanism, MechanismParts, MechanismState, Outputs};
pub use crate::mechanism::{CrankInput, StepStats};
use crate::scene::Scene;

/// A saved state: restoring it and replaying the same calls gives bit-identical outputs.
#[derive(Clone, Debug, PartialEq)]
pub struct Snapshot {
    state: MechanismState,
}

impl Snapshot {
    /// The time of the saved state, s.
    pub fn time(&self) -> f64 {
        self.state.time
    }
}

/// One slider-crank simulation.
pub struct Simulation {
    mechanism: Mechanism,
    /// Identifies the model in serialized states ([`Scene::fingerprint`] with the rod model
    /// `auto` built and its segment count).
    fingerprint: u64,
    state: MechanismState,
    /// The warning that `rod.error_estimate` passed `solver.tolerance` was given (once per
    /// simulation).
    error_estimate_warned: bool,
    /// The warning of `error_estimate_warned` not yet collected: time, estimate, peak.
    estimate_warning: Option<[f64; 3]>,
}

/// Magic bytes and version of serialized snapshots.
const SNAPSHOT_MAGIC: &[u8; 8] = b"FLEXROD\0";
const SNAPSHOT_VERSION: u32 = 7;

/// The inputs of a simulation at one moment ([`Simulation::inputs_snapshot`]).
#[derive(Clone, Copy, Debug)]
pub struct InputSnapshot {
    input: CrankInput,
    input_time: f64,
    previous_input: CrankInput,
    previous_input_time: f64,
    slider_force: f64,
}

/// Largest magnitude of the slider force, N.
pub const SLIDER_FORCE_WINDOW: f64 = 1e8;

/// Largest magnitudes of the inputs (past them no output can be trusted): the crank law's
/// angle, speed and acceleration ([`crate::mechanism::crank`]), the slider force.
pub const INPUT_WINDOWS: [f64; 4] = [
    crank::ANGLE_WINDOW,
    crank::SPEED_WINDOW,
    crank::ACCELERATION_WINDOW,
    SLIDER_FORCE_WINDOW,
];

pub use crate::mechanism::crank::JERK_WINDOW;

impl Simulation {
    /// Build the model of `scene`: validate the parameters, preprocess the rod (modes,
    /// shape integrals). Errors name the parameter and its allowed range.
    pub fn new(scene: &Scene) -> Result<Simulation, ModelError> {
        let parts = MechanismParts::new(&scene.mechanism_spec())?;
        let choice = integrator_choice::choose(&parts.spec().solver, parts.facts())?;
        let mechanism = Mechanism::new(parts, choice)?;
        let state = mechanism.initial_state(0.0, CrankInput::default(), 0.0)?;
        let built = format!(
            "{:016x} {} {}",
            scene.fingerprint(),
            mechanism.spec.rod.model.name(),
            mechanism.spec.rod.elements
        );
        Ok(Simulation {
            mechanism,
            fingerprint: crate::hash::fnv1a_64(built.as_bytes()),
            state,
            error_estimate_warned: false,
            estimate_warning: None,
        })
    }

    /// Natural frequencies of the rod under its reference conditions, Hz, lowest first
    /// (all of them, retained or not).
    pub fn frequencies_hz(&self) -> &[f64] {
        self.mechanism.frequencies_hz()
    }

    /// The rod model and what it keeps (the FFR rod: the retained modes, bending or axial), and
    /// the integrator, in words.
    pub fn describe(&self) -> String {
        let (integrator, _) = self.mechanism.integrator_name();
        format!(
            "{}; {}; integrator {integrator}",
            self.mechanism.rod.describe(),
            self.mechanism.physics.describe()
        )
    }

    /// The rod as built, in the scene's words: the rod model and its settings (`auto`
    /// resolved) and what it keeps. The FFR rod: how many modes it retains, bending and axial,
    /// and what chose them (the band `rod.mode_band_hz`, else `rod.modes`), then the retained
    /// modes themselves (`"rod.model = ffr, rod.elements = 8, rod.reference = simply_supported,
    /// rod.mass = consistent; 3 modes retained (2 bending, 1 axial), every mode up to
    /// rod.mode_band_hz = 6000 Hz; FFR rod, modes kept: 2012 Hz bending, ..."`).
    pub fn rod_summary(&self) -> String {
        let spec = &self.mechanism.spec.rod;
        let rod = &self.mechanism.rod;
        let mut text = format!(
            "rod.model = {}, rod.elements = {}",
            spec.model.name(),
            spec.elements
        );
        if spec.model == crate::rod::RodModelKind::Ffr {
            let kept = rod.elastic_coordinates().map_or(0, |r| r.len());
            let axial = rod.axial_mode_indices().len();
            let chosen = match spec.mode_band_hz {
                Some(band) => format!(
                    "every mode up to rod.mode_band_hz = {} Hz",
                    crate::text::number(band)
                ),
                None if spec.axial_in_addition => format!(
                    "rod.modes = {} bending modes, the axial in addition",
                    spec.modes
                ),
                None => format!("rod.modes = {}", spec.modes),
            };
            text += &format!(
                ", rod.reference = {}, rod.mass = {}; {kept} modes retained ({} bending, {axial} axial), {chosen}",
                spec.reference.name(),
                spec.mass.name(),
                kept - axial,
            );
        }
        format!("{text}; {}", rod.describe())
    }

    /// Consistent start at `t0`: rod undeformed, rigid coordinates and velocities
    /// consistent with the crank input, accelerations and joint forces consistent too.
    pub fn start(
        &mut self,
        t0: f64,
        input: CrankInput,
        slider_force: f64,
    ) -> Result<(), ModelError> {
        check_input(input, slider_force)?;
        self.state = self.mechanism.initial_state(t0, input, slider_force)?;
        Ok(())
    }

    /// Set the crank input that holds from the current time on. Set again at the same time,
    /// the last one holds, and the law before the first stays the one the state followed
    /// (which the next step compares the new law with).
    pub fn set_input(&mut self, input: CrankInput) -> Result<(), ModelError> {
        check_input(input, self.state.slider_force)?;
        if self.state.input_time != self.state.time {
            self.state.previous_input = self.state.input;
            self.state.previous_input_time = self.state.input_time;
        }
        self.state.input = input;
        self.state.input_time = self.state.time;
        Ok(())
    }

    /// The inputs in force (crank laws and slider force), to put back with
    /// [`Simulation::restore_inputs`] when a step that set them is refused.
    pub fn inputs_snapshot(&self) -> InputSnapshot {
        let s = &self.state;
        InputSnapshot {
            input: s.input,
            input_time: s.input_time,
            previous_input: s.previous_input,
            previous_input_time: s.previous_input_time,
            slider_force: s.slider_force,
        }
    }

    /// Put back inputs saved with [`Simulation::inputs_snapshot`]: a refused step leaves the
    /// simulation exactly as before it (the next step then sees the same change of crank law
    /// as a run that never tried, and restarts on it alike).
    pub fn restore_inputs(&mut self, saved: InputSnapshot) {
        let s = &mut self.state;
        s.input = saved.input;
        s.input_time = saved.input_time;
        s.previous_input = saved.previous_input;
        s.previous_input_time = saved.previous_input_time;
        s.slider_force = saved.slider_force;
    }

    /// Refuse, before anything changes, a communication step `h` that needs more internal
    /// steps than [`crate::mechanism::MAX_INTERNAL_STEPS`] (`ModelError::TooMuchWork`).
    pub fn check_work(&self, h: f64) -> Result<(), ModelError> {
        self.mechanism.check_work(self.state.time, h)
    }

    /// Set the external slider force along +x, N, from the current time on.
    pub fn set_slider_force(&mut self, force: f64) -> Result<(), ModelError> {
        check_input(self.state.input, force)?;
        self.state.slider_force = force;
        Ok(())
    }

    /// Current time, s.
    pub fn time(&self) -> f64 {
        self.state.time
    }

    /// Integrate from the current time to `time() + h` in internal steps no larger than the
    /// scene's solver step, landing exactly on `time() + h`. On failure the state from before
    /// the call is kept and the error says when and why.
    pub fn advance(&mut self, h: f64) -> Result<StepStats, ModelError> {
        if !(h.is_finite() && h > 0.0) {
            return Err(ModelError::InvalidParameter {
                name: "communication step h",
                value: h,
                allowed: "a finite value > 0".into(),
            });
        }
        self.mechanism.advance(&mut self.state, h)?;
        let estimate = self.error_estimate();
        let tolerance = self.mechanism.spec.solver.tolerance;
        if estimate > tolerance && !self.error_estimate_warned {
            // Formatted by `take_warnings`, outside the step (no allocation while stepping).
            self.error_estimate_warned = true;
            self.estimate_warning = Some([self.state.time, estimate, self.state.amplitude]);
        }
        Ok(self.state.stats)
    }

    /// Outputs at the current time (docs/physics.md, "Output definitions").
    pub fn outputs(&self) -> Outputs {
        Outputs {
            error_estimate: self.error_estimate(),
            ..self.state.outputs
        }
    }

    /// `rod.error_estimate` now: the estimated error of `v_mid / L` relative to its peak so
    /// far, model and integration together, with the free vibration the start rang
    /// ([`crate::rod::PhysicsChoice::error_estimate`]).
    pub fn error_estimate(&self) -> f64 {
        self.mechanism
            .physics
            .error_estimate(self.state.amplitude, self.state.start_vibration)
    }

    /// Cumulative integrator counters.
    pub fn stats(&self) -> StepStats {
        self.state.stats
    }

    /// Warnings raised since the last call (e.g. deflection beyond the small-deformation range).
    pub fn take_warnings(&mut self) -> Vec<String> {
        let mut warnings = std::mem::take(&mut self.state.warnings);
        if let Some([time, estimate, peak]) = self.estimate_warning.take() {
            warnings.push(format!(
                "rod.error_estimate = {estimate:.2e} at t = {} s exceeds solver.tolerance = {:e} (model and integration, peak |v_mid/L| so far {peak:.2e}; {})",
                crate::text::time(time),
                self.mechanism.spec.solver.tolerance,
                self.mechanism.physics.summary()
            ));
        }
        warnings
    }

    /// The model (for tools that need energies, momenta, the rod itself).
    pub fn mechanism(&self) -> &Mechanism {
        &self.mechanism
    }

    /// The current state (read only).
    pub fn state(&self) -> &MechanismState {
        &self.state
    }

    /// Save the state.
    pub fn snapshot(&self) -> Snapshot {
        Snapshot {
            state: self.state.clone(),
        }
    }

    /// Restore a state saved from this simulation.
    pub fn restore(&mut self, snapshot: &Snapshot) {
        self.state.clone_from(&snapshot.state);
    }

    /// Serialize the state on its own: magic, version, then [`Simulation::state_to_bytes`].
    pub fn snapshot_to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::new();
        out.extend_from_slice(SNAPSHOT_MAGIC);
        out.extend_from_slice(&SNAPSHOT_VERSION.to_le_bytes());
        out.extend_from_slice(&self.state_to_bytes());
        out
    }

    /// Restore a state from bytes written by [`Simulation::snapshot_to_bytes`] of the same
    /// model. Foreign, truncated or other-model bytes are rejected and the state is unchanged.
    pub fn restore_from_bytes(&mut self, bytes: &[u8]) -> Result<(), ModelError> {
        if bytes.len() < 12 || &bytes[..8] != SNAPSHOT_MAGIC {
            return Err(rejected(
                "it does not start with this model's header (foreign or truncated bytes)",
            ));
        }
        let version = u32::from_le_bytes(bytes[8..12].try_into().unwrap());
        if version != SNAPSHOT_VERSION {
            return Err(rejected(&format!(
                "version {version}, this model reads version {SNAPSHOT_VERSION}"
            )));
        }
        self.restore_state_bytes(&bytes[12..])
    }

    /// The state as part of a larger saved state (whose format carries the version): the
    /// model's 64-bit fingerprint, then the numbers (`MechanismState::write_bytes`, little
    /// endian).
    pub fn state_to_bytes(&self) -> Vec<u8> {
        let mut out = self.fingerprint.to_le_bytes().to_vec();
        self.state.write_bytes(&mut out);
        out
    }

    /// Restore a state from bytes written by [`Simulation::state_to_bytes`] of the same model:
    /// the fingerprint must be this model's, every number in the range of an accepted step and
    /// the crank laws within the input windows. On error the state is unchanged.
    pub fn restore_state_bytes(&mut self, bytes: &[u8]) -> Result<(), ModelError> {
        if bytes.len() < 8 {
            return Err(rejected(&format!(
                "{} bytes cannot hold the model's fingerprint (truncated bytes)",
                bytes.len()
            )));
        }
        let fingerprint = u64::from_le_bytes(bytes[..8].try_into().unwrap());
        if fingerprint != self.fingerprint {
            return Err(rejected(
                "it was saved by a model with other parameters or another scene",
            ));
        }
        let mut state = self.state.clone();
        state
            .read_bytes(&bytes[8..])
            .map_err(|m: String| rejected(&m))?;
        // The input windows of the set calls, for the law in force and the one before it.
        check_input(state.input, state.slider_force).map_err(|e| rejected(&e.to_string()))?;
        check_input(state.previous_input, state.slider_force)
            .map_err(|e| rejected(&format!("the previous law: {e}")))?;
        self.state = state;
        Ok(())
    }
}

/// A refused serialized state, with the reason.
fn rejected(reason: &str) -> ModelError {
    ModelError::State {
        message: format!("serialized state rejected: {reason}"),
    }
}

fn check_input(input: CrankInput, slider_force: f64) -> Result<(), ModelError> {
    input.check()?;
    if !(slider_force.is_finite() && slider_force.abs() <= SLIDER_FORCE_WINDOW) {
        return Err(ModelError::InvalidParameter {
            name: "slider.force",
            value: slider_force,
            allowed: format!("a finite value with |value| <= {SLIDER_FORCE_WINDOW:e} N"),
        });
    }
    Ok(())
}
