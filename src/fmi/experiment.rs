//! The experiment an importer sets up (`fmi2SetupExperiment`, the arguments of
//! `fmi3EnterInitializationMode`).

/// Relative tolerance on `currentCommunicationPoint` and `stopTime`.
pub(crate) const TIME_TOLERANCE: f64 = 1e-9;

/// Start and stop time of the experiment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Experiment {
    pub start_time: f64,
    pub stop_time: Option<f64>,
}

impl Experiment {
    /// The experiment's times within the ranges of a scene's `[experiment]` (one check,
    /// [`crate::cosimulation::experiment::check_experiment_times`]), as a message naming the value (`names`: the
    /// start's and the stop's) and its range.
    pub fn check_times(
        start_time: f64,
        stop_time: Option<f64>,
        names: [&'static str; 2],
    ) -> Result<(), String> {
        crate::cosimulation::experiment::check_experiment_times(start_time, stop_time, names)
            .map_err(|e| match e {
                crate::error::ModelError::InvalidParameter {
                    name,
                    value,
                    allowed,
                } => format!("{name} = {value:e} is out of range: allowed {allowed}"),
                e => e.to_string(),
            })
    }
}
