//! The segment chain linearized about the straight, resting configuration
//! (`theta_k = 0`, `s_j = 0`): `M_0 q'' + K q = 0` with `M_0 = M(q = 0)` of the body itself
//! ([`SegmentRod`]'s mass matrix) and `K` the joint springs. About this state the bending
//! (angles) and axial (slides, `x_B`) coordinates decouple (`M_{theta s} ~ sin(theta_j - theta_i)
//! = 0`, `M_{B theta} ~ n_j` is along y, `M_{B s} ~ e_j` along x).
//!
//! End conditions are eliminated with explicit null-space bases `q = T r`, and
//! `T^T K T a = omega^2 T^T M_0 T a` is solved by
//! [`generalized_symmetric_eigen`](crate::modal::eigen::generalized_symmetric_eigen):
//! - pinned-pinned bending (the mechanism's end conditions, both ends pinned): `x_B = y_B = 0`
//!   and `y_C = l sum_k theta_k = 0`, so `theta_{N-1} = -sum_{k<N-1} theta_k` (N - 1 modes);
//!   shear-deformable: `y_B = y_0 - t_B = 0` and `y_C = t_B + l sum_k theta_k + sum_j t_j +
//!   t_C = 0` give `y_0 = t_B` and the massless `t_C` (2 N modes: N - 1 bending, N + 1 shear);
//! - fixed-fixed axial (both pins also hold the ends along the rod): `x_B = 0`,
//!   `x_C - L = sum_j s_j = 0` (N - 2 modes);
//! - free-free axial (the convergence table of R. L. Huston, "Computer methods in flexible
//!   multibody dynamics", *IJNME* 32, 1991, table II): `x_B` and all
//!   `s_j` free; the rigid translation (`omega = 0`) is dropped (N - 1 modes).
//!
//! The free-free axial chain is `N` masses `m = rho A l` joined by `N - 1` springs `k = E A / l`,
//! the end ones `E A / (1.5 l)` (they also take the half segments at the pins); with equal
//! springs (Huston's chain) the closed form would be `f_n = (1/pi) sqrt(k/m) sin(n pi / (2N))`
//! (tests/segments.rs checks the convergence to the continuum).

use faer::Mat;

use super::rod::SegmentRod;
use crate::beam::RodProperties;
use crate::error::ModelError;
use crate::modal::eigen::{generalized_symmetric_eigen, generalized_symmetric_eigen_by_stiffness};
use crate::rod::RodBody;

/// The pinned-pinned bending eigenproblem of a chain: the bending coordinates `z` (their
/// indices `idx` in `q`), the end conditions `z = t r`, stiffness `k` and mass `m` on `z`.
struct BendingProblem {
    idx: Vec<usize>,
    t: Mat<f64>,
    k: Mat<f64>,
    m: Mat<f64>,
}

/// The `count` lowest modes of `K z = w^2 M z` on the coordinates `z = t r` (rows `idx` of the
/// chain's `q`): `(w^2, shapes)` with the shapes as columns over `q` (`n_coordinates` rows, zero
/// outside `idx`), each of unit modal mass `z^T M z = 1`. Refused, naming `chain`, where there
/// are fewer modes or one is not finite and positive.
fn lowest_modes(
    chain: &str,
    k: &Mat<f64>,
    m: &Mat<f64>,
    t: &Mat<f64>,
    idx: &[usize],
    count: usize,
    n_coordinates: usize,
) -> Result<(Vec<f64>, Mat<f64>), ModelError> {
    let (kr, mr) = (project(k, t), project(m, t));
    let e = generalized_symmetric_eigen_by_stiffness(&kr, &mr)
        .or_else(|_| generalized_symmetric_eigen(&kr, &mr))?;
    if e.values.len() < count {
        return Err(ModelError::Numerical {
            message: format!(
                "{chain}: {count} modes asked for, it has {}",
                e.values.len()
            ),
        });
    }
    let mut shapes = Mat::<f64>::zeros(n_coordinates, count);
    for j in 0..count {
        let w2 = e.values[j];
        if !(w2.is_finite() && w2 > 0.0) {
            return Err(ModelError::Numerical {
                message: format!(
                    "{chain}: natural frequency {} is not a finite positive value (eigenvalue {w2:e} (rad/s)^2)",
                    j + 1
                ),
            });
        }
        let z = t * e.vectors.col(j);
        let modal_mass: f64 = z.transpose() * m * &z;
        let scale = 1.0 / modal_mass.sqrt();
        for (i, &qi) in idx.iter().enumerate() {
            shapes[(qi, j)] = z[i] * scale;
        }
    }
    Ok((e.values[..count].to_vec(), shapes))
}

/// `M_0` and the spring constants of a chain.
pub(crate) struct LinearizedChain {
    mass: Mat<f64>,
    n_seg: usize,
    axial: bool,
    k_rot: Vec<f64>,
    k_ax: Vec<f64>,
    /// Shear springs and the index of `t_B` in `q` (shear-deformable chains).
    k_sh: Vec<f64>,
    shear_base: usize,
    /// Segment length l, m.
    segment_length: f64,
    /// The end body rotations: (index in `q`, end segment, spring N m/rad).
    end_rotations: Vec<(usize, usize, f64)>,
}

/// `T^T A T` for a dense `a` (n x n) and `t` (n x r).
fn project(a: &Mat<f64>, t: &Mat<f64>) -> Mat<f64> {
    t.transpose() * a * t
}

/// Natural frequencies in Hz from `K a = omega^2 M a`, ascending; eigenvalues below
/// `drop_below` (rigid-body modes, in (rad/s)^2) are left out. Without rigid-body modes (`K`
/// positive definite: the pinned chains) the problem is solved through the Cholesky factor of
/// `K`: a fine chain's mass matrix spans `m l^2` of its segments to the end bodies' inertias, and
/// the `M`-based form lost the lowest eigenvalue to round-off (a zero first frequency at 128
/// segments of the benchmark rod with end inertias), the `K`-based form keeps it to `eps`.
///
/// Every value kept must be finite and positive (the end conditions leave no rigid motion): a
/// zero, negative or non-finite eigenvalue is an error naming the chain, never a frequency.
fn frequencies(
    k: &Mat<f64>,
    m: &Mat<f64>,
    drop_below: Option<f64>,
    chain: &str,
) -> Result<Vec<f64>, ModelError> {
    let e = match drop_below {
        None => generalized_symmetric_eigen_by_stiffness(k, m)
            .or_else(|_| generalized_symmetric_eigen(k, m))?,
        Some(_) => generalized_symmetric_eigen(k, m)?,
    };
    let kept: Vec<f64> = e
        .values
        .iter()
        .copied()
        .filter(|&w2| drop_below.is_none_or(|tol| w2 > tol))
        .collect();
    if let Some((i, w2)) = kept
        .iter()
        .enumerate()
        .find(|(_, w2)| !(w2.is_finite() && **w2 > 0.0))
    {
        return Err(ModelError::Numerical {
            message: format!(
                "{chain}: natural frequency {} is not a finite positive value (eigenvalue {w2:e} (rad/s)^2)",
                i + 1
            ),
        });
    }
    Ok(kept
        .iter()
        .map(|&w2| w2.sqrt() / (2.0 * std::f64::consts::PI))
        .collect())
}

impl LinearizedChain {
    pub(crate) fn new(rod: &SegmentRod) -> LinearizedChain {
        let n = rod.n_coordinates();
        let q0 = vec![0.0; n];
        let mut mass = Mat::zeros(n, n);
        rod.mass(&q0, mass.as_mut());
        let (k_rot, k_ax) = rod.joint_springs();
        let (k_rot, k_ax) = (k_rot.to_vec(), k_ax.to_vec());
        LinearizedChain {
            mass,
            n_seg: rod.n_segments(),
            axial: rod.has_axial_springs(),
            k_rot,
            k_ax,
            k_sh: rod.shear_springs().0.to_vec(),
            shear_base: rod.shear_index(0),
            segment_length: rod.segment().0,
            end_rotations: [(0, 0), (1, rod.n_segments() - 1)]
                .into_iter()
                .filter(|&(e, _)| rod.has_end_rotation(e))
                .map(|(e, k)| (rod.end_rotation_index(e), k, rod.end_springs()[e]))
                .collect(),
        }
    }

    /// The chain in words for messages: its modes, `rod.elements`, the segment length and the
    /// range of its joint springs.
    fn describe(&self, modes: &str) -> String {
        let range = |v: &[f64]| {
            if v.is_empty() {
                return "none (one segment): 0".to_string();
            }
            let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            format!("{lo:e} to {hi:e}")
        };
        format!(
            "segment chain ({modes}) with rod.elements = {} segments of {:e} m, rotational springs {} N m/rad{}",
            self.n_seg,
            self.segment_length,
            range(&self.k_rot),
            if self.axial {
                format!(", axial springs {} N/m", range(&self.k_ax))
            } else {
                String::new()
            }
        )
    }

    /// The pinned-pinned bending problem: the indices in `q` of the bending coordinates `z`,
    /// the basis `T` (`z = T r`) of the end conditions, and `K`, `M` on `z`; `None` for a chain
    /// without bending modes.
    fn pinned_bending_problem(&self) -> Option<BendingProblem> {
        let n = self.n_seg;
        let shear = !self.k_sh.is_empty();
        if n < 2 && !shear && self.end_rotations.is_empty() {
            return None;
        }
        // Bending coordinates z: the angles, then (shear) y_0 and t_0 .. t_N, then the end body
        // rotations.
        let mut idx: Vec<usize> = (0..n).map(|k| 2 + k).collect();
        if shear {
            idx.push(1);
            idx.extend((0..=n).map(|i| self.shear_base + i));
        }
        let n_base = idx.len();
        idx.extend(self.end_rotations.iter().map(|&(i, _, _)| i));
        let nz = idx.len();
        let m = Mat::from_fn(nz, nz, |i, j| self.mass[(idx[i], idx[j])]);
        // Joint j joins angles j and j + 1 (K_ii = k_{i-1} + k_i, K_{i,i+1} = -k_i); the shear
        // springs are diagonal.
        let mut k = Mat::<f64>::zeros(nz, nz);
        for (j, &kr) in self.k_rot.iter().enumerate() {
            k[(j, j)] += kr;
            k[(j + 1, j + 1)] += kr;
            k[(j, j + 1)] -= kr;
            k[(j + 1, j)] -= kr;
        }
        for (i, &ks) in self.k_sh.iter().enumerate() {
            k[(n + 1 + i, n + 1 + i)] += ks;
        }
        for (r, &(_, segment, ke)) in self.end_rotations.iter().enumerate() {
            let (a, b) = (n_base + r, segment);
            k[(a, a)] += ke;
            k[(b, b)] += ke;
            k[(a, b)] -= ke;
            k[(b, a)] -= ke;
        }
        let base = if shear {
            // r = [theta_0 .. theta_{N-1}, t_B, t_1 .. t_{N-1}]: y_0 = t_B,
            // t_C = -(t_B + l sum theta + sum t_j).
            // z index n + 1 + i holds t_i, r index n + i (i < N).
            let one = |b: bool| if b { 1.0 } else { 0.0 };
            Mat::from_fn(n_base, 2 * n, |i, j| {
                if i < n {
                    one(i == j)
                } else if i == n {
                    one(j == n)
                } else if i < n_base - 1 {
                    one(j == i - 1)
                } else if j < n {
                    -self.segment_length
                } else {
                    -1.0
                }
            })
        } else {
            // theta_j = r_j (j < N-1), theta_{N-1} = -sum r_j.
            Mat::from_fn(n, n - 1, |i, j| {
                if i == j {
                    1.0
                } else if i == n - 1 {
                    -1.0
                } else {
                    0.0
                }
            })
        };
        // The end rotations are free: identity.
        let (rb, cb) = (base.nrows(), base.ncols());
        let ne = self.end_rotations.len();
        let t = Mat::from_fn(rb + ne, cb + ne, |i, j| {
            if i < rb && j < cb {
                base[(i, j)]
            } else if i >= rb && j >= cb && i - rb == j - cb {
                1.0
            } else {
                0.0
            }
        });
        Some(BendingProblem { idx, t, k, m })
    }

    /// Pinned-pinned bending frequencies, Hz (N - 1 of them; 2 N with shear slides, the
    /// N + 1 highest being the shear modes).
    pub(crate) fn pinned_bending_hz(&self) -> Result<Vec<f64>, ModelError> {
        let Some(p) = self.pinned_bending_problem() else {
            return Ok(Vec::new());
        };
        frequencies(
            &project(&p.k, &p.t),
            &project(&p.m, &p.t),
            None,
            &self.describe("pinned-pinned bending"),
        )
    }

    /// The `count` lowest pinned-pinned bending modes: their circular frequencies squared,
    /// (rad/s)^2, ascending, and their shapes as columns over the chain's coordinates `q`
    /// (zero on `x_B`, the slides, and `y_B` without shear), each of unit modal mass
    /// `a^T M_0 a = 1`. Refused where the chain has fewer modes or one is not finite and
    /// positive.
    pub(crate) fn pinned_bending_modes(
        &self,
        count: usize,
        n_coordinates: usize,
    ) -> Result<(Vec<f64>, Mat<f64>), ModelError> {
        let chain = self.describe("pinned-pinned bending");
        let p = self
            .pinned_bending_problem()
            .ok_or_else(|| ModelError::Numerical {
                message: format!("{chain}: no bending modes"),
            })?;
        lowest_modes(&chain, &p.k, &p.m, &p.t, &p.idx, count, n_coordinates)
    }

    /// The `count` lowest axial modes of the chain held at B with `slider_mass` (kg) moving
    /// with C along the rod (the slider-rod axial modes of the mechanism at its dead centres;
    /// the small end's mass is in the chain's own mass matrix): `(w^2, shapes)` as in
    /// [`Self::pinned_bending_modes`], over the slides (`x_C - x_B = sum_j s_j` at the straight
    /// chain, so the slider adds `m_s 1 1^T`), of unit modal mass with the slider. Needs axial
    /// springs.
    pub(crate) fn loaded_axial_modes(
        &self,
        count: usize,
        slider_mass: f64,
        n_coordinates: usize,
    ) -> Result<(Vec<f64>, Mat<f64>), ModelError> {
        let chain = self.describe("axial, held at B, the slider at C");
        let n = self.n_seg;
        if !self.axial || n < 2 {
            return Err(ModelError::Numerical {
                message: format!("{chain}: no axial springs"),
            });
        }
        let ns = n - 1;
        let s0 = 2 + n;
        let m = Mat::from_fn(ns, ns, |i, j| self.mass[(s0 + i, s0 + j)] + slider_mass);
        let k = Mat::from_fn(ns, ns, |i, j| if i == j { self.k_ax[i] } else { 0.0 });
        let slides: Vec<usize> = (s0..s0 + ns).collect();
        let all = Mat::<f64>::identity(ns, ns);
        lowest_modes(&chain, &k, &m, &all, &slides, count, n_coordinates)
    }

    /// Fixed-fixed axial frequencies, Hz (N - 2 of them; needs axial springs).
    pub(crate) fn pinned_axial_hz(&self) -> Result<Vec<f64>, ModelError> {
        let n = self.n_seg;
        if !self.axial || n < 3 {
            return Ok(Vec::new());
        }
        let ns = n - 1;
        let s0 = 2 + n;
        let m = Mat::from_fn(ns, ns, |i, j| self.mass[(s0 + i, s0 + j)]);
        let k = Mat::from_fn(ns, ns, |i, j| if i == j { self.k_ax[i] } else { 0.0 });
        let t = Mat::from_fn(ns, ns - 1, |i, j| {
            if i == j {
                1.0
            } else if i == ns - 1 {
                -1.0
            } else {
                0.0
            }
        });
        frequencies(
            &project(&k, &t),
            &project(&m, &t),
            None,
            &self.describe("fixed-fixed axial"),
        )
    }

    /// Free-free axial frequencies, Hz (N - 1 of them; needs axial springs).
    pub(crate) fn free_free_axial_hz(&self) -> Result<Vec<f64>, ModelError> {
        let n = self.n_seg;
        if !self.axial || n < 2 {
            return Ok(Vec::new());
        }
        // Coordinates [x_B, s_0..s_{N-2}].
        let idx = |i: usize| if i == 0 { 0 } else { 2 + n + (i - 1) };
        let m = Mat::from_fn(n, n, |i, j| self.mass[(idx(i), idx(j))]);
        let k = Mat::from_fn(n, n, |i, j| {
            if i == j && i > 0 {
                self.k_ax[i - 1]
            } else {
                0.0
            }
        });
        // The rigid mode has omega^2 ~ round-off; the lowest elastic one is
        // (2 sin(pi/2N))^2 k/m >= (pi/N)^2 k/m (1 - small), far above the tolerance.
        let k_min = self.k_ax.iter().cloned().fold(f64::INFINITY, f64::min);
        let k_over_m = k_min / self.mass[(0, 0)] * n as f64;
        let tol = 1e-6 * (std::f64::consts::PI / n as f64).powi(2) * k_over_m;
        frequencies(&k, &m, Some(tol), &self.describe("free-free axial"))
    }
}

/// Axial frequencies of the free-free segment chain of a rod (Huston 1991, table II), Hz,
/// ascending: `n_segments` rigid segments with axial springs in prismatic joints (`E A / l`,
/// the end ones `E A / (1.5 l)`),
/// from the linearized [`SegmentRod`] (its own mass matrix and springs). `N - 1` values.
pub fn axial_chain_frequencies_hz(
    props: RodProperties,
    n_segments: usize,
) -> Result<Vec<f64>, ModelError> {
    let rod = SegmentRod::new(props, n_segments, 0.0, true)?;
    LinearizedChain::new(&rod).free_free_axial_hz()
}
