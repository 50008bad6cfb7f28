//! The FFR rod's precomputed data in fixed-size arrays for the minimal-coordinate right-hand
//! side of the slider-crank (`mechanism::minimal`): the shape integrals of
//! [`crate::modal::ShapeIntegrals`] (Agrawal and Shabana 1985, eq. 3.17-3.18 and 6.2;
//! docs/physics.md, "Rod model 1") for at most [`MAX_MODES`] retained modes, copied once when
//! the rod is built, so that an evaluation runs on the stack with loops of a size known at
//! compile time and pays no general library's per-call overhead.
//!
//! Two combinations are formed once:
//! - the velocity part of the axial stiffening is `-phi'^2 G_v p` in `Q_p` for every rod: for
//!   the plain rod the quadratic axial force `n0 + n1 s + n2 s^2` of
//!   [`FfrRod::axial_force_coefficients`] is linear in `phi'^2`, so
//!   `G_v = rho A ((L x_b + L^2 / 2) G_0 - x_b G_1 - G_2 / 2)`; other rods carry `G_v` in
//!   `ShapeIntegrals::g_axial`. The kernel keeps `M_uu - G_v` (`Qv_p = phi'^2 (I4 + (M_uu -
//!   G_v) p) - ...`);
//! - the acceleration part `M_pR = c_s (G_a p) (A e_x)^T` of [`FfrRod::add_stiffening_coupling`]
//!   keeps `c_s G_a` (`c_s` the coupling scale).
//!
//! Units: SI (kg, m, s); body-frame quantities as in [`FfrRod`].

use super::rod::FfrRod;

/// Most retained modes the fixed-size kernel takes (more fall back to the general path).
pub const MAX_MODES: usize = 8;

/// Rows of [`Stacked`] for `n` modes: the [`Stacked::HEAD`] single rows and nine `n x n`
/// blocks.
pub const fn stacked_rows(n: usize) -> usize {
    Stacked::HEAD + 9 * n
}

/// The leading rows of [`Stacked`] an evaluation multiplies by the modal velocities `p'`: the
/// single rows and the blocks `G_0`, `S~` and `Z`.
pub const fn rate_rows(n: usize) -> usize {
    Stacked::HEAD + 3 * n
}

/// Rows of [`Stacked`] at [`MAX_MODES`].
pub const STACKED_ROWS: usize = stacked_rows(MAX_MODES);

type Row = [f64; MAX_MODES];
type Square = [[f64; MAX_MODES]; MAX_MODES];

/// The rod's shape integrals, fixed size (entries beyond `n` are zero).
#[derive(Clone, Debug)]
pub struct FfrKernel {
    /// Retained modes n (1..=MAX_MODES).
    pub n: usize,
    /// Rod mass with end bodies m, kg.
    pub mass: f64,
    /// I1 (body frame), kg m.
    pub i1: [f64; 2],
    /// I2 = int rho S_hat: rows x and y.
    pub i2: [Row; 2],
    /// I3, kg m^2.
    pub i3: f64,
    pub i4: Row,
    pub i5: Row,
    pub i_rot: Row,
    pub m_ff: Square,
    pub m_uu: Square,
    /// `M_uu - G_v` (see the module documentation); `M_uu` when the stiffening is off.
    pub m_uu_gv: Square,
    pub s_tilde: Square,
    /// `c_s G_a` (zero when the stiffening is off).
    pub g_a: Square,
    /// G_0 (zero when the stiffening is off: no foreshortening at C).
    pub g0: Square,
    /// Undeformed body-frame x of B, C and the midpoint, m.
    pub x_b: f64,
    pub x_c: f64,
    pub x_mid: f64,
    /// S_hat at B, C and the midpoint: rows x and y.
    pub s_b: [Row; 2],
    pub s_c: [Row; 2],
    pub s_mid: [Row; 2],
    /// Modal stiffness `w_i^2` and damping `2 zeta w_i`.
    pub stiffness: Row,
    pub damping: Row,
    /// Axial stiffening on (foreshortening at C, stiffening terms).
    pub stiffening: bool,
    /// The modes leave the pins in place: [`FfrKernel::pin_mobility`] at most
    /// [`PINNED_MOBILITY`], and then `s_b`, `s_c` are set to zero (their round-off), so the
    /// closed form leaves their terms out.
    pub pinned: bool,
    /// The axial strain's coupling with the bending ([`crate::modal::axial_coupling`]), where
    /// the rod has it.
    pub axial_coupling: Option<Box<crate::modal::axial_coupling::AxialCoupling>>,
    /// The same in fixed-size arrays where one mode is axial (the common case: the slider-rod
    /// axial mode), which the closed form takes instead.
    pub axial_one: Option<Box<AxialOne>>,
    /// Every matrix the closed form multiplies by `p` (or `p'`), stacked.
    pub stacked: Stacked,
    /// `S_hat` at B, C and the midpoint as the shape integrals give them (the pin rows not set
    /// to zero with [`FfrKernel::pinned`]), for [`FfrKernel::mid_deflection`].
    pub points: [[Row; 2]; 3],
}

/// The rows an evaluation multiplies by the modal coordinates `p`, stacked into one matrix so
/// that `S p` is one pass (column by column, every row's sum in the order of a dot product):
/// the single rows `S_B` (x, y), `S_C` (x, y), `I2` (x, y), `I4`, then the `n x n` blocks
/// `G_0`, `S~`, `Z`, `S~^T`, `M_uu`, `c_s G_a`, `M_uu - G_v`, `T`, `F` (the last three of
/// [`AxialOne`], zero without one axial mode), block `b` at row [`Stacked::block`]`(b, n)`.
/// The first [`rate_rows`] rows are also the products with `p'`.
#[derive(Clone, Debug)]
pub struct Stacked {
    /// Column `j`: column `j` of every stacked row.
    pub columns: [[f64; STACKED_ROWS]; MAX_MODES],
}

impl Stacked {
    pub const S_B: usize = 0;
    pub const S_C: usize = 2;
    pub const I2: usize = 4;
    pub const I4: usize = 6;
    /// Single rows before the blocks.
    pub const HEAD: usize = 7;
    pub const G0: usize = 0;
    pub const S_TILDE: usize = 1;
    pub const Z: usize = 2;
    pub const S_TILDE_T: usize = 3;
    pub const M_UU: usize = 4;
    pub const G_A: usize = 5;
    pub const M_UU_GV: usize = 6;
    pub const T3: usize = 7;
    pub const T4: usize = 8;

    /// First row of block `b` for `n` modes.
    pub const fn block(b: usize, n: usize) -> usize {
        Self::HEAD + b * n
    }

    /// The stack of `k`'s rows.
    fn of(k: &FfrKernel) -> Stacked {
        let n = k.n;
        let mut columns = [[0.0; STACKED_ROWS]; MAX_MODES];
        let zero = [[0.0; MAX_MODES]; MAX_MODES];
        let axial = k.axial_one.as_deref();
        let blocks: [(usize, &Square, bool); 9] = [
            (Self::G0, &k.g0, false),
            (Self::S_TILDE, &k.s_tilde, false),
            (Self::Z, axial.map_or(&zero, |a| &a.z), false),
            (Self::S_TILDE_T, &k.s_tilde, true),
            (Self::M_UU, &k.m_uu, false),
            (Self::G_A, &k.g_a, false),
            (Self::M_UU_GV, &k.m_uu_gv, false),
            (Self::T3, axial.map_or(&zero, |a| &a.t3), false),
            (Self::T4, axial.map_or(&zero, |a| &a.t4), false),
        ];
        for (j, column) in columns.iter_mut().enumerate().take(n) {
            let single = [
                k.s_b[0][j],
                k.s_b[1][j],
                k.s_c[0][j],
                k.s_c[1][j],
                k.i2[0][j],
                k.i2[1][j],
                k.i4[j],
            ];
            column[..Self::HEAD].copy_from_slice(&single);
            for (b, m, transposed) in blocks {
                for i in 0..n {
                    column[Self::block(b, n) + i] = if transposed { m[j][i] } else { m[i][j] };
                }
            }
        }
        Stacked { columns }
    }
}

/// [`crate::modal::axial_coupling::AxialCoupling`] with one axial mode `a`: its rows `T_aij`,
/// `Z_aij` and `F_aaij`.
#[derive(Clone, Debug)]
pub struct AxialOne {
    pub a: usize,
    pub t3: Square,
    pub z: Square,
    pub t4: Square,
}

impl AxialOne {
    fn of(ac: &crate::modal::axial_coupling::AxialCoupling) -> Option<AxialOne> {
        let n = ac.n;
        if ac.axial.len() != 1 || n > MAX_MODES {
            return None;
        }
        Some(AxialOne {
            a: ac.axial[0],
            t3: square(n, |i, j| ac.t3[i * n + j]),
            z: square(n, |i, j| ac.z[i * n + j]),
            t4: square(n, |i, j| ac.t4[i * n + j]),
        })
    }
}

/// [`FfrKernel::pin_mobility`] below which the pin rows are round-off of exact zeros (the
/// constrained degrees of freedom of the reduced eigenproblem are exactly zero; a bending
/// mode's axial displacement at C is zero but for the eigensolver's round-off, about 1e-16).
pub const PINNED_MOBILITY: f64 = 1e-12;

fn square(n: usize, f: impl Fn(usize, usize) -> f64) -> Square {
    let mut s = [[0.0; MAX_MODES]; MAX_MODES];
    for (i, row) in s.iter_mut().enumerate().take(n) {
        for (j, x) in row.iter_mut().enumerate().take(n) {
            *x = f(i, j);
        }
    }
    s
}

fn row(n: usize, f: impl Fn(usize) -> f64) -> Row {
    let mut r = [0.0; MAX_MODES];
    for (j, x) in r.iter_mut().enumerate().take(n) {
        *x = f(j);
    }
    r
}

impl FfrKernel {
    /// How far the retained modes move the pins B and C in the body frame, per unit
    /// deflection: `max_j max(|S_B e_j|, |S_C e_j|) sqrt(m)` (dimensionless; a deflection `d`
    /// is a modal amplitude of about `d sqrt(m)` at unit modal mass). Zero (to round-off) for
    /// the modes of the pinned rod (simply supported bending modes): then the modal
    /// coordinates are the mechanism's own linear oscillators at the undeformed configuration
    /// (the reduced mass `T^T M T` is `M_ff` there, docs/physics.md "Minimal coordinates"),
    /// whatever the crank angle and the slider mass.
    pub fn pin_mobility(&self) -> f64 {
        let mut largest: f64 = 0.0;
        for j in 0..self.n {
            for rows in [&self.s_b, &self.s_c] {
                largest = largest.max(rows[0][j].hypot(rows[1][j]));
            }
        }
        largest * self.mass.sqrt()
    }

    /// The rod's mid-deflection ([`crate::rod::body::chord_distance`] of `ubar` at B, C and
    /// the midpoint) from its modal coordinates `p`: `ubar = xbar + S_hat p`, at C less
    /// `1/2 p^T G_0 p` with the stiffening on, the sums in the order of the rod's own `ubar`.
    pub fn mid_deflection(&self, p: &[f64]) -> f64 {
        let p = &p[..self.n];
        let [b, mut c, mid] = [(self.x_b, 0), (self.x_c, 1), (self.x_mid, 2)].map(|(x, at)| {
            let [rx, ry] = &self.points[at];
            let mut u = nalgebra::Vector2::new(x, 0.0);
            for ((sx, sy), pj) in rx.iter().zip(ry).zip(p) {
                u.x += sx * pj;
                u.y += sy * pj;
            }
            u
        });
        if self.stiffening {
            let mut quad = 0.0;
            for (row, pi) in self.g0.iter().zip(p) {
                for (g, pj) in row.iter().zip(p) {
                    quad += pi * g * pj;
                }
            }
            c.x -= 0.5 * quad;
        }
        crate::rod::body::chord_distance([b, c, mid])
    }

    /// Set [`FfrKernel::pinned`] (and the pin rows to zero) where the modes leave the pins in
    /// place, then stack the rows ([`Stacked`]).
    fn with_pins_checked(mut self) -> FfrKernel {
        if self.pin_mobility() <= PINNED_MOBILITY {
            self.pinned = true;
            self.s_b = [[0.0; MAX_MODES]; 2];
            self.s_c = [[0.0; MAX_MODES]; 2];
        }
        self.stacked = Stacked::of(&self);
        self
    }

    /// The kernel of `rod`, or `None` if it has no modes or more than [`MAX_MODES`].
    pub fn new(rod: &FfrRod) -> Option<FfrKernel> {
        let n = rod.n_modes();
        if n == 0 || n > MAX_MODES {
            return None;
        }
        let ig = &rod.integrals;
        let stiff = rod.axial_stiffening;
        let (l, xb, ra) = (rod.length, ig.x_b, rod.rho_a);
        let g_v = |i: usize, j: usize| -> f64 {
            if !stiff {
                return 0.0;
            }
            match &ig.g_axial {
                Some([_, g_v]) => g_v[(i, j)],
                None => {
                    ra * ((l * xb + 0.5 * l * l) * ig.g[0][(i, j)]
                        - xb * ig.g[1][(i, j)]
                        - 0.5 * ig.g[2][(i, j)])
                }
            }
        };
        let two = |m: &nalgebra::DMatrix<f64>| [row(n, |j| m[(0, j)]), row(n, |j| m[(1, j)])];
        Some(
            FfrKernel {
                n,
                mass: ig.mass,
                i1: [ig.i1.x, ig.i1.y],
                i2: two(&ig.i2),
                i3: ig.i3,
                i4: row(n, |j| ig.i4[j]),
                i5: row(n, |j| ig.i5[j]),
                i_rot: row(n, |j| ig.i_rot[j]),
                m_ff: square(n, |i, j| ig.m_ff[(i, j)]),
                m_uu: square(n, |i, j| ig.m_uu[(i, j)]),
                m_uu_gv: square(n, |i, j| ig.m_uu[(i, j)] - g_v(i, j)),
                s_tilde: square(n, |i, j| ig.s_tilde[(i, j)]),
                g_a: square(n, |i, j| {
                    if stiff {
                        rod.coupling_scale * rod.acceleration_stiffness[(i, j)]
                    } else {
                        0.0
                    }
                }),
                g0: square(n, |i, j| if stiff { ig.g[0][(i, j)] } else { 0.0 }),
                x_b: ig.x_b,
                x_c: ig.x_c,
                x_mid: ig.x_mid,
                s_b: two(&ig.s_b),
                s_c: two(&ig.s_c),
                s_mid: two(&ig.s_mid),
                stiffness: row(n, |j| rod.stiffness[j]),
                damping: row(n, |j| rod.damping[j]),
                stiffening: stiff,
                pinned: false,
                axial_coupling: rod.axial_coupling.clone().map(Box::new),
                axial_one: rod
                    .axial_coupling
                    .as_ref()
                    .and_then(AxialOne::of)
                    .map(Box::new),
                stacked: Stacked {
                    columns: [[0.0; STACKED_ROWS]; MAX_MODES],
                },
                points: [two(&ig.s_b), two(&ig.s_c), two(&ig.s_mid)],
            }
            .with_pins_checked(),
        )
    }
}
