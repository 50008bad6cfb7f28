//! The segment chain as a [`RodBody`]: mass matrix, forces, points and energies (the
//! equations are in the documentation of [`super::rod`]).

use faer::MatMut;
use nalgebra::Vector2;

use super::kinematics::axes;
use super::rod::SegmentRod;
use crate::rod::body::{RodBody, RodPoint};
use crate::rod::sections::LoadWalk;

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

    fn add_gravity(&self, q: &[f64], g: Vector2<f64>, f: &mut [f64]) {
        // Sum over the segment centroids of m_k g . d g_k / dq: Q_B = m g,
        // Q_theta_i = (f_i + a_i L_i) n_i . g, Q_s_j = a_j e_j . g.
        f[0] += self.total * g.x;
        f[1] += self.total * g.y;
        for i in 0..self.n_seg {
            let t = self.theta_index(i);
            let (e, n) = axes(q[t]);
            let h = self.first[i] + self.beyond[i] * self.lever_q(i, q);
            f[t] += h * n.dot(&g);
            if self.axial && i + 1 < self.n_seg {
                f[self.stretch_index(i)] += self.beyond[i] * e.dot(&g);
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
        // Walk from C: the pin force, then segment k (its centroid's d'Alembert force and
        // couple) before the cut at its B-side joint (cut k; cut N is C). The end bodies are
        // part of the first and last segments.
        let n = self.n_seg;
        let mut walk = LoadWalk::new();
        let r_c = self.material_point(n - 1, self.seg_len, q);
        walk.add(r_c, force_c, 0.0);
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
        let n = self.n_seg;
        let ns = self.n_stretch();
        let a = |j: usize| self.beyond[j];
        // B block.
        mm[(0, 0)] = self.total;
        mm[(1, 1)] = self.total;
        mm[(0, 1)] = 0.0;
        mm[(1, 0)] = 0.0;
        for j in 0..n {
            let tj = self.theta_index(j);
            let (ej, nj) = axes(q[tj]);
            let lj = self.lever_q(j, q);
            let hj = self.first[j] + a(j) * lj;
            mm[(0, tj)] = hj * nj.x;
            mm[(1, tj)] = hj * nj.y;
            mm[(tj, 0)] = hj * nj.x;
            mm[(tj, 1)] = hj * nj.y;
            // Angle-angle block: row i <= j.
            mm[(tj, tj)] = self.second[j] + a(j) * lj * lj;
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
                    (self.first[i] + a(i) * self.lever_q(i, q)) * snij
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
            let (li, _) = self.lever(i, q, v);
            f[t] = -m * nn.dot(&(gamma_i * self.weighted_first[i] + downstream * li));
            if self.axial && i + 1 < n {
                let s = self.stretch_index(i);
                f[s] = -m * e.dot(&downstream) - self.k_ax[i] * q[s] - self.c_ax[i] * v[s];
            }
            prefix += self.bias_term(i, q, v);
        }
        // Joint springs and dampers.
        for j in 0..n.saturating_sub(1) {
            let (ti, tj) = (self.theta_index(j), self.theta_index(j + 1));
            let tau = self.k_rot[j] * (q[tj] - q[ti]) + self.c_rot[j] * (v[tj] - v[ti]);
            f[ti] += tau;
            f[tj] -= tau;
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
    }

    fn point(&self, p: RodPoint, q: &[f64]) -> Vector2<f64> {
        let (k, xi) = self.locate(p);
        self.material_point(k, xi, q)
    }

    fn point_at(&self, s: f64, q: &[f64]) -> Vector2<f64> {
        // Segment k holds the arc lengths k l .. (k + 1) l; rigid, so the point is at s - k l
        // along it from its B-side joint.
        let s = s.clamp(0.0, self.length);
        let k = ((s / self.seg_len).floor() as usize).min(self.n_seg - 1);
        self.material_point(k, s - k as f64 * self.seg_len, q)
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
        let mut joint = Vector2::new(v[0], v[1]);
        let mut t2 = 0.0;
        for k in 0..self.n_seg {
            let t = self.theta_index(k);
            let (e, nn) = axes(q[t]);
            let g = joint + nn * (self.centroids[k] * v[t]);
            t2 += self.masses[k] * g.norm_squared() + self.inertias[k] * v[t] * v[t];
            let (lk, sd) = self.lever(k, q, v);
            joint += e * sd + nn * (lk * v[t]);
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
        0.5 * u
    }

    fn linear_momentum(&self, q: &[f64], v: &[f64]) -> Vector2<f64> {
        let mut joint = Vector2::new(v[0], v[1]);
        let mut p = Vector2::zeros();
        for k in 0..self.n_seg {
            let t = self.theta_index(k);
            let (e, nn) = axes(q[t]);
            p += (joint + nn * (self.centroids[k] * v[t])) * self.weights[k];
            let (lk, sd) = self.lever(k, q, v);
            joint += e * sd + nn * (lk * v[t]);
        }
        p * self.weight_scale
    }

    fn frequencies_hz(&self) -> &[f64] {
        &self.frequencies
    }

    fn length(&self) -> f64 {
        self.length
    }

    fn total_mass(&self) -> f64 {
        self.total_mass
    }
}
