//! The segment chain as a [`RodBody`]: mass matrix, forces, points and energies (the
//! equations are in the documentation of [`super::rod`]).

use faer::reborrow::ReborrowMut;
use faer::MatMut;
use nalgebra::Vector2;

use super::kinematics::{axes, EndSlide, Located};
use super::rod::SegmentRod;
use crate::rod::body::{RodBody, RodPoint};
use crate::rod::sections::LoadWalk;

impl RodBody for SegmentRod {
    fn n_coordinates(&self) -> usize {
        2 + self.n_seg + self.n_stretch() + self.n_shear() + self.n_end_rotations()
    }

    fn coordinate_scale(&self, i: usize) -> f64 {
        match i {
            0 | 1 => self.length,
            i if i < 2 + self.n_seg => 1.0,
            // The end body rotations, last.
            i if i >= 2 + self.n_seg + self.n_stretch() + self.n_shear() => 1.0,
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
        for e in 0..2 {
            if self.has_end_rotation(e) {
                q[self.end_rotation_index(e)] = theta;
                v[self.end_rotation_index(e)] = omega;
            }
        }
    }

    fn add_gravity(&self, q: &[f64], g: Vector2<f64>, f: &mut [f64]) {
        // Sum over the segment centroids of m_k g . d g_k / dq: Q_B = m g,
        // Q_theta_i = (f_i n_i + a_i perp(d_i)) . g, Q_s_j = a_j e_j . g, Q_t_j = a_j n_j . g
        // (the end slides carry no mass).
        f[0] += self.total * g.x;
        f[1] += self.total * g.y;
        for i in 0..self.n_seg {
            let t = self.theta_index(i);
            let (e, n) = axes(q[t]);
            let h = n * self.first[i] + self.offset_q(i, q).lever(e, n) * self.beyond[i];
            f[t] += h.dot(&g);
            if i + 1 < self.n_seg {
                if self.axial {
                    f[self.stretch_index(i)] += self.beyond[i] * e.dot(&g);
                }
                if self.shear {
                    f[self.shear_index(i + 1)] += self.beyond[i] * n.dot(&g);
                }
            }
        }
        // The end bodies' masses at the pins: m J^T g.
        for (p, m) in self.pins().into_iter().zip(self.end_mass) {
            if m > 0.0 {
                self.for_each_column(p, q, |c, u| f[c] += m * u.dot(&g));
            }
        }
    }

    fn section_loads(
        &self,
        q: &[f64],
        v: &[f64],
        qdd: &[f64],
        g: Vector2<f64>,
        force_c: Vector2<f64>,
    ) -> crate::rod::SectionLoads {
        // Walk from C: the pin force and the small end body (d'Alembert force and couple) before
        // the cut at C (cut N), then segment k (its centroid's d'Alembert force and couple)
        // before the cut at its B-side joint (cut k). The big end body lies beyond the cut at B
        // (between it and the pin): no cut carries it. As the FFR rod's walk.
        let n = self.n_seg;
        let mut walk = LoadWalk::new();
        let [_, pin_c] = self.pins();
        let end_body = |walk: &mut LoadWalk, p: super::kinematics::Located, e: usize| {
            let r = self.located_point(p, q);
            let a = self.located_velocity(p, q, qdd) + self.located_bias(p, q, v);
            let couple = if self.has_end_rotation(e) {
                -self.end_inertia[e] * qdd[self.end_rotation_index(e)]
            } else {
                0.0
            };
            walk.add(r, (g - a) * self.end_mass[e], couple);
        };
        let r_c = self.located_point(pin_c, q);
        walk.add(r_c, force_c, 0.0);
        end_body(&mut walk, pin_c, 1);
        let (e_last, _) = axes(q[self.theta_index(n - 1)]);
        walk.cut(&self.cuts[n], r_c, e_last, self.mid_cut == n);
        for k in (0..n).rev() {
            let t = self.theta_index(k);
            let ck = self.centroids[k];
            let r = self.material_point(k, ck, q);
            let a = self.material_velocity(k, ck, q, qdd) + self.bias_at(k, ck, q, v);
            walk.add(r, (g - a) * self.masses[k], -self.inertias[k] * qdd[t]);
            let (e, _) = axes(q[t]);
            walk.cut(
                &self.cuts[k],
                self.material_point(k, 0.0, q),
                e,
                self.mid_cut == k,
            );
        }
        walk.out
    }

    fn mass(&self, q: &[f64], mut mm: MatMut<'_, f64>) {
        // Module docs, "Equations", with the joint offsets d_j = L_j e_j + t_j n_j:
        // M_{B theta_j} = H_j = f_j n_j + a_j perp(d_j), M_{theta_j theta_j} = J_j + a_j |d_j|^2,
        // M_{theta_i theta_j} = perp(d_i) . H_j (i < j); a slide of joint j along u (e_j or
        // n_j): M_{B u} = a_j u, M_{theta_i u} = a_j perp(d_i) . u (i <= j), H_i . u (i > j),
        // M_{u w} = a_{max(i, j)} u . w. The end slides carry no mass (zero rows).
        // The axes e_k, n_k, levers perp(d_k) and H_k of every segment once, on the stack.
        let n = self.n_seg;
        let a = |j: usize| self.beyond[j];
        let zero = Vector2::zeros();
        let mut axis = [(zero, zero); super::SEGMENT_RANGE.1];
        let mut lever = [zero; super::SEGMENT_RANGE.1];
        let mut h = [zero; super::SEGMENT_RANGE.1];
        for k in 0..n {
            let (e, nn) = axes(q[self.theta_index(k)]);
            axis[k] = (e, nn);
            lever[k] = self.offset_q(k, q).lever(e, nn);
            h[k] = nn * self.first[k] + lever[k] * a(k);
        }
        mm.fill(0.0);
        mm[(0, 0)] = self.total;
        mm[(1, 1)] = self.total;
        for j in 0..n {
            let tj = self.theta_index(j);
            let hj = h[j];
            mm[(0, tj)] = hj.x;
            mm[(1, tj)] = hj.y;
            mm[(tj, 0)] = hj.x;
            mm[(tj, 1)] = hj.y;
            mm[(tj, tj)] = self.second[j] + a(j) * lever[j].norm_squared();
            for i in 0..j {
                let ti = self.theta_index(i);
                let v = lever[i].dot(&hj);
                mm[(ti, tj)] = v;
                mm[(tj, ti)] = v;
            }
        }
        // Joint slide m: joint j, coordinate, direction (axial slides first, then shear).
        let ns = self.n_stretch();
        let slide = |m: usize| {
            if m < ns {
                (m, self.stretch_index(m), axis[m].0)
            } else {
                let j = m - ns;
                (j, self.shear_index(j + 1), axis[j].1)
            }
        };
        for m in 0..self.n_joint_slides() {
            let (j, sj, u) = slide(m);
            let aj = a(j);
            mm[(0, sj)] = aj * u.x;
            mm[(1, sj)] = aj * u.y;
            mm[(sj, 0)] = aj * u.x;
            mm[(sj, 1)] = aj * u.y;
            for i in 0..n {
                let ti = self.theta_index(i);
                let v = if i <= j {
                    aj * lever[i].dot(&u)
                } else {
                    h[i].dot(&u)
                };
                mm[(ti, sj)] = v;
                mm[(sj, ti)] = v;
            }
            for m2 in 0..=m {
                let (i, si, w) = slide(m2);
                let v = a(i.max(j)) * u.dot(&w);
                mm[(si, sj)] = v;
                mm[(sj, si)] = v;
            }
        }
        // The end bodies: m J^T J at the pins, and their inertias on their own rotations.
        for (p, m) in self.pins().into_iter().zip(self.end_mass) {
            if m > 0.0 {
                self.add_point_mass(p, m, q, mm.rb_mut());
            }
        }
        for e in 0..2 {
            if self.has_end_rotation(e) {
                let i = self.end_rotation_index(e);
                mm[(i, i)] = self.end_inertia[e];
            }
        }
    }

    fn forces(&self, q: &[f64], v: &[f64], f: &mut [f64]) {
        let n = self.n_seg;
        let m = self.weight_scale;
        // Pass 1: the (weighted) sum of the centroid bias accelerations gamma_k.
        let mut prefix = Vector2::zeros(); // A_k = sum_{j<k} w_j
        let mut total = Vector2::zeros();
        for k in 0..n {
            let t = self.theta_index(k);
            let (e, _) = axes(q[t]);
            total += (prefix - e * (self.centroids[k] * v[t] * v[t])) * self.weights[k];
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
            let gamma_i = prefix - e * (self.centroids[i] * v[t] * v[t]);
            done += gamma_i * self.weights[i];
            let downstream = total - done;
            let lever = self.offset_q(i, q).lever(e, nn);
            f[t] = -m * (nn.dot(&gamma_i) * self.weighted_first[i] + lever.dot(&downstream));
            if self.axial && i + 1 < n {
                let s = self.stretch_index(i);
                f[s] = -m * e.dot(&downstream) - self.k_ax[i] * q[s] - self.c_ax[i] * v[s];
            }
            if self.shear && i + 1 < n {
                let s = self.shear_index(i + 1);
                f[s] = -m * nn.dot(&downstream) - self.k_sh[i + 1] * q[s] - self.c_sh[i + 1] * v[s];
            }
            prefix += self.bias_term(i, q, v);
        }
        if self.shear {
            // The end slides: springs and dampers only.
            for i in [0, n] {
                let s = self.shear_index(i);
                f[s] = -self.k_sh[i] * q[s] - self.c_sh[i] * v[s];
            }
        }
        // Joint springs and dampers.
        for j in 0..n.saturating_sub(1) {
            let (ti, tj) = (self.theta_index(j), self.theta_index(j + 1));
            let tau = self.k_rot[j] * (q[tj] - q[ti]) + self.c_rot[j] * (v[tj] - v[ti]);
            f[ti] += tau;
            f[tj] -= tau;
        }
        // The end bodies: -m J^T (J' q') of the masses at the pins; the springs and dampers
        // between the end rotations and the end segments (tau on the segment side, B:
        // tau = k (phi_B - theta_0), C: tau = k (phi_C - theta_{N-1})).
        for (p, mass) in self.pins().into_iter().zip(self.end_mass) {
            if mass > 0.0 {
                let bias = self.located_bias(p, q, v);
                self.for_each_column(p, q, |c, u| f[c] -= mass * u.dot(&bias));
            }
        }
        for (e, segment) in [(0, 0), (1, n - 1)] {
            if self.has_end_rotation(e) {
                let (i, t) = (self.end_rotation_index(e), self.theta_index(segment));
                let tau = self.k_end[e] * (q[i] - q[t]) + self.c_end[e] * (v[i] - v[t]);
                f[t] += tau;
                f[i] = -tau;
            }
        }
    }

    fn add_tangent(&self, _q: &[f64], _v: &[f64], c_k: f64, c_d: f64, mut out: MatMut<'_, f64>) {
        // Exact for the springs and dampers; the velocity-product terms are left out (their
        // share of the Newton matrix is O((h omega)^2) and O(h omega) of the mass).
        for j in 0..self.n_seg.saturating_sub(1) {
            let kr = c_k * self.k_rot[j] + c_d * self.c_rot[j];
            let (ti, tj) = (self.theta_index(j), self.theta_index(j + 1));
            out[(ti, ti)] += kr;
            out[(tj, tj)] += kr;
            out[(ti, tj)] -= kr;
            out[(tj, ti)] -= kr;
        }
        for j in 0..self.n_stretch() {
            let ka = c_k * self.k_ax[j] + c_d * self.c_ax[j];
            let s = self.stretch_index(j);
            out[(s, s)] += ka;
        }
        for i in 0..self.n_shear() {
            let s = self.shear_index(i);
            out[(s, s)] += c_k * self.k_sh[i] + c_d * self.c_sh[i];
        }
        for (e, segment) in [(0, 0), (1, self.n_seg - 1)] {
            if self.has_end_rotation(e) {
                let (i, t) = (self.end_rotation_index(e), self.theta_index(segment));
                let k = c_k * self.k_end[e] + c_d * self.c_end[e];
                out[(i, i)] += k;
                out[(t, t)] += k;
                out[(i, t)] -= k;
                out[(t, i)] -= k;
            }
        }
    }

    fn point(&self, p: RodPoint, q: &[f64]) -> Vector2<f64> {
        match self.locate(p) {
            (a, None) => self.located_point(a, q),
            (a, Some(b)) => (self.located_point(a, q) + self.located_point(b, q)) * 0.5,
        }
    }

    fn point_at(&self, s: f64, q: &[f64]) -> Vector2<f64> {
        // Segment k holds the arc lengths k l .. (k + 1) l; rigid, so the point is at s - k l
        // along it from its B-side joint.
        let s = s.clamp(0.0, self.length);
        let k = ((s / self.seg_len).floor() as usize).min(self.n_seg - 1);
        self.material_point(k, s - k as f64 * self.seg_len, q)
    }

    fn point_jacobian(&self, p: RodPoint, q: &[f64], mut out: MatMut<'_, f64>) {
        out.fill(0.0);
        match self.locate(p) {
            (a, None) => self.add_located_jacobian(a, 1.0, q, out),
            (a, Some(b)) => {
                self.add_located_jacobian(a, 0.5, q, out.rb_mut());
                self.add_located_jacobian(b, 0.5, q, out);
            }
        }
    }

    fn point_bias_acceleration(&self, p: RodPoint, q: &[f64], v: &[f64]) -> Vector2<f64> {
        match self.locate(p) {
            (a, None) => self.located_bias(a, q, v),
            (a, Some(b)) => (self.located_bias(a, q, v) + self.located_bias(b, q, v)) * 0.5,
        }
    }

    fn add_point_force_tangent(
        &self,
        p: RodPoint,
        q: &[f64],
        f: Vector2<f64>,
        coef: f64,
        mut out: MatMut<'_, f64>,
    ) {
        match self.locate(p) {
            (a, None) => self.add_located_force_tangent(a, q, f, coef, out),
            (a, Some(b)) => {
                self.add_located_force_tangent(a, q, f, 0.5 * coef, out.rb_mut());
                self.add_located_force_tangent(b, q, f, 0.5 * coef, out);
            }
        }
    }

    fn kinetic_energy(&self, q: &[f64], v: &[f64]) -> f64 {
        // T = sum_k (m |g_k'|^2 + I_c theta_k'^2) / 2, accumulating the joint velocities.
        let mut joint = Vector2::new(v[0], v[1]);
        let mut t2 = 0.0;
        for k in 0..self.n_seg {
            let t = self.theta_index(k);
            let (_, nn) = axes(q[t]);
            let g = joint + nn * (self.centroids[k] * v[t]);
            t2 += self.masses[k] * g.norm_squared() + self.inertias[k] * v[t] * v[t];
            joint += self.joint_velocity(k, q, v);
        }
        for (e, p) in self.pins().into_iter().enumerate() {
            t2 += self.end_mass[e] * self.located_velocity(p, q, v).norm_squared();
            if self.has_end_rotation(e) {
                let w = v[self.end_rotation_index(e)];
                t2 += self.end_inertia[e] * w * w;
            }
        }
        0.5 * t2
    }

    fn strain_energy(&self, q: &[f64]) -> f64 {
        let mut u = 0.0;
        for j in 0..self.n_seg.saturating_sub(1) {
            let d = q[self.theta_index(j + 1)] - q[self.theta_index(j)];
            u += self.k_rot[j] * d * d;
        }
        for j in 0..self.n_stretch() {
            let s = q[self.stretch_index(j)];
            u += self.k_ax[j] * s * s;
        }
        for i in 0..self.n_shear() {
            let t = q[self.shear_index(i)];
            u += self.k_sh[i] * t * t;
        }
        for (e, segment) in [(0, 0), (1, self.n_seg - 1)] {
            if self.has_end_rotation(e) {
                let d = q[self.end_rotation_index(e)] - q[self.theta_index(segment)];
                u += self.k_end[e] * d * d;
            }
        }
        0.5 * u
    }

    fn linear_momentum(&self, q: &[f64], v: &[f64]) -> Vector2<f64> {
        let mut joint = Vector2::new(v[0], v[1]);
        let mut p = Vector2::zeros();
        for k in 0..self.n_seg {
            let t = self.theta_index(k);
            let (_, nn) = axes(q[t]);
            p += (joint + nn * (self.centroids[k] * v[t])) * self.weights[k];
            joint += self.joint_velocity(k, q, v);
        }
        let mut ends = Vector2::zeros();
        for (p_end, m) in self.pins().into_iter().zip(self.end_mass) {
            ends += self.located_velocity(p_end, q, v) * m;
        }
        p * self.weight_scale + ends
    }

    fn frequencies_hz(&self) -> &[f64] {
        &self.frequencies
    }

    fn describe(&self) -> String {
        let mut kinds = vec!["rotational springs"];
        if self.axial {
            kinds.push("axial springs");
        }
        if self.shear {
            kinds.push("shear slides");
        }
        format!(
            "segment chain, {} segments with {}",
            self.n_seg,
            kinds.join(", ")
        )
    }

    fn length(&self) -> f64 {
        self.length
    }

    fn total_mass(&self) -> f64 {
        self.total_mass
    }
}

/// Most nonzero columns of a point's Jacobian: `x_B`, `y_B`, the angles, both slides of every
/// joint and an end slide.
const MAX_POINT_COLUMNS: usize = 3 + 3 * super::SEGMENT_RANGE.1;

impl SegmentRod {
    /// Number of joint slides (axial and shear, `N - 1` of each kind present; the end slides
    /// are not joint slides).
    #[inline]
    fn n_joint_slides(&self) -> usize {
        self.n_stretch() + if self.shear { self.n_seg - 1 } else { 0 }
    }

    /// `eta = sign t` of an end slide (0 without one).
    #[inline]
    fn end_offset(&self, end: Option<EndSlide>, q: &[f64]) -> f64 {
        end.map_or(0.0, |s| s.sign * q[s.index])
    }
}

impl SegmentRod {
    /// Add `weight` times the Jacobian of a located point to `out` (2 x n).
    fn add_located_jacobian(&self, p: Located, weight: f64, q: &[f64], mut out: MatMut<'_, f64>) {
        self.for_each_column(p, q, |c, u| {
            out[(0, c)] += weight * u.x;
            out[(1, c)] += weight * u.y;
        });
    }

    /// Add the mass matrix `m J^T J` of a point mass `m` (kg) at a located point to `mm`
    /// (its Jacobian's columns gathered on the stack: no allocation).
    fn add_point_mass(&self, p: Located, m: f64, q: &[f64], mut mm: MatMut<'_, f64>) {
        let mut cols = [(0usize, Vector2::zeros()); MAX_POINT_COLUMNS];
        let mut len = 0;
        self.for_each_column(p, q, |c, u| {
            cols[len] = (c, u);
            len += 1;
        });
        for &(i, ui) in &cols[..len] {
            for &(j, uj) in &cols[..len] {
                mm[(i, j)] += m * ui.dot(&uj);
            }
        }
    }

    /// Add `coef d(J^T f) / dq` of a located point to `out`:
    /// (J^T f)_theta_j = perp(d_j) . f, (J^T f)_s_j = e_j . f, (J^T f)_t_j = n_j . f;
    /// d perp(d_j) / d theta_j = -d_j, d perp(d_j) / d s_j = n_j, d perp(d_j) / d t_j = -e_j,
    /// d e_j / d theta_j = n_j, d n_j / d theta_j = -e_j. Exact.
    fn add_located_force_tangent(
        &self,
        p: Located,
        q: &[f64],
        f: Vector2<f64>,
        coef: f64,
        mut out: MatMut<'_, f64>,
    ) {
        for j in 0..p.k {
            let t = self.theta_index(j);
            let (e, nn) = axes(q[t]);
            out[(t, t)] -= coef * self.offset_q(j, q).vector(e, nn).dot(&f);
            if self.axial {
                let s = self.stretch_index(j);
                let c = coef * nn.dot(&f);
                out[(t, s)] += c;
                out[(s, t)] += c;
            }
            if self.shear {
                let s = self.shear_index(j + 1);
                let c = -coef * e.dot(&f);
                out[(t, s)] += c;
                out[(s, t)] += c;
            }
        }
        let t = self.theta_index(p.k);
        let (e, nn) = axes(q[t]);
        out[(t, t)] -= coef * (e * p.xi + nn * self.end_offset(p.end, q)).dot(&f);
        if let Some(s) = p.end {
            let c = -coef * s.sign * e.dot(&f);
            out[(t, s.index)] += c;
            out[(s.index, t)] += c;
        }
    }
}
