//! Derivatives: `fmi2SetRealInputDerivatives` (what each derivative means is the model's),
//! and the two derivative functions this FMU does not provide.

use super::Instance;
use crate::cosimulation::CoSimulationModel;
use crate::fmi::state_machine::{Call, MachineState};
use crate::fmi::status::{FmiError, FmiResult, Status};
use crate::fmi::variables::{Family, ValueReference};

impl<M: CoSimulationModel + ?Sized> Instance<M> {
    /// `fmi2SetRealInputDerivatives`: derivatives of inputs at this communication point (the
    /// rod's model: the crank acceleration and jerk of the law that starts there). Unknown value
    /// references, variables that are not Real, and the model's refusals are errors, and
    /// then nothing is set; the model's warnings are logged.
    pub fn set_real_input_derivatives(
        &mut self,
        vrs: &[ValueReference],
        orders: &[i32],
        values: &[f64],
    ) -> FmiResult<Status> {
        for ((&vr, &order), &x) in vrs.iter().zip(orders).zip(values) {
            self.variable(vr, Family::Real)?;
            self.model
                .check_input_derivative(vr, order, x)
                .map_err(FmiError::rejected)?;
        }
        let items: Vec<(ValueReference, i32, f64)> = vrs
            .iter()
            .zip(orders)
            .zip(values)
            .map(|((&vr, &order), &x)| (vr, order, x))
            .collect();
        let warnings = self
            .model
            .set_input_derivatives(&items)
            .map_err(FmiError::rejected)?;
        let call = Call::SetRealInputDerivatives.name(self.standard);
        for w in &warnings {
            self.logger.status(Status::Warning, &format!("{call}: {w}"));
        }
        if self.state != MachineState::StepComplete {
            self.model.invalidate(false);
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
}
