//! The inputs and their law between communication points (`docs/fmu.md`, "Input law between
//! communication points"):
//! `theta(t_k + s) = theta_k + omega_k s + alpha_k s^2 / 2 + j_k s^3 / 6`,
//! `omega(t_k + s) = omega_k + alpha_k s + j_k s^2 / 2`.
//!
//! At every communication step from `t_k` to `t_k + h` a new law starts at `t_k`:
//! - `theta_k`, `omega_k`: the values set by the importer at `t_k`; for an input not set at
//!   `t_k`, the value the previous law has at `t_k` (so a model left without inputs continues
//!   the motion it was started with);
//! - `alpha_k`: the crank acceleration set at `t_k` as an input derivative (order 1 of
//!   `crank.speed`, or order 2 of `crank.angle`), and 0 if none was set at `t_k`;
//! - `j_k`: the crank jerk set at `t_k` as an input derivative (order 2 of `crank.speed`, or
//!   order 3 of `crank.angle`), and 0 if none was set at `t_k`. With it a master that knows
//!   the crank's motion over the step sets `j_k = 2 (omega(t_k + h) - omega_k - alpha_k h) /
//!   h^2`: the speed reaches the motion's at `t_k + h`, and the acceleration steps at the
//!   points by `h^2 alpha'' / 6` only (docs/fmu.md, "Input law between communication points").
//!
//! An interface without input derivatives has the inputs `crank.acceleration` and `crank.jerk`
//! instead, which, like every input, hold their values until they are set again.
//!
//! After the step, `crank.angle` and `crank.speed` read the values the law had at `t_k + h`
//! (read back from the core's law, so they are exactly those the integrator used there).

use super::variables::{Access, InputSlot, Value, Variable, VariableTable};
use crate::simulation::{CrankInput, INPUT_WINDOWS, JERK_WINDOW};

impl InputSlot {
    /// The largest magnitude the input takes, in SI units ([`INPUT_WINDOWS`]).
    pub fn window(self) -> f64 {
        match self {
            InputSlot::CrankAngle => INPUT_WINDOWS[0],
            InputSlot::CrankSpeed => INPUT_WINDOWS[1],
            InputSlot::CrankAcceleration => INPUT_WINDOWS[2],
            InputSlot::SliderForce => INPUT_WINDOWS[3],
            InputSlot::CrankJerk => JERK_WINDOW,
        }
    }
}

/// Where the crank acceleration of the current communication point came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AccelerationSource {
    /// Not set at this point: `alpha_k` = 0.
    None,
    /// Order 1 of `crank.speed` (takes precedence).
    Speed,
    /// Order 2 of `crank.angle`.
    Angle,
    /// The input `crank.acceleration`. An input keeps its value until it is set again, so
    /// unlike an input derivative it carries over to the next communication points.
    Input,
}

impl AccelerationSource {
    /// Stable code for serialized states.
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
    /// Crank jerk set at this communication point (meaningful unless `jerk_source` is `None`):
    /// an input derivative, or the input `crank.jerk`, which keeps its value.
    pub jerk: f64,
    pub jerk_source: AccelerationSource,
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
            jerk: 0.0,
            jerk_source: AccelerationSource::None,
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
            InputSlot::CrankJerk => match self.jerk_source {
                AccelerationSource::Input => self.jerk,
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
            InputSlot::CrankJerk => {
                self.jerk = x;
                self.jerk_source = AccelerationSource::Input;
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
            jerk: if self.jerk_source == AccelerationSource::None {
                0.0
            } else {
                self.jerk
            },
        }
    }

    /// After a step: the current values are the law's values at the new time; nothing is set
    /// at the new communication point yet (an input derivative does not carry over; the input
    /// `crank.acceleration` keeps its value, as every input does).
    pub fn after_step(&mut self, angle: f64, speed: f64) {
        self.angle = angle;
        self.speed = speed;
        if self.source != AccelerationSource::Input {
            self.acceleration = 0.0;
            self.source = AccelerationSource::None;
        }
        if self.jerk_source != AccelerationSource::Input {
            self.jerk = 0.0;
            self.jerk_source = AccelerationSource::None;
        }
        self.force_changed = false;
    }
}

impl Inputs {
    /// Number of bytes of [`Inputs::to_bytes`].
    pub const BYTES: usize = 43;

    /// The byte form (little endian): angle, speed, slider force, acceleration, jerk f64,
    /// acceleration source u8 (0 none, 1 crank.speed, 2 crank.angle, 3 the input
    /// crank.acceleration), jerk source u8 (0 none, 1 crank.speed, 2 crank.angle, 3 the input
    /// crank.jerk), force changed u8.
    pub fn to_bytes(&self) -> [u8; Inputs::BYTES] {
        let mut out = [0u8; Inputs::BYTES];
        for (k, x) in [
            self.angle,
            self.speed,
            self.slider_force,
            self.acceleration,
            self.jerk,
        ]
        .into_iter()
        .enumerate()
        {
            out[8 * k..8 * k + 8].copy_from_slice(&x.to_le_bytes());
        }
        out[40] = self.source.code();
        out[41] = self.jerk_source.code();
        out[42] = u8::from(self.force_changed);
        out
    }

    /// Read [`Inputs::to_bytes`]; the error names the offending value.
    pub fn from_bytes(bytes: &[u8; Inputs::BYTES]) -> Result<Inputs, String> {
        let f = |k: usize| {
            let mut b = [0u8; 8];
            b.copy_from_slice(&bytes[8 * k..8 * k + 8]);
            f64::from_le_bytes(b)
        };
        let source = AccelerationSource::from_code(bytes[40])
            .ok_or_else(|| format!("acceleration source code {} is unknown", bytes[40]))?;
        let jerk_source = AccelerationSource::from_code(bytes[41])
            .ok_or_else(|| format!("jerk source code {} is unknown", bytes[41]))?;
        let force_changed = match bytes[42] {
            0 => false,
            1 => true,
            b => return Err(format!("the slider force flag is {b}, allowed 0 or 1")),
        };
        let inputs = Inputs {
            angle: f(0),
            speed: f(1),
            slider_force: f(2),
            acceleration: f(3),
            source,
            jerk: f(4),
            jerk_source,
            force_changed,
        };
        // The windows of the set calls ([`InputSlot::window`]): a state holds no input a
        // set call would refuse.
        for (name, x, bound) in [
            ("crank.angle", inputs.angle, InputSlot::CrankAngle.window()),
            ("crank.speed", inputs.speed, InputSlot::CrankSpeed.window()),
            (
                "slider.force",
                inputs.slider_force,
                InputSlot::SliderForce.window(),
            ),
            (
                "the crank acceleration",
                inputs.acceleration,
                InputSlot::CrankAcceleration.window(),
            ),
            ("the crank jerk", inputs.jerk, JERK_WINDOW),
        ] {
            if !x.is_finite() {
                return Err(format!(
                    "{name} is {x}, allowed a finite value with |value| <= {bound:e}"
                ));
            }
            if x.abs() > bound {
                return Err(format!(
                    "{name} is {x:e}, allowed |value| <= {bound:e} in SI units (the input window of its set call)"
                ));
            }
        }
        Ok(inputs)
    }

    /// Check one input derivative before anything is set ([`Inputs::set_derivatives`]).
    pub fn check_derivative(v: &Variable, order: i32, x: f64) -> Result<(), String> {
        if !matches!(v.access, Access::Input(_)) {
            return Err(format!(
                "{} (value reference {}) has causality {}: input derivatives can be set only for inputs (crank.speed, crank.angle); nothing was set",
                v.name,
                v.value_reference,
                v.causality.as_str()
            ));
        }
        if order <= 0 {
            return Err(format!(
                "derivative order {order} of {} is out of range: allowed an order >= 1 (order 1 of crank.speed or order 2 of crank.angle is the crank acceleration); nothing was set",
                v.name
            ));
        }
        if !x.is_finite() {
            return Err(format!(
                "order-{order} derivative of {} = {x} is out of range: allowed a finite value; nothing was set",
                v.name
            ));
        }
        Ok(())
    }

    /// Set input derivatives at this communication point: `(variable, order, value)`. The
    /// crank acceleration alpha_k and jerk j_k of the law that starts here:
    ///
    /// - Order 1 of `crank.speed` and order 2 of `crank.angle` are alpha_k, order 2 of
    ///   `crank.speed` and order 3 of `crank.angle` are j_k. If both are given at the same
    ///   point and differ, `crank.speed`'s is used, with a warning.
    /// - Order 1 of `crank.angle` is accepted and not used (the angle follows from
    ///   `crank.speed`); a value different from `crank.speed` gives a warning.
    /// - A derivative the law already has (0 for `slider.force`, which is held over a step,
    ///   for order >= 3 of `crank.speed` and order >= 4 of `crank.angle`) is accepted
    ///   silently; any other value of these cannot be used: it is ignored with a warning.
    /// - Order <= 0, variables that are not inputs and non-finite values are errors, and then
    ///   nothing is set.
    ///
    /// Returns the warnings.
    pub fn set_derivatives(
        &mut self,
        items: &[(&Variable, i32, f64)],
    ) -> Result<Vec<String>, String> {
        for &(v, order, x) in items {
            Inputs::check_derivative(v, order, x)?;
        }
        let mut warnings = Vec::new();
        for &(v, order, x) in items {
            let Access::Input(slot) = v.access else {
                continue;
            };
            match (slot, order) {
                (InputSlot::CrankSpeed, 1) | (InputSlot::CrankAngle, 2) => LawTerm::ACCELERATION
                    .set(
                        &mut self.acceleration,
                        &mut self.source,
                        slot == InputSlot::CrankSpeed,
                        x,
                        &mut warnings,
                    ),
                (InputSlot::CrankSpeed, 2) | (InputSlot::CrankAngle, 3) => LawTerm::JERK.set(
                    &mut self.jerk,
                    &mut self.jerk_source,
                    slot == InputSlot::CrankSpeed,
                    x,
                    &mut warnings,
                ),
                (InputSlot::CrankAngle, 1) => {
                    let speed = self.speed;
                    if (x - speed).abs() > 1e-9 * speed.abs().max(1.0) {
                        warnings.push(format!(
                            "order-1 derivative of crank.angle = {x} rad/s differs from crank.speed = {speed} rad/s; it is not used (the angle follows from crank.speed)"
                        ));
                    }
                }
                (_, _) if x == 0.0 => {}
                (slot, order) => {
                    let why = match slot {
                        InputSlot::SliderForce => "slider.force is held constant over a step",
                        InputSlot::CrankSpeed
                        | InputSlot::CrankAngle
                        | InputSlot::CrankAcceleration
                        | InputSlot::CrankJerk => {
                            "the crank law has a constant jerk over a step (acceleration: order 1 of crank.speed or order 2 of crank.angle; jerk: order 2 of crank.speed or order 3 of crank.angle)"
                        }
                    };
                    warnings.push(format!(
                        "order-{order} derivative of {} = {x} cannot be used and is ignored: {why}",
                        v.name
                    ));
                }
            }
        }
        Ok(warnings)
    }
}

/// A term of the crank law set by an input derivative: the acceleration (order `order` = 1 of
/// `crank.speed`, 2 of `crank.angle`) or the jerk (2 of `crank.speed`, 3 of `crank.angle`).
struct LawTerm {
    name: &'static str,
    order: i32,
    unit: &'static str,
}

impl LawTerm {
    const ACCELERATION: LawTerm = LawTerm {
        name: "crank acceleration",
        order: 1,
        unit: "rad/s^2",
    };
    const JERK: LawTerm = LawTerm {
        name: "crank jerk",
        order: 2,
        unit: "rad/s^3",
    };

    /// Set the term to `x` from `crank.speed` (`by_speed`) or `crank.angle`. Given by both at
    /// the same point with different values, `crank.speed`'s is used, with a warning.
    fn set(
        &self,
        value: &mut f64,
        source: &mut AccelerationSource,
        by_speed: bool,
        x: f64,
        warnings: &mut Vec<String>,
    ) {
        let (name, unit) = (self.name, self.unit);
        let (speed_order, angle_order) = (self.order, self.order + 1);
        if by_speed {
            if *source == AccelerationSource::Angle && *value != x {
                warnings.push(format!(
                    "the {name} is given twice at this point: order {angle_order} of crank.angle = {} {unit} and order {speed_order} of crank.speed = {x} {unit}; crank.speed's is used",
                    *value
                ));
            }
            *value = x;
            *source = AccelerationSource::Speed;
        } else if *source == AccelerationSource::Speed {
            if *value != x {
                warnings.push(format!(
                    "the {name} is given twice at this point: order {speed_order} of crank.speed = {} {unit} and order {angle_order} of crank.angle = {x} {unit}; crank.speed's is used",
                    *value
                ));
            }
        } else {
            *value = x;
            *source = AccelerationSource::Angle;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    fn variable<'a>(table: &'a VariableTable, name: &str) -> &'a Variable {
        table
            .variables()
            .iter()
            .find(|v| v.name == name)
            .expect("a variable of the default scene")
    }

    /// Order 2 of crank.speed and order 3 of crank.angle set the jerk of the law that starts
    /// here; given by both with different values, crank.speed's is used with a warning; it
    /// does not carry over to the next communication point; it survives the byte form.
    #[test]
    fn jerk_from_input_derivatives() {
        let table = VariableTable::new(&Scene::benchmark(), 0);
        let (speed, angle) = (
            variable(&table, "crank.speed"),
            variable(&table, "crank.angle"),
        );
        let mut inputs = Inputs::from_start_values(&table);
        assert_eq!(inputs.set_derivatives(&[(speed, 2, 3e5)]), Ok(vec![]));
        assert_eq!(inputs.crank_input().jerk, 3e5);
        assert_eq!(Inputs::from_bytes(&inputs.to_bytes()), Ok(inputs));
        let warnings = inputs.set_derivatives(&[(angle, 3, -1e5)]).unwrap();
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        assert!(
            warnings[0].contains("crank jerk is given twice"),
            "{warnings:?}"
        );
        assert_eq!(inputs.crank_input().jerk, 3e5);
        inputs.after_step(1.0, 150.0);
        assert_eq!(inputs.crank_input().jerk, 0.0);
        assert_eq!(inputs.set_derivatives(&[(angle, 3, -1e5)]), Ok(vec![]));
        assert_eq!(inputs.crank_input().jerk, -1e5);
        // Order 3 of crank.speed is beyond the law: ignored with a warning.
        let warnings = inputs.set_derivatives(&[(speed, 3, 7.0)]).unwrap();
        assert!(warnings[0].contains("cannot be used"), "{warnings:?}");
        // The input crank.jerk (interfaces without input derivatives) holds across steps.
        let mut held = inputs;
        held.set(InputSlot::CrankJerk, 5e4);
        held.after_step(2.0, 150.0);
        assert_eq!(held.crank_input().jerk, 5e4);
        assert_eq!(held.value(InputSlot::CrankJerk), 5e4);
        assert_eq!(Inputs::from_bytes(&held.to_bytes()), Ok(held));
        let mut bad = inputs.to_bytes();
        bad[41] = 4;
        assert!(Inputs::from_bytes(&bad)
            .unwrap_err()
            .contains("jerk source code 4"));
        let mut bad = inputs.to_bytes();
        bad[32..40].copy_from_slice(&2e12f64.to_le_bytes());
        assert!(Inputs::from_bytes(&bad)
            .unwrap_err()
            .contains("the crank jerk"));
    }

    #[test]
    fn byte_form_round_trips() {
        let table = VariableTable::new(&Scene::benchmark(), 0);
        let mut inputs = Inputs::from_start_values(&table);
        inputs.set(InputSlot::SliderForce, -3.5);
        inputs.set(InputSlot::CrankAcceleration, 12.0);
        assert_eq!(Inputs::from_bytes(&inputs.to_bytes()), Ok(inputs));
        let mut bad = inputs.to_bytes();
        bad[40] = 9;
        assert!(Inputs::from_bytes(&bad)
            .unwrap_err()
            .contains("source code 9"));
        let mut bad = inputs.to_bytes();
        bad[0..8].copy_from_slice(&f64::NAN.to_le_bytes());
        assert!(Inputs::from_bytes(&bad)
            .unwrap_err()
            .contains("crank.angle"));
    }
}
