//! Material points of the FFR rod: body-frame position `ubar = xbar + S_hat p` (with the chord
//! foreshortening at C when the axial stiffening is on) and its derivatives, and the helpers
//! for `A(phi)` and `I~`. Frames: `ubar` in the body frame, positions global, m.

use nalgebra::{DMatrix, Vector2};

use super::rod::FfrRod;
use crate::rod::body::RodPoint;

/// Rotation matrix entries (cos, sin).
#[inline]
pub(super) fn rot(phi: f64) -> (f64, f64) {
    (phi.cos(), phi.sin())
}

/// `A v`.
#[inline]
pub(super) fn rotate(c: f64, s: f64, v: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(c * v.x - s * v.y, s * v.x + c * v.y)
}

/// `I~ v` (rotation by +90 degrees).
#[inline]
pub(super) fn tilde(v: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(-v.y, v.x)
}

impl FfrRod {
    pub(super) fn point_data(&self, p: RodPoint) -> (f64, &DMatrix<f64>) {
        let ig = &self.integrals;
        match p {
            RodPoint::B => (ig.x_b, &ig.s_b),
            RodPoint::C => (ig.x_c, &ig.s_c),
            RodPoint::Mid => (ig.x_mid, &ig.s_mid),
        }
    }

    /// Body-frame position of a material point, `ubar = xbar + S_hat p`, and at the C end,
    /// with axial stiffening on, the foreshortening of the chord `-1/2 p^T G_0 p` along x.
    pub(super) fn ubar(&self, p: RodPoint, q: &[f64]) -> Vector2<f64> {
        let (x, s) = self.point_data(p);
        // 2 x n by construction (`modal::point_shape` of the rod's n modes); the zip below
        // relies on it.
        debug_assert_eq!(s.shape(), (2, self.n), "S_hat of a point is 2 x n");
        let mut u = Vector2::new(x, 0.0);
        // `S_hat` is 2 x n and column-major: mode j's column is (x, y).
        for (column, &pj) in s.as_slice().chunks_exact(2).zip(&q[3..3 + self.n]) {
            u.x += column[0] * pj;
            u.y += column[1] * pj;
        }
        if self.foreshortening(p) {
            u.x -= 0.5 * self.quad(&q[3..], &q[3..]);
        }
        u
    }

    /// Body-frame position of the material point at arc length `s` from B,
    /// `ubar(s) = (x_b + s, 0) + S_hat(s) p` (Agrawal and Shabana 1985, eq. 3.5; `S_hat(s)` as
    /// `modal::point_shape`, the element's shape functions times the element rows of the
    /// mode shapes), summed in place without allocating. No chord foreshortening: it is
    /// applied at C alone ([`FfrRod::ubar`]).
    pub(super) fn ubar_at(&self, s: f64, q: &[f64]) -> Vector2<f64> {
        let mesh = &self.modes.mesh;
        let s = s.clamp(0.0, self.length);
        let (e, xi) = mesh.locate(s);
        let mut u = Vector2::new(self.integrals.x_b + s, 0.0);
        let mut add = |shape: &dyn Fn(usize, usize) -> f64, dofs: &[usize]| {
            for j in 0..self.n {
                let (mut sx, mut sy) = (0.0, 0.0);
                for (i, &d) in dofs.iter().enumerate() {
                    let phi = self.modes.shapes[(d, j)];
                    sx += shape(0, i) * phi;
                    sy += shape(1, i) * phi;
                }
                u.x += sx * q[3 + j];
                u.y += sy * q[3 + j];
            }
        };
        if mesh.is_plain() {
            // The closed-form element: fixed-size rows, no allocation.
            let shape = mesh.element().shape(xi);
            let b = 3 * e;
            add(
                &|r, i| shape[(r, i)],
                &[b, b + 1, b + 2, b + 3, b + 4, b + 5],
            );
        } else {
            let shape = mesh.shape(e, xi);
            add(&|r, i| shape[(r, i)], &mesh.element_dofs(e));
        }
        u
    }

    /// Body-frame `d ubar / dp` column j (with the foreshortening at C).
    pub(super) fn ubar_p(&self, p: RodPoint, q: &[f64], j: usize) -> Vector2<f64> {
        let (_, sh) = self.point_data(p);
        let mut c = Vector2::new(sh[(0, j)], sh[(1, j)]);
        if self.foreshortening(p) {
            let g = &self.integrals.g[0];
            c.x -= (0..self.n).map(|k| g[(j, k)] * q[3 + k]).sum::<f64>();
        }
        c
    }

    /// Body-frame `S_hat x` at a point for modal values `x` (rates `p'` or accelerations
    /// `p''`), without the chord's foreshortening.
    pub(super) fn shape_times(&self, p: RodPoint, x: &[f64]) -> Vector2<f64> {
        let (_, sh) = self.point_data(p);
        let mut u = Vector2::zeros();
        for (j, &xj) in x.iter().enumerate().take(self.n) {
            u += Vector2::new(sh[(0, j)], sh[(1, j)]) * xj;
        }
        u
    }

    /// Body-frame elastic velocity `(d ubar / dp) p'` at a point.
    pub(super) fn shape_rate(&self, p: RodPoint, q: &[f64], v: &[f64]) -> Vector2<f64> {
        let mut u = Vector2::zeros();
        for j in 0..self.n {
            u += self.ubar_p(p, q, j) * v[3 + j];
        }
        u
    }

    /// `I1 + I2 p` (body frame).
    pub(super) fn first_moment(&self, q: &[f64]) -> Vector2<f64> {
        let ig = &self.integrals;
        let mut c = ig.i1;
        for j in 0..self.n {
            c.x += ig.i2[(0, j)] * q[3 + j];
            c.y += ig.i2[(1, j)] * q[3 + j];
        }
        c
    }
}
