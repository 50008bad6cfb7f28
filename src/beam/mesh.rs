//! A straight rod of `N` equal elements along the body frame's x axis.
//!
//! Node `i` (0 = the B end, N = the C end) sits at `x = x_b + i L / N` in the body frame,
//! `x_b` being the B end's position (0 when the frame sits at B, `-L/2` when it sits at the
//! middle). Global coordinates: node `i` owns `[3i, 3i+1, 3i+2] = [u, v, slope]` (for the
//! shear-deformable rod the third is the section rotation `psi`).
//!
//! The uniform Euler-Bernoulli rod without end bodies ([`RodDefinition::is_plain`]) uses the
//! closed-form [`BeamElement`]; every other rod the [`SectionElement`] on the rod's section
//! table, with the end bodies' masses added on `u`, `v` and their inertias on the rotation of
//! the end nodes (lumped, rigidly attached at B and C).

use faer::Mat;

use super::definition::RodDefinition;
use super::element::{BeamElement, ElementMatrix, ShapeMatrix, SlopeRow};
use super::section::RodProperties;
use super::section_element::SectionElement;
use super::section_table::SectionTable;
use crate::beam::MassKind;
use crate::error::ModelError;

/// Largest number of elements a mesh takes (`rod.elements`; the FMU declares it as the
/// parameter's `max`). Measured (issue 14, `tests/abuse.rs`): 128 elements build in about
/// 0.05 s and 20 MB and run the benchmark; from about 160 elements the reduced stiffness loses
/// definiteness in double precision (Newton fails, or "reduced stiffness is indefinite" from
/// 172), and 1024 elements took 13 s and 0.9 GB.
pub const MAX_ELEMENTS: usize = 128;

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
            return Err(ModelError::InvalidParameter {
                name: "rod.elements",
                value: n_elements as f64,
                allowed: format!(
                    "an integer in 1..={MAX_ELEMENTS} beam elements (rod.model = \"ffr\"; more lose precision in the reduced stiffness)"
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

    /// Number of nodal coordinates, 3 (N + 1).
    pub fn n_coordinates(&self) -> usize {
        3 * self.n_nodes()
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
        Some(SectionElement::new(
            table,
            e as f64 * l,
            l,
            self.section.youngs_modulus,
            self.section.density,
            self.definition.shear_modulus,
        ))
    }

    /// The section table of a rod that is not plain.
    pub fn section_table(&self) -> Option<&SectionTable> {
        self.table.as_ref()
    }

    /// Shape matrix of element `e` at `xi`.
    pub fn shape(&self, e: usize, xi: f64) -> ShapeMatrix {
        match self.section_element(e) {
            Some(el) => el.shape(xi),
            None => self.element().shape(xi),
        }
    }

    /// Slope `dv/dx` row of element `e` at `xi`.
    pub fn slope(&self, e: usize, xi: f64) -> SlopeRow {
        match self.section_element(e) {
            Some(el) => el.slope(xi),
            None => self.element().slope(xi),
        }
    }

    /// Section rotation row of element `e` at `xi` (the slope for Euler-Bernoulli).
    pub fn rotation(&self, e: usize, xi: f64) -> SlopeRow {
        match self.section_element(e) {
            Some(el) => el.rotation(xi),
            None => self.element().slope(xi),
        }
    }

    /// Body-frame x of node `i`.
    pub fn node_x(&self, i: usize) -> f64 {
        self.x_b + i as f64 * self.element_length()
    }

    /// Global coordinate indices of element `e`.
    pub fn element_dofs(&self, e: usize) -> [usize; 6] {
        let b = 3 * e;
        [b, b + 1, b + 2, b + 3, b + 4, b + 5]
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
                scatter(&mut k, &el.stiffness(), &dofs);
                scatter(&mut m, &el.mass(), &dofs);
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
    /// y translation, rotation about the body frame's origin.
    pub fn rigid_modes(&self) -> Mat<f64> {
        let n = self.n_coordinates();
        Mat::from_fn(n, 3, |row, col| {
            let (node, kind) = (row / 3, row % 3);
            match (kind, col) {
                (0, 0) | (1, 1) | (2, 2) => 1.0,
                (1, 2) => self.node_x(node),
                _ => 0.0,
            }
        })
    }
}

fn scatter(global: &mut Mat<f64>, local: &ElementMatrix, dofs: &[usize; 6]) {
    for (i, &gi) in dofs.iter().enumerate() {
        for (j, &gj) in dofs.iter().enumerate() {
            global[(gi, gj)] += local[(i, j)];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn assembled_mass_gives_rod_mass_for_translation() {
        let mesh = RodMesh::new(RodProperties::seed001_benchmark(), 5, 0.0).unwrap();
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
        let mesh = RodMesh::new(RodProperties::seed001_benchmark(), 4, 0.0).unwrap();
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
        let err = RodMesh::new(RodProperties::seed001_benchmark(), 0, 0.0).unwrap_err();
        assert!(err.to_string().contains("rod.elements"));
    }
}
