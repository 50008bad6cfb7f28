//! Inputs between communication points follow the contract's law
//! `theta(t_k + s) = theta_k + omega_k s + alpha_k s^2 / 2`, `omega(t_k + s) = omega_k + alpha_k s`:
//! when the importer sets `crank.angle`, `crank.speed` or the crank acceleration (order-1
//! derivative of `crank.speed`) at `t_k`, a new law starts at `t_k` with `alpha_k` = the
//! derivative set at `t_k`, or 0. When it sets none of them, the current law continues, and
//! `fmi2GetReal` of the inputs reports the law's values at the current time.

use super::variables::{Access, InputSlot, Value, VariableTable};
use crate::simulation::CrankInput;

/// The inputs as the instance keeps them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inputs {
    /// Current values (set by the importer, or the law evaluated at the current time).
    pub angle: f64,
    pub speed: f64,
    pub slider_force: f64,
    /// Order-1 derivative of `crank.speed` set at this communication point.
    pub acceleration: f64,
    pub acceleration_set: bool,
    /// A crank value or derivative was set since the last step: a new law starts.
    pub crank_changed: bool,
    /// `slider.force` was set since the last step.
    pub force_changed: bool,
    /// The law in use and the time it started.
    pub law: CrankInput,
    pub law_time: f64,
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
        let (angle, speed) = (start(InputSlot::CrankAngle), start(InputSlot::CrankSpeed));
        Inputs {
            angle,
            speed,
            slider_force: start(InputSlot::SliderForce),
            acceleration: 0.0,
            acceleration_set: false,
            crank_changed: false,
            force_changed: false,
            law: CrankInput {
                angle,
                speed,
                acceleration: 0.0,
            },
            law_time: 0.0,
        }
    }

    pub fn value(&self, slot: InputSlot) -> f64 {
        match slot {
            InputSlot::CrankAngle => self.angle,
            InputSlot::CrankSpeed => self.speed,
            InputSlot::SliderForce => self.slider_force,
        }
    }

    pub fn set(&mut self, slot: InputSlot, x: f64) {
        match slot {
            InputSlot::CrankAngle => self.angle = x,
            InputSlot::CrankSpeed => self.speed = x,
            InputSlot::SliderForce => self.slider_force = x,
        }
        match slot {
            InputSlot::CrankAngle | InputSlot::CrankSpeed => self.crank_changed = true,
            InputSlot::SliderForce => self.force_changed = true,
        }
    }

    /// The crank input at the current communication point.
    pub fn crank_input(&self) -> CrankInput {
        CrankInput {
            angle: self.angle,
            speed: self.speed,
            acceleration: if self.acceleration_set {
                self.acceleration
            } else {
                0.0
            },
        }
    }

    /// Start a new law at `time` from the current values; clear the change flags.
    pub fn start_law(&mut self, time: f64) {
        self.law = self.crank_input();
        self.law_time = time;
        self.clear_point();
    }

    /// After a step to `time`: the current values are the law's values there.
    pub fn follow_law(&mut self, time: f64) {
        let s = time - self.law_time;
        let law = self.law;
        self.angle = law.angle + law.speed * s + 0.5 * law.acceleration * s * s;
        self.speed = law.speed + law.acceleration * s;
        self.clear_point();
    }

    fn clear_point(&mut self) {
        self.acceleration = 0.0;
        self.acceleration_set = false;
        self.crank_changed = false;
        self.force_changed = false;
    }
}

/// `fmi2SetupExperiment` values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Experiment {
    pub start_time: f64,
    pub stop_time: Option<f64>,
}
