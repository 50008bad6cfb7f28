//! Derivatives: `fmi2SetRealInputDerivatives` (the crank acceleration of the input law, see
//! [`crate::fmi::inputs`]), and the two derivative functions this FMU does not provide.

use super::Instance;
use crate::fmi::inputs::AccelerationSource;
use crate::fmi::state_machine::MachineState;
use crate::fmi::status::{FmiError, FmiResult, Status};
use crate::fmi::variables::{Access, Family, InputSlot, ValueReference};

impl Instance {
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
                    AccelerationSource::None
                    | AccelerationSource::Angle
                    | AccelerationSource::Input => {
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
                        InputSlot::CrankSpeed
                        | InputSlot::CrankAngle
                        | InputSlot::CrankAcceleration => {
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
}
