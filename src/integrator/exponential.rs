//! The linear part of the exponential integrator on a second-order system: each independent
//! coordinate `z` has a damped oscillator `z'' = -w^2 z - c z' + n(t, z, z')` split off
//! (`w`, `c` constant), so that with `y = (z, z')` the system reads `y' = A y + e2 n` with
//! `A = [[0, 1], [-w^2, -c]]`, `e2 = (0, 1)`. The oscillator is taken exactly by the
//! propagator `E(tau) = exp(tau A)` and the functions `phi_k(tau A) e2` (k = 1, 2, 3) that
//! integrate a polynomial remainder against it (Hochbruck and Ostermann 2010, "Exponential
//! integrators", Acta Numerica 19, sections 2.1-2.3):
//!
//! `int_0^tau E(tau - u) e2 u^(k-1) / (k-1)! du = tau^k phi_k(tau A) e2`,
//! `phi_0(Z) = e^Z`, `phi_(k+1)(Z) = Z^-1 (phi_k(Z) - I / k!)`.
//!
//! With `x = c / 2` and `wd^2 = w^2 - x^2`, the free motion from `(z0, v0)` is
//! `z(tau) = e^{-x tau} (C z0 + S (v0 + x z0))`, `z'(tau) = e^{-x tau} (C v0 - S (w^2 z0 + x v0))`
//! with `C = cos(wd tau)`, `S = sin(wd tau) / wd` (underdamped), `C = cosh(|wd| tau)`,
//! `S = sinh(|wd| tau) / |wd|` (overdamped) and `C = 1`, `S = tau` (critical) (e.g.
//! Meirovitch, *Fundamentals of Vibrations*, section 2.5). Units: `z` in the coordinate's unit,
//! `tau` in s, `w^2` in rad^2/s^2, `c` in 1/s.

/// The split-off linear oscillator of one coordinate: `z'' = -omega2 z - damping z' + ...`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Oscillator {
    /// Square of the circular frequency, rad^2/s^2 (> 0).
    pub omega2: f64,
    /// Viscous coefficient `c = 2 zeta w`, 1/s (>= 0).
    pub damping: f64,
    /// `|wd|`, `wd^2 = w^2 - c^2 / 4`, its reciprocal and `1 / w^2` (computed once: the
    /// propagator and the particular solution are evaluated at every interpolated point).
    wd: f64,
    inv_wd: f64,
    inv_omega2: f64,
}

/// The 2 x 2 propagator of `(z, z')` over a time `tau`: `[zz, zv, vz, vv]`, so that
/// `z(tau) = zz z0 + zv v0`, `z'(tau) = vz z0 + vv v0`.
pub type Propagator = [f64; 4];

/// `E(tau)` and `phi_k(tau A) e2` for k = 1, 2, 3 (module documentation) of one oscillator.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct PhiFunctions {
    pub e: Propagator,
    /// `phi[k - 1] = phi_k(tau A) e2` as `(z, z')` components.
    pub phi: [[f64; 2]; 3],
}

impl Oscillator {
    /// The oscillator `z'' = -omega2 z - damping z'`.
    pub fn new(omega2: f64, damping: f64) -> Oscillator {
        let x = 0.5 * damping;
        let wd = (omega2 - x * x).abs().sqrt();
        Oscillator {
            omega2,
            damping,
            wd,
            inv_wd: 1.0 / wd,
            inv_omega2: 1.0 / omega2,
        }
    }

    /// The remainder `n = z'' + w^2 z + c z'` of an acceleration `z''` at `(z, z')`.
    #[inline(always)]
    pub fn remainder(&self, z: f64, zd: f64, zdd: f64) -> f64 {
        zdd + self.omega2 * z + self.damping * zd
    }

    /// The damping ratio `zeta = c / (2 w)`.
    pub fn damping_ratio(&self) -> f64 {
        0.5 * self.damping * self.inv_omega2.sqrt()
    }

    /// `E(tau)` (module documentation).
    pub fn propagator(&self, tau: f64) -> Propagator {
        let x = 0.5 * self.damping;
        let wd2 = self.omega2 - x * x;
        let wd = self.wd;
        let (cc, ss) = if wd2 > 0.0 {
            let (s, c) = crate::trig::sin_cos(wd * tau);
            (c, s * self.inv_wd)
        } else if wd2 < 0.0 {
            let (e_plus, e_minus) = ((wd * tau).exp(), (-wd * tau).exp());
            (
                0.5 * (e_plus + e_minus),
                0.5 * (e_plus - e_minus) * self.inv_wd,
            )
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

    /// The exact motion over `tau` from `y0 = (z0, z0')` under the remainder
    /// `n(u) = n0 + n1 u + n2 u^2`, given `e = E(tau)`: with the polynomial particular solution
    /// `P(u) = p0 + p1 u + p2 u^2` of `P'' + c P' + w^2 P = n` (`p2 = n2 / w^2`,
    /// `p1 = (n1 - 2 c p2) / w^2`, `p0 = (n0 - c p1 - 2 p2) / w^2`),
    /// `y(tau) = E(tau) (y0 - (P(0), P'(0))) + (P(tau), P'(tau))` (the same as
    /// `E(tau) y0 + tau phi_1 n0 + tau^2 phi_2 n1 + 2 tau^3 phi_3 n2`, without the phi
    /// functions; its absolute error is round-off of `|P| ~ |n| / w^2`, the quasi-static
    /// response).
    #[inline]
    pub fn quadratic_response(
        &self,
        e: &Propagator,
        tau: f64,
        y0: (f64, f64),
        n: [f64; 3],
    ) -> (f64, f64) {
        let inv = self.inv_omega2;
        let c = self.damping;
        let p2 = n[2] * inv;
        let p1 = (n[1] - 2.0 * c * p2) * inv;
        let p0 = (n[0] - c * p1 - 2.0 * p2) * inv;
        let (zh, vh) = apply(e, y0.0 - p0, y0.1 - p1);
        (zh + p0 + (p1 + p2 * tau) * tau, vh + p1 + 2.0 * p2 * tau)
    }

    /// `E(tau)` and `phi_1..3(tau A) e2` for `tau >= 0`. Where `tau A` is small
    /// (`tau max(w, c) <= 1/2`): `phi_3(Z) e2 = sum_(j <= 12) Z^j e2 / (j + 3)!` by Horner's rule
    /// (the first term left out is below `0.5^13 / 16! = 6e-18`), then
    /// `phi_k(Z) = I / k! + Z phi_(k+1)(Z)` down to `phi_1`, and `E = I + Z phi_1(Z)` (its first
    /// column `e1 - tau w^2 phi_1(Z) e2`, since `Z e1 = -tau w^2 e2`): no trigonometry. Else
    /// `E(tau)` in closed form and the recurrence `phi_(k+1)(Z) = Z^-1 (phi_k(Z) - I / k!)`
    /// with `Z^-1 = A^-1 / tau`, `A^-1 = [[-c / w^2, -1 / w^2], [1, 0]]` (it loses at most a
    /// factor `|Z|^-3 <= 8` to cancellation).
    pub fn phi_functions(&self, tau: f64) -> PhiFunctions {
        let (w2, c) = (self.omega2, self.damping);
        // Z x for x = (z, z').
        let z_times = |x: [f64; 2]| [tau * x[1], -tau * (w2 * x[0] + c * x[1])];
        if tau * w2.sqrt().max(c) <= 0.5 {
            const INV_FACTORIAL: [f64; 16] = {
                let mut f = [1.0; 16];
                let mut i = 1;
                while i < 16 {
                    f[i] = f[i - 1] / i as f64;
                    i += 1;
                }
                f
            };
            let mut p3 = [0.0, INV_FACTORIAL[15]];
            for j in (0..12).rev() {
                let zp = z_times(p3);
                p3 = [zp[0], zp[1] + INV_FACTORIAL[j + 3]];
            }
            let zp = z_times(p3);
            let p2 = [zp[0], zp[1] + 0.5];
            let zp = z_times(p2);
            let p1 = [zp[0], zp[1] + 1.0];
            let col2 = z_times(p1);
            let e = [
                1.0 - tau * w2 * p1[0],
                col2[0],
                -tau * w2 * p1[1],
                1.0 + col2[1],
            ];
            PhiFunctions {
                e,
                phi: [p1, p2, p3],
            }
        } else {
            let e = self.propagator(tau);
            let inv_tau = 1.0 / tau;
            let inv_w2_tau = inv_tau / w2;
            let inv = |x: [f64; 2]| [(-c * x[0] - x[1]) * inv_w2_tau, x[0] * inv_tau];
            let p1 = inv([e[1], e[3] - 1.0]);
            let p2 = inv([p1[0], p1[1] - 1.0]);
            let p3 = inv([p2[0], p2[1] - 0.5]);
            PhiFunctions {
                e,
                phi: [p1, p2, p3],
            }
        }
    }
}

/// `E (z, v)`.
#[inline(always)]
pub fn apply(e: &Propagator, z: f64, v: f64) -> (f64, f64) {
    (e[0] * z + e[1] * v, e[2] * z + e[3] * v)
}

/// The weights of one step of size `h` of the fourth-order exponential Runge-Kutta method
/// ETDRK4-B of Krogstad for one oscillator (S. Krogstad, "Generalized integrating factor
/// methods for stiff PDEs", J. Comput. Phys. 203, 2005; Hochbruck and Ostermann 2010,
/// section 2.3): with `N0, Na, Nb, Nc` the remainders at the stages,
/// `a = E(h/2) y0 + h/2 phi_1(hA/2) e2 N0` and
/// `b = E(h/2) y0 + h/2 phi_1(hA/2) e2 N0 + h phi_2(hA/2) e2 (Na - N0)` (at `t + h/2`),
/// `c = E(h) y0 + h phi_1(hA) e2 N0 + 2 h phi_2(hA) e2 (Nb - N0)` (at `t + h`),
/// `y1 = E(h) y0 + h (f1 N0 + 2 f2 (Na + Nb) + f3 Nc)` with `f1 = phi_1 - 3 phi_2 + 4 phi_3`,
/// `f2 = phi_2 - 2 phi_3`, `f3 = -phi_2 + 4 phi_3` (at `hA`, times `e2`; the weights of Cox
/// and Matthews 2002, "Exponential time differencing for stiff systems", J. Comput. Phys. 176,
/// whose stages b and c are `E(h/2) y0 + h/2 phi_1(hA/2) e2 Na` and
/// `E(h/2) a + h/2 phi_1(hA/2) e2 (2 Nb - N0)`). For `A -> 0` both are the classic RK4. Stages
/// b and c of Krogstad's form take the remainder's change over the step against the oscillator
/// by `phi_2` (the first-order term of its expansion, which the Cox and Matthews stages take
/// at the stage's start): on the undamped benchmark rod the Cox and Matthews form raised the
/// first mode's amplitude by 10 % in 100 s at `h = 1e-3 s`, Krogstad's lowered it by 0.8 %
/// (docs/solvers.md, "Long runs").
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct EtdWeights {
    /// `E(h/2)`, `phi_1(hA/2) e2` and `phi_2(hA/2) e2`.
    pub half: Propagator,
    pub half_phi1: [f64; 2],
    pub half_phi2: [f64; 2],
    /// `E(h)`, `phi_1(hA) e2` and `phi_2(hA) e2`.
    pub full: Propagator,
    pub full_phi1: [f64; 2],
    pub full_phi2: [f64; 2],
    /// `f1, f2, f3` (times `e2`).
    pub f: [[f64; 2]; 3],
}

impl EtdWeights {
    pub fn new(osc: &Oscillator, h: f64) -> EtdWeights {
        let half = osc.phi_functions(0.5 * h);
        let full = osc.phi_functions(h);
        let p = &full.phi;
        let comb = |a: f64, b: f64, c: f64| {
            [
                a * p[0][0] + b * p[1][0] + c * p[2][0],
                a * p[0][1] + b * p[1][1] + c * p[2][1],
            ]
        };
        EtdWeights {
            half: half.e,
            half_phi1: half.phi[0],
            half_phi2: half.phi[1],
            full: full.e,
            full_phi1: p[0],
            full_phi2: p[1],
            f: [
                comb(1.0, -3.0, 4.0),
                comb(0.0, 1.0, -2.0),
                comb(0.0, -1.0, 4.0),
            ],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The response from rest over `tau` to `n(u) = n0 + n1 u + n2 u^2` by the phi functions:
    /// `tau phi_1 n0 + tau^2 phi_2 n1 + 2 tau^3 phi_3 n2`.
    fn forced(p: &PhiFunctions, tau: f64, n0: f64, n1: f64, n2: f64) -> (f64, f64) {
        let (a, b, c) = (tau * n0, tau * tau * n1, 2.0 * tau * tau * tau * n2);
        let p = &p.phi;
        (
            a * p[0][0] + b * p[1][0] + c * p[2][0],
            a * p[0][1] + b * p[1][1] + c * p[2][1],
        )
    }

    const CASES: [(f64, f64); 5] = [
        (900.0, 0.0),
        (900.0, 6.0),
        (900.0, 60.0),
        (900.0, 150.0),
        (6.0e7, 0.0),
    ];

    /// `y' = A y + e2 g(t)` from `(z0, v0)` over `tau` by a fine classic RK4.
    fn fine(osc: &Oscillator, tau: f64, y0: (f64, f64), g: impl Fn(f64) -> f64) -> (f64, f64) {
        let f = |t: f64, z: f64, v: f64| (v, -osc.omega2 * z - osc.damping * v + g(t));
        let (mut z, mut v) = y0;
        let n = 40_000;
        let h = tau / n as f64;
        for i in 0..n {
            let t = i as f64 * h;
            let k1 = f(t, z, v);
            let k2 = f(t + 0.5 * h, z + 0.5 * h * k1.0, v + 0.5 * h * k1.1);
            let k3 = f(t + 0.5 * h, z + 0.5 * h * k2.0, v + 0.5 * h * k2.1);
            let k4 = f(t + h, z + h * k3.0, v + h * k3.1);
            z += h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
            v += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
        }
        (z, v)
    }

    /// The propagator is the free motion; the phi functions (and the particular solution of
    /// [`Oscillator::quadratic_response`]) are the exact response to a
    /// quadratic remainder, on both sides of the switch between the series and the recurrence
    /// (w tau from 0.05 to 8), under-, critically and over-damped.
    #[test]
    fn phi_functions_are_the_forced_response() {
        for (omega2, damping) in CASES {
            let osc = Oscillator::new(omega2, damping);
            let w = omega2.sqrt();
            for wt in [0.05, 0.49, 0.51, 1.2, 8.0] {
                let tau = wt / w;
                let p = osc.phi_functions(tau);
                let (n0, n1, n2) = (3.0, -2.0 / tau, 5.0 / (tau * tau));
                let y0 = (0.7 / omega2, -0.4 / w);
                let (zf, vf) = apply(&p.e, y0.0, y0.1);
                let (zn, vn) = forced(&p, tau, n0, n1, n2);
                let (z, v) = (zf + zn, vf + vn);
                let (zr, vr) = fine(&osc, tau, y0, |u| n0 + n1 * u + n2 * u * u);
                let (zq, vq) = osc.quadratic_response(&p.e, tau, y0, [n0, n1, n2]);
                assert!(
                    (zq - zr).abs() < 1e-9 / omega2 && (vq - vr).abs() < 1e-9 * w / omega2,
                    "{omega2} {damping} {wt}: quadratic response ({zq}, {vq}) vs ({zr}, {vr})"
                );
                let scale = 1.0 / omega2;
                assert!(
                    (z - zr).abs() < 1e-9 * scale,
                    "{omega2} {damping} {wt}: z {z} vs {zr}"
                );
                assert!(
                    (v - vr).abs() < 1e-9 * scale * w,
                    "{omega2} {damping} {wt}: v {v} vs {vr}"
                );
            }
        }
    }

    /// With a vanishing linear part the ETDRK4 weights are the classic RK4 weights
    /// (1/6, 2 x 1/6, 1/6 on the velocity row).
    #[test]
    fn etd_weights_tend_to_rk4() {
        let osc = Oscillator::new(1e-6, 0.0);
        let w = EtdWeights::new(&osc, 1e-3);
        assert!((w.f[0][1] - 1.0 / 6.0).abs() < 1e-12);
        assert!((w.f[1][1] - 1.0 / 6.0).abs() < 1e-12);
        assert!((w.f[2][1] - 1.0 / 6.0).abs() < 1e-12);
        assert!((w.half_phi1[1] - 1.0).abs() < 1e-12);
        assert!((w.half_phi2[1] - 0.5).abs() < 1e-12);
        assert!((w.full_phi1[1] - 1.0).abs() < 1e-12);
        assert!((w.full_phi2[1] - 0.5).abs() < 1e-12);
    }
}
