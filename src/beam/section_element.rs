//! The planar beam element of a rod whose section varies ([`SectionTable`]), Euler-Bernoulli
//! or shear-deformable (Timoshenko).
//!
//! Coordinates as in [`super::element`]: `e = [u1, v1, psi1, u2, v2, psi2]` in the element axis.
//! For Euler-Bernoulli `psi` is the slope `v'`; for Timoshenko it is the rotation of the
//! section, and the shear strain is `gamma = v' - psi`.
//!
//! # Shear-deformable element: interdependent interpolation (IIE)
//! Friedman and Kosmatka 1993 ("An improved two-node Timoshenko beam finite element",
//! *Computers & Structures* 47(3), 473-481, eq. 14-15; the same element is Reddy 1997, "On
//! locking-free shear deformable beam finite elements", *CMAME* 149, 113-132, the IIE of
//! section 3): with `xi = x / l`, `Phi = 12 E I / (G A_s l^2)` and `mu = 1 / (1 + Phi)`,
//!
//! ```text
//! v   = mu [ (2xi^3 - 3xi^2 - Phi xi + 1 + Phi) v1 + l (xi^3 - (2 + Phi/2) xi^2 + (1 + Phi/2) xi) psi1
//!          - (2xi^3 - 3xi^2 - Phi xi) v2          + l (xi^3 - (1 - Phi/2) xi^2 - (Phi/2) xi) psi2 ]
//! psi = mu [ (6/l)(xi^2 - xi) v1 + (3xi^2 - (4 + Phi) xi + 1 + Phi) psi1
//!          - (6/l)(xi^2 - xi) v2 + (3xi^2 - (2 - Phi) xi) psi2 ]
//! ```
//!
//! These solve the homogeneous Timoshenko equations of the uniform element exactly, so the
//! shear strain is constant over the element and there is no shear locking; at `Phi = 0`
//! (`G -> infinity`) they are the Hermite cubics and `psi = v'` (Euler-Bernoulli). For a
//! varying section `Phi` is formed with the element means of `E I` and `G A_s`.
//!
//! # Hierarchical element (the rod's shear-deformable element)
//! The IIE's shear strain is constant per element, so once shear energy matters its
//! frequencies converge at second order only. [`SectionElement::with_degree`] adds interior
//! ("bubble") coordinates after the six nodal ones: with `t = 2 xi - 1` and the integrated
//! Legendre polynomials `N_k(t) = (P_k(t) - P_{k-2}(t)) / sqrt(2 (2k - 1))`, `k >= 2`, which
//! vanish at both ends and have `dN_k / dt = sqrt((2k - 1) / 2) P_{k-1}(t)` (Szabo and Babuska,
//! *Finite Element Analysis*, 1991, ch. 3, the hierarchic p-version shape
//! functions), degree `p` adds `N_2 .. N_p` on `v` and `N_2 .. N_{p-1}` on `psi` (`2 p - 3`
//! coordinates). With the IIE's nodal functions (cubic `v`, quadratic `psi`) the element for
//! `p = 3` spans exactly `v` in P3, `psi` in P2, independent per element and C0 across nodes:
//! the locking-free `P_{k+1} / P_k` pair (`psi = v'` representable for every cubic `v`; Reddy
//! 1997, *CMAME* 149), with a linear shear strain and curvature, and fourth-order
//! frequencies (measured in tests/rod_exact_frequencies.rs). The rod uses `p` =
//! [`TIMOSHENKO_DEGREE`] = 3. For a uniform section the IIE's nodal functions, which solve the
//! homogeneous equations, are stiffness-orthogonal to the interior ones (boundary terms of
//! functions that vanish at the nodes), which keeps the stiffness well conditioned; without
//! interior coordinates (`p = 0`) the element is the IIE, bit for bit.
//!
//! # Matrices
//! Energies integrated over the element with the properties at each point (exact: the
//! properties are linear on each piece of [`SectionTable::pieces`], the integrands polynomial
//! of degree <= 7, 4-point Gauss per piece):
//! - stiffness `K = int (E A u'^T u' + E I psi'^T psi' + G A_s gamma^T gamma) dx` (the shear term
//!   only for Timoshenko; for Euler-Bernoulli `psi' = v''`);
//! - consistent mass `M = int (rho A S^T S + rho I psi^T psi) dx` (rotary inertia only for
//!   Timoshenko: the Euler-Bernoulli element keeps the convention of [`super::element`]).
//!
//! With interior coordinates ([`SectionElement::stiffness_full`], [`SectionElement::mass_full`])
//! the same integrals; for `p = 3` the highest degree is `rho A v^2` on a linear piece,
//! 3 + 3 + 1 = 7, still exact with 4 points.
//!
//! For a uniform section these give the closed forms (Przemieniecki eq. 5.25, 5.31, 11.19; the
//! IIE stiffness `E I / ((1 + Phi) l^3) [[12, 6l, -12, 6l], [6l, (4 + Phi) l^2, -6l,
//! (2 - Phi) l^2], ...]`, Przemieniecki eq. 5.115); the unit tests check both.

use nalgebra::DMatrix;

use super::element::{ElementMatrix, ShapeMatrix, SlopeRow};
use super::section_table::{SectionTable, SectionValues};

/// Degree of `v` of the hierarchical shear-deformable element the rod uses (`psi` one lower):
/// 3, i.e. `v` in P3 and `psi` in P2, three interior coordinates per element (module
/// documentation, "Hierarchical element").
pub const TIMOSHENKO_DEGREE: usize = 3;

/// The integrated Legendre polynomial `N_k` (k >= 2) at `x` in [0, 1] (`xi = 2 x - 1`) and its
/// derivative `dN_k / d xi`: `N_k = (P_k - P_{k-2}) / sqrt(2 (2k - 1))`,
/// `dN_k / d xi = sqrt((2k - 1) / 2) P_{k-1}` (Szabo and Babuska 1991, ch. 3, hierarchic shape functions; zero at both
/// ends).
pub fn integrated_legendre(k: usize, x: f64) -> (f64, f64) {
    let t = 2.0 * x - 1.0;
    // P_0 .. P_k by Bonnet's recurrence (n + 1) P_{n+1} = (2n + 1) t P_n - n P_{n-1}.
    let mut p = [1.0, t, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    for n in 1..k {
        let nf = n as f64;
        p[n + 1] = ((2.0 * nf + 1.0) * t * p[n] - nf * p[n - 1]) / (nf + 1.0);
    }
    let c = (2.0 * k as f64 - 1.0).sqrt();
    (
        (p[k] - p[k - 2]) / (std::f64::consts::SQRT_2 * c),
        c / std::f64::consts::SQRT_2 * p[k - 1],
    )
}

/// `(element column, Legendre index k)` of interior functions.
type BubbleColumns = Vec<(usize, usize)>;

/// One element `[s0, s0 + length]` of a rod with a section table.
#[derive(Clone, Copy, Debug)]
pub struct SectionElement<'a> {
    /// Arc length of the element's first node from B, m.
    pub s0: f64,
    /// Element length l, m.
    pub length: f64,
    /// E, Pa.
    pub youngs_modulus: f64,
    /// rho, kg/m^3.
    pub density: f64,
    /// G, Pa, for the shear-deformable element; `None` = Euler-Bernoulli.
    pub shear_modulus: Option<f64>,
    pub table: &'a SectionTable,
    /// `Phi = 12 E I / (G A_s l^2)` with element means (0 for Euler-Bernoulli).
    phi: f64,
    /// Degree of `v` of the hierarchical element (interior coordinates after the six nodal
    /// ones); 0 = the IIE (or Euler-Bernoulli) element alone.
    degree: usize,
}

impl<'a> SectionElement<'a> {
    pub fn new(
        table: &'a SectionTable,
        s0: f64,
        length: f64,
        youngs_modulus: f64,
        density: f64,
        shear_modulus: Option<f64>,
    ) -> SectionElement<'a> {
        let phi = match shear_modulus {
            None => 0.0,
            Some(g) => {
                let Pair(ei, gas) = table.integrate(s0, s0 + length, Pair(0.0, 0.0), |_, v, w| {
                    Pair(youngs_modulus * v.area_moment * w, g * v.shear_area * w)
                });
                12.0 * ei / (gas * length * length)
            }
        };
        SectionElement {
            s0,
            length,
            youngs_modulus,
            density,
            shear_modulus,
            table,
            phi,
            degree: 0,
        }
    }

    /// The hierarchical shear-deformable element of `v` degree `degree` =
    /// [`TIMOSHENKO_DEGREE`] (`psi` of degree `degree - 1`): the IIE's six nodal functions plus
    /// `degree - 1` interior functions of `v` and `degree - 2` of `psi` (module documentation).
    /// `degree` 0 keeps the element as it is; only for the shear-deformable element (an
    /// Euler-Bernoulli element ignores it). Higher degrees would need more quadrature points
    /// than [`SectionTable::quadrature_points`] has (module documentation, "Matrices").
    pub fn with_degree(mut self, degree: usize) -> SectionElement<'a> {
        assert!(
            degree == 0 || degree == TIMOSHENKO_DEGREE,
            "element degree {degree}"
        );
        if self.shear_modulus.is_some() {
            self.degree = degree;
        }
        self
    }

    /// Number of interior (bubble) coordinates, `2 p - 3` for `v` degree `p` (0 for the IIE
    /// and the Euler-Bernoulli element).
    pub fn n_bubbles(&self) -> usize {
        if self.degree == 0 {
            0
        } else {
            2 * self.degree - 3
        }
    }

    /// Number of element coordinates: six nodal, then the interior ones (`v` bubbles of
    /// degree 2..=p, then `psi` bubbles of degree 2..=p-1).
    pub fn width(&self) -> usize {
        6 + self.n_bubbles()
    }

    /// `(column, k)` of the `v` bubbles and of the `psi` bubbles.
    fn bubbles(&self) -> (BubbleColumns, BubbleColumns) {
        if self.degree == 0 {
            return (Vec::new(), Vec::new());
        }
        let nv = self.degree - 1;
        let v = (0..nv).map(|i| (6 + i, 2 + i)).collect();
        let r = (0..self.degree - 2).map(|i| (6 + nv + i, 2 + i)).collect();
        (v, r)
    }

    /// Shape matrix (2 x [`Self::width`]) with the interior functions: rows `u`, `v`.
    pub fn shape_full(&self, xi: f64) -> DMatrix<f64> {
        let mut s = DMatrix::zeros(2, self.width());
        s.view_mut((0, 0), (2, 6)).copy_from(&self.shape(xi));
        for (col, k) in self.bubbles().0 {
            s[(1, col)] = integrated_legendre(k, xi).0;
        }
        s
    }

    /// Slope row `v'` (1 x [`Self::width`]).
    pub fn slope_full(&self, xi: f64) -> DMatrix<f64> {
        let mut d = DMatrix::zeros(1, self.width());
        d.view_mut((0, 0), (1, 6)).copy_from(&self.slope(xi));
        for (col, k) in self.bubbles().0 {
            d[(0, col)] = 2.0 / self.length * integrated_legendre(k, xi).1;
        }
        d
    }

    /// Rotation row `psi` (1 x [`Self::width`]).
    pub fn rotation_full(&self, xi: f64) -> DMatrix<f64> {
        let mut r = DMatrix::zeros(1, self.width());
        r.view_mut((0, 0), (1, 6)).copy_from(&self.rotation(xi));
        for (col, k) in self.bubbles().1 {
            r[(0, col)] = integrated_legendre(k, xi).0;
        }
        r
    }

    /// Curvature row `psi'` (1 x [`Self::width`]), per metre.
    pub fn curvature_full(&self, xi: f64) -> DMatrix<f64> {
        let mut c = DMatrix::zeros(1, self.width());
        c.view_mut((0, 0), (1, 6)).copy_from(&self.curvature(xi));
        for (col, k) in self.bubbles().1 {
            c[(0, col)] = 2.0 / self.length * integrated_legendre(k, xi).1;
        }
        c
    }

    /// Shear strain row `gamma = v' - psi` (1 x [`Self::width`]): the IIE's constant row plus
    /// the bubbles' `N_k'` on `v` and `-N_k` on `psi`.
    pub fn shear_strain_full(&self, xi: f64) -> DMatrix<f64> {
        let mut g = DMatrix::zeros(1, self.width());
        g.view_mut((0, 0), (1, 6)).copy_from(&self.shear_strain());
        let (vb, rb) = self.bubbles();
        for (col, k) in vb {
            g[(0, col)] = 2.0 / self.length * integrated_legendre(k, xi).1;
        }
        for (col, k) in rb {
            g[(0, col)] = -integrated_legendre(k, xi).0;
        }
        g
    }

    /// Stiffness with the interior coordinates ([`Self::width`] square); the same integral as
    /// [`Self::stiffness`], which it equals without interior coordinates.
    pub fn stiffness_full(&self) -> DMatrix<f64> {
        if self.degree == 0 {
            return DMatrix::from_column_slice(6, 6, self.stiffness().as_slice());
        }
        let e = self.youngs_modulus;
        let g = self.shear_modulus.unwrap_or(0.0);
        let mut ua = DMatrix::zeros(1, self.width());
        ua.view_mut((0, 0), (1, 6)).copy_from(&self.axial_strain());
        let uu = ua.transpose() * &ua;
        self.integrate_full(|xi, v| {
            let k = self.curvature_full(xi);
            let gam = self.shear_strain_full(xi);
            &uu * (e * v.area)
                + k.transpose() * &k * (e * v.area_moment)
                + gam.transpose() * &gam * (g * v.shear_area)
        })
    }

    /// Consistent mass with the interior coordinates, `int (rho A S^T S + rho I psi^T psi) dx`
    /// ([`Self::width`] square; [`Self::mass`] without interior coordinates).
    pub fn mass_full(&self) -> DMatrix<f64> {
        if self.degree == 0 {
            return DMatrix::from_column_slice(6, 6, self.mass().as_slice());
        }
        let rho = self.density;
        self.integrate_full(|xi, v| {
            let s = self.shape_full(xi);
            let r = self.rotation_full(xi);
            s.transpose() * &s * (rho * v.area) + r.transpose() * &r * (rho * v.area_moment)
        })
    }

    /// `int f dx` over the element for the matrices with interior coordinates: 4-point Gauss
    /// per piece of the section table, exact up to degree 7 (for `p = 3`: `rho A v^2` is
    /// 3 + 3 + 1; every other integrand is lower).
    fn integrate_full<F>(&self, mut f: F) -> DMatrix<f64>
    where
        F: FnMut(f64, SectionValues) -> DMatrix<f64>,
    {
        let (s0, l) = (self.s0, self.length);
        let w = self.width();
        let mut acc = DMatrix::zeros(w, w);
        for (s, v, wt) in self.table.quadrature_points(s0, s0 + l) {
            acc += f((s - s0) / l, v) * wt;
        }
        acc
    }

    /// `Phi = 12 E I / (G A_s l^2)` of the element (0 for Euler-Bernoulli).
    pub fn shear_parameter(&self) -> f64 {
        self.phi
    }

    /// Shape matrix at `xi` in [0, 1]: rows axial `u` and transverse `v`.
    pub fn shape(&self, xi: f64) -> ShapeMatrix {
        let (l, p) = (self.length, self.phi);
        let mu = 1.0 / (1.0 + p);
        let (x2, x3) = (xi * xi, xi * xi * xi);
        let mut s = ShapeMatrix::zeros();
        s[(0, 0)] = 1.0 - xi;
        s[(0, 3)] = xi;
        s[(1, 1)] = mu * (2.0 * x3 - 3.0 * x2 - p * xi + 1.0 + p);
        s[(1, 2)] = mu * l * (x3 - (2.0 + 0.5 * p) * x2 + (1.0 + 0.5 * p) * xi);
        s[(1, 4)] = -mu * (2.0 * x3 - 3.0 * x2 - p * xi);
        s[(1, 5)] = mu * l * (x3 - (1.0 - 0.5 * p) * x2 - 0.5 * p * xi);
        s
    }

    /// Slope `dv/dx` at `xi` (per metre).
    pub fn slope(&self, xi: f64) -> SlopeRow {
        let (l, p) = (self.length, self.phi);
        let mu = 1.0 / (1.0 + p);
        let x2 = xi * xi;
        let mut d = SlopeRow::zeros();
        d[(0, 1)] = mu * (6.0 * x2 - 6.0 * xi - p) / l;
        d[(0, 2)] = mu * (3.0 * x2 - (4.0 + p) * xi + 1.0 + 0.5 * p);
        d[(0, 4)] = -mu * (6.0 * x2 - 6.0 * xi - p) / l;
        d[(0, 5)] = mu * (3.0 * x2 - (2.0 - p) * xi - 0.5 * p);
        d
    }

    /// Section rotation `psi` at `xi` (the slope for Euler-Bernoulli).
    pub fn rotation(&self, xi: f64) -> SlopeRow {
        let (l, p) = (self.length, self.phi);
        let mu = 1.0 / (1.0 + p);
        let x2 = xi * xi;
        let mut r = SlopeRow::zeros();
        r[(0, 1)] = 6.0 * mu / l * (x2 - xi);
        r[(0, 2)] = mu * (3.0 * x2 - (4.0 + p) * xi + 1.0 + p);
        r[(0, 4)] = -6.0 * mu / l * (x2 - xi);
        r[(0, 5)] = mu * (3.0 * x2 - (2.0 - p) * xi);
        r
    }

    /// Curvature `psi'` at `xi` (per metre; `v''` for Euler-Bernoulli).
    pub fn curvature(&self, xi: f64) -> SlopeRow {
        let (l, p) = (self.length, self.phi);
        let mu = 1.0 / (1.0 + p);
        let mut c = SlopeRow::zeros();
        c[(0, 1)] = 6.0 * mu / (l * l) * (2.0 * xi - 1.0);
        c[(0, 2)] = mu * (6.0 * xi - 4.0 - p) / l;
        c[(0, 4)] = -6.0 * mu / (l * l) * (2.0 * xi - 1.0);
        c[(0, 5)] = mu * (6.0 * xi - 2.0 + p) / l;
        c
    }

    /// Shear strain `gamma = v' - psi` (constant over the element; zero for Euler-Bernoulli).
    pub fn shear_strain(&self) -> SlopeRow {
        let (l, p) = (self.length, self.phi);
        let g = p / (1.0 + p) / l;
        let mut r = SlopeRow::zeros();
        r[(0, 1)] = -g;
        r[(0, 2)] = -0.5 * g * l;
        r[(0, 4)] = g;
        r[(0, 5)] = -0.5 * g * l;
        r
    }

    /// Axial strain row `u'`.
    fn axial_strain(&self) -> SlopeRow {
        let mut r = SlopeRow::zeros();
        r[(0, 0)] = -1.0 / self.length;
        r[(0, 3)] = 1.0 / self.length;
        r
    }

    /// Section properties at `xi` (inside a piece; for output, not for integrals).
    pub fn section_at(&self, xi: f64) -> SectionValues {
        self.table.at(self.s0 + xi * self.length)
    }

    /// `int f(xi, section, dx)` over the element, exact for piecewise polynomials of degree <= 7.
    fn integrate<F>(&self, mut f: F) -> ElementMatrix
    where
        F: FnMut(f64, SectionValues) -> ElementMatrix,
    {
        let (s0, l) = (self.s0, self.length);
        self.table
            .integrate(s0, s0 + l, ElementMatrix::zeros(), |s, v, w| {
                f((s - s0) / l, v) * w
            })
    }

    /// Stiffness `int (E A u'^T u' + E I psi'^T psi' + G A_s gamma^T gamma) dx`.
    pub fn stiffness(&self) -> ElementMatrix {
        let e = self.youngs_modulus;
        let ua = self.axial_strain();
        let gam = self.shear_strain();
        let g = self.shear_modulus.unwrap_or(0.0);
        let uu = ua.transpose() * ua;
        let gg = gam.transpose() * gam;
        self.integrate(|xi, v| {
            let k = self.curvature(xi);
            let mut m = uu * (e * v.area) + k.transpose() * k * (e * v.area_moment);
            if self.shear_modulus.is_some() {
                m += gg * (g * v.shear_area);
            }
            m
        })
    }

    /// Consistent mass `int (rho A S^T S + rho I psi^T psi) dx` (rotary inertia for Timoshenko
    /// only).
    pub fn mass(&self) -> ElementMatrix {
        let rho = self.density;
        self.integrate(|xi, v| {
            let s = self.shape(xi);
            let mut m = s.transpose() * s * (rho * v.area);
            if self.shear_modulus.is_some() {
                let r = self.rotation(xi);
                m += r.transpose() * r * (rho * v.area_moment);
            }
            m
        })
    }

    /// The rotary inertia part `int rho I psi^T psi dx` of [`Self::mass`] (zero for
    /// Euler-Bernoulli).
    pub fn rotary_mass(&self) -> ElementMatrix {
        if self.shear_modulus.is_none() {
            return ElementMatrix::zeros();
        }
        let rho = self.density;
        self.integrate(|xi, v| {
            let r = self.rotation(xi);
            r.transpose() * r * (rho * v.area_moment)
        })
    }
}

/// Two accumulated scalars (for [`SectionTable::integrate`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct Pair(pub f64, pub f64);

impl Pair {
    /// The two values.
    pub fn into_tuple(self) -> (f64, f64) {
        (self.0, self.1)
    }
}

impl std::ops::AddAssign for Pair {
    fn add_assign(&mut self, o: Pair) {
        self.0 += o.0;
        self.1 += o.1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beam::element::BeamElement;
    use crate::beam::{MassKind, RodProperties};

    fn uniform() -> (RodProperties, SectionTable) {
        let p = RodProperties::cdi_benchmark();
        (p, SectionTable::uniform(p.length, p.area, p.area_moment))
    }

    /// Uniform Euler-Bernoulli: the quadrature gives Przemieniecki's closed forms.
    #[test]
    fn uniform_euler_bernoulli_matches_closed_forms() {
        let (p, t) = uniform();
        let l = 0.1;
        let el = SectionElement::new(&t, 0.05, l, p.youngs_modulus, p.density, None);
        let closed = BeamElement {
            length: l,
            section: p,
        };
        let dk = (el.stiffness() - closed.stiffness()).abs().max() / closed.stiffness().abs().max();
        let dm = (el.mass() - closed.mass(MassKind::Consistent)).abs().max()
            / closed.mass(MassKind::Consistent).abs().max();
        assert!(dk < 1e-13 && dm < 1e-13, "{dk} {dm}");
        for xi in [0.0, 0.3, 1.0] {
            assert!((el.shape(xi) - closed.shape(xi)).abs().max() < 1e-15);
            assert!((el.slope(xi) - closed.slope(xi)).abs().max() < 1e-13);
        }
    }

    /// Uniform Timoshenko: the IIE stiffness in closed form (Przemieniecki eq. 5.115), and the
    /// slope and rotation interpolations differ by the constant shear strain.
    #[test]
    fn uniform_timoshenko_matches_closed_form_stiffness() {
        let (p, t) = uniform();
        let l = 0.05;
        let g = p.youngs_modulus / 2.6;
        let el = SectionElement::new(&t, 0.0, l, p.youngs_modulus, p.density, Some(g));
        let phi = 12.0 * p.bending_rigidity() / (g * p.area / 1.2 * l * l);
        assert!((el.shear_parameter() - phi).abs() < 1e-12 * phi);
        let c = p.bending_rigidity() / ((1.0 + phi) * l * l * l);
        let b = [
            [12.0, 6.0 * l, -12.0, 6.0 * l],
            [6.0 * l, (4.0 + phi) * l * l, -6.0 * l, (2.0 - phi) * l * l],
            [-12.0, -6.0 * l, 12.0, -6.0 * l],
            [6.0 * l, (2.0 - phi) * l * l, -6.0 * l, (4.0 + phi) * l * l],
        ];
        let k = el.stiffness();
        let idx = [1, 2, 4, 5];
        for (i, &r) in idx.iter().enumerate() {
            for (j, &cc) in idx.iter().enumerate() {
                let d = (k[(r, cc)] - c * b[i][j]).abs();
                assert!(
                    d < 1e-10 * c * l * l * 12.0,
                    "({r},{cc}) {} vs {}",
                    k[(r, cc)],
                    c * b[i][j]
                );
            }
        }
        for xi in [0.1, 0.6] {
            let gam = el.slope(xi) - el.rotation(xi);
            assert!((gam - el.shear_strain()).abs().max() < 1e-12);
        }
        // Rigid motions carry no strain.
        let r = BeamElement {
            length: l,
            section: p,
        }
        .rigid_modes(0.2);
        assert!((k * r).abs().max() < 1e-6 * k.abs().max());
    }

    /// G -> infinity: the Timoshenko element becomes the Euler-Bernoulli element (stiffness,
    /// shape functions; the mass differs by exactly the rotary inertia it adds).
    #[test]
    fn timoshenko_reduces_to_euler_bernoulli() {
        let (p, t) = uniform();
        let l = 0.07;
        let eb = SectionElement::new(&t, 0.0, l, p.youngs_modulus, p.density, None);
        let mut last = f64::INFINITY;
        for g in [1e12, 1e15, 1e18] {
            let ti = SectionElement::new(&t, 0.0, l, p.youngs_modulus, p.density, Some(g));
            let dk = (ti.stiffness() - eb.stiffness()).abs().max() / eb.stiffness().abs().max();
            let dm = (ti.mass() - ti.rotary_mass() - eb.mass()).abs().max() / eb.mass().abs().max();
            assert!(dk < last && dm < 1e-3, "G {g}: {dk} {dm}");
            last = dk;
        }
        assert!(last < 1e-8, "{last}");
    }

    /// The hierarchical element: interior functions vanish at both nodes; the nodal 6 x 6
    /// blocks are the IIE's; rows are derivatives of each other; rigid motions (nodal, zero
    /// interior coordinates) carry no strain; for a uniform section the IIE's nodal functions
    /// (exact homogeneous solutions) are stiffness-orthogonal to the interior ones.
    #[test]
    fn hierarchical_element_extends_the_iie() {
        let (p, t) = uniform();
        let l = 0.05;
        let g = p.youngs_modulus / 2.6;
        let iie = SectionElement::new(&t, 0.0, l, p.youngs_modulus, p.density, Some(g));
        let el = iie.with_degree(TIMOSHENKO_DEGREE);
        assert_eq!((el.n_bubbles(), el.width()), (3, 9));
        for xi in [0.0, 1.0] {
            assert!(el.shape_full(xi).columns(6, 3).abs().max() < 1e-15);
            assert!(el.rotation_full(xi).columns(6, 3).abs().max() < 1e-15);
        }
        let (k, m) = (el.stiffness_full(), el.mass_full());
        let kk = k.view((0, 0), (6, 6)) - iie.stiffness();
        let mm = m.view((0, 0), (6, 6)) - iie.mass();
        assert!(kk.abs().max() < 1e-12 * k.abs().max(), "{kk}");
        assert!(mm.abs().max() < 1e-12 * m.abs().max(), "{mm}");
        assert!((&k - k.transpose()).abs().max() == 0.0);
        let coupling = k.view((0, 6), (6, 3)).abs().max() / k.abs().max();
        assert!(coupling < 1e-12, "{coupling}");
        // Interior block regular (the interior functions are independent).
        assert!(k.view((6, 6), (3, 3)).into_owned().determinant() > 0.0);
        let h = 1e-6;
        for xi in [0.2, 0.55, 0.9] {
            let fd = |f: &dyn Fn(f64) -> DMatrix<f64>, row: usize| {
                (f(xi + h).row(row) - f(xi - h).row(row)) / (2.0 * h * l)
            };
            let dv = fd(&|x| el.shape_full(x), 1) - el.slope_full(xi);
            let dpsi = fd(&|x| el.rotation_full(x), 0) - el.curvature_full(xi);
            assert!(dv.abs().max() < 1e-6, "{dv}");
            assert!(dpsi.abs().max() < 1e-4 / l, "{dpsi}");
            let gam = el.slope_full(xi) - el.rotation_full(xi) - el.shear_strain_full(xi);
            assert!(gam.abs().max() < 1e-12, "{gam}");
        }
        let r = BeamElement {
            length: l,
            section: p,
        }
        .rigid_modes(0.2);
        let mut rf = DMatrix::zeros(9, 3);
        rf.view_mut((0, 0), (6, 3)).copy_from(&r);
        assert!((&k * rf).abs().max() < 1e-6 * k.abs().max());
    }

    /// The element's space is v in P3, psi in P2: any such pair (here v = x^3, psi = x^2 on
    /// the element, plus rigid terms) is represented exactly by nodal values and interior
    /// coordinates, the latter found by least squares on sample points.
    #[test]
    fn hierarchical_element_spans_p3_p2() {
        let (p, t) = uniform();
        let l = 0.04;
        let el =
            SectionElement::new(&t, 0.0, l, p.youngs_modulus, p.density, Some(8e10)).with_degree(3);
        let v = |x: f64| 0.3 * x * x * x - 0.1 * x + 0.002;
        let psi = |x: f64| 5.0 * x * x + 0.7 * x - 0.01;
        // Nodal coordinates from the fields; interior ones by least squares.
        let xs: Vec<f64> = (0..12).map(|k| k as f64 / 11.0).collect();
        let nodal = nalgebra::DVector::from_vec(vec![0.0, v(0.0), psi(0.0), 0.0, v(l), psi(l)]);
        let mut a = DMatrix::zeros(2 * xs.len(), 3);
        let mut b = nalgebra::DVector::zeros(2 * xs.len());
        for (i, &xi) in xs.iter().enumerate() {
            let (s, r) = (el.shape_full(xi), el.rotation_full(xi));
            let sn = s.columns(0, 6) * &nodal;
            let rn = r.columns(0, 6) * &nodal;
            b[2 * i] = v(xi * l) - sn[1];
            b[2 * i + 1] = psi(xi * l) - rn[0];
            a.row_mut(2 * i).copy_from(&s.view((1, 6), (1, 3)));
            a.row_mut(2 * i + 1).copy_from(&r.columns(6, 3));
        }
        let c = a.clone().svd(true, true).solve(&b, 1e-14).unwrap();
        let residual = (&a * c - b).abs().max();
        assert!(residual < 1e-13, "{residual}");
    }

    /// A linearly tapered element: the mass is the integral of rho A(s) (exact).
    #[test]
    fn tapered_element_mass_is_exact() {
        use crate::beam::section_table::SectionStation;
        let st = |position: f64, area: f64| SectionStation {
            position,
            area,
            area_moment: 1e-10,
            shear_area: None,
            fibre_distance: None,
        };
        let t = SectionTable::new(1.0, &[st(0.0, 1e-4), st(0.3, 2e-4), st(1.0, 1e-4)]).unwrap();
        let el = SectionElement::new(&t, 0.1, 0.5, 2e11, 7800.0, None);
        let m = el.mass();
        // Translation in x: u1 = u2 = 1.
        let total = m[(0, 0)] + m[(0, 3)] + m[(3, 0)] + m[(3, 3)];
        let (a0, _) = t.tail_integrals(0.1);
        let (a1, _) = t.tail_integrals(0.6);
        let exact = 7800.0 * (a0 - a1);
        assert!((total - exact).abs() < 1e-13 * exact, "{total} vs {exact}");
    }
}
