//! Generalized-alpha for index-3 DAEs (Arnold and Bruls 2007, section 3 and eq. 10-12).
//!
//! Parameters from the spectral radius at infinity `rho_inf` in [0, 1] (Chung and Hulbert
//! 1993, eq. 25; Arnold and Bruls eq. 24):
//! `alpha_m = (2 rho - 1) / (rho + 1)`, `alpha_f = rho / (rho + 1)`,
//! `gamma = 1/2 + alpha_f - alpha_m`, `beta = (gamma + 1/2)^2 / 4`.
//! One step from `t_n` to `t_{n+1} = t_n + h`:
//! `q_{n+1} = q_n + h q'_n + h^2 (1/2 - beta) a_n + h^2 beta a_{n+1}`,
//! `q'_{n+1} = q'_n + h (1 - gamma) a_n + h gamma a_{n+1}`,
//! `(1 - alpha_m) a_{n+1} + alpha_m a_n = (1 - alpha_f) q''_{n+1} + alpha_f q''_n`,
//! with `M q''_{n+1} + Phi_q^T lambda_{n+1} = Q` and `Phi(q_{n+1}, t_{n+1}) = 0` solved by
//! Newton in the unknowns `(q_{n+1}, lambda_{n+1})`. The iteration matrix is scaled after
//! Bottasso, Dopico and Trainelli (2008): the equilibrium rows by `beta h^2` and the
//! multipliers by `1 / (beta h^2)`, so that every block is O(1) as h -> 0:
//! `[M (1 - alpha_m)/(1 - alpha_f) + gamma h C_t + beta h^2 K_t, Phi_q^T; Phi_q, 0]`.
//! The matrix is factored at the first iteration and again only when the contraction is poor
//! (modified Newton).

use faer::Mat;

use super::dense_lu::DenseLu;
use super::failure::{StepError, StepFailure};
use super::state::DaeState;
use super::system::DaeSystem;
use super::{quantize_step, Integrator};

/// Method coefficients.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AlphaCoefficients {
    pub alpha_m: f64,
    pub alpha_f: f64,
    pub gamma: f64,
    pub beta: f64,
}

impl AlphaCoefficients {
    /// From the spectral radius at infinity, clamped to [0, 1].
    pub fn from_rho_inf(rho: f64) -> Self {
        let rho = rho.clamp(0.0, 1.0);
        let alpha_m = (2.0 * rho - 1.0) / (rho + 1.0);
        let alpha_f = rho / (rho + 1.0);
        let gamma = 0.5 + alpha_f - alpha_m;
        let beta = 0.25 * (gamma + 0.5).powi(2);
        AlphaCoefficients {
            alpha_m,
            alpha_f,
            gamma,
            beta,
        }
    }
}

/// Settings of the error control of the adaptive generalized-alpha method.
#[derive(Clone, Debug)]
pub struct AlphaErrorControl {
    /// Local tolerance per unit amplitude.
    pub tolerance: f64,
    /// Floor `A_min` of the amplitude scale (dimensionless, like `v_mid / L`).
    pub amplitude_floor: f64,
    /// First step when the state has no proposal yet, s.
    pub initial_step: f64,
    /// Rejected tries of one step before it counts as failed.
    pub max_rejections: usize,
}

/// The integrator and its workspace (sized once for one system).
pub struct GeneralizedAlpha {
    pub coefficients: AlphaCoefficients,
    /// Error control (adaptive steps), or fixed steps when `None`.
    pub adaptive: Option<AlphaErrorControl>,
    /// The amplitude `A` the accuracy refers to ([`Integrator::set_amplitude`]).
    amplitude: f64,
    pub tolerance: f64,
    pub max_iterations: usize,
    n: usize,
    m: usize,
    lu: DenseLu,
    mass: Mat<f64>,
    jac: Mat<f64>,
    force: Vec<f64>,
    phi: Vec<f64>,
    rhs: Vec<f64>,
    trial: DaeState,
    /// The step size the current factorization was made for (reused across steps).
    factored_for: Option<f64>,
}

impl GeneralizedAlpha {
    pub fn new(
        system: &dyn DaeSystem,
        rho_inf: f64,
        tolerance: f64,
        max_iterations: usize,
    ) -> Self {
        let n = system.n_coordinates();
        let m = system.n_constraints();
        GeneralizedAlpha {
            coefficients: AlphaCoefficients::from_rho_inf(rho_inf),
            tolerance,
            max_iterations,
            n,
            m,
            lu: DenseLu::new(n + m),
            mass: Mat::zeros(n, n),
            jac: Mat::zeros(m, n),
            force: vec![0.0; n],
            phi: vec![0.0; m],
            rhs: vec![0.0; n + m],
            trial: DaeState::zeros(n, m),
            factored_for: None,
            adaptive: None,
            amplitude: 0.0,
        }
    }

    /// The local error estimate of the accepted try in `self.trial` against `state`, scaled:
    /// `e = (beta - 1/6) h^2 (a_{n+1} - a_n)` (the Newmark truncation error, Zienkiewicz and Xie
    /// 1991, "A simple error estimator and adaptive time stepping procedure for dynamic
    /// analysis", Earthquake Eng. Struct. Dyn. 20, eq. 10, with the algorithmic accelerations),
    /// over `tol max(A, A_min) s_i` per coordinate (see [`AlphaErrorControl`]).
    fn error_norm(&self, system: &dyn DaeSystem, state: &DaeState, h: f64) -> f64 {
        let control = self.adaptive.as_ref().expect("adaptive");
        let c = (self.coefficients.beta - 1.0 / 6.0).abs() * h * h;
        // Not below what the Newton iteration resolves (its tolerance on the scaled correction).
        let tol = (control.tolerance * self.amplitude.max(control.amplitude_floor))
            .max(10.0 * self.tolerance);
        let mut err: f64 = 0.0;
        for i in 0..self.n {
            let e = c * (self.trial.acc[i] - state.acc[i]);
            err = err.max(e.abs() / (tol * system.coordinate_scale(i)));
        }
        err
    }

    /// Adaptive step: tries of the state's proposed step (stretched to `h_max` within 25 %),
    /// shrunk on a failed Newton iteration or a local error above the tolerance.
    fn adaptive_step(
        &mut self,
        system: &dyn DaeSystem,
        state: &mut DaeState,
        h_max: f64,
    ) -> Result<usize, StepError> {
        let control = self.adaptive.clone().expect("adaptive");
        let proposal = if state.step_hint > 0.0 {
            state.step_hint
        } else {
            control.initial_step
        }
        .min(super::MAX_ADAPTIVE_STEP);
        let mut h = if h_max <= 1.25 * proposal {
            h_max
        } else {
            proposal
        };
        let mut work = 0;
        let mut last = StepFailure::NonFinite;
        let mut rejected = false;
        for _ in 0..=control.max_rejections {
            let mut iterations = 0;
            let err = match self.try_step(system, state, h, &mut iterations) {
                Ok(_) => self.error_norm(system, state, h),
                Err(failure) => {
                    last = failure;
                    f64::INFINITY
                }
            };
            work += iterations;
            if err <= 1.0 {
                let grow = if err == 0.0 {
                    2.0
                } else {
                    (0.9 * err.powf(-1.0 / 3.0)).clamp(0.3, 2.0)
                };
                let mut next = h * if rejected { grow.min(1.0) } else { grow };
                if h == h_max && h < proposal {
                    next = next.max(proposal);
                }
                let tr = &self.trial;
                state.accept(state.t + h, &tr.q, &tr.v, &tr.qdd, &tr.acc, &tr.lambda);
                state.step_hint = quantize_step(next);
                return Ok(work);
            }
            rejected = true;
            h = quantize_step(
                h * if err.is_finite() {
                    (0.9 * err.powf(-1.0 / 3.0)).clamp(0.2, 0.9)
                } else {
                    0.5
                },
            );
            if h < 1e-14 * (1.0 + state.t.abs()) {
                break;
            }
        }
        Err(last.after(work))
    }

    /// One try of the step of [`Integrator::step`] into `self.trial` (the state untouched);
    /// Newton iterations counted in `work`.
    fn try_step(
        &mut self,
        system: &dyn DaeSystem,
        state: &mut DaeState,
        h: f64,
        work: &mut usize,
    ) -> Result<usize, StepFailure> {
        let (n, m) = (self.n, self.m);
        let AlphaCoefficients {
            alpha_m,
            alpha_f,
            gamma,
            beta,
        } = self.coefficients;
        let t1 = state.t + h;
        let s = beta * h * h;
        let beta_p = (1.0 - alpha_m) / (beta * h * h * (1.0 - alpha_f));
        let gamma_p = gamma / (beta * h);
        let mass_factor = (1.0 - alpha_m) / (1.0 - alpha_f);

        // Predictor: q''_{n+1} = q''_n, lambda_{n+1} = lambda_n.
        let tr = &mut self.trial;
        tr.t = t1;
        for i in 0..n {
            let qdd = state.qdd[i];
            let acc = (alpha_f * state.qdd[i] - alpha_m * state.acc[i] + (1.0 - alpha_f) * qdd)
                / (1.0 - alpha_m);
            tr.qdd[i] = qdd;
            tr.acc[i] = acc;
            tr.q[i] =
                state.q[i] + h * state.v[i] + h * h * ((0.5 - beta) * state.acc[i] + beta * acc);
            tr.v[i] = state.v[i] + h * ((1.0 - gamma) * state.acc[i] + gamma * acc);
        }
        tr.lambda.copy_from_slice(&state.lambda);

        // Modified Newton: the factorization of an earlier step with the same h is reused; it
        // is refreshed when the contraction is poor.
        let mut factored = self.factored_for == Some(h);
        let mut previous = f64::INFINITY;
        for iteration in 0..self.max_iterations {
            *work = iteration + 1;
            let tr = &mut self.trial;
            system.mass(&tr.q, self.mass.as_mut());
            system.forces(t1, &tr.q, &tr.v, &mut self.force);
            system.constraint_jacobian(&tr.q, self.jac.as_mut());
            system.constraints(t1, &tr.q, &mut self.phi);
            for i in 0..n {
                let mut r = -self.force[i];
                for j in 0..n {
                    r += self.mass[(i, j)] * tr.qdd[j];
                }
                for k in 0..m {
                    r += self.jac[(k, i)] * tr.lambda[k];
                }
                self.rhs[i] = -s * r;
            }
            for k in 0..m {
                self.rhs[n + k] = -self.phi[k];
            }
            if !factored {
                self.lu.set_saddle_point(&self.mass, mass_factor, &self.jac);
                system.add_tangent(
                    &tr.q,
                    &tr.v,
                    &tr.lambda,
                    s,
                    gamma * h,
                    self.lu.matrix.as_mut().submatrix_mut(0, 0, n, n),
                );
                if !self.lu.factor() {
                    self.factored_for = None;
                    return Err(StepFailure::SingularMatrix);
                }
                factored = true;
                self.factored_for = Some(h);
            }
            self.lu.solve(&mut self.rhs);
            let mut err: f64 = 0.0;
            for i in 0..n {
                let dq = self.rhs[i];
                tr.q[i] += dq;
                tr.v[i] += gamma_p * dq;
                tr.qdd[i] += beta_p * dq;
                err = err.max((dq / system.coordinate_scale(i)).abs());
            }
            for k in 0..m {
                tr.lambda[k] += self.rhs[n + k] / s;
            }
            if !err.is_finite() {
                self.factored_for = None;
                return Err(StepFailure::NonFinite);
            }
            // Converged, or stagnating at round-off within 100 x the tolerance (large
            // deflections: the correction stops shrinking at the floating-point floor).
            let stagnated = iteration >= 2 && err <= 100.0 * self.tolerance && err > 0.5 * previous;
            if err <= self.tolerance || stagnated {
                for i in 0..n {
                    tr.acc[i] = (alpha_f * state.qdd[i] - alpha_m * state.acc[i]
                        + (1.0 - alpha_f) * tr.qdd[i])
                        / (1.0 - alpha_m);
                }
                if tr.lambda.iter().any(|x| !x.is_finite()) {
                    return Err(StepFailure::NonFinite);
                }
                return Ok(iteration + 1);
            }
            // Refactor when the contraction is poor.
            if err > 0.25 * previous {
                factored = false;
            }
            previous = err;
            if iteration + 1 == self.max_iterations {
                self.factored_for = None;
                return Err(StepFailure::NewtonDiverged {
                    iterations: self.max_iterations,
                    last_correction: err,
                });
            }
        }
        Err(StepFailure::NewtonDiverged {
            iterations: self.max_iterations,
            last_correction: previous,
        })
    }
}

impl Integrator for GeneralizedAlpha {
    fn set_amplitude(&mut self, amplitude: f64) {
        self.amplitude = amplitude;
    }

    fn step(
        &mut self,
        system: &dyn DaeSystem,
        state: &mut DaeState,
        h: f64,
    ) -> Result<usize, StepError> {
        if self.adaptive.is_some() {
            return self.adaptive_step(system, state, h);
        }
        let mut work = 0;
        self.try_step(system, state, h, &mut work)
            .map_err(|failure| failure.after(work))?;
        let tr = &self.trial;
        state.accept(state.t + h, &tr.q, &tr.v, &tr.qdd, &tr.acc, &tr.lambda);
        Ok(work)
    }

    fn is_adaptive(&self) -> bool {
        self.adaptive.is_some()
    }

    /// Forget the kept factorization. Called at every communication step, so that the result
    /// of a step depends on the state alone (a restored state replays bit for bit).
    fn forget_between_steps(&mut self) {
        self.factored_for = None;
    }

    fn name(&self) -> &'static str {
        "generalized-alpha"
    }

    fn work_unit(&self) -> &'static str {
        "Newton iterations"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coefficients_match_arnold_bruls() {
        let c = AlphaCoefficients::from_rho_inf(1.0);
        assert!((c.alpha_m - 0.5).abs() < 1e-15 && (c.alpha_f - 0.5).abs() < 1e-15);
        assert!((c.gamma - 0.5).abs() < 1e-15 && (c.beta - 0.25).abs() < 1e-15);
        let c = AlphaCoefficients::from_rho_inf(0.0);
        assert!((c.alpha_m + 1.0).abs() < 1e-15 && c.alpha_f.abs() < 1e-15);
        assert!((c.gamma - 1.5).abs() < 1e-15 && (c.beta - 1.0).abs() < 1e-15);
    }
}
