//! The exact motion of the crankshaft over one step with a torque linear in time.
//!
//! With k = c / J, the variation-of-constants formula for `w' = -k w + (T0 + T1 s) / J`
//! and its integral give, for s in [0, h]:
//!
//! ```text
//! w(s)     = w0 e^(-k s) + (T0 / J) u1(s) + (T1 / J) u2(s)
//! theta(s) = theta0 + w0 u1(s) + (T0 / J) u2(s) + (T1 / J) u3(s)
//! u_j(s)   = s^j phi_j(-k s),   phi_j(z) = sum_{n >= 0} z^n / (n + j)!
//! ```
//!
//! (phi_1(z) = (e^z - 1) / z, phi_2(z) = (e^z - 1 - z) / z^2, phi_3(z) = (e^z - 1 - z - z^2 / 2)
//! / z^3; M. Hochbruck and A. Ostermann, "Exponential integrators", Acta Numerica 19, 2010,
//! section 2). Each u_j is the integral of u_(j-1) from 0 (u_0 = e^(-k s)), which gives the
//! angle. The phi functions are summed as their series for |z| < 1 and from the closed forms
//! otherwise, so c = 0 (k = 0: u_j = s^j / j!) needs no special case.

/// The state of the crankshaft: angle (rad), speed (rad/s).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Motion {
    pub angle: f64,
    pub speed: f64,
}

/// The net torque over a step: `T0 + T1 s`, N m and N m/s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinearTorque {
    pub value: f64,
    pub rate: f64,
}

/// phi_1, phi_2, phi_3 at z.
pub fn phi(z: f64) -> [f64; 3] {
    if z.abs() < 1.0 {
        // phi_j(z) = sum_n z^n / (n + j)!: 25 terms leave less than 1e-25 for |z| < 1.
        let mut out = [0.0; 3];
        for (j, phi_j) in out.iter_mut().enumerate() {
            let mut term = 1.0 / factorial(j + 1);
            let mut sum = 0.0;
            for n in 0..25 {
                sum += term;
                term *= z / (n + j + 2) as f64;
            }
            *phi_j = sum;
        }
        out
    } else {
        let e = z.exp();
        let p1 = (e - 1.0) / z;
        let p2 = (p1 - 1.0) / z;
        let p3 = (p2 - 0.5) / z;
        [p1, p2, p3]
    }
}

fn factorial(n: usize) -> f64 {
    (1..=n).map(|k| k as f64).product()
}

/// The motion after `h` s from `start` under `torque`, with inertia `j` > 0 and loss
/// coefficient `c` >= 0.
pub fn advance(start: Motion, torque: LinearTorque, j: f64, c: f64, h: f64) -> Motion {
    let k = c / j;
    let [p1, p2, p3] = phi(-k * h);
    let (u1, u2, u3) = (h * p1, h * h * p2, h * h * h * p3);
    let decay = (-k * h).exp();
    let (a0, a1) = (torque.value / j, torque.rate / j);
    Motion {
        speed: start.speed * decay + a0 * u1 + a1 * u2,
        angle: start.angle + start.speed * u1 + a0 * u2 + a1 * u3,
    }
}

/// The angular acceleration, rad/s^2: `(T - c w) / J`.
pub fn acceleration(speed: f64, torque: f64, j: f64, c: f64) -> f64 {
    (torque - c * speed) / j
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn phi_matches_the_closed_forms_on_both_sides_of_the_switch() {
        for z in [-0.999, -0.5, -1e-3, 0.0, 1e-3, 0.7] {
            let [p1, p2, p3] = phi(z);
            if z != 0.0 {
                let e = z.exp();
                assert!((p1 - (e - 1.0) / z).abs() < 1e-12, "{z}");
                assert!((p2 - (e - 1.0 - z) / (z * z)).abs() < 1e-9, "{z}");
                assert!(
                    (p3 - (e - 1.0 - z - z * z / 2.0) / (z * z * z)).abs() < 1e-6,
                    "{z}"
                );
            } else {
                assert_eq!([p1, p2, p3], [1.0, 0.5, 1.0 / 6.0]);
            }
        }
        // Continuity at |z| = 1.
        let (a, b) = (phi(-1.0 + 1e-12), phi(-1.0));
        for i in 0..3 {
            assert!((a[i] - b[i]).abs() < 1e-12);
        }
    }

    #[test]
    fn without_loss_the_motion_is_the_polynomial() {
        let start = Motion {
            angle: 0.3,
            speed: 100.0,
        };
        let torque = LinearTorque {
            value: 50.0,
            rate: -2e3,
        };
        let (j, h) = (0.2, 0.01);
        let m = advance(start, torque, j, 0.0, h);
        let speed = 100.0 + (50.0 * h - 2e3 * h * h / 2.0) / j;
        let angle = 0.3 + 100.0 * h + (50.0 * h * h / 2.0 - 2e3 * h * h * h / 6.0) / j;
        assert!((m.speed - speed).abs() < 1e-12 * speed);
        assert!((m.angle - angle).abs() < 1e-12 * angle);
    }

    #[test]
    fn with_loss_a_constant_torque_relaxes_to_its_steady_speed() {
        // w(t) = T / c + (w0 - T / c) e^(-c t / J); theta from its integral.
        let (j, c, t) = (0.5, 0.8, 50.0);
        let start = Motion {
            angle: 0.0,
            speed: 10.0,
        };
        let torque = LinearTorque {
            value: 40.0,
            rate: 0.0,
        };
        let tau = j / c;
        let w_inf = 40.0 / c;
        for h in [1e-3, 0.1, 2.0, t] {
            let m = advance(start, torque, j, c, h);
            let speed = w_inf + (10.0 - w_inf) * (-h / tau).exp();
            let angle = w_inf * h + (10.0 - w_inf) * tau * (1.0 - (-h / tau).exp());
            assert!((m.speed - speed).abs() < 1e-12 * w_inf, "{h}");
            assert!(
                (m.angle - angle).abs() < 1e-12 * angle.abs().max(1.0),
                "{h}"
            );
        }
    }

    #[test]
    fn steps_compose_exactly_for_a_linear_torque() {
        let (j, c) = (0.3, 0.05);
        let start = Motion {
            angle: 1.0,
            speed: 200.0,
        };
        let torque = LinearTorque {
            value: 80.0,
            rate: 400.0,
        };
        let whole = advance(start, torque, j, c, 0.02);
        let half = advance(start, torque, j, c, 0.01);
        let later = LinearTorque {
            value: 80.0 + 400.0 * 0.01,
            rate: 400.0,
        };
        let two = advance(half, later, j, c, 0.01);
        assert!((whole.speed - two.speed).abs() < 1e-12 * whole.speed);
        assert!((whole.angle - two.angle).abs() < 1e-12 * whole.angle);
    }
}
