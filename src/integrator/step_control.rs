//! What the error-controlled explicit integrators share ([`super::AdaptiveRungeKutta`], the
//! embedded Runge-Kutta pairs; [`super::ExponentialRungeKutta`], ETDRK4): the workspace of the
//! stages on the independent coordinates `y = (z, z')` of a [`PartitionedRhs`], the error norm
//! and the step-size control around one try of a step, the start of a held step and the
//! complete evaluation that ends an interpolation.
//!
//! Error norm (maximum norm, so the control is pointwise):
//! `err = max_i |e_i| / sc_i`, `sc_z = tol max(A, A_min) s`, `sc_z' = w sc_z`,
//! with `e` the local error estimate of a try, `A` the amplitude of the motion the accuracy is
//! stated for (set by the caller through `Integrator::set_amplitude`: the mechanism passes the
//! largest `|v_mid / L|` so far),
//! `A_min` a floor, `s` the coordinate's scale (its value for a deflection of the rod's length)
//! and `w` the mode's circular frequency (units: `z` in the coordinate's unit, `w` in rad/s). The
//! step is accepted when `err <= 1`; the next one is `h min(5, max(0.2, 0.9 err^(-1/p)))` with
//! `p` the order of the estimate (after a rejection, at most h) (Hairer, Norsett and Wanner,
//! *Solving ODEs I*, 2nd ed., section II.4). The step proposal is part of the state
//! ([`DaeState::step_hint`]), so a restored state replays bit for bit.

use super::failure::{StepError, StepFailure};
use super::partitioned::PartitionedRhs;
use super::quantize_step;
use super::state::{DaeState, StepAhead};
use super::system::DaeSystem;

/// Settings of the error control.
#[derive(Clone, Debug)]
pub struct ErrorControl {
    /// Local tolerance (relative to the amplitude scale).
    pub tolerance: f64,
    /// Floor `A_min` of the amplitude scale (dimensionless, like `v_mid / L`).
    pub amplitude_floor: f64,
    /// Scale `s` of each independent coordinate (its value for a deflection of one rod length).
    pub scales: Vec<f64>,
    /// Weight `w` of each independent coordinate's rate (its circular frequency, rad/s).
    pub rate_weights: Vec<f64>,
    /// First step when the state has no proposal yet, s.
    pub initial_step: f64,
    /// Rejected tries of one step before it counts as failed.
    pub max_rejections: usize,
    /// Error per unit step: with `Some(c)` the local tolerance of a step of size `h` is
    /// `tolerance min(1, c h / T)`, `T` the system's [`DaeSystem::error_time_scale`], so that
    /// the local errors of the `T / h` steps of one period add up to a bounded global error
    /// however small the steps are (Hairer, Norsett and Wanner, *Solving ODEs I*, section
    /// II.4, "error per unit step"); `None`: error per step.
    pub per_unit_step: Option<f64>,
}

/// The stages' workspace (sized once) and the error control of an explicit integrator on the
/// independent coordinates (module documentation).
pub(super) struct EmbeddedSteps {
    /// The system evaluates its reduced right-hand side in closed form (for the name).
    pub closed_form: bool,
    pub rhs: PartitionedRhs,
    pub control: ErrorControl,
    /// The amplitude `A` the accuracy refers to ([`super::Integrator::set_amplitude`]).
    pub amplitude: f64,
    pub k: usize,
    /// Stage derivatives: `kz[s]` = z' and `kv[s]` = z'' at stage s (k each).
    pub kz: [Vec<f64>; 7],
    pub kv: [Vec<f64>; 7],
    pub z0: Vec<f64>,
    pub zd0: Vec<f64>,
    pub z: Vec<f64>,
    pub zd: Vec<f64>,
    pub q0: Vec<f64>,
    /// The first stage must be evaluated (the inputs may have changed at this communication
    /// point), not taken from the state's accelerations.
    pub fresh: bool,
}

/// `err^(-1/p)`, `p` the order `estimate_order` of the estimate (two square roots for p = 4).
fn root(estimate_order: f64, err: f64) -> f64 {
    if estimate_order == 4.0 {
        1.0 / err.sqrt().sqrt()
    } else {
        err.powf(-1.0 / estimate_order)
    }
}

impl EmbeddedSteps {
    /// The workspace for the coordinates `independent` of `system`, with the error control
    /// `control`.
    pub fn new(
        system: &dyn DaeSystem,
        independent: Vec<usize>,
        control: ErrorControl,
    ) -> EmbeddedSteps {
        let rhs = PartitionedRhs::new(system, independent);
        let k = rhs.k();
        assert_eq!(control.rate_weights.len(), k);
        let stage = || std::array::from_fn(|_| vec![0.0; k]);
        EmbeddedSteps {
            closed_form: system.has_reduced_rhs(),
            q0: vec![0.0; system.n_coordinates()],
            rhs,
            control,
            amplitude: 0.0,
            k,
            kz: stage(),
            kv: stage(),
            z0: vec![0.0; k],
            zd0: vec![0.0; k],
            z: vec![0.0; k],
            zd: vec![0.0; k],
            fresh: true,
        }
    }

    /// One accepted step of at most `h_max` from `state` (the state's proposal, at most
    /// `max_step`, stretched to `h_max` when within 25 % of it), with `attempt` the method's try
    /// of a step of size h (it leaves the try's solution in the evaluation workspace and
    /// returns the error norm) and `estimate_order` the order of its estimate. The step's
    /// start goes into `z0`, `zd0` and the first stage (the state's accelerations, first same
    /// as last, or a new evaluation when [`EmbeddedSteps::fresh`]); on success the state is
    /// the step's end with the next proposal in [`DaeState::step_hint`].
    pub fn step<F>(
        &mut self,
        system: &dyn DaeSystem,
        state: &mut DaeState,
        h_max: f64,
        max_step: f64,
        estimate_order: f64,
        mut attempt: F,
    ) -> Result<usize, StepError>
    where
        F: FnMut(
            &mut EmbeddedSteps,
            &dyn DaeSystem,
            &DaeState,
            f64,
            &mut usize,
        ) -> Result<f64, StepFailure>,
    {
        let mut work = 0;
        for (a, &i) in self.rhs.independent.iter().enumerate() {
            self.z0[a] = state.q[i];
            self.zd0[a] = state.v[i];
            // First same as last: the state's accelerations are the first stage.
            self.kz[0][a] = state.v[i];
            self.kv[0][a] = state.qdd[i];
        }
        self.q0.copy_from_slice(&state.q);
        if self.fresh {
            self.rhs.q.copy_from_slice(&self.q0);
            let (z0, zd0) = (&self.z0, &self.zd0);
            if let Err(failure) = self.rhs.evaluate(system, state.t, z0, zd0, &mut self.kv[0]) {
                return Err(failure.after(1));
            }
            work += 1;
        }
        let proposal = if state.step_hint > 0.0 {
            state.step_hint
        } else {
            self.control.initial_step
        }
        .min(max_step);
        let mut h = if h_max <= 1.25 * proposal {
            h_max
        } else {
            proposal
        };
        let mut rejected = false;
        for _ in 0..=self.control.max_rejections {
            // A failed evaluation (a position solve that does not converge, a singular matrix)
            // counts as a large error: the step shrinks.
            let err = attempt(self, system, state, h, &mut work).unwrap_or(f64::INFINITY);
            if err <= 1.0 {
                let grow = if err == 0.0 {
                    5.0
                } else {
                    (0.9 * root(estimate_order, err)).clamp(0.2, 5.0)
                };
                let mut next = h * if rejected { grow.min(1.0) } else { grow };
                if h == h_max && h < proposal {
                    // Landing on the communication point cut the step: keep the proposal.
                    next = next.max(proposal);
                }
                self.rhs.multipliers();
                let t1 = state.t + h;
                let r = &self.rhs;
                state.accept(t1, &r.q, &r.v, &r.qdd, &r.qdd, &r.lambda);
                // On the step grid, or exactly the largest step where that binds (a constant
                // of the run, so the steps stay the same whatever drives it).
                state.step_hint = if next >= max_step {
                    max_step
                } else {
                    quantize_step(next)
                };
                self.fresh = false;
                return Ok(work);
            }
            rejected = true;
            let shrink = if err.is_finite() {
                (0.9 * root(estimate_order, err)).clamp(0.2, 1.0)
            } else {
                0.25
            };
            h = quantize_step(h * shrink);
            if h < 1e-14 * (1.0 + state.t.abs()) {
                break;
            }
        }
        Err(StepFailure::NewtonDiverged {
            iterations: self.control.max_rejections,
            last_correction: h,
        }
        .after(work))
    }

    /// The local tolerance of a step `h` (module documentation: relative to the amplitude set
    /// last; error per unit step where set).
    pub fn local_tolerance(&self, system: &dyn DaeSystem, h: f64) -> f64 {
        let mut tol = self.control.tolerance * self.amplitude.max(self.control.amplitude_floor);
        let period = system.error_time_scale();
        if let Some(c) = self
            .control
            .per_unit_step
            .filter(|_| period.is_finite() && period > 0.0)
        {
            tol *= (c * h / period).min(1.0);
        }
        tol
    }

    /// Coordinate `a`'s term of the error norm for the local errors `(ez, ev)` of `z`, `z'`.
    #[inline(always)]
    pub fn error_ratio(&self, a: usize, tol: f64, ez: f64, ev: f64) -> f64 {
        let sc_z = tol * self.control.scales[a];
        let sc_v = self.control.rate_weights[a] * sc_z;
        (ez.abs() / sc_z).max(ev.abs() / sc_v)
    }

    /// The start of the step just taken from `state` into `ahead` (`t0`, `z0`, `zd0`, `zdd0`:
    /// the first stage).
    pub fn hold_start(&self, state: &DaeState, ahead: &mut StepAhead) {
        ahead.t0 = state.t;
        ahead.z0.copy_from_slice(&self.z0);
        ahead.zd0.copy_from_slice(&self.zd0);
        ahead.zdd0.copy_from_slice(&self.kv[0]);
    }

    /// The end of an interpolation at `t` inside the held step of `ahead`, with the
    /// interpolated independent coordinates and rates in `z`, `zd`: one complete evaluation at
    /// `(t, z, z')` (the end's dependent positions choose the assembly branch and the frame
    /// angle's turn) into `out`, with the end's step proposal. Returns the work done.
    pub fn finish_interpolation(
        &mut self,
        system: &dyn DaeSystem,
        ahead: &StepAhead,
        t: f64,
        out: &mut DaeState,
    ) -> Result<usize, StepFailure> {
        let end = &ahead.end;
        self.rhs.q.copy_from_slice(&end.q);
        let (z, zd, zdd) = (&self.z, &self.zd, &mut self.kv[6]);
        self.rhs.evaluate_stage(system, t, z, zd, zdd, true)?;
        self.rhs.multipliers();
        let r = &self.rhs;
        out.accept(t, &r.q, &r.v, &r.qdd, &r.qdd, &r.lambda);
        out.step_hint = end.step_hint;
        Ok(1)
    }
}
