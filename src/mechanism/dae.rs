//! The slider-crank as an index-3 DAE for the integrator.
//!
//! Coordinates `q = [q_rod..., x_s]` (x_s: slider position, m). Constraints (4):
//! pin B `r_B(q) - r_crank(t) = 0` (2), pin C `r_C(q) - (x_s, e) = 0` (2), `e` the slider
//! line offset. Gravity `g` acts on the rod ([`RodBody::add_gravity`]) and on the slider
//! (`m_s g_x` along its line; the guide takes `m_s g_y`).
//! Multipliers `lambda = [B_x, B_y, C_x, C_y]`: with `M q'' + Phi_q^T lambda = Q`, the force
//! of the rod on the crank pin is `lambda_B` and on the slider `lambda_C` (global, N).

use std::cell::Cell;

use faer::reborrow::ReborrowMut;
use faer::MatMut;
use nalgebra::Vector2;

use super::crank::CrankLaw;
use super::gas_force::GasForce;
use crate::integrator::DaeSystem;
use crate::rod::{RodBody, RodPoint};

/// One evaluation context: the rod, the crank law in force, the slider.
pub struct SliderCrankDae<'a> {
    pub rod: &'a dyn RodBody,
    pub crank: CrankLaw,
    /// Slider mass m_s, kg (0 allowed).
    pub slider_mass: f64,
    /// External force on the slider along +x, N (the `slider.force` input).
    pub slider_force: f64,
    /// The force of `[slider.gas_force]` as a function of the crank angle, if the scene has one.
    pub gas: Option<&'a GasForce>,
    /// The slider line `y = slider_offset`, m.
    pub slider_offset: f64,
    /// Gravity, m/s^2, global frame.
    pub gravity: Vector2<f64>,
    /// The crank pin's motion at the last time and law asked for ([`PinAt::pin`]; stages of a
    /// Runge-Kutta step share their times, and the outputs ask for the time of the evaluation
    /// that ended the communication step). Derived data, kept by the mechanism across
    /// evaluation contexts.
    pub pin_cache: &'a Cell<PinAt>,
}

/// The crank pin's position, velocity and acceleration at a time under a crank law, and the
/// gas force at the crank angle then (a cache: [`PinAt::pin_and_gas`]; the stages of a step
/// share their times).
#[derive(Clone, Copy, Debug)]
pub struct PinAt {
    /// An entry is held (the default holds none).
    filled: bool,
    law: CrankLaw,
    t: f64,
    pin: [Vector2<f64>; 3],
    /// The gas force at `t`, N, once asked for (NaN before).
    gas: f64,
}

impl Default for PinAt {
    /// Nothing cached.
    fn default() -> PinAt {
        PinAt {
            filled: false,
            law: CrankLaw {
                length: 0.0,
                t_k: 0.0,
                input: Default::default(),
            },
            t: f64::NAN,
            pin: [Vector2::zeros(); 3],
            gas: f64::NAN,
        }
    }
}

/// The two laws are the same numbers bit for bit (a signed zero differs from the other zero,
/// unlike `==`), so that the cache returns exactly what [`CrankLaw::pin`] would.
fn same_bits(a: &CrankLaw, b: &CrankLaw) -> bool {
    let same = |x: f64, y: f64| x.to_bits() == y.to_bits();
    same(a.length, b.length)
        && same(a.t_k, b.t_k)
        && same(a.input.angle, b.input.angle)
        && same(a.input.speed, b.input.speed)
        && same(a.input.acceleration, b.input.acceleration)
        && same(a.input.jerk, b.input.jerk)
}

impl PinAt {
    /// [`CrankLaw::pin`] of `law` at `t`, from `cache` when it holds the same law and time bit
    /// for bit (so the same numbers as without the cache).
    pub fn pin(
        cache: &Cell<PinAt>,
        law: &CrankLaw,
        t: f64,
    ) -> (Vector2<f64>, Vector2<f64>, Vector2<f64>) {
        let ([p, v, a], _) = PinAt::pin_and_gas(cache, law, t, None);
        (p, v, a)
    }

    /// [`PinAt::pin`] and, with a `gas` table, the gas force at the crank angle of `law` at
    /// `t` (0 without), N: one look into `cache`, which holds both for the same law and time
    /// bit for bit.
    pub fn pin_and_gas(
        cache: &Cell<PinAt>,
        law: &CrankLaw,
        t: f64,
        gas: Option<&GasForce>,
    ) -> ([Vector2<f64>; 3], f64) {
        let mut entry = cache.get();
        let hit = entry.filled && entry.t.to_bits() == t.to_bits() && same_bits(&entry.law, law);
        let mut changed = !hit;
        if !hit {
            let (p, v, a) = law.pin(t);
            entry = PinAt {
                filled: true,
                law: *law,
                t,
                pin: [p, v, a],
                gas: f64::NAN,
            };
        }
        let force = match gas {
            None => 0.0,
            Some(table) if entry.gas.is_nan() => {
                entry.gas = table.at(law.kinematics(t).0);
                changed = true;
                entry.gas
            }
            Some(_) => entry.gas,
        };
        if changed {
            cache.set(entry);
        }
        (entry.pin, force)
    }
}

impl SliderCrankDae<'_> {
    /// Pins B and C, two each.
    pub const N_CONSTRAINTS: usize = 4;

    /// [`CrankLaw::pin`] of the law in force at `t` ([`PinAt::pin`]).
    pub fn pin_at(&self, t: f64) -> (Vector2<f64>, Vector2<f64>, Vector2<f64>) {
        PinAt::pin(self.pin_cache, &self.crank, t)
    }

    /// The force on the slider along +x at `t`, N: the `slider.force` input plus the gas force
    /// at the crank angle of `t`.
    pub fn slider_force_at(&self, t: f64) -> f64 {
        match self.gas {
            Some(gas) => {
                self.slider_force + PinAt::pin_and_gas(self.pin_cache, &self.crank, t, Some(gas)).1
            }
            None => self.slider_force,
        }
    }

    fn nr(&self) -> usize {
        self.rod.n_coordinates()
    }

    /// `M` and `Q` as [`DaeSystem::mass`] and [`DaeSystem::forces`] give them, the rod's in one
    /// call ([`RodBody::mass_and_forces`]).
    pub(super) fn mass_and_forces(
        &self,
        t: f64,
        q: &[f64],
        v: &[f64],
        mut m: MatMut<'_, f64>,
        f: &mut [f64],
    ) {
        let nr = self.nr();
        m.fill(0.0);
        self.rod
            .mass_and_forces(q, v, m.rb_mut().submatrix_mut(0, 0, nr, nr), &mut f[..nr]);
        m[(nr, nr)] = self.slider_mass;
        f[nr] = self.slider_force_at(t);
        if self.gravity != Vector2::zeros() {
            self.rod.add_gravity(q, self.gravity, &mut f[..nr]);
            f[nr] += self.slider_mass * self.gravity.x;
        }
    }
}

/// Crank speed below which [`DaeSystem::error_time_scale`] stays at `2 pi / 10 s`, rad/s.
pub const ERROR_TIME_SCALE_MIN_SPEED: f64 = 10.0;

impl DaeSystem for SliderCrankDae<'_> {
    fn n_coordinates(&self) -> usize {
        self.nr() + 1
    }

    fn n_constraints(&self) -> usize {
        Self::N_CONSTRAINTS
    }

    fn coordinate_scale(&self, i: usize) -> f64 {
        if i < self.nr() {
            self.rod.coordinate_scale(i)
        } else {
            self.rod.length()
        }
    }

    fn mass(&self, q: &[f64], mut m: MatMut<'_, f64>) {
        let nr = self.nr();
        m.fill(0.0);
        self.rod.mass(q, m.rb_mut().submatrix_mut(0, 0, nr, nr));
        m[(nr, nr)] = self.slider_mass;
    }

    fn forces(&self, t: f64, q: &[f64], v: &[f64], f: &mut [f64]) {
        let nr = self.nr();
        self.rod.forces(q, v, &mut f[..nr]);
        f[nr] = self.slider_force_at(t);
        if self.gravity != Vector2::zeros() {
            self.rod.add_gravity(q, self.gravity, &mut f[..nr]);
            f[nr] += self.slider_mass * self.gravity.x;
        }
    }

    fn constraints(&self, t: f64, q: &[f64], phi: &mut [f64]) {
        let nr = self.nr();
        let (pin, _, _) = self.crank.pin(t);
        let b = self.rod.point(RodPoint::B, q) - pin;
        let c = self.rod.point(RodPoint::C, q) - Vector2::new(q[nr], self.slider_offset);
        phi[0] = b.x;
        phi[1] = b.y;
        phi[2] = c.x;
        phi[3] = c.y;
    }

    fn constraint_jacobian(&self, q: &[f64], mut jac: MatMut<'_, f64>) {
        let nr = self.nr();
        jac.fill(0.0);
        self.rod
            .point_jacobian(RodPoint::B, q, jac.rb_mut().submatrix_mut(0, 0, 2, nr));
        self.rod
            .point_jacobian(RodPoint::C, q, jac.rb_mut().submatrix_mut(2, 0, 2, nr));
        jac[(2, nr)] = -1.0;
    }

    fn constraint_rate(&self, t: f64, _q: &[f64], out: &mut [f64]) {
        let (_, vel, _) = self.crank.pin(t);
        out[0] = -vel.x;
        out[1] = -vel.y;
        out[2] = 0.0;
        out[3] = 0.0;
    }

    fn constraint_acceleration_rhs(&self, t: f64, q: &[f64], v: &[f64], out: &mut [f64]) {
        let (_, _, acc) = self.crank.pin(t);
        let b = acc - self.rod.point_bias_acceleration(RodPoint::B, q, v);
        let c = -self.rod.point_bias_acceleration(RodPoint::C, q, v);
        out[0] = b.x;
        out[1] = b.y;
        out[2] = c.x;
        out[3] = c.y;
    }

    /// Closed form for a rod with one body frame (FFR, the chain on its modes): with the frame
    /// at the origin the points give the body-frame chord `d = u_C - u_B`; pin B gives the
    /// origin `R = r_pin - B_0` with `B_0` the pin at the frame's angle and the origin, pin C's
    /// line constraint `y_pin + (A(phi) d)_y = y_line`, i.e. `sin(phi + beta) = (y_line -
    /// y_pin) / |d|` with `beta = atan2(d_y, d_x)` (the root nearest the current angle: the
    /// assembly mode does not change), and the slider `x_s = x_pin + (A(phi) d)_x`. The pin
    /// position and the line come from the constraint residuals at the current `q`, so the
    /// closed form follows whatever the constraints say.
    fn solve_dependent_positions(&self, t: f64, q: &mut [f64]) -> bool {
        let Some([ix, iy, iphi]) = self.rod.frame_coordinates() else {
            return false;
        };
        let nr = self.nr();
        let mut residual = [0.0; 4];
        self.constraints(t, q, &mut residual);
        let b_now = self.rod.point(RodPoint::B, q);
        let c_now = self.rod.point(RodPoint::C, q);
        let pin = b_now - Vector2::new(residual[0], residual[1]);
        let y_line = c_now.y - residual[3];
        let (rx, ry, phi0) = (q[ix], q[iy], q[iphi]);
        q[ix] = 0.0;
        q[iy] = 0.0;
        q[iphi] = 0.0;
        let u_b = self.rod.point(RodPoint::B, q);
        let d = self.rod.point(RodPoint::C, q) - u_b;
        let rho = d.norm();
        let sine = (y_line - pin.y) / rho;
        if !(rho > 0.0 && sine.abs() <= 1.0) {
            q[ix] = rx;
            q[iy] = ry;
            q[iphi] = phi0;
            return false;
        }
        let beta = d.y.atan2(d.x);
        let a = sine.asin();
        let nearest = |x: f64| {
            let k = ((phi0 - x) / std::f64::consts::TAU).round();
            x + k * std::f64::consts::TAU
        };
        let (p1, p2) = (nearest(a - beta), nearest(std::f64::consts::PI - a - beta));
        let phi = if (p1 - phi0).abs() <= (p2 - phi0).abs() {
            p1
        } else {
            p2
        };
        // The pins at the frame's angle with the frame at the origin: B's share of the elastic
        // coordinates need not turn with the frame (a shear chain's modes move its first
        // segment's start across B's slide in the global axes), only the chord does.
        q[iphi] = phi;
        let b0 = self.rod.point(RodPoint::B, q);
        let c0 = self.rod.point(RodPoint::C, q);
        let r = pin - b0;
        q[ix] = r.x;
        q[iy] = r.y;
        q[nr] = r.x + c0.x;
        true
    }

    fn has_reduced_rhs(&self) -> bool {
        self.rod.ffr_kernel().is_some()
    }

    /// One crank revolution at the crank speed of the law in force, `2 pi / |omega|`, the
    /// speed floored at [`ERROR_TIME_SCALE_MIN_SPEED`] (standstill and slow turning accumulate
    /// errors over at most that long).
    fn error_time_scale(&self) -> f64 {
        std::f64::consts::TAU / self.crank.input.speed.abs().max(ERROR_TIME_SCALE_MIN_SPEED)
    }

    /// The FFR rod's closed form on minimal coordinates ([`super::minimal`]); for a rod that
    /// asks for it ([`RodBody::frame_form`]: the chain on its modes) the closed form on its
    /// frame ([`super::frame_coordinates_closed_form`]).
    fn reduced_rhs(
        &self,
        t: f64,
        q: &mut [f64],
        v: &mut [f64],
        qdd: &mut [f64],
        lambda: Option<&mut [f64]>,
    ) -> Option<Result<(), crate::integrator::StepFailure>> {
        match self.rod.ffr_kernel() {
            Some(kernel) => Some(self.minimal_rhs(kernel, t, q, v, qdd, lambda)),
            None if self.rod.frame_form() => self.frame_form_rhs(t, q, v, qdd, lambda),
            None => None,
        }
    }

    fn add_tangent(
        &self,
        q: &[f64],
        v: &[f64],
        lambda: &[f64],
        c_k: f64,
        c_d: f64,
        mut out: MatMut<'_, f64>,
    ) {
        let nr = self.nr();
        let mut rod_block = out.rb_mut().submatrix_mut(0, 0, nr, nr);
        self.rod.add_tangent(q, v, c_k, c_d, rod_block.rb_mut());
        self.rod.add_point_force_tangent(
            RodPoint::B,
            q,
            Vector2::new(lambda[0], lambda[1]),
            c_k,
            rod_block.rb_mut(),
        );
        self.rod.add_point_force_tangent(
            RodPoint::C,
            q,
            Vector2::new(lambda[2], lambda[3]),
            c_k,
            rod_block,
        );
    }
}
