//! The chain on its modes evaluated directly in its reduced coordinates, for a chain without
//! axial springs and end body rotations (with or without shear slides): the same equations as
//! the projection `T^T M(T r) T`, `T^T Q(T r, T r')` of [`super::modal`], in `O(N n^2)` instead
//! of `O(N^2 n)`, with one `sin`/`cos` per segment shared by every function at the same
//! coordinates.
//!
//! With `r = [x_B, y_B, alpha, p_1 .. p_m]` (`n = 3 + m`; `S_0`, the start of segment 0, is
//! `(x_B, y_B)` plus the modes' share: a shear chain's modes move it across B's end slide), the
//! segment angles are `theta_k = sum_c Psi_kc r_c` (`Psi_k,alpha = 1`)
//! and the shear slides `t_i = sum_c Sigma_ic r_c` (`i = 0..N`: `t_B`, the joints', `t_C`; zero
//! without shear). With `e_k = (cos theta_k, sin theta_k)`, `n_k = (-sin theta_k, cos theta_k)`,
//! the offsets `d_k = l e_k + t_{k+1} n_k` (docs/physics.md, "Rod model 2", "Shear-deformable
//! chains"; `d_{N-1}` ends at C) and `w_k`, `t_i'` the rates:
//! - the centroid `g_k = S_0 + sum_{j<k} d_j + c_k e_k` has the reduced partial velocities
//!   `G_k = d g_k / d r`: the unit vectors on `x_B`, `y_B`, and
//!   `P_k,c + c_k n_k Psi_kc` on the others, `P_k,c = d S_0 / d r_c + sum_{j<k} (perp(d_j)
//!   Psi_jc + n_j Sigma_{j+1,c})`, `perp(d_j) = l n_j - t_{j+1} e_j`;
//! - its velocity-product acceleration `gamma_k = sum_{j<k} (-2 w_j t_{j+1}' e_j - w_j^2 d_j)
//!   - c_k w_k^2 e_k`;
//! - mass `M_r = sum_k (m_k G_k^T G_k + I_k Psi_k Psi_k^T) + m_B J_B^T J_B + m_C J_C^T J_C`,
//!   velocity products `Q_r = -sum_k m_k G_k^T gamma_k - m_B J_B^T gamma_B - m_C J_C^T gamma_C`
//!   (the end bodies' masses at the pins);
//! - a point `S_0 + sum_{j<k} d_j + xi e_k + w t_i n_k` (B: `k = 0`, `xi = 0`, `t_B` with
//!   `w = -1`; C: `k = N - 1`, `xi = l`, `t_C` with `w = 1`; the midpoint) has the Jacobian
//!   `P_k + xi n_k Psi_k - w t_i e_k Psi_k + w n_k Sigma_i` and the velocity products
//!   `gamma` of its segments, `- xi w_k^2 e_k - w (2 w_k t_i' e_k + w_k^2 t_i n_k)`;
//! - joint springs and dampers, linear in the coordinates: the constant reduced matrices
//!   `K_r = T^T K T`, `C_r = T^T C T` of the chain ([`Plain::new`] takes them).

use faer::MatMut;
use nalgebra::Vector2;

use super::rod::SegmentRod;
use crate::rod::body::RodPoint;

/// Largest number of reduced coordinates of the direct evaluation (`3 +` modes).
pub const MAX_REDUCED: usize = 3 + 16;

/// One row of reduced coordinates on the stack.
type Row = [f64; MAX_REDUCED];

/// `self.method::<N>(args)` with `N = self.n` (4 to [`MAX_REDUCED`]): the loops over the reduced
/// coordinates get their length at compile time.
macro_rules! dispatch {
    ($self:ident . $method:ident ( $($arg:expr),* )) => {
        match $self.n {
            4 => $self.$method::<4>($($arg),*),
            5 => $self.$method::<5>($($arg),*),
            6 => $self.$method::<6>($($arg),*),
            7 => $self.$method::<7>($($arg),*),
            8 => $self.$method::<8>($($arg),*),
            9 => $self.$method::<9>($($arg),*),
            10 => $self.$method::<10>($($arg),*),
            11 => $self.$method::<11>($($arg),*),
            12 => $self.$method::<12>($($arg),*),
            13 => $self.$method::<13>($($arg),*),
            14 => $self.$method::<14>($($arg),*),
            15 => $self.$method::<15>($($arg),*),
            16 => $self.$method::<16>($($arg),*),
            17 => $self.$method::<17>($($arg),*),
            18 => $self.$method::<18>($($arg),*),
            19 => $self.$method::<19>($($arg),*),
            n => unreachable!("{n} reduced coordinates: 4 to {MAX_REDUCED}"),
        }
    };
}

/// A point of the chain: on segment `k` at `xi` (m) from its start, plus `w t_i n_k` across
/// the shear slide `i`.
#[derive(Clone, Copy, Debug)]
struct ChainPoint {
    k: usize,
    xi: f64,
    slide: Option<(usize, f64)>,
}

/// The chain's data in reduced coordinates.
pub(super) struct Plain {
    /// Reduced coordinates, `3 + m`.
    n: usize,
    /// Segment length l, m.
    l: f64,
    /// Per segment: mass m_k (kg), centroid offset c_k (m) (the inertias I_k about the
    /// centroids, the sections' rotary inertia included, are in `rotary`).
    masses: Vec<f64>,
    centroids: Vec<f64>,
    /// `Psi`, segment-major: `psi[k * n + c]` (zero for c = 0, 1).
    psi: Vec<f64>,
    /// `Sigma`, slide-major (`N + 1` slides): `sigma[i * n + c]`; all zero without shear.
    sigma: Vec<f64>,
    /// `S_0`'s share of the angle and slide columns (x, y): a shear chain's modes move `S_0`
    /// across the end slide at B, so that B stays (`y_0 = t_B`); zero without shear.
    base_x: Row,
    base_y: Row,
    /// End bodies' masses at B and C, kg.
    end_mass: [f64; 2],
    /// B, C and the midpoint.
    points: [ChainPoint; 3],
    /// `sum_k I_k Psi_k Psi_k^T` (n x n, row-major): the segments' rotary inertia, constant.
    rotary: Vec<f64>,
    /// The rod's and the end bodies' mass, kg.
    total_mass: f64,
    /// `K_r`, `C_r` (n x n, row-major).
    stiffness: Vec<f64>,
    damping: Vec<f64>,
}

/// Angles' cosines and sines and the slides at the last coordinates asked for:
/// `theta_k = alpha + phi_k(p)`, the elastic part `phi_k` kept while the modal coordinates `p`
/// stay (the constraint iterations change only `x_B`, `y_B`, `alpha`), turned by `alpha`
/// without another `sin`, `cos` per segment.
pub(super) struct Trig {
    r: Vec<f64>,
    valid: bool,
    /// `cos`, `sin` hold the segments' angles at `r` (turned by `alpha` only when a walk in
    /// the global axes asks: the pins' positions turn the body points instead).
    global_valid: bool,
    cos: Vec<f64>,
    sin: Vec<f64>,
    slides: Vec<f64>,
    elastic_valid: bool,
    /// The elastic angles `phi_k`, their cosines and sines.
    elastic: Vec<f64>,
    elastic_cos: Vec<f64>,
    elastic_sin: Vec<f64>,
    /// B's, C's and the midpoint's position (from `S_0`) and Jacobian columns at `r`, once
    /// computed (the constraint iterations ask for both at the same coordinates).
    points: [Option<(Vector2<f64>, Row, Row)>; 3],
    /// The same in the frame turned by `-alpha` without `S_0`'s share, kept while the modal
    /// coordinates stay: every vector of the walk turns with `alpha`, so the constraint
    /// iterations rotate these instead of walking the chain again.
    body_points: [Option<(Vector2<f64>, Row, Row)>; 3],
    /// `cos alpha`, `sin alpha` at `r`.
    alpha: (f64, f64),
    /// C's velocity products at `r` and the velocities `bias_v`, left by
    /// [`Plain::mass_and_forces`] (its walk ends at C).
    bias_c: Option<Vector2<f64>>,
    bias_v: Vec<f64>,
}

/// The axes a walk uses: the segments' own, or those of the frame turned by `-alpha` (the
/// elastic angles alone; `S_0`'s share of the columns left out).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Frame {
    Global,
    Body,
}

impl Trig {
    pub(super) fn new(n: usize, segments: usize) -> Trig {
        Trig {
            r: vec![0.0; n],
            valid: false,
            global_valid: false,
            cos: vec![0.0; segments],
            sin: vec![0.0; segments],
            slides: vec![0.0; segments + 1],
            elastic_valid: false,
            elastic: vec![0.0; segments],
            elastic_cos: vec![0.0; segments],
            elastic_sin: vec![0.0; segments],
            points: [None; 3],
            body_points: [None; 3],
            alpha: (1.0, 0.0),
            bias_c: None,
            bias_v: vec![0.0; n],
        }
    }

    fn axes_in(&self, frame: Frame, k: usize) -> (Vector2<f64>, Vector2<f64>) {
        match frame {
            Frame::Global => self.axes(k),
            Frame::Body => {
                let (c, s) = (self.elastic_cos[k], self.elastic_sin[k]);
                (Vector2::new(c, s), Vector2::new(-s, c))
            }
        }
    }

    fn axes(&self, k: usize) -> (Vector2<f64>, Vector2<f64>) {
        debug_assert!(self.global_valid, "Plain::global_axes first");
        let (c, s) = (self.cos[k], self.sin[k]);
        (Vector2::new(c, s), Vector2::new(-s, c))
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

impl Plain {
    /// The chain `chain` (no axial springs, no end body rotations) with the basis `t(row, c)`
    /// over its coordinates and its reduced spring and damper matrices (row-major, `n x n`).
    pub(super) fn new(
        chain: &SegmentRod,
        n: usize,
        t: impl Fn(usize, usize) -> f64,
        stiffness: Vec<f64>,
        damping: Vec<f64>,
    ) -> Plain {
        assert!(n <= MAX_REDUCED);
        let segments = chain.n_seg;
        let mut psi = vec![0.0; segments * n];
        for k in 0..segments {
            for c in 2..n {
                psi[k * n + c] = t(chain.theta_index(k), c);
            }
        }
        let mut sigma = vec![0.0; (segments + 1) * n];
        if chain.has_shear() {
            for i in 0..=segments {
                for c in 2..n {
                    sigma[i * n + c] = t(chain.shear_index(i), c);
                }
            }
        }
        let (mut base_x, mut base_y) = ([0.0; MAX_REDUCED], [0.0; MAX_REDUCED]);
        for c in 2..n {
            base_x[c] = t(0, c);
            base_y[c] = t(1, c);
        }
        let shear = chain.has_shear();
        let slide = |i: usize, w: f64| shear.then_some((i, w));
        let (k_mid, xi_mid) = chain.mid;
        let mid = if xi_mid == 0.0 && k_mid > 0 && shear {
            // Halfway across the joint's slide (the chain's own midpoint).
            ChainPoint {
                k: k_mid - 1,
                xi: chain.seg_len,
                slide: Some((k_mid, 0.5)),
            }
        } else {
            ChainPoint {
                k: k_mid,
                xi: xi_mid,
                slide: None,
            }
        };
        let points = [
            ChainPoint {
                k: 0,
                xi: 0.0,
                slide: slide(0, -1.0),
            },
            ChainPoint {
                k: segments - 1,
                xi: chain.seg_len,
                slide: slide(segments, 1.0),
            },
            mid,
        ];
        let mut rotary = vec![0.0; n * n];
        for k in 0..segments {
            let psi = &psi[k * n..(k + 1) * n];
            for c in 2..n {
                for d in 2..n {
                    rotary[c * n + d] += chain.inertias[k] * psi[c] * psi[d];
                }
            }
        }
        let total_mass = chain.masses.iter().sum::<f64>() + chain.end_mass[0] + chain.end_mass[1];
        Plain {
            n,
            rotary,
            total_mass,
            l: chain.seg_len,
            masses: chain.masses.clone(),
            centroids: chain.centroids.clone(),
            psi,
            sigma,
            base_x,
            base_y,
            end_mass: chain.end_mass,
            points,
            stiffness,
            damping,
        }
    }

    fn segments(&self) -> usize {
        self.masses.len()
    }

    /// `Psi_k` with its length `N = n` known to the compiler.
    #[inline(always)]
    fn psi_n<const N: usize>(&self, k: usize) -> &[f64; N] {
        self.psi[k * N..(k + 1) * N].try_into().expect("n columns")
    }

    /// `Sigma_i` with its length `N = n` known to the compiler.
    #[inline(always)]
    fn sigma_n<const N: usize>(&self, i: usize) -> &[f64; N] {
        self.sigma[i * N..(i + 1) * N]
            .try_into()
            .expect("n columns")
    }

    fn point_of(&self, p: RodPoint) -> ChainPoint {
        match p {
            RodPoint::B => self.points[0],
            RodPoint::C => self.points[1],
            RodPoint::Mid => self.points[2],
        }
    }

    /// Cosines and sines of the angles and the slides at `r` into `trig` (kept while `r` is
    /// the same).
    pub(super) fn angles(&self, r: &[f64], trig: &mut Trig) {
        dispatch!(self.angles_n(r, trig))
    }

    fn angles_n<const N: usize>(&self, r: &[f64], trig: &mut Trig) {
        let r: &[f64; N] = r[..N].try_into().expect("n coordinates");
        let same = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits());
        if trig.valid && same(&trig.r, r) {
            return;
        }
        if !(trig.elastic_valid && same(&trig.r[3..], &r[3..])) {
            // Psi_k,alpha = 1: the elastic part is the modes' share alone; the slides are the
            // modes' alone.
            for k in 0..self.segments() {
                trig.elastic[k] = dot(&self.psi_n::<N>(k)[3..], &r[3..]);
            }
            crate::trig::sin_cos_all(&trig.elastic, &mut trig.elastic_sin, &mut trig.elastic_cos);
            for i in 0..=self.segments() {
                trig.slides[i] = dot(&self.sigma_n::<N>(i)[3..], &r[3..]);
            }
            trig.elastic_valid = true;
            trig.body_points = [None; 3];
        }
        let (sa, ca) = crate::trig::sin_cos(r[2]);
        trig.r.copy_from_slice(r);
        trig.valid = true;
        trig.global_valid = false;
        trig.points = [None; 3];
        trig.bias_c = None;
        trig.alpha = (ca, sa);
    }

    /// The segments' angles in the global axes at the coordinates of `trig` (after
    /// [`Self::angles`]): the elastic ones turned by `alpha`.
    fn global_axes(&self, trig: &mut Trig) {
        if trig.global_valid {
            return;
        }
        let (ca, sa) = trig.alpha;
        for k in 0..self.segments() {
            let (c, s) = (trig.elastic_cos[k], trig.elastic_sin[k]);
            trig.cos[k] = ca * c - sa * s;
            trig.sin[k] = sa * c + ca * s;
        }
        trig.global_valid = true;
    }

    /// Position (from `S_0`) and Jacobian columns of `p` at the coordinates of `trig`, kept in
    /// it.
    fn point_cached(&self, p: RodPoint, trig: &mut Trig) -> (Vector2<f64>, Row, Row) {
        let i = match p {
            RodPoint::B => 0,
            RodPoint::C => 1,
            RodPoint::Mid => 2,
        };
        if let Some(x) = trig.points[i] {
            return x;
        }
        let (xb, jxb, jyb) = match trig.body_points[i] {
            Some(b) => b,
            None => {
                let (x, jx, jy, _) = dispatch!(self.point_parts(p, trig, None, Frame::Body));
                trig.body_points[i] = Some((x, jx, jy));
                (x, jx, jy)
            }
        };
        let (ca, sa) = trig.alpha;
        let turn = |x: f64, y: f64| (ca * x - sa * y, sa * x + ca * y);
        let (px, py) = turn(xb.x, xb.y);
        let (mut jx, mut jy) = (self.base_x, self.base_y);
        for c in 2..self.n {
            let (u, w) = turn(jxb[c], jyb[c]);
            jx[c] += u;
            jy[c] += w;
        }
        let x = Vector2::new(px, py);
        trig.points[i] = Some((x, jx, jy));
        (x, jx, jy)
    }

    /// Walk the segments: `visit(k, G_k x, G_k y, gamma_k)` with the reduced partial velocities
    /// of the centroid (angle and slide columns; the columns of `x_B`, `y_B` are the unit
    /// vectors) and, with velocities `v`, its velocity-product acceleration. Stops before
    /// segment `stop` and returns the prefix sums `P` (x, y), `sum d_j` and `gamma` there.
    fn walk<const N: usize>(
        &self,
        trig: &Trig,
        v: Option<&[f64]>,
        stop: usize,
        frame: Frame,
        mut visit: impl FnMut(usize, &Row, &Row, Vector2<f64>),
    ) -> (Row, Row, Vector2<f64>, Vector2<f64>) {
        let n = N;
        let (mut px, mut py) = match frame {
            Frame::Global => (self.base_x, self.base_y),
            Frame::Body => ([0.0; MAX_REDUCED], [0.0; MAX_REDUCED]),
        };
        let (mut gx, mut gy) = ([0.0; MAX_REDUCED], [0.0; MAX_REDUCED]);
        let mut offset = Vector2::zeros();
        let mut gamma = Vector2::zeros();
        for k in 0..stop {
            let (e, nn) = trig.axes_in(frame, k);
            let psi = self.psi_n::<N>(k);
            let ck = self.centroids[k];
            for c in 2..n {
                let lever = ck * psi[c];
                gx[c] = px[c] + nn.x * lever;
                gy[c] = py[c] + nn.y * lever;
            }
            let (w, slide_rate) = match v {
                Some(v) => (
                    dot(&psi[2..], &v[2..n]),
                    dot(&self.sigma_n::<N>(k + 1)[2..], &v[2..n]),
                ),
                None => (0.0, 0.0),
            };
            visit(k, &gx, &gy, gamma - e * (ck * w * w));
            let t = trig.slides[k + 1];
            let perp = nn * self.l - e * t;
            let sigma = self.sigma_n::<N>(k + 1);
            for c in 2..n {
                px[c] += perp.x * psi[c] + nn.x * sigma[c];
                py[c] += perp.y * psi[c] + nn.y * sigma[c];
            }
            let d = e * self.l + nn * t;
            offset += d;
            gamma -= e * (2.0 * w * slide_rate) + d * (w * w);
        }
        (px, py, offset, gamma)
    }

    /// Position, Jacobian (angle and slide columns, x and y) and, with `v`, the velocity
    /// products of point `p`.
    fn point_parts<const N: usize>(
        &self,
        p: RodPoint,
        trig: &Trig,
        v: Option<&[f64]>,
        frame: Frame,
    ) -> (Vector2<f64>, Row, Row, Vector2<f64>) {
        let n = N;
        let cp = self.point_of(p);
        let (mut jx, mut jy, offset, mut gamma) =
            self.walk::<N>(trig, v, cp.k, frame, |_, _, _, _| {});
        let (e, nn) = trig.axes_in(frame, cp.k);
        let psi = self.psi_n::<N>(cp.k);
        let w = v.map_or(0.0, |v| dot(&psi[2..], &v[2..n]));
        let mut x = offset + e * cp.xi;
        gamma -= e * (cp.xi * w * w);
        for c in 2..n {
            jx[c] += nn.x * cp.xi * psi[c];
            jy[c] += nn.y * cp.xi * psi[c];
        }
        if let Some((i, weight)) = cp.slide {
            let t = trig.slides[i];
            let sigma = self.sigma_n::<N>(i);
            x += nn * (weight * t);
            for c in 2..n {
                jx[c] += weight * (nn.x * sigma[c] - e.x * t * psi[c]);
                jy[c] += weight * (nn.y * sigma[c] - e.y * t * psi[c]);
            }
            let rate = v.map_or(0.0, |v| dot(&sigma[2..], &v[2..n]));
            gamma -= (e * (2.0 * w * rate) + nn * (w * w * t)) * weight;
        }
        (x, jx, jy, gamma)
    }

    /// Position of `p`.
    pub(super) fn point(&self, p: RodPoint, r: &[f64], trig: &mut Trig) -> Vector2<f64> {
        let (x, _, _) = self.point_cached(p, trig);
        let n = self.n;
        let s0 = Vector2::new(
            r[0] + dot(&self.base_x[2..n], &r[2..n]),
            r[1] + dot(&self.base_y[2..n], &r[2..n]),
        );
        x + s0
    }

    /// `J_P` (2 x n) into `out`.
    pub(super) fn point_jacobian(&self, p: RodPoint, trig: &mut Trig, mut out: MatMut<'_, f64>) {
        let (_, jx, jy) = self.point_cached(p, trig);
        out[(0, 0)] = 1.0;
        out[(1, 0)] = 0.0;
        out[(0, 1)] = 0.0;
        out[(1, 1)] = 1.0;
        for c in 2..self.n {
            out[(0, c)] = jx[c];
            out[(1, c)] = jy[c];
        }
    }

    /// `J_P' r'`, the velocity products of `p`'s acceleration.
    pub(super) fn point_bias(&self, p: RodPoint, v: &[f64], trig: &mut Trig) -> Vector2<f64> {
        if let (RodPoint::C, Some(bias)) = (p, trig.bias_c) {
            let same =
                |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits());
            if same(&trig.bias_v, &v[..self.n]) {
                return bias;
            }
        }
        self.global_axes(trig);
        dispatch!(self.point_bias_n(p, v, trig))
    }

    fn point_bias_n<const N: usize>(&self, p: RodPoint, v: &[f64], trig: &Trig) -> Vector2<f64> {
        // The velocity products of `point_parts` alone (no Jacobian columns): the segments'
        // `-2 w_j t_{j+1}' e_j - w_j^2 d_j` up to the point, then its own segment's share.
        let n = N;
        let cp = self.point_of(p);
        let mut gamma = Vector2::zeros();
        for k in 0..cp.k {
            let (e, nn) = trig.axes(k);
            let w = dot(&self.psi_n::<N>(k)[2..], &v[2..n]);
            let rate = dot(&self.sigma_n::<N>(k + 1)[2..], &v[2..n]);
            let d = e * self.l + nn * trig.slides[k + 1];
            gamma -= e * (2.0 * w * rate) + d * (w * w);
        }
        let (e, nn) = trig.axes(cp.k);
        let w = dot(&self.psi_n::<N>(cp.k)[2..], &v[2..n]);
        gamma -= e * (cp.xi * w * w);
        if let Some((i, weight)) = cp.slide {
            let rate = dot(&self.sigma_n::<N>(i)[2..], &v[2..n]);
            gamma -= (e * (2.0 * w * rate) + nn * (w * w * trig.slides[i])) * weight;
        }
        gamma
    }

    /// `m J^T J` of a point mass into the upper triangle of `m`.
    fn add_point_mass<const N: usize>(&self, mass: f64, gx: &Row, gy: &Row, m: &mut [[f64; N]; N]) {
        // The whole square (fixed bounds: the compiler vectorizes), symmetric by construction.
        for c in 2..N {
            let (ax, ay) = (mass * gx[c], mass * gy[c]);
            m[0][c] += ax;
            m[1][c] += ay;
            let row = &mut m[c];
            for d in 2..N {
                row[d] += ax * gx[d] + ay * gy[d];
            }
        }
    }

    /// The mass matrix (n x n) into `out` (overwritten).
    pub(super) fn mass(&self, trig: &mut Trig, out: MatMut<'_, f64>) {
        self.global_axes(trig);
        dispatch!(self.mass_n(trig, out))
    }

    fn mass_n<const N: usize>(&self, trig: &Trig, out: MatMut<'_, f64>) {
        let mut m = [[0.0; N]; N];
        self.walk_bodies::<N>(trig, None, |mass, gx, gy, _| {
            self.add_point_mass::<N>(mass, gx, gy, &mut m)
        });
        self.finish_mass::<N>(&mut m, out);
    }

    /// Walk the point masses in the global axes: `visit(m, G x, G y, gamma)` of every segment's
    /// centroid, then of the end bodies' masses at B and C (where present), with their
    /// velocity products at the velocities `v` (zero without); returns C's velocity products
    /// (where the walk ends: `J_C = P_N`).
    fn walk_bodies<const N: usize>(
        &self,
        trig: &Trig,
        v: Option<&[f64]>,
        mut visit: impl FnMut(f64, &Row, &Row, Vector2<f64>),
    ) -> Vector2<f64> {
        let (jcx, jcy, _, gamma_c) =
            self.walk::<N>(trig, v, self.segments(), Frame::Global, |k, gx, gy, g| {
                visit(self.masses[k], gx, gy, g)
            });
        if self.end_mass[0] > 0.0 {
            let (_, jx, jy, gamma) = self.point_parts::<N>(RodPoint::B, trig, v, Frame::Global);
            visit(self.end_mass[0], &jx, &jy, gamma);
        }
        if self.end_mass[1] > 0.0 {
            visit(self.end_mass[1], &jcx, &jcy, gamma_c);
        }
        gamma_c
    }

    /// The translations' total mass and the constant rotary inertia added to the walk's `m`
    /// (upper triangle), written symmetric into `out`.
    fn finish_mass<const N: usize>(&self, m: &mut [[f64; N]; N], mut out: MatMut<'_, f64>) {
        m[0][0] = self.total_mass;
        m[1][1] = self.total_mass;
        for c in 0..N {
            for d in c..N {
                let x = m[c][d] + self.rotary[c * N + d];
                out[(c, d)] = x;
                out[(d, c)] = x;
            }
        }
    }

    /// The mass matrix into `out` and the forces into `f`, as [`Self::mass`] and
    /// [`Self::forces`] give them, in one walk; C's velocity products (where the walk ends) kept
    /// in `trig` for [`Self::point_bias`].
    pub(super) fn mass_and_forces(
        &self,
        r: &[f64],
        v: &[f64],
        trig: &mut Trig,
        out: MatMut<'_, f64>,
        f: &mut [f64],
    ) {
        self.global_axes(trig);
        let bias = dispatch!(self.mass_and_forces_n(r, v, trig, out, f));
        trig.bias_c = Some(bias);
        trig.bias_v.copy_from_slice(&v[..self.n]);
    }

    fn mass_and_forces_n<const N: usize>(
        &self,
        r: &[f64],
        v: &[f64],
        trig: &Trig,
        out: MatMut<'_, f64>,
        f: &mut [f64],
    ) -> Vector2<f64> {
        let mut m = [[0.0; N]; N];
        let mut q = [0.0; N];
        let gamma_c = self.walk_bodies::<N>(trig, Some(v), |mass, gx, gy, g| {
            self.add_point_mass::<N>(mass, gx, gy, &mut m);
            self.add_point_inertia::<N>(mass, gx, gy, g, &mut q);
        });
        self.finish_mass::<N>(&mut m, out);
        self.finish_forces::<N>(r, v, &q, f);
        gamma_c
    }

    /// `q -= m J^T gamma` of a point mass.
    fn add_point_inertia<const N: usize>(
        &self,
        mass: f64,
        gx: &Row,
        gy: &Row,
        gamma: Vector2<f64>,
        q: &mut [f64; N],
    ) {
        q[0] -= mass * gamma.x;
        q[1] -= mass * gamma.y;
        for c in 2..N {
            q[c] -= mass * (gx[c] * gamma.x + gy[c] * gamma.y);
        }
    }

    /// Velocity products, springs and dampers (n entries, overwritten).
    pub(super) fn forces(&self, r: &[f64], v: &[f64], trig: &mut Trig, f: &mut [f64]) {
        self.global_axes(trig);
        dispatch!(self.forces_n(r, v, trig, f))
    }

    fn forces_n<const N: usize>(&self, r: &[f64], v: &[f64], trig: &Trig, f: &mut [f64]) {
        let mut q = [0.0; N];
        self.walk_bodies::<N>(trig, Some(v), |mass, gx, gy, g| {
            self.add_point_inertia::<N>(mass, gx, gy, g, &mut q)
        });
        self.finish_forces::<N>(r, v, &q, f);
    }

    /// The springs and dampers `-K_r r - C_r r'` added to the velocity products `q` into `f`.
    fn finish_forces<const N: usize>(&self, r: &[f64], v: &[f64], q: &[f64; N], f: &mut [f64]) {
        for (c, fc) in f[..N].iter_mut().enumerate() {
            let row = c * N;
            let mut x = q[c];
            for d in 0..N {
                x -= self.stiffness[row + d] * r[d] + self.damping[row + d] * v[d];
            }
            *fc = x;
        }
    }

    /// Add the gravity forces `sum m_k G_k^T g` (rod and end bodies) into `f`.
    pub(super) fn add_gravity(&self, trig: &mut Trig, g: Vector2<f64>, f: &mut [f64]) {
        self.global_axes(trig);
        dispatch!(self.add_gravity_n(trig, g, f))
    }

    fn add_gravity_n<const N: usize>(&self, trig: &Trig, g: Vector2<f64>, f: &mut [f64]) {
        let mut q = [0.0; N];
        // Gravity is the point-inertia term with gamma = -g.
        self.walk_bodies::<N>(trig, None, |mass, gx, gy, _| {
            self.add_point_inertia::<N>(mass, gx, gy, -g, &mut q)
        });
        for c in 0..N {
            f[c] += q[c];
        }
    }
}
