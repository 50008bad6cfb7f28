//! The slider-crank with the FFR rod on minimal coordinates, in closed form
//! (docs/physics.md, "Minimal coordinates"): with the crank prescribed, the mechanism's own
//! degrees of freedom are the rod's modal coordinates `p` (n of them); the frame `(R, phi)` and
//! the slider `x_s` follow from the four pin constraints of [`super::dae`].
//!
//! Notation (global frame unless "body"): pin B at `P(t)` with velocity `V` and acceleration
//! `a_P` ([`super::crank::CrankLaw::pin`]); slider line `y = e`; body-frame points
//! `u_B = xbar_B + S_B p`, `u_C = xbar_C + S_C p - 1/2 (p^T G_0 p) e_x` (the foreshortening
//! with axial stiffening, [`crate::rod::ffr::stiffening`]); chord `d = u_C - u_B` (body),
//! `rho = |d|`; `(X, Y) = A(phi) d` (global chord; `Y = e - P_y` by the C constraint).
//!
//! - Positions: `sin psi = Y / rho`, `cos psi = +-sqrt(1 - sin^2 psi)` (the sign of `X`: the
//!   assembly branch, kept), with `psi = phi + beta`, `beta` the body angle of `d`:
//!   `cos phi = (cos psi d_x + sin psi d_y) / rho`, `sin phi = (sin psi d_x - cos psi d_y) /
//!   rho` (no inverse trigonometry on the way); `R = P - A u_B`, `x_s = P_x + X`.
//! - Velocities `q' = T p' + t_v`: the difference of the pin constraints,
//!   `phi' I~ A d + A D p' = (x_s', 0) - V` with `D = J_C - S_B` (body, `J_C = S_C -
//!   e_x (G_0 p)^T`), gives from its y row `phi' = g_phi p' - V_y / X`,
//!   `g_phi = -(A D)_y / X`, from its x row `x_s' = V_x - Y phi' + (A D)_x p'`, and pin B
//!   `R' = V - phi' I~ A u_B - A S_B p'`.
//! - Accelerations `q'' = T p'' + b` from the same rows with the velocity-product terms
//!   `beta_P = A(-phi'^2 u_P + 2 phi' I~ J_P p')` (`- (p'^T G_0 p') e_x` at C, body):
//!   `delta = beta_B - beta_C - a_P`, `b_phi = delta_y / X`, `b_x = -Y b_phi - delta_x`,
//!   `b_R = a_P - beta_B - I~ A u_B b_phi`.
//! - The reduced equations `(T^T M T) p'' = T^T (Q - M b)` (n x n; `M`, `Q` of
//!   [`crate::rod::ffr::FfrRod`] with the slider, Agrawal and Shabana 1985, eq. 3.17-3.18,
//!   6.2), assembled from the block structure of `M` (no general matrix), solved by Gaussian
//!   elimination with partial pivoting (`M` carries the non-symmetric stiffening coupling
//!   `M_pR`).
//! - Multipliers from the dependent rows of `M q'' + Phi_q^T lambda = Q` in the same
//!   evaluation: `Phi_D^T lambda = (Q - M q'')_D` is, with `a_B = I~ A u_B`,
//!   `a_C = a_B + (-Y, X)`: `lambda_B + lambda_C = r_R`, `a_B.lambda_B + a_C.lambda_C = r_phi`,
//!   `-lambda_Cx = r_s`, solved in closed form (the 2 x 2 part has determinant `X`).
//!
//! Everything is on the stack, in loops of the compile-time size `N` (one instance per mode
//! count up to [`MAX_MODES`]). An intermediate stage (no multipliers asked) computes the modal
//! accelerations only: no frame angle (`atan2`), dependent velocities and accelerations or
//! multipliers; the crank pin's motion is cached per time (stages share their times).

use nalgebra::Vector2;

use super::dae::{PinAt, SliderCrankDae};
use crate::integrator::StepFailure;
use crate::rod::ffr::{rate_rows, stacked_rows, FfrKernel, Stacked};

/// `a . b`, summed from the first product (no leading `0 +`).
#[inline(always)]
fn dot_n<const N: usize>(a: &[f64; N], b: &[f64; N]) -> f64 {
    let mut s = a[0] * b[0];
    for j in 1..N {
        s += a[j] * b[j];
    }
    s
}

/// The first `R` rows of the kernel's stacked matrix times `x` ([`Stacked`]): one pass over
/// its columns, each row summed in the order of a dot product from the first product.
#[inline(always)]
fn stacked_product<const N: usize, const R: usize>(k: &FfrKernel, x: &[f64; N]) -> [f64; R] {
    let columns = &k.stacked.columns;
    let mut out: [f64; R] = std::array::from_fn(|r| columns[0][r] * x[0]);
    for j in 1..N {
        for r in 0..R {
            out[r] += columns[j][r] * x[j];
        }
    }
    out
}

/// Block `b` ([`Stacked::block`]) of a stacked product.
#[inline(always)]
fn block<const N: usize, const R: usize>(product: &[f64; R], b: usize) -> [f64; N] {
    std::array::from_fn(|i| product[Stacked::block(b, N) + i])
}

/// The inputs of one evaluation besides the coordinates.
struct Inputs {
    pin: Vector2<f64>,
    pin_v: Vector2<f64>,
    pin_a: Vector2<f64>,
    offset: f64,
    slider_mass: f64,
    slider_force: f64,
    gravity: Vector2<f64>,
}

impl SliderCrankDae<'_> {
    /// The closed-form evaluation (module documentation) where the rod has a kernel.
    pub(super) fn minimal_rhs(
        &self,
        kernel: &FfrKernel,
        t: f64,
        q: &mut [f64],
        v: &mut [f64],
        qdd: &mut [f64],
        lambda: Option<&mut [f64]>,
    ) -> Result<(), StepFailure> {
        let ([pin, pin_v, pin_a], gas) =
            PinAt::pin_and_gas(self.pin_cache, &self.crank, t, self.gas);
        let inputs = Inputs {
            pin,
            pin_v,
            pin_a,
            offset: self.slider_offset,
            slider_mass: self.slider_mass,
            slider_force: if self.gas.is_some() {
                self.slider_force + gas
            } else {
                self.slider_force
            },
            gravity: self.gravity,
        };
        if kernel.pinned {
            evaluate_modes::<true>(kernel, &inputs, q, v, qdd, lambda)
        } else {
            evaluate_modes::<false>(kernel, &inputs, q, v, qdd, lambda)
        }
    }
}

/// [`evaluate`] instantiated for the kernel's mode count (with its stacked rows, all and those
/// for the velocities: [`stacked_rows`], [`rate_rows`]).
fn evaluate_modes<const PINNED: bool>(
    k: &FfrKernel,
    inputs: &Inputs,
    q: &mut [f64],
    v: &mut [f64],
    qdd: &mut [f64],
    lambda: Option<&mut [f64]>,
) -> Result<(), StepFailure> {
    match k.n {
        1 => evaluate::<1, PINNED, 16, 10>(k, inputs, q, v, qdd, lambda),
        2 => evaluate::<2, PINNED, 25, 13>(k, inputs, q, v, qdd, lambda),
        3 => evaluate::<3, PINNED, 34, 16>(k, inputs, q, v, qdd, lambda),
        4 => evaluate::<4, PINNED, 43, 19>(k, inputs, q, v, qdd, lambda),
        5 => evaluate::<5, PINNED, 52, 22>(k, inputs, q, v, qdd, lambda),
        6 => evaluate::<6, PINNED, 61, 25>(k, inputs, q, v, qdd, lambda),
        7 => evaluate::<7, PINNED, 70, 28>(k, inputs, q, v, qdd, lambda),
        8 => evaluate::<8, PINNED, 79, 31>(k, inputs, q, v, qdd, lambda),
        _ => Err(StepFailure::SingularMatrix),
    }
}

/// `x` wrapped to (-pi, pi].
fn wrap(x: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    x - TAU * ((x + PI) / TAU).ceil() + TAU
}

/// Solve `a x = b` (n x n) by Gaussian elimination with partial pivoting; `b` becomes `x`.
/// The pivots' reciprocals are kept, so that the back substitution multiplies (one division
/// per column instead of two in the dependent chain).
#[inline(always)]
fn solve<const N: usize>(a: &mut [[f64; N]; N], b: &mut [f64; N]) -> Result<(), StepFailure> {
    let mut inv = [0.0; N];
    for col in 0..N {
        let mut piv = col;
        for r in col + 1..N {
            if a[r][col].abs() > a[piv][col].abs() {
                piv = r;
            }
        }
        if a[piv][col] == 0.0 || !a[piv][col].is_finite() {
            return Err(StepFailure::SingularMatrix);
        }
        if piv != col {
            a.swap(col, piv);
            b.swap(col, piv);
        }
        inv[col] = 1.0 / a[col][col];
        for r in col + 1..N {
            let f = a[r][col] * inv[col];
            for c in col + 1..N {
                a[r][c] -= f * a[col][c];
            }
            b[r] -= f * b[col];
        }
    }
    for col in (0..N).rev() {
        let mut s = b[col];
        for c in col + 1..N {
            s -= a[col][c] * b[c];
        }
        b[col] = s * inv[col];
    }
    Ok(())
}

/// The mechanism's positions at the modal coordinates (module documentation, "Positions"):
/// the body-frame pins, the global chord and the frame's rotation.
struct Frame {
    /// `u_B`, `u_C` (body, m).
    u_b: [f64; 2],
    u_c: [f64; 2],
    /// `Y = e - P_y`, `X = rho cos psi` (m) and `1 / X`.
    y: f64,
    x: f64,
    inv_x: f64,
    /// `cos phi`, `sin phi`.
    c: f64,
    s: f64,
    /// `A u_B` and `I~ A u_B` (m).
    wb: [f64; 2],
    a_b: [f64; 2],
}

impl Frame {
    /// `A(phi) w`.
    #[inline(always)]
    fn rot(&self, w: [f64; 2]) -> [f64; 2] {
        [self.c * w[0] - self.s * w[1], self.s * w[0] + self.c * w[1]]
    }
}

/// The velocity map `T` over the modal columns (module documentation, "Velocities"), with
/// `A D`, whose x row is the slider's.
struct VelocityMap<const N: usize> {
    /// `g_phi` (1/m per unit `p'`), the slider row `t_x` and the frame rows `t_R`.
    g_phi: [f64; N],
    t_x: [f64; N],
    t_r: [[f64; N]; 2],
    /// `A D` (body `D = J_C - S_B` turned to global).
    ad: [[f64; N]; 2],
}

/// The velocity-product part `b` of the accelerations `q'' = T p'' + b` (module documentation,
/// "Accelerations"): `b_phi` (rad/s^2), `b_x`, `b_R` (m/s^2).
struct Bias {
    b_phi: f64,
    b_x: f64,
    b_r: [f64; 2],
}

/// The blocks of the mass matrix `M` of the rod and slider that the reduced equations use
/// (Agrawal and Shabana 1985, eq. 3.17; global frame).
struct MassBlocks<const N: usize> {
    /// `I1 + I2 p` (body, kg m) and `arm = I~ A (I1 + I2 p)`, the `M_Rphi` column.
    f: [f64; 2],
    arm: [f64; 2],
    /// `A I2` (2 x N), `M_uu p`, `M_phiphi`, `M_phip` and `G_a p` (the stiffening coupling).
    ai2: [[f64; N]; 2],
    muu_p: [f64; N],
    m_phiphi: f64,
    m_phip: [f64; N],
    gap: [f64; N],
    /// The rows of `M_pR = (A I2)^T + c_s (G_a p) (A e_x)^T` (row i `u_i`).
    u: [[f64; N]; 2],
}

/// `r = Q - M b` in its row blocks R (N), phi (N m), p and slider (N).
struct Residual<const N: usize> {
    r_r: [f64; 2],
    r_phi: f64,
    r_p: [f64; N],
    r_s: f64,
}

/// `M T` in its row blocks R, phi and slider over the modal columns.
struct MassTimesMap<const N: usize> {
    mt_r: [[f64; N]; 2],
    mt_phi: [f64; N],
    mt_s: [f64; N],
}

/// The products of the one axial mode `a`'s coupling ([`crate::rod::ffr::AxialOne`]) with `p`
/// and `p'`: `T p`, `Z p`, `F p` and `Z p'` (the rows of `AxialCoupling::add_forces`).
struct AxialProducts<const N: usize> {
    a: usize,
    t3p: [f64; N],
    zp: [f64; N],
    t4p: [f64; N],
    zpd: [f64; N],
}

/// With `PINNED` ([`FfrKernel::pinned`]: `S_B = S_C = 0`, the modes leave the pins in place)
/// the terms of `S_B` and `S_C` are left out: the body-frame chord is `(d_x, 0)`, so `rho =
/// |d_x|` without a square root and the frame angle is `psi` itself.
fn evaluate<const N: usize, const PINNED: bool, const R: usize, const RD: usize>(
    k: &FfrKernel,
    inp: &Inputs,
    q: &mut [f64],
    v: &mut [f64],
    qdd: &mut [f64],
    lambda: Option<&mut [f64]>,
) -> Result<(), StepFailure> {
    const { assert!(R == stacked_rows(N) && RD == rate_rows(N)) };
    let complete = lambda.is_some();
    let p: [f64; N] = std::array::from_fn(|j| q[3 + j]);
    let pd: [f64; N] = std::array::from_fn(|j| v[3 + j]);
    // Every product of the kernel's matrices with p and p' in two passes.
    let sp = stacked_product::<N, R>(k, &p);
    let spd = stacked_product::<N, RD>(k, &pd);
    let g0p: [f64; N] = block(&sp, Stacked::G0);
    let frame = positions::<N, PINNED, R>(k, inp, &p, &sp, &g0p, q, complete)?;
    let map = velocity_map::<N, PINNED>(k, &frame, &g0p);
    let w = velocities::<N, PINNED, RD>(inp, &frame, &map, &pd, &spd, v, complete);
    let bias = bias::<N, PINNED, RD>(inp, &frame, w, &pd, &g0p, &spd);
    let mass = mass_blocks::<N, R>(k, &frame, &p, &sp);
    let axial = axial_products::<N, R, RD>(k, &sp, &spd);
    let residual =
        residual::<N, R, RD>(k, inp, &frame, &mass, &bias, &axial, w, &p, &pd, &sp, &spd);
    // M T (not needed by an intermediate stage of the pinned rod, whose reduced system comes
    // from its scalar form).
    let mt = if !PINNED || complete {
        mass_times_map(k, inp, &map, &mass)
    } else {
        MassTimesMap {
            mt_r: [[0.0; N]; 2],
            mt_phi: [0.0; N],
            mt_s: [0.0; N],
        }
    };
    let (mut reduced, mut rhs) = if PINNED {
        reduced_pinned(k, inp, &frame, &mass, &residual, &g0p)
    } else {
        reduced_general(k, inp, &map, &mass, &mt, &residual)
    };
    if let Some(AxialProducts { a, zp, .. }) = &axial {
        for j in 0..N {
            reduced[*a][j] -= zp[j];
            reduced[j][*a] -= zp[j];
        }
    } else if let Some(ac) = &k.axial_coupling {
        ac.add_mass(&p, |i, j, x| reduced[i][j] += x);
    }
    solve(&mut reduced, &mut rhs)?;
    let zdd = rhs;
    if zdd.iter().any(|x| !x.is_finite()) {
        return Err(StepFailure::NonFinite);
    }
    // Accelerations (the dependent ones at a last stage only).
    qdd[3..3 + N].copy_from_slice(&zdd);
    if let Some(lambda) = lambda {
        dependent_accelerations_and_multipliers(
            &frame, &map, &bias, &mt, &residual, &zdd, qdd, lambda,
        );
    }
    Ok(())
}

/// The positions (module documentation): `u_B`, `u_C`, the chord and its angle on the
/// assembly branch of `q` (the sign of the chord's x, from the last slider position, or from
/// the last frame angle when the chord is near the perpendicular to the line); writes `R`,
/// `x_s` and, for a `complete` evaluation, the frame angle (on the turn of the last one) into
/// `q`.
#[inline(always)]
fn positions<const N: usize, const PINNED: bool, const R: usize>(
    k: &FfrKernel,
    inp: &Inputs,
    p: &[f64; N],
    sp: &[f64; R],
    g0p: &[f64; N],
    q: &mut [f64],
    complete: bool,
) -> Result<Frame, StepFailure> {
    let ns = 3 + N;
    let (u_b, u_c) = if PINNED {
        ([k.x_b, 0.0], [k.x_c - 0.5 * dot_n(p, g0p), 0.0])
    } else {
        (
            [k.x_b + sp[Stacked::S_B], sp[Stacked::S_B + 1]],
            [
                k.x_c + sp[Stacked::S_C] - 0.5 * dot_n(p, g0p),
                sp[Stacked::S_C + 1],
            ],
        )
    };
    let d = [u_c[0] - u_b[0], u_c[1] - u_b[1]];
    let rho = if PINNED {
        d[0].abs()
    } else {
        (d[0] * d[0] + d[1] * d[1]).sqrt()
    };
    let y = inp.offset - inp.pin.y;
    let sine = y / rho;
    if !(rho > 0.0 && sine.abs() < 1.0) {
        return Err(StepFailure::SingularMatrix);
    }
    let x_last = q[ns] - inp.pin.x;
    let branch = if x_last.abs() > 0.25 * rho {
        x_last.signum()
    } else {
        let (s0, c0) = q[2].sin_cos();
        if c0 * d[0] - s0 * d[1] >= 0.0 {
            1.0
        } else {
            -1.0
        }
    };
    let cos_psi = branch * (1.0 - sine * sine).sqrt();
    let x = rho * cos_psi;
    let (c, s) = if PINNED {
        // d = (d_x, 0): the chord's body angle is 0 or pi.
        let sign = d[0].signum();
        (cos_psi * sign, sine * sign)
    } else {
        (
            (cos_psi * d[0] + sine * d[1]) / rho,
            (sine * d[0] - cos_psi * d[1]) / rho,
        )
    };
    let mut frame = Frame {
        u_b,
        u_c,
        y,
        x,
        inv_x: 1.0 / x,
        c,
        s,
        wb: [0.0; 2],
        a_b: [0.0; 2],
    };
    let wb = frame.rot(u_b);
    frame.wb = wb;
    frame.a_b = [-wb[1], wb[0]];
    q[0] = inp.pin.x - wb[0];
    q[1] = inp.pin.y - wb[1];
    if complete {
        q[2] += wrap(s.atan2(c) - q[2]);
    }
    q[ns] = inp.pin.x + x;
    Ok(frame)
}

/// The velocity map `T`: rows R (2), phi, x_s over the modal columns (module documentation,
/// "Velocities").
#[inline(always)]
#[allow(clippy::needless_range_loop)]
fn velocity_map<const N: usize, const PINNED: bool>(
    k: &FfrKernel,
    frame: &Frame,
    g0p: &[f64; N],
) -> VelocityMap<N> {
    let (c, s, y, inv_x, a_b) = (frame.c, frame.s, frame.y, frame.inv_x, frame.a_b);
    let mut g_phi = [0.0; N];
    let mut t_x = [0.0; N];
    let mut t_r = [[0.0; N]; 2];
    let mut ad = [[0.0; N]; 2];
    for j in 0..N {
        if PINNED {
            ad[0][j] = -c * g0p[j];
            ad[1][j] = -s * g0p[j];
        } else {
            let d0 = k.s_c[0][j] - g0p[j] - k.s_b[0][j];
            let d1 = k.s_c[1][j] - k.s_b[1][j];
            ad[0][j] = c * d0 - s * d1;
            ad[1][j] = s * d0 + c * d1;
        }
        g_phi[j] = -ad[1][j] * inv_x;
        t_x[j] = -y * g_phi[j] + ad[0][j];
        if PINNED {
            t_r[0][j] = -a_b[0] * g_phi[j];
            t_r[1][j] = -a_b[1] * g_phi[j];
        } else {
            let asb = frame.rot([k.s_b[0][j], k.s_b[1][j]]);
            t_r[0][j] = -a_b[0] * g_phi[j] - asb[0];
            t_r[1][j] = -a_b[1] * g_phi[j] - asb[1];
        }
    }
    VelocityMap {
        g_phi,
        t_x,
        t_r,
        ad,
    }
}

/// `S_B p'` (body; zero for the pinned rod).
#[inline(always)]
fn s_b_rate<const PINNED: bool, const RD: usize>(spd: &[f64; RD]) -> [f64; 2] {
    if PINNED {
        [0.0; 2]
    } else {
        [spd[Stacked::S_B], spd[Stacked::S_B + 1]]
    }
}

/// The velocities (module documentation): returns the frame's angular velocity `phi'`
/// (rad/s), written into `v` with, for a `complete` evaluation, `R'` and `x_s'`.
#[inline(always)]
fn velocities<const N: usize, const PINNED: bool, const RD: usize>(
    inp: &Inputs,
    frame: &Frame,
    map: &VelocityMap<N>,
    pd: &[f64; N],
    spd: &[f64; RD],
    v: &mut [f64],
    complete: bool,
) -> f64 {
    let ns = 3 + N;
    let a_b = frame.a_b;
    let w = dot_n(&map.g_phi, pd) - inp.pin_v.y * frame.inv_x;
    let asb_pd = if PINNED {
        [0.0; 2]
    } else {
        frame.rot(s_b_rate::<PINNED, RD>(spd))
    };
    v[2] = w;
    if complete {
        v[0] = inp.pin_v.x - a_b[0] * w - asb_pd[0];
        v[1] = inp.pin_v.y - a_b[1] * w - asb_pd[1];
        v[ns] = inp.pin_v.x - frame.y * w + dot_n(&map.ad[0], pd);
    }
    w
}

/// The velocity-product terms of the pin accelerations `beta_B`, `beta_C` (body, then global)
/// and from them `b` (module documentation, "Accelerations"), at the angular velocity `w`.
#[inline(always)]
fn bias<const N: usize, const PINNED: bool, const RD: usize>(
    inp: &Inputs,
    frame: &Frame,
    w: f64,
    pd: &[f64; N],
    g0p: &[f64; N],
    spd: &[f64; RD],
) -> Bias {
    let (u_b, u_c, y, inv_x, a_b) = (frame.u_b, frame.u_c, frame.y, frame.inv_x, frame.a_b);
    let w2 = w * w;
    let sb_pd = s_b_rate::<PINNED, RD>(spd);
    let sc_pd = if PINNED {
        [-dot_n(g0p, pd), 0.0]
    } else {
        [spd[Stacked::S_C] - dot_n(g0p, pd), spd[Stacked::S_C + 1]]
    };
    let g0pd: [f64; N] = block(spd, Stacked::G0);
    let beta_b = frame.rot([
        -w2 * u_b[0] - 2.0 * w * sb_pd[1],
        -w2 * u_b[1] + 2.0 * w * sb_pd[0],
    ]);
    let beta_c = frame.rot([
        -w2 * u_c[0] - 2.0 * w * sc_pd[1] - dot_n(pd, &g0pd),
        -w2 * u_c[1] + 2.0 * w * sc_pd[0],
    ]);
    let delta = [
        beta_b[0] - beta_c[0] - inp.pin_a.x,
        beta_b[1] - beta_c[1] - inp.pin_a.y,
    ];
    let b_phi = delta[1] * inv_x;
    Bias {
        b_phi,
        b_x: -y * b_phi - delta[0],
        b_r: [
            inp.pin_a.x - beta_b[0] - a_b[0] * b_phi,
            inp.pin_a.y - beta_b[1] - a_b[1] * b_phi,
        ],
    }
}

/// The mass matrix blocks at `p` ([`MassBlocks`]).
#[inline(always)]
#[allow(clippy::needless_range_loop)]
fn mass_blocks<const N: usize, const R: usize>(
    k: &FfrKernel,
    frame: &Frame,
    p: &[f64; N],
    sp: &[f64; R],
) -> MassBlocks<N> {
    let f = [k.i1[0] + sp[Stacked::I2], k.i1[1] + sp[Stacked::I2 + 1]];
    let af = frame.rot(f);
    let arm = [-af[1], af[0]];
    let mut ai2 = [[0.0; N]; 2];
    for j in 0..N {
        let col = frame.rot([k.i2[0][j], k.i2[1][j]]);
        ai2[0][j] = col[0];
        ai2[1][j] = col[1];
    }
    let muu_p: [f64; N] = block(sp, Stacked::M_UU);
    let m_phiphi = k.i3 + 2.0 * sp[Stacked::I4] + dot_n(p, &muu_p);
    let pst: [f64; N] = block(sp, Stacked::S_TILDE_T);
    let mut m_phip = [0.0; N];
    for j in 0..N {
        m_phip[j] = -(k.i5[j] + pst[j]) + k.i_rot[j];
    }
    let gap: [f64; N] = block(sp, Stacked::G_A);
    let mut u = [[0.0; N]; 2];
    for i in 0..N {
        u[0][i] = ai2[0][i] + gap[i] * frame.c;
        u[1][i] = ai2[1][i] + gap[i] * frame.s;
    }
    MassBlocks {
        f,
        arm,
        ai2,
        muu_p,
        m_phiphi,
        m_phip,
        gap,
        u,
    }
}

/// The one axial mode's products ([`AxialProducts`]) where the kernel has them.
#[inline(always)]
fn axial_products<const N: usize, const R: usize, const RD: usize>(
    k: &FfrKernel,
    sp: &[f64; R],
    spd: &[f64; RD],
) -> Option<AxialProducts<N>> {
    k.axial_one.as_ref().map(|one| AxialProducts {
        a: one.a,
        t3p: block::<N, R>(sp, Stacked::T3),
        zp: block::<N, R>(sp, Stacked::Z),
        t4p: block::<N, R>(sp, Stacked::T4),
        zpd: block::<N, RD>(spd, Stacked::Z),
    })
}

/// `r = Q - M b` (module documentation, "The reduced equations"): the forces `Q` (velocity
/// products at the angular velocity `w`, gravity, elastic and damping forces, the slider
/// force, the axial strain's coupling with the bending) less the mass times the bias `b`.
#[inline(always)]
#[allow(clippy::too_many_arguments, clippy::needless_range_loop)]
fn residual<const N: usize, const R: usize, const RD: usize>(
    k: &FfrKernel,
    inp: &Inputs,
    frame: &Frame,
    mass: &MassBlocks<N>,
    bias: &Bias,
    axial: &Option<AxialProducts<N>>,
    w: f64,
    p: &[f64; N],
    pd: &[f64; N],
    sp: &[f64; R],
    spd: &[f64; RD],
) -> Residual<N> {
    let (f, arm, ai2, u) = (mass.f, mass.arm, &mass.ai2, &mass.u);
    let (b_phi, b_r) = (bias.b_phi, bias.b_r);
    let w2 = w * w;
    let m = k.mass;
    let g = inp.gravity;
    let i2pd = [spd[Stacked::I2], spd[Stacked::I2 + 1]];
    let qr = frame.rot([w2 * f[0] + 2.0 * w * i2pd[1], w2 * f[1] - 2.0 * w * i2pd[0]]);
    let mut q_phi = arm[0] * g.x + arm[1] * g.y;
    for j in 0..N {
        q_phi -= 2.0 * w * (k.i4[j] + mass.muu_p[j]) * pd[j];
    }
    let mgv_p: [f64; N] = block(sp, Stacked::M_UU_GV);
    let st_pd: [f64; N] = block(spd, Stacked::S_TILDE);
    let r_r = [
        qr[0] + m * g.x - m * b_r[0] - arm[0] * b_phi,
        qr[1] + m * g.y - m * b_r[1] - arm[1] * b_phi,
    ];
    let r_phi = q_phi - (arm[0] * b_r[0] + arm[1] * b_r[1]) - mass.m_phiphi * b_phi;
    let mut r_p = [0.0; N];
    for i in 0..N {
        r_p[i] = w2 * (k.i4[i] + mgv_p[i])
            - 2.0 * w * st_pd[i]
            - k.stiffness[i] * p[i]
            - k.damping[i] * pd[i]
            + ai2[0][i] * g.x
            + ai2[1][i] * g.y
            - u[0][i] * b_r[0]
            - u[1][i] * b_r[1]
            - mass.m_phip[i] * b_phi;
    }
    // The axial strain's coupling with the bending (crate::modal::axial_coupling; the same sums
    // in the same order as `AxialCoupling::add_forces`, on fixed-size arrays for one axial mode):
    // the axial mode's own row `p.(T p) - w^2/2 p.(Z p) + p_a p.(F p) + p'.(Z p')` and every
    // row m `p_a (2 (T p)_m - w^2 (Z p)_m + p_a (F p)_m)`; `Z p` also gives the mass part.
    if let Some(AxialProducts {
        a,
        t3p,
        zp,
        t4p,
        zpd,
    }) = axial
    {
        let pa = p[*a];
        let own = dot_n(p, t3p) - 0.5 * w2 * dot_n(p, zp) + pa * dot_n(p, t4p) + dot_n(pd, zpd);
        r_p[*a] += own;
        for m in 0..N {
            r_p[m] += pa * (2.0 * t3p[m] - w2 * zp[m] + pa * t4p[m]);
        }
    } else if let Some(ac) = &k.axial_coupling {
        ac.add_forces(p, pd, w, &mut r_p);
    }
    Residual {
        r_r,
        r_phi,
        r_p,
        r_s: inp.slider_force + inp.slider_mass * g.x - inp.slider_mass * bias.b_x,
    }
}

/// `M T` ([`MassTimesMap`]).
#[inline(always)]
fn mass_times_map<const N: usize>(
    k: &FfrKernel,
    inp: &Inputs,
    map: &VelocityMap<N>,
    mass: &MassBlocks<N>,
) -> MassTimesMap<N> {
    let (t_r, g_phi, arm, ai2) = (&map.t_r, &map.g_phi, mass.arm, &mass.ai2);
    let m = k.mass;
    let mut mt = MassTimesMap {
        mt_r: [[0.0; N]; 2],
        mt_phi: [0.0; N],
        mt_s: [0.0; N],
    };
    for j in 0..N {
        mt.mt_r[0][j] = m * t_r[0][j] + arm[0] * g_phi[j] + ai2[0][j];
        mt.mt_r[1][j] = m * t_r[1][j] + arm[1] * g_phi[j] + ai2[1][j];
        mt.mt_phi[j] =
            arm[0] * t_r[0][j] + arm[1] * t_r[1][j] + mass.m_phiphi * g_phi[j] + mass.m_phip[j];
        mt.mt_s[j] = inp.slider_mass * map.t_x[j];
    }
    mt
}

/// The reduced system `T^T M T p'' = T^T r` of the pinned rod (without the axial coupling's
/// mass part). Every column of T is a multiple of `G_0 p`: `T = tau (G_0 p)^T` with `tau` over
/// the rows R, phi, x_s (`g_phi = (s / X) G_0 p`, `t_x = (-Y s / X - c) G_0 p`,
/// `t_R = -a_B g_phi`). So `T^T M T + M_pR T_R + M_pphi g_phi` is `M_ff` plus the rank-two
/// update `(G_0 p) a^T + b (G_0 p)^T`, with `a = alpha G_0 p + beta`, `b = beta + gamma G_a p`:
/// `alpha = tau^T M_DD tau`
/// `= m |tau_R|^2 + 2 tau_phi (arm . tau_R) + M_phiphi tau_phi^2 + m_s tau_x^2`,
/// `beta = (A I2)^T tau_R + M_pphi tau_phi` and `gamma = (A e_x) . tau_R` (the stiffening
/// coupling `M_pR = (A I2)^T + c_s (G_a p) (A e_x)^T`, `c_s G_a` the kernel's `g_a`).
#[inline(always)]
#[allow(clippy::needless_range_loop)]
fn reduced_pinned<const N: usize>(
    k: &FfrKernel,
    inp: &Inputs,
    frame: &Frame,
    mass: &MassBlocks<N>,
    residual: &Residual<N>,
    g0p: &[f64; N],
) -> ([[f64; N]; N], [f64; N]) {
    let (c, s, y, a_b, arm) = (frame.c, frame.s, frame.y, frame.a_b, mass.arm);
    let (ai2, gap) = (&mass.ai2, &mass.gap);
    let (r_r, r_phi, r_s, r_p) = (residual.r_r, residual.r_phi, residual.r_s, &residual.r_p);
    let m = k.mass;
    let mut reduced = [[0.0; N]; N];
    let mut rhs = [0.0; N];
    let tau_phi = s * frame.inv_x;
    let tau_r = [-a_b[0] * tau_phi, -a_b[1] * tau_phi];
    let tau_x = -y * tau_phi - c;
    let alpha = m * (tau_r[0] * tau_r[0] + tau_r[1] * tau_r[1])
        + 2.0 * tau_phi * (arm[0] * tau_r[0] + arm[1] * tau_r[1])
        + mass.m_phiphi * tau_phi * tau_phi
        + inp.slider_mass * tau_x * tau_x;
    let gamma = c * tau_r[0] + s * tau_r[1];
    let mut a = [0.0; N];
    let mut b = [0.0; N];
    for j in 0..N {
        let beta = tau_r[0] * ai2[0][j] + tau_r[1] * ai2[1][j] + tau_phi * mass.m_phip[j];
        a[j] = alpha * g0p[j] + beta;
        b[j] = beta + gamma * gap[j];
    }
    let r_tau = tau_r[0] * r_r[0] + tau_r[1] * r_r[1] + tau_phi * r_phi + tau_x * r_s;
    for i in 0..N {
        for j in 0..N {
            reduced[i][j] = k.m_ff[i][j] + g0p[i] * a[j] + b[i] * g0p[j];
        }
        rhs[i] = g0p[i] * r_tau + r_p[i];
    }
    (reduced, rhs)
}

/// The reduced system `T^T M T p'' = T^T r` (without the axial coupling's mass part): the R,
/// phi and slider rows through `T`, the p rows directly (`M_pR T_R + M_pphi g_phi + M_ff`).
#[inline(always)]
#[allow(clippy::needless_range_loop)]
fn reduced_general<const N: usize>(
    k: &FfrKernel,
    inp: &Inputs,
    map: &VelocityMap<N>,
    mass: &MassBlocks<N>,
    mt: &MassTimesMap<N>,
    residual: &Residual<N>,
) -> ([[f64; N]; N], [f64; N]) {
    let (t_r, g_phi, t_x, u) = (&map.t_r, &map.g_phi, &map.t_x, &mass.u);
    let (mt_r, mt_phi, mt_s) = (&mt.mt_r, &mt.mt_phi, &mt.mt_s);
    let (r_r, r_phi, r_s, r_p) = (residual.r_r, residual.r_phi, residual.r_s, &residual.r_p);
    let slider = inp.slider_mass != 0.0;
    let mut reduced = [[0.0; N]; N];
    let mut rhs = [0.0; N];
    for i in 0..N {
        for j in 0..N {
            let mut e = k.m_ff[i][j]
                + t_r[0][i] * mt_r[0][j]
                + t_r[1][i] * mt_r[1][j]
                + u[0][i] * t_r[0][j]
                + u[1][i] * t_r[1][j]
                + g_phi[i] * mt_phi[j]
                + mass.m_phip[i] * g_phi[j];
            if slider {
                e += t_x[i] * mt_s[j];
            }
            reduced[i][j] = e;
        }
        rhs[i] = t_r[0][i] * r_r[0] + t_r[1][i] * r_r[1] + g_phi[i] * r_phi + r_p[i] + t_x[i] * r_s;
    }
    (reduced, rhs)
}

/// The dependent accelerations `q'' = T p'' + b` from the modal ones `zdd` into `qdd`, and
/// the multipliers from `Phi_D^T lambda = (Q - M q'')_D` (module documentation,
/// "Multipliers") into `lambda`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn dependent_accelerations_and_multipliers<const N: usize>(
    frame: &Frame,
    map: &VelocityMap<N>,
    bias: &Bias,
    mt: &MassTimesMap<N>,
    residual: &Residual<N>,
    zdd: &[f64; N],
    qdd: &mut [f64],
    lambda: &mut [f64],
) {
    let ns = 3 + N;
    let (y, x, a_b) = (frame.y, frame.x, frame.a_b);
    qdd[0] = dot_n(&map.t_r[0], zdd) + bias.b_r[0];
    qdd[1] = dot_n(&map.t_r[1], zdd) + bias.b_r[1];
    qdd[2] = dot_n(&map.g_phi, zdd) + bias.b_phi;
    qdd[ns] = dot_n(&map.t_x, zdd) + bias.b_x;
    let rr = [
        residual.r_r[0] - dot_n(&mt.mt_r[0], zdd),
        residual.r_r[1] - dot_n(&mt.mt_r[1], zdd),
    ];
    let rphi = residual.r_phi - dot_n(&mt.mt_phi, zdd);
    let rs = residual.r_s - dot_n(&mt.mt_s, zdd);
    let a_c = [a_b[0] - y, a_b[1] + x];
    let lcx = -rs;
    let lbx = rr[0] + rs;
    let kappa = rphi - a_b[0] * lbx - a_c[0] * lcx;
    let lcy = (kappa - a_b[1] * rr[1]) * frame.inv_x;
    lambda[0] = lbx;
    lambda[1] = rr[1] - lcy;
    lambda[2] = lcx;
    lambda[3] = lcy;
}
