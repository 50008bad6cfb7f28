//! The mechanism's state: everything a snapshot must hold to replay bit for bit.

use super::crank::CrankInput;
use super::outputs::Outputs;
use crate::bytes::{ByteReader, ByteWriter};
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
    /// The amplitude the error control's accuracy refers to: the largest `|v_mid / L|` so far
    /// (at communication points and after each accepted internal step; 0 at the start).
    pub amplitude: f64,
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
    /// Append the state as little-endian numbers (the layout: `docs/fmu.md`, "FMU states and
    /// serialization").
    pub fn write_bytes(&self, out: &mut Vec<u8>) {
        let mut w = ByteWriter::default();
        for x in self.scalars() {
            w.f64(x);
        }
        for v in [
            &self.dae.q,
            &self.dae.v,
            &self.dae.qdd,
            &self.dae.acc,
            &self.dae.lambda,
        ] {
            v.iter().for_each(|&x| w.f64(x));
        }
        let s = &self.outputs.section;
        for x in [
            s.axial_force_mid,
            s.bending_moment_mid,
            s.stress_max,
            s.stress_max_position,
        ] {
            w.f64(x);
        }
        let c = &self.stats;
        for n in [c.steps, c.newton_iterations, c.halvings] {
            w.u64(n);
        }
        w.flag(self.large_deflection_warned);
        let a = &self.ahead;
        w.flag(a.held);
        if a.held {
            for x in [a.t0, a.end.t, a.end.step_hint] {
                w.f64(x);
            }
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
                v.iter().for_each(|&x| w.f64(x));
            }
        }
        out.extend_from_slice(&w.bytes);
    }

    /// The scalars of the byte form, in order: times, the two crank laws, the slider force,
    /// the nine cached outputs, the integrator's time, step proposal and amplitude, the start's
    /// vibration.
    fn scalars(&self) -> [f64; 25] {
        let (p, i, o) = (&self.previous_input, &self.input, &self.outputs);
        [
            self.time,
            self.input_time,
            self.previous_input_time,
            p.angle,
            p.speed,
            p.acceleration,
            p.jerk,
            i.angle,
            i.speed,
            i.acceleration,
            i.jerk,
            self.slider_force,
            o.deflection,
            o.deflection_rel,
            o.pin_b_force[0],
            o.pin_b_force[1],
            o.pin_c_force[0],
            o.pin_c_force[1],
            o.crank_torque,
            o.slider_position,
            o.slider_velocity,
            self.dae.t,
            self.dae.step_hint,
            self.amplitude,
            self.start_vibration,
        ]
    }

    fn set_scalars(&mut self, x: [f64; 25]) {
        let [time, input_time, previous_input_time, pa, ps, pacc, pj, ia, is, iacc, ij, force, o0, o1, o2, o3, o4, o5, o6, o7, o8, t, hint, amplitude, vibration] =
            x;
        self.time = time;
        self.input_time = input_time;
        self.previous_input_time = previous_input_time;
        self.previous_input = CrankInput {
            angle: pa,
            speed: ps,
            acceleration: pacc,
            jerk: pj,
        };
        self.input = CrankInput {
            angle: ia,
            speed: is,
            acceleration: iacc,
            jerk: ij,
        };
        self.slider_force = force;
        let o = &mut self.outputs;
        o.deflection = o0;
        o.deflection_rel = o1;
        o.pin_b_force = [o2, o3];
        o.pin_c_force = [o4, o5];
        o.crank_torque = o6;
        o.slider_position = o7;
        o.slider_velocity = o8;
        self.dae.t = t;
        self.dae.step_hint = hint;
        self.amplitude = amplitude;
        self.start_vibration = vibration;
    }

    /// Read what [`Self::write_bytes`] wrote, into a state of the same dimensions; every
    /// field checked ([`Self::validate`]).
    pub fn read_bytes(&mut self, bytes: &[u8]) -> Result<(), String> {
        let mut r = ByteReader::new(bytes);
        let other_model = |e: String| format!("{e} (truncated or from another model)");
        let mut scalars = [0.0; 25];
        for x in scalars.iter_mut() {
            *x = r.f64("the state").map_err(other_model)?;
        }
        self.set_scalars(scalars);
        for v in [
            &mut self.dae.q,
            &mut self.dae.v,
            &mut self.dae.qdd,
            &mut self.dae.acc,
            &mut self.dae.lambda,
        ] {
            for x in v.iter_mut() {
                *x = r.f64("the coordinates").map_err(other_model)?;
            }
        }
        let s = &mut self.outputs.section;
        for x in [
            &mut s.axial_force_mid,
            &mut s.bending_moment_mid,
            &mut s.stress_max,
            &mut s.stress_max_position,
        ] {
            *x = r.f64("the section outputs").map_err(other_model)?;
        }
        let c = &mut self.stats;
        for n in [&mut c.steps, &mut c.newton_iterations, &mut c.halvings] {
            *n = r.u64("the counters").map_err(other_model)?;
        }
        if !(self.start_vibration.is_finite() && self.start_vibration >= 0.0) {
            return Err(format!(
                "the start's vibration amplitude is {}, allowed a finite value >= 0",
                self.start_vibration
            ));
        }
        self.large_deflection_warned =
            r.flag("the deflection warning flag").map_err(other_model)?;
        self.read_held_step(&mut r).map_err(other_model)?;
        r.finish("the state").map_err(other_model)?;
        self.validate()?;
        self.warnings.clear();
        Ok(())
    }

    /// The held internal step: its flag (1 only with dense output) and its values.
    fn read_held_step(&mut self, r: &mut ByteReader<'_>) -> Result<(), String> {
        let dense = !self.ahead.z0.is_empty();
        self.ahead.held = match r.u8("the held-step flag")? {
            0 => false,
            1 if dense => true,
            b => {
                let allowed = if dense {
                    " or 1"
                } else {
                    " (this model has no dense output)"
                };
                return Err(format!("the held-step flag is {b}, allowed 0{allowed}"));
            }
        };
        if self.ahead.held {
            let a = &mut self.ahead;
            for x in [&mut a.t0, &mut a.end.t, &mut a.end.step_hint] {
                *x = r.f64("the held step")?;
            }
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
                    *x = r.f64("the held step")?;
                }
            }
        }
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
            ("the deflection amplitude", self.amplitude),
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
            ("the deflection amplitude", self.amplitude),
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
        if d.step_hint < 0.0 || self.amplitude < 0.0 {
            return Err(format!(
                "the step proposal {:e} s or the amplitude {:e} is negative, allowed >= 0",
                d.step_hint, self.amplitude
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
            let values = [a.t0, a.end.t, a.end.step_hint];
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
            if a.end.step_hint < 0.0 {
                return Err(format!(
                    "the held step's proposal {:e} s is negative, allowed >= 0",
                    a.end.step_hint
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
