//! Advancing the slider-crank over one communication step: equal sub-steps no larger than the
//! solver step, each halved on failure up to `solver.max_halvings` times, then a typed error
//! with the state from before the communication step restored.

use super::crank::CrankLaw;
use super::slider_crank::{dae_context, Mechanism, OutputSolve};
use super::state::MechanismState;
use crate::error::ModelError;
use crate::integrator::DaeSystem;

/// |v_mid| / L above which the small-deformation assumption is flagged.
pub const LARGE_DEFLECTION_WARNING: f64 = 0.05;

impl Mechanism {
    /// Integrate `state` over `[t, t + h]`; on failure `state` is restored and the error says why.
    pub fn advance(&mut self, state: &mut MechanismState, h: f64) -> Result<(), ModelError> {
        self.backup.clone_from(&state.dae);
        self.integrator.forget_between_steps();
        let backup_stats = state.stats;
        let t_start = state.time;
        let t_end = t_start + h;
        let n_sub = ((h / self.max_step) * (1.0 - 1e-12)).ceil().max(1.0) as usize;
        let adaptive = self.integrator.is_adaptive();
        let result = (|| {
            if adaptive {
                self.restart_consistently(state)?;
                return self.adaptive_steps(state, t_end);
            }
            for k in 0..n_sub {
                let target = if k + 1 == n_sub {
                    t_end
                } else {
                    t_start + h * (k + 1) as f64 / n_sub as f64
                };
                self.step_with_halving(state, target, 0)?;
            }
            Ok(())
        })();
        let restore = |mech: &Mechanism, state: &mut MechanismState| {
            state.dae.clone_from(&mech.backup);
            state.time = t_start;
            state.stats = backup_stats;
        };
        match result {
            Ok(()) => {
                state.time = t_end;
                state.dae.t = t_end;
                let mut work = self
                    .output_solve
                    .take()
                    .unwrap_or_else(|| OutputSolve::new(self.rod.n_coordinates() + 1));
                let outputs = self.compute_outputs(&mut work, state);
                self.output_solve = Some(work);
                match outputs {
                    Ok(o) => {
                        state.outputs = o;
                        state.dae.amplitude = state.dae.amplitude.max(o.deflection_rel.abs());
                        self.check_large_deflection(state);
                        Ok(())
                    }
                    Err(e) => {
                        restore(self, state);
                        Err(e)
                    }
                }
            }
            Err((t_fail, h_fail, reason)) => {
                restore(self, state);
                let tries = if adaptive {
                    "the error control found no acceptable step".to_string()
                } else {
                    format!("after {} step halvings", self.max_halvings)
                };
                Err(ModelError::StepFailed {
                    time: t_fail,
                    step: h_fail,
                    reason: format!(
                        "{reason} ({tries}; the communication step started at t = {t_start} s)"
                    ),
                })
            }
        }
    }

    /// Before the steps of an adaptive integrator: where the inputs set at this communication
    /// point moved the crank off the law the state followed (a sampled motion's new angle,
    /// speed and acceleration), the positions and velocities move onto the new law's
    /// constraints by the M-weighted least change (the index-1 projection, as the fixed-step
    /// RK4 does after every step), and the accelerations and multipliers are recomputed: the
    /// jump is not charged to the error control as a local error.
    fn restart_consistently(
        &mut self,
        state: &mut MechanismState,
    ) -> Result<(), (f64, f64, String)> {
        let t = state.dae.t;
        let sys = dae_context(self.rod.as_ref(), &self.spec, state);
        let mut phi = [0.0; 4];
        sys.constraints(t, &state.dae.q, &mut phi);
        let tolerance = 1e-14 * self.rod.length();
        let mut work = self
            .output_solve
            .take()
            .unwrap_or_else(|| OutputSolve::new(self.rod.n_coordinates() + 1));
        let fail = |f: crate::integrator::StepFailure| {
            (t, 0.0, format!("restart at the communication point: {f}"))
        };
        let result = (|| {
            let positions_off = phi.iter().any(|x| x.abs() > tolerance);
            let mut rate = [0.0; 4];
            sys.constraint_rate(t, &state.dae.q, &mut rate);
            let mut velocities_off = positions_off;
            if !velocities_off {
                let previous = CrankLaw {
                    length: self.crank_length,
                    t_k: state.previous_input_time,
                    input: state.previous_input,
                };
                let (_, v_new, a_new) = sys.crank.pin(t);
                let (_, v_old, a_old) = previous.pin(t);
                velocities_off = (v_new - v_old).norm() > 1e-14 * (1.0 + v_new.norm())
                    || (a_new - a_old).norm() > 1e-12 * (1.0 + a_new.norm());
            }
            if !velocities_off {
                return Ok(());
            }
            work.solve
                .project_positions(&sys, t, &mut state.dae.q, tolerance, 4)
                .map_err(fail)?;
            work.solve.factor(&sys, &state.dae.q).map_err(fail)?;
            work.solve
                .project_velocities(&sys, t, &state.dae.q, &mut state.dae.v);
            work.solve
                .accelerations(&sys, t, &state.dae.q, &state.dae.v)
                .map_err(fail)?;
            state.dae.qdd.copy_from_slice(&work.solve.qdd);
            state.dae.acc.copy_from_slice(&work.solve.qdd);
            state.dae.lambda.copy_from_slice(&work.solve.lambda);
            Ok(())
        })();
        self.output_solve = Some(work);
        result
    }

    /// Accepted steps of an adaptive integrator until `t_end` (the last one lands on it).
    fn adaptive_steps(
        &mut self,
        state: &mut MechanismState,
        t_end: f64,
    ) -> Result<(), (f64, f64, String)> {
        while state.dae.t < t_end {
            let h_max = t_end - state.dae.t;
            let sys = dae_context(self.rod.as_ref(), &self.spec, state);
            match self.integrator.step(&sys, &mut state.dae, h_max) {
                Ok(work) => {
                    state.stats.steps += 1;
                    state.stats.newton_iterations += work as u64;
                    if state.dae.t >= t_end - 1e-12 * h_max {
                        state.dae.t = t_end;
                    }
                }
                Err(error) => {
                    state.stats.newton_iterations += error.work as u64;
                    return Err((state.dae.t, h_max, error.failure.to_string()));
                }
            }
        }
        Ok(())
    }

    /// One internal step to `target`, split in halves on failure (recursively, `depth` deep).
    fn step_with_halving(
        &mut self,
        state: &mut MechanismState,
        target: f64,
        depth: usize,
    ) -> Result<(), (f64, f64, String)> {
        let h = target - state.dae.t;
        let sys = dae_context(self.rod.as_ref(), &self.spec, state);
        match self.integrator.step(&sys, &mut state.dae, h) {
            Ok(work) => {
                state.dae.t = target;
                state.stats.steps += 1;
                state.stats.newton_iterations += work as u64;
                Ok(())
            }
            Err(error) => {
                state.stats.newton_iterations += error.work as u64;
                if depth >= self.max_halvings {
                    return Err((state.dae.t, h, error.failure.to_string()));
                }
                state.stats.halvings += 1;
                let mid = state.dae.t + 0.5 * h;
                self.step_with_halving(state, mid, depth + 1)?;
                self.step_with_halving(state, target, depth + 1)
            }
        }
    }

    fn check_large_deflection(&self, state: &mut MechanismState) {
        let d = state.outputs.deflection_rel.abs();
        if d > LARGE_DEFLECTION_WARNING && !state.large_deflection_warned {
            state.large_deflection_warned = true;
            state.warnings.push(format!(
                "rod deflection |v_mid/L| = {d:.3e} at t = {} s exceeds {LARGE_DEFLECTION_WARNING} (the small-deformation range of the rod model); results beyond it are not accurate",
                state.time
            ));
        }
    }
}
