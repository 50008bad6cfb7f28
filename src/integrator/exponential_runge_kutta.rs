//! The exponential Runge-Kutta integrator ETDRK4 with error control on the mechanism's
//! independent coordinates, each with its linear oscillator taken exactly
//! ([`super::exponential`]): `z'' = -w^2 z - c z' + n(t, z, z')`, `y = (z, z')`,
//! `y' = A y + e2 n` (Hochbruck and Ostermann 2010, "Exponential integrators", Acta
//! Numerica 19). The stages are those of Krogstad (S. Krogstad, "Generalized integrating factor
//! methods for stiff PDEs", J. Comput. Phys. 203, 2005) with the weights of Cox and Matthews
//! (S. M. Cox and P. C. Matthews, "Exponential time differencing for stiff systems", J. Comput.
//! Phys. 176, 2002) ([`EtdWeights`]); for `A -> 0` they are the classic RK4 of the RK4(3) pair
//! ([`super::RK4_FSAL`]), and the embedded estimate tends to that pair's.
//!
//! A mode's own oscillation then costs no steps, and neither does the forced response of a
//! stiff mode: the step follows how fast the remainder `n` (the coupling to the rigid motion,
//! the stiffening, the forcing) changes, up to the largest step set at construction (the phase
//! caps on the modes measured on this product's rods, where the integrator is chosen:
//! `crate::mechanism::integrator_choice`, which also decides where `auto` takes it: where the
//! modes are the mechanism's own oscillators, leaving the pins in place or carrying the slider
//! as mass-loaded modes).
//!
//! The step control, the error norm and the workspace are those of the embedded pairs
//! ([`super::step_control`]).

use super::exponential::{self, EtdWeights, Oscillator, Propagator};
use super::failure::{StepError, StepFailure};
use super::state::{DaeState, StepAhead};
use super::step_control::{EmbeddedSteps, ErrorControl};
use super::system::DaeSystem;
use super::Integrator;

/// The order of the embedded estimate, that of the RK4(3) pair ([`super::RK4_FSAL`]): the step
/// control's exponent is its reciprocal.
const ESTIMATE_ORDER: f64 = 4.0;

/// The name on minimal coordinates in closed form.
const NAME_MINIMAL: &str =
    "exponential Runge-Kutta 4(3) (ETDRK4, modal oscillators exact) on minimal coordinates (closed form)";

/// The name on the general partitioned evaluation (the chain on its modes).
const NAME_GENERAL: &str =
    "exponential Runge-Kutta 4(3) (ETDRK4, modal oscillators exact) on the modal coordinates (general evaluation)";

/// The ETDRK4 integrator (module documentation): the oscillators, the step control and their
/// workspace, sized once.
pub struct ExponentialRungeKutta {
    steps: EmbeddedSteps,
    form: ExponentialForm,
}

/// The oscillators of the exponential integrator and their workspace (sized once).
struct ExponentialForm {
    /// Each independent coordinate's split-off oscillator.
    oscillators: Vec<Oscillator>,
    /// The ETDRK4 weights of the step `weights_h` (recomputed when the step size changes;
    /// derived data, so a restored state replays bit for bit).
    weights: Vec<EtdWeights>,
    weights_h: f64,
    /// The weights of the step size before (`previous_h`), kept: the steps alternate between
    /// a proposal and the landing on a communication point.
    previous: Vec<EtdWeights>,
    previous_h: f64,
    /// `E(h)` of the held step `interpolation_h` (the end of the interpolant).
    full: Vec<Propagator>,
    interpolation_h: f64,
    /// Stage remainders `n = z'' + w^2 z + c z'`: start, a, b, c, end.
    remainders: [Vec<f64>; 5],
    /// The free responses of the step's start, `E(h/2) y0` and `E(h) y0` (`z` and `z'` of
    /// each), which stages a, b and c, end share.
    free: Vec<[f64; 4]>,
    /// The largest step the caller allows, s ([`ExponentialRungeKutta::new`]).
    max_step: f64,
}

impl ExponentialRungeKutta {
    /// ETDRK4 with the error control `control` on the coordinates `independent` of `system`,
    /// coordinate `a`'s linear oscillator `oscillators[a]` split off and taken exactly, the
    /// remainder integrated against it with the phi functions; its embedded estimate
    /// `h f3(hA) e2 (N_c - N_end)` (the RK4(3) pair's `h (k_4 - k_5) / 6` for `A -> 0`; `N_end`
    /// the remainder at the new solution, first same as last). Dense output by the oscillator's
    /// exact response to a quadratic remainder ([`Integrator::interpolate`]). The steps
    /// proposed are at most `max_step`, s (and [`super::MAX_ADAPTIVE_STEP`]): the oscillators'
    /// own motion does not bound the step, so the caller bounds what the embedded estimate does
    /// not see (the phase `w h` over which the stages still sample the remainder's oscillating
    /// terms).
    pub fn new(
        system: &dyn DaeSystem,
        independent: Vec<usize>,
        control: ErrorControl,
        oscillators: Vec<Oscillator>,
        max_step: f64,
    ) -> ExponentialRungeKutta {
        let steps = EmbeddedSteps::new(system, independent, control);
        let k = steps.k;
        assert_eq!(oscillators.len(), k);
        ExponentialRungeKutta {
            steps,
            form: ExponentialForm {
                weights: vec![EtdWeights::default(); k],
                weights_h: f64::NAN,
                previous: vec![EtdWeights::default(); k],
                previous_h: f64::NAN,
                full: vec![[0.0; 4]; k],
                interpolation_h: f64::NAN,
                remainders: std::array::from_fn(|_| vec![0.0; k]),
                free: vec![[0.0; 4]; k],
                max_step,
                oscillators,
            },
        }
    }

    /// The largest step proposed: [`super::MAX_ADAPTIVE_STEP`] and the caller's `max_step`
    /// ([`ExponentialRungeKutta::new`]).
    fn max_step(&self) -> f64 {
        self.form.max_step.min(super::MAX_ADAPTIVE_STEP)
    }
}

impl ExponentialForm {
    /// One try of size h from `state` (the step's start and first stage in `steps`): the stages
    /// of [`EtdWeights`] at `t + h/2` (a, b), `t + h` (c) and the new solution (first same as
    /// last), the estimate `h f3 (N_c - N_end)`; returns the error norm (the solution of the
    /// try is left in `steps.z`, `steps.zd` and the evaluation workspace). Stages b and c take
    /// the change of the remainder against the oscillator by `phi_2` (Krogstad's stages): the
    /// stages of Cox and Matthews, which take the remainder at one stage as constant over the
    /// next, let the undamped benchmark rod's first mode gain 10 % of amplitude in 100 s (2,400
    /// revolutions, 1,000 steps a second at `w_1 h = 0.87`), Krogstad's lose 0.8 %.
    fn attempt(
        &mut self,
        steps: &mut EmbeddedSteps,
        system: &dyn DaeSystem,
        state: &DaeState,
        h: f64,
        work: &mut usize,
    ) -> Result<f64, StepFailure> {
        let k = steps.k;
        if self.weights_h != h {
            std::mem::swap(&mut self.weights, &mut self.previous);
            std::mem::swap(&mut self.weights_h, &mut self.previous_h);
            if self.weights_h != h {
                for (w, osc) in self.weights.iter_mut().zip(&self.oscillators) {
                    *w = EtdWeights::new(osc, h);
                }
                self.weights_h = h;
            }
        }
        let weights = &self.weights[..k];
        let oscillators = &self.oscillators[..k];
        let (z0, zd0) = (&steps.z0[..k], &steps.zd0[..k]);
        for (a, free) in self.free[..k].iter_mut().enumerate() {
            self.remainders[0][a] = oscillators[a].remainder(z0[a], zd0[a], steps.kv[0][a]);
            let (zh, vh) = exponential::apply(&weights[a].half, z0[a], zd0[a]);
            let (zf, vf) = exponential::apply(&weights[a].full, z0[a], zd0[a]);
            *free = [zh, vh, zf, vf];
        }
        steps.rhs.q.copy_from_slice(&steps.q0);
        for s in 1..5 {
            exponential_stage(
                s,
                h,
                weights,
                &self.free[..k],
                &self.remainders,
                &mut steps.z[..k],
                &mut steps.zd[..k],
            );
            let t = state.t + if s <= 2 { 0.5 * h } else { h };
            steps
                .rhs
                .evaluate_stage(system, t, &steps.z, &steps.zd, &mut steps.kv[s], s == 4)?;
            *work += 1;
            let (z, zd, kv) = (&steps.z[..k], &steps.zd[..k], &steps.kv[s][..k]);
            for (a, n) in self.remainders[s][..k].iter_mut().enumerate() {
                *n = oscillators[a].remainder(z[a], zd[a], kv[a]);
            }
        }
        let tol = steps.local_tolerance(system, h);
        let mut err: f64 = 0.0;
        for a in 0..k {
            let d = h * (self.remainders[3][a] - self.remainders[4][a]);
            let f3 = weights[a].f[2];
            err = err.max(steps.error_ratio(a, tol, f3[0] * d, f3[1] * d));
        }
        if !err.is_finite() {
            return Err(StepFailure::NonFinite);
        }
        Ok(err)
    }
}

/// Stage `s` of ETDRK4 ([`EtdWeights`]; 1, 2: a, b at `t + h/2`; 3: c at `t + h`; 4: the new
/// solution) from the free responses `free` of the step's start (`E(h/2) y0`, `E(h) y0`) and
/// the remainders `n` of the stages before, into `z`, `z'`:
/// `a = E(h/2) y0 + phi_1(h/2) g`, `g = h/2 N0`; `b = a + phi_2(h/2) h (Na - N0)`;
/// `c = E(h) y0 + phi_1(h) h N0 + phi_2(h) 2 h (Nb - N0)`;
/// `y1 = E(h) y0 + f1 h N0 + f2 2 h (Na + Nb) + f3 h Nc`.
fn exponential_stage(
    s: usize,
    h: f64,
    weights: &[EtdWeights],
    free: &[[f64; 4]],
    n: &[Vec<f64>; 5],
    z: &mut [f64],
    zd: &mut [f64],
) {
    let k = z.len();
    let (weights, free, zd) = (&weights[..k], &free[..k], &mut zd[..k]);
    let [n0, n1, n2, n3] = [&n[0][..k], &n[1][..k], &n[2][..k], &n[3][..k]];
    for (a, z) in z.iter_mut().enumerate() {
        let w = &weights[a];
        let [zh, vh, zf, vf] = free[a];
        let (zs, vs) = match s {
            1 => {
                let g = 0.5 * h * n0[a];
                (zh + w.half_phi1[0] * g, vh + w.half_phi1[1] * g)
            }
            2 => {
                let (g, g2) = (0.5 * h * n0[a], h * (n1[a] - n0[a]));
                (
                    zh + w.half_phi1[0] * g + w.half_phi2[0] * g2,
                    vh + w.half_phi1[1] * g + w.half_phi2[1] * g2,
                )
            }
            3 => {
                let (g, g2) = (h * n0[a], 2.0 * h * (n2[a] - n0[a]));
                (
                    zf + w.full_phi1[0] * g + w.full_phi2[0] * g2,
                    vf + w.full_phi1[1] * g + w.full_phi2[1] * g2,
                )
            }
            _ => {
                let (g0, g1, g3) = (h * n0[a], 2.0 * h * (n1[a] + n2[a]), h * n3[a]);
                let f = &w.f;
                (
                    zf + f[0][0] * g0 + f[1][0] * g1 + f[2][0] * g3,
                    vf + f[0][1] * g0 + f[1][1] * g1 + f[2][1] * g3,
                )
            }
        };
        *z = zs;
        zd[a] = vs;
    }
}

impl Integrator for ExponentialRungeKutta {
    fn set_amplitude(&mut self, amplitude: f64) {
        self.steps.amplitude = amplitude;
    }

    /// Takes one accepted step of at most `h` (the rest of the communication step): the
    /// state's proposal, stretched to `h` when within 25 % of it.
    fn step(
        &mut self,
        system: &dyn DaeSystem,
        state: &mut DaeState,
        h_max: f64,
    ) -> Result<usize, StepError> {
        let max_step = self.max_step();
        let form = &mut self.form;
        self.steps.step(
            system,
            state,
            h_max,
            max_step,
            ESTIMATE_ORDER,
            |steps, system, state, h, work| form.attempt(steps, system, state, h, work),
        )
    }

    /// The inputs may change at a communication point: the next step evaluates its first stage.
    fn forget_between_steps(&mut self) {
        self.steps.fresh = true;
    }

    /// The inputs did not change at this communication point: the state's accelerations
    /// (the last stage of the previous step) are the first stage.
    fn reuse_first_stage(&mut self) {
        self.steps.fresh = false;
    }

    fn name(&self) -> &'static str {
        if self.steps.closed_form {
            NAME_MINIMAL
        } else {
            NAME_GENERAL
        }
    }

    fn work_unit(&self) -> &'static str {
        "right-hand sides"
    }

    fn is_adaptive(&self) -> bool {
        true
    }

    fn consistent_outputs(&self) -> bool {
        true
    }

    /// On minimal coordinates in closed form (where a complete evaluation gives the whole
    /// state from the independent coordinates without a Newton iteration).
    fn dense_output(&self) -> bool {
        self.steps.closed_form
    }

    fn step_ahead(
        &mut self,
        system: &dyn DaeSystem,
        state: &DaeState,
        ahead: &mut StepAhead,
    ) -> Result<usize, StepError> {
        ahead.end.clone_from(state);
        // No communication point to land on: the step is the state's proposal (or less after
        // rejections).
        let work = self.step(system, &mut ahead.end, f64::INFINITY)?;
        self.steps.hold_start(state, ahead);
        // The remainder at the step's middle for the interpolant: the mean of stages a, b.
        let remainders = &self.form.remainders;
        for (m, (na, nb)) in ahead
            .nmid
            .iter_mut()
            .zip(remainders[1].iter().zip(&remainders[2]))
        {
            *m = 0.5 * (na + nb);
        }
        ahead.held = true;
        Ok(work)
    }

    /// The oscillator's exact response over `tau = t - t0` to the remainder taken as the
    /// quadratic through its values at the held step's start, middle ([`StepAhead::nmid`]) and
    /// end ([`Oscillator::quadratic_response`]: `E(tau)` and the polynomial particular
    /// solution), plus `tau / h` times its miss of the step's end (a local error), so that it
    /// ends on the step's solution. Then one complete evaluation at `(t, z, z')`.
    fn interpolate(
        &mut self,
        system: &dyn DaeSystem,
        ahead: &StepAhead,
        t: f64,
        out: &mut DaeState,
    ) -> Result<usize, StepFailure> {
        let end = &ahead.end;
        let h = end.t - ahead.t0;
        let s = ((t - ahead.t0) / h).clamp(0.0, 1.0);
        let form = &mut self.form;
        if form.interpolation_h != h {
            for (e, osc) in form.full.iter_mut().zip(&form.oscillators) {
                *e = osc.propagator(h);
            }
            form.interpolation_h = h;
        }
        let tau = s * h;
        let inv_h = 1.0 / h;
        let steps = &mut self.steps;
        for (a, &i) in steps.rhs.independent.iter().enumerate() {
            let osc = &form.oscillators[a];
            let (z0, zd0) = (ahead.z0[a], ahead.zd0[a]);
            let n0 = osc.remainder(z0, zd0, ahead.zdd0[a]);
            let n1 = osc.remainder(end.q[i], end.v[i], end.qdd[i]);
            let nm = ahead.nmid[a];
            // n(u) = n0 + alpha u + beta u^2 through (0, n0), (h/2, nm), (h, n1).
            let alpha = (4.0 * nm - 3.0 * n0 - n1) * inv_h;
            let beta = 2.0 * (n1 - 2.0 * nm + n0) * inv_h * inv_h;
            let n = [n0, alpha, beta];
            let (z1, zd1) = osc.quadratic_response(&form.full[a], h, (z0, zd0), n);
            let (z, zd) = if s == 1.0 {
                (z1, zd1)
            } else {
                osc.quadratic_response(&osc.propagator(tau), tau, (z0, zd0), n)
            };
            steps.z[a] = z + s * (end.q[i] - z1);
            steps.zd[a] = zd + s * (end.v[i] - zd1);
        }
        steps.finish_interpolation(system, ahead, t, out)
    }
}
