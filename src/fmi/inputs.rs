//! The inputs and their law between communication points (`docs/fmu.md`, "Input law between communication points"):
//! `theta(t_k + s) = theta_k + omega_k s + alpha_k s^2 / 2`, `omega(t_k + s) = omega_k + alpha_k s`.
//!
//! At every `fmi2DoStep(t_k, h)` a new law starts at `t_k`:
//! - `theta_k`, `omega_k`: the values set by the importer at `t_k`; for an input not set at
//!   `t_k`, the value the previous law has at `t_k` (so an FMU left without inputs continues the
//!   motion it was started with);
//! - `alpha_k`: the crank acceleration set at `t_k` with `fmi2SetRealInputDerivatives` (order 1
//!   of `crank.speed`, or order 2 of `crank.angle`), and 0 if none was set at `t_k`.
//!
//! FMI 3.0 has no input derivatives: there `alpha_k` is the input `crank.acceleration`, which,
//! like every input, holds its value until it is set again.
//!
//! After the step, `fmi2GetReal` of `crank.angle` and `crank.speed` returns the values the law
//! had at `t_k + h` (read back from the core's law, so they are exactly those the integrator
//! used there).

use super::variables::{Access, InputSlot, Value, VariableTable};
use crate::simulation::CrankInput;

/// Where the crank acceleration of the current communication point came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AccelerationSource {
    /// Not set at this point: `alpha_k` = 0.
    None,
    /// Order 1 of `crank.speed` (takes precedence).
    Speed,
    /// Order 2 of `crank.angle`.
    Angle,
    /// FMI 3.0: the input `crank.acceleration`. An input keeps its value until it is set
    /// again, so unlike an FMI 2.0 input derivative it carries over to the next
    /// communication points.
    Input,
}

impl AccelerationSource {
    /// Stable code for serialized FMU states.
    pub fn code(self) -> u8 {
        match self {
            AccelerationSource::None => 0,
            AccelerationSource::Speed => 1,
            AccelerationSource::Angle => 2,
            AccelerationSource::Input => 3,
        }
    }

    /// Decode [`AccelerationSource::code`].
    pub fn from_code(code: u8) -> Option<AccelerationSource> {
        [
            AccelerationSource::None,
            AccelerationSource::Speed,
            AccelerationSource::Angle,
            AccelerationSource::Input,
        ]
        .into_iter()
        .find(|s| s.code() == code)
    }
}

/// The inputs as the instance keeps them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inputs {
    /// Current values: set by the importer, or the law's values at the current time.
    pub angle: f64,
    pub speed: f64,
    pub slider_force: f64,
    /// Crank acceleration set at this communication point (meaningful unless `source` is
    /// `None`).
    pub acceleration: f64,
    pub source: AccelerationSource,
    /// `slider.force` was set since the last step.
    pub force_changed: bool,
}

impl Inputs {
    pub fn from_start_values(table: &VariableTable) -> Inputs {
        let start = |slot: InputSlot| {
            table
                .variables()
                .iter()
                .find_map(|v| match (v.access, v.start) {
                    (Access::Input(s), Some(Value::Real(x))) if s == slot => Some(x),
                    _ => None,
                })
                .unwrap_or(0.0)
        };
        Inputs {
            angle: start(InputSlot::CrankAngle),
            speed: start(InputSlot::CrankSpeed),
            slider_force: start(InputSlot::SliderForce),
            acceleration: 0.0,
            source: AccelerationSource::None,
            force_changed: false,
        }
    }

    pub fn value(&self, slot: InputSlot) -> f64 {
        match slot {
            InputSlot::CrankAngle => self.angle,
            InputSlot::CrankSpeed => self.speed,
            InputSlot::SliderForce => self.slider_force,
            InputSlot::CrankAcceleration => match self.source {
                AccelerationSource::Input => self.acceleration,
                _ => 0.0,
            },
        }
    }

    pub fn set(&mut self, slot: InputSlot, x: f64) {
        match slot {
            InputSlot::CrankAngle => self.angle = x,
            InputSlot::CrankSpeed => self.speed = x,
            InputSlot::SliderForce => {
                self.slider_force = x;
                self.force_changed = true;
            }
            InputSlot::CrankAcceleration => {
                self.acceleration = x;
                self.source = AccelerationSource::Input;
            }
        }
    }

    /// The acceleration set at this point, if any.
    pub fn acceleration_set(&self) -> Option<f64> {
        (self.source != AccelerationSource::None).then_some(self.acceleration)
    }

    /// The law that starts at the current communication point.
    pub fn crank_input(&self) -> CrankInput {
        CrankInput {
            angle: self.angle,
            speed: self.speed,
            acceleration: self.acceleration_set().unwrap_or(0.0),
        }
    }

    /// After a step: the current values are the law's values at the new time; nothing is set
    /// at the new communication point yet (an FMI 2.0 input derivative does not carry over;
    /// the FMI 3.0 input `crank.acceleration` keeps its value, as every input does).
    pub fn after_step(&mut self, angle: f64, speed: f64) {
        self.angle = angle;
        self.speed = speed;
        if self.source != AccelerationSource::Input {
            self.acceleration = 0.0;
            self.source = AccelerationSource::None;
        }
        self.force_changed = false;
    }
}

/// `fmi2SetupExperiment` values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Experiment {
    pub start_time: f64,
    pub stop_time: Option<f64>,
}
