//! Classic fourth-order Runge-Kutta on the index-1 form of the constrained equations, with
//! coordinate projection (Hairer and Wanner, *Solving ODEs II*, section VII.2; Eich-Soellner
//! and Fuhrer, *Numerical Methods in Multibody Dynamics*, section 5.3): an explicit path for
//! scenes whose retained modes are not stiff (stable for `w_max h < 2.78`).
//!
//! Accelerations and multipliers at `(t, q, v)` from
//! `[M Phi_q^T; Phi_q 0] [q''; lambda] = [Q; gamma]`. One step:
//! `k_i = (v_i, q''_i)` at the four stages, `y_{n+1} = y_n + h/6 (k1 + 2 k2 + 2 k3 + k4)`, then
//! positions projected on `Phi(q, t_{n+1}) = 0` (Newton, `[M Phi_q^T; Phi_q 0] [dq; mu] = [0; -Phi]`)
//! and velocities on `Phi_q v + Phi_t = 0` the same way; the accelerations and multipliers at the
//! projected state are stored and serve as `k1` of the next step.

use faer::Mat;

use super::dense_lu::DenseLu;
use super::generalized_alpha::{DaeState, StepFailure};
use super::system::DaeSystem;

/// The explicit integrator and its workspace (sized once).
pub struct ExplicitRk4 {
    n: usize,
    m: usize,
    lu: DenseLu,
    mass: Mat<f64>,
    jac: Mat<f64>,
    force: Vec<f64>,
    gamma: Vec<f64>,
    rhs: Vec<f64>,
    q: Vec<f64>,
    v: Vec<f64>,
    sum_q: Vec<f64>,
    sum_v: Vec<f64>,
    kq: Vec<f64>,
    kv: Vec<f64>,
    phi: Vec<f64>,
    stage_a: Vec<f64>,
    stage_lambda: Vec<f64>,
}

impl ExplicitRk4 {
    pub fn new(system: &dyn DaeSystem) -> Self {
        let n = system.n_coordinates();
        let m = system.n_constraints();
        ExplicitRk4 {
            n,
            m,
            lu: DenseLu::new(n + m),
            mass: Mat::zeros(n, n),
            jac: Mat::zeros(m, n),
            force: vec![0.0; n],
            gamma: vec![0.0; m],
            rhs: vec![0.0; n + m],
            q: vec![0.0; n],
            v: vec![0.0; n],
            sum_q: vec![0.0; n],
            sum_v: vec![0.0; n],
            kq: vec![0.0; n],
            kv: vec![0.0; n],
            phi: vec![0.0; m],
            stage_a: vec![0.0; n],
            stage_lambda: vec![0.0; m],
        }
    }

    /// Factor the saddle-point matrix at `q`.
    fn factor_at(&mut self, system: &dyn DaeSystem, q: &[f64]) -> Result<(), StepFailure> {
        system.mass(q, self.mass.as_mut());
        system.constraint_jacobian(q, self.jac.as_mut());
        self.lu.set_saddle_point(&self.mass, 1.0, &self.jac);
        if self.lu.factor() {
            Ok(())
        } else {
            Err(StepFailure::SingularMatrix)
        }
    }

    /// Accelerations and multipliers at `(t, self.q, self.v)` into `stage_a`, `stage_lambda`.
    /// The forces may depend on the accelerations and multipliers (axial stiffening): the solve
    /// is repeated on the same factorization until they settle (fixed point, starting from the
    /// previous stage's values).
    fn accelerations(&mut self, system: &dyn DaeSystem, t: f64) -> Result<(), StepFailure> {
        let q = std::mem::take(&mut self.q);
        let result = self.factor_at(system, &q);
        self.q = q;
        result?;
        self.solve_accelerations(system, t)
    }

    /// The fixed-point solve of [`Self::accelerations`] on the current factorization.
    fn solve_accelerations(&mut self, system: &dyn DaeSystem, t: f64) -> Result<(), StepFailure> {
        let (n, m) = (self.n, self.m);
        system.constraint_acceleration_rhs(t, &self.q, &self.v, &mut self.gamma);
        let passes = if system.forces_depend_on_accelerations() {
            8
        } else {
            1
        };
        for _ in 0..passes {
            system.forces(
                t,
                &self.q,
                &self.v,
                &self.stage_a,
                &self.stage_lambda,
                &mut self.force,
            );
            self.rhs[..n].copy_from_slice(&self.force);
            self.rhs[n..].copy_from_slice(&self.gamma);
            self.lu.solve(&mut self.rhs);
            if self.rhs.iter().any(|x| !x.is_finite()) {
                return Err(StepFailure::NonFinite);
            }
            let mut change: f64 = 0.0;
            let mut size: f64 = 0.0;
            for i in 0..n {
                change = change.max((self.rhs[i] - self.stage_a[i]).abs());
                size = size.max(self.rhs[i].abs());
            }
            self.stage_a.copy_from_slice(&self.rhs[..n]);
            self.stage_lambda.copy_from_slice(&self.rhs[n..n + m]);
            if change <= 1e-13 * size {
                break;
            }
        }
        Ok(())
    }

    /// Advance `state` by `h`; on failure `state` is untouched. Returns the number of
    /// factorizations used (reported as iterations).
    pub fn step(
        &mut self,
        system: &dyn DaeSystem,
        state: &mut DaeState,
        h: f64,
    ) -> Result<usize, StepFailure> {
        let (n, m) = (self.n, self.m);
        let t0 = state.t;
        let t1 = t0 + h;
        let mut factorizations = 0;
        // k1 = (v_n, q''_n): the stored consistent accelerations of the state.
        self.kq.copy_from_slice(&state.v);
        self.kv.copy_from_slice(&state.qdd);
        self.sum_q.copy_from_slice(&state.v);
        self.sum_v.copy_from_slice(&state.qdd);
        self.stage_a.copy_from_slice(&state.qdd);
        self.stage_lambda.copy_from_slice(&state.lambda);
        for (c, weight, t) in [
            (0.5, 2.0, t0 + 0.5 * h),
            (0.5, 2.0, t0 + 0.5 * h),
            (1.0, 1.0, t1),
        ] {
            for i in 0..n {
                self.q[i] = state.q[i] + c * h * self.kq[i];
                self.v[i] = state.v[i] + c * h * self.kv[i];
            }
            self.accelerations(system, t)?;
            factorizations += 1;
            self.kq.copy_from_slice(&self.v);
            self.kv.copy_from_slice(&self.stage_a);
            for i in 0..n {
                self.sum_q[i] += weight * self.kq[i];
                self.sum_v[i] += weight * self.kv[i];
            }
        }
        for i in 0..n {
            self.q[i] = state.q[i] + h / 6.0 * self.sum_q[i];
            self.v[i] = state.v[i] + h / 6.0 * self.sum_v[i];
        }
        // Positions onto Phi(q, t1) = 0 (M-weighted least change, simplified Newton).
        let tolerance = 1e-14 * system.coordinate_scale(0);
        for _ in 0..4 {
            system.constraints(t1, &self.q, &mut self.phi);
            if self.phi.iter().all(|x| x.abs() <= tolerance) {
                break;
            }
            let q = std::mem::take(&mut self.q);
            let result = self.factor_at(system, &q);
            self.q = q;
            result?;
            factorizations += 1;
            self.rhs[..n].iter_mut().for_each(|x| *x = 0.0);
            for k in 0..m {
                self.rhs[n + k] = -self.phi[k];
            }
            self.lu.solve(&mut self.rhs);
            for i in 0..n {
                self.q[i] += self.rhs[i];
            }
        }
        // Velocities onto Phi_q v + Phi_t = 0 at the projected positions.
        let q = std::mem::take(&mut self.q);
        let result = self.factor_at(system, &q);
        self.q = q;
        result?;
        factorizations += 1;
        system.constraint_rate(t1, &self.q, &mut self.phi);
        self.rhs[..n].iter_mut().for_each(|x| *x = 0.0);
        for k in 0..m {
            let jv: f64 = (0..n).map(|j| self.jac[(k, j)] * self.v[j]).sum();
            self.rhs[n + k] = -(jv + self.phi[k]);
        }
        self.lu.solve(&mut self.rhs);
        for i in 0..n {
            self.v[i] += self.rhs[i];
        }
        // Consistent accelerations and multipliers of the new state (the next step's k1).
        self.solve_accelerations(system, t1)?;
        if self.q.iter().chain(&self.v).any(|x| !x.is_finite()) {
            return Err(StepFailure::NonFinite);
        }
        // RK4 keeps no algorithmic acceleration: `acc` is the true one.
        state.accept(
            t1,
            &self.q,
            &self.v,
            &self.stage_a,
            &self.stage_a,
            &self.stage_lambda,
        );
        Ok(factorizations)
    }
}
