//! Classic fourth-order Runge-Kutta on the index-1 form of the constrained equations, with
//! coordinate projection (Hairer and Wanner, *Solving ODEs II*, section VII.2; Eich-Soellner
//! and Fuhrer, *Numerical Methods in Multibody Dynamics*, section 5.3): an explicit path for
//! scenes whose retained modes are not stiff (stable for `w_max h < 2.78`).
//!
//! Accelerations and multipliers at `(t, q, v)` from
//! `[M Phi_q^T; Phi_q 0] [q''; lambda] = [Q; gamma]` ([`ConstrainedSolve`]). One step:
//! `k_i = (v_i, q''_i)` at the four stages, `y_{n+1} = y_n + h/6 (k1 + 2 k2 + 2 k3 + k4)`, then
//! positions projected on `Phi(q, t_{n+1}) = 0` and velocities on `Phi_q v + Phi_t = 0`; the
//! accelerations and multipliers at the projected state are stored and serve as `k1` of the
//! next step.

use super::constrained::ConstrainedSolve;
use super::failure::{StepError, StepFailure};
use super::state::DaeState;
use super::system::DaeSystem;
use super::Integrator;

/// The explicit integrator and its workspace (sized once).
pub struct ExplicitRk4 {
    n: usize,
    solve: ConstrainedSolve,
    q: Vec<f64>,
    v: Vec<f64>,
    sum_q: Vec<f64>,
    sum_v: Vec<f64>,
    kq: Vec<f64>,
    kv: Vec<f64>,
}

impl ExplicitRk4 {
    pub fn new(system: &dyn DaeSystem) -> Self {
        let n = system.n_coordinates();
        ExplicitRk4 {
            n,
            solve: ConstrainedSolve::for_system(system),
            q: vec![0.0; n],
            v: vec![0.0; n],
            sum_q: vec![0.0; n],
            sum_v: vec![0.0; n],
            kq: vec![0.0; n],
            kv: vec![0.0; n],
        }
    }

    /// The step of [`Integrator::step`], counting factorizations in `work`.
    fn try_step(
        &mut self,
        system: &dyn DaeSystem,
        state: &mut DaeState,
        h: f64,
        work: &mut usize,
    ) -> Result<(), StepFailure> {
        let n = self.n;
        let t0 = state.t;
        let t1 = t0 + h;
        // k1 = (v_n, q''_n): the stored consistent accelerations of the state.
        self.kq.copy_from_slice(&state.v);
        self.kv.copy_from_slice(&state.qdd);
        self.sum_q.copy_from_slice(&state.v);
        self.sum_v.copy_from_slice(&state.qdd);
        for (c, weight, t) in [
            (0.5, 2.0, t0 + 0.5 * h),
            (0.5, 2.0, t0 + 0.5 * h),
            (1.0, 1.0, t1),
        ] {
            for i in 0..n {
                self.q[i] = state.q[i] + c * h * self.kq[i];
                self.v[i] = state.v[i] + c * h * self.kv[i];
            }
            self.solve.factor(system, &self.q)?;
            *work += 1;
            self.solve.accelerations(system, t, &self.q, &self.v)?;
            self.kq.copy_from_slice(&self.v);
            self.kv.copy_from_slice(&self.solve.qdd);
            for i in 0..n {
                self.sum_q[i] += weight * self.kq[i];
                self.sum_v[i] += weight * self.kv[i];
            }
        }
        for i in 0..n {
            self.q[i] = state.q[i] + h / 6.0 * self.sum_q[i];
            self.v[i] = state.v[i] + h / 6.0 * self.sum_v[i];
        }
        let tolerance = 1e-14 * system.coordinate_scale(0);
        *work += self
            .solve
            .project_positions(system, t1, &mut self.q, tolerance, 4)?;
        self.solve.factor(system, &self.q)?;
        *work += 1;
        self.solve
            .project_velocities(system, t1, &self.q, &mut self.v);
        // Consistent accelerations and multipliers of the new state (the next step's k1).
        self.solve.accelerations(system, t1, &self.q, &self.v)?;
        if self.q.iter().chain(&self.v).any(|x| !x.is_finite()) {
            return Err(StepFailure::NonFinite);
        }
        // RK4 keeps no algorithmic acceleration: `acc` is the true one.
        state.accept(
            t1,
            &self.q,
            &self.v,
            &self.solve.qdd,
            &self.solve.qdd,
            &self.solve.lambda,
        );
        Ok(())
    }
}

impl Integrator for ExplicitRk4 {
    fn step(
        &mut self,
        system: &dyn DaeSystem,
        state: &mut DaeState,
        h: f64,
    ) -> Result<usize, StepError> {
        let mut work = 0;
        match self.try_step(system, state, h, &mut work) {
            Ok(()) => Ok(work),
            Err(failure) => Err(failure.after(work)),
        }
    }

    fn name(&self) -> &'static str {
        "RK4 (explicit, projected)"
    }

    fn work_unit(&self) -> &'static str {
        "factorizations"
    }
}
