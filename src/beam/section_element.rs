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
//! # Matrices
//! Energies integrated over the element with the properties at each point (exact: the
//! properties are linear on each piece of [`SectionTable::pieces`], the integrands polynomial
//! of degree <= 7, 4-point Gauss per piece):
//! - stiffness `K = int (E A u'^T u' + E I psi'^T psi' + G A_s gamma^T gamma) dx` (the shear term
//!   only for Timoshenko; for Euler-Bernoulli `psi' = v''`);
//! - consistent mass `M = int (rho A S^T S + rho I psi^T psi) dx` (rotary inertia only for
//!   Timoshenko: the Euler-Bernoulli element keeps the convention of [`super::element`]).
//!
//! For a uniform section these give the closed forms (Przemieniecki eq. 5.25, 5.31, 11.19; the
//! IIE stiffness `E I / ((1 + Phi) l^3) [[12, 6l, -12, 6l], [6l, (4 + Phi) l^2, -6l,
//! (2 - Phi) l^2], ...]`, Przemieniecki eq. 5.115); the unit tests check both.

use super::element::{ElementMatrix, ShapeMatrix, SlopeRow};
use super::section_table::{SectionTable, SectionValues};

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
        }
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
        let p = RodProperties::seed001_benchmark();
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
