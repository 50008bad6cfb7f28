//! Life cycle: debug logging, `fmi2SetupExperiment`, initialization mode, terminate, reset,
//! and building and starting the simulation from the instance's parameters.

use crate::text::time;
use std::borrow::Cow;

use super::Instance;
use crate::cosimulation::CoSimulationModel;
use crate::fmi::experiment::Experiment;
use crate::fmi::state_machine::{Call, MachineState};
use crate::fmi::status::{FmiError, FmiResult, Status};

impl<M: CoSimulationModel + ?Sized> Instance<M> {
    /// `fmi2SetDebugLogging`.
    pub fn set_debug_logging(&mut self, on: bool, categories: &[Cow<str>]) -> FmiResult<Status> {
        let names: Vec<&str> = categories.iter().map(|c| c.as_ref()).collect();
        self.logger.set_debug_logging(on, &names)?;
        Ok(Status::Ok)
    }

    /// `fmi2SetupExperiment` (and the experiment of `fmi3EnterInitializationMode`): the times
    /// within the ranges of a scene's `[experiment]` ([`Experiment::check_times`]), refused
    /// before anything changes. The tolerance is not used: the solver settings come from the
    /// scene.
    pub fn setup_experiment(
        &mut self,
        tolerance: Option<f64>,
        start_time: f64,
        stop_time: Option<f64>,
    ) -> FmiResult<Status> {
        Experiment::check_times(start_time, stop_time, ["startTime", "stopTime"])
            .map_err(FmiError::rejected)?;
        if let Some(tol) = tolerance {
            self.logger.event(&format!(
                "{}: tolerance = {tol} is not used; {}",
                Call::SetupExperiment.name(self.standard),
                self.model.accuracy_note()
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
        self.model.invalidate(false);
        Ok(Status::Ok)
    }

    /// `fmi2ExitInitializationMode`: build the model from the instance's scene (if not yet
    /// built for a read in initialization mode) and start it consistently with the inputs.
    pub fn exit_initialization_mode(&mut self) -> FmiResult<Status> {
        if let Err(e) = self.ensure_started() {
            // Nothing may look started: outputs read in the Error state fail with this reason.
            self.model.discard_built();
            self.failure = Some(e.message.clone());
            return Err(FmiError::failed(e.message));
        }
        let t0 = self.experiment.start_time;
        self.model.begin_stepping();
        self.state = MachineState::StepComplete;
        self.last_step = Status::Ok;
        if self.logger.events_on() {
            self.logger.event(&format!(
                "initialized at t = {} s with {}",
                time(t0),
                self.model.start_summary()
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
        self.model.reset();
        self.experiment = Experiment {
            start_time: self.model.info().default_experiment.start_time,
            stop_time: None,
        };
        self.last_step = Status::Ok;
        self.failure = None;
        self.state = MachineState::Instantiated;
        Ok(Status::Ok)
    }

    /// Build the simulation for the current parameters if needed and start it with the
    /// current inputs at the start time.
    pub(super) fn ensure_started(&mut self) -> FmiResult<()> {
        self.model
            .ensure_started(self.experiment.start_time)
            .map_err(FmiError::rejected)
    }
}
