//! The crank input law, one owner (docs/fmu.md, "Input law between communication points"):
//! `theta(t) = theta_k + omega_k s + alpha_k s^2 / 2 + j_k s^3 / 6`, `s = t - t_k`, from the
//! inputs set at the communication point `t_k`; pin B at `r (cos theta, sin theta)`. Here: the
//! law's values and their windows, its check, the pin's motion, and how a drive continues a law
//! at the next communication point.

use nalgebra::Vector2;

use crate::error::ModelError;

/// Largest |crank angle| of a law, rad (the phase keeps 1e-7 rad).
pub const ANGLE_WINDOW: f64 = 1e9;
/// Largest |crank speed|, rad/s (95 000 rpm): `crank.speed` and `[experiment] crank_speed`.
pub const SPEED_WINDOW: f64 = 1e4;
/// Largest |crank acceleration| `alpha_k`, rad/s^2.
pub const ACCELERATION_WINDOW: f64 = 1e8;
/// Largest |crank jerk| `j_k`, rad/s^3: the acceleration window reached in 1e-4 s.
pub const JERK_WINDOW: f64 = 1e12;

/// Crank input at a communication point.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct CrankInput {
    /// theta_k, rad.
    pub angle: f64,
    /// omega_k, rad/s.
    pub speed: f64,
    /// alpha_k, rad/s^2 (the crank acceleration given with the inputs; 0 otherwise).
    pub acceleration: f64,
    /// j_k, rad/s^3 (the crank jerk given with the inputs, the rate of the acceleration over
    /// the step; 0 otherwise).
    pub jerk: f64,
}

/// Crank motion from the input at the communication point `t_k`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CrankLaw {
    /// Crank length r, m.
    pub length: f64,
    pub t_k: f64,
    pub input: CrankInput,
}

impl CrankInput {
    /// Every value finite and within its window; the error names the value as the set calls
    /// do (the order-1 and order-2 derivatives of `crank.speed` are the acceleration and jerk).
    pub fn check(&self) -> Result<(), ModelError> {
        let checks: [(&'static str, f64, f64, &str); 4] = [
            ("crank.angle", self.angle, ANGLE_WINDOW, "rad"),
            ("crank.speed", self.speed, SPEED_WINDOW, "rad/s"),
            (
                "crank.speed derivative (crank acceleration)",
                self.acceleration,
                ACCELERATION_WINDOW,
                "rad/s^2",
            ),
            (
                "crank.speed order-2 derivative (crank jerk)",
                self.jerk,
                JERK_WINDOW,
                "rad/s^3",
            ),
        ];
        for (name, value, bound, unit) in checks {
            if !(value.is_finite() && value.abs() <= bound) {
                return Err(ModelError::InvalidParameter {
                    name,
                    value,
                    allowed: format!("a finite value with |value| <= {bound:e} {unit}"),
                });
            }
        }
        Ok(())
    }

    /// The input that continues this crank law (set `s` seconds ago): its angle and speed
    /// carried on as `CrankLaw` carries them, with the constant acceleration that reaches the drive's
    /// `speed` (rad/s) after the next communication step `h`. The speed follows the drive exactly at
    /// the communication points, the angle by the trapezoidal rule (within `alpha_max h^2 / 12`,
    /// 2e-7 rad on the ramp to 6000 rpm), and the state needs no projection at the new input
    /// (`Mechanism::advance`: a new acceleration on the same angle and speed).
    pub fn continued(&self, s: f64, speed: f64, h: f64) -> CrankInput {
        let (angle, omega, _) = self.after(s);
        CrankInput {
            angle,
            speed: omega,
            acceleration: (speed - omega) / h,
            jerk: 0.0,
        }
    }

    /// The input that continues this crank law (set `s` seconds ago, with its jerk) in
    /// angle and speed, with the drive's acceleration `now` (rad/s^2) and the jerk that reaches the
    /// drive's `speed` (rad/s) after the next communication step `h`:
    /// `j = 2 (speed - omega - alpha h) / h^2`. The angle and the speed are continuous across the
    /// input points and the speed follows the drive exactly there; the acceleration steps at a
    /// point by the difference of the quadratic speed from the drive's, `h^2 alpha'' / 6` (25
    /// rad/s^2 on the ramp to 6000 rpm at `h = 1e-3` s, against `h alpha'` = 1940 rad/s^2 for an
    /// acceleration held over the step), so the steps barely ring the rod. (Continuing the
    /// acceleration too would leave the steps' speeds no free parameter but the jerk, and any
    /// error of the first acceleration would alternate in sign from step to step for ever.)
    pub fn continued_smoothly(&self, s: f64, now: f64, speed: f64, h: f64) -> CrankInput {
        let (angle, omega, _) = self.after(s);
        CrankInput {
            angle,
            speed: omega,
            acceleration: now,
            jerk: 2.0 * (speed - omega - now * h) / (h * h),
        }
    }

    /// Angle, speed and acceleration `s` seconds after this input was set:
    /// `theta_k + omega_k s + alpha_k s^2 / 2 + j_k s^3 / 6` and its derivatives.
    pub fn after(&self, s: f64) -> (f64, f64, f64) {
        let CrankInput {
            angle,
            speed,
            acceleration,
            jerk,
        } = *self;
        // Without a jerk the same operations as the quadratic law (bit for bit).
        (
            angle + speed * s + 0.5 * acceleration * s * s + jerk * s * s * s * (1.0 / 6.0),
            speed + acceleration * s + 0.5 * jerk * s * s,
            acceleration + jerk * s,
        )
    }
}

impl CrankLaw {
    /// Angle, speed and acceleration at time t ([`CrankInput::after`] of the input at `t_k`).
    pub fn kinematics(&self, t: f64) -> (f64, f64, f64) {
        self.input.after(t - self.t_k)
    }

    /// Position, velocity and acceleration of the crank pin B (global, m, m/s, m/s^2).
    pub fn pin(&self, t: f64) -> (Vector2<f64>, Vector2<f64>, Vector2<f64>) {
        let (th, w, al) = self.kinematics(t);
        let (s, c) = crate::trig::sin_cos(th);
        let r = self.length;
        let pos = Vector2::new(r * c, r * s);
        let tangent = Vector2::new(-r * s, r * c);
        (pos, tangent * w, tangent * al - pos * (w * w))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The pin's velocity and acceleration are the derivatives of its position, and the
    /// law's speed and acceleration those of its angle, with and without a jerk.
    #[test]
    fn pin_kinematics_are_derivatives() {
        for jerk in [0.0, 4.0e6, -2.5e7] {
            let law = CrankLaw {
                length: 0.15,
                t_k: 0.1,
                input: CrankInput {
                    angle: 0.3,
                    speed: 120.0,
                    acceleration: 900.0,
                    jerk,
                },
            };
            let (t, h) = (0.1013, 1e-6);
            let (p1, _, _) = law.pin(t - h);
            let (p2, v, a) = law.pin(t);
            let (p3, _, _) = law.pin(t + h);
            assert!(((p3 - p1) / (2.0 * h) - v).norm() < 1e-5 * v.norm());
            assert!(((p3 - 2.0 * p2 + p1) / (h * h) - a).norm() < 1e-3 * a.norm());
            let (th1, w1, a1) = law.kinematics(t - h);
            let (_, w, a) = law.kinematics(t);
            let (th3, w3, a3) = law.kinematics(t + h);
            assert!(((th3 - th1) / (2.0 * h) - w).abs() < 1e-7 * w.abs());
            assert!(((w3 - w1) / (2.0 * h) - a).abs() < 1e-6 * a.abs().max(1.0));
            assert!(((a3 - a1) / (2.0 * h) - jerk).abs() < 1e-6 * jerk.abs().max(1.0));
            // At the law's start: the input itself.
            assert_eq!(law.kinematics(0.1), (0.3, 120.0, 900.0));
        }
    }
}
