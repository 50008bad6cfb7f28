//! One FMU instance: the whole FMI 2.0 and FMI 3.0 Co-Simulation behaviour in safe Rust
//! (one code for both: the instance's [`Standard`] only selects function names in messages
//! and the type families of get/set).
//!
//! `ffi/` (FMI 2.0) and `ffi/fmi3/` (FMI 3.0) turn each C call into one call of
//! [`Instance::run`] with the matching method;
//! `run` checks the call sequence against the state machine, catches panics, logs failures
//! through the importer's logger and folds everything into a [`Status`].
//!
//! The methods, one concept per file:
//! - this file: the instance, `fmi2Instantiate` and [`Instance::run`];
//! - [`lifecycle`]: debug logging, setup, initialization mode, terminate, reset;
//! - [`values`]: `fmi2Get*` / `fmi2Set*` through the variable table;
//! - [`derivatives`]: input derivatives (the crank law's acceleration), output and
//!   directional derivatives (not provided);
//! - [`stepping`]: `fmi2DoStep` and the status queries;
//! - [`states`]: FMU states and their serialization.
//!
//! The model behind the instance is any [`CoSimulationModel`]: the instance drives its
//! hooks and adds the state machine, the experiment, logging, statuses and saved FMU states.
//! The C functions hold an `Instance<dyn CoSimulationModel>` (the default); which model a
//! resource folder holds is decided in one place, [`crate::fmi::registry`].

mod derivatives;
mod lifecycle;
mod states;
mod stepping;
mod values;

use std::collections::HashMap;
use std::panic::AssertUnwindSafe;

use super::description::ModelDescription;
use super::experiment::Experiment;
use super::fmu_state::FmuState;
use super::guard;
use super::logging::Logger;
use super::resource;
use super::standard::Standard;
use super::state_machine::{self, Call, MachineState};
use super::status::{FmiResult, Status};
use crate::cosimulation::{CoSimulationModel, Declarations};

/// `fmi2Type` value of Co-Simulation.
pub const FMI2_CO_SIMULATION: i32 = 1;

pub(crate) use super::experiment::TIME_TOLERANCE;

/// Arguments of `fmi2Instantiate` or `fmi3InstantiateCoSimulation`, already converted from C.
pub struct InstantiateArgs<'a> {
    pub standard: Standard,
    pub instance_name: &'a str,
    /// `fmuType` of FMI 2.0; FMI 3.0 has one function per interface (pass
    /// [`FMI2_CO_SIMULATION`]).
    pub fmu_type: i32,
    /// The GUID (FMI 2.0) or the `instantiationToken` (FMI 3.0).
    pub guid: &'a str,
    pub resource_location: Option<&'a str>,
}

/// One FMU instance of the model `M`.
pub struct Instance<M: CoSimulationModel + ?Sized = dyn CoSimulationModel> {
    /// FMI 2.0 or FMI 3.0: names in messages and the type families of get/set.
    standard: Standard,
    guid: String,
    /// The model: its parameters (the exported start values, restored by `fmi2Reset`), its
    /// inputs and what it built from them.
    model: Box<M>,
    state: MachineState,
    logger: Logger,
    experiment: Experiment,
    /// Status of the last `fmi2DoStep`.
    last_step: Status,
    /// Why the simulation is missing after a failed initialization (for messages).
    failure: Option<String>,
    fmu_states: HashMap<usize, FmuState>,
    /// Last serialization: (handle, bytes), so size and content are computed once.
    serialized: Option<(usize, Vec<u8>)>,
}

impl Instance {
    /// `fmi2Instantiate`: load the model from the resources, check the GUID. Failures are
    /// logged and give `None`.
    pub fn instantiate(args: InstantiateArgs<'_>, logger: Logger) -> Option<Instance> {
        let result = guard::catch(AssertUnwindSafe(|| load(&args, &logger)));
        let failure = match result {
            Ok(Ok(loaded)) => {
                return Some(Instance::new(loaded.model, &loaded.description, logger))
            }
            Ok(Err(message)) => message,
            Err(panic) => {
                format!("internal error (a panic was caught at the FMI boundary): {panic}")
            }
        };
        logger.status(
            Status::Error,
            &format!(
                "{} of \"{}\": {failure}",
                instantiate_name(args.standard),
                args.instance_name
            ),
        );
        None
    }
}

impl<M: CoSimulationModel + ?Sized> Instance<M> {
    /// An instance of `model` with its description (for tools and tests; no GUID check).
    pub fn new(model: Box<M>, description: &ModelDescription, logger: Logger) -> Instance<M> {
        let experiment = Experiment {
            start_time: model.info().default_experiment.start_time,
            stop_time: None,
        };
        Instance {
            standard: description.standard,
            guid: description.guid.clone(),
            model,
            state: MachineState::Instantiated,
            logger,
            experiment,
            last_step: Status::Ok,
            failure: None,
            fmu_states: HashMap::new(),
            serialized: None,
        }
    }

    /// The instance's state in the FMI state machine.
    pub fn machine_state(&self) -> MachineState {
        self.state
    }

    /// The standard the instance was created by.
    pub fn standard(&self) -> Standard {
        self.standard
    }

    /// The GUID of the FMU this instance belongs to.
    pub fn guid(&self) -> &str {
        &self.guid
    }

    /// The model's variables.
    fn table(&self) -> &Declarations {
        self.model.declarations()
    }

    /// Run one FMI call: check the call sequence, run `f` with panics caught, log a failure
    /// and return the status for the importer.
    pub fn run(
        &mut self,
        call: Call,
        f: impl FnOnce(&mut Instance<M>) -> FmiResult<Status>,
    ) -> Status {
        let result = guard::catch(AssertUnwindSafe(|| {
            state_machine::check(call, self.state, self.standard)?;
            f(self)
        }));
        let (status, message) = match result {
            Ok(Ok(status)) => return status,
            Ok(Err(e)) => {
                if e.instance_failed {
                    self.state = MachineState::Error;
                }
                (
                    e.status,
                    format!("{}: {}", call.name(self.standard), e.message),
                )
            }
            Err(panic) => {
                self.state = MachineState::Error;
                (
                    Status::Error,
                    format!(
                        "{}: internal error (a panic was caught at the FMI boundary): {panic}; the instance is in the Error state: call {}, {} or {}",
                        call.name(self.standard),
                        Call::Reset.name(self.standard),
                        Call::SetFMUstate.name(self.standard),
                        Call::FreeInstance.name(self.standard),
                    ),
                )
            }
        };
        let logger = &self.logger;
        if guard::catch(AssertUnwindSafe(|| logger.status(status, &message))).is_err() {
            self.enter_error_state();
            return Status::Error;
        }
        status
    }

    /// A panic escaped a call (in the logging path): the instance cannot be trusted to
    /// continue and enters the `Error` state.
    pub fn enter_error_state(&mut self) {
        self.state = MachineState::Error;
    }
}

/// `fmi2Instantiate` or `fmi3InstantiateCoSimulation`.
pub fn instantiate_name(standard: Standard) -> &'static str {
    match standard {
        Standard::Fmi2 => "fmi2Instantiate",
        Standard::Fmi3 => "fmi3InstantiateCoSimulation",
    }
}

/// Check the arguments of `fmi2Instantiate` and load the scene its resources name.
fn load(args: &InstantiateArgs<'_>, logger: &Logger) -> Result<resource::LoadedModel, String> {
    if args.instance_name.is_empty() {
        return Err(
            "instanceName is empty: allowed a non-empty name (it identifies the instance in messages)"
                .to_string(),
        );
    }
    if args.standard == Standard::Fmi2 && args.fmu_type != FMI2_CO_SIMULATION {
        return Err(format!(
            "fmuType = {} is not supported: allowed {FMI2_CO_SIMULATION} (fmi2CoSimulation); this FMU implements only Co-Simulation",
            args.fmu_type
        ));
    }
    let loaded = resource::load_model_for(args.resource_location, args.guid, args.standard)?;
    logger.event(&format!(
        "instance \"{}\" of {} uses {}",
        args.instance_name, loaded.description.guid, loaded.origin
    ));
    Ok(loaded)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fmi::logging::LogSink;
    use crate::fmi::status::StatusKind;

    /// An instance of the compiled-in default scene.
    fn default_instance(standard: Standard, logger: Logger) -> Instance {
        let model = crate::fmi::registry::default_model(standard).unwrap();
        let description = ModelDescription::of(&*model, standard).unwrap();
        Instance::new(model, &description, logger)
    }

    struct PanickingSink;
    impl LogSink for PanickingSink {
        fn emit(&self, _: Status, _: &'static str, message: &str) {
            panic!("the logger failed on: {message}");
        }
    }

    fn instance(sink: Option<Box<dyn LogSink>>) -> Instance {
        let logger = Logger::new(sink, false);
        default_instance(Standard::Fmi2, logger)
    }

    #[test]
    fn a_panic_while_logging_moves_the_instance_to_error() {
        let mut i = instance(Some(Box::new(PanickingSink)));
        let status = i.run(Call::GetReal, |i| i.get_real(&[9999], &mut [0.0]));
        assert_eq!(status, Status::Error);
        assert_eq!(i.machine_state(), MachineState::Error);
    }

    /// Collects the messages it is given.
    struct Capture(std::sync::Arc<std::sync::Mutex<Vec<String>>>);
    impl LogSink for Capture {
        fn emit(&self, _: Status, _: &'static str, message: &str) {
            self.0.lock().unwrap().push(message.to_string());
        }
    }

    #[test]
    fn fmi3_messages_name_fmi3_functions() {
        let messages = std::sync::Arc::new(std::sync::Mutex::new(Vec::new()));
        let sink = Box::new(Capture(messages.clone()));
        let logger = Logger::new(Some(sink), false);
        let mut i = default_instance(Standard::Fmi3, logger);
        let stop = Some(1e-3);
        assert_eq!(
            i.run(Call::SetupExperiment, |i| i
                .setup_experiment(None, 0.0, stop)),
            Status::Ok
        );
        i.run(
            Call::EnterInitializationMode,
            Instance::enter_initialization_mode,
        );
        i.run(
            Call::ExitInitializationMode,
            Instance::exit_initialization_mode,
        );
        let vr = i.table().by_name("rod.length").unwrap().value_reference;
        // A fixed parameter after initialization, a step past the stop time, a wrong size.
        assert_eq!(
            i.run(Call::SetReal, |i| i.set_real(&[vr], &[0.3])),
            Status::Error
        );
        assert_eq!(i.run(Call::DoStep, |i| i.do_step(0.0, 1.0)), Status::Error);
        let handle = i.get_fmu_state(None).unwrap();
        let status = i.run(Call::SerializeFMUstate, |i| {
            i.serialize_fmu_state(handle, &mut [0u8; 3])
        });
        assert_eq!(status, Status::Error);
        let messages = messages.lock().unwrap();
        let text = messages.join("\n");
        for name in [
            "fmi3SetFloat64",
            "fmi3ExitInitializationMode",
            "fmi3DoStep",
            "fmi3EnterInitializationMode",
            "fmi3SerializeFMUState",
            "fmi3SerializedFMUStateSize",
        ] {
            assert!(text.contains(name), "{name} not in {text}");
        }
        assert!(!text.contains("fmi2"), "{text}");
    }

    #[test]
    fn unavailable_status_kinds_are_discarded() {
        let mut i = instance(None);
        for call in [Call::SetupExperiment, Call::EnterInitializationMode] {
            let status = i.run(call, |i| match call {
                Call::SetupExperiment => i.setup_experiment(None, 0.0, None),
                _ => i.enter_initialization_mode(),
            });
            assert_eq!(status, Status::Ok);
        }
        assert_eq!(
            i.run(
                Call::ExitInitializationMode,
                Instance::exit_initialization_mode
            ),
            Status::Ok
        );
        let e = i.get_integer_status(StatusKind::DoStepStatus).unwrap_err();
        assert_eq!(e.status, Status::Discard);
        assert_eq!(
            i.get_status(StatusKind::PendingStatus).unwrap_err().status,
            Status::Discard
        );
        assert_eq!(StatusKind::from_code(9).unwrap_err().status, Status::Error);
    }
}
