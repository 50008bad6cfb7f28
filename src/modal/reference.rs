//! Reference conditions: linear constraints that remove the rigid-body modes of the element
//! shape functions, `q_f = B_r q_r` (O. P. Agrawal and A. A. Shabana, "Dynamic analysis of
//! multibody systems using component modes", *Computers & Structures* 21(6), 1985, eq. 3.9 and
//! section 3.2; J. O'Shea, "CDI Parametric Study: Analysis of the Small-Deformation Connecting
//! Rod: Slider Crank Mechanism", "Reference conditions & the elimination of rigid body modes").

use faer::Mat;

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
    /// of deformation; Agrawal and Shabana 1985, section 3.2, eq. 3.6-3.7 and 5.3-5.4, and
    /// section 5.2).
    MeanAxis,
    /// All three coordinates of node `node` zero (node N/2 = midpoint, node 0 = cantilever at B);
    /// frame at that node.
    BodyFixed { node: usize },
    /// A user-given set of constrained nodal coordinates (global indices `3 i + {0: u, 1: v,
    /// 2: slope}`); frame at B. Must remove exactly the three rigid-body modes.
    Constrained { coordinates: Vec<usize> },
}

/// The result of applying reference conditions to a mesh: `q_f = B_r q_r` with
/// `B_r = P S`, `S` selecting the coordinates `kept` (n_full x n_reduced) and `P` either the
/// identity (constrained coordinates) or the `M`-orthogonal projector away from the rigid-body
/// motions (mean axis).
pub struct ReferenceBasis {
    /// `B_r`, n_full x n_reduced.
    pub b_r: Mat<f64>,
    /// The coordinates `S` keeps, ascending (column `j` of `B_r` is `P e_kept[j]`).
    pub kept: Vec<usize>,
    /// Whether `B_r` only selects coordinates (`P = I`: constrained-coordinate reference
    /// conditions), so that `B_r^T K B_r` is a submatrix (no products needed).
    pub selects: bool,
    /// Mean axis: `Y = (M R)^T S` (3 x n_reduced) and `(R^T M R)^-1`, for the reduced mass
    /// matrix `S^T M S - Y^T (R^T M R)^-1 Y`.
    rigid: Option<(Mat<f64>, Mat<f64>)>,
    /// Body-frame x of the B end.
    pub x_b: f64,
}

impl ReferenceBasis {
    /// The reduced matrices `K_rr = B_r^T K B_r`, `M_rr = B_r^T M B_r`. For the mean axis
    /// `K R = 0` (strain-free rigid motions) gives `K_rr = S^T K S` exactly, and
    /// `M_rr = S^T M S - Y^T (R^T M R)^-1 Y` (the mass of the selected coordinates less its
    /// rigid-body part).
    pub fn reduce(&self, k: &Mat<f64>, m: &Mat<f64>) -> (Mat<f64>, Mat<f64>) {
        let kept = &self.kept;
        let r = kept.len();
        let k_rr = Mat::from_fn(r, r, |i, j| k[(kept[i], kept[j])]);
        let mut m_rr = Mat::from_fn(r, r, |i, j| m[(kept[i], kept[j])]);
        if let Some((y, rmr_inv)) = &self.rigid {
            let z = rmr_inv * y;
            let correction = y.transpose() * &z;
            for j in 0..r {
                for i in 0..r {
                    m_rr[(i, j)] -= 0.5 * (correction[(i, j)] + correction[(j, i)]);
                }
            }
        }
        (k_rr, m_rr)
    }
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
                    return Err(ModelError::InvalidInteger {
                        name: "rod.elements",
                        value: n_elements as i64,
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

    /// The conditions in words, as a scene names them (`n_elements` tells the midpoint).
    pub fn describe(&self, n_elements: usize) -> String {
        match self {
            ReferenceConditions::SimplySupported => ReferenceKind::SimplySupported.name().into(),
            ReferenceConditions::MeanAxis => ReferenceKind::MeanAxis.name().into(),
            ReferenceConditions::BodyFixed { node: 0 } => ReferenceKind::Cantilever.name().into(),
            ReferenceConditions::BodyFixed { node } if 2 * node == n_elements => {
                ReferenceKind::BodyFixedMid.name().into()
            }
            ReferenceConditions::BodyFixed { node } => format!("body-fixed at node {node}"),
            ReferenceConditions::Constrained { coordinates } => {
                format!("constrained coordinates {coordinates:?}")
            }
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
    pub fn basis(&self, mesh: &RodMesh, m: &Mat<f64>) -> Result<ReferenceBasis, ModelError> {
        let n = mesh.n_coordinates();
        let x_b = mesh.x_b;
        let selection =
            |fixed: &[usize]| -> Vec<usize> { (0..n).filter(|i| !fixed.contains(i)).collect() };
        match self.constrained(mesh) {
            Some(fixed) => {
                check_constraint_set(mesh, &fixed)?;
                let kept = selection(&fixed);
                let b_r = Mat::from_fn(n, kept.len(), |i, j| if kept[j] == i { 1.0 } else { 0.0 });
                Ok(ReferenceBasis {
                    b_r,
                    kept,
                    selects: true,
                    rigid: None,
                    x_b,
                })
            }
            None => {
                // Mean axis: the elastic modes of the free-free rod span the M-orthogonal
                // complement of the rigid-body motions R, `R^T M q_f = 0` (zero linear and
                // angular momentum of deformation). A basis: `B_r = P S` with
                // `P = I - R (R^T M R)^-1 R^T M` and `S` the coordinates left by any set that
                // fixes the rigid motions (here u = v = 0 at B, v = 0 at C). Then `K_rr` is
                // the constrained rod's stiffness and the free-free elastic modes follow from
                // one positive definite eigenproblem, without rigid-body eigenvalues to tell
                // from zero: `K P = K` because `K R = 0`, so `B_r^T K B_r = S^T K S`, and
                // `B_r^T M B_r = S^T M S - Y^T (R^T M R)^-1 Y` ([`ReferenceBasis::reduce`]).
                // The eigenvalues are those of the free-free rod's elastic modes, the vectors
                // `B_r a` satisfy the mean-axis conditions by construction.
                let last = mesh.n_elements;
                let fixed = [0, 1, 3 * last + 1];
                check_constraint_set(mesh, &fixed)?;
                let kept = selection(&fixed);
                let r = mesh.rigid_modes();
                let mr = m * &r;
                let rmr = r.transpose() * &mr;
                let rmr = nalgebra::Matrix3::from_fn(|i, j| rmr[(i, j)]);
                let rmr_inv = rmr.try_inverse().ok_or_else(|| ModelError::Numerical {
                    message: "rigid-body mass matrix is singular".into(),
                })?;
                let rmr_inv = Mat::from_fn(3, 3, |i, j| rmr_inv[(i, j)]);
                // Y = (M R)^T S; B_r = S - R (R^T M R)^-1 Y.
                let y = Mat::from_fn(3, kept.len(), |i, j| mr[(kept[j], i)]);
                let x = &rmr_inv * &y;
                let mut b_r = &r * &x * -1.0;
                for (j, &row) in kept.iter().enumerate() {
                    b_r[(row, j)] += 1.0;
                }
                Ok(ReferenceBasis {
                    b_r,
                    kept,
                    selects: false,
                    rigid: Some((y, rmr_inv)),
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
        return Err(ModelError::InvalidInteger {
            name: "constrained nodal coordinate",
            value: bad as i64,
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
