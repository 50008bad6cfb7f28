//! The segment chain on its lowest modes: the chain's coordinates `q` (module documentation of
//! [`super::rod`]) restricted to the rigid motions and the `n` lowest pinned-pinned bending
//! modes of the linearized chain ([`super::linear`]),
//! `q = T r`, `r = [x_B, y_B, alpha, p_1 .. p_n]`:
//! - `x_B`, `y_B`: the chain's own first two coordinates, the start `S_0` of segment 0 (pin B
//!   without shear slides; with them the modes move `S_0` across B's end slide);
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
use super::modal_direct_evaluation::{Plain, Trig, MAX_REDUCED};
use super::rod::SegmentRod;
use crate::error::ModelError;
use crate::rod::body::{RodBody, RodPoint};

/// The chain on its modes keeps every bending mode up to this multiple of its first bending
/// frequency (at least `rod.modes` of them): the response of the modes left out has no static
/// correction here. Measured on the random rods in docs/physics.md, "Rod model 3: the segment
/// chain on its modes".
pub const BAND_FACTOR: f64 = 20.0;

/// The number of bending modes the chain on its modes keeps: `modes`, or more, every pinned
/// bending mode of `chain` up to [`BAND_FACTOR`] times the first (at most the chain's own count).
pub fn band_modes(chain: &SegmentRod, modes: usize) -> usize {
    let factor = BAND_FACTOR;
    let hz = chain.bending_frequencies_hz();
    let Some(&first) = hz.first() else {
        return modes;
    };
    let in_band = hz.iter().filter(|&&f| f <= factor * first).count();
    modes.max(in_band.min(hz.len())).min(MAX_REDUCED - 4)
}

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
    /// The plain chain's angles at the last coordinates ([`Plain::angles`]).
    trig: Trig,
}

/// The segment chain restricted to its rigid motions and lowest bending modes (module
/// documentation).
pub struct ModalSegmentRod {
    chain: SegmentRod,
    /// `T`, the chain's coordinates (rows) over the reduced ones (columns).
    basis: Mat<f64>,
    /// The retained modes' circular frequencies, rad/s: the bending modes, then the axial ones.
    omega: Vec<f64>,
    /// The number of retained axial modes (the last columns of `T`).
    axial: usize,
    /// The retained modes' damping `C_r,ii`, 1/s (the diagonal of `T^T C T` on the modes of
    /// unit modal mass), computed once at construction.
    modal_damping: Vec<f64>,
    /// The direct evaluation in reduced coordinates, for a chain without end body rotations
    /// ([`super::modal_direct_evaluation`]); the projection of the chain's own functions otherwise.
    plain: Option<Plain>,
    scratch: RefCell<Scratch>,
}

impl ModalSegmentRod {
    /// The chain `chain` on its `modes` lowest pinned-pinned bending modes and, where it has
    /// axial springs, its `axial` lowest axial modes held at B with the slider's
    /// `slider_mass` (kg) at C ([`LinearizedChain::loaded_axial_modes`]; at least one there).
    /// Refused where the chain has fewer modes.
    pub fn new(
        chain: SegmentRod,
        modes: usize,
        axial: usize,
        slider_mass: f64,
    ) -> Result<ModalSegmentRod, ModelError> {
        let axial = if chain.has_axial_springs() {
            axial.max(1)
        } else {
            0
        };
        if modes == 0 {
            return Err(ModelError::InvalidParameter {
                name: "rod.modes",
                value: 0.0,
                allowed: "at least 1 with rod.model = modal_segments".into(),
            });
        }
        let n_full = chain.n_coordinates();
        let linear = LinearizedChain::new(&chain);
        let (mut omega2, mut shapes) = linear.pinned_bending_modes(modes, n_full)?;
        if axial > 0 {
            let (w2, a) = linear.loaded_axial_modes(axial, slider_mass, n_full)?;
            omega2.extend(w2);
            shapes = Mat::from_fn(n_full, modes + axial, |i, j| {
                if j < modes {
                    shapes[(i, j)]
                } else {
                    a[(i, j - modes)]
                }
            });
        }
        let n = 3 + modes + axial;
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
        for j in 0..modes + axial {
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
            trig: Trig::new(n, chain.n_segments()),
        });
        let mut rod = ModalSegmentRod {
            chain,
            basis,
            omega: omega2.iter().map(|w2| w2.sqrt()).collect(),
            axial,
            modal_damping: Vec::new(),
            plain: None,
            scratch,
        };
        let (stiffness, damping) = rod.spring_matrices();
        rod.modal_damping = (3..n).map(|c| damping[c * n + c]).collect();
        let plain = !rod.chain.has_axial_springs()
            && !rod.chain.has_end_rotation(0)
            && !rod.chain.has_end_rotation(1)
            && n <= MAX_REDUCED;
        if plain {
            let basis = &rod.basis;
            rod.plain = Some(Plain::new(
                &rod.chain,
                n,
                |row, c| basis[(row, c)],
                stiffness,
                damping,
            ));
        }
        Ok(rod)
    }

    /// `K_r = T^T K T` and `C_r = T^T C T` (row-major), from the chain's forces: its springs
    /// and dampers are linear in the coordinates and velocities, the velocity products
    /// quadratic, so central differences at the straight chain give them exactly (to round-off).
    fn spring_matrices(&self) -> (Vec<f64>, Vec<f64>) {
        let n = self.basis.ncols();
        let (mut stiffness, mut damping) = (vec![0.0; n * n], vec![0.0; n * n]);
        let zero = vec![0.0; n];
        let (mut plus, mut minus) = (vec![0.0; n], vec![0.0; n]);
        for d in 0..n {
            let mut x = zero.clone();
            x[d] = 1e-3;
            self.generic_forces(&x, &zero, &mut plus);
            x[d] = -1e-3;
            self.generic_forces(&x, &zero, &mut minus);
            for c in 0..n {
                stiffness[c * n + d] = -(plus[c] - minus[c]) / 2e-3;
            }
            x[d] = 1e-3;
            self.generic_forces(&zero, &x, &mut plus);
            x[d] = -1e-3;
            self.generic_forces(&zero, &x, &mut minus);
            for c in 0..n {
                damping[c * n + d] = -(plus[c] - minus[c]) / 2e-3;
            }
        }
        (stiffness, damping)
    }

    /// The projection `T^T Q(T r, T r')` of the chain's forces.
    fn generic_forces(&self, r: &[f64], rv: &[f64], out: &mut [f64]) {
        let mut s = self.scratch.borrow_mut();
        let Scratch { q, v, f, .. } = &mut *s;
        self.expand(r, q);
        self.expand(rv, v);
        f.iter_mut().for_each(|x| *x = 0.0);
        self.chain.forces(q, v, f);
        out[..self.basis.ncols()].iter_mut().for_each(|x| *x = 0.0);
        self.add_projected(f, out);
    }

    /// Whether the direct evaluation is in use (a plain chain).
    pub fn is_direct(&self) -> bool {
        self.plain.is_some()
    }

    /// `f(plain, trig)` with the angles at `r`, where the chain is plain.
    fn direct<R>(&self, r: &[f64], f: impl FnOnce(&Plain, &mut Trig) -> R) -> Option<R> {
        let plain = self.plain.as_ref()?;
        let mut s = self.scratch.borrow_mut();
        plain.angles(r, &mut s.trig);
        Some(f(plain, &mut s.trig))
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

    /// `x_B`, `y_B` translate every point, `alpha` turns every segment (module documentation).
    fn frame_coordinates(&self) -> Option<[usize; 3]> {
        Some([0, 1, 2])
    }

    fn frame_form(&self) -> bool {
        true
    }

    /// The direct evaluation costs like the reduced coordinates; the projection works on the
    /// chain's own (`O(N_full^2)` a mass matrix).
    fn work_coordinates(&self) -> usize {
        if self.plain.is_some() {
            self.n_coordinates()
        } else {
            self.chain.n_coordinates()
        }
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

    /// The axial modes, the last elastic coordinates.
    fn axial_mode_indices(&self) -> Vec<usize> {
        let n = self.omega.len();
        (n - self.axial..n).collect()
    }

    /// The pinned modes with the chain's stiffness-proportional dampers: `(w^2, C_r,ii)` of the
    /// reduced spring and damper matrices (diagonal on modes of unit modal mass).
    fn modal_oscillators(&self) -> Option<Vec<(f64, f64)>> {
        Some(
            self.omega
                .iter()
                .zip(&self.modal_damping)
                .map(|(w, c)| (w * w, *c))
                .collect(),
        )
    }

    fn mass(&self, r: &[f64], mut out: MatMut<'_, f64>) {
        if self.direct(r, |p, t| p.mass(t, out.rb_mut())).is_some() {
            return;
        }
        let mut s = self.scratch.borrow_mut();
        let Scratch { q, m, at, .. } = &mut *s;
        self.expand(r, q);
        m.fill(0.0);
        self.chain.mass(q, m.as_mut());
        out.fill(0.0);
        self.add_congruent(m, at, out.rb_mut());
    }

    fn forces(&self, r: &[f64], rv: &[f64], out: &mut [f64]) {
        if self.direct(r, |p, t| p.forces(r, rv, t, out)).is_none() {
            self.generic_forces(r, rv, out);
        }
    }

    fn mass_and_forces(&self, r: &[f64], rv: &[f64], mut m: MatMut<'_, f64>, f: &mut [f64]) {
        let direct = self.direct(r, |p, t| p.mass_and_forces(r, rv, t, m.rb_mut(), f));
        if direct.is_none() {
            self.mass(r, m);
            self.forces(r, rv, f);
        }
    }

    fn add_gravity(&self, r: &[f64], g: Vector2<f64>, out: &mut [f64]) {
        if self.direct(r, |p, t| p.add_gravity(t, g, out)).is_some() {
            return;
        }
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
        if let Some(x) = self.direct(r, |plain, t| plain.point(p, r, t)) {
            return x;
        }
        self.with_q(r, |c, q| c.point(p, q))
    }

    fn point_at(&self, x: f64, r: &[f64]) -> Vector2<f64> {
        self.with_q(r, |c, q| c.point_at(x, q))
    }

    fn points(&self, r: &[f64]) -> [Vector2<f64>; 3] {
        if let Some(x) = self.direct(r, |plain, t| {
            [RodPoint::B, RodPoint::C, RodPoint::Mid].map(|p| plain.point(p, r, t))
        }) {
            return x;
        }
        self.with_q(r, |c, q| c.points(q))
    }

    fn mid_deflection(&self, r: &[f64]) -> f64 {
        if self.plain.is_some() {
            return crate::rod::body::chord_distance(self.points(r));
        }
        self.with_q(r, |c, q| c.mid_deflection(q))
    }

    fn point_jacobian(&self, p: RodPoint, r: &[f64], mut out: MatMut<'_, f64>) {
        if self
            .direct(r, |plain, t| plain.point_jacobian(p, t, out.rb_mut()))
            .is_some()
        {
            return;
        }
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
        if let Some(a) = self.direct(r, |plain, t| plain.point_bias(p, rv, t)) {
            return a;
        }
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
        let hz = |w: &[f64]| {
            w.iter()
                .map(|w| format!("{:.1}", w / (2.0 * std::f64::consts::PI)))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let bending = self.omega.len() - self.axial;
        let axial = match self.axial {
            0 => String::new(),
            1 => format!(
                " and its slider-rod axial mode ({} Hz)",
                hz(&self.omega[bending..])
            ),
            n => format!(" and {n} axial modes ({} Hz)", hz(&self.omega[bending..])),
        };
        format!(
            "segment chain of {} segments on its {bending} lowest bending modes ({} Hz){axial}",
            self.chain.n_segments(),
            hz(&self.omega[..bending]),
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beam::section_table::EndBody;
    use crate::beam::{RodDefinition, RodProperties};

    /// The direct evaluation is the projection of the chain's own functions: mass, forces,
    /// gravity, points, Jacobians and velocity products at bent, moving states, with end masses
    /// at both pins and a damped chain, with and without shear slides, even and odd segment
    /// counts (the midpoint on a joint or inside a segment).
    #[test]
    fn direct_evaluation_is_the_projection() {
        let props = RodProperties::cdi_benchmark();
        let definition = RodDefinition {
            properties: props,
            table: None,
            shear_modulus: None,
            uniform_shear_area: None,
            big_end: EndBody {
                mass: 0.03,
                inertia: 0.0,
            },
            small_end: EndBody {
                mass: 0.02,
                inertia: 0.0,
            },
        };
        for shear in [None, Some(props.youngs_modulus / 2.6)] {
            for segments in [12, 13] {
                check_direct(
                    &RodDefinition {
                        shear_modulus: shear,
                        ..definition.clone()
                    },
                    segments,
                );
            }
        }
    }

    fn check_direct(definition: &RodDefinition, segments: usize) {
        let build = || {
            let chain = SegmentRod::from_definition(definition, segments, 0.02, false).unwrap();
            ModalSegmentRod::new(chain, 4, 0, 0.0).unwrap()
        };
        let direct = build();
        let mut projected = build();
        assert!(direct.is_direct());
        projected.plain = None;
        let n = direct.n_coordinates();
        for trial in 0..5 {
            let x = trial as f64;
            let r: Vec<f64> = (0..n)
                .map(|i| match i {
                    0 | 1 => 0.1 * (x + i as f64).sin(),
                    2 => 0.7 * x - 1.0,
                    _ => 0.02 * (1.3 * x + i as f64).cos(),
                })
                .collect();
            let v: Vec<f64> = (0..n)
                .map(|i| match i {
                    0 | 1 => 3.0 * (x + 2.0 * i as f64).cos(),
                    2 => 150.0 + 10.0 * x,
                    _ => 5.0 * (0.7 * x + i as f64).sin(),
                })
                .collect();
            let close = |a: f64, b: f64, scale: f64, what: &str| {
                let what = format!(
                    "{what} ({segments} segments, shear {})",
                    definition.shear_modulus.is_some()
                );
                assert!((a - b).abs() <= 1e-11 * scale, "{what}: {a} vs {b}");
            };
            let (mut ma, mut mb) = (Mat::<f64>::zeros(n, n), Mat::<f64>::zeros(n, n));
            direct.mass(&r, ma.as_mut());
            projected.mass(&r, mb.as_mut());
            let scale = (0..n).map(|i| mb[(i, i)].abs()).fold(0.0, f64::max);
            for i in 0..n {
                for j in 0..n {
                    close(
                        ma[(i, j)],
                        mb[(i, j)],
                        scale,
                        &format!(
                            "mass ({i}, {j}), {segments} segments, shear {}",
                            definition.shear_modulus.is_some()
                        ),
                    );
                }
            }
            let (mut fa, mut fb) = (vec![0.0; n], vec![0.0; n]);
            direct.forces(&r, &v, &mut fa);
            projected.forces(&r, &v, &mut fb);
            let g = Vector2::new(0.3, -9.81);
            direct.add_gravity(&r, g, &mut fa);
            projected.add_gravity(&r, g, &mut fb);
            let scale = fb.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            for (a, b) in fa.iter().zip(&fb) {
                close(*a, *b, scale, "forces");
            }
            for p in [RodPoint::B, RodPoint::C, RodPoint::Mid] {
                let (xa, xb) = (direct.point(p, &r), projected.point(p, &r));
                close((xa - xb).norm(), 0.0, 1.0, "point");
                let (mut ja, mut jb) = (Mat::<f64>::zeros(2, n), Mat::<f64>::zeros(2, n));
                direct.point_jacobian(p, &r, ja.as_mut());
                projected.point_jacobian(p, &r, jb.as_mut());
                let scale = (0..n)
                    .map(|j| jb[(0, j)].abs().max(jb[(1, j)].abs()))
                    .fold(1.0, f64::max);
                for i in 0..2 {
                    for j in 0..n {
                        close(ja[(i, j)], jb[(i, j)], scale, "jacobian");
                    }
                }
                let (aa, ab) = (
                    direct.point_bias_acceleration(p, &r, &v),
                    projected.point_bias_acceleration(p, &r, &v),
                );
                close((aa - ab).norm(), 0.0, ab.norm().max(1.0), "bias");
            }
            close(
                direct.mid_deflection(&r),
                projected.mid_deflection(&r),
                1.0,
                "v_mid",
            );
            // Mass and forces in one pass, and C's velocity products it leaves behind.
            let (mut mc, mut fc) = (Mat::<f64>::zeros(n, n), vec![0.0; n]);
            direct.mass_and_forces(&r, &v, mc.as_mut(), &mut fc);
            projected.forces(&r, &v, &mut fb);
            for i in 0..n {
                close(fc[i], fb[i], scale.max(1.0), "forces in one pass");
                for j in 0..n {
                    close(mc[(i, j)], mb[(i, j)], mb[(0, 0)], "mass in one pass");
                }
            }
            // C's velocity products: left behind for these velocities, computed for others.
            let w: Vec<f64> = v.iter().map(|x| 0.5 * x).collect();
            for (u, what) in [
                (&v, "C's bias after one pass"),
                (&w, "C's bias at other velocities"),
            ] {
                let (aa, ab) = (
                    direct.point_bias_acceleration(RodPoint::C, &r, u),
                    projected.point_bias_acceleration(RodPoint::C, &r, u),
                );
                close((aa - ab).norm(), 0.0, ab.norm().max(1.0), what);
            }
        }
    }
}
