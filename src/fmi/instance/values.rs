//! `fmi2Get*` and `fmi2Set*`: dispatch through the variable table, checks before any change
//! (a rejected call sets nothing), and the model rebuilt on demand in initialization mode.

use super::Instance;
use crate::fmi::state_machine::MachineState;
use crate::fmi::status::{FmiError, FmiResult, Status};
use crate::fmi::variables::{Access, Causality, Family, ValueReference, Variable};

impl Instance {
    pub(super) fn variable(&self, vr: ValueReference, family: Family) -> FmiResult<&Variable> {
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
    pub(super) fn invalidate(&mut self, parameter_changed: bool) {
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
                Access::RodMass => {
                    self.scene.rod.total_mass().map_err(|e| {
                        FmiError::rejected(format!("{} is not available: {e}", v.name))
                    })?
                }
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
}
