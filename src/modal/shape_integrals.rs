//! Inertia shape integrals of the retained modes, computed once (the "preprocessor" of
//! Agrawal and Shabana 1985, Fig. 4; Shabana, *Dynamics of Multibody Systems*, 4th ed., section 5.5).
//!
//! With `xbar(s) = (x_b + s, 0)` the undeformed position of the material point at arc length
//! `s` from B in the body frame, `S_hat(s)` (2 x n) the modal shape matrix and
//! `I~ = [[0, -1], [1, 0]]`:
//! `m = int rho`, `I1 = int rho xbar`, `I2 = int rho S_hat`, `I3 = int rho xbar.xbar`,
//! `I4 = int rho xbar^T S_hat`, `I5 = int rho xbar^T I~ S_hat`, `M_ff = int rho S_hat^T S_hat`,
//! `S~ = int rho S_hat^T I~ S_hat` (skew), all over the rod (`int rho f = int_0^L rho A f ds`).
//!
//! Consistent mass: exact 4-point Gauss quadrature per element (integrands of degree <= 6).
//! Lumped mass: point masses at the nodes plus nodal rotary inertia `J_i`; the rotary inertia
//! adds `sum J_i` to `I3` and the row `I_rot = sum J_i Theta_i` (Theta_i = slope row of node i)
//! to the rotation-deformation coupling (it is zero for the consistent Euler-Bernoulli mass).
//!
//! For the axial stiffening the chord-relative slope `D(s) = v'(s) - (v(L) - v(0)) / L`
//! (1 x n) gives `G_k = int_0^L s^k D^T D ds`, k = 0, 1, 2: the geometric stiffness of an axial
//! force `N(s) = n0 + n1 s + n2 s^2` is `K_G = n0 G_0 + n1 G_1 + n2 G_2` (Cook, Malkus,
//! Plesha and Witt, *Concepts and Applications of FEA*, 4th ed., eq. 18.3-4).
//!
//! For the shear-deformable rod the foreshortening's integrand `v'^2` becomes
//! `2 v' psi - psi^2 = v'^2 - gamma^2` (Reissner's axial strain along the section normal,
//! `eps = u' + v' psi - psi^2 / 2` to second order: E. Reissner, ZAMP 23, 1972), so `D^T D` in
//! every `G_k` becomes `D^T D_psi + D_psi^T D - D_psi^T D_psi` with `D_psi` the chord-relative
//! section rotation row (docs/physics.md, "The shear-deformable rod").
//!
//! A rod that is not plain (section table, shear deformation, end bodies; see
//! [`crate::beam::RodDefinition::is_plain`]) takes every integral with `rho A(s)` on the pieces
//! of its section table (exact Gauss quadrature per piece), plus:
//! - the end bodies as point masses at B and C (`m_B`, `m_C`) and rotary inertias `J_B`, `J_C`
//!   on the end nodes' rotation rows `Theta_B`, `Theta_C` (like the lumped rotary inertia:
//!   `I3 += J`, `I_rot += J Theta`, `M_ff += J Theta^T Theta`);
//! - the section's rotary inertia `rho I(s)` on the rotation `psi(s)` for the shear-deformable
//!   rod, in the same three places;
//! - `M_ff = M_uu + (rotary part)`, which is the identity for the mass-normalized modes;
//! - for the axial stiffening, the axial force is no longer a quadratic in `s`: with
//!   `mu(s) = int_s^L rho A ds' + m_C` (mass beyond s) and
//!   `nu(s) = int_s^L rho A (x_b + s') ds' + m_C (x_b + L)`, the force of the frame motion is
//!   `N(s) = -mu(s) e.R'' + phi'^2 nu(s)`, and its geometric stiffness
//!   `K_G = (e.R'') G_a + phi'^2 G_v` with `G_a = -int mu D^T D ds`, `G_v = int nu D^T D ds`
//!   (field [`ShapeIntegrals::g_axial`]; for the plain rod they are `rho A (G_1 - L G_0)` and
//!   the quadratic `n0 G_0 + n1 G_1 + n2 G_2` at `phi' = 1`, kept in that original form).

use nalgebra::{DMatrix, DVector, RowDVector, Vector2};

use super::component_modes::ComponentModes;
use crate::beam::quadrature::GAUSS4;
use crate::beam::MassKind;

/// The shape integrals of one rod with its retained modes.
#[derive(Clone, Debug)]
pub struct ShapeIntegrals {
    /// Rod mass m, kg.
    pub mass: f64,
    /// I1 = int rho xbar (2), kg m.
    pub i1: Vector2<f64>,
    /// I2 = int rho S_hat (2 x n).
    pub i2: DMatrix<f64>,
    /// I3 = int rho xbar.xbar (+ nodal rotary inertia), kg m^2.
    pub i3: f64,
    /// I4 = int rho xbar^T S_hat (n).
    pub i4: DVector<f64>,
    /// I5 = int rho xbar^T I~ S_hat (n).
    pub i5: DVector<f64>,
    /// Rotary coupling row sum J_i Theta_i (n); zero for consistent mass.
    pub i_rot: DVector<f64>,
    /// M_ff = int rho S_hat^T S_hat (n x n) plus, for lumped mass, the nodal rotary inertia;
    /// the identity for mass-normalized modes.
    pub m_ff: DMatrix<f64>,
    /// The translational part of M_ff (no rotary inertia): the quadratic terms of `M_phiphi`,
    /// `Qv_phi` and `Qv_p` come from `int rho ubar.ubar` and use this one.
    pub m_uu: DMatrix<f64>,
    /// S~ = int rho S_hat^T I~ S_hat (n x n, skew).
    pub s_tilde: DMatrix<f64>,
    /// Geometric stiffness moments G_0, G_1, G_2 (n x n each), chord-relative slopes (the
    /// shear-deformable rod: Reissner's form, module documentation).
    pub g: [DMatrix<f64>; 3],
    /// Rods that are not plain: `[G_a, G_v]`, the geometric stiffness per unit `e.R''` and per
    /// unit `phi'^2` of the axial force of the frame motion (module documentation); `None` for
    /// the plain rod, whose force is the quadratic of the `G_k`.
    pub g_axial: Option<[DMatrix<f64>; 2]>,
    /// S_hat at the B end (s = 0), the C end (s = L) and the midpoint (s = L / 2).
    pub s_b: DMatrix<f64>,
    pub s_c: DMatrix<f64>,
    pub s_mid: DMatrix<f64>,
    /// Undeformed body-frame x of B, C and the midpoint.
    pub x_b: f64,
    pub x_c: f64,
    pub x_mid: f64,
}

impl ShapeIntegrals {
    /// Compute every integral for `modes`.
    pub fn new(modes: &ComponentModes) -> ShapeIntegrals {
        Self::with_extent(modes, Extent::Full)
    }

    /// Only the integrals linear in the modes (`m`, `I1`, `I2`, `I3`, `I4`, `I5`, `I_rot`, the
    /// point shapes): the n x n ones (`M_ff`, `M_uu`, `S~`, the `G`) are left empty (0 x 0).
    /// Cost O(n) per quadrature point instead of O(n^2): for many modes at once (every mode of
    /// the rod, for the static corrections of the left-out ones).
    pub fn first_order(modes: &ComponentModes) -> ShapeIntegrals {
        Self::with_extent(modes, Extent::FirstOrder)
    }

    fn with_extent(modes: &ComponentModes, extent: Extent) -> ShapeIntegrals {
        if modes.mesh.is_plain() {
            Self::plain(modes, extent)
        } else {
            Self::general(modes, extent)
        }
    }

    /// The plain rod (uniform, Euler-Bernoulli, no end bodies): closed-form element.
    fn plain(modes: &ComponentModes, extent: Extent) -> ShapeIntegrals {
        let mesh = &modes.mesh;
        let n = modes.n_modes();
        let el = mesh.element();
        let l = el.length;
        let rho_a = mesh.section.mass_per_length();
        let length = mesh.section.length;
        let nn = extent.square_size(n);

        let mut sums = MassSums::new(n, nn);
        let mut g = [
            DMatrix::zeros(nn, nn),
            DMatrix::zeros(nn, nn),
            DMatrix::zeros(nn, nn),
        ];

        // The chord rotation row (v(L) - v(0)) / L.
        let s_b = point_shape(modes, 0.0);
        let s_c = point_shape(modes, length);
        let s_mid = point_shape(modes, 0.5 * length);
        let chord = (s_c.row(1) - s_b.row(1)) / length;

        for e in 0..mesh.n_elements {
            let t = modes.element_shapes(e);
            let s0 = e as f64 * l;
            match modes.mass_kind {
                MassKind::Consistent => {
                    for (xi, w) in GAUSS4 {
                        let sh = el.shape(xi) * &t;
                        let a = sh.rows(0, 1).into_owned();
                        let b = sh.rows(1, 1).into_owned();
                        sums.add_point(w * l * rho_a, mesh.x_b + s0 + xi * l, &a, &b);
                    }
                }
                MassKind::Lumped => {
                    let half = 0.5 * rho_a * l;
                    let j_rot = rho_a * l * l * l / 78.0;
                    for (node_xi, node_row) in [(0.0, 0usize), (1.0, 3usize)] {
                        let a = t.rows(node_row, 1).into_owned();
                        let b = t.rows(node_row + 1, 1).into_owned();
                        sums.add_point(half, mesh.x_b + s0 + node_xi * l, &a, &b);
                        // The nodal rotary inertia on the slope row (its part of `M_ff` comes
                        // with the assembled lumped mass below).
                        sums.add_rotary(j_rot, &t.rows(node_row + 2, 1).into_owned());
                    }
                }
            }
            // Geometric stiffness moments, always by exact quadrature of the slopes.
            for (xi, w) in GAUSS4.into_iter().filter(|_| extent == Extent::Full) {
                let s = s0 + xi * l;
                let d = el.slope(xi) * &t - &chord;
                let dtd = d.transpose() * &d;
                for (k, gk) in g.iter_mut().enumerate() {
                    *gk += &dtd * (w * l * s.powi(k as i32));
                }
            }
        }

        let m_ff = match modes.mass_kind {
            _ if extent == Extent::FirstOrder => DMatrix::zeros(0, 0),
            MassKind::Consistent => {
                let mut m_ff = DMatrix::zeros(nn, nn);
                for e in 0..mesh.n_elements {
                    let t = modes.element_shapes(e);
                    for (xi, w) in GAUSS4 {
                        let sh = el.shape(xi) * &t;
                        m_ff += sh.transpose() * &sh * (w * l * rho_a);
                    }
                }
                m_ff
            }
            MassKind::Lumped => {
                let (_, m) = mesh.assemble(MassKind::Lumped);
                let psi = &modes.shapes;
                let mm = psi.transpose() * &m * psi;
                DMatrix::from_fn(n, n, |i, j| mm[(i, j)])
            }
        };

        ShapeIntegrals {
            mass: rho_a * length,
            i1: sums.i1,
            i2: sums.i2,
            i3: sums.i3 + sums.rotary_total,
            i4: sums.i4,
            i5: sums.i5,
            i_rot: sums.i_rot,
            m_ff,
            m_uu: sums.m_uu,
            s_tilde: sums.s_tilde,
            g,
            g_axial: None,
            s_b,
            s_c,
            s_mid,
            x_b: mesh.x_b,
            x_c: mesh.x_b + length,
            x_mid: mesh.x_b + 0.5 * length,
        }
    }

    /// A rod with a section table, shear deformation or end bodies (module documentation).
    fn general(modes: &ComponentModes, extent: Extent) -> ShapeIntegrals {
        let mesh = &modes.mesh;
        let def = &mesh.definition;
        let n = modes.n_modes();
        let nn = extent.square_size(n);
        let length = mesh.section.length;
        let x_b = mesh.x_b;

        let s_b = point_shape(modes, 0.0);
        let s_c = point_shape(modes, length);
        let s_mid = point_shape(modes, 0.5 * length);
        let chord = (s_c.row(1) - s_b.row(1)) / length;

        let mut sums = MassSums::new(n, nn);
        let mut stiffness = GeometricMoments::new(nn);
        for e in 0..mesh.n_elements {
            general_element(modes, e, extent, &chord, &mut sums, &mut stiffness);
        }
        // End bodies: point masses and rotary inertias at the end nodes.
        let last = mesh.n_elements;
        for (node, body) in [(0usize, def.big_end), (last, def.small_end)] {
            let row = |k: usize| DMatrix::from_fn(1, n, |_, j| modes.shapes[(3 * node + k, j)]);
            sums.add_point(body.mass, mesh.node_x(node), &row(0), &row(1));
            sums.add_rotary(body.inertia, &row(2));
        }
        let m_ff = &sums.m_uu + &sums.m_rot;

        ShapeIntegrals {
            mass: def.total_mass(),
            i1: sums.i1,
            i2: sums.i2,
            i3: sums.i3 + sums.rotary_total,
            i4: sums.i4,
            i5: sums.i5,
            i_rot: sums.i_rot,
            m_ff,
            m_uu: sums.m_uu,
            s_tilde: sums.s_tilde,
            g: stiffness.g,
            g_axial: Some([stiffness.g_a, stiffness.g_v]),
            s_b,
            s_c,
            s_mid,
            x_b,
            x_c: x_b + length,
            x_mid: x_b + 0.5 * length,
        }
    }
}

/// The integrals over the rod's mass, summed over mass points (the quadrature points with
/// their weight times `rho A`, the lumped masses, the end bodies) and rotary inertias (module
/// documentation): `I1` to `I5`, `I_rot`, `S~`, `M_uu` and the rotary part of `M_ff`; `n`
/// modes, `nn` the side of the n x n integrals ([`Extent::square_size`]).
struct MassSums {
    n: usize,
    nn: usize,
    i1: Vector2<f64>,
    i2: DMatrix<f64>,
    /// `int rho xbar.xbar` of the mass points (the rotary inertias are in `rotary_total`).
    i3: f64,
    i4: DVector<f64>,
    i5: DVector<f64>,
    i_rot: DVector<f64>,
    s_tilde: DMatrix<f64>,
    m_uu: DMatrix<f64>,
    /// `sum J Theta^T Theta` over the rotary inertias `J` on their rotation rows `Theta`.
    m_rot: DMatrix<f64>,
    /// `sum J`, kg m^2.
    rotary_total: f64,
}

impl MassSums {
    fn new(n: usize, nn: usize) -> MassSums {
        MassSums {
            n,
            nn,
            i1: Vector2::zeros(),
            i2: DMatrix::zeros(2, n),
            i3: 0.0,
            i4: DVector::zeros(n),
            i5: DVector::zeros(n),
            i_rot: DVector::zeros(n),
            s_tilde: DMatrix::zeros(nn, nn),
            m_uu: DMatrix::zeros(nn, nn),
            m_rot: DMatrix::zeros(nn, nn),
            rotary_total: 0.0,
        }
    }

    /// One mass point: mass `w` (kg), body-frame x (m), modal shape rows `a` (axial) and `b`
    /// (transverse), 1 x n each. `S^T I~ S = -a^T b + b^T a`; `S^T S = a^T a + b^T b`.
    fn add_point(&mut self, w: f64, x: f64, a: &DMatrix<f64>, b: &DMatrix<f64>) {
        self.i1[0] += w * x;
        self.i3 += w * x * x;
        for j in 0..self.n {
            self.i2[(0, j)] += w * a[(0, j)];
            self.i2[(1, j)] += w * b[(0, j)];
            self.i4[j] += w * x * a[(0, j)];
            self.i5[j] -= w * x * b[(0, j)];
        }
        for i in 0..self.nn {
            for j in 0..self.nn {
                self.s_tilde[(i, j)] += w * (b[(0, i)] * a[(0, j)] - a[(0, i)] * b[(0, j)]);
                self.m_uu[(i, j)] += w * (a[(0, i)] * a[(0, j)] + b[(0, i)] * b[(0, j)]);
            }
        }
    }

    /// Rotary inertia `j` (kg m^2) on the rotation row `theta` (1 x n): `I3 += j`,
    /// `I_rot += j Theta`, `M_ff += j Theta^T Theta`.
    fn add_rotary(&mut self, j: f64, theta: &DMatrix<f64>) {
        self.rotary_total += j;
        for a in 0..self.n {
            self.i_rot[a] += j * theta[(0, a)];
            for b in 0..self.nn {
                self.m_rot[(a, b)] += j * theta[(0, a)] * theta[(0, b)];
            }
        }
    }
}

/// The geometric stiffness moments of a rod that is not plain (module documentation): `G_0`,
/// `G_1`, `G_2` and `G_a`, `G_v`, nn x nn each.
struct GeometricMoments {
    g: [DMatrix<f64>; 3],
    g_a: DMatrix<f64>,
    g_v: DMatrix<f64>,
}

impl GeometricMoments {
    fn new(nn: usize) -> GeometricMoments {
        GeometricMoments {
            g: [
                DMatrix::zeros(nn, nn),
                DMatrix::zeros(nn, nn),
                DMatrix::zeros(nn, nn),
            ],
            g_a: DMatrix::zeros(nn, nn),
            g_v: DMatrix::zeros(nn, nn),
        }
    }
}

/// The quadrature points of element `e` of a rod that is not plain, into `sums` (mass and the
/// section's rotary inertia on the rotation `psi` of the shear-deformable rod) and, for
/// [`Extent::Full`], `stiffness` (the foreshortening's integrand `D^T D` against `s^k`, `-mu`
/// and `nu`, module documentation; `chord` the chord rotation row).
fn general_element(
    modes: &ComponentModes,
    e: usize,
    extent: Extent,
    chord: &RowDVector<f64>,
    sums: &mut MassSums,
    stiffness: &mut GeometricMoments,
) {
    let mesh = &modes.mesh;
    let def = &mesh.definition;
    let table = mesh.section_table().expect("not plain");
    let n = modes.n_modes();
    let l = mesh.element_length();
    let rho = mesh.section.density;
    let (length, x_b, small) = (mesh.section.length, mesh.x_b, def.small_end.mass);
    let t = modes.element_shapes(e);
    let el = mesh.section_element(e).expect("not plain");
    let s0 = e as f64 * l;
    let bubbles = el.n_bubbles() > 0;
    // Integrands up to degree 2 p + 1 = 7 (rho A v^2 on a linear piece; mu D^T D with the
    // quadratic mu is 2 (p - 1) + 2): exact with 4-point Gauss per piece.
    for (s, sec, w) in table.quadrature_points(s0, s0 + l) {
        let xi = (s - s0) / l;
        let sh = if bubbles {
            el.shape_full(xi) * &t
        } else {
            dynamic(el.shape(xi) * &t)
        };
        let a = sh.rows(0, 1).into_owned();
        let b = sh.rows(1, 1).into_owned();
        sums.add_point(w * rho * sec.area, x_b + s, &a, &b);
        let psi = def.shear_modulus.map(|_| {
            if bubbles {
                el.rotation_full(xi) * &t
            } else {
                dynamic(el.rotation(xi) * &t)
            }
        });
        if let Some(psi) = &psi {
            sums.add_rotary(
                w * rho * sec.area_moment,
                &DMatrix::from_fn(1, n, |_, j| psi[(0, j)]),
            );
        }
        if extent == Extent::FirstOrder {
            continue;
        }
        // Geometric stiffness: slopes of the element's v interpolation.
        let slope = if bubbles {
            el.slope_full(xi) * &t
        } else {
            dynamic(el.slope(xi) * &t)
        };
        let d = slope - chord;
        // The foreshortening's integrand: `v'^2` (Euler-Bernoulli), `2 v' psi - psi^2 =
        // v'^2 - gamma^2` for the shear-deformable rod (module documentation).
        let dtd = match &psi {
            None => d.transpose() * &d,
            Some(psi) => {
                let dpsi = psi - chord;
                let cross = d.transpose() * &dpsi;
                &cross + cross.transpose() - dpsi.transpose() * &dpsi
            }
        };
        for (k, gk) in stiffness.g.iter_mut().enumerate() {
            *gk += &dtd * (w * s.powi(k as i32));
        }
        let (tail_a, tail_m) = table.tail_integrals(s);
        let mu = rho * tail_a + small;
        let nu = rho * (x_b * tail_a + tail_m) + small * (x_b + length);
        stiffness.g_a -= &dtd * (w * mu);
        stiffness.g_v += &dtd * (w * nu);
    }
}

/// Which integrals [`ShapeIntegrals`] computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Extent {
    /// Every integral.
    Full,
    /// Those linear in the modes ([`ShapeIntegrals::first_order`]).
    FirstOrder,
}

impl Extent {
    /// The side of the n x n integrals for `n` modes.
    fn square_size(self, n: usize) -> usize {
        match self {
            Extent::Full => n,
            Extent::FirstOrder => 0,
        }
    }
}

/// A fixed-row matrix as a dynamic one (the same numbers).
fn dynamic<R: nalgebra::DimName>(m: nalgebra::OMatrix<f64, R, nalgebra::Dyn>) -> DMatrix<f64> {
    DMatrix::from_column_slice(m.nrows(), m.ncols(), m.as_slice())
}

/// `S_hat(s)` (2 x n) at arc length `s` from B.
pub fn point_shape(modes: &ComponentModes, s: f64) -> DMatrix<f64> {
    let (e, xi) = modes.mesh.locate(s);
    let sh = modes.mesh.shape(e, xi) * modes.element_shapes(e);
    DMatrix::from_fn(2, sh.ncols(), |i, j| sh[(i, j)])
}

/// The rotation row `psi(s)` (1 x n) at arc length `s` from B: the slope for Euler-Bernoulli,
/// the section rotation for the shear-deformable rod.
pub fn point_rotation(modes: &ComponentModes, s: f64) -> DMatrix<f64> {
    let (e, xi) = modes.mesh.locate(s);
    let r = modes.mesh.rotation(e, xi) * modes.element_shapes(e);
    DMatrix::from_fn(1, r.ncols(), |_, j| r[(0, j)])
}
