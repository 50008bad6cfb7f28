//! The mechanism's state: everything a snapshot must hold to replay bit for bit.

use super::crank::CrankInput;
use super::outputs::Outputs;
use crate::integrator::{DaeState, StepAhead};
use crate::text::time;

/// Counters of the integrator, cumulative since the start.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct StepStats {
    /// Internal steps taken (accepted).
    pub steps: u64,
    /// Newton iterations over all accepted and rejected steps (generalized-alpha), or matrix
    /// factorizations (explicit RK4).
    pub newton_iterations: u64,
    /// Steps that failed and were retried with half the step.
    pub halvings: u64,
}

/// Dynamic state of the slider-crank plus its inputs and cached outputs.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct MechanismState {
    /// Current time, s (equals `dae.t`).
    pub time: f64,
    /// Integrator state: coordinates `[rod..., x_slider]`, multipliers `[B_x, B_y, C_x, C_y]`.
    pub dae: DaeState,
    /// Crank input and the time it was set at.
    pub input: CrankInput,
    pub input_time: f64,
    /// The crank input and its time before the last `set_input` (an adaptive integrator
    /// restarts where the new input leaves the previous law).
    pub previous_input: CrankInput,
    pub previous_input_time: f64,
    /// External slider force, N.
    pub slider_force: f64,
    /// Outputs at `time`.
    pub outputs: Outputs,
    pub stats: StepStats,
    /// Warnings not yet collected (not serialized).
    pub warnings: Vec<String>,
    /// The large-deflection warning was already given.
    pub large_deflection_warned: bool,
    /// The amplitude of `v_mid / L` of the free vibration the start rang (an undeformed start
    /// at speed; 0 otherwise): `Mechanism::start_vibration`, for the error estimate.
    pub start_vibration: f64,
    /// An internal step past `time` whose interpolant gave the state at `time` (dense output
    /// where stepping past the communication point is cheaper than landing on it; nothing held
    /// otherwise).
    pub ahead: StepAhead,
}

impl MechanismState {
    /// Append the state as little-endian numbers.
    pub fn write_bytes(&self, out: &mut Vec<u8>) {
        let mut put = |x: f64| out.extend_from_slice(&x.to_le_bytes());
        put(self.time);
        put(self.input_time);
        put(self.previous_input_time);
        put(self.previous_input.angle);
        put(self.previous_input.speed);
        put(self.previous_input.acceleration);
        put(self.previous_input.jerk);
        put(self.input.angle);
        put(self.input.speed);
        put(self.input.acceleration);
        put(self.input.jerk);
        put(self.slider_force);
        let o = &self.outputs;
        for x in [
            o.deflection,
            o.deflection_rel,
            o.pin_b_force[0],
            o.pin_b_force[1],
            o.pin_c_force[0],
            o.pin_c_force[1],
            o.crank_torque,
            o.slider_position,
            o.slider_velocity,
        ] {
            put(x);
        }
        put(self.dae.t);
        put(self.dae.step_hint);
        put(self.dae.amplitude);
        put(self.start_vibration);
        for v in [
            &self.dae.q,
            &self.dae.v,
            &self.dae.qdd,
            &self.dae.acc,
            &self.dae.lambda,
        ] {
            for &x in v.iter() {
                put(x);
            }
        }
        let s = &self.outputs.section;
        for x in [
            s.axial_force_mid,
            s.bending_moment_mid,
            s.stress_max,
            s.stress_max_position,
        ] {
            put(x);
        }
        for c in [
            self.stats.steps,
            self.stats.newton_iterations,
            self.stats.halvings,
        ] {
            out.extend_from_slice(&c.to_le_bytes());
        }
        out.push(self.large_deflection_warned as u8);
        let a = &self.ahead;
        out.push(a.held as u8);
        if a.held {
            let mut put = |x: f64| out.extend_from_slice(&x.to_le_bytes());
            put(a.t0);
            put(a.end.t);
            put(a.end.step_hint);
            put(a.end.amplitude);
            for v in [
                &a.z0,
                &a.zd0,
                &a.zdd0,
                &a.nmid,
                &a.end.q,
                &a.end.v,
                &a.end.qdd,
                &a.end.acc,
                &a.end.lambda,
            ] {
                for &x in v.iter() {
                    put(x);
                }
            }
        }
    }

    /// Read what [`Self::write_bytes`] wrote, into a state of the same dimensions.
    pub fn read_bytes(&mut self, bytes: &[u8]) -> Result<(), String> {
        let n = self.dae.q.len();
        let m = self.dae.lambda.len();
        let base = 8 * (29 + 4 * n + m) + 8 * 3 + 1;
        let k = self.ahead.z0.len();
        let ahead_len = 8 * (4 + 4 * k + 4 * n + m);
        let held = match bytes.get(base) {
            Some(0) => false,
            Some(1) if k > 0 => true,
            Some(b) => {
                return Err(format!(
                    "the held-step flag is {b}, allowed 0{}",
                    if k > 0 {
                        " or 1"
                    } else {
                        " (this model has no dense output)"
                    }
                ))
            }
            None => {
                return Err(format!(
                "{} bytes of state, this model needs at least {} (truncated or from another model)",
                bytes.len(),
                base + 1
            ))
            }
        };
        let expected = base + 1 + if held { ahead_len } else { 0 };
        if bytes.len() != expected {
            return Err(format!(
                "{} bytes of state, this model needs {expected} (truncated or from another model)",
                bytes.len()
            ));
        }
        let mut at = 0usize;
        let mut get = || {
            let x = f64::from_le_bytes(bytes[at..at + 8].try_into().unwrap());
            at += 8;
            x
        };
        self.time = get();
        self.input_time = get();
        self.previous_input_time = get();
        self.previous_input.angle = get();
        self.previous_input.speed = get();
        self.previous_input.acceleration = get();
        self.previous_input.jerk = get();
        self.input.angle = get();
        self.input.speed = get();
        self.input.acceleration = get();
        self.input.jerk = get();
        self.slider_force = get();
        let o = &mut self.outputs;
        o.deflection = get();
        o.deflection_rel = get();
        o.pin_b_force = [get(), get()];
        o.pin_c_force = [get(), get()];
        o.crank_torque = get();
        o.slider_position = get();
        o.slider_velocity = get();
        self.dae.t = get();
        self.dae.step_hint = get();
        self.dae.amplitude = get();
        self.start_vibration = get();
        for v in [
            &mut self.dae.q,
            &mut self.dae.v,
            &mut self.dae.qdd,
            &mut self.dae.acc,
        ] {
            for x in v.iter_mut() {
                *x = get();
            }
        }
        for x in self.dae.lambda.iter_mut() {
            *x = get();
        }
        let s = &mut self.outputs.section;
        s.axial_force_mid = get();
        s.bending_moment_mid = get();
        s.stress_max = get();
        s.stress_max_position = get();
        let mut at = base - 25;
        let mut count = || {
            let c = u64::from_le_bytes(bytes[at..at + 8].try_into().unwrap());
            at += 8;
            c
        };
        self.stats.steps = count();
        self.stats.newton_iterations = count();
        self.stats.halvings = count();
        if !(self.start_vibration.is_finite() && self.start_vibration >= 0.0) {
            return Err(format!(
                "the start's vibration amplitude is {}, allowed a finite value >= 0",
                self.start_vibration
            ));
        }
        self.large_deflection_warned = match bytes[base - 1] {
            0 => false,
            1 => true,
            b => {
                return Err(format!(
                    "the deflection warning flag is {b}, allowed 0 or 1"
                ))
            }
        };
        self.ahead.held = held;
        if held {
            let mut at = base + 1;
            let mut get = || {
                let x = f64::from_le_bytes(bytes[at..at + 8].try_into().unwrap());
                at += 8;
                x
            };
            let a = &mut self.ahead;
            a.t0 = get();
            a.end.t = get();
            a.end.step_hint = get();
            a.end.amplitude = get();
            for v in [
                &mut a.z0,
                &mut a.zd0,
                &mut a.zdd0,
                &mut a.nmid,
                &mut a.end.q,
                &mut a.end.v,
                &mut a.end.qdd,
                &mut a.end.acc,
                &mut a.end.lambda,
            ] {
                for x in v.iter_mut() {
                    *x = get();
                }
            }
        }
        self.validate()?;
        self.warnings.clear();
        Ok(())
    }

    /// Every field of a state read from bytes in range (the checksum of the byte form is
    /// unkeyed, so crafted bytes must not get in): all numbers finite, the outputs in the range
    /// of an accepted step ([`super::Outputs::out_of_range`]), the times within the
    /// experiment's range, the step proposal and the amplitudes >= 0 and bounded like the
    /// outputs, `dae.t == time`, `input_time <= time`. The ranges of every field:
    /// the table in `src/fmi/fmu_state.rs`.
    pub fn validate(&self) -> Result<(), String> {
        let o = &self.outputs;
        let named = [
            ("the time", self.time),
            ("the input time", self.input_time),
            ("the previous input time", self.previous_input_time),
            ("the previous crank angle", self.previous_input.angle),
            ("the previous crank speed", self.previous_input.speed),
            (
                "the previous crank acceleration",
                self.previous_input.acceleration,
            ),
            ("crank.angle", self.input.angle),
            ("crank.speed", self.input.speed),
            ("the crank acceleration", self.input.acceleration),
            ("the previous crank jerk", self.previous_input.jerk),
            ("the crank jerk", self.input.jerk),
            ("slider.force", self.slider_force),
            ("the integrator time", self.dae.t),
            ("the step proposal", self.dae.step_hint),
            ("the deflection amplitude", self.dae.amplitude),
        ];
        for (name, x) in named {
            if !x.is_finite() {
                return Err(format!("{name} is {x}, allowed a finite value"));
            }
        }
        // The outputs in the range of an accepted step (the same check).
        if let Some((name, x)) = o.out_of_range() {
            return Err(format!(
                "output {name} is {x:e}, allowed finite with |value| < {:e} in SI units (the range of every accepted step)",
                super::MAX_OUTPUT_MAGNITUDE
            ));
        }
        // The times within the experiment's range (`[experiment]`, the FMI experiment).
        let limit = crate::limits::EXPERIMENT_TIME_LIMIT * (1.0 + 1e-9);
        for (name, t) in [
            ("the time", self.time),
            ("the input time", self.input_time),
            ("the previous input time", self.previous_input_time),
        ] {
            if t.abs() > limit {
                return Err(format!(
                    "{name} is {t:e} s, allowed within +-{:e} s (the experiment's range)",
                    crate::limits::EXPERIMENT_TIME_LIMIT
                ));
            }
        }
        // Amplitudes of v_mid/L and of the deflection: bounded like the outputs.
        for (name, x) in [
            ("the deflection amplitude", self.dae.amplitude),
            ("the start's vibration amplitude", self.start_vibration),
        ] {
            if x.abs() >= super::MAX_OUTPUT_MAGNITUDE {
                return Err(format!(
                    "{name} is {x:e}, allowed |value| < {:e}",
                    super::MAX_OUTPUT_MAGNITUDE
                ));
            }
        }
        let d = &self.dae;
        for (name, v) in [
            ("a coordinate", &d.q),
            ("a velocity", &d.v),
            ("an acceleration", &d.qdd),
            ("an integrator acceleration", &d.acc),
            ("a joint force", &d.lambda),
        ] {
            if let Some(x) = v.iter().find(|x| !x.is_finite()) {
                return Err(format!("{name} is {x}, allowed a finite value"));
            }
        }
        if d.step_hint < 0.0 || d.amplitude < 0.0 {
            return Err(format!(
                "the step proposal {:e} s or the amplitude {:e} is negative, allowed >= 0",
                d.step_hint, d.amplitude
            ));
        }
        if d.t != self.time {
            return Err(format!(
                "the integrator time {} s differs from the time {} s (they are equal in every saved state)",
                time(d.t),
                time(self.time)
            ));
        }
        let a = &self.ahead;
        if a.held {
            let values = [a.t0, a.end.t, a.end.step_hint, a.end.amplitude];
            if let Some(x) = values
                .iter()
                .chain(&a.z0)
                .chain(&a.zd0)
                .chain(&a.zdd0)
                .chain(&a.nmid)
                .chain(&a.end.q)
                .chain(&a.end.v)
                .chain(&a.end.qdd)
                .chain(&a.end.acc)
                .chain(&a.end.lambda)
                .find(|x| !x.is_finite())
            {
                return Err(format!(
                    "a value of the held internal step is {x}, allowed a finite value"
                ));
            }
            let longest = 1.25 * crate::integrator::MAX_ADAPTIVE_STEP;
            if !(a.end.t - a.t0 > 0.0 && a.end.t - a.t0 <= longest) {
                return Err(format!(
                    "the held internal step [{}, {}] s is not between 0 and {longest} s long",
                    time(a.t0),
                    time(a.end.t)
                ));
            }
            if !(a.t0 <= self.time && self.time < a.end.t) {
                return Err(format!(
                    "the held internal step [{}, {}] s does not contain the time {} s (it starts at or before it and ends after it)",
                    time(a.t0),
                    time(a.end.t),
                    time(self.time)
                ));
            }
            if a.end.step_hint < 0.0 || a.end.amplitude < 0.0 {
                return Err(format!(
                    "the held step's proposal {:e} s or amplitude {:e} is negative, allowed >= 0",
                    a.end.step_hint, a.end.amplitude
                ));
            }
        }
        if self.input_time > self.time {
            return Err(format!(
                "the input law starts at {} s, after the time {} s (allowed <= the time)",
                time(self.input_time),
                time(self.time)
            ));
        }
        Ok(())
    }
}
