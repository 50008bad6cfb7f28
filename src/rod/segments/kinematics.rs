//! Kinematics of the segment chain: material points, their velocities and the
//! velocity-product (bias) part of their accelerations, and the lever arms of the axial
//! springs. Positions global, m; `xi` in [0, 1] along a segment from its B-side joint.

use nalgebra::Vector2;

use super::rod::SegmentRod;
use crate::rod::body::RodPoint;

/// Unit vectors `(e, n)` of angle `theta`: along the segment and 90 degrees to its left.
#[inline]
pub(super) fn axes(theta: f64) -> (Vector2<f64>, Vector2<f64>) {
    let (s, c) = theta.sin_cos();
    (Vector2::new(c, s), Vector2::new(-s, c))
}

impl SegmentRod {
    /// Number of slide coordinates (N - 1 with axial springs, else 0).
    #[inline]
    pub(super) fn n_stretch(&self) -> usize {
        if self.axial {
            self.n_seg - 1
        } else {
            0
        }
    }

    /// `L_j = l + s_j` and `s_j'` of joint `j` (`l`, 0 past the last joint or without springs).
    #[inline]
    pub(super) fn lever(&self, j: usize, q: &[f64], v: &[f64]) -> (f64, f64) {
        if self.axial && j + 1 < self.n_seg {
            let i = self.stretch_index(j);
            (self.seg_len + q[i], v[i])
        } else {
            (self.seg_len, 0.0)
        }
    }

    /// `L_j` from positions only.
    #[inline]
    pub(super) fn lever_q(&self, j: usize, q: &[f64]) -> f64 {
        if self.axial && j + 1 < self.n_seg {
            self.seg_len + q[self.stretch_index(j)]
        } else {
            self.seg_len
        }
    }

    /// Segment and offset of a rod point.
    #[inline]
    pub(super) fn locate(&self, p: RodPoint) -> (usize, f64) {
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
    pub(super) fn bias_term(&self, j: usize, q: &[f64], v: &[f64]) -> Vector2<f64> {
        let t = self.theta_index(j);
        let (e, nn) = axes(q[t]);
        let (lj, sd) = self.lever(j, q, v);
        let w = v[t];
        nn * (2.0 * sd * w) - e * (lj * w * w)
    }

    /// Velocity-product acceleration `J' q'` of the point at `xi` on segment `k`.
    pub(super) fn bias_at(&self, k: usize, xi: f64, q: &[f64], v: &[f64]) -> Vector2<f64> {
        let mut g = Vector2::zeros();
        for j in 0..k {
            g += self.bias_term(j, q, v);
        }
        let t = self.theta_index(k);
        let (e, _) = axes(q[t]);
        g - e * (xi * v[t] * v[t])
    }
}
