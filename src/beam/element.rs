//! The planar Euler-Bernoulli beam element.
//!
//! Coordinates, in the element's own axis (which is parallel to the body frame's x axis):
//! `e = [u1, v1, theta1, u2, v2, theta2]` (axial, transverse, slope at each node).
//! Shape functions, with `xi = x / l` in [0, 1] (Shabana, *Dynamics of Multibody Systems*,
//! eq. 6.13 restricted to the plane; Agrawal and Shabana 1985, eq. 5.1-5.2):
//! `u = (1 - xi) u1 + xi u2`,
//! `v = (1 - 3 xi^2 + 2 xi^3) v1 + l (xi - 2 xi^2 + xi^3) theta1 + (3 xi^2 - 2 xi^3) v2 + l (xi^3 - xi^2) theta2`.
//! Linear axial, cubic (Hermite) transverse.

use nalgebra::{SMatrix, SVector};

use super::section::RodProperties;
use serde::{Deserialize, Serialize};

/// Mass matrix of the beam element.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum MassKind {
    #[default]
    Consistent,
    Lumped,
}

impl MassKind {
    /// Every variant, in the order of the FMU's enumeration items and Integer codes (1-based).
    pub const ALL: [MassKind; 2] = [MassKind::Consistent, MassKind::Lumped];

    /// The name used in scenes, the FMU's enumeration items and messages.
    pub fn name(self) -> &'static str {
        match self {
            MassKind::Consistent => "consistent",
            MassKind::Lumped => "lumped",
        }
    }

    /// The variant of a name (see [`Self::name`]).
    pub fn from_name(name: &str) -> Option<MassKind> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }
}

/// 6 x 6 element matrix.
pub type ElementMatrix = SMatrix<f64, 6, 6>;
/// 2 x 6 shape matrix `S(xi)`: rows are axial and transverse displacement.
pub type ShapeMatrix = SMatrix<f64, 2, 6>;
/// 1 x 6 row of the slope dv/dx.
pub type SlopeRow = SMatrix<f64, 1, 6>;

/// One element of length `length` with the rod's section properties.
#[derive(Clone, Copy, Debug)]
pub struct BeamElement {
    pub length: f64,
    pub section: RodProperties,
}

impl BeamElement {
    /// Shape matrix at `xi` in [0, 1]; displacement in the element axis = `S(xi) e`.
    pub fn shape(&self, xi: f64) -> ShapeMatrix {
        let l = self.length;
        let (x2, x3) = (xi * xi, xi * xi * xi);
        let mut s = ShapeMatrix::zeros();
        s[(0, 0)] = 1.0 - xi;
        s[(0, 3)] = xi;
        s[(1, 1)] = 1.0 - 3.0 * x2 + 2.0 * x3;
        s[(1, 2)] = l * (xi - 2.0 * x2 + x3);
        s[(1, 4)] = 3.0 * x2 - 2.0 * x3;
        s[(1, 5)] = l * (x3 - x2);
        s
    }

    /// Slope dv/dx at `xi` (per metre of x).
    pub fn slope(&self, xi: f64) -> SlopeRow {
        let l = self.length;
        let x2 = xi * xi;
        let mut d = SlopeRow::zeros();
        d[(0, 1)] = (-6.0 * xi + 6.0 * x2) / l;
        d[(0, 2)] = 1.0 - 4.0 * xi + 3.0 * x2;
        d[(0, 4)] = (6.0 * xi - 6.0 * x2) / l;
        d[(0, 5)] = 3.0 * x2 - 2.0 * xi;
        d
    }

    /// Stiffness matrix: axial `EA/l [1 -1; -1 1]`, bending `EI/l^3 [12 6l -12 6l; ...]`
    /// (Przemieniecki, *Theory of Matrix Structural Analysis*, 1968, eq. 5.25 and 5.31).
    pub fn stiffness(&self) -> ElementMatrix {
        let l = self.length;
        let ea = self.section.axial_rigidity() / l;
        let ei = self.section.bending_rigidity() / (l * l * l);
        let mut k = ElementMatrix::zeros();
        k[(0, 0)] = ea;
        k[(0, 3)] = -ea;
        k[(3, 0)] = -ea;
        k[(3, 3)] = ea;
        let b = [
            [12.0, 6.0 * l, -12.0, 6.0 * l],
            [6.0 * l, 4.0 * l * l, -6.0 * l, 2.0 * l * l],
            [-12.0, -6.0 * l, 12.0, -6.0 * l],
            [6.0 * l, 2.0 * l * l, -6.0 * l, 4.0 * l * l],
        ];
        let idx = [1, 2, 4, 5];
        for (i, &ri) in idx.iter().enumerate() {
            for (j, &cj) in idx.iter().enumerate() {
                k[(ri, cj)] = ei * b[i][j];
            }
        }
        k
    }

    /// Mass matrix, consistent (`rho A l / 420 [156 22l 54 -13l; ...]` for bending,
    /// `rho A l / 6 [2 1; 1 2]` axial; Przemieniecki eq. 11.19) or lumped
    /// (half the mass at each node, rotary inertia `m l^2 / 78` by HRZ diagonal scaling,
    /// Hinton, Rock and Zienkiewicz 1976; the CDI benchmark note uses a lumped scheme).
    pub fn mass(&self, kind: MassKind) -> ElementMatrix {
        let l = self.length;
        let m = self.section.mass_per_length() * l;
        let mut mm = ElementMatrix::zeros();
        match kind {
            MassKind::Consistent => {
                mm[(0, 0)] = 2.0 * m / 6.0;
                mm[(0, 3)] = m / 6.0;
                mm[(3, 0)] = m / 6.0;
                mm[(3, 3)] = 2.0 * m / 6.0;
                let b = [
                    [156.0, 22.0 * l, 54.0, -13.0 * l],
                    [22.0 * l, 4.0 * l * l, 13.0 * l, -3.0 * l * l],
                    [54.0, 13.0 * l, 156.0, -22.0 * l],
                    [-13.0 * l, -3.0 * l * l, -22.0 * l, 4.0 * l * l],
                ];
                let idx = [1, 2, 4, 5];
                for (i, &ri) in idx.iter().enumerate() {
                    for (j, &cj) in idx.iter().enumerate() {
                        mm[(ri, cj)] = m / 420.0 * b[i][j];
                    }
                }
            }
            MassKind::Lumped => {
                for i in [0, 1, 3, 4] {
                    mm[(i, i)] = m / 2.0;
                }
                mm[(2, 2)] = m * l * l / 78.0;
                mm[(5, 5)] = m * l * l / 78.0;
            }
        }
        mm
    }

    /// Nodal coordinates of a rigid motion of the element whose left node sits at `x_left` in
    /// the body frame: columns are x translation, y translation, rotation about the frame origin.
    pub fn rigid_modes(&self, x_left: f64) -> SMatrix<f64, 6, 3> {
        let mut r = SMatrix::<f64, 6, 3>::zeros();
        for (node, x) in [(0usize, x_left), (1, x_left + self.length)] {
            r[(3 * node, 0)] = 1.0;
            r[(3 * node + 1, 1)] = 1.0;
            r[(3 * node + 1, 2)] = x;
            r[(3 * node + 2, 2)] = 1.0;
        }
        r
    }
}

/// The element displacement vector as a nalgebra vector, for tests.
pub type ElementVector = SVector<f64, 6>;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beam::quadrature::GAUSS4;

    fn element() -> BeamElement {
        BeamElement {
            length: 0.1524,
            section: RodProperties::cdi_benchmark(),
        }
    }

    /// The consistent mass matrix is the quadrature of rho A S^T S.
    #[test]
    fn consistent_mass_is_integral_of_shape_products() {
        let e = element();
        let mut m = ElementMatrix::zeros();
        for (xi, w) in GAUSS4 {
            let s = e.shape(xi);
            m += s.transpose() * s * (w * e.length * e.section.mass_per_length());
        }
        let diff = (m - e.mass(MassKind::Consistent)).abs().max();
        assert!(diff < 1e-14, "{diff}");
    }

    /// The bending stiffness is the quadrature of EI v''^T v''; rigid modes carry no strain.
    #[test]
    fn stiffness_annihilates_rigid_modes() {
        let e = element();
        let k = e.stiffness();
        let r = e.rigid_modes(0.3);
        let kr = (k * r).abs().max();
        assert!(kr < 1e-6 * k.abs().max(), "{kr}");
    }

    #[test]
    fn lumped_mass_keeps_total_mass() {
        let e = element();
        let m = e.mass(MassKind::Lumped);
        let total = m[(0, 0)] + m[(3, 3)];
        assert!((total - e.section.mass_per_length() * e.length).abs() < 1e-15);
    }

    #[test]
    fn slope_is_derivative_of_shape() {
        let e = element();
        let h = 1e-6;
        for xi in [0.1, 0.5, 0.77] {
            let fd = (e.shape(xi + h) - e.shape(xi - h)) / (2.0 * h * e.length);
            let d = e.slope(xi);
            for j in 0..6 {
                assert!((fd[(1, j)] - d[(0, j)]).abs() < 1e-6);
            }
        }
    }
}
