//! The prescribed crank (docs/fmu.md, "Behaviour"):
//! `theta(t) = theta_k + omega_k s + alpha_k s^2 / 2 + j_k s^3 / 6`, `s = t - t_k`; pin B at
//! `r (cos theta, sin theta)`.

use nalgebra::Vector2;

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
