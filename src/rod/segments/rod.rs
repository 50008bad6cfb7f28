//! The finite segment rod body (seed 002, `002_e6c2c81d944c25fc.txt`, "Flexibility effects"
//! and "Illustrations/convergence"; docs/physics.md, "Rod model 2: finite segments").
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
//! `k_r = E I / l` (docs/physics.md): the joint rotation `theta_{j+1} - theta_j` is the curvature
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

use super::linear::LinearizedChain;
use super::validate_segments;
use crate::beam::{RodDefinition, RodProperties};
use crate::error::{require_non_negative, ModelError};

/// The finite segment rod.
pub struct SegmentRod {
    /// Number of segments N.
    pub(super) n_seg: usize,
    /// Prismatic joints with axial springs (coordinates `s_j`).
    pub(super) axial: bool,
    /// Rod length L, m.
    pub(super) length: f64,
    /// Segment length l = L/N, m.
    pub(super) seg_len: f64,
    /// Segment masses m_k, kg (uniform rod: rho A l each).
    pub(super) masses: Vec<f64>,
    /// Centroid offsets c_k from each segment's B-side joint, m (uniform: l / 2).
    pub(super) centroids: Vec<f64>,
    /// Centroidal inertias I_k, kg m^2 (uniform: m l^2 / 12).
    pub(super) inertias: Vec<f64>,
    /// First moments about the B-side joint, `f_k = m_k c_k`, kg m (uniform: m l / 2).
    pub(super) first: Vec<f64>,
    /// Second moments about the B-side joint, `J_k = I_k + m_k c_k^2`, kg m^2 (uniform: m l^2 / 3).
    pub(super) second: Vec<f64>,
    /// Mass beyond segment j, `a_j = sum_{k>j} m_k`, kg (uniform: m (N - 1 - j)).
    pub(super) beyond: Vec<f64>,
    /// Total mass of the segments (end bodies included), kg (uniform: N m).
    pub(super) total: f64,
    /// The velocity-product sums are accumulated with the weights `weights[k]` and multiplied
    /// by `weight_scale` at the end: `(1, m)` for the uniform rod (the original arithmetic), and
    /// `(m_k, 1)` otherwise. `weighted_first[k]` is `f_k / weight_scale` (uniform: l / 2).
    pub(super) weights: Vec<f64>,
    pub(super) weight_scale: f64,
    pub(super) weighted_first: Vec<f64>,
    /// Rotational springs k_r of the joints, N m/rad, and dampers c_r, N m s/rad (N - 1 each).
    pub(super) k_rot: Vec<f64>,
    pub(super) c_rot: Vec<f64>,
    /// Axial springs k_a, N/m, and dampers c_a, N s/m, of the joints (0 without axial springs).
    pub(super) k_ax: Vec<f64>,
    pub(super) c_ax: Vec<f64>,
    /// Mass of the rod with its end bodies, kg.
    pub(super) total_mass: f64,
    /// The material midpoint: (segment, distance from its start in m).
    pub(super) mid: (usize, f64),
    /// Pinned-pinned frequencies of the linearized chain, Hz: all, bending, axial.
    pub(super) frequencies: Vec<f64>,
    pub(super) bending: Vec<f64>,
    pub(super) axial_modes: Vec<f64>,
    /// Cuts of the section-force recovery: B, the joints, C (N + 1, ascending), and the
    /// index of the one nearest the midpoint.
    pub(super) cuts: Vec<crate::rod::sections::CutSection>,
    pub(super) mid_cut: usize,
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
        let k_rot = props.bending_rigidity() / l;
        let k_ax = if axial_springs {
            props.axial_rigidity() / l
        } else {
            0.0
        };
        let mut rod = Self::empty(props.length, n, axial_springs);
        rod.masses = vec![m; n];
        rod.centroids = vec![0.5 * l; n];
        rod.inertias = vec![m * l * l / 12.0; n];
        rod.first = vec![0.5 * m * l; n];
        rod.second = vec![m * l * l / 3.0; n];
        rod.beyond = (0..n).map(|j| m * (n - 1 - j) as f64).collect();
        rod.total = m * n as f64;
        rod.weights = vec![1.0; n];
        rod.weight_scale = m;
        rod.weighted_first = vec![0.5 * l; n];
        rod.k_rot = vec![k_rot; n - 1];
        rod.k_ax = vec![k_ax; n - 1];
        rod.total_mass = props.mass();
        rod.set_cuts(&crate::beam::SectionTable::uniform(
            props.length,
            props.area,
            props.area_moment,
        ));
        rod.finish(damping_ratio, |_| {
            Ok(2.0 * (k_ax / m).sqrt() * (std::f64::consts::PI / (2.0 * n as f64)).sin())
        })?;
        Ok(rod)
    }

    /// Build the chain of any rod: each segment `k` (arc lengths `[k l, (k + 1) l]`) takes the
    /// mass, centroid and centroidal inertia of its piece of the section table,
    /// `int rho A`, `int rho A s`, `int rho A s^2` (exact; the section's own rotary inertia
    /// `rho I` is left out, as in the uniform chain and the Euler-Bernoulli beam), and the end
    /// bodies are added to the first and last segment (point mass at B or C, inertia about it;
    /// parallel-axis theorem). The joint between segments `j` and `j + 1` stands for the rod
    /// from the middle of segment `j` to the middle of segment `j + 1` (two half segments in
    /// series): `k_r = 1 / int ds / (E I(s))` over that length, the harmonic mean of `E I / l`
    /// (exact for linear `I`: the `ln` form of
    /// [`crate::beam::SectionTable::compliance_integral`]); the same for the axial spring with
    /// `E A(s)`. For the uniform rod these are `E I / l` and `E A / l`. The shear-deformable
    /// option does not apply to the chain (rejected).
    pub fn from_definition(
        def: &RodDefinition,
        n_segments: usize,
        damping_ratio: f64,
        axial_springs: bool,
    ) -> Result<SegmentRod, ModelError> {
        if def.is_plain() {
            return Self::new(def.properties, n_segments, damping_ratio, axial_springs);
        }
        def.validate()?;
        validate_segments(n_segments)?;
        require_non_negative("rod.damping_ratio", damping_ratio)?;
        if let Some(g) = def.shear_modulus {
            return Err(ModelError::InvalidParameter {
                name: "rod.shear_deformation",
                value: g,
                allowed: "false with rod.model = \"segments\" (the chain has no shear flexibility; use rod.model = \"ffr\")".into(),
            });
        }
        let n = n_segments;
        let length = def.properties.length;
        let l = length / n as f64;
        let rho = def.properties.density;
        let e_mod = def.properties.youngs_modulus;
        let table = def.section_table();
        let mut rod = Self::empty(length, n, axial_springs);
        for k in 0..n {
            let s0 = k as f64 * l;
            let moments = |p: i32| {
                table.integrate(s0, s0 + l, 0.0, |s, v, w| {
                    rho * v.area * (s - s0).powi(p) * w
                })
            };
            let (mut mk, mut fk, mut jk) = (moments(0), moments(1), moments(2));
            if k == 0 {
                mk += def.big_end.mass;
                jk += def.big_end.inertia;
            }
            if k == n - 1 {
                let c = def.small_end;
                mk += c.mass;
                fk += c.mass * l;
                jk += c.mass * l * l + c.inertia;
            }
            let ck = fk / mk;
            rod.masses.push(mk);
            rod.centroids.push(ck);
            rod.inertias.push(jk - mk * ck * ck);
            rod.first.push(fk);
            rod.second.push(jk);
            rod.weights.push(mk);
            rod.weighted_first.push(fk);
        }
        rod.weight_scale = 1.0;
        rod.total = rod.masses.iter().sum();
        rod.beyond = (0..n).map(|j| rod.masses[j + 1..].iter().sum()).collect();
        for j in 0..n - 1 {
            let (a, b) = ((j as f64 + 0.5) * l, (j as f64 + 1.5) * l);
            rod.k_rot
                .push(e_mod / table.compliance_integral(a, b, |v| v.area_moment));
            rod.k_ax.push(if axial_springs {
                e_mod / table.compliance_integral(a, b, |v| v.area)
            } else {
                0.0
            });
        }
        rod.total_mass = def.total_mass();
        rod.set_cuts(&table);
        rod.finish(damping_ratio, |rod| {
            let f = LinearizedChain::new(rod).free_free_axial_hz()?;
            Ok(2.0 * std::f64::consts::PI * f.first().copied().unwrap_or(1.0))
        })?;
        Ok(rod)
    }

    /// The cuts at B, the joints and C.
    fn set_cuts(&mut self, table: &crate::beam::SectionTable) {
        let l = self.seg_len;
        self.cuts = (0..=self.n_seg)
            .map(|i| crate::rod::sections::CutSection::new(table, i as f64 * l))
            .collect();
    }

    /// A chain with its geometry set and no masses or springs yet.
    fn empty(length: f64, n: usize, axial: bool) -> SegmentRod {
        let l = length / n as f64;
        let half = 0.5 * length;
        let k_mid = ((half / l).floor() as usize).min(n - 1);
        SegmentRod {
            n_seg: n,
            axial,
            length,
            seg_len: l,
            masses: Vec::with_capacity(n),
            centroids: Vec::with_capacity(n),
            inertias: Vec::with_capacity(n),
            first: Vec::with_capacity(n),
            second: Vec::with_capacity(n),
            beyond: Vec::with_capacity(n),
            total: 0.0,
            weights: Vec::with_capacity(n),
            weight_scale: 1.0,
            weighted_first: Vec::with_capacity(n),
            k_rot: Vec::with_capacity(n),
            c_rot: Vec::new(),
            k_ax: Vec::with_capacity(n),
            c_ax: Vec::new(),
            total_mass: 0.0,
            mid: (k_mid, half - k_mid as f64 * l),
            frequencies: Vec::new(),
            bending: Vec::new(),
            axial_modes: Vec::new(),
            cuts: Vec::new(),
            mid_cut: n / 2,
        }
    }

    /// Frequencies of the linearized chain and the dampers (`first_axial` gives the first
    /// free-free axial circular frequency of the chain, rad/s).
    fn finish<F>(&mut self, damping_ratio: f64, first_axial: F) -> Result<(), ModelError>
    where
        F: FnOnce(&SegmentRod) -> Result<f64, ModelError>,
    {
        let n = self.n_seg;
        self.c_rot = vec![0.0; n - 1];
        self.c_ax = vec![0.0; n - 1];
        let chain = LinearizedChain::new(self);
        self.bending = chain.pinned_bending_hz()?;
        if self.axial {
            self.axial_modes = chain.pinned_axial_hz()?;
        }
        let mut all: Vec<f64> = self
            .bending
            .iter()
            .chain(&self.axial_modes)
            .copied()
            .collect();
        all.sort_by(|a, b| a.total_cmp(b));
        self.frequencies = all;
        if let Some(f1) = self.bending.first() {
            let f1 = *f1;
            for (c, k) in self.c_rot.iter_mut().zip(&self.k_rot) {
                *c = 2.0 * damping_ratio / (2.0 * std::f64::consts::PI * f1) * k;
            }
        }
        if self.axial && n >= 2 {
            let w1 = first_axial(self)?;
            for (c, k) in self.c_ax.iter_mut().zip(&self.k_ax) {
                *c = 2.0 * damping_ratio / w1 * k;
            }
        }
        Ok(())
    }

    /// Number of segments N.
    pub fn n_segments(&self) -> usize {
        self.n_seg
    }

    /// Whether the joints carry axial springs (slide coordinates `s_j`).
    pub fn has_axial_springs(&self) -> bool {
        self.axial
    }

    /// Segment length l, m; mass of the first segment, kg (every segment's, for the uniform
    /// rod; see [`Self::segment_masses`]).
    pub fn segment(&self) -> (f64, f64) {
        (self.seg_len, self.masses[0])
    }

    /// Per segment: mass (kg), centroid offset from its B-side joint (m), centroidal inertia
    /// (kg m^2).
    pub fn segment_masses(&self) -> (&[f64], &[f64], &[f64]) {
        (&self.masses, &self.centroids, &self.inertias)
    }

    /// Mass of the rod with its end bodies, kg (the FMU's `rod.mass`).
    pub fn total_mass(&self) -> f64 {
        self.total_mass
    }

    /// Joint spring constants `(k_r, k_a)` of the first joint: N m/rad and N/m (`k_a = 0`
    /// without axial springs; `(0, 0)` for one segment). Every joint's: [`Self::joint_springs`].
    pub fn spring_constants(&self) -> (f64, f64) {
        (
            self.k_rot.first().copied().unwrap_or(0.0),
            self.k_ax.first().copied().unwrap_or(0.0),
        )
    }

    /// Every joint's springs `(k_r, k_a)`, N - 1 each.
    pub fn joint_springs(&self) -> (&[f64], &[f64]) {
        (&self.k_rot, &self.k_ax)
    }

    /// Joint damper constants `(c_r, c_a)` of the first joint: N m s/rad and N s/m.
    pub fn damper_constants(&self) -> (f64, f64) {
        (
            self.c_rot.first().copied().unwrap_or(0.0),
            self.c_ax.first().copied().unwrap_or(0.0),
        )
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
}
