//! What the integrator needs from a constrained mechanical system (after Project Chrono's
//! `ChIntegrable`): mass, forces, constraints and their Jacobian, and an approximate tangent.
//!
//! The system is `M(q) q'' + Phi_q(q)^T lambda = Q(t, q, q')`, `Phi(q, t) = 0`,
//! with `n` coordinates and `m` constraints. All outputs are written into caller-owned buffers
//! (no allocation).

use faer::MatMut;

use super::failure::StepFailure;

pub trait DaeSystem {
    /// Number of coordinates n.
    fn n_coordinates(&self) -> usize;
    /// Number of constraints m.
    fn n_constraints(&self) -> usize;
    /// Scale of each coordinate for the Newton convergence test (a typical magnitude).
    fn coordinate_scale(&self, i: usize) -> f64;
    /// `M(q)` into `m` (n x n, fully written).
    fn mass(&self, q: &[f64], m: MatMut<'_, f64>);
    /// Applied and inertial-velocity forces `Q(t, q, q')` into `f` (n).
    fn forces(&self, t: f64, q: &[f64], v: &[f64], f: &mut [f64]);
    /// Constraint residual `Phi(q, t)` into `phi` (m).
    fn constraints(&self, t: f64, q: &[f64], phi: &mut [f64]);
    /// Constraint Jacobian `Phi_q` into `jac` (m x n, fully written).
    fn constraint_jacobian(&self, q: &[f64], jac: MatMut<'_, f64>);
    /// `Phi_t` into `out` (m): the velocity constraint is `Phi_q q' + Phi_t = 0`.
    fn constraint_rate(&self, t: f64, q: &[f64], out: &mut [f64]);
    /// `gamma` into `out` (m): the acceleration constraint is `Phi_q q'' = gamma`.
    fn constraint_acceleration_rhs(&self, t: f64, q: &[f64], v: &[f64], out: &mut [f64]);
    /// For a partitioned integration: the dependent coordinates (all but the independent ones
    /// the integrator holds) written into `q` in closed form so that `Phi(q, t) = 0`, from
    /// the independent ones already in `q`. Returns false where the system has no closed form
    /// (the integrator then solves by Newton).
    fn solve_dependent_positions(&self, _t: f64, _q: &mut [f64]) -> bool {
        false
    }
    /// The duration over which the stated accuracy of an error-controlled run accumulates
    /// local errors, s (one period of the motion that drives the system); infinite when the
    /// system names none (then each step's error is held to the local tolerance alone).
    fn error_time_scale(&self) -> f64 {
        f64::INFINITY
    }
    /// Whether [`DaeSystem::reduced_rhs`] has a closed form for this system.
    fn has_reduced_rhs(&self) -> bool {
        false
    }
    /// For a partitioned integration, the whole right-hand side in closed form (minimal
    /// coordinates): with the independent coordinates already in `q` and `v` (and the
    /// dependent positions of the last evaluation in `q`, which pick the assembly branch),
    /// write the dependent positions and velocities into `q` and `v` (so that `Phi = 0` and
    /// `Phi_q q' + Phi_t = 0`), all accelerations into `qdd` and the multipliers into `lambda`,
    /// from one evaluation of `M q'' + Phi_q^T lambda = Q`, `Phi_q q'' = gamma`. With
    /// `lambda = None` (an intermediate stage) the system may skip what only a state needs:
    /// the multipliers, the dependent velocities and accelerations, and dependent coordinates
    /// that no acceleration needs (the FFR frame angle itself, whose sine and cosine are all
    /// the equations use); the independent accelerations are always written. Returns `None` where
    /// the system has no closed form (the integrator then takes the general path).
    fn reduced_rhs(
        &self,
        _t: f64,
        _q: &mut [f64],
        _v: &mut [f64],
        _qdd: &mut [f64],
        _lambda: Option<&mut [f64]>,
    ) -> Option<Result<(), StepFailure>> {
        None
    }
    /// Add `c_k (K_t + d(Phi_q^T lambda)/dq) + c_d C_t` to `out` (n x n), with `K_t = -dQ/dq`
    /// and `C_t = -dQ/dq'` (approximations are fine: they only steer Newton).
    fn add_tangent(
        &self,
        q: &[f64],
        v: &[f64],
        lambda: &[f64],
        c_k: f64,
        c_d: f64,
        out: MatMut<'_, f64>,
    );
}

/// A system seen without its closed form ([`DaeSystem::reduced_rhs`]): an integrator then
/// takes the general path (for comparisons and benchmarks of the two).
pub struct GeneralPath<'a>(pub &'a dyn DaeSystem);

impl DaeSystem for GeneralPath<'_> {
    fn n_coordinates(&self) -> usize {
        self.0.n_coordinates()
    }
    fn n_constraints(&self) -> usize {
        self.0.n_constraints()
    }
    fn coordinate_scale(&self, i: usize) -> f64 {
        self.0.coordinate_scale(i)
    }
    fn error_time_scale(&self) -> f64 {
        self.0.error_time_scale()
    }
    fn mass(&self, q: &[f64], m: MatMut<'_, f64>) {
        self.0.mass(q, m)
    }
    fn forces(&self, t: f64, q: &[f64], v: &[f64], f: &mut [f64]) {
        self.0.forces(t, q, v, f)
    }
    fn constraints(&self, t: f64, q: &[f64], phi: &mut [f64]) {
        self.0.constraints(t, q, phi)
    }
    fn constraint_jacobian(&self, q: &[f64], jac: MatMut<'_, f64>) {
        self.0.constraint_jacobian(q, jac)
    }
    fn constraint_rate(&self, t: f64, q: &[f64], out: &mut [f64]) {
        self.0.constraint_rate(t, q, out)
    }
    fn constraint_acceleration_rhs(&self, t: f64, q: &[f64], v: &[f64], out: &mut [f64]) {
        self.0.constraint_acceleration_rhs(t, q, v, out)
    }
    fn solve_dependent_positions(&self, t: f64, q: &mut [f64]) -> bool {
        self.0.solve_dependent_positions(t, q)
    }
    fn add_tangent(
        &self,
        q: &[f64],
        v: &[f64],
        lambda: &[f64],
        c_k: f64,
        c_d: f64,
        out: MatMut<'_, f64>,
    ) {
        self.0.add_tangent(q, v, lambda, c_k, c_d, out)
    }
}
