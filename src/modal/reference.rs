//! Reference conditions: linear constraints that remove the rigid-body modes of the element
//! shape functions, `q_f = B_r q_r` (seed 000, eq. 3.9 and section 3.2; seed 001,
//! "Reference conditions & the elimination of rigid body modes").

use faer::Mat;

use super::eigen::{generalized_symmetric_eigen, generalized_symmetric_eigen_scaled};
use crate::beam::RodMesh;
use crate::error::ModelError;
use serde::{Deserialize, Serialize};

/// Reference conditions of the FFR rod (docs/physics.md, "Rod model 1").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ReferenceKind {
    /// `u = v = 0` at B, `v = 0` at C; frame at B, x axis through C.
    SimplySupported,
    /// Free-free modes with the rigid-body modes removed; frame at the centre of mass.
    MeanAxis,
    /// All three coordinates of the middle node zero (needs an even number of elements).
    BodyFixedMid,
    /// All three coordinates of the B node zero (a cantilever from B).
    Cantilever,
}

impl ReferenceKind {
    /// Every variant, in the order of the FMU's enumeration items and Integer codes (1-based).
    pub const ALL: [ReferenceKind; 4] = [
        ReferenceKind::SimplySupported,
        ReferenceKind::MeanAxis,
        ReferenceKind::BodyFixedMid,
        ReferenceKind::Cantilever,
    ];

    /// The name used in scenes, the FMU's enumeration items and messages.
    pub fn name(self) -> &'static str {
        match self {
            ReferenceKind::SimplySupported => "simply_supported",
            ReferenceKind::MeanAxis => "mean_axis",
            ReferenceKind::BodyFixedMid => "body_fixed_mid",
            ReferenceKind::Cantilever => "cantilever",
        }
    }

    /// The variant of a name (see [`Self::name`]).
    pub fn from_name(name: &str) -> Option<ReferenceKind> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }
}

/// The supported reference conditions.
#[derive(Clone, Debug, PartialEq)]
pub enum ReferenceConditions {
    /// `u = v = 0` at the B node, `v = 0` at the C node; frame at B, x axis through C.
    SimplySupported,
    /// Free-free modes with the three rigid-body modes removed; frame at the centre of mass.
    /// The retained modes satisfy the mean-axis conditions (zero linear and angular momentum
    /// of deformation; seed 000 section 3.2, eq. 3.6-3.7 and 5.3-5.4, and section 5.2).
    MeanAxis,
    /// All three coordinates of node `node` zero (node N/2 = midpoint, node 0 = cantilever at B);
    /// frame at that node.
    BodyFixed { node: usize },
    /// A user-given set of constrained nodal coordinates (global indices `3 i + {0: u, 1: v,
    /// 2: slope}`); frame at B. Must remove exactly the three rigid-body modes.
    Constrained { coordinates: Vec<usize> },
}

/// The result of applying reference conditions to a mesh.
pub struct ReferenceBasis {
    /// `B_r`, n_full x n_reduced.
    pub b_r: Mat<f64>,
    /// When `B_r` only selects coordinates (constrained-coordinate reference conditions): the
    /// kept coordinates, so that `B_r^T K B_r` is a submatrix (no products needed).
    pub selection: Option<Vec<usize>>,
    /// Body-frame x of the B end.
    pub x_b: f64,
}

impl ReferenceConditions {
    /// From a scene's choice; `n_elements` locates the midpoint (it must be a node).
    pub fn from_kind(kind: ReferenceKind, n_elements: usize) -> Result<Self, ModelError> {
        Ok(match kind {
            ReferenceKind::SimplySupported => ReferenceConditions::SimplySupported,
            ReferenceKind::MeanAxis => ReferenceConditions::MeanAxis,
            ReferenceKind::Cantilever => ReferenceConditions::BodyFixed { node: 0 },
            ReferenceKind::BodyFixedMid => {
                if !n_elements.is_multiple_of(2) {
                    return Err(ModelError::InvalidParameter {
                        name: "rod.elements",
                        value: n_elements as f64,
                        allowed: "an even number with rod.reference = body_fixed_mid (the midpoint must be a node)".into(),
                    });
                }
                ReferenceConditions::BodyFixed {
                    node: n_elements / 2,
                }
            }
        })
    }

    /// Parse a name as used in scenes: `simply_supported`, `mean_axis`, `body_fixed_mid`,
    /// `cantilever`.
    pub fn parse(name: &str, n_elements: usize) -> Result<Self, ModelError> {
        let kind =
            ReferenceKind::from_name(name).ok_or_else(|| ModelError::ReferenceConditions {
                message: format!(
                    "unknown reference condition '{name}': allowed {}",
                    ReferenceKind::ALL.map(ReferenceKind::name).join(", ")
                ),
            })?;
        Self::from_kind(kind, n_elements)
    }

    /// The constrained coordinates, for the kinds that constrain coordinates.
    fn constrained(&self, mesh: &RodMesh) -> Option<Vec<usize>> {
        let last = mesh.n_elements;
        match self {
            ReferenceConditions::SimplySupported => Some(vec![0, 1, 3 * last + 1]),
            ReferenceConditions::BodyFixed { node } => {
                Some(vec![3 * node, 3 * node + 1, 3 * node + 2])
            }
            ReferenceConditions::Constrained { coordinates } => Some(coordinates.clone()),
            ReferenceConditions::MeanAxis => None,
        }
    }

    /// Body-frame x of the B end (where the frame sits relative to the rod).
    pub fn frame_x_b(&self, section_length: f64, n_elements: usize) -> f64 {
        match self {
            ReferenceConditions::MeanAxis => -0.5 * section_length,
            ReferenceConditions::BodyFixed { node } => {
                -(*node as f64) * section_length / n_elements as f64
            }
            _ => 0.0,
        }
    }

    /// Build `B_r` for `mesh` (whose `x_b` must be [`Self::frame_x_b`]). Rejects sets that
    /// leave a rigid-body mode in or over-constrain the rod, saying which.
    pub fn basis(
        &self,
        mesh: &RodMesh,
        k: &Mat<f64>,
        m: &Mat<f64>,
    ) -> Result<ReferenceBasis, ModelError> {
        let n = mesh.n_coordinates();
        let x_b = mesh.x_b;
        match self.constrained(mesh) {
            Some(fixed) => {
                check_constraint_set(mesh, &fixed)?;
                let free: Vec<usize> = (0..n).filter(|i| !fixed.contains(i)).collect();
                let b_r = Mat::from_fn(n, free.len(), |i, j| if free[j] == i { 1.0 } else { 0.0 });
                Ok(ReferenceBasis {
                    b_r,
                    selection: Some(free),
                    x_b,
                })
            }
            None => {
                // Mean axis: the elastic modes of the free-free rod span the M-orthogonal
                // complement of the rigid-body modes.
                let eig = if mesh.n_bubbles() > 0 {
                    generalized_symmetric_eigen_scaled(k, m)?
                } else {
                    generalized_symmetric_eigen(k, m)?
                };
                let scale = eig
                    .values
                    .get(3)
                    .copied()
                    .unwrap_or(1.0)
                    .abs()
                    .max(f64::MIN_POSITIVE);
                for (i, v) in eig.values.iter().take(3).enumerate() {
                    if v.abs() > 1e-6 * scale {
                        return Err(ModelError::Numerical {
                            message: format!(
                                "free-free rod: rigid-body eigenvalue {i} = {v:e} is not zero against the first elastic one {scale:e}"
                            ),
                        });
                    }
                }
                let mut b_r = eig.vectors.subcols(3, n - 3).to_owned();
                if mesh.n_bubbles() > 0 {
                    // Project the rigid motions out once more (M-orthogonally,
                    // `B_r -= R (R^T M R)^-1 R^T M B_r`): the eigenvectors of the scaled
                    // solver leave about 1e-11 of linear momentum in the modes.
                    let r = mesh.rigid_modes();
                    let mr = m * &r;
                    let rmr = r.transpose() * &mr;
                    let coupling = mr.transpose() * &b_r;
                    let rmr = nalgebra::Matrix3::from_fn(|i, j| rmr[(i, j)]);
                    let rmr_inv = rmr.try_inverse().ok_or_else(|| ModelError::Numerical {
                        message: "rigid-body mass matrix is singular".into(),
                    })?;
                    let x = Mat::from_fn(3, n - 3, |i, j| {
                        (0..3)
                            .map(|k| rmr_inv[(i, k)] * coupling[(k, j)])
                            .sum::<f64>()
                    });
                    b_r = &b_r - &r * x;
                }
                Ok(ReferenceBasis {
                    b_r,
                    selection: None,
                    x_b,
                })
            }
        }
    }
}

/// The constrained coordinates must be exactly three and must fix the three rigid-body
/// motions: the 3 x 3 matrix of rigid modes at those coordinates must be regular.
fn check_constraint_set(mesh: &RodMesh, fixed: &[usize]) -> Result<(), ModelError> {
    let n = mesh.n_coordinates();
    if let Some(&bad) = fixed.iter().find(|&&i| i >= n) {
        return Err(ModelError::InvalidParameter {
            name: "constrained nodal coordinate",
            value: bad as f64,
            allowed: format!("0..={} (3 per node: u, v, slope)", n - 1),
        });
    }
    let mut unique = fixed.to_vec();
    unique.sort_unstable();
    unique.dedup();
    if unique.len() != fixed.len() {
        return Err(ModelError::ReferenceConditions {
            message: format!("the constrained coordinates {fixed:?} repeat a coordinate"),
        });
    }
    let rigid = mesh.rigid_modes();
    let rc = Mat::from_fn(unique.len(), 3, |i, j| rigid[(unique[i], j)]);
    let rank = if unique.is_empty() {
        0
    } else {
        let s = rc.singular_values().map_err(|e| ModelError::Numerical {
            message: format!("SVD of the constraint set failed ({e:?})"),
        })?;
        let smax = s.iter().cloned().fold(0.0, f64::max);
        s.iter().filter(|&&v| v > 1e-9 * smax.max(1e-300)).count()
    };
    let free_rigid = 3 - rank;
    let extra = unique.len() - rank;
    match (free_rigid, extra) {
        (0, 0) => Ok(()),
        (r, 0) => Err(ModelError::ReferenceConditions {
            message: format!(
                "the constrained coordinates {fixed:?} leave {r} rigid-body mode(s) in (need 3 independent constraints on the rigid motions, got {rank})"
            ),
        }),
        (0, e) => Err(ModelError::ReferenceConditions {
            message: format!(
                "the constrained coordinates {fixed:?} over-constrain the rod: {e} constraint(s) beyond the 3 that fix the frame remove elastic deformation"
            ),
        }),
        (r, e) => Err(ModelError::ReferenceConditions {
            message: format!(
                "the constrained coordinates {fixed:?} leave {r} rigid-body mode(s) in and over-constrain the rod by {e}"
            ),
        }),
    }
}
