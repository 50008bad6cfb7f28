//! The linear part of an exponential (Lawson) Runge-Kutta method on a second-order system:
//! each independent coordinate `z` has a damped oscillator `z'' = -w^2 z - c z' + n(t, z, z')`
//! split off, whose flow over a time `tau` is the 2 x 2 propagator `E(tau)` of `(z, z')`
//! (exact), and the method integrates only the remainder `n` (Lawson 1967, "Generalized
//! Runge-Kutta processes for stable systems with large Lipschitz constants", SIAM J. Numer.
//! Anal. 4; Hochbruck and Ostermann 2010, "Exponential integrators", Acta Numerica 19,
//! section 2.7).
//!
//! With `x = c / 2` and `wd^2 = w^2 - x^2`, the free motion from `(z0, v0)` is
//! `z(tau) = e^{-x tau} (C z0 + S (v0 + x z0))`, `z'(tau) = e^{-x tau} (C v0 - S (w^2 z0 + x v0))`
//! with `C = cos(wd tau)`, `S = sin(wd tau) / wd` (underdamped), `C = cosh(|wd| tau)`,
//! `S = sinh(|wd| tau) / |wd|` (overdamped) and `C = 1`, `S = tau` (critical): the solution of
//! the constant-coefficient equation (e.g. Meirovitch, *Fundamentals of Vibrations*, section
//! 2.5). Negative `tau` runs it backwards (the interpolant of dense output needs `E(-h)`).

/// The split-off linear oscillator of one coordinate: `z'' = -omega2 z - damping z' + ...`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Oscillator {
    /// Square of the circular frequency, rad^2/s^2 (>= 0).
    pub omega2: f64,
    /// Viscous coefficient `c = 2 zeta w`, 1/s (>= 0).
    pub damping: f64,
}

/// The 2 x 2 propagator of `(z, z')` over a time `tau`: `[zz, zv, vz, vv]`, so that
/// `z(tau) = zz z0 + zv v0`, `z'(tau) = vz z0 + vv v0`.
pub type Propagator = [f64; 4];

/// The identity propagator (`tau = 0`).
pub const IDENTITY: Propagator = [1.0, 0.0, 0.0, 1.0];

impl Oscillator {
    /// The remainder `n = z'' + w^2 z + c z'` of an acceleration `z''` at `(z, z')`.
    #[inline(always)]
    pub fn remainder(&self, z: f64, zd: f64, zdd: f64) -> f64 {
        zdd + self.omega2 * z + self.damping * zd
    }

    /// `E(tau)` (module documentation).
    pub fn propagator(&self, tau: f64) -> Propagator {
        let x = 0.5 * self.damping;
        let wd2 = self.omega2 - x * x;
        let (cc, ss) = if wd2 > 0.0 {
            let wd = wd2.sqrt();
            let (s, c) = (wd * tau).sin_cos();
            (c, s / wd)
        } else if wd2 < 0.0 {
            let wd = (-wd2).sqrt();
            let (e_plus, e_minus) = ((wd * tau).exp(), (-wd * tau).exp());
            (0.5 * (e_plus + e_minus), 0.5 * (e_plus - e_minus) / wd)
        } else {
            (1.0, tau)
        };
        let decay = if x == 0.0 { 1.0 } else { (-x * tau).exp() };
        [
            decay * (cc + x * ss),
            decay * ss,
            -decay * self.omega2 * ss,
            decay * (cc - x * ss),
        ]
    }
}

/// `E (z, v)`.
#[inline(always)]
pub fn apply(e: &Propagator, z: f64, v: f64) -> (f64, f64) {
    (e[0] * z + e[1] * v, e[2] * z + e[3] * v)
}

/// The product `a b` of two propagators (`E(s) E(t) = E(s + t)`).
#[inline(always)]
pub fn compose(a: &Propagator, b: &Propagator) -> Propagator {
    [
        a[0] * b[0] + a[1] * b[2],
        a[0] * b[1] + a[1] * b[3],
        a[2] * b[0] + a[3] * b[2],
        a[2] * b[1] + a[3] * b[3],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The propagator against a fine RK4 integration of the free oscillator, for under-,
    /// critically and over-damped coordinates and both directions of time; `E(s) E(t) =
    /// E(s + t)`.
    #[test]
    fn propagator_is_the_free_motion() {
        for (omega2, damping) in [(900.0, 0.0), (900.0, 6.0), (900.0, 60.0), (900.0, 150.0)] {
            let osc = Oscillator { omega2, damping };
            for tau in [0.07, -0.03] {
                let e = osc.propagator(tau);
                for (z0, v0) in [(1.0, 0.0), (0.0, 1.0)] {
                    let f = |z: f64, v: f64| (v, -omega2 * z - damping * v);
                    let (mut z, mut v) = (z0, v0);
                    let n = 20_000;
                    let h = tau / n as f64;
                    for _ in 0..n {
                        let k1 = f(z, v);
                        let k2 = f(z + 0.5 * h * k1.0, v + 0.5 * h * k1.1);
                        let k3 = f(z + 0.5 * h * k2.0, v + 0.5 * h * k2.1);
                        let k4 = f(z + h * k3.0, v + h * k3.1);
                        z += h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
                        v += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
                    }
                    let (ze, ve) = apply(&e, z0, v0);
                    let scale = 1.0 + z.abs() + v.abs() / 30.0;
                    assert!((ze - z).abs() < 1e-9 * scale, "{omega2} {damping} {tau}");
                    assert!((ve - v).abs() < 30e-9 * scale, "{omega2} {damping} {tau}");
                }
            }
            let sum = compose(&osc.propagator(0.02), &osc.propagator(0.05));
            let direct = osc.propagator(0.07);
            for k in 0..4 {
                assert!((sum[k] - direct[k]).abs() < 1e-12 * (1.0 + direct[k].abs()));
            }
        }
    }
}
