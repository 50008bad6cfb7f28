//! `fmi2DoStep` and the status queries.

use super::{Instance, TIME_TOLERANCE};
use crate::cosimulation::{CoSimulationModel, StepOutcome};
use crate::fmi::state_machine::{Call, MachineState};
use crate::fmi::status::{FmiError, FmiResult, Status, StatusKind};
use crate::limits::EXPERIMENT_TIME_LIMIT;
use crate::text::time;

impl<M: CoSimulationModel + ?Sized> Instance<M> {
    /// `fmi2DoStep`: integrate from the FMU time `t` to `t + h`.
    pub fn do_step(&mut self, t: f64, h: f64) -> FmiResult<Status> {
        let Some(now) = self.model.time() else {
            return Err(FmiError::failed("no simulation (internal error)"));
        };
        let tolerance = TIME_TOLERANCE * now.abs().max(1.0);
        if !(t.is_finite() && (t - now).abs() <= tolerance) {
            return Err(FmiError::rejected(format!(
                "currentCommunicationPoint = {} s does not match the FMU time {} s: allowed {} +- {tolerance:e} s",
                time(t),
                time(now),
                time(now)
            )));
        }
        if !(h.is_finite() && h > 0.0) {
            return Err(FmiError::rejected(format!(
                "communicationStepSize = {} s is out of range: allowed a finite value > 0",
                time(h)
            )));
        }
        if let Some(stop) = self.experiment.stop_time {
            // In the master's terms: the communication point it passed, not the FMU's own
            // (accumulated) time, which agrees with it only within the tolerance above.
            let end = t + h;
            if end > stop + TIME_TOLERANCE * stop.abs().max(1.0) {
                return Err(FmiError::rejected(format!(
                    "the step from currentCommunicationPoint = {} s with communicationStepSize = {} s would end at {} s, after stopTime = {} s of {}: allowed communicationStepSize <= {} s",
                    time(t),
                    time(h),
                    time(end),
                    time(stop),
                    Call::SetupExperiment.name(self.standard),
                    time(stop - t)
                )));
            }
        }
        // The FMU's time stays within the experiment's range (`[experiment]` of a scene, the
        // times of the experiment set up), also without a stop time.
        let limit = EXPERIMENT_TIME_LIMIT;
        if t + h > limit * (1.0 + TIME_TOLERANCE) {
            return Err(FmiError::rejected(format!(
                "the step from currentCommunicationPoint = {t} s with communicationStepSize = {h} s would end at {} s, after the end of the time range {limit:e} s: allowed communicationStepSize <= {} s",
                t + h,
                limit - t
            )));
        }
        // A new input law starts at every communication point; refused inputs or work
        // change nothing, a discarded step keeps the state before it.
        match self.model.step(h) {
            StepOutcome::Done => {
                self.last_step = Status::Ok;
                Ok(self.take_warnings())
            }
            StepOutcome::Refused(reason) => {
                self.take_warnings();
                Err(FmiError::rejected(reason))
            }
            StepOutcome::Discarded { reason, remedy } => {
                self.state = MachineState::StepFailed;
                self.last_step = Status::Discard;
                self.take_warnings();
                Err(FmiError::discard(format!(
                    "{reason}. Restore a state saved before the step ({}) and {remedy}",
                    Call::SetFMUstate.name(self.standard)
                )))
            }
            StepOutcome::Failed(reason) => {
                self.take_warnings();
                Err(FmiError::failed(reason))
            }
        }
    }

    /// The FMU's time: the simulation's, or the start time before there is one (FMI 3.0
    /// `time` and `lastSuccessfulTime`).
    pub fn time(&self) -> f64 {
        self.model.time().unwrap_or(self.experiment.start_time)
    }

    /// Pass the simulation's warnings to the logger; `Warning` if there were any.
    pub(super) fn take_warnings(&mut self) -> Status {
        let warnings = self.model.take_warnings();
        for w in &warnings {
            self.logger.status(Status::Warning, w);
        }
        if warnings.is_empty() {
            Status::Ok
        } else {
            Status::Warning
        }
    }

    /// `fmi2GetStatus`.
    pub fn get_status(&self, kind: StatusKind) -> FmiResult<Status> {
        match kind {
            StatusKind::DoStepStatus => Ok(self.last_step),
            _ => Err(self.undefined_status(kind, "fmi2GetStatus", "only fmi2DoStepStatus")),
        }
    }

    /// `fmi2GetRealStatus`: `fmi2LastSuccessfulTime` is the FMU time (after a discarded step,
    /// the time before it).
    pub fn get_real_status(&self, kind: StatusKind) -> FmiResult<f64> {
        match (kind, self.model.time()) {
            (StatusKind::LastSuccessfulTime, Some(time)) => Ok(time),
            _ => {
                Err(self.undefined_status(kind, "fmi2GetRealStatus", "only fmi2LastSuccessfulTime"))
            }
        }
    }

    /// `fmi2GetIntegerStatus`: FMI 2.0 defines no integer status.
    pub fn get_integer_status(&self, kind: StatusKind) -> FmiResult<i32> {
        Err(self.undefined_status(
            kind,
            "fmi2GetIntegerStatus",
            "no integer status (FMI 2.0 defines none)",
        ))
    }

    /// `fmi2GetBooleanStatus`: `fmi2Terminated` is false (the FMU never asks to stop).
    pub fn get_boolean_status(&self, kind: StatusKind) -> FmiResult<bool> {
        match kind {
            StatusKind::Terminated => Ok(false),
            _ => Err(self.undefined_status(kind, "fmi2GetBooleanStatus", "only fmi2Terminated")),
        }
    }

    /// `fmi2GetStringStatus`: only `fmi2PendingStatus` exists, and no step is ever pending.
    pub fn get_string_status(&self, kind: StatusKind) -> FmiResult<Status> {
        Err(self.undefined_status(
            kind,
            "fmi2GetStringStatus",
            "fmi2PendingStatus only while fmi2DoStep is pending, which never happens here (canRunAsynchronuously = false)",
        ))
    }

    /// A status kind this FMU cannot provide: `fmi2Discard` (FMI 2.0, 4.2.3: "If a status is
    /// required which cannot be retrieved by the slave it returns fmi2Discard"). Invalid kind
    /// codes are errors ([`StatusKind::from_code`]).
    fn undefined_status(&self, kind: StatusKind, function: &str, allowed: &str) -> FmiError {
        FmiError::discard(format!(
            "{function} cannot provide {}: it provides {allowed}",
            kind.name()
        ))
    }
}
