//! Kinematics of the segment chain: material points, their velocities and the
//! velocity-product (bias) part of their accelerations, and the joint offsets (the lever arms
//! of the axial slides and the shear slides). Positions global, m; `xi` in m along a segment
//! from its B-side joint.

use nalgebra::Vector2;

use super::rod::SegmentRod;
use crate::rod::body::RodPoint;

/// Unit vectors `(e, n)` of angle `theta`: along the segment and 90 degrees to its left.
#[inline]
pub(super) fn axes(theta: f64) -> (Vector2<f64>, Vector2<f64>) {
    let (s, c) = theta.sin_cos();
    (Vector2::new(c, s), Vector2::new(-s, c))
}

/// Joint `j`'s offset from the start of segment `j` to the start of segment `j + 1`, in
/// segment `j`'s axes: `d_j = L_j e_j + t_j n_j` with `L_j = l + s_j` (axial slide) and `t_j`
/// (shear slide), and their rates.
#[derive(Clone, Copy, Debug)]
pub(super) struct JointOffset {
    /// `L_j`, m, and `L_j' = s_j'`, m/s.
    pub along: f64,
    pub along_rate: f64,
    /// `t_j`, m, and `t_j'`, m/s.
    pub across: f64,
    pub across_rate: f64,
}

impl JointOffset {
    /// `d_j` (global) for the axes `(e, n)` of segment `j`.
    #[inline]
    pub fn vector(&self, e: Vector2<f64>, n: Vector2<f64>) -> Vector2<f64> {
        e * self.along + n * self.across
    }

    /// `perp(d_j) = L_j n_j - t_j e_j = d d_j / d theta_j` (`d_j` turned 90 degrees).
    #[inline]
    pub fn lever(&self, e: Vector2<f64>, n: Vector2<f64>) -> Vector2<f64> {
        n * self.along - e * self.across
    }

    /// The slides' share of `d_j'`: `s_j' e_j + t_j' n_j`.
    #[inline]
    pub fn slide_rate(&self, e: Vector2<f64>, n: Vector2<f64>) -> Vector2<f64> {
        e * self.along_rate + n * self.across_rate
    }
}

/// A rod point: the point `xi` along segment `k` (m from its B-side joint), across the end
/// slide `end` if any.
#[derive(Clone, Copy, Debug)]
pub(super) struct Located {
    pub k: usize,
    pub xi: f64,
    pub end: Option<EndSlide>,
}

/// The end slide of a pin: the pin is the point `(xi, eta)` of segment `k` in its axes,
/// `eta = sign t` with `t = q[index]` (B: `-t_B` on segment 0 at `xi = 0`, C: `+t_C` on segment
/// `N - 1` at `xi = l`).
#[derive(Clone, Copy, Debug)]
pub(super) struct EndSlide {
    pub index: usize,
    pub sign: f64,
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

    /// Number of shear slide coordinates (N + 1 with shear deformation, else 0).
    #[inline]
    pub(super) fn n_shear(&self) -> usize {
        if self.shear {
            self.n_seg + 1
        } else {
            0
        }
    }

    /// Number of end body rotation coordinates (`phi_B`, `phi_C`: one per end body with an
    /// inertia).
    #[inline]
    pub(super) fn n_end_rotations(&self) -> usize {
        usize::from(self.has_end_rotation(0)) + usize::from(self.has_end_rotation(1))
    }

    /// Joint `j`'s offset with its rates (`L_j = l`, `t_j = 0` past the last joint or without
    /// the slides).
    #[inline]
    pub(super) fn offset(&self, j: usize, q: &[f64], v: &[f64]) -> JointOffset {
        self.offset_with(j, q, Some(v))
    }

    /// Joint `j`'s offset from positions only (rates zero).
    #[inline]
    pub(super) fn offset_q(&self, j: usize, q: &[f64]) -> JointOffset {
        self.offset_with(j, q, None)
    }

    /// [`Self::offset`], the rates read from `v` if given.
    #[inline(always)]
    fn offset_with(&self, j: usize, q: &[f64], v: Option<&[f64]>) -> JointOffset {
        let mut d = JointOffset {
            along: self.seg_len,
            along_rate: 0.0,
            across: 0.0,
            across_rate: 0.0,
        };
        if j + 1 < self.n_seg {
            let rate = |i: usize| v.map_or(0.0, |v| v[i]);
            if self.axial {
                let i = self.stretch_index(j);
                d.along += q[i];
                d.along_rate = rate(i);
            }
            if self.shear {
                let i = self.shear_index(j + 1);
                d.across = q[i];
                d.across_rate = rate(i);
            }
        }
        d
    }

    /// Where a rod point sits: one located point, or (the midpoint of a chain with joint
    /// slides and an even number of segments) the mean of two: the midpoint is then a joint,
    /// and the rod's centre line there is halfway across the joint's slides, between the end of
    /// segment `N/2 - 1` and the start of segment `N/2` (the slides stand for the strain of
    /// the length around the joint, so either side alone is off by half a slide, first order
    /// in `l`). B and C sit across their end slides from the segments' ends (shear-deformable
    /// chains).
    #[inline]
    pub(super) fn locate(&self, p: RodPoint) -> (Located, Option<Located>) {
        let on = |k: usize, xi: f64| Located { k, xi, end: None };
        match p {
            RodPoint::B => (
                Located {
                    k: 0,
                    xi: 0.0,
                    end: self.shear.then(|| EndSlide {
                        index: self.shear_index(0),
                        sign: -1.0,
                    }),
                },
                None,
            ),
            RodPoint::C => (
                Located {
                    k: self.n_seg - 1,
                    xi: self.seg_len,
                    end: self.shear.then(|| EndSlide {
                        index: self.shear_index(self.n_seg),
                        sign: 1.0,
                    }),
                },
                None,
            ),
            RodPoint::Mid => {
                let (k, xi) = self.mid;
                if xi == 0.0 && k > 0 && (self.axial || self.shear) {
                    (on(k - 1, self.seg_len), Some(on(k, 0.0)))
                } else {
                    (on(k, xi), None)
                }
            }
        }
    }

    /// Position of the material point at `xi` on segment `k`: `S_0 + sum_{j<k} d_j + xi e_k`
    /// (`S_0 = (q_0, q_1)` the start of segment 0, B itself without shear deformation).
    pub fn material_point(&self, k: usize, xi: f64, q: &[f64]) -> Vector2<f64> {
        let mut r = Vector2::new(q[0], q[1]);
        for j in 0..k {
            let (e, n) = axes(q[self.theta_index(j)]);
            r += self.offset_q(j, q).vector(e, n);
        }
        let (e, _) = axes(q[self.theta_index(k)]);
        r + e * xi
    }

    /// Position of a located point: its material point, plus `eta n_k` across an end slide.
    pub(super) fn located_point(&self, p: Located, q: &[f64]) -> Vector2<f64> {
        let r = self.material_point(p.k, p.xi, q);
        match p.end {
            Some(s) => {
                let (_, n) = axes(q[self.theta_index(p.k)]);
                r + n * (s.sign * q[s.index])
            }
            None => r,
        }
    }

    /// The columns of a located point's Jacobian `d r / d q`, each nonzero column once:
    /// `d r / d theta_j = perp(d_j)` (j < k), `d r / d s_j = e_j`, `d r / d t_j = n_j`; on the
    /// point's own segment `perp(xi e_k + eta n_k)`, and `sign n_k` for its end slide.
    pub(super) fn for_each_column<F: FnMut(usize, Vector2<f64>)>(
        &self,
        p: Located,
        q: &[f64],
        mut f: F,
    ) {
        f(0, Vector2::new(1.0, 0.0));
        f(1, Vector2::new(0.0, 1.0));
        for j in 0..p.k {
            let t = self.theta_index(j);
            let (e, nn) = axes(q[t]);
            f(t, self.offset_q(j, q).lever(e, nn));
            if self.axial {
                f(self.stretch_index(j), e);
            }
            if self.shear {
                f(self.shear_index(j + 1), nn);
            }
        }
        let t = self.theta_index(p.k);
        let (e, nn) = axes(q[t]);
        let eta = p.end.map_or(0.0, |s| s.sign * q[s.index]);
        f(t, nn * p.xi - e * eta);
        if let Some(s) = p.end {
            f(s.index, nn * s.sign);
        }
    }

    /// `J q'` of a located point (its velocity for `q' = v`; with the accelerations, the part
    /// of its acceleration without [`Self::located_bias`]).
    pub(super) fn located_velocity(&self, p: Located, q: &[f64], v: &[f64]) -> Vector2<f64> {
        let mut r = Vector2::zeros();
        self.for_each_column(p, q, |c, u| r += u * v[c]);
        r
    }

    /// The pins B and C as located points (the end bodies' places).
    #[inline]
    pub(super) fn pins(&self) -> [Located; 2] {
        [self.locate(RodPoint::B).0, self.locate(RodPoint::C).0]
    }

    /// Velocity of the material point at `xi` on segment `k`.
    pub fn material_velocity(&self, k: usize, xi: f64, q: &[f64], v: &[f64]) -> Vector2<f64> {
        let mut r = Vector2::new(v[0], v[1]);
        for j in 0..k {
            r += self.joint_velocity(j, q, v);
        }
        let t = self.theta_index(k);
        let (_, nn) = axes(q[t]);
        r + nn * (xi * v[t])
    }

    /// `d_j' = s_j' e_j + t_j' n_j + theta_j' perp(d_j)`.
    #[inline]
    pub(super) fn joint_velocity(&self, j: usize, q: &[f64], v: &[f64]) -> Vector2<f64> {
        let t = self.theta_index(j);
        let (e, n) = axes(q[t]);
        let d = self.offset(j, q, v);
        d.slide_rate(e, n) + d.lever(e, n) * v[t]
    }

    /// `b_j = 2 theta_j' (s_j' n_j - t_j' e_j) - theta_j'^2 d_j`: joint j's share of the
    /// velocity-product acceleration of everything beyond it.
    #[inline]
    pub(super) fn bias_term(&self, j: usize, q: &[f64], v: &[f64]) -> Vector2<f64> {
        let t = self.theta_index(j);
        let (e, nn) = axes(q[t]);
        let d = self.offset(j, q, v);
        let w = v[t];
        (nn * d.along_rate - e * d.across_rate) * (2.0 * w) - d.vector(e, nn) * (w * w)
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

    /// [`Self::bias_at`] of a rod point, with its end slide `eta n_k`:
    /// `- 2 eta' theta_k' e_k - eta theta_k'^2 n_k` more.
    pub(super) fn located_bias(&self, p: Located, q: &[f64], v: &[f64]) -> Vector2<f64> {
        let g = self.bias_at(p.k, p.xi, q, v);
        match p.end {
            Some(s) => {
                let t = self.theta_index(p.k);
                let (e, n) = axes(q[t]);
                let (eta, eta_rate) = (s.sign * q[s.index], s.sign * v[s.index]);
                let w = v[t];
                g - e * (2.0 * eta_rate * w) - n * (eta * w * w)
            }
            None => g,
        }
    }
}
