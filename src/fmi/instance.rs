//! One FMU instance: the whole FMI 2.0 Co-Simulation behaviour in safe Rust.
//!
//! `ffi.rs` turns each C call into one call of [`Instance::run`] with the matching method;
//! `run` checks the call sequence against the state machine, catches panics, logs failures
//! through the importer's logger and folds everything into a [`Status`].
//!
//! The inputs and their law between communication points: [`super::inputs`].

use std::collections::HashMap;
use std::panic::AssertUnwindSafe;
use std::sync::atomic::{AtomicUsize, Ordering};

use super::description::ModelDescription;
use super::fmu_state::{self, FmuState};
use super::guard;
use super::inputs::{AccelerationSource, Experiment, Inputs};
use super::logging::Logger;
use super::resource;
use super::state_machine::{self, Call, MachineState};
use super::status::{FmiError, FmiResult, Status, StatusKind};
use super::variables::{
    Access, Causality, Family, InputSlot, ValueReference, Variable, VariableTable,
};
use crate::error::ModelError;
use crate::scene::Scene;
use crate::simulation::Simulation;

/// `fmi2Type` value of Co-Simulation.
const FMI2_CO_SIMULATION: i32 = 1;

/// Relative tolerance on `currentCommunicationPoint` and `stopTime`.
const TIME_TOLERANCE: f64 = 1e-9;

/// Handles of FMU states are unique across all instances of the process, so a state of
/// another instance is recognized as foreign.
static NEXT_STATE_HANDLE: AtomicUsize = AtomicUsize::new(1);

/// Arguments of `fmi2Instantiate`, already converted from C.
pub struct InstantiateArgs<'a> {
    pub instance_name: &'a str,
    pub fmu_type: i32,
    pub guid: &'a str,
    pub resource_location: Option<&'a str>,
}

/// One FMU instance.
pub struct Instance {
    guid: String,
    table: VariableTable,
    /// The scene the FMU was exported for: the start values, restored by `fmi2Reset`.
    exported: Scene,
    /// The instance's own copy, with the parameters the importer set.
    scene: Scene,
    state: MachineState,
    logger: Logger,
    inputs: Inputs,
    experiment: Experiment,
    /// Built from `scene` (invariant: `Some` only if built from the current `scene`).
    simulation: Option<Simulation>,
    /// In initialization mode: the simulation was started with the current inputs.
    started: bool,
    /// Status of the last `fmi2DoStep`.
    last_step: Status,
    /// Why the simulation is missing after a failed initialization (for messages).
    failure: Option<String>,
    fmu_states: HashMap<usize, FmuState>,
    /// Last serialization: (handle, bytes), so size and content are computed once.
    serialized: Option<(usize, Vec<u8>)>,
}

fn model_error(e: ModelError) -> String {
    e.to_string()
}

impl Instance {
    /// `fmi2Instantiate`: load the scene from the resources, check the GUID. Failures are
    /// logged and give `None`.
    pub fn instantiate(args: InstantiateArgs<'_>, logger: Logger) -> Option<Instance> {
        let result = guard::catch(AssertUnwindSafe(|| load(&args, &logger)));
        let failure = match result {
            Ok(Ok(model)) => {
                return Some(Instance::from_description(
                    model.scene,
                    model.description,
                    logger,
                ))
            }
            Ok(Err(message)) => message,
            Err(panic) => {
                format!("internal error (a panic was caught at the FMI boundary): {panic}")
            }
        };
        logger.status(
            Status::Error,
            &format!("fmi2Instantiate of \"{}\": {failure}", args.instance_name),
        );
        None
    }

    /// An instance of `scene` with its description (for tools and tests; no GUID check).
    pub fn from_description(
        scene: Scene,
        description: ModelDescription,
        logger: Logger,
    ) -> Instance {
        let inputs = Inputs::from_start_values(&description.table);
        let experiment = Experiment {
            start_time: scene.experiment.start_time,
            stop_time: None,
        };
        Instance {
            guid: description.guid,
            table: description.table,
            exported: scene.clone(),
            scene,
            state: MachineState::Instantiated,
            logger,
            inputs,
            experiment,
            simulation: None,
            started: false,
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

    /// The GUID of the FMU this instance belongs to.
    pub fn guid(&self) -> &str {
        &self.guid
    }

    /// Run one FMI call: check the call sequence, run `f` with panics caught, log a failure
    /// and return the status for the importer.
    pub fn run(
        &mut self,
        call: Call,
        f: impl FnOnce(&mut Instance) -> FmiResult<Status>,
    ) -> Status {
        let result = guard::catch(AssertUnwindSafe(|| {
            state_machine::check(call, self.state)?;
            f(self)
        }));
        let (status, message) = match result {
            Ok(Ok(status)) => return status,
            Ok(Err(e)) => {
                if e.instance_failed {
                    self.state = MachineState::Error;
                }
                (e.status, format!("{}: {}", call.name(), e.message))
            }
            Err(panic) => {
                self.state = MachineState::Error;
                (
                    Status::Error,
                    format!(
                        "{}: internal error (a panic was caught at the FMI boundary): {panic}; the instance is in the Error state: call fmi2Reset, fmi2SetFMUstate or fmi2FreeInstance",
                        call.name()
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

    // ---------------------------------------------------------------- logging and setup

    /// `fmi2SetDebugLogging`.
    pub fn set_debug_logging(&mut self, on: bool, categories: &[&str]) -> FmiResult<Status> {
        self.logger.set_debug_logging(on, categories)?;
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
                "fmi2SetupExperiment: tolerance = {tol} is not used; the integrator follows the scene's [solver] settings (step = {} s, newton_tolerance = {})",
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
            let f = self.simulation.as_ref().map(Simulation::frequencies_hz);
            self.logger.event(&format!(
                "initialized at t = {t0} s with crank.angle = {} rad, crank.speed = {} rad/s; lowest natural frequency {:?} Hz",
                self.inputs.angle,
                self.inputs.speed,
                f.and_then(|f| f.first())
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
    fn ensure_started(&mut self) -> FmiResult<()> {
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

    // ---------------------------------------------------------------- get and set

    fn variable(&self, vr: ValueReference, family: Family) -> FmiResult<&Variable> {
        let v = self.table.get(vr).ok_or_else(|| {
            FmiError::rejected(format!(
                "unknown value reference {vr}: no {} variable of this FMU has it (see modelDescription.xml)",
                family.name()
            ))
        })?;
        let actual = v.value_type.family();
        if actual != family {
            return Err(FmiError::rejected(format!(
                "value reference {vr} ({}) is a {} variable, not {}: use fmi2Get{}/fmi2Set{}",
                v.name,
                actual.name(),
                family.name(),
                actual.name(),
                actual.name()
            )));
        }
        Ok(v)
    }

    fn settable(&self, vr: ValueReference, family: Family) -> FmiResult<&Variable> {
        let v = self.variable(vr, family)?;
        match v.causality {
            Causality::Input => Ok(v),
            Causality::Parameter => match self.state {
                MachineState::Instantiated | MachineState::InitializationMode => Ok(v),
                state => Err(FmiError::rejected(format!(
                    "{} (value reference {vr}) is a fixed parameter: it can be set only before fmi2ExitInitializationMode, and the instance is in state {}",
                    v.name,
                    state.name()
                ))),
            },
            Causality::Output | Causality::CalculatedParameter => {
                Err(FmiError::rejected(format!(
                    "{} (value reference {vr}) has causality {}: only inputs and parameters can be set",
                    v.name,
                    v.causality.as_str()
                )))
            }
        }
    }

    /// A parameter or input changed during initialization: the start must be redone.
    fn invalidate(&mut self, parameter_changed: bool) {
        if parameter_changed {
            self.simulation = None;
        }
        self.started = false;
    }

    /// Make the simulation that provides outputs and frequencies available (built on
    /// demand in initialization mode).
    fn prepare_values(&mut self) -> FmiResult<()> {
        if self.state == MachineState::InitializationMode {
            self.ensure_started()?;
        }
        match &self.simulation {
            Some(_) => Ok(()),
            None => Err(FmiError::rejected(format!(
                "outputs and calculated parameters are not available: {}",
                self.failure
                    .as_deref()
                    .unwrap_or("the model was not initialized")
            ))),
        }
    }

    /// `fmi2GetReal`.
    pub fn get_real(&mut self, vrs: &[ValueReference], values: &mut [f64]) -> FmiResult<Status> {
        let mut needs_simulation = false;
        for &vr in vrs {
            let v = self.variable(vr, Family::Real)?;
            needs_simulation |= matches!(v.access, Access::Output(_) | Access::Frequency(_));
        }
        if needs_simulation {
            self.prepare_values()?;
        }
        let (outputs, frequencies) = match &self.simulation {
            Some(s) if needs_simulation => (s.outputs(), s.frequencies_hz()),
            _ => (Default::default(), &[][..]),
        };
        for (&vr, out) in vrs.iter().zip(values.iter_mut()) {
            let v = self.table.get(vr).expect("checked above");
            *out = match v.access {
                Access::Input(slot) => self.inputs.value(slot),
                Access::Output(get) => get(&outputs),
                Access::RealParameter { get, .. } => get(&self.scene),
                Access::Frequency(i) => *frequencies.get(i).ok_or_else(|| {
                    FmiError::rejected(format!("{} does not exist for these parameters", v.name))
                })?,
                Access::IntegerParameter { .. } => unreachable!("family checked"),
            };
        }
        Ok(Status::Ok)
    }

    /// `fmi2GetInteger` (Integer and Enumeration variables).
    pub fn get_integer(&mut self, vrs: &[ValueReference], values: &mut [i32]) -> FmiResult<Status> {
        for (&vr, out) in vrs.iter().zip(values.iter_mut()) {
            let v = self.variable(vr, Family::Integer)?;
            *out = match v.access {
                Access::IntegerParameter { get, .. } => get(&self.scene),
                _ => unreachable!("only Integer parameters are Integer variables"),
            };
        }
        Ok(Status::Ok)
    }

    /// `fmi2SetReal`: all values are checked first; on error nothing is set.
    pub fn set_real(&mut self, vrs: &[ValueReference], values: &[f64]) -> FmiResult<Status> {
        for (&vr, &x) in vrs.iter().zip(values) {
            let v = self.settable(vr, Family::Real)?;
            if !x.is_finite() {
                return Err(FmiError::rejected(format!(
                    "{} = {x} (value reference {vr}) is out of range: allowed a finite value; nothing was set",
                    v.name
                )));
            }
        }
        let mut parameter_changed = false;
        for (&vr, &x) in vrs.iter().zip(values) {
            let access = self.table.get(vr).expect("checked above").access;
            match access {
                Access::Input(slot) => self.inputs.set(slot, x),
                Access::RealParameter { set, .. } => {
                    set(&mut self.scene, x);
                    parameter_changed = true;
                }
                _ => unreachable!("settable Real variables are inputs or Real parameters"),
            }
        }
        if self.state != MachineState::StepComplete {
            self.invalidate(parameter_changed);
        }
        Ok(Status::Ok)
    }

    /// `fmi2SetInteger`: all values are checked first; on error nothing is set.
    pub fn set_integer(&mut self, vrs: &[ValueReference], values: &[i32]) -> FmiResult<Status> {
        let mut scene = self.scene.clone();
        for (&vr, &n) in vrs.iter().zip(values) {
            let v = self.settable(vr, Family::Integer)?;
            if let Access::IntegerParameter { set, .. } = v.access {
                set(&mut scene, n).map_err(|allowed| {
                    FmiError::rejected(format!(
                        "{} = {n} (value reference {vr}) is out of range: allowed {allowed}; nothing was set",
                        v.name
                    ))
                })?;
            }
        }
        if !vrs.is_empty() {
            self.scene = scene;
            self.invalidate(true);
        }
        Ok(Status::Ok)
    }

    /// `fmi2GetBoolean`, `fmi2SetBoolean`, `fmi2GetString`, `fmi2SetString`: this FMU has no
    /// such variables, so any value reference is unknown.
    pub fn no_variables_of(&self, family: Family, vrs: &[ValueReference]) -> FmiResult<Status> {
        match vrs.first() {
            None => Ok(Status::Ok),
            Some(&vr) => self.variable(vr, family).map(|_| Status::Ok),
        }
    }

    /// `fmi2SetRealInputDerivatives`: the crank acceleration alpha_k of the law that starts
    /// at this communication point.
    ///
    /// - Order 1 of `crank.speed` and order 2 of `crank.angle` are alpha_k. If both are given
    ///   at the same point and differ, `crank.speed`'s is used, with a warning.
    /// - Order 1 of `crank.angle` is accepted and not used (the angle follows from
    ///   `crank.speed`); a value different from `crank.speed` gives a warning.
    /// - A derivative the law already has (0 for `slider.force`, which is held over a step, for
    ///   order >= 2 of `crank.speed` and order >= 3 of `crank.angle`) is accepted silently; any
    ///   other value of these cannot be used: it is ignored with a warning.
    /// - Order <= 0, unknown value references, variables that are not inputs and non-finite
    ///   values are errors, and then nothing is set.
    pub fn set_real_input_derivatives(
        &mut self,
        vrs: &[ValueReference],
        orders: &[i32],
        values: &[f64],
    ) -> FmiResult<Status> {
        for ((&vr, &order), &x) in vrs.iter().zip(orders).zip(values) {
            let v = self.variable(vr, Family::Real)?;
            if !matches!(v.access, Access::Input(_)) {
                return Err(FmiError::rejected(format!(
                    "{} (value reference {vr}) has causality {}: input derivatives can be set only for inputs (crank.speed, crank.angle); nothing was set",
                    v.name,
                    v.causality.as_str()
                )));
            }
            if order <= 0 {
                return Err(FmiError::rejected(format!(
                    "derivative order {order} of {} is out of range: allowed an order >= 1 (order 1 of crank.speed or order 2 of crank.angle is the crank acceleration); nothing was set",
                    v.name
                )));
            }
            if !x.is_finite() {
                return Err(FmiError::rejected(format!(
                    "order-{order} derivative of {} = {x} is out of range: allowed a finite value; nothing was set",
                    v.name
                )));
            }
        }
        let mut warnings = Vec::new();
        for ((&vr, &order), &x) in vrs.iter().zip(orders).zip(values) {
            let Some(Access::Input(slot)) = self.table.get(vr).map(|v| v.access) else {
                continue;
            };
            match (slot, order) {
                (InputSlot::CrankSpeed, 1) => {
                    let previous = self.inputs.acceleration;
                    if self.inputs.source == AccelerationSource::Angle && previous != x {
                        warnings.push(format!(
                            "the crank acceleration is given twice at this point: order 2 of crank.angle = {previous} rad/s^2 and order 1 of crank.speed = {x} rad/s^2; crank.speed's is used"
                        ));
                    }
                    self.inputs.acceleration = x;
                    self.inputs.source = AccelerationSource::Speed;
                }
                (InputSlot::CrankAngle, 2) => match self.inputs.source {
                    AccelerationSource::Speed => {
                        let used = self.inputs.acceleration;
                        if used != x {
                            warnings.push(format!(
                                "the crank acceleration is given twice at this point: order 1 of crank.speed = {used} rad/s^2 and order 2 of crank.angle = {x} rad/s^2; crank.speed's is used"
                            ));
                        }
                    }
                    AccelerationSource::None | AccelerationSource::Angle => {
                        self.inputs.acceleration = x;
                        self.inputs.source = AccelerationSource::Angle;
                    }
                },
                (InputSlot::CrankAngle, 1) => {
                    let speed = self.inputs.speed;
                    if (x - speed).abs() > 1e-9 * speed.abs().max(1.0) {
                        warnings.push(format!(
                            "order-1 derivative of crank.angle = {x} rad/s differs from crank.speed = {speed} rad/s; it is not used (the angle follows from crank.speed)"
                        ));
                    }
                }
                (_, _) if x == 0.0 => {}
                (slot, order) => {
                    let name = self.table.get(vr).map(|v| v.name.as_str()).unwrap_or("?");
                    let why = match slot {
                        InputSlot::SliderForce => "slider.force is held constant over a step",
                        InputSlot::CrankSpeed | InputSlot::CrankAngle => {
                            "the crank law has a constant acceleration over a step (order 1 of crank.speed or order 2 of crank.angle)"
                        }
                    };
                    warnings.push(format!(
                        "order-{order} derivative of {name} = {x} cannot be used and is ignored: {why}"
                    ));
                }
            }
        }
        for w in &warnings {
            self.logger.status(
                Status::Warning,
                &format!("fmi2SetRealInputDerivatives: {w}"),
            );
        }
        if self.state != MachineState::StepComplete {
            self.invalidate(false);
        }
        Ok(if warnings.is_empty() {
            Status::Ok
        } else {
            Status::Warning
        })
    }

    /// `fmi2GetRealOutputDerivatives`: not provided (`maxOutputDerivativeOrder="0"`).
    pub fn get_real_output_derivatives(&self) -> FmiResult<Status> {
        Err(FmiError::rejected(
            "output derivatives are not provided (maxOutputDerivativeOrder = 0)",
        ))
    }

    /// `fmi2GetDirectionalDerivative`: not provided (`providesDirectionalDerivative="false"`).
    pub fn get_directional_derivative(&self) -> FmiResult<Status> {
        Err(FmiError::rejected(
            "directional derivatives are not provided (providesDirectionalDerivative = false)",
        ))
    }

    // ---------------------------------------------------------------- stepping

    /// `fmi2DoStep`: integrate from the FMU time `t` to `t + h`.
    pub fn do_step(&mut self, t: f64, h: f64) -> FmiResult<Status> {
        let Some(simulation) = self.simulation.as_mut() else {
            return Err(FmiError::failed("no simulation (internal error)"));
        };
        let now = simulation.time();
        let tolerance = TIME_TOLERANCE * now.abs().max(1.0);
        if !(t.is_finite() && (t - now).abs() <= tolerance) {
            return Err(FmiError::rejected(format!(
                "currentCommunicationPoint = {t} s does not match the FMU time {now} s: allowed {now} +- {tolerance:e} s"
            )));
        }
        if !(h.is_finite() && h > 0.0) {
            return Err(FmiError::rejected(format!(
                "communicationStepSize = {h} s is out of range: allowed a finite value > 0"
            )));
        }
        if let Some(stop) = self.experiment.stop_time {
            if now + h > stop + TIME_TOLERANCE * stop.abs().max(1.0) {
                return Err(FmiError::rejected(format!(
                    "the step from t = {now} s with h = {h} s would end at {} s, after stopTime = {stop} s of fmi2SetupExperiment: allowed h <= {}",
                    now + h,
                    stop - now
                )));
            }
        }
        // A new law starts at every communication point: theta_k, omega_k as set (or the
        // previous law's values at t_k), alpha_k as set at t_k or 0 (see `inputs`).
        simulation
            .set_input(self.inputs.crank_input())
            .map_err(|e| FmiError::rejected(model_error(e)))?;
        if self.inputs.force_changed {
            simulation
                .set_slider_force(self.inputs.slider_force)
                .map_err(|e| FmiError::rejected(model_error(e)))?;
        }
        match simulation.advance(h) {
            Ok(_) => {
                // The values the law used at the new time, from the core's own law.
                let time = simulation.time();
                let (angle, speed, _) = simulation
                    .mechanism()
                    .crank_law(simulation.state())
                    .kinematics(time);
                self.inputs.after_step(angle, speed);
                self.last_step = Status::Ok;
                Ok(self.take_warnings())
            }
            Err(e @ ModelError::StepFailed { .. }) => {
                self.state = MachineState::StepFailed;
                self.last_step = Status::Discard;
                self.take_warnings();
                Err(FmiError::discard(format!(
                    "{e}. Restore a state saved before the step (fmi2SetFMUstate) and retry with a smaller communication step, or terminate"
                )))
            }
            Err(e) => {
                self.take_warnings();
                Err(FmiError::failed(model_error(e)))
            }
        }
    }

    /// Pass the simulation's warnings to the logger; `Warning` if there were any.
    fn take_warnings(&mut self) -> Status {
        let Some(simulation) = self.simulation.as_mut() else {
            return Status::Ok;
        };
        let warnings = simulation.take_warnings();
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
        match (kind, &self.simulation) {
            (StatusKind::LastSuccessfulTime, Some(s)) => Ok(s.time()),
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

    // ---------------------------------------------------------------- FMU states

    fn capture(&self) -> FmuState {
        FmuState {
            machine: self.state,
            scene: self.scene.clone(),
            inputs: self.inputs,
            experiment: self.experiment,
            started: self.started,
            last_step: self.last_step,
            simulation: self.simulation.as_ref().map(Simulation::snapshot),
        }
    }

    fn saved(&self, handle: usize) -> FmiResult<&FmuState> {
        self.fmu_states.get(&handle).ok_or_else(|| {
            FmiError::rejected(format!(
                "FMU state {handle:#x} is not a state of this instance (never created here, or already freed)"
            ))
        })
    }

    /// The handle to store a state under: `existing` if it is a live state of this instance
    /// (it is overwritten), else a new one (NULL, or a handle of another instance or one
    /// already freed: that handle is left alone).
    fn handle_for(&self, existing: Option<usize>) -> usize {
        match existing {
            Some(h) if self.fmu_states.contains_key(&h) => h,
            _ => NEXT_STATE_HANDLE.fetch_add(1, Ordering::Relaxed),
        }
    }

    /// `fmi2GetFMUstate`: a new handle, or `existing` overwritten if it is this instance's.
    pub fn get_fmu_state(&mut self, existing: Option<usize>) -> FmiResult<usize> {
        let state = self.capture();
        let handle = self.handle_for(existing);
        self.fmu_states.insert(handle, state);
        if matches!(self.serialized, Some((h, _)) if h == handle) {
            self.serialized = None;
        }
        Ok(handle)
    }

    /// `fmi2SetFMUstate`: everything, including the state machine's state, as when saved.
    pub fn set_fmu_state(&mut self, handle: usize) -> FmiResult<Status> {
        self.saved(handle)?;
        let saved = &self.fmu_states[&handle];
        match &saved.simulation {
            None => self.simulation = None,
            Some(snapshot) => {
                let reuse = self.simulation.is_some() && self.scene == saved.scene;
                if !reuse {
                    let rebuilt = Simulation::new(&saved.scene)
                        .map_err(|e| FmiError::rejected(model_error(e)))?;
                    self.simulation = Some(rebuilt);
                }
                if let Some(simulation) = self.simulation.as_mut() {
                    simulation.restore(snapshot);
                }
            }
        }
        self.scene.clone_from(&saved.scene);
        self.inputs = saved.inputs;
        self.experiment = saved.experiment;
        self.started = saved.started;
        self.last_step = saved.last_step;
        self.state = saved.machine;
        self.failure = None;
        Ok(Status::Ok)
    }

    /// `fmi2FreeFMUstate`.
    pub fn free_fmu_state(&mut self, handle: usize) -> FmiResult<Status> {
        self.saved(handle)?;
        self.fmu_states.remove(&handle);
        if matches!(self.serialized, Some((h, _)) if h == handle) {
            self.serialized = None;
        }
        Ok(Status::Ok)
    }

    /// Bytes of a saved state (computed once per handle).
    fn serialized(&mut self, handle: usize) -> FmiResult<&[u8]> {
        let cached = matches!(&self.serialized, Some((h, _)) if *h == handle);
        if !cached {
            self.saved(handle)?;
            let saved = &self.fmu_states[&handle];
            // The core serializes the current state of a simulation: bring the saved
            // snapshot in, write it, and put the current state back.
            let simulation_bytes = match &saved.simulation {
                None => None,
                Some(snapshot) => Some(with_simulation_of(
                    self.simulation.as_mut(),
                    &self.scene,
                    &saved.scene,
                    |s| {
                        s.restore(snapshot);
                        Ok(s.snapshot_to_bytes())
                    },
                )?),
            };
            let bytes = fmu_state::serialize(&self.guid, saved, simulation_bytes.as_deref());
            self.serialized = Some((handle, bytes));
        }
        Ok(self
            .serialized
            .as_ref()
            .map(|(_, b)| b.as_slice())
            .unwrap_or(&[]))
    }

    /// `fmi2SerializedFMUstateSize`.
    pub fn serialized_size(&mut self, handle: usize) -> FmiResult<usize> {
        Ok(self.serialized(handle)?.len())
    }

    /// `fmi2SerializeFMUstate`: `out` must have exactly the size reported.
    pub fn serialize_fmu_state(&mut self, handle: usize, out: &mut [u8]) -> FmiResult<Status> {
        let bytes = self.serialized(handle)?;
        if out.len() != bytes.len() {
            return Err(FmiError::rejected(format!(
                "size = {} bytes is wrong: allowed {} (from fmi2SerializedFMUstateSize)",
                out.len(),
                bytes.len()
            )));
        }
        out.copy_from_slice(bytes);
        Ok(Status::Ok)
    }

    /// `fmi2DeSerializeFMUstate`: a new handle, or `existing` overwritten if it is this
    /// instance's (a handle of another instance, e.g. the one the bytes were serialized from,
    /// gets a new handle here). Foreign, truncated, corrupted or other-model bytes are
    /// rejected and nothing changes.
    pub fn deserialize_fmu_state(
        &mut self,
        bytes: &[u8],
        existing: Option<usize>,
    ) -> FmiResult<usize> {
        let parsed = fmu_state::deserialize(&self.guid, bytes)
            .map_err(|m| FmiError::rejected(format!("serialized state rejected: {m}")))?;
        let simulation = match parsed.simulation_bytes {
            None => None,
            Some(b) => Some(with_simulation_of(
                self.simulation.as_mut(),
                &self.scene,
                &parsed.state.scene,
                |s| {
                    s.restore_from_bytes(b)?;
                    Ok(s.snapshot())
                },
            )?),
        };
        let state = FmuState {
            simulation,
            ..parsed.state
        };
        let handle = self.handle_for(existing);
        self.fmu_states.insert(handle, state);
        if matches!(self.serialized, Some((h, _)) if h == handle) {
            self.serialized = None;
        }
        Ok(handle)
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
    if args.fmu_type != FMI2_CO_SIMULATION {
        return Err(format!(
            "fmuType = {} is not supported: allowed {FMI2_CO_SIMULATION} (fmi2CoSimulation); this FMU implements only Co-Simulation",
            args.fmu_type
        ));
    }
    let loaded = resource::load_model(args.resource_location, args.guid)?;
    logger.event(&format!(
        "instance \"{}\" of {} uses {}",
        args.instance_name, loaded.description.guid, loaded.origin
    ));
    Ok(loaded)
}

/// Run `f` on a simulation of `scene` whose state `f` may replace: the instance's own one if
/// it was built from the same scene (its state is put back bit for bit afterwards), else a
/// scratch one.
fn with_simulation_of<T>(
    own: Option<&mut Simulation>,
    own_scene: &Scene,
    scene: &Scene,
    f: impl FnOnce(&mut Simulation) -> Result<T, ModelError>,
) -> FmiResult<T> {
    let result = match own {
        Some(simulation) if own_scene == scene => {
            let current = simulation.snapshot();
            let result = f(simulation);
            simulation.restore(&current);
            result
        }
        _ => Simulation::new(scene).and_then(|mut scratch| f(&mut scratch)),
    };
    result.map_err(|e| FmiError::rejected(model_error(e)))
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

/// Message of a caught panic payload.
pub(crate) fn panic_text(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "unknown panic payload".to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fmi::logging::LogSink;

    struct PanickingSink;
    impl LogSink for PanickingSink {
        fn emit(&self, _: Status, _: &'static str, message: &str) {
            panic!("the logger failed on: {message}");
        }
    }

    fn instance(sink: Option<Box<dyn LogSink>>) -> Instance {
        let scene = Scene::benchmark();
        let description = ModelDescription::for_scene(&scene).unwrap();
        Instance::from_description(scene, description, Logger::new(sink, false))
    }

    #[test]
    fn a_panic_while_logging_moves_the_instance_to_error() {
        let mut i = instance(Some(Box::new(PanickingSink)));
        let status = i.run(Call::GetReal, |i| i.get_real(&[9999], &mut [0.0]));
        assert_eq!(status, Status::Error);
        assert_eq!(i.machine_state(), MachineState::Error);
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
