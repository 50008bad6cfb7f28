//! The rod's component modes: mesh + reference conditions + eigenproblem + selection.
//!
//! Deformation field in the body frame: `u_f(x) = S(x) B_r Phi p = S_hat(x) p`
//! (seed 000, eq. 4.4 and the modal transformation eq. 6.1).

use faer::Mat;

use super::eigen::{
    generalized_symmetric_eigen, generalized_symmetric_eigen_by_stiffness,
    generalized_symmetric_eigen_by_stiffness_scaled, generalized_symmetric_eigen_scaled,
};
use super::reference::ReferenceConditions;
use super::selection::ModeSelection;
use crate::beam::MassKind;
use crate::beam::{RodDefinition, RodMesh, RodProperties};
use crate::error::ModelError;

/// Retained modes of the rod and the spectrum they come from.
#[derive(Clone, Debug)]
pub struct ComponentModes {
    pub mesh: RodMesh,
    pub reference: ReferenceConditions,
    pub mass_kind: MassKind,
    /// Every natural frequency of the reduced rod, Hz, ascending (retained or not).
    pub all_frequencies_hz: Vec<f64>,
    /// Every mode's share of its kinetic energy in the axial displacements `u`, 0 to 1 (same
    /// order): a mode is axial above 1/2, else bending.
    pub all_axial_shares: Vec<f64>,
    /// Indices of the retained modes into `all_frequencies_hz`.
    pub retained: Vec<usize>,
    /// Squared circular frequencies of the retained modes, (rad/s)^2.
    pub omega2: Vec<f64>,
    /// Retained mode shapes in full nodal coordinates, `B_r Phi` (n_full x n_modes),
    /// normalized to unit modal mass.
    pub shapes: Mat<f64>,
}

impl ComponentModes {
    /// Preprocess: assemble, apply reference conditions, solve `K_rr a = w^2 M_rr a`
    /// (seed 000, eq. 4.4), keep the selected modes.
    pub fn new(
        section: RodProperties,
        n_elements: usize,
        reference: ReferenceConditions,
        mass_kind: MassKind,
        selection: &ModeSelection,
    ) -> Result<ComponentModes, ModelError> {
        Self::from_definition(
            RodDefinition::uniform(section),
            n_elements,
            reference,
            mass_kind,
            selection,
        )
    }

    /// As [`Self::new`] for any rod: a section table, shear deformation, end bodies (whose
    /// masses and inertias enter `M` at the end nodes before the eigenproblem). With the mean
    /// axis the frame sits at the centre of mass of rod and end bodies. Lumped mass is
    /// available for the plain uniform Euler-Bernoulli rod only.
    pub fn from_definition(
        definition: RodDefinition,
        n_elements: usize,
        reference: ReferenceConditions,
        mass_kind: MassKind,
        selection: &ModeSelection,
    ) -> Result<ComponentModes, ModelError> {
        definition.validate()?;
        let section = definition.properties;
        if !definition.is_plain() && mass_kind == MassKind::Lumped {
            return Err(ModelError::InvalidParameter {
                name: "rod.mass",
                value: f64::NAN,
                allowed: "\"consistent\" for a rod with a section table, shear deformation or end bodies (\"lumped\" only for the uniform Euler-Bernoulli rod)".into(),
            });
        }
        let x_b = match reference {
            ReferenceConditions::MeanAxis if !definition.is_plain() => -definition.centre_of_mass(),
            _ => reference.frame_x_b(section.length, n_elements.max(1)),
        };
        let mesh = RodMesh::from_definition(definition, n_elements, x_b)?;
        if let ReferenceConditions::BodyFixed { node } = reference {
            if node > n_elements {
                return Err(ModelError::InvalidParameter {
                    name: "body-fixed node",
                    value: node as f64,
                    allowed: format!("0..={n_elements}"),
                });
            }
        }
        let (k, m) = mesh.assemble(mass_kind);
        let basis = reference.basis(&mesh, &k, &m)?;
        let b = &basis.b_r;
        let (k_rr, m_rr) = match &basis.selection {
            // B_r selects coordinates: the reduced matrices are submatrices.
            Some(kept) => (
                Mat::from_fn(kept.len(), kept.len(), |i, j| k[(kept[i], kept[j])]),
                Mat::from_fn(kept.len(), kept.len(), |i, j| m[(kept[i], kept[j])]),
            ),
            None => (b.transpose() * &k * b, b.transpose() * &m * b),
        };
        // Rods with interior coordinates: the scaled QR form (modal::eigen, measured there).
        let mut eig = if mesh.n_bubbles() > 0 {
            let eig = generalized_symmetric_eigen_scaled(&k_rr, &m_rr)?;
            // The mass-based form's absolute error is about eps lambda_max: when the spectrum
            // spans more than 1e10 (a nearly rigid shear modulus) the stiffness-based form
            // keeps the lowest modes accurate, where the reduced stiffness is definite.
            let spread = match (eig.values.first(), eig.values.last()) {
                (Some(&lo), Some(&hi)) => hi / lo.abs().max(f64::MIN_POSITIVE),
                _ => 0.0,
            };
            match spread > 1e10 {
                true => {
                    generalized_symmetric_eigen_by_stiffness_scaled(&k_rr, &m_rr).unwrap_or(eig)
                }
                false => eig,
            }
        } else {
            generalized_symmetric_eigen(&k_rr, &m_rr)?
        };
        let indefinite = |eig: &super::eigen::GeneralizedEigen| match eig.values.first() {
            Some(&lowest) => lowest < -1e-9 * eig.values.last().copied().unwrap_or(1.0).abs(),
            None => false,
        };
        if indefinite(&eig) {
            // Round-off of an ill-conditioned mass matrix (a fine mesh of a stubby
            // shear-deformable rod), or a truly indefinite stiffness: the stiffness-based form
            // tells them apart (it fails on the latter).
            if let Ok(by_stiffness) = generalized_symmetric_eigen_by_stiffness(&k_rr, &m_rr) {
                eig = by_stiffness;
            }
        }
        if let Some(&lowest) = eig.values.first() {
            let top = eig.values.last().copied().unwrap_or(1.0).abs();
            if lowest < -1e-9 * top {
                return Err(ModelError::ReferenceConditions {
                    message: format!("the reduced stiffness is indefinite (eigenvalue {lowest:e})"),
                });
            }
        }
        let all_frequencies_hz: Vec<f64> = eig
            .values
            .iter()
            .map(|&l| l.max(0.0).sqrt() / (2.0 * std::f64::consts::PI))
            .collect();
        // Each mode in full coordinates, and its kinetic energy in the axial displacements
        // (node i's u at 3 i): s_u^T M_uu s_u / s^T M s.
        let full_shape = |j: usize| -> Vec<f64> {
            match &basis.selection {
                Some(kept) => {
                    let mut full = vec![0.0; b.nrows()];
                    for (i, &row) in kept.iter().enumerate() {
                        full[row] = eig.vectors[(i, j)];
                    }
                    full
                }
                None => (0..b.nrows())
                    .map(|r| {
                        (0..b.ncols())
                            .map(|c| b[(r, c)] * eig.vectors[(c, j)])
                            .sum()
                    })
                    .collect(),
            }
        };
        let n_full = m.nrows();
        let mesh_ref = &mesh;
        let all_axial_shares: Vec<f64> = (0..eig.values.len())
            .map(|j| {
                let x = full_shape(j);
                let (mut axial, mut total) = (0.0, 0.0);
                for r in 0..n_full {
                    for c in 0..n_full {
                        let e = x[r] * m[(r, c)] * x[c];
                        total += e;
                        if mesh_ref.is_axial_coordinate(r) && mesh_ref.is_axial_coordinate(c) {
                            axial += e;
                        }
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
        let phi = Mat::from_fn(eig.vectors.nrows(), retained.len(), |i, j| {
            eig.vectors[(i, retained[j])]
        });
        let shapes = match &basis.selection {
            Some(kept) => {
                let mut full = Mat::zeros(b.nrows(), phi.ncols());
                for (i, &row) in kept.iter().enumerate() {
                    for j in 0..phi.ncols() {
                        full[(row, j)] = phi[(i, j)];
                    }
                }
                full
            }
            None => b * &phi,
        };
        let omega2 = retained.iter().map(|&i| eig.values[i].max(0.0)).collect();
        Ok(ComponentModes {
            mesh,
            reference,
            mass_kind,
            all_frequencies_hz,
            all_axial_shares,
            retained,
            omega2,
            shapes,
        })
    }

    /// Number of retained modes.
    pub fn n_modes(&self) -> usize {
        self.retained.len()
    }

    /// Whether mode `k` of the full list is axial (more than half its kinetic energy in the
    /// axial displacements).
    pub fn is_axial(&self, k: usize) -> bool {
        self.all_axial_shares[k] > 0.5
    }

    /// The retained modes in words: `"2010 Hz bending, 7310 Hz axial, ..."`.
    pub fn summary(&self) -> String {
        if self.retained.is_empty() {
            return "no elastic modes (rigid rod)".into();
        }
        self.retained
            .iter()
            .map(|&k| {
                format!(
                    "{:.0} Hz {}",
                    self.all_frequencies_hz[k],
                    if self.is_axial(k) { "axial" } else { "bending" }
                )
            })
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The rows of `B_r Phi` for element `e` (the element's coordinates, 6 nodal and any
    /// interior ones, x n_modes).
    pub fn element_shapes(&self, e: usize) -> nalgebra::DMatrix<f64> {
        let dofs = self.mesh.element_dofs(e);
        nalgebra::DMatrix::from_fn(dofs.len(), self.n_modes(), |i, j| self.shapes[(dofs[i], j)])
    }
}
