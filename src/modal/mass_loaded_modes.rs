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

use super::component_modes::{axial_energy_shares, ComponentModes};
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
        let extra: Vec<(usize, f64)> = added.iter().map(|a| (a.coordinate, a.mass)).collect();
        let all_axial_shares =
            axial_energy_shares(&m, &loaded, |k| mesh.is_axial_coordinate(k), &extra);
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

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::beam::{EndBody, RodProperties};

    /// A steel rod, 0.15 m, with a small end (also the fixture of
    /// `crate::modal::axial_coupling`'s tests).
    pub(crate) fn rod() -> RodDefinition {
        let mut def = RodDefinition::uniform(RodProperties {
            length: 0.15,
            youngs_modulus: 2e11,
            density: 7800.0,
            area: 2e-4,
            area_moment: 1.5e-8,
        });
        def.small_end = EndBody {
            mass: 0.05,
            inertia: 1e-5,
        };
        def
    }

    fn modes(added: &[AddedMass], selection: ModeSelection) -> ComponentModes {
        ComponentModes::from_definition_loaded(
            rod(),
            8,
            ReferenceConditions::from_kind(crate::modal::ReferenceKind::SimplySupported, 8)
                .unwrap(),
            MassKind::Consistent,
            &selection,
            added,
        )
        .unwrap()
    }

    /// Without added mass the free modes; with it, `Phi^T (M + Delta M) Phi = I` and
    /// `Phi^T K Phi = diag(w^2)`, and the rod's own modal mass is `I - Phi^T Delta M Phi`.
    #[test]
    fn loaded_modes_are_orthonormal_in_the_loaded_mass() {
        let free = modes(&[], ModeSelection::Count(5));
        let plain = ComponentModes::from_definition(
            rod(),
            8,
            ReferenceConditions::from_kind(crate::modal::ReferenceKind::SimplySupported, 8)
                .unwrap(),
            MassKind::Consistent,
            &ModeSelection::Count(5),
        )
        .unwrap();
        assert_eq!(free.all_frequencies_hz, plain.all_frequencies_hz);
        let c = axial_coordinate_at_c(8);
        let added = [AddedMass {
            coordinate: c,
            mass: 0.5,
        }];
        let loaded = modes(&added, ModeSelection::Count(5));
        let (k, m) = loaded.mesh.assemble(MassKind::Consistent);
        let phi = &loaded.shapes;
        let mut m_loaded = m.clone();
        m_loaded[(c, c)] += 0.5;
        let mm = phi.transpose() * &m_loaded * phi;
        let kk = phi.transpose() * &k * phi;
        for i in 0..5 {
            for j in 0..5 {
                let id = if i == j { 1.0 } else { 0.0 };
                assert!((mm[(i, j)] - id).abs() < 1e-9, "M {i} {j}: {}", mm[(i, j)]);
                let kd = if i == j { loaded.omega2[i] } else { 0.0 };
                assert!(
                    (kk[(i, j)] - kd).abs() < 1e-9 * loaded.omega2[4],
                    "K {i} {j}: {}",
                    kk[(i, j)]
                );
            }
        }
        // The first axial mode comes down with the mass at C; bending modes stay.
        let first_axial = |cm: &ComponentModes| {
            (0..cm.all_frequencies_hz.len())
                .find(|&k| cm.is_axial(k))
                .map(|k| cm.all_frequencies_hz[k])
                .unwrap()
        };
        assert!(first_axial(&loaded) < 0.7 * first_axial(&free));
        assert!((loaded.all_frequencies_hz[0] - free.all_frequencies_hz[0]).abs() < 1e-9);
    }

    #[test]
    fn refuses_a_coordinate_outside_the_mesh() {
        let r = ComponentModes::from_definition_loaded(
            rod(),
            8,
            ReferenceConditions::from_kind(crate::modal::ReferenceKind::SimplySupported, 8)
                .unwrap(),
            MassKind::Consistent,
            &ModeSelection::Count(2),
            &[AddedMass {
                coordinate: 10_000,
                mass: 1.0,
            }],
        );
        assert!(r.is_err());
    }
}
