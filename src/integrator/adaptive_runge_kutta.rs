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

/// Largest phase `w_min h` of the lowest mode over one step of ETDRK4
/// ([`super::ExponentialRungeKutta`]). The remainder carries the modes' parametric terms (the
/// axial stiffening moves the first mode's stiffness by about 10 % on the benchmark rod),
/// which oscillate with the modes: over longer
/// steps the stages no longer resolve them and the estimate misses the error (a random
/// parameter set of `tests/error_control.rs` with `w_1 h` up to 2.4 was 1.6 times its
/// tolerance off, 5 times at a tighter one). Measured with this constant set to 1, 1.25 and 1.5
/// on the 30 random parameter sets of `tests/error_control.rs` damped at 5 % at tolerance 1e-2
/// or 3e-3 (where the damping lifts the drift cap to 1.49 and 1.41): the largest error is 0.031,
/// 0.031 and 0.054 of the tolerance; the four sets it binds are 0.007 to 0.012, 0.018 to 0.028
/// and 0.036 to 0.054 of theirs and take 15 to 20 % fewer steps at 1.25 than at 1. A step
/// landing on a communication point may stretch to 1.25 times it (`w_1 h` up to 1.56,
/// [`Integrator::step`]). Below a local tolerance of [`EXPONENTIAL_DRIFT_TOLERANCE`] the cap is
/// tighter ([`exponential_max_phase`]: 0.36 at the default scene's), and on a damped rod it is
/// [`damped_max_phase`].
pub const EXPONENTIAL_MAX_PHASE: f64 = 1.25;

/// Largest phase `w_ax h` of an axial mode over one step of ETDRK4
/// ([`super::ExponentialRungeKutta`]), at the local tolerance [`AXIAL_PHASE_TOLERANCE`] and above ([`axial_max_phase`]). An axial mode's
/// oscillation enters the bending modes' remainder through the axial force; over longer steps
/// the stages sample that coupling too coarsely and the embedded estimate misses its error.
/// Measured with `axial_max_phase` returning one cap at every tolerance, over the 30 random
/// parameter sets of `tests/error_control.rs` (abrupt starts, one revolution, the error against
/// the same model at a thousandth of the tolerance): the largest error of the FFR sets is 0.21
/// of their tolerance with the cap at 1, 0.33 at 2, 0.44 at 3 and 2.5 without a cap (an
/// undamped set, tolerance 3e-3); and the automotive rod at tolerance 1e-3 (`cargo run
/// --release --example exponential_choice`) is 2.5e-4 off at the cap 1 and 1.1e-3 at 2 (416
/// and 317 steps). That missed error does not shrink with the tolerance, so the cap does.
pub const AXIAL_MAX_PHASE: f64 = 2.0;

/// The local tolerance (that of `solver.tolerance = 1e-2` in the RK4(3) pair) at and above
/// which the axial modes' cap is [`AXIAL_MAX_PHASE`] ([`axial_max_phase`]).
pub const AXIAL_PHASE_TOLERANCE: f64 = 3e-4;

/// Smallest phase cap of an axial mode ([`axial_max_phase`] at tight tolerances): the cap at
/// which the measurements at [`AXIAL_MAX_PHASE`] held the FFR sets to 0.21 of their tolerance.
pub const AXIAL_MIN_PHASE: f64 = 1.0;

/// The axial modes' phase cap at the local tolerance `tolerance`: [`AXIAL_MAX_PHASE`] times
/// `(tolerance / AXIAL_PHASE_TOLERANCE)^(1/2)`, between [`AXIAL_MIN_PHASE`] and
/// [`AXIAL_MAX_PHASE`]. The missed error grows about as the square of the phase (the
/// automotive rod at tolerance 1e-3: 4.4 times from the cap 1 to 2), so the cap goes with the
/// square root of the tolerance: 2 at `solver.tolerance = 1e-2`, 1.1 at 3e-3, 1 from 2.5e-3
/// down.
pub fn axial_max_phase(tolerance: f64) -> f64 {
    let ratio = (tolerance / AXIAL_PHASE_TOLERANCE).min(1.0);
    (AXIAL_MAX_PHASE * ratio.sqrt()).max(AXIAL_MIN_PHASE)
}

/// The local tolerance (relative to the amplitude scale) at which the undamped drift cap of the
/// exponential form is `w_1 h = 1`; at other tolerances it is
/// `(tolerance / EXPONENTIAL_DRIFT_TOLERANCE)^(1/5)` ([`exponential_max_phase`]).
pub const EXPONENTIAL_DRIFT_TOLERANCE: f64 = 4.9e-3;

/// The largest phase `w_min h` of ETDRK4 at the local tolerance `tolerance`:
/// `(tolerance / EXPONENTIAL_DRIFT_TOLERANCE)^(1/5)`, at most [`EXPONENTIAL_MAX_PHASE`]. Over a
/// long undamped run the local errors of the parametric and coupling terms of the remainder (the axial stiffening of the first mode and its coupling
/// to the second, whose oscillation the stages sample at `w_2 h / 2`) do not cancel: they add
/// up to a drift of the free vibration's amplitude that grows with the number of steps (a
/// method that is not symmetric has no bounded energy error on a nearly integrable
/// oscillatory system: Hairer, Lubich and Wanner, *Geometric Numerical Integration*, 2nd ed.,
/// 2006, chapters X and XI). Measured on the undamped benchmark rod at fixed steps, the drift
/// per revolution goes with `(w_1 h)^5` (33 times less at half the step); the cap makes it
/// proportional to the tolerance, so the tolerance bounds the amplitude error over a stated
/// number of revolutions rather than over a few (docs/solvers.md, "Long runs"). The error
/// estimate sees no part of it: it measures the local error, whose part across the oscillation
/// (the phase) outweighs the part along it (the amplitude) by far.
pub fn exponential_max_phase(tolerance: f64) -> f64 {
    (tolerance / EXPONENTIAL_DRIFT_TOLERANCE)
        .powf(0.2)
        .min(EXPONENTIAL_MAX_PHASE)
}

/// Relative drift of the lowest mode's free-vibration amplitude per period of that mode at the
/// phase `w_1 h = 1` (docs/solvers.md, "Long runs"), an upper bound: the long-run table's drift
/// at its largest phase (the default scene undamped at tolerance 1e-2, `w_1 h = 0.57`, over
/// 10,000 revolutions) extrapolated along the table's own slope between its smallest and
/// largest phase stays below it (`tests/long_run.rs`, `drift_per_period_bounds_the_long_run_table`,
/// checks it against the generated table and prints the extrapolation). Below `w_1 h = 1`,
/// `DRIFT_PER_PERIOD (w_1 h)^5` bounds the drift from above; between 1 and
/// [`EXPONENTIAL_MAX_PHASE`] (damped rods only) it extrapolates the same power.
pub const DRIFT_PER_PERIOD: f64 = 5.1e-6;

/// The largest phase `w_1 h` of ETDRK4 at the local tolerance `tolerance` on a
/// lowest mode with damping ratio `zeta`: the drift that [`exponential_max_phase`] bounds
/// accumulates only while the free vibration lasts. Damped, a free amplitude loses the
/// fraction `2 pi zeta` per period, so a drift `DRIFT_PER_PERIOD (w_1 h)^5` per period settles
/// at `DRIFT_PER_PERIOD (w_1 h)^5 / (2 pi zeta)` of the amplitude, below `tolerance` for
/// `w_1 h <= (2 pi zeta tolerance / DRIFT_PER_PERIOD)^(1/5)`. The larger of that and
/// [`exponential_max_phase`], at most [`EXPONENTIAL_MAX_PHASE`] (the cap on the stages'
/// sampling of the remainder's parametric terms, which holds whatever the damping).
pub fn damped_max_phase(tolerance: f64, zeta: f64) -> f64 {
    let undamped = exponential_max_phase(tolerance);
    let damped = if zeta > 0.0 {
        (2.0 * std::f64::consts::PI * zeta * tolerance / DRIFT_PER_PERIOD).powf(0.2)
    } else {
        0.0
    };
    undamped.max(damped).min(EXPONENTIAL_MAX_PHASE)
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
    let tol = steps.local_tolerance(system, state, h);
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Undamped, the damped cap is the drift cap; at the default tolerance's local tolerance
    /// (0.03 x 1e-3) a damping ratio of 2.7 % lifts it to `w_1 h = 1` and one of 8.3 % to
    /// `EXPONENTIAL_MAX_PHASE` (docs/solvers.md, "Long runs"), and it grows with the damping in
    /// between. The automotive scene's lowest mode (2 % damping, local tolerance 3e-4) has the
    /// full cap; its piston-rod mode's axial cap, slightly tighter, sets its steps.
    #[test]
    fn damping_lifts_the_drift_cap() {
        let tol = 3e-5;
        assert_eq!(damped_max_phase(tol, 0.0), exponential_max_phase(tol));
        assert!((exponential_max_phase(tol) - 0.36).abs() < 0.01);
        assert!((damped_max_phase(tol, 0.0271) - 1.0).abs() < 1e-3);
        assert_eq!(damped_max_phase(tol, 0.083), EXPONENTIAL_MAX_PHASE);
        assert!(damped_max_phase(tol, 0.082) < EXPONENTIAL_MAX_PHASE);
        let (low, mid) = (damped_max_phase(tol, 1e-3), damped_max_phase(tol, 3e-3));
        assert!(exponential_max_phase(tol) < low && low < mid && mid < 1.0);
        assert_eq!(damped_max_phase(3e-4, 0.02), EXPONENTIAL_MAX_PHASE);
        // The drift it allows settles within the tolerance: D phi^5 / (2 pi zeta) <= tol.
        for zeta in [1e-3, 3e-3, 6e-3, 0.02, 0.05] {
            let phi = damped_max_phase(tol, zeta);
            let settled = DRIFT_PER_PERIOD * phi.powi(5) / (2.0 * std::f64::consts::PI * zeta);
            assert!(settled <= tol * (1.0 + 1e-12), "{zeta}: {settled}");
        }
    }
}
