//! The segment chain on its lowest modes: the chain's coordinates `q` (module documentation of
//! [`super::rod`]) restricted to the rigid motions and the `n` lowest pinned-pinned bending
//! modes of the linearized chain ([`super::linear`]),
//! `q = T r`, `r = [x_B, y_B, alpha, p_1 .. p_n]`:
//! - `x_B`, `y_B`: pin B's position (the chain's own first two coordinates);
//! - `alpha`: a rigid rotation, every segment angle and end body rotation `alpha`;
//! - `p_i`: the amplitude of bending mode `a_i` (unit modal mass, `a_i^T M_0 a_i = 1`) over the
//!   angles, shear slides and end body rotations.
//!
//! The kinematics stay the chain's, exact for any rotation of its segments: only the shape of
//! the angle field is restricted (a Ritz projection of the chain's equations, J. N. Reddy,
//! "Energy Principles and Variational Methods in Applied Mechanics", Wiley 2002, ch. 7: `T^T M(T r)
//! T r'' = T^T Q(T r, T r')`). The bending modes' shapes are those of the straight rod; their
//! stiffening by the axial force, the foreshortening of the chord and the nonlinear inertia
//! come from the chain's exact kinematics. The modes left out are the chain's stiff ones, so
//! an explicit integrator's step is set by the retained ones.

use std::cell::RefCell;

use faer::reborrow::ReborrowMut;
use faer::{Mat, MatMut};
use nalgebra::Vector2;

use super::linear::LinearizedChain;
use super::rod::SegmentRod;
use crate::error::ModelError;
use crate::rod::body::{RodBody, RodPoint};

/// Buffers over the chain's coordinates, sized at construction.
struct Scratch {
    q: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    f: Vec<f64>,
    m: Mat<f64>,
    /// `A T` of [`ModalSegmentRod::add_congruent`].
    at: Mat<f64>,
    j: Mat<f64>,
}

/// The segment chain restricted to its rigid motions and lowest bending modes (module
/// documentation).
pub struct ModalSegmentRod {
    chain: SegmentRod,
    /// `T`, the chain's coordinates (rows) over the reduced ones (columns).
    basis: Mat<f64>,
    /// The retained modes' circular frequencies, rad/s.
    omega: Vec<f64>,
    /// The retained modes' damping ratio times `2 omega` (modal damping), 1/s.
    scratch: RefCell<Scratch>,
}

impl ModalSegmentRod {
    /// The chain `chain` on its `modes` lowest pinned-pinned bending modes. Refused where the
    /// chain has axial springs (their modes are not among the bending ones) or fewer modes.
    pub fn new(chain: SegmentRod, modes: usize) -> Result<ModalSegmentRod, ModelError> {
        if chain.has_axial_springs() {
            return Err(ModelError::InvalidParameter {
                name: "rod.axial_springs",
                value: 1.0,
                allowed:
                    "off with rod.model = modal_segments (the modes are the chain's bending modes)"
                        .into(),
            });
        }
        if modes == 0 {
            return Err(ModelError::InvalidParameter {
                name: "rod.modes",
                value: 0.0,
                allowed: "at least 1 with rod.model = modal_segments".into(),
            });
        }
        let n_full = chain.n_coordinates();
        let (omega2, shapes) = LinearizedChain::new(&chain).pinned_bending_modes(modes, n_full)?;
        let n = 3 + modes;
        let mut basis = Mat::<f64>::zeros(n_full, n);
        basis[(0, 0)] = 1.0;
        basis[(1, 1)] = 1.0;
        for k in 0..chain.n_segments() {
            basis[(chain.theta_index(k), 2)] = 1.0;
        }
        for e in 0..2 {
            if chain.has_end_rotation(e) {
                basis[(chain.end_rotation_index(e), 2)] = 1.0;
            }
        }
        for j in 0..modes {
            for i in 0..n_full {
                basis[(i, 3 + j)] = shapes[(i, j)];
            }
        }
        let scratch = RefCell::new(Scratch {
            q: vec![0.0; n_full],
            v: vec![0.0; n_full],
            a: vec![0.0; n_full],
            f: vec![0.0; n_full],
            m: Mat::zeros(n_full, n_full),
            at: Mat::zeros(n_full, n),
            j: Mat::zeros(2, n_full),
        });
        Ok(ModalSegmentRod {
            chain,
            basis,
            omega: omega2.iter().map(|w2| w2.sqrt()).collect(),
            scratch,
        })
    }

    /// The chain underneath.
    pub fn chain(&self) -> &SegmentRod {
        &self.chain
    }

    /// `x = T r` into `out` (`r` may go on with coordinates of the mechanism's: the first
    /// `T`'s columns count).
    fn expand(&self, r: &[f64], out: &mut [f64]) {
        let t = &self.basis;
        for (i, o) in out.iter_mut().enumerate() {
            let mut s = 0.0;
            for (j, rj) in r[..t.ncols()].iter().enumerate() {
                s += t[(i, j)] * rj;
            }
            *o = s;
        }
    }

    /// `out += T^T x`.
    fn add_projected(&self, x: &[f64], out: &mut [f64]) {
        let t = &self.basis;
        for (j, o) in out[..t.ncols()].iter_mut().enumerate() {
            let mut s = 0.0;
            for (i, xi) in x.iter().enumerate() {
                s += t[(i, j)] * xi;
            }
            *o += s;
        }
    }

    /// `out += T^T A T` for the chain's `a` (n_full x n_full), through `A T` (the chain's rows
    /// once per column of `T`, skipping `T`'s zeros).
    fn add_congruent(&self, a: &Mat<f64>, at: &mut Mat<f64>, mut out: MatMut<'_, f64>) {
        let t = &self.basis;
        let (nf, n) = (t.nrows(), t.ncols());
        at.fill(0.0);
        for j in 0..n {
            for l in 0..nf {
                let tl = t[(l, j)];
                if tl == 0.0 {
                    continue;
                }
                for k in 0..nf {
                    at[(k, j)] += a[(k, l)] * tl;
                }
            }
        }
        for j in 0..n {
            for i in 0..n {
                let mut s = 0.0;
                for k in 0..nf {
                    s += t[(k, i)] * at[(k, j)];
                }
                out[(i, j)] += s;
            }
        }
    }

    fn with_q<R>(&self, r: &[f64], f: impl FnOnce(&SegmentRod, &[f64]) -> R) -> R {
        let mut s = self.scratch.borrow_mut();
        let mut q = std::mem::take(&mut s.q);
        self.expand(r, &mut q);
        let out = f(&self.chain, &q);
        s.q = q;
        out
    }

    fn with_qv<R>(
        &self,
        r: &[f64],
        rv: &[f64],
        f: impl FnOnce(&SegmentRod, &[f64], &[f64]) -> R,
    ) -> R {
        let mut s = self.scratch.borrow_mut();
        let (mut q, mut v) = (std::mem::take(&mut s.q), std::mem::take(&mut s.v));
        self.expand(r, &mut q);
        self.expand(rv, &mut v);
        let out = f(&self.chain, &q, &v);
        s.q = q;
        s.v = v;
        out
    }
}

impl RodBody for ModalSegmentRod {
    fn n_coordinates(&self) -> usize {
        self.basis.ncols()
    }

    fn coordinate_scale(&self, i: usize) -> f64 {
        match i {
            0 | 1 => self.chain.length(),
            2 => 1.0,
            // Unit modal mass: a displacement d is a modal amplitude of about d sqrt(m).
            _ => self.chain.length() * self.chain.total_mass().sqrt(),
        }
    }

    fn place_undeformed(
        &self,
        b: Vector2<f64>,
        c: Vector2<f64>,
        vb: Vector2<f64>,
        omega: f64,
        q: &mut [f64],
        v: &mut [f64],
    ) {
        let d = c - b;
        q.iter_mut().for_each(|x| *x = 0.0);
        v.iter_mut().for_each(|x| *x = 0.0);
        q[0] = b.x;
        q[1] = b.y;
        q[2] = d.y.atan2(d.x);
        v[0] = vb.x;
        v[1] = vb.y;
        v[2] = omega;
    }

    fn elastic_coordinates(&self) -> Option<std::ops::Range<usize>> {
        Some(3..self.basis.ncols())
    }

    fn elastic_circular_frequencies(&self) -> Option<Vec<f64>> {
        Some(self.omega.clone())
    }

    fn mass(&self, r: &[f64], mut out: MatMut<'_, f64>) {
        let mut s = self.scratch.borrow_mut();
        let Scratch { q, m, at, .. } = &mut *s;
        self.expand(r, q);
        m.fill(0.0);
        self.chain.mass(q, m.as_mut());
        out.fill(0.0);
        self.add_congruent(m, at, out.rb_mut());
    }

    fn forces(&self, r: &[f64], rv: &[f64], out: &mut [f64]) {
        let mut s = self.scratch.borrow_mut();
        let Scratch { q, v, f, .. } = &mut *s;
        self.expand(r, q);
        self.expand(rv, v);
        f.iter_mut().for_each(|x| *x = 0.0);
        self.chain.forces(q, v, f);
        out[..self.basis.ncols()].iter_mut().for_each(|x| *x = 0.0);
        self.add_projected(f, out);
    }

    fn add_gravity(&self, r: &[f64], g: Vector2<f64>, out: &mut [f64]) {
        let mut s = self.scratch.borrow_mut();
        let Scratch { q, f, .. } = &mut *s;
        self.expand(r, q);
        f.iter_mut().for_each(|x| *x = 0.0);
        self.chain.add_gravity(q, g, f);
        self.add_projected(f, out);
    }

    fn section_loads(
        &self,
        r: &[f64],
        rv: &[f64],
        rdd: &[f64],
        g: Vector2<f64>,
        force_c: Vector2<f64>,
    ) -> crate::rod::SectionLoads {
        let mut s = self.scratch.borrow_mut();
        let Scratch { q, v, a, .. } = &mut *s;
        self.expand(r, q);
        self.expand(rv, v);
        self.expand(rdd, a);
        self.chain.section_loads(q, v, a, g, force_c)
    }

    fn add_tangent(&self, r: &[f64], rv: &[f64], c_k: f64, c_d: f64, out: MatMut<'_, f64>) {
        let mut s = self.scratch.borrow_mut();
        let Scratch { q, v, m, at, .. } = &mut *s;
        self.expand(r, q);
        self.expand(rv, v);
        m.fill(0.0);
        self.chain.add_tangent(q, v, c_k, c_d, m.as_mut());
        self.add_congruent(m, at, out);
    }

    fn point(&self, p: RodPoint, r: &[f64]) -> Vector2<f64> {
        self.with_q(r, |c, q| c.point(p, q))
    }

    fn point_at(&self, x: f64, r: &[f64]) -> Vector2<f64> {
        self.with_q(r, |c, q| c.point_at(x, q))
    }

    fn points(&self, r: &[f64]) -> [Vector2<f64>; 3] {
        self.with_q(r, |c, q| c.points(q))
    }

    fn mid_deflection(&self, r: &[f64]) -> f64 {
        self.with_q(r, |c, q| c.mid_deflection(q))
    }

    fn point_jacobian(&self, p: RodPoint, r: &[f64], mut out: MatMut<'_, f64>) {
        let mut s = self.scratch.borrow_mut();
        let Scratch { q, j, .. } = &mut *s;
        self.expand(r, q);
        j.fill(0.0);
        self.chain.point_jacobian(p, q, j.as_mut());
        let t = &self.basis;
        for row in 0..2 {
            for c in 0..t.ncols() {
                let mut sum = 0.0;
                for k in 0..t.nrows() {
                    sum += j[(row, k)] * t[(k, c)];
                }
                out[(row, c)] = sum;
            }
        }
    }

    fn point_bias_acceleration(&self, p: RodPoint, r: &[f64], rv: &[f64]) -> Vector2<f64> {
        // T is constant: the velocity-product part is the chain's at v = T r'.
        self.with_qv(r, rv, |c, q, v| c.point_bias_acceleration(p, q, v))
    }

    fn add_point_force_tangent(
        &self,
        p: RodPoint,
        r: &[f64],
        force: Vector2<f64>,
        c: f64,
        out: MatMut<'_, f64>,
    ) {
        let mut s = self.scratch.borrow_mut();
        let Scratch { q, m, at, .. } = &mut *s;
        self.expand(r, q);
        m.fill(0.0);
        self.chain
            .add_point_force_tangent(p, q, force, c, m.as_mut());
        self.add_congruent(m, at, out);
    }

    fn kinetic_energy(&self, r: &[f64], rv: &[f64]) -> f64 {
        self.with_qv(r, rv, |c, q, v| c.kinetic_energy(q, v))
    }

    fn strain_energy(&self, r: &[f64]) -> f64 {
        self.with_q(r, |c, q| c.strain_energy(q))
    }

    fn linear_momentum(&self, r: &[f64], rv: &[f64]) -> Vector2<f64> {
        self.with_qv(r, rv, |c, q, v| c.linear_momentum(q, v))
    }

    fn frequencies_hz(&self) -> &[f64] {
        self.chain.frequencies_hz()
    }

    fn describe(&self) -> String {
        let hz: Vec<String> = self
            .omega
            .iter()
            .map(|w| format!("{:.1}", w / (2.0 * std::f64::consts::PI)))
            .collect();
        format!(
            "segment chain of {} segments on its {} lowest bending modes ({} Hz)",
            self.chain.n_segments(),
            self.omega.len(),
            hz.join(", ")
        )
    }

    fn length(&self) -> f64 {
        self.chain.length()
    }

    fn total_mass(&self) -> f64 {
        self.chain.total_mass()
    }

    fn highest_frequency_hz(&self) -> f64 {
        self.omega.iter().copied().fold(0.0, f64::max) / (2.0 * std::f64::consts::PI)
    }
}
