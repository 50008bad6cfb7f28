//! Life cycle: debug logging, `fmi2SetupExperiment`, initialization mode, terminate, reset,
//! and building and starting the simulation from the instance's parameters.

use std::borrow::Cow;

use super::{model_error, Instance};
use crate::fmi::inputs::{Experiment, Inputs};
use crate::fmi::state_machine::{Call, MachineState};
use crate::fmi::status::{FmiError, FmiResult, Status};
use crate::scene::Scene;
use crate::simulation::Simulation;

impl Instance {
    /// `fmi2SetDebugLogging`.
    pub fn set_debug_logging(&mut self, on: bool, categories: &[Cow<str>]) -> FmiResult<Status> {
        let names: Vec<&str> = categories.iter().map(|c| c.as_ref()).collect();
        self.logger.set_debug_logging(on, &names)?;
        Ok(Status::Ok)
    }

    /// `fmi2SetupExperiment`. The tolerance is not used: the solver settings come from the scene.
    pub fn setup_experiment(
        &mut self,
        tolerance: Option<f64>,
        start_time: f64,
        stop_time: Option<f64>,
    ) -> FmiResult<Status> {
        if !start_time.is_finite() {
            return Err(FmiError::rejected(format!(
                "startTime = {start_time} is out of range: allowed a finite value"
            )));
        }
        if let Some(stop) = stop_time {
            if !(stop.is_finite() && stop >= start_time) {
                return Err(FmiError::rejected(format!(
                    "stopTime = {stop} is out of range: allowed a finite value >= startTime = {start_time}"
                )));
            }
        }
        if let Some(tol) = tolerance {
            self.logger.event(&format!(
                "{}: tolerance = {tol} is not used; the integrator follows the scene's [solver] settings (step = {} s, newton_tolerance = {}; the parameter solver.tolerance sets the error control)",
                Call::SetupExperiment.name(self.standard),
                self.scene.solver.step, self.scene.solver.newton_tolerance
            ));
        }
        self.experiment = Experiment {
            start_time,
            stop_time,
        };
        Ok(Status::Ok)
    }

    /// `fmi2EnterInitializationMode`.
    pub fn enter_initialization_mode(&mut self) -> FmiResult<Status> {
        self.state = MachineState::InitializationMode;
        self.started = false;
        Ok(Status::Ok)
    }

    /// `fmi2ExitInitializationMode`: build the model from the instance's scene (if not yet
    /// built for a read in initialization mode) and start it consistently with the inputs.
    pub fn exit_initialization_mode(&mut self) -> FmiResult<Status> {
        if let Err(e) = self.ensure_started() {
            // Nothing may look started: outputs read in the Error state fail with this reason.
            self.simulation = None;
            self.started = false;
            self.failure = Some(e.message.clone());
            return Err(FmiError::failed(e.message));
        }
        let t0 = self.experiment.start_time;
        // The simulation starts with the current slider force; the crank acceleration set in
        // initialization mode holds for the first step (it was set at t0).
        self.inputs.force_changed = false;
        self.state = MachineState::StepComplete;
        self.last_step = Status::Ok;
        if self.logger.events_on() {
            let lowest = self
                .simulation
                .as_ref()
                .and_then(|s| s.frequencies_hz().first().copied());
            let frequency = match lowest {
                Some(f) => format!("lowest natural frequency {f} Hz"),
                None => "no natural frequency (rigid rod)".to_string(),
            };
            let model = self
                .simulation
                .as_ref()
                .map(|s| s.describe())
                .unwrap_or_default();
            self.logger.event(&format!(
                "initialized at t = {t0} s with crank.angle = {} rad, crank.speed = {} rad/s; {frequency}; {model}",
                self.inputs.angle, self.inputs.speed,
            ));
        }
        Ok(self.take_warnings())
    }

    /// `fmi2Terminate`.
    pub fn terminate(&mut self) -> FmiResult<Status> {
        self.state = MachineState::Terminated;
        Ok(Status::Ok)
    }

    /// `fmi2Reset`: back to `Instantiated` with the start values of the exported scene and
    /// the logging settings of `fmi2Instantiate` (its `loggingOn`). Saved FMU states stay
    /// valid.
    pub fn reset(&mut self) -> FmiResult<Status> {
        self.logger.reset();
        self.scene = self.exported.clone();
        self.inputs = Inputs::from_start_values(&self.table);
        self.experiment = Experiment {
            start_time: self.scene.experiment.start_time,
            stop_time: None,
        };
        self.simulation = None;
        self.started = false;
        self.last_step = Status::Ok;
        self.failure = None;
        self.state = MachineState::Instantiated;
        Ok(Status::Ok)
    }

    /// Build the simulation for the current scene if needed and start it with the current
    /// inputs at the start time.
    pub(super) fn ensure_started(&mut self) -> FmiResult<()> {
        if self.simulation.is_none() {
            check_geometry(&self.scene)?;
            let simulation =
                Simulation::new(&self.scene).map_err(|e| FmiError::rejected(model_error(e)))?;
            let available = simulation.frequencies_hz().len();
            let declared = self.table.frequency_count();
            if available < declared {
                return Err(FmiError::rejected(format!(
                    "rod.elements = {} with these rod.model and rod.reference leaves {available} natural frequencies, but this FMU declares rod.frequency[1..{declared}]: allowed parameters that leave at least {declared} (e.g. more elements), or export the scene with [outputs] frequencies <= {available}",
                    self.scene.rod.elements
                )));
            }
            self.simulation = Some(simulation);
            self.started = false;
        }
        if !self.started {
            let input = self.inputs.crank_input();
            let force = self.inputs.slider_force;
            let t0 = self.experiment.start_time;
            if let Some(simulation) = self.simulation.as_mut() {
                simulation
                    .start(t0, input, force)
                    .map_err(|e| FmiError::rejected(model_error(e)))?;
            }
            self.started = true;
        }
        Ok(())
    }
}

/// The slider-crank turns a full revolution only with r < L; the core checks the rest.
fn check_geometry(scene: &Scene) -> FmiResult<()> {
    let (r, l) = (scene.crank.length, scene.rod.length);
    if r.is_finite() && l.is_finite() && r >= l {
        return Err(FmiError::rejected(format!(
            "crank.length = {r} m must be smaller than rod.length = {l} m: allowed 0 < crank.length < rod.length (otherwise the crank cannot turn a full revolution)"
        )));
    }
    Ok(())
}
