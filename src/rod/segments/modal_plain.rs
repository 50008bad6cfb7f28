//! The chain on its modes evaluated directly in its reduced coordinates, for a plain chain (no
//! shear slides, no end body rotations, no axial springs): the same equations as the projection
//! `T^T M(T r) T`, `T^T Q(T r, T r')` of [`super::modal`], in `O(N n^2)` instead of `O(N^2 n)`,
//! with one `sin`/`cos` per segment shared by every function at the same coordinates.
//!
//! With `r = [x_B, y_B, alpha, p_1 .. p_m]` (`n = 3 + m`), the segment angles are
//! `theta_k = sum_c Psi_kc r_c` (`Psi_k,alpha = 1`, `Psi_k,p_i` the mode's angle on segment
//! `k`, zero on `x_B`, `y_B`), and with `e_k = (cos theta_k, sin theta_k)`,
//! `n_k = (-sin theta_k, cos theta_k)` (docs/physics.md, "Rod model 2" and "Rod model 3"):
//! - the centroid `g_k = B + sum_{j<k} l e_j + c_k e_k` has the reduced partial velocities
//!   `G_k = d g_k / d r`: `(1, 0)`, `(0, 1)` on `x_B`, `y_B`, and
//!   `P_k,c + c_k n_k Psi_kc` on the angle columns, `P_k,c = sum_{j<k} l n_j Psi_jc`;
//! - mass `M_r = sum_k (m_k G_k^T G_k + I_k Psi_k Psi_k^T) + m_B J_B^T J_B + m_C J_C^T J_C`
//!   (the end bodies' masses at the pins, `J_C = [I, P_N]`);
//! - velocity products `Q_r = -sum_k m_k G_k^T gamma_k - m_C J_C^T gamma_C`, with
//!   `gamma_k = -sum_{j<k} l w_j^2 e_j - c_k w_k^2 e_k` and `w_k = sum_c Psi_kc r_c'`;
//! - joint springs and dampers, linear in the angle differences: the constant reduced
//!   matrices `K_r = T^T K T`, `C_r = T^T C T` of the chain ([`Plain::new`] takes them).

use faer::MatMut;
use nalgebra::Vector2;

use super::rod::SegmentRod;
use crate::rod::body::RodPoint;

/// Largest number of reduced coordinates of the direct evaluation (`3 +` modes).
pub const MAX_REDUCED: usize = 3 + 16;

/// One row of reduced coordinates on the stack.
type Row = [f64; MAX_REDUCED];

/// The plain chain's data in reduced coordinates.
pub(super) struct Plain {
    /// Reduced coordinates, `3 + m`.
    n: usize,
    /// Segment length l, m.
    l: f64,
    /// Per segment: mass m_k (kg), centroid offset c_k (m), centroidal inertia I_k (kg m^2).
    masses: Vec<f64>,
    centroids: Vec<f64>,
    inertias: Vec<f64>,
    /// `Psi`, segment-major: `psi[k * n + c]` (zero for c = 0, 1).
    psi: Vec<f64>,
    /// End bodies' masses at B and C, kg.
    end_mass: [f64; 2],
    /// The material midpoint: segment and distance from its start, m.
    mid: (usize, f64),
    /// `K_r`, `C_r` (n x n, row-major).
    stiffness: Vec<f64>,
    damping: Vec<f64>,
}

/// Angles' cosines and sines at the last coordinates asked for: `theta_k = alpha + phi_k(p)`,
/// the elastic part `phi_k` kept while the modal coordinates `p` stay (the constraint
/// iterations change only `x_B`, `y_B`, `alpha`), turned by `alpha` without another `sin`,
/// `cos` per segment.
pub(super) struct Trig {
    r: Vec<f64>,
    valid: bool,
    cos: Vec<f64>,
    sin: Vec<f64>,
    elastic_valid: bool,
    elastic_cos: Vec<f64>,
    elastic_sin: Vec<f64>,
}

impl Trig {
    pub(super) fn new(n: usize, segments: usize) -> Trig {
        Trig {
            r: vec![0.0; n],
            valid: false,
            cos: vec![0.0; segments],
            sin: vec![0.0; segments],
            elastic_valid: false,
            elastic_cos: vec![0.0; segments],
            elastic_sin: vec![0.0; segments],
        }
    }
}

impl Plain {
    /// The plain chain `chain` with the basis `psi(k, c)` (segment `k`'s angle per reduced
    /// coordinate `c`) and its reduced spring and damper matrices (row-major, `n x n`).
    pub(super) fn new(
        chain: &SegmentRod,
        n: usize,
        psi: impl Fn(usize, usize) -> f64,
        stiffness: Vec<f64>,
        damping: Vec<f64>,
    ) -> Plain {
        assert!(n <= MAX_REDUCED);
        let segments = chain.n_seg;
        let mut table = vec![0.0; segments * n];
        for k in 0..segments {
            for c in 2..n {
                table[k * n + c] = psi(k, c);
            }
        }
        Plain {
            n,
            l: chain.seg_len,
            masses: chain.masses.clone(),
            centroids: chain.centroids.clone(),
            inertias: chain.inertias.clone(),
            psi: table,
            end_mass: chain.end_mass,
            mid: chain.mid,
            stiffness,
            damping,
        }
    }

    fn segments(&self) -> usize {
        self.masses.len()
    }

    fn psi(&self, k: usize) -> &[f64] {
        &self.psi[k * self.n..(k + 1) * self.n]
    }

    /// The segment angle rates `w_k = Psi_k . r'`.
    fn rate(&self, k: usize, v: &[f64]) -> f64 {
        self.psi(k)[2..]
            .iter()
            .zip(&v[2..self.n])
            .map(|(a, b)| a * b)
            .sum()
    }

    /// Cosines and sines of the angles at `r` into `trig` (kept while `r` is the same).
    pub(super) fn angles(&self, r: &[f64], trig: &mut Trig) {
        let r = &r[..self.n];
        let same = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits());
        if trig.valid && same(&trig.r, r) {
            return;
        }
        if !(trig.elastic_valid && same(&trig.r[3..], &r[3..])) {
            // Psi_k,alpha = 1: the elastic part is the modes' share alone.
            for k in 0..self.segments() {
                let phi: f64 = self.psi(k)[3..]
                    .iter()
                    .zip(&r[3..])
                    .map(|(a, b)| a * b)
                    .sum();
                let (s, c) = phi.sin_cos();
                trig.elastic_cos[k] = c;
                trig.elastic_sin[k] = s;
            }
            trig.elastic_valid = true;
        }
        let (sa, ca) = r[2].sin_cos();
        for k in 0..self.segments() {
            let (c, s) = (trig.elastic_cos[k], trig.elastic_sin[k]);
            trig.cos[k] = ca * c - sa * s;
            trig.sin[k] = sa * c + ca * s;
        }
        trig.r.copy_from_slice(r);
        trig.valid = true;
    }

    fn axes(trig: &Trig, k: usize) -> (Vector2<f64>, Vector2<f64>) {
        let (c, s) = (trig.cos[k], trig.sin[k]);
        (Vector2::new(c, s), Vector2::new(-s, c))
    }

    /// `J_P` of point `p` in reduced coordinates, column `c` of the angle part (`c >= 2`)
    /// through `columns(c, vector)`; the columns of `x_B`, `y_B` are the unit vectors.
    fn point_columns(
        &self,
        p: RodPoint,
        trig: &Trig,
        mut columns: impl FnMut(usize, Vector2<f64>),
    ) {
        let (k_end, xi) = match p {
            RodPoint::B => (0, 0.0),
            RodPoint::C => (self.segments() - 1, self.l),
            RodPoint::Mid => self.mid,
        };
        let mut acc = [Vector2::zeros(); MAX_REDUCED];
        if p != RodPoint::B {
            for k in 0..=k_end {
                let (_, nn) = Self::axes(trig, k);
                let lever = if k < k_end { self.l } else { xi };
                let psi = self.psi(k);
                for c in 2..self.n {
                    acc[c] += nn * (lever * psi[c]);
                }
            }
        }
        for (c, a) in acc.iter().enumerate().take(self.n).skip(2) {
            columns(c, *a);
        }
    }

    /// Position of `p`.
    pub(super) fn point(&self, p: RodPoint, r: &[f64], trig: &Trig) -> Vector2<f64> {
        let mut x = Vector2::new(r[0], r[1]);
        let (k_end, xi) = match p {
            RodPoint::B => return x,
            RodPoint::C => (self.segments() - 1, self.l),
            RodPoint::Mid => self.mid,
        };
        for k in 0..=k_end {
            let (e, _) = Self::axes(trig, k);
            x += e * if k < k_end { self.l } else { xi };
        }
        x
    }

    /// `J_P` (2 x n) into `out`.
    pub(super) fn point_jacobian(&self, p: RodPoint, trig: &Trig, mut out: MatMut<'_, f64>) {
        out[(0, 0)] = 1.0;
        out[(1, 0)] = 0.0;
        out[(0, 1)] = 0.0;
        out[(1, 1)] = 1.0;
        self.point_columns(p, trig, |c, u| {
            out[(0, c)] = u.x;
            out[(1, c)] = u.y;
        });
    }

    /// `J_P' r'`: `-sum l w_k^2 e_k` over the segments up to the point.
    pub(super) fn point_bias(&self, p: RodPoint, v: &[f64], trig: &Trig) -> Vector2<f64> {
        let (k_end, xi) = match p {
            RodPoint::B => return Vector2::zeros(),
            RodPoint::C => (self.segments() - 1, self.l),
            RodPoint::Mid => self.mid,
        };
        let mut a = Vector2::zeros();
        for k in 0..=k_end {
            let (e, _) = Self::axes(trig, k);
            let w = self.rate(k, v);
            a -= e * (w * w * if k < k_end { self.l } else { xi });
        }
        a
    }

    /// Walk the segments with their reduced partial velocities `G_k` (angle columns; the
    /// columns of `x_B`, `y_B` are the unit vectors) and, with velocities `v`, the centroid's
    /// velocity-product acceleration `gamma_k`: `visit(k, G_k, gamma_k)`. Returns `J_C`'s
    /// angle columns and `gamma_C`.
    fn walk(
        &self,
        trig: &Trig,
        v: Option<&[f64]>,
        mut visit: impl FnMut(usize, &[Vector2<f64>; MAX_REDUCED], Vector2<f64>),
    ) -> ([Vector2<f64>; MAX_REDUCED], Vector2<f64>) {
        let n = self.n;
        let mut prefix = [Vector2::zeros(); MAX_REDUCED];
        let mut g = [Vector2::zeros(); MAX_REDUCED];
        let mut gamma_prefix = Vector2::zeros();
        for k in 0..self.segments() {
            let (e, nn) = Self::axes(trig, k);
            let psi = self.psi(k);
            let ck = self.centroids[k];
            for c in 2..n {
                g[c] = prefix[c] + nn * (ck * psi[c]);
            }
            let w2 = v.map_or(0.0, |v| {
                let w = self.rate(k, v);
                w * w
            });
            visit(k, &g, gamma_prefix - e * (ck * w2));
            for c in 2..n {
                prefix[c] += nn * (self.l * psi[c]);
            }
            gamma_prefix -= e * (self.l * w2);
        }
        (prefix, gamma_prefix)
    }

    /// The mass matrix (n x n) into `out` (overwritten): the walk of [`Self::walk`] with the
    /// partial velocities' components in plain arrays (the inner loop of `O(N n^2)`).
    pub(super) fn mass(&self, trig: &Trig, mut out: MatMut<'_, f64>) {
        let n = self.n;
        let mut m = [[0.0; MAX_REDUCED]; MAX_REDUCED];
        let (mut px, mut py) = ([0.0; MAX_REDUCED], [0.0; MAX_REDUCED]);
        let (mut gx, mut gy) = ([0.0; MAX_REDUCED], [0.0; MAX_REDUCED]);
        let mut add = |mass: f64, gx: &Row, gy: &Row, m: &mut [Row; MAX_REDUCED]| {
            for c in 2..n {
                let (ax, ay) = (mass * gx[c], mass * gy[c]);
                m[0][c] += ax;
                m[1][c] += ay;
                let row = &mut m[c];
                for d in c..n {
                    row[d] += ax * gx[d] + ay * gy[d];
                }
            }
        };
        for k in 0..self.segments() {
            let (c_k, s_k) = (trig.cos[k], trig.sin[k]);
            let psi = self.psi(k);
            let ck = self.centroids[k];
            for c in 2..n {
                let lever = ck * psi[c];
                gx[c] = px[c] - s_k * lever;
                gy[c] = py[c] + c_k * lever;
            }
            add(self.masses[k], &gx, &gy, &mut m);
            let inertia = self.inertias[k];
            for c in 2..n {
                let a = inertia * psi[c];
                let row = &mut m[c];
                for d in c..n {
                    row[d] += a * psi[d];
                }
            }
            for c in 2..n {
                let lever = self.l * psi[c];
                px[c] -= s_k * lever;
                py[c] += c_k * lever;
            }
        }
        let total: f64 = self.masses.iter().sum::<f64>() + self.end_mass[0] + self.end_mass[1];
        if self.end_mass[1] > 0.0 {
            add(self.end_mass[1], &px, &py, &mut m);
        }
        m[0][0] = total;
        m[1][1] = total;
        for c in 0..n {
            for d in c..n {
                out[(c, d)] = m[c][d];
                out[(d, c)] = m[c][d];
            }
        }
    }

    /// Velocity products, springs and dampers (n entries, overwritten).
    pub(super) fn forces(&self, r: &[f64], v: &[f64], trig: &Trig, f: &mut [f64]) {
        let n = self.n;
        let mut q = [0.0; MAX_REDUCED];
        let mut project = |mass: f64, g: &[Vector2<f64>; MAX_REDUCED], gamma: Vector2<f64>| {
            q[0] -= mass * gamma.x;
            q[1] -= mass * gamma.y;
            for c in 2..n {
                q[c] -= mass * g[c].dot(&gamma);
            }
        };
        let (j_c, gamma_c) = self.walk(trig, Some(v), |k, g, gamma| {
            project(self.masses[k], g, gamma)
        });
        if self.end_mass[1] > 0.0 {
            project(self.end_mass[1], &j_c, gamma_c);
        }
        for (c, fc) in f[..n].iter_mut().enumerate() {
            let row = c * n;
            let mut x = q[c];
            for d in 0..n {
                x -= self.stiffness[row + d] * r[d] + self.damping[row + d] * v[d];
            }
            *fc = x;
        }
    }

    /// Add the gravity forces `sum m_k G_k^T g` (rod and end bodies) into `f`.
    pub(super) fn add_gravity(&self, trig: &Trig, g: Vector2<f64>, f: &mut [f64]) {
        let n = self.n;
        let mut total = self.end_mass[0];
        let mut q = [0.0; MAX_REDUCED];
        let (j_c, _) = self.walk(trig, None, |k, gk, _| {
            total += self.masses[k];
            for c in 2..n {
                q[c] += self.masses[k] * gk[c].dot(&g);
            }
        });
        total += self.end_mass[1];
        for c in 2..n {
            q[c] += self.end_mass[1] * j_c[c].dot(&g);
        }
        f[0] += total * g.x;
        f[1] += total * g.y;
        for c in 2..n {
            f[c] += q[c];
        }
    }
}
