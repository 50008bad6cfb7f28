//! Advancing the slider-crank over one communication step: equal sub-steps no larger than the
//! solver step, each halved on failure up to `solver.max_halvings` times, then a typed error
//! with the state from before the communication step restored.

use super::crank::CrankLaw;
use super::slider_crank::{dae_context, AheadBackup, Mechanism, OutputSolve};
use super::state::{MechanismState, StepStats};
use crate::error::ModelError;
use crate::integrator::MAX_ADAPTIVE_STEP;
use crate::rod::DeflectionPolicy;
use crate::text::time;

/// |v_mid| / L above which the small-deformation assumption is flagged.
pub const LARGE_DEFLECTION_WARNING: f64 = 0.05;

/// Most internal steps one communication step may take (fixed-step sub-steps before it starts,
/// accepted adaptive steps while it runs; about 1 to 10 s of work at the benchmark sizes).
/// A longer communication step is refused with the state kept (`ModelError::TooMuchWork`).
pub const MAX_INTERNAL_STEPS: u64 = 100_000;

pub use crate::rod::cost::WORK_BUDGET;

/// Largest `solver.max_halvings` (checked by the scene validation): a failed step is split
/// into at most `2^20` pieces, the smallest `1e-6` of it.
pub const MAX_HALVINGS: usize = 20;

/// Largest magnitude of an accepted output, in its SI unit (N, N m, m, m/s): anything larger is
/// a diverged integration, refused like a failed step.
pub const MAX_OUTPUT_MAGNITUDE: f64 = 1e12;

impl Mechanism {
    /// Integrate `state` over `[t, t + h]`; on failure `state` is restored and the error says why.
    pub fn advance(&mut self, state: &mut MechanismState, h: f64) -> Result<(), ModelError> {
        let t_start = state.time;
        self.check_work(t_start, h)?;
        self.call_deadline =
            std::time::Instant::now() + std::time::Duration::from_secs_f64(WALL_GUARD_SECONDS);
        self.backup.clone_from(&state.dae);
        self.ahead_backup = if state.ahead.held {
            AheadBackup::Untouched
        } else {
            AheadBackup::NoneHeld
        };
        self.integrator.forget_between_steps();
        let backup_stats = state.stats;
        let backup_amplitude = state.amplitude;
        let t_end = t_start + h;
        let adaptive = self.integrator.is_adaptive();
        let result = (|| {
            if adaptive {
                // The closed form on minimal coordinates keeps the constraints exactly: a crank
                // law set before the last step's end (no new input since) is the law that
                // step ended on, and the state is consistent with it without a check.
                let unchanged_law = state.stats.steps > 0
                    && self.rod.ffr_kernel().is_some()
                    && (state.input_time < state.dae.t || input_continues_law(state));
                let stale = !unchanged_law && self.restart_consistently(state)?;
                let new_inputs = stale || !self.slider_force_consistent(state);
                // A new jerk with the same angle, speed and acceleration now: the accelerations
                // stand (the first stage is the last one), the law after now does not.
                let new_jerk = state.input_time == state.dae.t && jerk_changed(state);
                if new_inputs || new_jerk {
                    // A step held ahead was taken under the old inputs.
                    state.ahead.held = false;
                }
                if !new_inputs {
                    self.integrator.reuse_first_stage();
                }
                return self.adaptive_steps(state, t_end, h, !(new_inputs || new_jerk));
            }
            let n_sub = ((h / self.max_step) * (1.0 - 1e-12)).ceil().max(1.0) as usize;
            for k in 0..n_sub {
                let target = if k + 1 == n_sub {
                    t_end
                } else {
                    t_start + h * (k + 1) as f64 / n_sub as f64
                };
                self.step_with_halving(state, target, &backup_stats)?;
            }
            Ok(())
        })();
        let restore = |mech: &Mechanism, state: &mut MechanismState| {
            state.dae.clone_from(&mech.backup);
            match mech.ahead_backup {
                AheadBackup::NoneHeld => state.ahead.held = false,
                AheadBackup::Untouched => state.ahead.held = true,
                AheadBackup::Saved => state.ahead.clone_from(&mech.backup_ahead),
            }
            state.time = t_start;
            state.stats = backup_stats;
            state.amplitude = backup_amplitude;
        };
        match result {
            Ok(()) => {
                state.time = t_end;
                state.dae.t = t_end;
                let outputs = if self.state_is_consistent(state) {
                    self.compute_outputs(None, state)
                } else {
                    let mut work = self
                        .output_solve
                        .take()
                        .unwrap_or_else(|| OutputSolve::new(self.rod.n_coordinates() + 1));
                    let outputs = self.compute_outputs(Some(&mut work), state);
                    self.output_solve = Some(work);
                    outputs
                }
                .and_then(|o| check_finite(state, &o, t_start, h).map(|()| o));
                match outputs {
                    Ok(o) => match self.check_large_deflection(state, &o) {
                        Ok(()) => {
                            state.outputs = o;
                            state.amplitude = state.amplitude.max(o.deflection_rel.abs());
                            Ok(())
                        }
                        Err(e) => {
                            restore(self, state);
                            Err(e)
                        }
                    },
                    Err(e) => {
                        restore(self, state);
                        Err(e)
                    }
                }
            }
            Err((t_fail, _, reason)) if reason == TOO_MANY_STEPS => {
                restore(self, state);
                Err(ModelError::TooMuchWork {
                    time: t_start,
                    step: h,
                    message: format!(
                        "the error control took {MAX_INTERNAL_STEPS} internal steps and reached only t = {} s of t = {} s, allowed at most {MAX_INTERNAL_STEPS} per communication step",
                        time(t_fail),
                        time(t_end)
                    ),
                })
            }
            Err((t_fail, _, reason)) if reason == OVER_BUDGET => {
                restore(self, state);
                let cost = self.evaluation_cost();
                Err(ModelError::TooMuchWork {
                    time: t_start,
                    step: h,
                    message: format!(
                        "it reached only t = {} s of t = {} s within the work budget of one call ({} evaluations of {cost:.3e} work units each for this model, WORK_BUDGET / cost, and at most {WALL_GUARD_SECONDS} s), allowed at most that much work per communication step",
                        time(t_fail),
                        time(t_end),
                        evaluations_allowed(cost)
                    ),
                })
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
                        "{reason} ({tries}; the communication step started at t = {} s)",
                        time(t_start)
                    ),
                })
            }
        }
    }

    /// Refuse, before anything changes, a communication step `h` from `t_start` that needs
    /// more than [`MAX_INTERNAL_STEPS`] internal steps: fixed-step integrators take equal
    /// sub-steps of at most the solver step; the error-controlled ones at most
    /// `1.25 MAX_ADAPTIVE_STEP` each.
    pub fn check_work(&self, t_start: f64, h: f64) -> Result<(), ModelError> {
        let refuse = |message: String| {
            Err(ModelError::TooMuchWork {
                time: t_start,
                step: h,
                message,
            })
        };
        if self.integrator.is_adaptive() {
            let bound = MAX_INTERNAL_STEPS as f64 * 1.25 * MAX_ADAPTIVE_STEP;
            if h.is_nan() || h > bound {
                return refuse(format!(
                    "the error-controlled internal steps are at most {:e} s, so it needs more than {MAX_INTERNAL_STEPS} internal steps, the most allowed per communication step (h <= {bound:e} s)",
                    1.25 * MAX_ADAPTIVE_STEP
                ));
            }
        } else {
            let n_sub = ((h / self.max_step) * (1.0 - 1e-12)).ceil().max(1.0);
            if n_sub.is_nan() || n_sub > MAX_INTERNAL_STEPS as f64 {
                return refuse(format!(
                    "it needs {n_sub:e} internal steps of at most {:e} s, allowed at most {MAX_INTERNAL_STEPS} per communication step (h <= {:e} s)",
                    self.max_step,
                    self.max_step * MAX_INTERNAL_STEPS as f64
                ));
            }
        }
        Ok(())
    }

    /// Before the steps of an adaptive integrator: where the inputs set at this communication
    /// point moved the crank off the law the state followed (a sampled motion's new angle,
    /// speed and acceleration), the positions and velocities move onto the new law's
    /// constraints and the accelerations and multipliers are recomputed: the jump is not
    /// charged to the error control as a local error. By the M-weighted least change (the
    /// index-1 projection, as the fixed-step RK4 does after every step), also on minimal
    /// coordinates. Returns whether the state's accelerations still need an evaluation (after
    /// the projection).
    fn restart_consistently(
        &mut self,
        state: &mut MechanismState,
    ) -> Result<bool, (f64, f64, String)> {
        let t = state.dae.t;
        let sys = dae_context(
            self.rod.as_ref(),
            self.gas.as_ref(),
            &self.spec,
            state,
            &self.pin_cache,
        );
        // The constraint residual of `SliderCrankDae::constraints`, with the pin's motion of
        // the new law computed once for the position and the velocity checks.
        let (pin, v_new, a_new) = sys.crank.pin(t);
        let [rb, rc, _] = self.rod.points(&state.dae.q);
        let ns = self.rod.n_coordinates();
        let phi = [
            rb.x - pin.x,
            rb.y - pin.y,
            rc.x - state.dae.q[ns],
            rc.y - sys.slider_offset,
        ];
        let tolerance = 1e-14 * self.rod.length();
        // The crank angle's own round-off: a master's angle `omega t` carries a few ulps of
        // `|theta|` (2e-13 rad at 1000 rad, a long run), which moves the pin by `r` times that
        // and turns its velocity and acceleration by as much. A law that differs by no more has
        // not changed: restarting on it cost a factorization every step of a long run.
        let angle_noise = angle_noise(state);
        let position_noise = tolerance + self.crank_length * angle_noise;
        let mut work = self
            .output_solve
            .take()
            .unwrap_or_else(|| OutputSolve::new(self.rod.n_coordinates() + 1));
        let fail = |f: crate::integrator::StepFailure| {
            (t, 0.0, format!("restart at the communication point: {f}"))
        };
        let result = (|| {
            let positions_off = phi.iter().any(|x| x.abs() > position_noise);
            let mut velocities_off = positions_off;
            let mut acceleration_only = false;
            if !velocities_off {
                let previous = CrankLaw {
                    length: self.crank_length,
                    t_k: state.previous_input_time,
                    input: state.previous_input,
                };
                let (_, v_old, a_old) = previous.pin(t);
                let speed_off = (v_new - v_old).norm()
                    > 1e-14 * (1.0 + v_new.norm()) + angle_noise * v_new.norm();
                let acceleration_off = (a_new - a_old).norm()
                    > 1e-12 * (1.0 + a_new.norm()) + angle_noise * a_new.norm();
                velocities_off = speed_off || acceleration_off;
                acceleration_only = !speed_off && acceleration_off;
            }
            if !velocities_off {
                return Ok(false);
            }
            // A new crank acceleration that continues the law's angle and speed (a smooth
            // motion sampled as a continuation, `drive::engine`): positions and velocities
            // already keep the new law's constraints, nothing to project. An integrator on the
            // closed-form minimal coordinates that evaluates its first stage (the step that
            // follows, with its inputs new) solves the new accelerations itself.
            if acceleration_only
                && self.rod.ffr_kernel().is_some()
                && self.integrator.dense_output()
            {
                return Ok(true);
            }
            // A change of the crank law (a sampled motion's new angle, speed or acceleration):
            // the M-weighted least change of positions and velocities, for the minimal
            // coordinates too. Keeping the modal coordinates and rates and moving only the frame
            // and the slider onto the new law (tried with the closed form) is not the same
            // state: a smooth start sampled every 1e-4 s drifted 0.54 % of the peak deflection
            // from the constraint-based RK4 (tests/minimal_coordinates.rs,
            // `sampled_ramp_matches_the_constraint_based_rk4`).
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
            Ok(true)
        })();
        self.output_solve = Some(work);
        result
    }

    /// Whether the state's accelerations and multipliers satisfy the slider's equation
    /// `m_s x_s'' - lambda_Cx = F_s + m_s g_x` with the slider force now in force (to
    /// round-off): then they came from the same inputs (the crank law checked by
    /// [`Mechanism::restart_consistently`]) and the next step may start from them. A function
    /// of the state alone, so a restored state replays bit for bit.
    fn slider_force_consistent(&self, state: &MechanismState) -> bool {
        let ns = self.rod.n_coordinates();
        let d = &state.dae;
        let m_s = self.slider_mass;
        let g_x = self.spec.mechanism.gravity[0];
        let inertia = m_s * d.qdd[ns];
        let force = self.system(state).slider_force_at(d.t);
        let residual = inertia - d.lambda[2] - force - m_s * g_x;
        let scale = inertia.abs() + d.lambda[2].abs() + force.abs() + (m_s * g_x).abs();
        residual.abs() <= 1e-12 * scale.max(1e-300)
    }

    /// Accepted steps of an adaptive integrator until `t_end`: the last one lands on it, or,
    /// with dense output where that is cheaper ([`steps_past_is_cheaper`], decided before each
    /// internal step on what is left of the communication step), reaches past it and the state at
    /// `t_end` is its interpolant ([`crate::integrator::StepAhead`]); the next communication
    /// steps inside the held step cost an interpolation and one evaluation each, so the
    /// internal step follows the error control, not the communication step. Not where new
    /// inputs came at this communication point (`may_step_ahead` false): a master that sets
    /// them at every point (a gas force, a sampled crank) would drop every held step at the
    /// next one, so the steps land there as without dense output.
    fn adaptive_steps(
        &mut self,
        state: &mut MechanismState,
        t_end: f64,
        h_comm: f64,
        may_step_ahead: bool,
    ) -> Result<(), (f64, f64, String)> {
        let mut taken = 0u64;
        let entry = state.stats;
        let dense = may_step_ahead && self.integrator.dense_output();
        while state.dae.t < t_end {
            if state.ahead.held {
                let sys = dae_context(
                    self.rod.as_ref(),
                    self.gas.as_ref(),
                    &self.spec,
                    state,
                    &self.pin_cache,
                );
                let t1 = state.ahead.end.t;
                if t_end < t1 - 1e-12 * (t1 - state.ahead.t0) {
                    let work = self
                        .integrator
                        .interpolate(&sys, &state.ahead, t_end, &mut state.dae)
                        .map_err(|f| (t_end, t1 - state.ahead.t0, f.to_string()))?;
                    state.stats.newton_iterations += work as u64;
                    return Ok(());
                }
                // The held step ends at or before `t_end`: its end is the state, and its last
                // stage (the same inputs) the next step's first.
                state.dae.clone_from(&state.ahead.end);
                state.amplitude = self.amplitude_with(&state.dae, state.amplitude);
                state.ahead.held = false;
                self.integrator.reuse_first_stage();
                if state.dae.t >= t_end - 1e-12 * h_comm {
                    state.dae.t = t_end;
                }
                continue;
            }
            if taken >= MAX_INTERNAL_STEPS {
                return Err((state.dae.t, t_end - state.dae.t, TOO_MANY_STEPS.to_string()));
            }
            if self.over_budget(state, &entry) {
                return Err((state.dae.t, t_end - state.dae.t, OVER_BUDGET.to_string()));
            }
            taken += 1;
            let h_max = t_end - state.dae.t;
            let sys = dae_context(
                self.rod.as_ref(),
                self.gas.as_ref(),
                &self.spec,
                state,
                &self.pin_cache,
            );
            if dense
                && state.dae.step_hint > 0.0
                && steps_past_is_cheaper(h_max, state.dae.step_hint.min(MAX_ADAPTIVE_STEP))
            {
                if self.ahead_backup == AheadBackup::Untouched {
                    // The step held before this communication step is about to be overwritten.
                    self.backup_ahead.save(&state.ahead);
                    self.ahead_backup = AheadBackup::Saved;
                }
                self.integrator.set_amplitude(state.amplitude);
                match self
                    .integrator
                    .step_ahead(&sys, &state.dae, &mut state.ahead)
                {
                    Ok(work) => {
                        state.stats.steps += 1;
                        state.stats.newton_iterations += work as u64;
                        continue;
                    }
                    Err(error) => {
                        state.stats.newton_iterations += error.work as u64;
                        return Err((state.dae.t, h_max, error.failure.to_string()));
                    }
                }
            }
            self.integrator.set_amplitude(state.amplitude);
            match self.integrator.step(&sys, &mut state.dae, h_max) {
                Ok(work) => {
                    state.stats.steps += 1;
                    state.stats.newton_iterations += work as u64;
                    state.amplitude = self.amplitude_with(&state.dae, state.amplitude);
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

    /// The error control's amplitude ([`MechanismState::amplitude`], the largest `|v_mid / L|`
    /// so far) with the deflection of `dae` itself, after each accepted internal step: the
    /// tolerance follows the motion inside a long communication step too (updated at
    /// communication points only, one communication step over two revolutions of the default
    /// scene was held to the floor's tolerance throughout and took 863 internal steps instead
    /// of about 100).
    fn amplitude_with(&self, dae: &crate::integrator::DaeState, amplitude: f64) -> f64 {
        let here = (self.rod.mid_deflection(&dae.q) / self.rod.length()).abs();
        amplitude.max(here)
    }

    /// One internal step to `target`, split in halves on failure, at most `solver.max_halvings`
    /// levels deep. A loop over a fixed stack of pending targets (the second halves, the
    /// deepest on top) takes the halves in the order a recursion would, with no call depth a
    /// scene controls and no allocation.
    fn step_with_halving(
        &mut self,
        state: &mut MechanismState,
        target: f64,
        entry: &StepStats,
    ) -> Result<(), (f64, f64, String)> {
        // At most one pending target per level: `MAX_HALVINGS + 1` entries, on the stack.
        let max_depth = self.max_halvings.min(MAX_HALVINGS);
        let mut pending = [(0.0, 0usize); MAX_HALVINGS + 1];
        pending[0] = (target, 0);
        let mut len = 1;
        while len > 0 {
            len -= 1;
            let (target, depth) = pending[len];
            if self.over_budget(state, entry) {
                return Err((state.dae.t, target - state.dae.t, OVER_BUDGET.to_string()));
            }
            let h = target - state.dae.t;
            let sys = dae_context(
                self.rod.as_ref(),
                self.gas.as_ref(),
                &self.spec,
                state,
                &self.pin_cache,
            );
            self.integrator.set_amplitude(state.amplitude);
            match self.integrator.step(&sys, &mut state.dae, h) {
                Ok(work) => {
                    state.dae.t = target;
                    state.stats.steps += 1;
                    state.stats.newton_iterations += work as u64;
                }
                Err(error) => {
                    state.stats.newton_iterations += error.work as u64;
                    if depth >= max_depth {
                        return Err((state.dae.t, h, error.failure.to_string()));
                    }
                    state.stats.halvings += 1;
                    pending[len] = (target, depth + 1);
                    pending[len + 1] = (state.dae.t + 0.5 * h, depth + 1);
                    len += 2;
                }
            }
        }
        Ok(())
    }

    /// The deflection policy (`rod.deflection_limit`, `rod.deflection_policy`) on the outputs
    /// `o` of a step: warn once, or refuse the step.
    fn check_large_deflection(
        &self,
        state: &mut MechanismState,
        o: &super::outputs::Outputs,
    ) -> Result<(), ModelError> {
        let d = o.deflection_rel.abs();
        let limit = self.spec.rod.deflection_limit();
        if d <= limit {
            return Ok(());
        }
        let range = self.spec.rod.model.validity();
        match self.spec.rod.deflection_policy {
            DeflectionPolicy::Warn => {
                if !state.large_deflection_warned {
                    state.large_deflection_warned = true;
                    state.warnings.push(format!(
                        "rod deflection |v_mid/L| = {d:.3e} at t = {} s exceeds rod.deflection_limit = {limit} ({range}); results beyond it are not accurate",
                        time(state.time)
                    ));
                }
                Ok(())
            }
            policy => Err(ModelError::DeflectionLimit {
                time: state.time,
                deflection: d,
                limit,
                discard: policy == DeflectionPolicy::Discard,
                range,
            }),
        }
    }
}

/// The evaluations [`WORK_BUDGET`] allows one communication step of a model whose evaluation
/// costs `cost` work units ([`Mechanism::evaluation_cost`]).
pub fn evaluations_allowed(cost: f64) -> u64 {
    (WORK_BUDGET / cost.max(1.0)) as u64
}

/// Whether the work since `entry` (the statistics at the start of the communication step)
/// has used up [`WORK_BUDGET`] for a model whose evaluation costs `cost` work units.
fn over_work_budget(state: &MechanismState, entry: &StepStats, cost: f64) -> bool {
    let evaluations = (state.stats.newton_iterations - entry.newton_iterations)
        + (state.stats.steps - entry.steps)
        + (state.stats.halvings - entry.halvings);
    evaluations > evaluations_allowed(cost)
}

/// The wall time after which a communication step is refused whatever its counted work, s:
/// the guard behind the work budget, for a model whose evaluations cost more than the cost
/// model charges (`rod::cost`). Below [`crate::rod::cost::WORST_CALL_SECONDS`], the bound of
/// one call; the range generator of the fuzz harness counts the calls it ends (none on the
/// reference machine is the aim: a call it ends is refused where another machine may finish).
pub const WALL_GUARD_SECONDS: f64 = 4.0;

impl Mechanism {
    /// The coordinates an evaluation costs like, for the work budget: the rod's
    /// ([`crate::rod::RodBody::work_coordinates`]) and the slider.
    pub fn work_coordinates(&self) -> usize {
        self.rod.work_coordinates() + 1
    }

    /// Whether the communication step in progress is over its work budget
    /// ([`over_work_budget`]) or past its wall-time guard ([`WALL_GUARD_SECONDS`]).
    fn over_budget(&self, state: &MechanismState, entry: &StepStats) -> bool {
        over_work_budget(state, entry, self.evaluation_cost)
            || std::time::Instant::now() > self.call_deadline
    }

    /// Work units of one evaluation ([`crate::rod::cost`]): the dense terms of
    /// [`Self::work_coordinates`] and what the rod adds
    /// ([`crate::rod::RodBody::extra_evaluation_cost`]), computed when the mechanism is built.
    pub fn evaluation_cost(&self) -> f64 {
        self.evaluation_cost
    }
}

/// The round-off a master's crank angle carries (`omega t` has a few ulps of `|theta|`): 4 ulps
/// of the larger of the new and the previous input angle, rad. A crank law that differs from
/// the previous one by no more has not changed.
fn angle_noise(state: &MechanismState) -> f64 {
    4.0 * f64::EPSILON
        * state
            .input
            .angle
            .abs()
            .max(state.previous_input.angle.abs())
}

/// Whether the input set at this communication point is the crank law the state followed,
/// continued: the angle to its round-off ([`angle_noise`], as
/// [`Mechanism::restart_consistently`] allows), the speed and acceleration to 1e-14 and 1e-12
/// relative (a master that sets the angle and speed of one smooth motion at every point,
/// e.g. `omega t`). Then a state that keeps the constraints exactly (minimal coordinates)
/// is consistent with it as it was, without computing the pin's motion.
fn input_continues_law(state: &MechanismState) -> bool {
    if state.input_time != state.dae.t {
        return false;
    }
    let previous = CrankLaw {
        length: 0.0,
        t_k: state.previous_input_time,
        input: state.previous_input,
    };
    let (angle, speed, acceleration) = previous.kinematics(state.input_time);
    let new = state.input;
    (new.angle - angle).abs() <= angle_noise(state)
        && (new.speed - speed).abs() <= 1e-14 * (1.0 + speed.abs())
        && (new.acceleration - acceleration).abs() <= 1e-12 * (1.0 + acceleration.abs())
}

/// Whether the law set at the communication point has another jerk than the law before it
/// (beyond 1e-12 relative): the two agree in angle, speed and acceleration now and part
/// after it.
fn jerk_changed(state: &MechanismState) -> bool {
    let (new, old) = (state.input.jerk, state.previous_input.jerk);
    (new - old).abs() > 1e-12 * (1.0 + old.abs())
}

/// Whether stepping past the communication point (dense output) is cheaper than landing on it,
/// for the rest `H` of the communication step (all of it at its start; after a held step that
/// ended inside it, what is left) and the internal step `p` the error control proposes (capped
/// at [`MAX_ADAPTIVE_STEP`], as the integrator caps it). Cost in evaluations (four a step):
/// landing takes the steps of size `p` until the rest is within the 25 % stretch of one,
/// `n = max(1, ceil(H / p - 1/4))` steps; stepping past it takes `H / p` steps on average plus
/// one evaluation for the interpolated state. Stepping past wins for `H / p + 1/4 < n`: every
/// rest below `3 p / 4`, and longer ones whose last landing step would be short (e.g.
/// `H = 1.5 p`: 1.75 steps instead of 2). Deciding on the rest, not the whole communication
/// step, keeps a step held past the middle of a communication step from being followed by a
/// short landing step (the `dense-output` fragment of `tests/error_control.rs` lists the cost on
/// several grids).
pub fn steps_past_is_cheaper(rest: f64, proposal: f64) -> bool {
    let r = rest / proposal;
    r.is_finite() && r + 0.25 < (r - 0.25).ceil().max(1.0)
}

/// Reason of an adaptive loop stopped by [`MAX_INTERNAL_STEPS`] (turned into `TooMuchWork`).
const TOO_MANY_STEPS: &str = "too many internal steps";
const OVER_BUDGET: &str = "over the work budget";

/// An accepted step's state and outputs must be finite and its outputs below
/// [`MAX_OUTPUT_MAGNITUDE`]; else the integration diverged and the step is refused.
fn check_finite(
    state: &MechanismState,
    o: &super::outputs::Outputs,
    t_start: f64,
    h: f64,
) -> Result<(), ModelError> {
    let fail = |reason: String| ModelError::StepFailed {
        time: t_start,
        step: h,
        reason,
    };
    let d = &state.dae;
    let out_of_range = o.out_of_range();
    if let Some(x) =
        d.q.iter()
            .chain(&d.v)
            .chain(&d.lambda)
            .find(|x| !x.is_finite())
    {
        return Err(fail(format!(
            "the integration diverged: a state coordinate is {x} after the step (state coordinates must be finite)"
        )));
    }
    if let Some((name, x)) = out_of_range {
        return Err(fail(format!(
            "the integration diverged: output {name} = {x:e} after the step (allowed finite and |value| < {MAX_OUTPUT_MAGNITUDE:e} in SI units)"
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanism::Outputs;

    /// The landing rule of dense output at communication steps `H = r p`: landing costs
    /// `max(1, ceil(r - 1/4))` steps, stepping past `r + 1/4`.
    #[test]
    fn stepping_past_where_it_costs_fewer_evaluations() {
        let p = 2e-4;
        for (r, past) in [
            (0.05, true),
            (0.74, true),
            (0.76, false),
            (1.0, false),
            (1.25, false),
            (1.3, true),
            (1.74, true),
            (1.76, false),
            (2.25, false),
            (2.6, true),
        ] {
            assert_eq!(steps_past_is_cheaper(r * p, p), past, "H / p = {r}");
        }
        assert!(!steps_past_is_cheaper(1e-4, 0.0));
    }

    /// A diverged segment chain can reach NaN and 1e254 N: the check every accepted step
    /// passes refuses both (and non-finite state coordinates).
    #[test]
    fn diverged_states_and_outputs_are_refused() {
        let mut state = MechanismState::default();
        state.dae.q = vec![0.1, 0.2];
        state.dae.v = vec![0.0, 1.0];
        state.dae.lambda = vec![1.0; 4];
        let good = Outputs {
            pin_b_force: [120.0, -3.0],
            ..Outputs::default()
        };
        assert!(check_finite(&state, &good, 0.5, 1e-3).is_ok());
        let mut huge = good;
        huge.pin_b_force[0] = 1e254;
        let e = check_finite(&state, &huge, 0.5, 1e-3).unwrap_err();
        assert!(matches!(e, ModelError::StepFailed { .. }));
        assert!(e.to_string().contains("pinB.force_x = 1e254"), "{e}");
        let mut nan = good;
        nan.crank_torque = f64::NAN;
        assert!(check_finite(&state, &nan, 0.5, 1e-3)
            .unwrap_err()
            .to_string()
            .contains("crank.torque = NaN"));
        state.dae.v[1] = f64::INFINITY;
        assert!(check_finite(&state, &good, 0.5, 1e-3)
            .unwrap_err()
            .to_string()
            .contains("state coordinate is inf"));
    }
}
