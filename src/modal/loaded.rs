//! Mass-loaded interface modes: component modes whose eigenproblem carries point masses at
//! chosen coordinates of the rod (the piston at C's axial coordinate), while the dynamics stay
//! the exact Galerkin projection with the real masses.
//!
//! The basis: the eigenvectors of `K_rr a = w^2 (M_rr + Delta M) a`, `Delta M` the added
//! masses on their coordinates. It spans the same space as the free modes when all are kept;
//! truncated, its lowest modes are the rod's modes with the masses attached, so that the
//! slider-rod axial mode and the bending modes with end bodies come out at their frequencies
//! in the mechanism (mass-loaded interface modes: Craig and Kurdila, *Fundamentals of
//! Structural Dynamics*, 2nd ed., 2006, section 18.5 "Mass-additive / loaded-interface
//! component modes"; Benfield and Hruda 1971, "Vibration analysis of structures by component
//! mode substitution", AIAA Journal 9(7)). The added masses do not enter the model's mass: the
//! shape integrals are formed with the rod's own mass matrix, so `M_ff = I - Phi^T Delta M Phi`
//! is no longer the identity (`crate::rod::ffr::FfrKernel` keeps the full `M_ff`), and
//! `Phi^T K Phi = diag(w^2)` still holds.
//!
//! Solved as a Ritz problem in the basis of every free mode `Phi_all` (n_r columns, a basis
//! of the reduced space): `diag(w_all^2) y = w^2 (I + Phi_all^T Delta M Phi_all) y`, shapes
//! `Phi_all y` (mass-normalized to `M + Delta M`).

use faer::Mat;

use super::component_modes::ComponentModes;
use super::eigen::generalized_symmetric_eigen;
use super::reference::ReferenceConditions;
use super::selection::ModeSelection;
use crate::beam::{MassKind, RodDefinition};
use crate::error::ModelError;

/// A point mass added in the eigenproblem only: `mass` kg on the full nodal coordinate
/// `coordinate` of the rod's mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AddedMass {
    pub coordinate: usize,
    pub mass: f64,
}

impl ComponentModes {
    /// The modes of [`ComponentModes::from_definition`] with `added` masses in the eigenproblem
    /// (module documentation); the same as it with none.
    pub fn from_definition_loaded(
        definition: RodDefinition,
        n_elements: usize,
        reference: ReferenceConditions,
        mass_kind: MassKind,
        selection: &ModeSelection,
        added: &[AddedMass],
    ) -> Result<ComponentModes, ModelError> {
        let added: Vec<AddedMass> = added.iter().copied().filter(|a| a.mass != 0.0).collect();
        if added.is_empty() {
            return ComponentModes::from_definition(
                definition, n_elements, reference, mass_kind, selection,
            );
        }
        let free = ComponentModes::from_definition(
            definition,
            n_elements,
            reference,
            mass_kind,
            &ModeSelection::Cutoff {
                max_hz: f64::INFINITY,
            },
        )?;
        let n_full = free.shapes.nrows();
        for a in &added {
            if a.coordinate >= n_full || !(a.mass.is_finite() && a.mass > 0.0) {
                return Err(ModelError::InvalidParameter {
                    name: "added interface mass",
                    value: a.mass,
                    allowed: format!("a positive mass on a coordinate 0..{n_full}"),
                });
            }
        }
        let r = free.shapes.ncols();
        let phi = &free.shapes;
        let k_tilde = Mat::from_fn(r, r, |i, j| if i == j { free.omega2[i] } else { 0.0 });
        let m_tilde = Mat::from_fn(r, r, |i, j| {
            let extra: f64 = added
                .iter()
                .map(|a| a.mass * phi[(a.coordinate, i)] * phi[(a.coordinate, j)])
                .sum();
            if i == j {
                1.0 + extra
            } else {
                extra
            }
        });
        let eig = generalized_symmetric_eigen(&k_tilde, &m_tilde)?;
        let loaded: Mat<f64> = phi * &eig.vectors;
        let all_frequencies_hz: Vec<f64> = eig
            .values
            .iter()
            .map(|&l| l.max(0.0).sqrt() / (2.0 * std::f64::consts::PI))
            .collect();
        // Kinetic energy share in the axial displacements, with the added masses (unit total:
        // the shapes are normalized to M + Delta M).
        let (_, m) = free.mesh.assemble(mass_kind);
        let mesh = &free.mesh;
        let all_axial_shares: Vec<f64> = (0..r)
            .map(|j| {
                let (mut axial, mut total) = (0.0, 0.0);
                for a in 0..n_full {
                    let xa = loaded[(a, j)];
                    if xa == 0.0 {
                        continue;
                    }
                    for b in 0..n_full {
                        let e = xa * m[(a, b)] * loaded[(b, j)];
                        total += e;
                        if mesh.is_axial_coordinate(a) && mesh.is_axial_coordinate(b) {
                            axial += e;
                        }
                    }
                }
                for am in &added {
                    let e = am.mass * loaded[(am.coordinate, j)].powi(2);
                    total += e;
                    if mesh.is_axial_coordinate(am.coordinate) {
                        axial += e;
                    }
                }
                if total > 0.0 {
                    axial / total
                } else {
                    0.0
                }
            })
            .collect();
        let retained = selection.select_classified(&all_frequencies_hz, &all_axial_shares)?;
        let shapes = Mat::from_fn(n_full, retained.len(), |i, j| loaded[(i, retained[j])]);
        let omega2 = retained.iter().map(|&i| eig.values[i].max(0.0)).collect();
        Ok(ComponentModes {
            mesh: free.mesh,
            reference: free.reference,
            mass_kind,
            all_frequencies_hz,
            all_axial_shares,
            retained,
            omega2,
            shapes,
        })
    }
}

/// The full nodal coordinate of the axial displacement at C (the last node) of a mesh of
/// `n_elements` elements.
pub fn axial_coordinate_at_c(n_elements: usize) -> usize {
    3 * n_elements
}
