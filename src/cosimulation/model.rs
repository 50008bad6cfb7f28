//! What a co-simulation interface asks of a model: the hooks of one model instance as an
//! importer drives it (the way a model of the Modelica Reference-FMUs implements a few
//! functions that a generic shell calls). Variables are named by their identifier; the model
//! looks up where their values live. Failures are texts naming the value and its allowed
//! range; a step reports a [`StepOutcome`]. Nothing here is of one standard: the FMI shell
//! (`crate::fmi`) turns outcomes into statuses and saved states into bytes with its header.

use std::any::Any;

use super::{Declarations, ModelInfo, VariableId};

/// A saved model: whatever the model needs to continue bit for bit, opaque to the interface
/// (it hands it back to the model that saved it).
pub type SavedState = Box<dyn Any>;

/// How a communication step ended.
#[derive(Clone, Debug, PartialEq)]
pub enum StepOutcome {
    /// The step is done.
    Done,
    /// Refused before anything changed (an input, the work it needs): the instance stays
    /// usable and continuing gives what a run that never tried gives.
    Refused(String),
    /// The step could not be completed and the state before it is kept; the caller may
    /// restore a state saved before the step and then do what `remedy` says.
    Discarded {
        reason: String,
        remedy: &'static str,
    },
    /// The step failed: the model cannot continue.
    Failed(String),
}

/// One model instance, as a co-simulation interface drives it.
pub trait CoSimulationModel {
    /// Its names, default experiment, units and enumeration types.
    fn info(&self) -> &ModelInfo;

    /// Its variables, declared for the interface it was built for.
    fn declarations(&self) -> &Declarations;

    /// What sets the accuracy instead of an importer's tolerance, in words.
    fn accuracy_note(&self) -> String;

    /// The model's time, once it is built.
    fn time(&self) -> Option<f64>;

    /// The model is built for the current parameters (outputs can be read).
    fn is_built(&self) -> bool;

    /// A parameter (`parameter_changed`) or an input changed before stepping: the start must
    /// be redone, and for a parameter the model rebuilt.
    fn invalidate(&mut self, parameter_changed: bool);

    /// Drop what was built (after a failed start nothing may look started).
    fn discard_built(&mut self);

    /// Build the model for the current parameters if needed and start it with the current
    /// inputs at `start_time`, s.
    fn ensure_started(&mut self, start_time: f64) -> Result<(), String>;

    /// Stepping begins (the end of initialization).
    fn begin_stepping(&mut self);

    /// The start in words, for the log.
    fn start_summary(&self) -> String;

    /// The values of the Real variable `vr` (one, or an array's elements) into `out`; `time`
    /// before the model is built is `start_time`. A computed value is handed out only within
    /// the range the model stands behind.
    fn get_real(&self, vr: VariableId, out: &mut [f64], start_time: f64) -> Result<(), String>;

    /// The value of the Integer or Enumeration variable `vr`.
    fn get_integer(&self, vr: VariableId) -> Result<i32, String>;

    /// Check a finite value for the Real input or parameter `vr` before anything is set: on
    /// refusal, the allowed values.
    fn check_real(&self, vr: VariableId, x: f64) -> Result<(), String>;

    /// Set the Real input or parameter `vr` (checked with [`Self::check_real`]); true if a
    /// parameter changed.
    fn set_real(&mut self, vr: VariableId, x: f64) -> Result<bool, String>;

    /// Set Integer or Enumeration parameters, all or none: on refusal, the position of the
    /// refused one and the allowed values.
    fn set_integers(&mut self, items: &[(VariableId, i32)]) -> Result<(), (usize, String)>;

    /// Check the derivative of order `order` of the input `vr` before anything is set.
    fn check_input_derivative(&self, vr: VariableId, order: i32, x: f64) -> Result<(), String>;

    /// Set input derivatives at this communication point, all or none; returns warnings.
    fn set_input_derivatives(
        &mut self,
        items: &[(VariableId, i32, f64)],
    ) -> Result<Vec<String>, String>;

    /// One communication step of `h` s from the current time.
    fn step(&mut self, h: f64) -> StepOutcome;

    /// Warnings since the last call.
    fn take_warnings(&mut self) -> Vec<String>;

    /// Back to the start values of the exported model, not built.
    fn reset(&mut self);

    /// Save everything.
    fn save(&self) -> SavedState;

    /// Restore a state this model saved or read.
    fn restore(&mut self, saved: &SavedState) -> Result<(), String>;

    /// The time of a saved state, if it holds a built model.
    fn saved_time(&self, saved: &SavedState) -> Option<f64>;

    /// The bytes of a saved state (the model's own format; the current state is left as it
    /// was).
    fn write_saved(&mut self, saved: &SavedState) -> Result<Vec<u8>, String>;

    /// A saved state from bytes [`Self::write_saved`] wrote, every field checked against its
    /// range: foreign, truncated or other-model bytes are refused with the reason.
    fn read_saved(&mut self, bytes: &[u8]) -> Result<SavedState, String>;
}
