//! The finite segment rod body (seed 002, `002_e6c2c81d944c25fc.txt`, "Flexibility effects"
//! and "Illustrations/convergence"; physics.md, "Rod model 2: finite segments").
//!
//! # Model
//! The rod of length `L` (m) is cut into `N` rigid segments `k = 0..N-1` (0-based here; seed
//! 002 counts from 1) of length `l = L/N`, mass `m = rho A l` (kg) and centroidal inertia
//! `I_c = m l^2 / 12` (kg m^2). Segment `k` and `k+1` meet in joint `k` (`k = 0..N-2`): a
//! revolute joint with a rotational spring `k_r` (N m/rad) and damper `c_r` (N m s/rad) and,
//! with `rod.axial_springs`, a prismatic joint along segment `k` with an axial spring
//! `k_a = E A / l` (N/m) and damper `c_a` (N s/m). As in seed 002, flexibility and damping live
//! in the joints only ("a lumped parameter method with the flexibility and damping modelled at
//! the joints"); planar, so one angle per segment and no Euler parameters (seed 002 says so).
//!
//! # Coordinates
//! `q = [x_B, y_B, theta_0, .., theta_{N-1}, s_0, .., s_{N-2}]`: the free end B of segment 0
//! (global, m), the absolute segment angles (rad, counter-clockwise from global x), and with
//! axial springs the slide `s_j` (m) of joint `j` (its extension). With
//! `e_k = (cos theta_k, sin theta_k)`, `n_k = (-sin theta_k, cos theta_k)` and the joint-to-joint
//! lengths `L_j = l + s_j` (`L_j = l` without axial springs), the material point at distance
//! `xi` in `[0, l]` from the start of segment `k` is
//! `r_k(xi) = B + sum_{j<k} L_j e_j + xi e_k`.
//! B is `r_0(0)`, C is `r_{N-1}(l)`, the midpoint is the material point at arc length `L/2`
//! (the centre of the middle segment for odd `N`, the start of segment `N/2` for even `N`).
//!
//! Seed 002 uses relative coordinates (the joint rotations `phi_k = theta_k - theta_{k-1}`) as
//! generalized speeds with Kane's equations. Absolute angles are the linear change
//! `theta = T phi` (`T` lower triangular of ones); Kane's equations in the relative speeds are
//! `T^T` times the equations here, so the dynamics are the same. The joint springs, single
//! entries in relative coordinates (seed 002's decoupling), are tridiagonal here; in exchange
//! the mass matrix stays as well conditioned as the chain itself and the pin constraint rows
//! are plain.
//!
//! # Equations (Lagrange, equivalently Kane)
//! The centroid of segment `k` is `g_k = r_k(l/2)`, its velocity `g_k' = J_k q'` with the
//! columns of the partial velocities `J_k` (Kane's `v_{kl}`):
//! `d g_k / d(x_B, y_B) = I`, `d g_k / d theta_j = L_j n_j` (`j < k`), `= (l/2) n_k` (`j = k`),
//! `d g_k / d s_j = e_j` (`j < k`), zero otherwise; the partial angular velocity of segment `k`
//! is the unit vector of `theta_k`. Kinetic energy
//! `T = 1/2 sum_k (m |g_k'|^2 + I_c theta_k'^2) = 1/2 q'^T M q'` with
//! `M = sum_k (m J_k^T J_k + I_c u_k u_k^T)`, dense in the angles. With `a_j = m (N - 1 - j)`
//! (mass beyond segment `j`), `h_j = m l / 2 + a_j L_j` and `c_ij = cos(theta_i - theta_j)`:
//! - `M_BB = N m I`, `M_{B theta_j} = h_j n_j`, `M_{B s_j} = a_j e_j`;
//! - `M_{theta_i theta_i} = m l^2 / 3 + a_i L_i^2`, `M_{theta_i theta_j} = L_i h_j c_ij` (`i < j`);
//! - `M_{theta_i s_j} = a_j L_i sin(theta_j - theta_i)` (`i < j`), `0` (`i = j`),
//!   `h_i sin(theta_j - theta_i)` (`i > j`);
//! - `M_{s_i s_j} = a_{max(i,j)} c_ij`.
//!
//! Quadratic velocity vector (Kane's generalized inertia force minus its `M q''` part):
//! `Q_v = -sum_k m J_k^T gamma_k`, with the velocity-product acceleration of the centroid
//! `gamma_k = (J_k' q') = sum_{j<k} (2 s_j' theta_j' n_j - L_j theta_j'^2 e_j) - (l/2) theta_k'^2 e_k`
//! (a rigid planar segment has no gyroscopic moment). With the downstream sums
//! `G_i = sum_{k>i} gamma_k`:
//! `Q_v,B = -m sum_k gamma_k`, `Q_v,theta_i = -m n_i . ((l/2) gamma_i + L_i G_i)`,
//! `Q_v,s_j = -m e_j . G_j`, computed in O(N). It equals `-(M' q' - dT/dq)` of Lagrange's
//! equations (checked in tests/segments.rs).
//!
//! Joint forces (seed 002 eq. 33-36: one spring or damper component per generalized force in
//! relative coordinates): the moment of joint `j` on segment `j`,
//! `tau_j = k_r (theta_{j+1} - theta_j) + c_r (theta_{j+1}' - theta_j')`, enters
//! `Q_theta_j += tau_j`, `Q_theta_{j+1} -= tau_j`; the axial force `-(k_a s_j + c_a s_j')`
//! enters `Q_s_j`. Strain energy
//! `U = sum_j (k_r (theta_{j+1} - theta_j)^2 + k_a s_j^2) / 2`.
//!
//! # Spring and damper constants
//! `k_r = E I / l` (physics.md): the joint rotation `theta_{j+1} - theta_j` is the curvature
//! integrated over the length `l` a joint stands for, so `k_r (Delta theta)^2 / 2 =
//! E I (Delta theta / l)^2 l / 2` is the beam's bending energy of that length. With the joint
//! deflections `w_j`, the joint rotations are the central second difference of `w` times `l`,
//! and the segments' kinetic energy is the consistent mass of a piecewise linear `w`; the
//! errors of the two cancel at second order. Pinned-pinned, the modes are sinusoidal and
//! `omega_n^2 = 48 E I sin^4(n pi / 2N) / (rho A l^4 (2 + cos(n pi / N)))
//! = (n pi / L)^4 E I / (rho A) (1 + O((n pi / N)^4))`: fourth order in `l` (tests/segments.rs
//! checks the closed form and the order), so no other spring constant is needed. A clamped end
//! (not used by the mechanism, whose ends are pinned) needs a root spring `2 E I / l` to the
//! support for second order (mirror ghost segment; tests/segments.rs, rotating cantilever).
//! `k_a = E A / l` is the exact stiffness of a bar of length `l`.
//!
//! Dampers are stiffness proportional, `c_r = beta_r k_r`, `c_a = beta_a k_a`. In the
//! linearized chain `C = beta K`, so mode `n` has damping ratio `beta omega_n / 2`; choosing
//! `beta_r = 2 zeta / omega_1` (first pinned-pinned bending mode of the chain, computed in
//! [`SegmentRod::new`]) gives that mode exactly `rod.damping_ratio = zeta`, and the higher modes
//! more (as in a material with Kelvin-Voigt damping). `beta_a = 2 zeta / omega_a1` with the first
//! free-free axial mode of the chain (the closed form of [`super::axial_chain_frequencies_hz`]).
//!
//! Geometric exactness: the segments move rigidly with the exact kinematics, so the axial
//! force in the chain (carried by the joints) acts on bending by itself: [`RodBody::forces`]
//! ignores its `a` and `end_force_c` arguments.
//!
//! No allocation in the per-iteration methods: everything is precomputed in [`SegmentRod::new`]
//! and the loops recompute `cos`/`sin` of the angles on the fly.

use faer::MatMut;
use nalgebra::Vector2;

use super::linear::LinearizedChain;
use super::validate_segments;
use crate::beam::RodProperties;
use crate::error::{require_non_negative, ModelError};
use crate::rod::body::{RodBody, RodPoint};

/// Unit vectors `(e, n)` of angle `theta`: along the segment and 90 degrees to its left.
#[inline]
fn axes(theta: f64) -> (Vector2<f64>, Vector2<f64>) {
    let (s, c) = theta.sin_cos();
    (Vector2::new(c, s), Vector2::new(-s, c))
}

/// The finite segment rod.
pub struct SegmentRod {
    /// Number of segments N.
    n_seg: usize,
    /// Prismatic joints with axial springs (coordinates `s_j`).
    axial: bool,
    /// Rod length L, m.
    length: f64,
    /// Segment length l = L/N, m.
    seg_len: f64,
    /// Segment mass m = rho A l, kg.
    seg_mass: f64,
    /// Centroidal inertia of a segment, m l^2 / 12, kg m^2.
    seg_inertia: f64,
    /// Rotational spring k_r = E I / l, N m/rad, and damper c_r, N m s/rad.
    k_rot: f64,
    c_rot: f64,
    /// Axial spring k_a = E A / l, N/m, and damper c_a, N s/m (0 without axial springs).
    k_ax: f64,
    c_ax: f64,
    /// The material midpoint: (segment, distance from its start in m).
    mid: (usize, f64),
    /// Pinned-pinned frequencies of the linearized chain, Hz: all, bending, axial.
    frequencies: Vec<f64>,
    bending: Vec<f64>,
    axial_modes: Vec<f64>,
}

impl SegmentRod {
    /// Build the chain of `n_segments` segments of a uniform rod. `damping_ratio` is the
    /// damping ratio of the first pinned-pinned bending mode (and of the first free-free axial
    /// mode for the axial dampers); `axial_springs` adds the prismatic joints.
    pub fn new(
        props: RodProperties,
        n_segments: usize,
        damping_ratio: f64,
        axial_springs: bool,
    ) -> Result<SegmentRod, ModelError> {
        props.validate()?;
        validate_segments(n_segments)?;
        require_non_negative("rod.damping_ratio", damping_ratio)?;
        let n = n_segments;
        let l = props.length / n as f64;
        let m = props.mass_per_length() * l;
        let half = 0.5 * props.length;
        let k_mid = ((half / l).floor() as usize).min(n - 1);
        let mut rod = SegmentRod {
            n_seg: n,
            axial: axial_springs,
            length: props.length,
            seg_len: l,
            seg_mass: m,
            seg_inertia: m * l * l / 12.0,
            k_rot: props.bending_rigidity() / l,
            c_rot: 0.0,
            k_ax: if axial_springs {
                props.axial_rigidity() / l
            } else {
                0.0
            },
            c_ax: 0.0,
            mid: (k_mid, half - k_mid as f64 * l),
            frequencies: Vec::new(),
            bending: Vec::new(),
            axial_modes: Vec::new(),
        };
        let chain = LinearizedChain::new(&rod);
        rod.bending = chain.pinned_bending_hz()?;
        if axial_springs {
            rod.axial_modes = chain.pinned_axial_hz()?;
        }
        let mut all: Vec<f64> = rod
            .bending
            .iter()
            .chain(&rod.axial_modes)
            .copied()
            .collect();
        all.sort_by(|a, b| a.total_cmp(b));
        rod.frequencies = all;
        if let Some(f1) = rod.bending.first() {
            rod.c_rot = 2.0 * damping_ratio / (2.0 * std::f64::consts::PI * f1) * rod.k_rot;
        }
        if axial_springs && n >= 2 {
            let w1 = 2.0 * (rod.k_ax / m).sqrt() * (std::f64::consts::PI / (2.0 * n as f64)).sin();
            rod.c_ax = 2.0 * damping_ratio / w1 * rod.k_ax;
        }
        Ok(rod)
    }

    /// Number of segments N.
    pub fn n_segments(&self) -> usize {
        self.n_seg
    }

    /// Whether the joints carry axial springs (slide coordinates `s_j`).
    pub fn has_axial_springs(&self) -> bool {
        self.axial
    }

    /// Segment length l, m; segment mass m, kg.
    pub fn segment(&self) -> (f64, f64) {
        (self.seg_len, self.seg_mass)
    }

    /// Joint spring constants `(k_r, k_a)`: N m/rad and N/m (`k_a = 0` without axial springs).
    pub fn spring_constants(&self) -> (f64, f64) {
        (self.k_rot, self.k_ax)
    }

    /// Joint damper constants `(c_r, c_a)`: N m s/rad and N s/m.
    pub fn damper_constants(&self) -> (f64, f64) {
        (self.c_rot, self.c_ax)
    }

    /// Pinned-pinned bending frequencies of the linearized chain, Hz, ascending (N - 1).
    pub fn bending_frequencies_hz(&self) -> &[f64] {
        &self.bending
    }

    /// Fixed-fixed axial frequencies of the linearized chain, Hz, ascending (empty without
    /// axial springs).
    pub fn axial_frequencies_hz(&self) -> &[f64] {
        &self.axial_modes
    }

    /// Index of `theta_k` in `q`.
    #[inline]
    pub fn theta_index(&self, k: usize) -> usize {
        2 + k
    }

    /// Index of `s_j` in `q` (axial springs only).
    #[inline]
    pub fn stretch_index(&self, j: usize) -> usize {
        2 + self.n_seg + j
    }

    /// Number of slide coordinates (N - 1 with axial springs, else 0).
    #[inline]
    fn n_stretch(&self) -> usize {
        if self.axial {
            self.n_seg - 1
        } else {
            0
        }
    }

    /// `L_j = l + s_j` and `s_j'` of joint `j` (`l`, 0 past the last joint or without springs).
    #[inline]
    fn lever(&self, j: usize, q: &[f64], v: &[f64]) -> (f64, f64) {
        if self.axial && j + 1 < self.n_seg {
            let i = self.stretch_index(j);
            (self.seg_len + q[i], v[i])
        } else {
            (self.seg_len, 0.0)
        }
    }

    /// `L_j` from positions only.
    #[inline]
    fn lever_q(&self, j: usize, q: &[f64]) -> f64 {
        if self.axial && j + 1 < self.n_seg {
            self.seg_len + q[self.stretch_index(j)]
        } else {
            self.seg_len
        }
    }

    /// Segment and offset of a rod point.
    #[inline]
    fn locate(&self, p: RodPoint) -> (usize, f64) {
        match p {
            RodPoint::B => (0, 0.0),
            RodPoint::C => (self.n_seg - 1, self.seg_len),
            RodPoint::Mid => self.mid,
        }
    }

    /// Position of the material point at `xi` on segment `k`: `B + sum_{j<k} L_j e_j + xi e_k`.
    pub fn material_point(&self, k: usize, xi: f64, q: &[f64]) -> Vector2<f64> {
        let mut r = Vector2::new(q[0], q[1]);
        for j in 0..k {
            let (e, _) = axes(q[self.theta_index(j)]);
            r += e * self.lever_q(j, q);
        }
        let (e, _) = axes(q[self.theta_index(k)]);
        r + e * xi
    }

    /// Velocity of the material point at `xi` on segment `k`.
    pub fn material_velocity(&self, k: usize, xi: f64, q: &[f64], v: &[f64]) -> Vector2<f64> {
        let mut r = Vector2::new(v[0], v[1]);
        for j in 0..k {
            let t = self.theta_index(j);
            let (e, nn) = axes(q[t]);
            let (lj, sd) = self.lever(j, q, v);
            r += e * sd + nn * (lj * v[t]);
        }
        let t = self.theta_index(k);
        let (_, nn) = axes(q[t]);
        r + nn * (xi * v[t])
    }

    /// `w_j = 2 s_j' theta_j' n_j - L_j theta_j'^2 e_j`: joint j's share of the
    /// velocity-product acceleration of everything beyond it.
    #[inline]
    fn bias_term(&self, j: usize, q: &[f64], v: &[f64]) -> Vector2<f64> {
        let t = self.theta_index(j);
        let (e, nn) = axes(q[t]);
        let (lj, sd) = self.lever(j, q, v);
        let w = v[t];
        nn * (2.0 * sd * w) - e * (lj * w * w)
    }

    /// Velocity-product acceleration `J' q'` of the point at `xi` on segment `k`.
    fn bias_at(&self, k: usize, xi: f64, q: &[f64], v: &[f64]) -> Vector2<f64> {
        let mut g = Vector2::zeros();
        for j in 0..k {
            g += self.bias_term(j, q, v);
        }
        let t = self.theta_index(k);
        let (e, _) = axes(q[t]);
        g - e * (xi * v[t] * v[t])
    }
}

impl RodBody for SegmentRod {
    fn n_coordinates(&self) -> usize {
        2 + self.n_seg + self.n_stretch()
    }

    fn coordinate_scale(&self, i: usize) -> f64 {
        match i {
            0 | 1 => self.length,
            i if i < 2 + self.n_seg => 1.0,
            // Slides: a fraction of the segment length.
            _ => self.seg_len,
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
        let theta = d.y.atan2(d.x);
        q.iter_mut().for_each(|x| *x = 0.0);
        v.iter_mut().for_each(|x| *x = 0.0);
        q[0] = b.x;
        q[1] = b.y;
        v[0] = vb.x;
        v[1] = vb.y;
        for k in 0..self.n_seg {
            q[self.theta_index(k)] = theta;
            v[self.theta_index(k)] = omega;
        }
    }

    fn mass(&self, q: &[f64], mut mm: MatMut<'_, f64>) {
        let n = self.n_seg;
        let m = self.seg_mass;
        let l = self.seg_len;
        let ns = self.n_stretch();
        let a = |j: usize| m * (n - 1 - j) as f64;
        // B block.
        mm[(0, 0)] = m * n as f64;
        mm[(1, 1)] = m * n as f64;
        mm[(0, 1)] = 0.0;
        mm[(1, 0)] = 0.0;
        for j in 0..n {
            let tj = self.theta_index(j);
            let (ej, nj) = axes(q[tj]);
            let lj = self.lever_q(j, q);
            let hj = 0.5 * m * l + a(j) * lj;
            mm[(0, tj)] = hj * nj.x;
            mm[(1, tj)] = hj * nj.y;
            mm[(tj, 0)] = hj * nj.x;
            mm[(tj, 1)] = hj * nj.y;
            // Angle-angle block: row i <= j.
            mm[(tj, tj)] = m * l * l / 3.0 + a(j) * lj * lj;
            for i in 0..j {
                let ti = self.theta_index(i);
                let (ei, _) = axes(q[ti]);
                let v = self.lever_q(i, q) * hj * ei.dot(&ej);
                mm[(ti, tj)] = v;
                mm[(tj, ti)] = v;
            }
            if j < ns {
                let sj = self.stretch_index(j);
                let aj = a(j);
                mm[(0, sj)] = aj * ej.x;
                mm[(1, sj)] = aj * ej.y;
                mm[(sj, 0)] = aj * ej.x;
                mm[(sj, 1)] = aj * ej.y;
            }
        }
        for j in 0..ns {
            let sj = self.stretch_index(j);
            let (ej, _) = axes(q[self.theta_index(j)]);
            // Angle-slide block: sin(theta_j - theta_i) = n_i . e_j.
            for i in 0..n {
                let ti = self.theta_index(i);
                let (_, ni) = axes(q[ti]);
                let snij = ni.dot(&ej);
                let v = if i < j {
                    a(j) * self.lever_q(i, q) * snij
                } else if i == j {
                    0.0
                } else {
                    (0.5 * m * l + a(i) * self.lever_q(i, q)) * snij
                };
                mm[(ti, sj)] = v;
                mm[(sj, ti)] = v;
            }
            // Slide-slide block: a_{max(i,j)} cos(theta_i - theta_j), i <= j.
            for i in 0..=j {
                let si = self.stretch_index(i);
                let (ei, _) = axes(q[self.theta_index(i)]);
                let v = a(j) * ei.dot(&ej);
                mm[(si, sj)] = v;
                mm[(sj, si)] = v;
            }
        }
    }

    fn forces(&self, q: &[f64], v: &[f64], f: &mut [f64]) {
        let n = self.n_seg;
        let m = self.seg_mass;
        let half = 0.5 * self.seg_len;
        // Pass 1: sum of the centroid bias accelerations gamma_k.
        let mut prefix = Vector2::zeros(); // A_k = sum_{j<k} w_j
        let mut total = Vector2::zeros();
        for k in 0..n {
            let t = self.theta_index(k);
            let (e, _) = axes(q[t]);
            total += prefix - e * (half * v[t] * v[t]);
            prefix += self.bias_term(k, q, v);
        }
        f[0] = -m * total.x;
        f[1] = -m * total.y;
        // Pass 2: G_i = total - sum_{k<=i} gamma_k.
        let mut prefix = Vector2::zeros();
        let mut done = Vector2::zeros();
        for i in 0..n {
            let t = self.theta_index(i);
            let (e, nn) = axes(q[t]);
            let gamma_i = prefix - e * (half * v[t] * v[t]);
            done += gamma_i;
            let downstream = total - done;
            let (li, _) = self.lever(i, q, v);
            f[t] = -m * nn.dot(&(gamma_i * half + downstream * li));
            if self.axial && i + 1 < n {
                let s = self.stretch_index(i);
                f[s] = -m * e.dot(&downstream) - self.k_ax * q[s] - self.c_ax * v[s];
            }
            prefix += self.bias_term(i, q, v);
        }
        // Joint springs and dampers.
        for j in 0..n.saturating_sub(1) {
            let (ti, tj) = (self.theta_index(j), self.theta_index(j + 1));
            let tau = self.k_rot * (q[tj] - q[ti]) + self.c_rot * (v[tj] - v[ti]);
            f[ti] += tau;
            f[tj] -= tau;
        }
    }

    fn add_tangent(&self, _q: &[f64], _v: &[f64], c_k: f64, c_d: f64, mut out: MatMut<'_, f64>) {
        // Exact for the springs and dampers; the velocity-product terms are left out (their
        // share of the Newton matrix is O((h omega)^2) and O(h omega) of the mass).
        let kr = c_k * self.k_rot + c_d * self.c_rot;
        for j in 0..self.n_seg.saturating_sub(1) {
            let (ti, tj) = (self.theta_index(j), self.theta_index(j + 1));
            out[(ti, ti)] += kr;
            out[(tj, tj)] += kr;
            out[(ti, tj)] -= kr;
            out[(tj, ti)] -= kr;
        }
        let ka = c_k * self.k_ax + c_d * self.c_ax;
        for j in 0..self.n_stretch() {
            let s = self.stretch_index(j);
            out[(s, s)] += ka;
        }
    }

    fn point(&self, p: RodPoint, q: &[f64]) -> Vector2<f64> {
        let (k, xi) = self.locate(p);
        self.material_point(k, xi, q)
    }

    fn point_jacobian(&self, p: RodPoint, q: &[f64], mut out: MatMut<'_, f64>) {
        let (k, xi) = self.locate(p);
        out.fill(0.0);
        out[(0, 0)] = 1.0;
        out[(1, 1)] = 1.0;
        for j in 0..=k {
            let t = self.theta_index(j);
            let (e, nn) = axes(q[t]);
            let arm = if j < k { self.lever_q(j, q) } else { xi };
            out[(0, t)] = arm * nn.x;
            out[(1, t)] = arm * nn.y;
            if j < k && j < self.n_stretch() {
                let s = self.stretch_index(j);
                out[(0, s)] = e.x;
                out[(1, s)] = e.y;
            }
        }
    }

    fn point_bias_acceleration(&self, p: RodPoint, q: &[f64], v: &[f64]) -> Vector2<f64> {
        let (k, xi) = self.locate(p);
        self.bias_at(k, xi, q, v)
    }

    fn add_point_force_tangent(
        &self,
        p: RodPoint,
        q: &[f64],
        f: Vector2<f64>,
        coef: f64,
        mut out: MatMut<'_, f64>,
    ) {
        // (J^T f)_theta_j = arm_j n_j . f, (J^T f)_s_j = e_j . f; d(n_j)/d theta_j = -e_j,
        // d(e_j)/d theta_j = n_j, d(arm_j)/d s_j = 1. Exact.
        let (k, xi) = self.locate(p);
        for j in 0..=k {
            let t = self.theta_index(j);
            let (e, nn) = axes(q[t]);
            let arm = if j < k { self.lever_q(j, q) } else { xi };
            out[(t, t)] -= coef * arm * e.dot(&f);
            if j < k && j < self.n_stretch() {
                let s = self.stretch_index(j);
                let c = coef * nn.dot(&f);
                out[(t, s)] += c;
                out[(s, t)] += c;
            }
        }
    }

    fn kinetic_energy(&self, q: &[f64], v: &[f64]) -> f64 {
        // T = sum_k (m |g_k'|^2 + I_c theta_k'^2) / 2, accumulating the joint velocities.
        let half = 0.5 * self.seg_len;
        let mut joint = Vector2::new(v[0], v[1]);
        let mut t2 = 0.0;
        for k in 0..self.n_seg {
            let t = self.theta_index(k);
            let (e, nn) = axes(q[t]);
            let g = joint + nn * (half * v[t]);
            t2 += self.seg_mass * g.norm_squared() + self.seg_inertia * v[t] * v[t];
            let (lk, sd) = self.lever(k, q, v);
            joint += e * sd + nn * (lk * v[t]);
        }
        0.5 * t2
    }

    fn strain_energy(&self, q: &[f64]) -> f64 {
        let mut u = 0.0;
        for j in 0..self.n_seg.saturating_sub(1) {
            let d = q[self.theta_index(j + 1)] - q[self.theta_index(j)];
            u += self.k_rot * d * d;
        }
        for j in 0..self.n_stretch() {
            let s = q[self.stretch_index(j)];
            u += self.k_ax * s * s;
        }
        0.5 * u
    }

    fn linear_momentum(&self, q: &[f64], v: &[f64]) -> Vector2<f64> {
        let half = 0.5 * self.seg_len;
        let mut joint = Vector2::new(v[0], v[1]);
        let mut p = Vector2::zeros();
        for k in 0..self.n_seg {
            let t = self.theta_index(k);
            let (e, nn) = axes(q[t]);
            p += joint + nn * (half * v[t]);
            let (lk, sd) = self.lever(k, q, v);
            joint += e * sd + nn * (lk * v[t]);
        }
        p * self.seg_mass
    }

    fn frequencies_hz(&self) -> &[f64] {
        &self.frequencies
    }

    fn length(&self) -> f64 {
        self.length
    }
}
