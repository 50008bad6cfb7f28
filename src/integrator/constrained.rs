//! The saddle-point solve of a constrained mechanical system, written once: the index-1 form
//! `[M Phi_q^T; Phi_q 0] [x; mu] = [f; g]` (Hairer and Wanner, *Solving ODEs II*, section
//! VII.1; Eich-Soellner and Fuhrer, *Numerical Methods in Multibody Dynamics*, section 5.3).
//!
//! With one factorization at `q` it gives
//! - the consistent accelerations and multipliers: `f = Q(t, q, q')`, `g = gamma(t, q, q')`,
//!   so `M q'' + Phi_q^T lambda = Q`, `Phi_q q'' = gamma`;
//! - the velocity projection on `Phi_q q' + Phi_t = 0` (the M-weighted least change):
//!   `f = 0`, `g = -(Phi_q q' + Phi_t)`, `q' += x`;
//! - one simplified-Newton correction of the positions onto `Phi(q, t) = 0`: `f = 0`,
//!   `g = -Phi`, `q += x`.
//!
//! The explicit integrator, the consistent start and the joint-force outputs all use it.
//! Buffers are sized once (no allocation per solve).

use faer::Mat;

use super::dense_lu::DenseLu;
use super::failure::StepFailure;
use super::system::DaeSystem;

/// Workspace of the saddle-point solve for a system of `n` coordinates and `m` constraints.
pub struct ConstrainedSolve {
    n: usize,
    m: usize,
    lu: DenseLu,
    mass: Mat<f64>,
    jac: Mat<f64>,
    rhs: Vec<f64>,
    force: Vec<f64>,
    gamma: Vec<f64>,
    phi: Vec<f64>,
    /// Accelerations `q''` of the last [`ConstrainedSolve::accelerations`].
    pub qdd: Vec<f64>,
    /// Multipliers `lambda` of the last [`ConstrainedSolve::accelerations`].
    pub lambda: Vec<f64>,
}

impl ConstrainedSolve {
    pub fn new(n: usize, m: usize) -> ConstrainedSolve {
        ConstrainedSolve {
            n,
            m,
            lu: DenseLu::new(n + m),
            mass: Mat::zeros(n, n),
            jac: Mat::zeros(m, n),
            rhs: vec![0.0; n + m],
            force: vec![0.0; n],
            gamma: vec![0.0; m],
            phi: vec![0.0; m],
            qdd: vec![0.0; n],
            lambda: vec![0.0; m],
        }
    }

    /// For `system`'s dimensions.
    pub fn for_system(system: &dyn DaeSystem) -> ConstrainedSolve {
        Self::new(system.n_coordinates(), system.n_constraints())
    }

    /// Assemble and factor `[M Phi_q^T; Phi_q 0]` at `q`.
    pub fn factor(&mut self, system: &dyn DaeSystem, q: &[f64]) -> Result<(), StepFailure> {
        system.mass(q, self.mass.as_mut());
        system.constraint_jacobian(q, self.jac.as_mut());
        self.lu.set_saddle_point(&self.mass, 1.0, &self.jac);
        if self.lu.factor() {
            Ok(())
        } else {
            Err(StepFailure::SingularMatrix)
        }
    }

    /// Consistent accelerations and multipliers at `(t, q, v)` on the factorization at `q`,
    /// into [`Self::qdd`] and [`Self::lambda`].
    pub fn accelerations(
        &mut self,
        system: &dyn DaeSystem,
        t: f64,
        q: &[f64],
        v: &[f64],
    ) -> Result<(), StepFailure> {
        let n = self.n;
        system.constraint_acceleration_rhs(t, q, v, &mut self.gamma);
        system.forces(t, q, v, &mut self.force);
        self.rhs[..n].copy_from_slice(&self.force);
        self.rhs[n..].copy_from_slice(&self.gamma);
        self.lu.solve(&mut self.rhs);
        if self.rhs.iter().any(|x| !x.is_finite()) {
            return Err(StepFailure::NonFinite);
        }
        self.qdd.copy_from_slice(&self.rhs[..n]);
        self.lambda.copy_from_slice(&self.rhs[n..]);
        Ok(())
    }

    /// Project `v` on `Phi_q v + Phi_t = 0` (M-weighted least change) on the factorization at
    /// `q`.
    pub fn project_velocities(&mut self, system: &dyn DaeSystem, t: f64, q: &[f64], v: &mut [f64]) {
        let (n, m) = (self.n, self.m);
        system.constraint_rate(t, q, &mut self.phi);
        self.rhs[..n].iter_mut().for_each(|x| *x = 0.0);
        for k in 0..m {
            let jv: f64 = (0..n).map(|j| self.jac[(k, j)] * v[j]).sum();
            self.rhs[n + k] = -(jv + self.phi[k]);
        }
        self.lu.solve(&mut self.rhs);
        for i in 0..n {
            v[i] += self.rhs[i];
        }
    }

    /// Move `q` onto `Phi(q, t) = 0` (M-weighted least change, simplified Newton refactored at
    /// each pass) until every residual is within `tolerance`, at most `max_passes` passes.
    /// Returns the factorizations used.
    pub fn project_positions(
        &mut self,
        system: &dyn DaeSystem,
        t: f64,
        q: &mut [f64],
        tolerance: f64,
        max_passes: usize,
    ) -> Result<usize, StepFailure> {
        let (n, m) = (self.n, self.m);
        let mut factorizations = 0;
        for _ in 0..max_passes {
            system.constraints(t, q, &mut self.phi);
            if self.phi.iter().all(|x| x.abs() <= tolerance) {
                break;
            }
            self.factor(system, q)?;
            factorizations += 1;
            self.rhs[..n].iter_mut().for_each(|x| *x = 0.0);
            for k in 0..m {
                self.rhs[n + k] = -self.phi[k];
            }
            self.lu.solve(&mut self.rhs);
            for i in 0..n {
                q[i] += self.rhs[i];
            }
        }
        Ok(factorizations)
    }
}
