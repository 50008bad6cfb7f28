//! Explicit adaptive Runge-Kutta integration with error control on the mechanism's independent
//! coordinates ([`super::PartitionedRhs`]; minimal coordinates in closed form where the system has
//! them, [`DaeSystem::reduced_rhs`]): `y = (z, z')`, `y' = (z', z'')`. One integrator,
//! [`AdaptiveRungeKutta`], parameterized by its embedded pair ([`Tableau`]):
//!
//! - [`DORMAND_PRINCE`]: the Dormand-Prince 5(4) pair (J. R. Dormand and P. J. Prince, "A family
//!   of embedded Runge-Kutta formulae", J. Comput. Appl. Math. 6, 1980; Hairer, Norsett and
//!   Wanner, *Solving ODEs I*, 2nd ed., table II.5.2 and section II.4);
//! - [`RK4_FSAL`]: the classic RK4 with an embedded third-order estimate, which `auto` takes on
//!   the FFR slider-crank: its step is bounded by the stiffest retained mode, where RK4 is
//!   stable to 2.8 times the Dormand-Prince step with four evaluations instead of six.
//!
//! The exponential form of the RK4(3) pair, ETDRK4 with each mode's oscillator exact, is an
//! integrator of its own ([`super::ExponentialRungeKutta`]) on the same step control.
//!
//! One step of size h: the stages (the last one at `t + h` on the new solution, reused as the
//! first stage of the next step: "first same as last"), the higher-order solution propagated
//! and the difference to the embedded one as the local error estimate `e`, whose error norm
//! sets the step (`h min(5, max(0.2, 0.9 err^(-1/p)))`, `p` the order of the estimate, 5 or 4:
//! [`super::step_control`]).

use super::failure::{StepError, StepFailure};
use super::state::{hermite5, DaeState, StepAhead};
use super::step_control::{EmbeddedSteps, ErrorControl};
use super::system::DaeSystem;
use super::Integrator;

/// An explicit embedded Runge-Kutta pair whose last stage is at `t + h` on the propagated
/// solution (first same as last): `stages` stages, nodes `c`, coefficients `a` (row s: the
/// weights of stages 0..s), the last row being the propagated weights; `e` the propagated
/// weights minus the embedded ones; `estimate_order` the order of the local error estimate
/// (the step control's exponent is `1 / estimate_order`).
#[derive(Debug)]
pub struct Tableau {
    /// The method's name on a system with a closed-form reduced right-hand side, and on one
    /// evaluated by the general partitioned path.
    pub name_minimal: &'static str,
    pub name_general: &'static str,
    pub stages: usize,
    pub c: &'static [f64],
    pub a: &'static [&'static [f64]],
    pub e: &'static [f64],
    pub estimate_order: f64,
    /// The pair has dense output on minimal coordinates ([`Integrator::dense_output`]): a field,
    /// not the tableau's address, since each use of a `const` may have an address of its own.
    pub dense_output: bool,
}

/// Dormand and Prince 5(4) (Hairer, Norsett and Wanner, table II.5.2): seven stages, six new
/// per step. Stable on the imaginary axis only up to `|h w|` of about 1 (`|R(i y)| > 1`
/// beyond), so an undamped stiff mode bounds its step.
pub const DORMAND_PRINCE: Tableau = Tableau {
    name_minimal: "Dormand-Prince 5(4) on minimal coordinates (closed form)",
    name_general: "Dormand-Prince 5(4) on independent coordinates (general partitioned evaluation)",
    stages: 7,
    c: &[0.0, 0.2, 0.3, 0.8, 8.0 / 9.0, 1.0, 1.0],
    a: &[
        &[],
        &[0.2],
        &[3.0 / 40.0, 9.0 / 40.0],
        &[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
        &[
            19372.0 / 6561.0,
            -25360.0 / 2187.0,
            64448.0 / 6561.0,
            -212.0 / 729.0,
        ],
        &[
            9017.0 / 3168.0,
            -355.0 / 33.0,
            46732.0 / 5247.0,
            49.0 / 176.0,
            -5103.0 / 18656.0,
        ],
        &[
            35.0 / 384.0,
            0.0,
            500.0 / 1113.0,
            125.0 / 192.0,
            -2187.0 / 6784.0,
            11.0 / 84.0,
        ],
    ],
    e: &[
        71.0 / 57600.0,
        0.0,
        -71.0 / 16695.0,
        71.0 / 1920.0,
        -17253.0 / 339200.0,
        22.0 / 525.0,
        -1.0 / 40.0,
    ],
    estimate_order: 5.0,
    dense_output: false,
};

/// The classic fourth-order Runge-Kutta method (Kutta 1901) with the evaluation at the new
/// solution as a fifth stage (first same as last) and the embedded third-order weights
/// `(1/6, 1/3, 1/3, 0, 1/6)` (they satisfy the order conditions `sum b = 1`, `sum b c = 1/2`,
/// `sum b c^2 = 1/3`, `sum b A c = 1/6`, not `sum b A c^2 = 1/12`), so the estimate is
/// `h (k_4 - k_5) / 6`: four new evaluations per step, and stable on the imaginary axis up to
/// `|h w| = 2 sqrt 2` (Hairer and Wanner, *Solving ODEs II*, section IV.2), 2.8 times the
/// step of [`DORMAND_PRINCE`] on an undamped stiff mode for two thirds of its evaluations.
pub const RK4_FSAL: Tableau = Tableau {
    name_minimal: "Runge-Kutta 4(3) on minimal coordinates (closed form)",
    name_general: "Runge-Kutta 4(3) on independent coordinates (general partitioned evaluation)",
    stages: 5,
    c: &[0.0, 0.5, 0.5, 1.0, 1.0],
    a: &[
        &[],
        &[0.5],
        &[0.0, 0.5],
        &[0.0, 0.0, 1.0],
        &[1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0],
    ],
    e: &[0.0, 0.0, 0.0, 1.0 / 6.0, -1.0 / 6.0],
    estimate_order: 4.0,
    dense_output: true,
};

/// The explicit adaptive Runge-Kutta integrator (module documentation): its pair and its
/// workspace, sized once.
pub struct AdaptiveRungeKutta {
    tableau: &'static Tableau,
    steps: EmbeddedSteps,
}

impl AdaptiveRungeKutta {
    /// The pair `tableau` with the error control `control` on the coordinates `independent`
    /// of `system`.
    pub fn new(
        system: &dyn DaeSystem,
        independent: Vec<usize>,
        control: ErrorControl,
        tableau: &'static Tableau,
    ) -> AdaptiveRungeKutta {
        assert!(tableau.stages <= 7 && tableau.a.len() == tableau.stages);
        AdaptiveRungeKutta {
            tableau,
            steps: EmbeddedSteps::new(system, independent, control),
        }
    }
}

/// One try of size h of the pair `tab` from `state` (the step's start and first stage in
/// `steps`); returns the error norm (the solution of the try is left in `steps.z`, `steps.zd`
/// and the evaluation workspace).
fn attempt(
    steps: &mut EmbeddedSteps,
    tab: &Tableau,
    system: &dyn DaeSystem,
    state: &DaeState,
    h: f64,
    work: &mut usize,
) -> Result<f64, StepFailure> {
    let k = steps.k;
    let last = tab.stages - 1;
    // Start every try from the state alone (the dependent positions too): replay is exact.
    steps.rhs.q.copy_from_slice(&steps.q0);
    for s in 1..tab.stages {
        for a in 0..k {
            let mut dz = 0.0;
            let mut dv = 0.0;
            for (j, &w) in tab.a[s].iter().enumerate() {
                dz += w * steps.kz[j][a];
                dv += w * steps.kv[j][a];
            }
            steps.z[a] = steps.z0[a] + h * dz;
            steps.zd[a] = steps.zd0[a] + h * dv;
        }
        let t = if s == last {
            state.t + h
        } else {
            state.t + tab.c[s] * h
        };
        let (kz, kv) = (&mut steps.kz, &mut steps.kv);
        kz[s].copy_from_slice(&steps.zd);
        steps
            .rhs
            .evaluate_stage(system, t, &steps.z, &steps.zd, &mut kv[s], s == last)?;
        *work += 1;
    }
    let tol = steps.local_tolerance(system, h);
    let mut err: f64 = 0.0;
    for a in 0..k {
        let mut ez = 0.0;
        let mut ev = 0.0;
        for (s, &w) in tab.e.iter().enumerate() {
            ez += w * steps.kz[s][a];
            ev += w * steps.kv[s][a];
        }
        err = err.max(steps.error_ratio(a, tol, h * ez, h * ev));
    }
    if !err.is_finite() {
        return Err(StepFailure::NonFinite);
    }
    Ok(err)
}

impl Integrator for AdaptiveRungeKutta {
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
        let tab = self.tableau;
        self.steps.step(
            system,
            state,
            h_max,
            super::MAX_ADAPTIVE_STEP,
            tab.estimate_order,
            |steps, system, state, h, work| attempt(steps, tab, system, state, h, work),
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
            self.tableau.name_minimal
        } else {
            self.tableau.name_general
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
    /// state from the independent coordinates without a Newton iteration), with the RK4(3)
    /// pair, whose stability bounds `|h w|` of every retained mode by 2.8, where the quintic
    /// interpolant is within 1 % of the mode's amplitude. Dormand-Prince steps longer on the
    /// stiff modes: interpolated on the automotive rod (8 elements, 6 modes, tolerance 1e-3)
    /// its midpoint moment was 2.9 % of the peak off the reference instead of 0.11 %, so it
    /// lands on every communication point.
    fn dense_output(&self) -> bool {
        self.steps.closed_form && self.tableau.dense_output
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
        ahead.nmid.fill(0.0);
        ahead.held = true;
        Ok(work)
    }

    /// Quintic Hermite interpolation ([`hermite5`]) of `z` and `z'` from both ends of the held
    /// step, whose accelerations are the method's first and last stages, then one complete
    /// evaluation at `(t, z, z')`.
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
        let steps = &mut self.steps;
        for (a, &i) in steps.rhs.independent.iter().enumerate() {
            let (z, zd) = hermite5(
                s,
                h,
                ahead.z0[a],
                ahead.zd0[a],
                ahead.zdd0[a],
                end.q[i],
                end.v[i],
                end.qdd[i],
            );
            steps.z[a] = z;
            steps.zd[a] = zd;
        }
        steps.finish_interpolation(system, ahead, t, out)
    }
}
