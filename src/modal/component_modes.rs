//! The rod's component modes: mesh + reference conditions + eigenproblem + selection.
//!
//! Deformation field in the body frame: `u_f(x) = S(x) B_r Phi p = S_hat(x) p`
//! (O. P. Agrawal and A. A. Shabana, "Dynamic analysis of multibody systems using component
//! modes", *Computers & Structures* 21(6), 1985: eq. 4.4 and the modal transformation eq. 6.1).

use faer::Mat;

use super::eigen::{
    generalized_symmetric_eigen, generalized_symmetric_eigen_by_stiffness,
    generalized_symmetric_eigen_by_stiffness_scaled, generalized_symmetric_eigen_scaled,
    GeneralizedEigen,
};
use super::reference::ReferenceConditions;
use super::selection::ModeSelection;
use crate::beam::MassKind;
use crate::beam::{RodDefinition, RodMesh, RodProperties};
use crate::error::ModelError;

/// Each column of `shapes` (full nodal coordinates): its kinetic energy share
/// `x_a^T M_aa x_a / x^T M x` in the coordinates where `is_axial` holds, with point masses
/// `extra` (coordinate, kg) added to `M`'s diagonal. Sums over `M`'s nonzeros only (the beam
/// mass matrix is banded): O(nonzeros x modes). 0 for a column of zero energy.
pub(super) fn axial_energy_shares(
    m: &Mat<f64>,
    shapes: &Mat<f64>,
    is_axial: impl Fn(usize) -> bool,
    extra: &[(usize, f64)],
) -> Vec<f64> {
    let mut entries: Vec<(usize, usize, f64, bool)> = Vec::new();
    for c in 0..m.ncols() {
        for r in 0..m.nrows() {
            let v = m[(r, c)];
            if v != 0.0 {
                entries.push((r, c, v, is_axial(r) && is_axial(c)));
            }
        }
    }
    for &(k, mass) in extra {
        entries.push((k, k, mass, is_axial(k)));
    }
    (0..shapes.ncols())
        .map(|j| {
            let (mut axial, mut total) = (0.0, 0.0);
            for &(r, c, v, both_axial) in &entries {
                let e = shapes[(r, j)] * v * shapes[(c, j)];
                total += e;
                if both_axial {
                    axial += e;
                }
            }
            if total > 0.0 {
                axial / total
            } else {
                0.0
            }
        })
        .collect()
}

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
    /// (Agrawal and Shabana 1985, eq. 4.4), keep the selected modes.
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
                return Err(ModelError::InvalidInteger {
                    name: "body-fixed node",
                    value: node as i64,
                    allowed: format!("0..={n_elements}"),
                });
            }
        }
        let (k, m) = mesh.assemble(mass_kind);
        let basis = reference.basis(&mesh, &m)?;
        let b = &basis.b_r;
        let (k_rr, m_rr) = basis.reduce(&k, &m);
        let axial: Vec<bool> = basis
            .kept
            .iter()
            .map(|&i| mesh.is_axial_coordinate(i))
            .collect();
        let eig = solve_reduced(&k_rr, &m_rr, mesh.n_bubbles() > 0, &axial)?;
        check_spectrum(&eig, &mesh, &reference)?;
        let all_frequencies_hz: Vec<f64> = eig
            .values
            .iter()
            .map(|&l| l.sqrt() / (2.0 * std::f64::consts::PI))
            .collect();
        // Every mode in full coordinates, and its kinetic energy share in the axial
        // displacements (node i's u at 3 i).
        let all_full = match basis.selects {
            true => {
                let mut full = Mat::zeros(b.nrows(), eig.vectors.ncols());
                for (i, &row) in basis.kept.iter().enumerate() {
                    for j in 0..eig.vectors.ncols() {
                        full[(row, j)] = eig.vectors[(i, j)];
                    }
                }
                full
            }
            false => b * &eig.vectors,
        };
        let all_axial_shares =
            axial_energy_shares(&m, &all_full, |r| mesh.is_axial_coordinate(r), &[]);
        let retained = selection.select_classified(&all_frequencies_hz, &all_axial_shares)?;
        let shapes = Mat::from_fn(all_full.nrows(), retained.len(), |i, j| {
            all_full[(i, retained[j])]
        });
        let omega2 = retained.iter().map(|&i| eig.values[i]).collect();
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

    /// The modes `selection` keeps of these, as if the eigenproblem had been solved with it:
    /// `self` must retain every mode it selects (e.g. `self` from
    /// `ModeSelection::Cutoff { max_hz: f64::INFINITY }`), else the missing one is refused.
    pub fn select(&self, selection: &ModeSelection) -> Result<ComponentModes, ModelError> {
        let retained =
            selection.select_classified(&self.all_frequencies_hz, &self.all_axial_shares)?;
        let mut columns = Vec::with_capacity(retained.len());
        for &k in &retained {
            let column = self.retained.iter().position(|&r| r == k).ok_or_else(|| {
                ModelError::InvalidInteger {
                    name: "mode index",
                    value: k as i64,
                    allowed: "a mode the set selected from retains".into(),
                }
            })?;
            columns.push(column);
        }
        Ok(ComponentModes {
            mesh: self.mesh.clone(),
            reference: self.reference.clone(),
            mass_kind: self.mass_kind,
            all_frequencies_hz: self.all_frequencies_hz.clone(),
            all_axial_shares: self.all_axial_shares.clone(),
            retained,
            omega2: columns.iter().map(|&c| self.omega2[c]).collect(),
            shapes: Mat::from_fn(self.shapes.nrows(), columns.len(), |i, j| {
                self.shapes[(i, columns[j])]
            }),
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

/// Relative resolution below which the lowest eigenvalue of the coupled solve counts as lost in
/// the round-off of the highest: the eigenvalues of [`generalized_symmetric_eigen`] carry an
/// absolute error of about `eps lambda_max`, so `lambda_1 >= 1e6 eps lambda_max` keeps
/// `lambda_1` to about 1e-6 relative.
const RESOLVED: f64 = 1e6 * f64::EPSILON;

/// `K_rr a = lambda M_rr a` of the reduced rod, eigenvalues ascending, vectors
/// `M_rr`-normalized. One coupled solve ([`solve_coupled`]); when its lowest eigenvalue is
/// not resolved against its highest ([`RESOLVED`]: a slender section, whose axial modes sit
/// `A L^2 / I` above the bending ones) and the axial and transverse coordinates decouple
/// exactly in `K_rr` and `M_rr` (the straight rod: every element and end body here), the two
/// blocks are solved apart, each against its own highest eigenvalue.
fn solve_reduced(
    k: &Mat<f64>,
    m: &Mat<f64>,
    bubbles: bool,
    axial: &[bool],
) -> Result<GeneralizedEigen, ModelError> {
    let coupled = solve_coupled(k, m, bubbles);
    if let Ok(eig) = &coupled {
        let lowest = eig.values.first().copied().unwrap_or(1.0);
        let highest = eig.values.last().copied().unwrap_or(1.0);
        if lowest > RESOLVED * highest.abs() {
            return coupled;
        }
    }
    let ia: Vec<usize> = (0..axial.len()).filter(|&i| axial[i]).collect();
    let ib: Vec<usize> = (0..axial.len()).filter(|&i| !axial[i]).collect();
    let decoupled = ia.iter().all(|&i| {
        ib.iter()
            .all(|&j| k[(i, j)] == 0.0 && m[(i, j)] == 0.0 && k[(j, i)] == 0.0 && m[(j, i)] == 0.0)
    });
    if ia.is_empty() || ib.is_empty() || !decoupled {
        return coupled;
    }
    let block = |idx: &[usize]| {
        let sub = |a: &Mat<f64>| Mat::from_fn(idx.len(), idx.len(), |i, j| a[(idx[i], idx[j])]);
        solve_coupled(&sub(k), &sub(m), bubbles)
    };
    let (Ok(ea), Ok(eb)) = (block(&ia), block(&ib)) else {
        return coupled;
    };
    // Merge: every pair in the reduced coordinates, ascending.
    let mut pairs: Vec<(f64, &[usize], &Mat<f64>, usize)> = (0..ia.len())
        .map(|j| (ea.values[j], ia.as_slice(), &ea.vectors, j))
        .chain((0..ib.len()).map(|j| (eb.values[j], ib.as_slice(), &eb.vectors, j)))
        .collect();
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let n = axial.len();
    let mut vectors = Mat::zeros(n, n);
    for (col, (_, idx, vecs, j)) in pairs.iter().enumerate() {
        for (r, &row) in idx.iter().enumerate() {
            vectors[(row, col)] = vecs[(r, *j)];
        }
    }
    Ok(GeneralizedEigen {
        values: pairs.iter().map(|p| p.0).collect(),
        vectors,
    })
}

/// One generalized eigenproblem of the reduced rod. Rods with interior coordinates: the
/// scaled QR form ([`generalized_symmetric_eigen_scaled`], measured there), and the
/// stiffness-based form when the spectrum spans more than 1e10 (a nearly rigid shear modulus:
/// the mass-based form's absolute error is about `eps lambda_max`, the stiffness-based form
/// keeps the lowest modes to `eps` where the reduced stiffness is definite). A negative lowest
/// eigenvalue (round-off of an ill-conditioned mass matrix, or a truly indefinite stiffness)
/// is retried in the stiffness-based form, which fails on the latter.
fn solve_coupled(
    k: &Mat<f64>,
    m: &Mat<f64>,
    bubbles: bool,
) -> Result<GeneralizedEigen, ModelError> {
    let mut eig = if bubbles {
        let eig = generalized_symmetric_eigen_scaled(k, m)?;
        let spread = match (eig.values.first(), eig.values.last()) {
            (Some(&lo), Some(&hi)) => hi / lo.abs().max(f64::MIN_POSITIVE),
            _ => 0.0,
        };
        match spread > 1e10 {
            true => generalized_symmetric_eigen_by_stiffness_scaled(k, m).unwrap_or(eig),
            false => eig,
        }
    } else {
        generalized_symmetric_eigen(k, m)?
    };
    let indefinite = match eig.values.first() {
        Some(&lowest) => lowest < -1e-9 * eig.values.last().copied().unwrap_or(1.0).abs(),
        None => false,
    };
    if indefinite {
        if let Ok(by_stiffness) = generalized_symmetric_eigen_by_stiffness(k, m) {
            eig = by_stiffness;
        }
    }
    Ok(eig)
}

/// Every eigenvalue of the reduced rod must be finite and positive: the reference conditions
/// leave no rigid-body motion, so a zero, negative or non-finite value is round-off or a
/// failed solve, never a frequency. The error names the rod's parameters.
fn check_spectrum(
    eig: &GeneralizedEigen,
    mesh: &RodMesh,
    reference: &ReferenceConditions,
) -> Result<(), ModelError> {
    let Some((k, &lambda)) = eig
        .values
        .iter()
        .enumerate()
        .find(|(_, l)| !(l.is_finite() && **l > 0.0))
    else {
        return Ok(());
    };
    let p = &mesh.section;
    let highest = eig.values.iter().copied().fold(0.0, f64::max);
    Err(ModelError::Numerical {
        message: format!(
            "natural frequency {} of the rod is not a finite positive value (eigenvalue {lambda:e} (rad/s)^2, the highest {highest:e}) for rod.length = {} m, rod.youngs_modulus = {:e} Pa, rod.density = {} kg/m^3, rod.area = {:e} m^2, rod.area_moment = {:e} m^4, rod.elements = {}, rod.reference = {}: double precision does not resolve this rod's spectrum; allowed: parameters whose eigenproblem is definite (a less slender section or fewer elements)",
            k + 1,
            p.length,
            p.youngs_modulus,
            p.density,
            p.area,
            p.area_moment,
            mesh.n_elements,
            reference.describe(mesh.n_elements),
        ),
    })
}
