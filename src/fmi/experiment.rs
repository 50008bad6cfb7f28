//! The experiment an importer sets up (`fmi2SetupExperiment`, the arguments of
//! `fmi3EnterInitializationMode`).

/// Start and stop time of the experiment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Experiment {
    pub start_time: f64,
    pub stop_time: Option<f64>,
}
