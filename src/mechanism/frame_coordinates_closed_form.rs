//! The slider-crank on its independent coordinates in closed form for a rod whose coordinates
//! begin with a frame (`RodBody::frame_coordinates`: `x`, `y`, `alpha` at 0, 1, 2, the elastic
//! coordinates `p` after them; the chain on its modes): the same equations as the general
//! partitioned evaluation (`crate::integrator::partitioned`, Wehage and Haug 1982), with the
//! constraint Jacobian's dependent block solved by hand instead of factored.
//!
//! Coordinates `q = [x, y, alpha, p, x_s]`; constraints `B(q) = P(t)` (2), `C(q) = (x_s, e)`
//! (2). The frame translates every point, so `dB/d(x, y) = dC/d(x, y) = 1`, and turns the chord,
//! so `dC/dalpha - dB/dalpha = perp(C - B)`, whose y entry is the chord's x extent `X` (nonzero
//! while the slider is not at the crank's side of the rod: the mechanism is assembled).
//! With the Jacobian columns `j_B`, `j_C` of `alpha` and `J_B`, `J_C` of `p`, `D = J_C - J_B`:
//! - velocities `q' = G p' + g`: `alpha' = -(V_y + D_y p') / X` from the y rows of the pins,
//!   `(x', y') = V - j_B alpha' - J_B p'` from pin B, `x_s' = x' + j_C,x alpha' + J_C,x p'`;
//! - accelerations `q'' = G p'' + b` from the same rows with the pins' velocity products
//!   `beta_B`, `beta_C` and the pin's acceleration `a_P`: `b_alpha = (beta_B,y - beta_C,y -
//!   a_P,y) / X`, `b_xy = a_P - beta_B - j_B b_alpha`, `b_s = b_x + j_C,x b_alpha + beta_C,x`;
//! - the reduced equations `(G^T M G) p'' = G^T (Q - M b)` (Gaussian elimination with partial
//!   pivoting);
//! - the multipliers from the dependent rows of `M q'' + Phi_q^T lambda = Q`: with `r = (Q - M
//!   q'')` on `x`, `y`, `alpha`, `x_s`: `lambda_Cx = -r_s`, `lambda_Bx = r_x - lambda_Cx`,
//!   `lambda_Cy = (r_alpha - j_B,x lambda_Bx - j_C,x lambda_Cx - j_B,y r_y) / X`, `lambda_By =
//!   r_y - lambda_Cy`.
//!
//! Everything lives on the stack, sized by [`FRAME_FORM_MAX`].

use faer::MatMut;
use nalgebra::Vector2;

use super::dae::SliderCrankDae;
use crate::integrator::{DaeSystem, StepFailure};
use crate::rod::{RodBody, RodPoint};

/// Largest number of coordinates (rod and slider) of the closed form; a larger system takes the
/// general partitioned evaluation (the chain on its modes has at most 20).
pub const FRAME_FORM_MAX: usize = 20;

/// Largest number of independent (elastic) coordinates.
const K_MAX: usize = FRAME_FORM_MAX - 4;

impl SliderCrankDae<'_> {
    /// The closed form (module documentation) where the rod's coordinates begin with its frame
    /// and the system is small enough; `None` elsewhere, and where the pins cannot be assembled
    /// at the independent coordinates (the general evaluation then says why).
    pub(super) fn frame_form_rhs(
        &self,
        t: f64,
        q: &mut [f64],
        v: &mut [f64],
        qdd: &mut [f64],
        lambda: Option<&mut [f64]>,
    ) -> Option<Result<(), StepFailure>> {
        let nr = self.rod.n_coordinates();
        let n = nr + 1;
        if self.rod.frame_coordinates() != Some([0, 1, 2]) || nr < 4 || n > FRAME_FORM_MAX {
            return None;
        }
        if !self.solve_dependent_positions(t, q) {
            return None;
        }
        Some(self.frame_form_evaluate(t, q, v, qdd, lambda))
    }

    /// The closed form at positions `q` on the constraints (module documentation): velocities
    /// into `v` (the dependent ones from the independent ones), accelerations into `qdd`,
    /// with `lambda` the multipliers.
    fn frame_form_evaluate(
        &self,
        t: f64,
        q: &[f64],
        v: &mut [f64],
        qdd: &mut [f64],
        lambda: Option<&mut [f64]>,
    ) -> Result<(), StepFailure> {
        let nr = self.rod.n_coordinates();
        let n = nr + 1;
        let pins = PinJacobians::new(self.rod, q)?;
        let g = pins.velocity_map();
        let (_, pin_v, pin_a) = self.pin_at(t);
        pins.velocities(&g, pin_v, v);
        // M and Q (the rod's in one pass, which leaves C's velocity products for the next
        // call), then the accelerations q'' = G p'' + b.
        let mut m = [0.0; FRAME_FORM_MAX * FRAME_FORM_MAX];
        let mut r = [0.0; FRAME_FORM_MAX];
        self.mass_and_forces(
            t,
            q,
            v,
            MatMut::from_column_major_slice_mut(&mut m[..n * n], n, n),
            &mut r[..n],
        );
        let b = pins.bias(self.rod, q, v, pin_a);
        // Q - M b, M G, the reduced system.
        for (j, bj) in [(0, b[0]), (1, b[1]), (2, b[2]), (nr, b[nr])] {
            for i in 0..n {
                r[i] -= m[j * n + i] * bj;
            }
        }
        let mg = pins.mass_times_map(&m, &g);
        let (mut reduced, mut pdd) = pins.reduced_system(&mg, &g, &r);
        let k = pins.k;
        solve(&mut reduced[..k * k], &mut pdd[..k], k)?;
        pins.accelerations(&g, &b, &pdd, qdd);
        if let Some(lambda) = lambda {
            pins.multipliers(&mg, &r, &pdd, lambda);
        }
        if qdd[..n].iter().any(|x| !x.is_finite()) {
            return Err(StepFailure::NonFinite);
        }
        Ok(())
    }
}

/// The pins' Jacobians at the positions `q` (module documentation): the columns `j_B`, `j_C`
/// of the frame angle `alpha` and those of the other coordinates, and the chord's x extent `X`.
struct PinJacobians {
    /// The rod's coordinates `nr` (the slider is coordinate `nr`) and the independent ones `k`.
    nr: usize,
    k: usize,
    /// `J_B`, `J_C` (2 x nr, column-major).
    jb: [f64; 2 * FRAME_FORM_MAX],
    jc: [f64; 2 * FRAME_FORM_MAX],
    /// Their columns of `alpha`, `j_B` and `j_C` (m/rad).
    jba: Vector2<f64>,
    jca: Vector2<f64>,
    /// `X = j_C,y - j_B,y`, m.
    chord_x: f64,
}

impl PinJacobians {
    /// The Jacobians of `rod`'s pins at `q`; refused where the chord is perpendicular to the
    /// slider's line (`X = 0`: not assembled) or not finite.
    #[inline(always)]
    fn new(rod: &dyn RodBody, q: &[f64]) -> Result<PinJacobians, StepFailure> {
        let nr = rod.n_coordinates();
        let (mut jb, mut jc) = ([0.0; 2 * FRAME_FORM_MAX], [0.0; 2 * FRAME_FORM_MAX]);
        rod.point_jacobian(
            RodPoint::B,
            q,
            MatMut::from_column_major_slice_mut(&mut jb[..2 * nr], 2, nr),
        );
        rod.point_jacobian(
            RodPoint::C,
            q,
            MatMut::from_column_major_slice_mut(&mut jc[..2 * nr], 2, nr),
        );
        let (jba, jca) = (Vector2::new(jb[4], jb[5]), Vector2::new(jc[4], jc[5]));
        let chord_x = jca.y - jba.y;
        if !(chord_x.abs() > 0.0 && chord_x.is_finite()) {
            return Err(StepFailure::SingularMatrix);
        }
        Ok(PinJacobians {
            nr,
            k: nr - 3,
            jb,
            jc,
            jba,
            jca,
            chord_x,
        })
    }

    /// G (n x k): its dependent rows x, y, alpha, x_s (row-major, `g[row * k + a]` with row
    /// 3 for x_s); the identity on p.
    #[inline(always)]
    fn velocity_map(&self) -> [f64; 4 * K_MAX] {
        let (k, jb, jc, jba, jca) = (self.k, &self.jb, &self.jc, self.jba, self.jca);
        let mut g = [0.0; 4 * K_MAX];
        for a in 0..k {
            let c = 3 + a;
            let (jbx, jby, jcx, jcy) = (jb[2 * c], jb[2 * c + 1], jc[2 * c], jc[2 * c + 1]);
            let ga = -(jcy - jby) / self.chord_x;
            let gx = -jba.x * ga - jbx;
            let gy = -jba.y * ga - jby;
            g[a] = gx;
            g[k + a] = gy;
            g[2 * k + a] = ga;
            g[3 * k + a] = gx + jca.x * ga + jcx;
        }
        g
    }

    /// The dependent velocities `x'`, `y'`, `alpha'`, `x_s'` into `v` from its independent
    /// ones and the pin's velocity `pin_v`.
    #[inline(always)]
    fn velocities(&self, g: &[f64; 4 * K_MAX], pin_v: Vector2<f64>, v: &mut [f64]) {
        let (k, nr, jb, jc) = (self.k, self.nr, &self.jb, &self.jc);
        let mut alpha_v = -pin_v.y / self.chord_x;
        for a in 0..k {
            alpha_v += g[2 * k + a] * v[3 + a];
        }
        let mut xy_v = pin_v - self.jba * alpha_v;
        let mut c_x = self.jca.x * alpha_v;
        for a in 0..k {
            let c = 3 + a;
            xy_v -= Vector2::new(jb[2 * c], jb[2 * c + 1]) * v[c];
            c_x += jc[2 * c] * v[c];
        }
        v[0] = xy_v.x;
        v[1] = xy_v.y;
        v[2] = alpha_v;
        v[nr] = xy_v.x + c_x;
    }

    /// The velocity-product part `b` of `q'' = G p'' + b` (module documentation), from the
    /// pins' velocity products of `rod` at `(q, v)` and the pin's acceleration `pin_a`.
    #[inline(always)]
    fn bias(
        &self,
        rod: &dyn RodBody,
        q: &[f64],
        v: &[f64],
        pin_a: Vector2<f64>,
    ) -> [f64; FRAME_FORM_MAX] {
        let beta_b = rod.point_bias_acceleration(RodPoint::B, q, v);
        let beta_c = rod.point_bias_acceleration(RodPoint::C, q, v);
        let b_alpha = (beta_b.y - beta_c.y - pin_a.y) / self.chord_x;
        let b_xy = pin_a - beta_b - self.jba * b_alpha;
        let mut b = [0.0; FRAME_FORM_MAX];
        b[0] = b_xy.x;
        b[1] = b_xy.y;
        b[2] = b_alpha;
        b[self.nr] = b_xy.x + self.jca.x * b_alpha + beta_c.x;
        b
    }

    /// `M G` (n x k, row-major) of the mass matrix `m` (n x n, column-major).
    #[inline(always)]
    fn mass_times_map(
        &self,
        m: &[f64; FRAME_FORM_MAX * FRAME_FORM_MAX],
        g: &[f64; 4 * K_MAX],
    ) -> [f64; FRAME_FORM_MAX * K_MAX] {
        let (k, nr) = (self.k, self.nr);
        let n = nr + 1;
        let mut mg = [0.0; FRAME_FORM_MAX * K_MAX];
        for i in 0..n {
            for a in 0..k {
                // G's column a: rows 0, 1, 2, 3 + a and nr.
                let s = m[i] * g[a]
                    + m[n + i] * g[k + a]
                    + m[2 * n + i] * g[2 * k + a]
                    + m[(3 + a) * n + i]
                    + m[nr * n + i] * g[3 * k + a];
                mg[i * k + a] = s;
            }
        }
        mg
    }

    /// The reduced system `(G^T M G) p'' = G^T (Q - M b)` (k x k, row-major, and its right-hand
    /// side) from `M G` and `r = Q - M b`.
    #[inline(always)]
    fn reduced_system(
        &self,
        mg: &[f64; FRAME_FORM_MAX * K_MAX],
        g: &[f64; 4 * K_MAX],
        r: &[f64; FRAME_FORM_MAX],
    ) -> ([f64; K_MAX * K_MAX], [f64; FRAME_FORM_MAX]) {
        let (k, nr) = (self.k, self.nr);
        let mut reduced = [0.0; K_MAX * K_MAX];
        let mut pdd = [0.0; FRAME_FORM_MAX];
        for a in 0..k {
            for c in 0..k {
                let mut s = mg[(3 + a) * k + c];
                for (row, i) in [0, 1, 2, nr].into_iter().enumerate() {
                    s += g[row * k + a] * mg[i * k + c];
                }
                reduced[a * k + c] = s;
            }
            let mut s = r[3 + a];
            for (row, i) in [0, 1, 2, nr].into_iter().enumerate() {
                s += g[row * k + a] * r[i];
            }
            pdd[a] = s;
        }
        (reduced, pdd)
    }

    /// The accelerations `q'' = G p'' + b` into `qdd` from the independent ones `pdd`.
    #[inline(always)]
    fn accelerations(
        &self,
        g: &[f64; 4 * K_MAX],
        b: &[f64; FRAME_FORM_MAX],
        pdd: &[f64; FRAME_FORM_MAX],
        qdd: &mut [f64],
    ) {
        let (k, nr) = (self.k, self.nr);
        for i in 0..nr + 1 {
            let row = match i {
                0..=2 => Some(i),
                _ if i == nr => Some(3),
                _ => None,
            };
            qdd[i] = match row {
                Some(row) => {
                    let mut s = b[i];
                    for a in 0..k {
                        s += g[row * k + a] * pdd[a];
                    }
                    s
                }
                None => pdd[i - 3],
            };
        }
    }

    /// The multipliers (module documentation) into `lambda` from `(Q - M q'')` on the
    /// dependent coordinates: `(Q - M b) - M G p''` with `r = Q - M b`.
    #[inline(always)]
    fn multipliers(
        &self,
        mg: &[f64; FRAME_FORM_MAX * K_MAX],
        r: &[f64; FRAME_FORM_MAX],
        pdd: &[f64; FRAME_FORM_MAX],
        lambda: &mut [f64],
    ) {
        let k = self.k;
        let residual = |i: usize| {
            let mut s = r[i];
            for a in 0..k {
                s -= mg[i * k + a] * pdd[a];
            }
            s
        };
        let (rx, ry, ra, rs) = (residual(0), residual(1), residual(2), residual(self.nr));
        let (jba, jca) = (self.jba, self.jca);
        let c_x = -rs;
        let b_x = rx - c_x;
        let c_y = (ra - jba.x * b_x - jca.x * c_x - jba.y * ry) / self.chord_x;
        lambda[0] = b_x;
        lambda[1] = ry - c_y;
        lambda[2] = c_x;
        lambda[3] = c_y;
    }
}

/// Solve `a x = b` (`k x k`, row-major) by Gaussian elimination with partial pivoting; `b`
/// becomes `x`.
fn solve(a: &mut [f64], b: &mut [f64], k: usize) -> Result<(), StepFailure> {
    for col in 0..k {
        let mut piv = col;
        for r in col + 1..k {
            if a[r * k + col].abs() > a[piv * k + col].abs() {
                piv = r;
            }
        }
        let p = a[piv * k + col];
        if p == 0.0 || !p.is_finite() {
            return Err(StepFailure::SingularMatrix);
        }
        if piv != col {
            for c in 0..k {
                a.swap(col * k + c, piv * k + c);
            }
            b.swap(col, piv);
        }
        let inv = 1.0 / a[col * k + col];
        for r in col + 1..k {
            let f = a[r * k + col] * inv;
            for c in col + 1..k {
                a[r * k + c] -= f * a[col * k + c];
            }
            b[r] -= f * b[col];
        }
    }
    for col in (0..k).rev() {
        let mut s = b[col];
        for c in col + 1..k {
            s -= a[col * k + c] * b[c];
        }
        b[col] = s / a[col * k + col];
    }
    Ok(())
}
