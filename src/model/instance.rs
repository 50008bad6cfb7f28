//! One model instance as an importer drives it: the parameters it set, its inputs and their
//! law, and the simulation built from them. These are the hooks an interface layer calls (the
//! way a model of the Modelica Reference-FMUs implements a few functions that a generic shell
//! calls); it says nothing of how the interface reports the outcome.

use super::inputs::Inputs;
use super::variables::{Access, Interface, Value, Variable, VariableId, VariableTable};
use crate::cosimulation::{DefaultExperiment, ModelInfo};
use crate::error::ModelError;
use crate::scene::Scene;
use crate::simulation::{Simulation, Snapshot};

/// Why a step did not complete.
#[derive(Debug)]
pub enum StepError {
    /// The inputs set for the step were refused; nothing changed.
    Inputs(ModelError),
    /// The step itself failed; the state before it is kept.
    Step(ModelError),
}

/// One instance of the rod's model.
pub struct RodModel {
    /// Its variables, declared for the interface it was built for.
    table: VariableTable,
    info: ModelInfo,
    /// The scene the model was exported for: the start values, restored by [`RodModel::reset`].
    exported: Scene,
    /// The instance's own copy, with the parameters the importer set.
    scene: Scene,
    inputs: Inputs,
    /// Built from `scene` (invariant: `Some` only if built from the current `scene`).
    simulation: Option<Simulation>,
    /// The simulation was started with the current inputs.
    started: bool,
    /// `crank.design_speed` was 0 and took this crank speed when the model was built: a new
    /// crank speed or parameter before stepping puts 0 back, so the next build takes the
    /// speed then.
    design_speed_filled: Option<f64>,
}

/// A saved model: everything [`RodModel::restore`] needs to continue bit for bit.
#[derive(Clone, Debug)]
pub struct SavedModel {
    scene: Scene,
    inputs: Inputs,
    started: bool,
    simulation: Option<Snapshot>,
}

impl SavedModel {
    /// The simulation's time, if a simulation was saved.
    pub fn time(&self) -> Option<f64> {
        self.simulation.as_ref().map(Snapshot::time)
    }

    /// The simulation was started with the saved inputs.
    pub fn started(&self) -> bool {
        self.started
    }

    /// A simulation was saved (the model had been built).
    pub fn has_simulation(&self) -> bool {
        self.simulation.is_some()
    }

    /// The inputs' byte form ([`Inputs::to_bytes`]).
    pub fn inputs_bytes(&self) -> [u8; Inputs::BYTES] {
        self.inputs.to_bytes()
    }

    /// The parameters as scene text (TOML).
    pub fn parameters_text(&self) -> String {
        self.scene.to_toml()
    }

    /// A saved model without a simulation from its parts (as [`SavedModel::started`],
    /// [`SavedModel::inputs_bytes`], [`SavedModel::parameters_text`] give them); the
    /// simulation's bytes are read by [`RodModel::saved_from_bytes`].
    pub fn from_parts(
        started: bool,
        inputs: &[u8; Inputs::BYTES],
        parameters: &str,
    ) -> Result<SavedModel, String> {
        let inputs = Inputs::from_bytes(inputs)?;
        let scene =
            Scene::from_toml_str(parameters, "the serialized state").map_err(|e| e.to_string())?;
        Ok(SavedModel {
            scene,
            inputs,
            started,
            simulation: None,
        })
    }
}

impl RodModel {
    /// A model of `scene` with its variables declared for `interface` (the model is built
    /// once to count the natural frequencies), not built yet.
    pub fn new(scene: Scene, interface: Interface) -> Result<RodModel, ModelError> {
        let table = VariableTable::for_scene(&scene, interface)?;
        RodModel::with_table(scene, table)
    }

    /// A model of `scene` with the variables of `table`, inputs at its start values, not
    /// built yet. The scene's texts must be ones descriptions carry.
    pub fn with_table(scene: Scene, table: VariableTable) -> Result<RodModel, ModelError> {
        // The scene's texts go into attributes: only characters XML 1.0 carries.
        scene.validate_texts()?;
        let e = &scene.experiment;
        let info = ModelInfo {
            name: scene.name.clone(),
            description: scene.description.clone(),
            default_experiment: DefaultExperiment {
                start_time: e.start_time,
                stop_time: e.stop_time,
                step_size: e.step_size,
            },
            units: crate::cosimulation::units::SI_UNITS,
            enumeration_types: &super::variables::ENUMERATION_TYPES,
        };
        Ok(RodModel {
            inputs: Inputs::from_start_values(&table),
            table,
            info,
            exported: scene.clone(),
            scene,
            simulation: None,
            started: false,
            design_speed_filled: None,
        })
    }

    /// Its variables.
    pub fn table(&self) -> &VariableTable {
        &self.table
    }

    /// The model's info (names, default experiment, units, enumeration types).
    pub fn model_info(&self) -> &ModelInfo {
        &self.info
    }

    /// Back to the start values of the exported scene and of the table, not built.
    pub fn reset(&mut self) {
        self.scene = self.exported.clone();
        self.inputs = Inputs::from_start_values(&self.table);
        self.simulation = None;
        self.started = false;
        self.design_speed_filled = None;
    }

    /// What sets the accuracy instead of an importer's tolerance, in words.
    pub fn accuracy_note(&self) -> String {
        format!(
            "the integrator follows the scene's [solver] settings (step = {} s, newton_tolerance = {}; the parameter solver.tolerance sets the error control)",
            self.scene.solver.step, self.scene.solver.newton_tolerance
        )
    }

    /// The simulation's time, if it is built.
    pub fn time(&self) -> Option<f64> {
        self.simulation.as_ref().map(Simulation::time)
    }

    /// The simulation is built (for the current parameters).
    pub fn is_built(&self) -> bool {
        self.simulation.is_some()
    }

    /// A parameter or input changed before stepping: the start must be redone (and, for a
    /// parameter, the model rebuilt).
    pub fn invalidate(&mut self, parameter_changed: bool) {
        if let Some(filled) = self.design_speed_filled {
            let speed_changed = self.inputs.speed.abs() != filled;
            if (parameter_changed || speed_changed) && self.scene.crank.design_speed == filled {
                self.scene.crank.design_speed = 0.0;
                self.design_speed_filled = None;
                self.simulation = None;
            }
        }
        if parameter_changed {
            self.simulation = None;
        }
        self.started = false;
    }

    /// Drop the simulation (after a failed start nothing may look started).
    pub fn discard_simulation(&mut self) {
        self.simulation = None;
        self.started = false;
    }

    /// Build the simulation for the current parameters if needed, with at least the
    /// frequencies `table` declares, and start it with the current inputs at `t0`.
    pub fn ensure_started(&mut self, t0: f64) -> Result<(), ModelError> {
        if self.simulation.is_none() {
            check_geometry(&self.scene)?;
            // `crank.design_speed = 0`: the crank speed at initialization, written into the
            // parameter (and, for a start from rest, into the experiment's speed the scene
            // falls back on) so that saved states, the model's fingerprint and a reader see the
            // speed the rod model was chosen for.
            if let Some(speed) = self.scene.take_design_speed(self.inputs.speed) {
                self.design_speed_filled = (speed > 0.0).then_some(speed);
            }
            let simulation = Simulation::new(&self.scene)?;
            let available = simulation.frequencies_hz().len();
            let declared = self.table.frequency_count();
            if available < declared {
                return Err(ModelError::State {
                    message: format!(
                        "rod.elements = {} with these rod.model and rod.reference leaves {available} natural frequencies, but the variable table declares rod.frequency[1..{declared}]: allowed parameters that leave at least {declared} (e.g. more elements), or export the scene with [outputs] frequencies <= {available}",
                        self.scene.rod.elements
                    ),
                });
            }
            self.simulation = Some(simulation);
            self.started = false;
        }
        if !self.started {
            let input = self.inputs.crank_input();
            let force = self.inputs.slider_force;
            if let Some(simulation) = self.simulation.as_mut() {
                simulation.start(t0, input, force)?;
            }
            self.started = true;
        }
        Ok(())
    }

    /// Stepping begins: the simulation started with the current slider force; the crank
    /// acceleration set before holds for the first step (it was set at the start time).
    pub fn begin_stepping(&mut self) {
        self.inputs.force_changed = false;
    }

    /// The start in words: the crank inputs, the lowest natural frequency, the rod model.
    pub fn start_summary(&self) -> String {
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
        let start = match &self.simulation {
            Some(s) if s.state().start_vibration > 0.0 => format!(
                "; the start at speed rings a free vibration of about {:.2e} in v_mid/L (quasi-static estimate; rod.error_estimate takes the forced deflection as the peak less it)",
                s.state().start_vibration
            ),
            Some(s) if s.mechanism().start_vibration_estimated(s.state().input) => {
                "; the free vibration of the start at speed was not estimated (its quasi-static deflection was not found): rod.error_estimate takes the whole peak".to_string()
            }
            _ => String::new(),
        };
        format!(
            "crank.angle = {} rad, crank.speed = {} rad/s; {frequency}; {model}{start}",
            self.inputs.angle, self.inputs.speed,
        )
    }

    /// The values of the Real variable `v` (one, or an array's elements) into `out`; outputs
    /// need the simulation (see [`Access::needs_simulation`]), `time` before it is built is
    /// `start_time`. A value the model computes (an output, the shape, a frequency) is handed
    /// out only within the range of an accepted step: finite, |value| <
    /// [`crate::mechanism::MAX_OUTPUT_MAGNITUDE`]; else an error names it.
    pub fn get_real(&self, v: &Variable, out: &mut [f64], start_time: f64) -> Result<(), String> {
        self.read_real(v, out, start_time)?;
        let computed = matches!(
            v.access,
            Access::Output(_) | Access::Frequency(_) | Access::Frequencies | Access::Shape
        );
        let bound = crate::mechanism::MAX_OUTPUT_MAGNITUDE;
        match out.iter().find(|x| !(x.is_finite() && x.abs() < bound)) {
            Some(x) if computed => Err(format!(
                "{} = {x:e} is outside the range of every accepted step (finite, |value| < {bound:e} in SI units): the model does not stand behind it",
                v.name
            )),
            _ => Ok(()),
        }
    }

    fn read_real(&self, v: &Variable, out: &mut [f64], start_time: f64) -> Result<(), String> {
        let frequencies = self
            .simulation
            .as_ref()
            .map_or(&[][..], |s| s.frequencies_hz());
        let missing = || format!("{} does not exist for these parameters", v.name);
        out[0] = match v.access {
            Access::Input(slot) => self.inputs.value(slot),
            Access::Output(get) => get(&self
                .simulation
                .as_ref()
                .map_or_else(Default::default, Simulation::outputs)),
            Access::RealParameter { get, applied, .. } => match (applied, &self.simulation) {
                (Some(applied), Some(s)) => applied(s),
                _ => get(&self.scene),
            },
            Access::Frequency(i) => *frequencies.get(i).ok_or_else(missing)?,
            Access::Frequencies => {
                let all = frequencies.get(..out.len()).ok_or_else(missing)?;
                out.copy_from_slice(all);
                return Ok(());
            }
            Access::Shape => {
                if let Some(s) = &self.simulation {
                    s.mechanism().deflection_shape(s.state(), out);
                }
                return Ok(());
            }
            Access::Time => self.time().unwrap_or(start_time),
            Access::RodMass => self
                .scene
                .rod
                .total_mass()
                .map_err(|e| format!("{} is not available: {e}", v.name))?,
            Access::IntegerParameter { .. } => {
                return Err(format!("{} is not a Real variable", v.name))
            }
        };
        Ok(())
    }

    /// The value of the Integer or Enumeration variable `v`.
    pub fn get_integer(&self, v: &Variable) -> Result<i32, String> {
        match v.access {
            Access::IntegerParameter { get, .. } => Ok(get(&self.scene)),
            _ => Err(format!("{} is not an Integer variable", v.name)),
        }
    }

    /// Check a value for the Real input or parameter `v` before anything is set: the
    /// allowed magnitude of an input, as an error text.
    pub fn check_real(v: &Variable, x: f64) -> Result<(), String> {
        if let Access::Input(slot) = v.access {
            let bound = slot.window();
            if x.abs() > bound {
                return Err(format!("|value| <= {bound:e} in SI units"));
            }
        }
        Ok(())
    }

    /// Set the Real input or parameter `vr`; true if a parameter changed.
    pub fn set_real(&mut self, vr: VariableId, x: f64) -> Result<bool, String> {
        let v = self.table.get(vr).ok_or_else(|| unknown(vr))?;
        match v.access {
            Access::Input(slot) => {
                self.inputs.set(slot, x);
                Ok(false)
            }
            Access::RealParameter { set, .. } => {
                set(&mut self.scene, x);
                Ok(true)
            }
            _ => Err(format!("{} cannot be set", v.name)),
        }
    }

    /// Set Integer parameters, all or none: on error, the position of the refused one and
    /// the allowed values.
    pub fn set_integers(&mut self, items: &[(VariableId, i32)]) -> Result<(), (usize, String)> {
        let mut scene = self.scene.clone();
        for (k, &(vr, n)) in items.iter().enumerate() {
            let v = self.table.get(vr).ok_or_else(|| (k, unknown(vr)))?;
            // The declared range holds at the set call. Where it is narrower than the setter's
            // own (`rod.elements`: the least count that leaves the declared frequencies for the
            // exported model), its text is the message; elsewhere the setter's, which names the
            // items of an enumeration.
            let declared = match (&v.min, &v.max) {
                (Some(Value::Integer(low)), Some(Value::Integer(high)))
                    if !(*low..=*high).contains(&n) =>
                {
                    Some(declared_range_text(v, *low, *high))
                }
                _ => None,
            };
            let narrower = NARROWER_THAN_THE_SETTER.contains(&v.name.as_str());
            if let (Some(text), true) = (&declared, narrower) {
                return Err((k, text.clone()));
            }
            match v.access {
                Access::IntegerParameter { set, .. } => set(&mut scene, n).map_err(|e| (k, e))?,
                _ => return Err((k, format!("{} cannot be set as an Integer", v.name))),
            }
            if let Some(text) = declared {
                return Err((k, text));
            }
        }
        if !items.is_empty() {
            self.scene = scene;
            self.invalidate(true);
        }
        Ok(())
    }

    /// Set input derivatives ([`Inputs::set_derivatives`]); returns the warnings.
    pub fn set_input_derivatives(
        &mut self,
        items: &[(VariableId, i32, f64)],
    ) -> Result<Vec<String>, String> {
        let mut resolved = Vec::with_capacity(items.len());
        for &(vr, order, x) in items {
            resolved.push((self.table.get(vr).ok_or_else(|| unknown(vr))?, order, x));
        }
        self.inputs.set_derivatives(&resolved)
    }

    /// Refuse, before anything changes, a communication step `h` that needs too much work.
    pub fn check_step(&self, h: f64) -> Result<(), ModelError> {
        match &self.simulation {
            Some(s) => s.check_work(h),
            None => Ok(()),
        }
    }

    /// One communication step of `h` from the current time: a new input law starts now
    /// (theta_k, omega_k as set, or the previous law's values now; alpha_k as set now, or 0,
    /// see [`super::inputs`]). A step that is refused or fails puts the inputs in force back
    /// (with the state, which the core restores), so that continuing gives what a run that
    /// never tried gives.
    pub fn step(&mut self, h: f64) -> Result<(), StepError> {
        let Some(simulation) = self.simulation.as_mut() else {
            return Err(StepError::Inputs(ModelError::State {
                message: "no simulation (internal error)".into(),
            }));
        };
        let saved_inputs = simulation.inputs_snapshot();
        let inputs = &self.inputs;
        let mut set_inputs = || {
            simulation.set_input(inputs.crank_input())?;
            if inputs.force_changed {
                simulation.set_slider_force(inputs.slider_force)?;
            }
            Ok(())
        };
        if let Err(e) = set_inputs() {
            simulation.restore_inputs(saved_inputs);
            return Err(StepError::Inputs(e));
        }
        if let Err(e) = simulation.advance(h) {
            simulation.restore_inputs(saved_inputs);
            return Err(StepError::Step(e));
        }
        // The values the law used at the new time, from the core's own law.
        let time = simulation.time();
        let (angle, speed, _) = simulation
            .mechanism()
            .crank_law(simulation.state())
            .kinematics(time);
        self.inputs.after_step(angle, speed);
        Ok(())
    }

    /// The simulation's warnings since the last call.
    pub fn take_warnings(&mut self) -> Vec<String> {
        match self.simulation.as_mut() {
            Some(s) => s.take_warnings(),
            None => Vec::new(),
        }
    }

    /// Save everything.
    pub fn save(&self) -> SavedModel {
        SavedModel {
            scene: self.scene.clone(),
            inputs: self.inputs,
            started: self.started,
            simulation: self.simulation.as_ref().map(Simulation::snapshot),
        }
    }

    /// Restore a saved model (rebuilding the simulation if the parameters differ).
    pub fn restore(&mut self, saved: &SavedModel) -> Result<(), ModelError> {
        match &saved.simulation {
            None => self.simulation = None,
            Some(snapshot) => {
                let reuse = self.simulation.is_some() && self.scene == saved.scene;
                if !reuse {
                    self.simulation = Some(Simulation::new(&saved.scene)?);
                }
                if let Some(simulation) = self.simulation.as_mut() {
                    simulation.restore(snapshot);
                }
            }
        }
        self.scene.clone_from(&saved.scene);
        self.inputs = saved.inputs;
        self.started = saved.started;
        self.design_speed_filled = None;
        Ok(())
    }

    /// The bytes of the simulation of `saved` (`None` without one): its model fingerprint,
    /// then its state ([`Simulation::state_to_bytes`]). The current state is left as it was.
    pub fn simulation_bytes(&mut self, saved: &SavedModel) -> Result<Option<Vec<u8>>, ModelError> {
        let Some(snapshot) = &saved.simulation else {
            return Ok(None);
        };
        self.with_simulation_of(&saved.scene, |s| {
            s.restore(snapshot);
            Ok(s.state_to_bytes())
        })
        .map(Some)
    }

    /// Refuse a saved model whose scene is not this model's exported scene with only the
    /// parameters of `table` changed ([`super::binding::check_same_model`]).
    pub fn check_same_model(&self, saved: &SavedModel) -> Result<(), String> {
        super::binding::check_same_model(&self.exported, &saved.scene, &self.table)
    }

    /// `saved` (from [`SavedModel::from_parts`]) with the simulation read from the core's
    /// bytes. Foreign, truncated or other-model bytes are rejected.
    pub fn saved_from_bytes(
        &mut self,
        saved: SavedModel,
        simulation_bytes: Option<&[u8]>,
    ) -> Result<SavedModel, ModelError> {
        let simulation = match simulation_bytes {
            None => None,
            Some(b) => Some(self.with_simulation_of(&saved.scene, |s| {
                s.restore_state_bytes(b)?;
                Ok(s.snapshot())
            })?),
        };
        Ok(SavedModel {
            simulation,
            ..saved
        })
    }

    /// Run `f` on a simulation of `scene` whose state `f` may replace: the instance's own one
    /// if it was built from the same scene (its state is put back bit for bit afterwards),
    /// else a scratch one.
    fn with_simulation_of<T>(
        &mut self,
        scene: &Scene,
        f: impl FnOnce(&mut Simulation) -> Result<T, ModelError>,
    ) -> Result<T, ModelError> {
        match self.simulation.as_mut() {
            Some(simulation) if self.scene == *scene => {
                let current = simulation.snapshot();
                let result = f(simulation);
                simulation.restore(&current);
                result
            }
            _ => Simulation::new(scene).and_then(|mut scratch| f(&mut scratch)),
        }
    }
}

/// The message for an identifier the table does not have.
fn unknown(vr: VariableId) -> String {
    format!("unknown value reference {vr}")
}

/// Integer parameters whose declared range is narrower than what their setter takes.
const NARROWER_THAN_THE_SETTER: [&str; 1] = ["rod.elements"];

/// The allowed values of an Integer parameter whose declared range refused a value.
fn declared_range_text(v: &Variable, low: i32, high: i32) -> String {
    if v.name == "rod.elements" {
        format!(
            "an integer in {low}..={high} (the declared range: the least count that leaves the declared rod.frequency values for the exported rod.model, up to the mesh limit)"
        )
    } else {
        format!("an integer in {low}..={high} (the declared range)")
    }
}

/// The slider-crank turns a full revolution only with r < L; the core checks the rest.
fn check_geometry(scene: &Scene) -> Result<(), ModelError> {
    let (r, l) = (scene.crank.length, scene.rod.length);
    if r.is_finite() && l.is_finite() && r >= l {
        return Err(ModelError::State {
            message: format!(
                "crank.length = {r} m must be smaller than rod.length = {l} m: allowed 0 < crank.length < rod.length (otherwise the crank cannot turn a full revolution)"
            ),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_crank_as_long_as_the_rod_is_refused_with_both_values() {
        let mut scene = Scene::benchmark();
        scene.crank.length = scene.rod.length;
        let table = VariableTable::new(&scene, 0);
        let mut model = RodModel::with_table(scene, table).unwrap();
        let e = model.ensure_started(0.0).unwrap_err().to_string();
        assert!(
            e.contains("crank.length = 0.3048 m") && e.contains("0 < crank.length < rod.length"),
            "{e}"
        );
        assert!(!model.is_built());
    }
}
