//! The rod model as a co-simulation model: the hooks an interface drives
//! ([`CoSimulationModel`]), each resolving a variable's identifier in the model's table and
//! calling the model's own method.

use super::inputs::Inputs;
use super::instance::{RodModel, SavedModel, StepError};
use super::variables::Variable;
use crate::cosimulation::{
    CoSimulationModel, Declarations, ModelInfo, SavedState, StepOutcome, VariableId,
};
use crate::error::ModelError;

impl RodModel {
    fn variable(&self, vr: VariableId) -> Result<&Variable, String> {
        self.table()
            .get(vr)
            .ok_or_else(|| format!("unknown value reference {vr}"))
    }
}

fn saved(state: &SavedState) -> Result<&SavedModel, String> {
    state
        .downcast_ref::<SavedModel>()
        .ok_or_else(|| "the saved state is not a state of the rod's model".to_string())
}

impl CoSimulationModel for RodModel {
    fn info(&self) -> &ModelInfo {
        self.model_info()
    }

    fn declarations(&self) -> &Declarations {
        self.table().declarations()
    }

    fn accuracy_note(&self) -> String {
        RodModel::accuracy_note(self)
    }

    fn time(&self) -> Option<f64> {
        RodModel::time(self)
    }

    fn is_built(&self) -> bool {
        RodModel::is_built(self)
    }

    fn invalidate(&mut self, parameter_changed: bool) {
        RodModel::invalidate(self, parameter_changed);
    }

    fn discard_built(&mut self) {
        self.discard_simulation();
    }

    fn ensure_started(&mut self, start_time: f64) -> Result<(), String> {
        RodModel::ensure_started(self, start_time).map_err(|e| e.to_string())
    }

    fn begin_stepping(&mut self) {
        RodModel::begin_stepping(self);
    }

    fn start_summary(&self) -> String {
        RodModel::start_summary(self)
    }

    fn get_real(&self, vr: VariableId, out: &mut [f64], start_time: f64) -> Result<(), String> {
        RodModel::get_real(self, self.variable(vr)?, out, start_time)
    }

    fn get_integer(&self, vr: VariableId) -> Result<i32, String> {
        RodModel::get_integer(self, self.variable(vr)?)
    }

    fn check_real(&self, vr: VariableId, x: f64) -> Result<(), String> {
        RodModel::check_real(self.variable(vr)?, x)
    }

    fn set_real(&mut self, vr: VariableId, x: f64) -> Result<bool, String> {
        RodModel::set_real(self, vr, x)
    }

    fn set_integers(&mut self, items: &[(VariableId, i32)]) -> Result<(), (usize, String)> {
        RodModel::set_integers(self, items)
    }

    fn check_input_derivative(&self, vr: VariableId, order: i32, x: f64) -> Result<(), String> {
        Inputs::check_derivative(self.variable(vr)?, order, x)
    }

    fn set_input_derivatives(
        &mut self,
        items: &[(VariableId, i32, f64)],
    ) -> Result<Vec<String>, String> {
        RodModel::set_input_derivatives(self, items)
    }

    fn step(&mut self, h: f64) -> StepOutcome {
        // Refusals that change nothing come first: a step beyond the work bound.
        if let Err(e) = self.check_step(h) {
            return StepOutcome::Refused(e.to_string());
        }
        match RodModel::step(self, h) {
            Ok(()) => StepOutcome::Done,
            Err(StepError::Inputs(e)) => StepOutcome::Refused(e.to_string()),
            Err(StepError::Step(e @ ModelError::StepFailed { .. })) => StepOutcome::Discarded {
                reason: e.to_string(),
                remedy: "retry with a smaller communication step, or terminate",
            },
            Err(StepError::Step(e @ ModelError::DeflectionLimit { discard: true, .. })) => {
                StepOutcome::Discarded {
                    reason: e.to_string(),
                    remedy: "continue, switch the model, or terminate",
                }
            }
            // Refused before or without changing anything: the instance stays usable.
            Err(StepError::Step(e @ ModelError::TooMuchWork { .. })) => {
                StepOutcome::Refused(e.to_string())
            }
            Err(StepError::Step(e)) => StepOutcome::Failed(e.to_string()),
        }
    }

    fn take_warnings(&mut self) -> Vec<String> {
        RodModel::take_warnings(self)
    }

    fn reset(&mut self) {
        RodModel::reset(self);
    }

    fn save(&self) -> SavedState {
        Box::new(RodModel::save(self))
    }

    fn restore(&mut self, state: &SavedState) -> Result<(), String> {
        RodModel::restore(self, saved(state)?).map_err(|e| e.to_string())
    }

    fn saved_time(&self, state: &SavedState) -> Option<f64> {
        saved(state).ok().and_then(SavedModel::time)
    }

    fn write_saved(&mut self, state: &SavedState) -> Result<Vec<u8>, String> {
        self.saved_to_bytes(saved(state)?)
            .map_err(|e| e.to_string())
    }

    fn read_saved(&mut self, bytes: &[u8]) -> Result<SavedState, String> {
        Ok(Box::new(self.saved_from_bytes_checked(bytes)?))
    }
}
