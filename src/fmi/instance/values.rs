//! `fmi2Get*`/`fmi2Set*` and `fmi3Get*`/`fmi3Set*`: dispatch through the variable table,
//! checks before any change (a rejected call sets nothing), and the model rebuilt on demand
//! in initialization mode. FMI 3.0 arrays take `value_count` consecutive values (the FMI 2.0
//! table has only scalars, so there one value reference is one value).

use super::Instance;
use crate::cosimulation::{CoSimulationModel, Declaration};
use crate::fmi::state_machine::{Call, MachineState};
use crate::fmi::status::{FmiError, FmiResult, Status};
use crate::fmi::variables::{Causality, Family, ValueReference};

impl<M: CoSimulationModel + ?Sized> Instance<M> {
    pub(super) fn variable(&self, vr: ValueReference, family: Family) -> FmiResult<&Declaration> {
        let standard = self.standard;
        let v = self.table().get(vr).ok_or_else(|| {
            FmiError::rejected(format!(
                "unknown value reference {vr}: no {} variable of this FMU has it (see modelDescription.xml)",
                family.name(standard)
            ))
        })?;
        let actual = Family::of(v.value_type, standard);
        if actual != family {
            return Err(FmiError::rejected(format!(
                "value reference {vr} ({}) is a {} variable, not {}: use {p}Get{}/{p}Set{}",
                v.name,
                actual.name(standard),
                family.name(standard),
                actual.name(standard),
                actual.name(standard),
                p = standard.prefix(),
            )));
        }
        Ok(v)
    }

    fn settable(&self, vr: ValueReference, family: Family) -> FmiResult<&Declaration> {
        let v = self.variable(vr, family)?;
        match v.causality {
            Causality::Input => Ok(v),
            Causality::Parameter => match self.state {
                MachineState::Instantiated | MachineState::InitializationMode => Ok(v),
                state => Err(FmiError::rejected(format!(
                    "{} (value reference {vr}) is a fixed parameter: it can be set only before {}, and the instance is in state {}",
                    v.name,
                    Call::ExitInitializationMode.name(self.standard),
                    state.name()
                ))),
            },
            Causality::Output | Causality::CalculatedParameter | Causality::Independent => {
                Err(FmiError::rejected(format!(
                    "{} (value reference {vr}) has causality {}: only inputs and parameters can be set",
                    v.name,
                    v.causality.as_str()
                )))
            }
        }
    }

    /// Make the simulation that provides outputs and frequencies available (built on
    /// demand in initialization mode).
    fn prepare_values(&mut self) -> FmiResult<()> {
        if self.state == MachineState::InitializationMode {
            self.ensure_started()?;
        }
        if self.model.is_built() {
            return Ok(());
        }
        Err(FmiError::rejected(format!(
            "outputs and calculated parameters are not available: {}",
            self.failure
                .as_deref()
                .unwrap_or("the model was not initialized")
        )))
    }

    /// The number of values `vrs` take: `n_values` must match it (FMI 3.0 `nValues`).
    fn check_value_count(&self, vrs: &[ValueReference], n_values: usize) -> FmiResult<()> {
        // Unknown references count one value here; they are reported by the checks after.
        let expected: usize = vrs
            .iter()
            .map(|&vr| self.table().get(vr).map_or(1, |v| v.value_count()))
            .sum();
        if expected != n_values {
            return Err(FmiError::rejected(format!(
                "nValues = {n_values} does not match the {} value references, which take {expected} values (arrays count their elements): allowed nValues = {expected}",
                vrs.len()
            )));
        }
        Ok(())
    }

    /// `fmi2GetReal` / `fmi3GetFloat64`: `values` holds the values of `vrs` one after the
    /// other, an array's elements in order.
    pub fn get_real(&mut self, vrs: &[ValueReference], values: &mut [f64]) -> FmiResult<Status> {
        self.check_value_count(vrs, values.len())?;
        let mut needs_simulation = false;
        for &vr in vrs {
            needs_simulation |= self.variable(vr, Family::Real)?.computed;
        }
        if needs_simulation {
            self.prepare_values()?;
        }
        let mut next = 0;
        for &vr in vrs {
            let n = self.table().get(vr).expect("checked above").value_count();
            let out = &mut values[next..next + n];
            next += n;
            self.model
                .get_real(vr, out, self.experiment.start_time)
                .map_err(FmiError::rejected)?;
        }
        Ok(Status::Ok)
    }

    /// `fmi2GetInteger` (Integer and Enumeration variables); FMI 3.0: `fmi3GetInt32`
    /// (`family` Integer) and `fmi3GetInt64` (`family` Enumeration).
    pub fn get_integer<T: From<i32>>(
        &mut self,
        family: Family,
        vrs: &[ValueReference],
        values: &mut [T],
    ) -> FmiResult<Status> {
        self.check_value_count(vrs, values.len())?;
        for (&vr, out) in vrs.iter().zip(values.iter_mut()) {
            self.variable(vr, family)?;
            *out = T::from(self.model.get_integer(vr).map_err(FmiError::rejected)?);
        }
        Ok(Status::Ok)
    }

    /// `fmi2SetReal` / `fmi3SetFloat64`: all values are checked first; on error nothing is set.
    pub fn set_real(&mut self, vrs: &[ValueReference], values: &[f64]) -> FmiResult<Status> {
        self.check_value_count(vrs, values.len())?;
        for (&vr, &x) in vrs.iter().zip(values) {
            let v = self.settable(vr, Family::Real)?;
            if !x.is_finite() {
                return Err(FmiError::rejected(format!(
                    "{} = {x} (value reference {vr}) is out of range: allowed a finite value; nothing was set",
                    v.name
                )));
            }
            if let Err(allowed) = self.model.check_real(vr, x) {
                return Err(FmiError::rejected(format!(
                    "{} = {x:e} (value reference {vr}) is out of range: allowed {allowed}; nothing was set",
                    v.name
                )));
            }
        }
        let mut parameter_changed = false;
        for (&vr, &x) in vrs.iter().zip(values) {
            parameter_changed |= self.model.set_real(vr, x).map_err(FmiError::rejected)?;
        }
        if self.state != MachineState::StepComplete {
            self.model.invalidate(parameter_changed);
        }
        Ok(Status::Ok)
    }

    /// `fmi2SetInteger`; FMI 3.0: `fmi3SetInt32` (`family` Integer) and `fmi3SetInt64`
    /// (`family` Enumeration). All values are checked first; on error nothing is set.
    pub fn set_integer<T: Copy + TryInto<i32> + std::fmt::Display>(
        &mut self,
        family: Family,
        vrs: &[ValueReference],
        values: &[T],
    ) -> FmiResult<Status> {
        self.check_value_count(vrs, values.len())?;
        let mut checked = Vec::with_capacity(vrs.len());
        for (&vr, &value) in vrs.iter().zip(values) {
            let v = self.settable(vr, family)?;
            let n: i32 = value.try_into().map_err(|_| {
                out_of_range(
                    v,
                    vr,
                    value,
                    "a value in the 32-bit integer range".to_string(),
                )
            })?;
            checked.push(n);
        }
        let items: Vec<(ValueReference, i32)> = vrs.iter().copied().zip(checked).collect();
        if let Err((k, allowed)) = self.model.set_integers(&items) {
            let v = self.table().get(vrs[k]).expect("checked above");
            return Err(out_of_range(v, vrs[k], values[k], allowed));
        }
        Ok(Status::Ok)
    }

    /// `fmi2GetBoolean`, `fmi2SetBoolean`, `fmi2GetString`, `fmi2SetString` and the FMI 3.0
    /// get/set functions of the other types: this FMU has no such variables, so any value
    /// reference is unknown (or of another type).
    pub fn no_variables_of(&self, family: Family, vrs: &[ValueReference]) -> FmiResult<Status> {
        match vrs.first() {
            None => Ok(Status::Ok),
            Some(&vr) => self.variable(vr, family).map(|_| Status::Ok),
        }
    }
}

/// A value refused by a set call, with the allowed values.
fn out_of_range(
    v: &Declaration,
    vr: ValueReference,
    value: impl std::fmt::Display,
    allowed: String,
) -> FmiError {
    FmiError::rejected(format!(
        "{} = {value} (value reference {vr}) is out of range: allowed {allowed}; nothing was set",
        v.name
    ))
}
