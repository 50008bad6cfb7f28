//! A straight rod of `N` equal elements along the body frame's x axis.
//!
//! Node `i` (0 = the B end, N = the C end) sits at `x = x_b + i L / N` in the body frame,
//! `x_b` being the B end's position (0 when the frame sits at B, `-L/2` when it sits at the
//! middle). Global coordinates: node `i` owns `[3i, 3i+1, 3i+2] = [u, v, slope]` (for the
//! shear-deformable rod the third is the section rotation `psi`). A shear-deformable rod's
//! element has interior coordinates too ([`RodMesh::n_bubbles`] per element, the hierarchical
//! element of [`SectionElement`]); they follow all nodal coordinates, element by element, so
//! node indexing, reference conditions, end bodies and rigid modes stay nodal.
//!
//! The uniform Euler-Bernoulli rod without end bodies ([`RodDefinition::is_plain`]) uses the
//! closed-form [`BeamElement`]; every other rod the [`SectionElement`] on the rod's section
//! table, with the end bodies' masses added on `u`, `v` and their inertias on the rotation of
//! the end nodes (lumped, rigidly attached at B and C).

use faer::Mat;
use nalgebra::DMatrix;

use super::definition::RodDefinition;
use super::element::{BeamElement, ElementMatrix};
use super::section::RodProperties;
use super::section_element::{SectionElement, TIMOSHENKO_DEGREE};
use super::section_table::SectionTable;
use crate::beam::MassKind;
use crate::error::ModelError;

/// Largest number of elements a mesh takes (`rod.elements`; the FMU declares it as the
/// parameter's `max`). Every count up to it gives the first three bending frequencies of the
/// uniform rod within the discretization error of the Euler-Bernoulli closed forms under every
/// reference condition (tests/every_element_count.rs). The bound is the cost of the dense
/// preprocessing, `O(N^3)`: measured on the benchmark rod on a shared host, one eigenproblem
/// takes about 0.3 s at 160 elements and 2 to 5 s at 384, where the round-off of the lowest
/// eigenvalue (about `eps` times the spread `N^4` of the spectrum) reaches 2e-5 for the
/// cantilever; tests/abuse.rs builds and runs the limit.
pub const MAX_ELEMENTS: usize = 128;

/// The least number of Euler-Bernoulli elements that leaves at least `frequencies` natural
/// frequencies: every reference condition leaves `3 N` of the `3 (N + 1)` nodal coordinates
/// (interior coordinates of the shear-deformable element add more; `body_fixed_mid` also needs
/// an even `N`, and refuses an odd one with a message). For the six frequencies of the default
/// scene: 2.
pub fn least_elements(frequencies: usize) -> usize {
    frequencies.div_ceil(3).max(1)
}

/// The rod's mesh.
#[derive(Clone, Debug)]
pub struct RodMesh {
    pub section: RodProperties,
    pub n_elements: usize,
    /// Position of the B end on the body frame's x axis, m.
    pub x_b: f64,
    /// The whole rod: section table, shear, end bodies.
    pub definition: RodDefinition,
    /// The section table of a rod that is not plain (the [`SectionElement`] path).
    table: Option<SectionTable>,
}

impl RodMesh {
    /// A mesh of `n_elements >= 1`; the section must be valid.
    pub fn new(section: RodProperties, n_elements: usize, x_b: f64) -> Result<RodMesh, ModelError> {
        Self::from_definition(RodDefinition::uniform(section), n_elements, x_b)
    }

    /// A mesh of `n_elements >= 1` of any rod; the definition must be valid.
    pub fn from_definition(
        definition: RodDefinition,
        n_elements: usize,
        x_b: f64,
    ) -> Result<RodMesh, ModelError> {
        definition.validate()?;
        let section = definition.properties;
        if n_elements == 0 || n_elements > MAX_ELEMENTS {
            return Err(ModelError::InvalidInteger {
                name: "rod.elements",
                value: n_elements as i64,
                allowed: format!(
                    "an integer in 1..={MAX_ELEMENTS} beam elements (rod.model = \"ffr\"; the preprocessing is dense, its cost grows as the cube of the count)"
                ),
            });
        }
        let table = (!definition.is_plain()).then(|| definition.section_table());
        Ok(RodMesh {
            section,
            n_elements,
            x_b,
            definition,
            table,
        })
    }

    pub fn n_nodes(&self) -> usize {
        self.n_elements + 1
    }

    /// Interior (bubble) coordinates per element: those of the hierarchical shear-deformable
    /// element ([`TIMOSHENKO_DEGREE`]), 0 for Euler-Bernoulli rods.
    pub fn n_bubbles(&self) -> usize {
        match self.element_degree() {
            0 => 0,
            p => 2 * p - 3,
        }
    }

    /// Degree of `v` of the hierarchical shear-deformable element ([`TIMOSHENKO_DEGREE`]), 0
    /// for Euler-Bernoulli rods (no interior coordinates).
    pub fn element_degree(&self) -> usize {
        if self.table.is_some() && self.definition.shear_modulus.is_some() {
            TIMOSHENKO_DEGREE
        } else {
            0
        }
    }

    /// Number of nodal coordinates, 3 (N + 1).
    pub fn n_nodal_coordinates(&self) -> usize {
        3 * self.n_nodes()
    }

    /// Number of coordinates: the nodal ones, 3 (N + 1), then the interior ones of every
    /// element, `n_b N` ([`Self::n_bubbles`]).
    pub fn n_coordinates(&self) -> usize {
        self.n_nodal_coordinates() + self.n_bubbles() * self.n_elements
    }

    /// Whether global coordinate `i` is an axial displacement `u` (node `i / 3`'s first).
    pub fn is_axial_coordinate(&self, i: usize) -> bool {
        i < self.n_nodal_coordinates() && i.is_multiple_of(3)
    }

    pub fn element_length(&self) -> f64 {
        self.section.length / self.n_elements as f64
    }

    pub fn element(&self) -> BeamElement {
        BeamElement {
            length: self.element_length(),
            section: self.section,
        }
    }

    /// Whether the rod uses the closed-form uniform Euler-Bernoulli element.
    pub fn is_plain(&self) -> bool {
        self.table.is_none()
    }

    /// Element `e` on the section table (`None` for a plain rod: use [`Self::element`]).
    pub fn section_element(&self, e: usize) -> Option<SectionElement<'_>> {
        let table = self.table.as_ref()?;
        let l = self.element_length();
        let el = SectionElement::new(
            table,
            e as f64 * l,
            l,
            self.section.youngs_modulus,
            self.section.density,
            self.definition.shear_modulus,
        );
        Some(el.with_degree(self.element_degree()))
    }

    /// The section table of a rod that is not plain.
    pub fn section_table(&self) -> Option<&SectionTable> {
        self.table.as_ref()
    }

    /// Shape matrix of element `e` at `xi` (2 x the element's coordinates,
    /// [`Self::element_dofs`]): rows `u`, `v`.
    pub fn shape(&self, e: usize, xi: f64) -> DMatrix<f64> {
        match self.section_element(e) {
            Some(el) => el.shape_full(xi),
            None => fixed(&self.element().shape(xi)),
        }
    }

    /// Slope `dv/dx` row of element `e` at `xi`.
    pub fn slope(&self, e: usize, xi: f64) -> DMatrix<f64> {
        match self.section_element(e) {
            Some(el) => el.slope_full(xi),
            None => fixed(&self.element().slope(xi)),
        }
    }

    /// Section rotation row of element `e` at `xi` (the slope for Euler-Bernoulli).
    pub fn rotation(&self, e: usize, xi: f64) -> DMatrix<f64> {
        match self.section_element(e) {
            Some(el) => el.rotation_full(xi),
            None => fixed(&self.element().slope(xi)),
        }
    }

    /// Curvature row `psi'` of element `e` at `xi` (`v''` for Euler-Bernoulli), per metre,
    /// with the interior coordinates' part.
    pub fn curvature(&self, e: usize, xi: f64) -> DMatrix<f64> {
        match self.section_element(e) {
            Some(el) => el.curvature_full(xi),
            None => {
                // v'' of the Hermite cubics (the Euler-Bernoulli section element's curvature).
                let l = self.element_length();
                let mut c = DMatrix::zeros(1, 6);
                c[(0, 1)] = (12.0 * xi - 6.0) / (l * l);
                c[(0, 2)] = (6.0 * xi - 4.0) / l;
                c[(0, 4)] = (6.0 - 12.0 * xi) / (l * l);
                c[(0, 5)] = (6.0 * xi - 2.0) / l;
                c
            }
        }
    }

    /// Body-frame x of node `i`.
    pub fn node_x(&self, i: usize) -> f64 {
        self.x_b + i as f64 * self.element_length()
    }

    /// Global coordinate indices of element `e`: its two nodes' `[u, v, psi]`, then its
    /// interior coordinates (which follow all nodal coordinates, element by element).
    pub fn element_dofs(&self, e: usize) -> Vec<usize> {
        let b = 3 * e;
        let nb = self.n_bubbles();
        let first = self.n_nodal_coordinates() + nb * e;
        [b, b + 1, b + 2, b + 3, b + 4, b + 5]
            .into_iter()
            .chain(first..first + nb)
            .collect()
    }

    /// The element and local `xi` holding arc length `s` in [0, L] from the B end.
    pub fn locate(&self, s: f64) -> (usize, f64) {
        let l = self.element_length();
        let e = ((s / l).floor() as isize).clamp(0, self.n_elements as isize - 1) as usize;
        (e, (s - e as f64 * l) / l)
    }

    /// Assembled stiffness and mass matrices (n x n, symmetric).
    pub fn assemble(&self, mass: MassKind) -> (Mat<f64>, Mat<f64>) {
        let n = self.n_coordinates();
        if !self.is_plain() {
            // Section elements (consistent mass) and the end bodies at the end nodes.
            let mut k = Mat::zeros(n, n);
            let mut m = Mat::zeros(n, n);
            for e in 0..self.n_elements {
                let el = self.section_element(e).expect("not plain");
                let dofs = self.element_dofs(e);
                if el.n_bubbles() == 0 {
                    scatter(&mut k, &el.stiffness(), &dofs);
                    scatter(&mut m, &el.mass(), &dofs);
                } else {
                    scatter_dyn(&mut k, &el.stiffness_full(), &dofs);
                    scatter_dyn(&mut m, &el.mass_full(), &dofs);
                }
            }
            let last = 3 * self.n_elements;
            for (base, body) in [
                (0, self.definition.big_end),
                (last, self.definition.small_end),
            ] {
                m[(base, base)] += body.mass;
                m[(base + 1, base + 1)] += body.mass;
                m[(base + 2, base + 2)] += body.inertia;
            }
            return (k, m);
        }
        let el = self.element();
        let (ke, me) = (el.stiffness(), el.mass(mass));
        let mut k = Mat::zeros(n, n);
        let mut m = Mat::zeros(n, n);
        for e in 0..self.n_elements {
            let dofs = self.element_dofs(e);
            scatter(&mut k, &ke, &dofs);
            scatter(&mut m, &me, &dofs);
        }
        (k, m)
    }

    /// The three rigid-body motions in nodal coordinates (n x 3): x translation,
    /// y translation, rotation about the body frame's origin (zero on the interior
    /// coordinates: the nodal functions carry the rigid motions exactly).
    pub fn rigid_modes(&self) -> Mat<f64> {
        let n = self.n_coordinates();
        let nodal = self.n_nodal_coordinates();
        Mat::from_fn(n, 3, |row, col| {
            if row >= nodal {
                return 0.0;
            }
            let (node, kind) = (row / 3, row % 3);
            match (kind, col) {
                (0, 0) | (1, 1) | (2, 2) => 1.0,
                (1, 2) => self.node_x(node),
                _ => 0.0,
            }
        })
    }
}

fn scatter(global: &mut Mat<f64>, local: &ElementMatrix, dofs: &[usize]) {
    for (i, &gi) in dofs.iter().enumerate() {
        for (j, &gj) in dofs.iter().enumerate() {
            global[(gi, gj)] += local[(i, j)];
        }
    }
}

fn scatter_dyn(global: &mut Mat<f64>, local: &DMatrix<f64>, dofs: &[usize]) {
    for (i, &gi) in dofs.iter().enumerate() {
        for (j, &gj) in dofs.iter().enumerate() {
            global[(gi, gj)] += local[(i, j)];
        }
    }
}

/// A fixed-size row block as a dynamic matrix.
fn fixed<const R: usize>(m: &nalgebra::SMatrix<f64, R, 6>) -> DMatrix<f64> {
    DMatrix::from_fn(R, 6, |i, j| m[(i, j)])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn assembled_mass_gives_rod_mass_for_translation() {
        let mesh = RodMesh::new(RodProperties::cdi_benchmark(), 5, 0.0).unwrap();
        for kind in [MassKind::Consistent, MassKind::Lumped] {
            let (_, m) = mesh.assemble(kind);
            let r = mesh.rigid_modes();
            let mt = r.transpose() * &m * &r;
            let mass = mesh.section.mass();
            assert!((mt[(0, 0)] - mass).abs() < 1e-14);
            assert!((mt[(1, 1)] - mass).abs() < 1e-14);
        }
    }

    #[test]
    fn locate_finds_element_and_xi() {
        let mesh = RodMesh::new(RodProperties::cdi_benchmark(), 4, 0.0).unwrap();
        let l = mesh.section.length;
        assert_eq!(mesh.locate(0.0), (0, 0.0));
        let (e, xi) = mesh.locate(l);
        assert_eq!(e, 3);
        assert!((xi - 1.0).abs() < 1e-12);
        let (e, xi) = mesh.locate(0.5 * l);
        assert_eq!(e, 2);
        assert!(xi.abs() < 1e-12);
    }

    #[test]
    fn zero_elements_is_rejected() {
        let err = RodMesh::new(RodProperties::cdi_benchmark(), 0, 0.0).unwrap_err();
        assert!(err.to_string().contains("rod.elements"));
    }
}
