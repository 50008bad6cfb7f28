//! The segment chain's data and construction; the model and its equations are documented in
//! the module [`super`].

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
    /// Shear slides (coordinates `t_i`, `i = 0..=N`: at B, at every joint, at C).
    pub(super) shear: bool,
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
    /// Total mass of the segments, kg (uniform: N m); the end bodies are point masses of their
    /// own ([`Self::end_bodies`]).
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
    /// Shear springs k_s, N/m, and dampers c_s, N s/m, of the shear slides (`N + 1` with shear
    /// deformation: slide 0 at B, slide `j + 1` at joint `j`, slide `N` at C; else empty).
    pub(super) k_sh: Vec<f64>,
    pub(super) c_sh: Vec<f64>,
    /// The end bodies at B and C: masses (kg, point masses at the pins) and inertias about the
    /// pins (kg m^2); an inertia turns with a rotation coordinate of its own (`phi_B`, `phi_C`)
    /// joined to the end segment by a rotational spring `k_end` (N m/rad: the half segment
    /// next to the pin, `1 / int ds / (E I)`) and damper `c_end` (N m s/rad).
    pub(super) end_mass: [f64; 2],
    pub(super) end_inertia: [f64; 2],
    pub(super) k_end: [f64; 2],
    pub(super) c_end: [f64; 2],
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
        if axial_springs && n >= 2 {
            // The end springs take the half segments at B and C too (the force at the pins
            // passes through them): the chain's static axial compliance is the rod's, L / (E A).
            for j in [0, n - 2] {
                let span = if n == 2 { 2.0 * l } else { 1.5 * l };
                rod.k_ax[j] = props.axial_rigidity() / span;
            }
        }
        rod.total_mass = props.mass();
        rod.set_cuts(&crate::beam::SectionTable::uniform(
            props.length,
            props.area,
            props.area_moment,
        ));
        rod.finish(damping_ratio, |rod| {
            let f = LinearizedChain::new(rod).free_free_axial_hz()?;
            Ok(2.0 * std::f64::consts::PI * f.first().copied().unwrap_or(1.0))
        })?;
        Ok(rod)
    }

    /// Build the chain of any rod: each segment `k` (arc lengths `[k l, (k + 1) l]`) takes the
    /// mass, centroid and centroidal inertia of its piece of the section table,
    /// `int rho A`, `int rho A s`, `int rho A s^2` (exact; the section's own rotary inertia
    /// `rho I` is left out, as in the uniform chain and the Euler-Bernoulli beam, except with
    /// shear deformation, where `int rho I` is added as in the Timoshenko beam), and the end
    /// bodies are added to the first and last segment (point mass at B or C, inertia about it;
    /// parallel-axis theorem). The joint between segments `j` and `j + 1` stands for the rod
    /// from the middle of segment `j` to the middle of segment `j + 1` (two half segments in
    /// series): `k_r = 1 / int ds / (E I(s))` over that length, the harmonic mean of `E I / l`
    /// (exact for linear `I`: the `ln` form of
    /// [`crate::beam::SectionTable::compliance_integral`]); the same for the axial spring with
    /// `E A(s)`, the end ones from the pins (`[0, 1.5 l]` and `[L - 1.5 l, L]`: the pins' forces
    /// pass through the half segments there). For the uniform rod these are `E I / l` and `E A
    /// / l` (`E A / (1.5 l)` at the ends).
    ///
    /// With shear deformation (`def.shear_modulus`), every joint also gets a shear slide with
    /// `k_s = 1 / int ds / (G A_s(s))` over the same length, and B and C get one each for the
    /// half segment next to them, `int_0^{l/2}` and `int_{L - l/2}^L` (module docs, "Shear").
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
        let n = n_segments;
        let length = def.properties.length;
        let l = length / n as f64;
        let rho = def.properties.density;
        let e_mod = def.properties.youngs_modulus;
        let table = def.section_table();
        let mut rod = Self::empty(length, n, axial_springs);
        rod.shear = def.shear_modulus.is_some();
        for k in 0..n {
            let s0 = k as f64 * l;
            let moments = |p: i32| {
                table.integrate(s0, s0 + l, 0.0, |s, v, w| {
                    rho * v.area * (s - s0).powi(p) * w
                })
            };
            let (mk, fk, mut jk) = (moments(0), moments(1), moments(2));
            if rod.shear {
                // Rotary inertia of the sections (Timoshenko): the segment turns with them.
                jk += table.integrate(s0, s0 + l, 0.0, |_, v, w| rho * v.area_moment * w);
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
            // The end springs take the half segments at B and C too.
            let a_ax = if j == 0 { 0.0 } else { a };
            let b_ax = if j == n - 2 { length } else { b };
            rod.k_ax.push(if axial_springs {
                e_mod / table.compliance_integral(a_ax, b_ax, |v| v.area)
            } else {
                0.0
            });
        }
        // The end bodies: point masses at the pins, their inertias on rotations of their own
        // joined to the end segments by the bending stiffness of the half segment between.
        rod.end_mass = [def.big_end.mass, def.small_end.mass];
        rod.end_inertia = [def.big_end.inertia, def.small_end.inertia];
        let half_segment = [(0.0, 0.5 * l), (length - 0.5 * l, length)];
        for (e, (a, b)) in half_segment.into_iter().enumerate() {
            if rod.end_inertia[e] > 0.0 {
                rod.k_end[e] = e_mod / table.compliance_integral(a, b, |v| v.area_moment);
            }
        }
        if let Some(g) = def.shear_modulus {
            let spring = |a: f64, b: f64| g / table.compliance_integral(a, b, |v| v.shear_area);
            rod.k_sh.push(spring(0.0, 0.5 * l));
            for j in 0..n - 1 {
                rod.k_sh
                    .push(spring((j as f64 + 0.5) * l, (j as f64 + 1.5) * l));
            }
            rod.k_sh.push(spring(length - 0.5 * l, length));
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
        // The material midpoint: the joint N/2 (start of segment N/2) for even N, the middle of
        // segment (N - 1)/2 for odd N (exactly, not by floor(half / l) and round-off).
        let (k_mid, xi_mid) = if n.is_multiple_of(2) {
            (n / 2, 0.0)
        } else {
            ((n - 1) / 2, 0.5 * l)
        };
        SegmentRod {
            n_seg: n,
            axial,
            shear: false,
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
            k_sh: Vec::new(),
            c_sh: Vec::new(),
            end_mass: [0.0; 2],
            end_inertia: [0.0; 2],
            k_end: [0.0; 2],
            c_end: [0.0; 2],
            total_mass: 0.0,
            mid: (k_mid, xi_mid),
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
        self.c_sh = vec![0.0; self.k_sh.len()];
        if let Some(f1) = self.bending.first() {
            // Stiffness-proportional: the rotational and shear springs with the same factor.
            let beta = 2.0 * damping_ratio / (2.0 * std::f64::consts::PI * f1);
            for (c, k) in self.c_rot.iter_mut().zip(&self.k_rot) {
                *c = beta * k;
            }
            for (c, k) in self.c_sh.iter_mut().zip(&self.k_sh) {
                *c = beta * k;
            }
            for (c, k) in self.c_end.iter_mut().zip(&self.k_end) {
                *c = beta * k;
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
    /// (kg m^2); the shank only (the end bodies: [`Self::end_bodies`]).
    pub fn segment_masses(&self) -> (&[f64], &[f64], &[f64]) {
        (&self.masses, &self.centroids, &self.inertias)
    }

    /// The end bodies at B and C: masses (kg) and inertias about the pins (kg m^2).
    pub fn end_bodies(&self) -> ([f64; 2], [f64; 2]) {
        (self.end_mass, self.end_inertia)
    }

    /// The rotational springs between the end bodies' rotations and the end segments, N m/rad
    /// (0 where an end body has no inertia).
    pub fn end_springs(&self) -> [f64; 2] {
        self.k_end
    }

    /// The dampers beside [`Self::end_springs`], N m s/rad (stiffness-proportional, as the
    /// joints').
    pub fn end_dampers(&self) -> [f64; 2] {
        self.c_end
    }

    /// Whether end body `e` (0 at B, 1 at C) turns with a rotation coordinate of its own
    /// (it has an inertia).
    #[inline]
    pub fn has_end_rotation(&self, e: usize) -> bool {
        self.end_inertia[e] > 0.0
    }

    /// Index of the end body rotation `phi_B` (`e = 0`) or `phi_C` (`e = 1`) in `q` (only
    /// where [`Self::has_end_rotation`]).
    #[inline]
    pub fn end_rotation_index(&self, e: usize) -> usize {
        let base = 2 + self.n_seg + self.n_stretch() + self.n_shear();
        base + usize::from(e == 1 && self.has_end_rotation(0))
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

    /// Whether the chain is shear-deformable (shear slides `t_i` at B, the joints and C).
    pub fn has_shear(&self) -> bool {
        self.shear
    }

    /// The shear springs `k_s` (N/m) and dampers `c_s` (N s/m): `N + 1` each with shear
    /// deformation (slide 0 at B, `j + 1` at joint `j`, `N` at C), else empty.
    pub fn shear_springs(&self) -> (&[f64], &[f64]) {
        (&self.k_sh, &self.c_sh)
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

    /// Index of the shear slide `t_i` in `q` (shear deformation only; `i = 0` at B, `j + 1`
    /// at joint `j`, `N` at C).
    #[inline]
    pub fn shear_index(&self, i: usize) -> usize {
        2 + self.n_seg + self.n_stretch() + i
    }
}
