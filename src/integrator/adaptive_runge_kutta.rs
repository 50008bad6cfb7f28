//! Explicit adaptive Runge-Kutta integration with error control on the mechanism's independent
//! coordinates ([`PartitionedRhs`]; minimal coordinates in closed form where the system has
//! them, [`DaeSystem::reduced_rhs`]): `y = (z, z')`, `y' = (z', z'')`. One integrator,
//! [`AdaptiveRungeKutta`], parameterized by its embedded pair ([`Tableau`]) and its form:
//!
//! - [`DORMAND_PRINCE`]: the Dormand-Prince 5(4) pair (J. R. Dormand and P. J. Prince, "A family
//!   of embedded Runge-Kutta formulae", J. Comput. Appl. Math. 6, 1980; Hairer, Norsett and
//!   Wanner, *Solving ODEs I*, 2nd ed., table II.5.2 and section II.4);
//! - [`RK4_FSAL`]: the classic RK4 with an embedded third-order estimate, which `auto` takes on
//!   the FFR slider-crank: its step is bounded by the stiffest retained mode, where RK4 is
//!   stable to 2.8 times the Dormand-Prince step with four evaluations instead of six;
//! - the exponential form of the RK4(3) pair ([`AdaptiveRungeKutta::exponential`]): ETDRK4 in
//!   the stages of Krogstad (2005) and the weights of Cox and Matthews (2002) with each mode's
//!   oscillator exact ([`super::exponential`]), whose steps no mode's frequency bounds; `auto`
//!   takes it where the modes are the mechanism's own oscillators (they leave the pins in place,
//!   or they carry the slider as mass-loaded modes: `crate::mechanism::integrator_choice`).
//!
//! One step of size h: the stages (the last one at `t + h` on the new solution, reused as the
//! first stage of the next step: "first same as last"), the higher-order solution propagated
//! and the difference to the embedded one as the local error estimate `e`. Error norm
//! (maximum norm, so the control is pointwise):
//! `err = max_i |e_i| / sc_i`, `sc_z = tol max(A, A_min) s`, `sc_z' = w sc_z`,
//! with `A` the amplitude of the motion the accuracy is stated for (the mechanism keeps the
//! largest `|v_mid / L|` so far in [`DaeState::amplitude`]), `A_min` a floor, `s` the
//! coordinate's scale (its value for a deflection of the rod's length) and `w` the mode's
//! circular frequency. The step is accepted when `err <= 1`; the next one is
//! `h min(5, max(0.2, 0.9 err^(-1/p)))` with `p` the order of the estimate (5 or 4; after a
//! rejection, at most h). The step proposal is
//! part of the state ([`DaeState::step_hint`]), so a restored state replays bit for bit.

use super::exponential::{self, EtdWeights, Oscillator, Propagator};
use super::failure::{StepError, StepFailure};
use super::partitioned::PartitionedRhs;
use super::state::{hermite5, DaeState, StepAhead};
use super::system::DaeSystem;
use super::{quantize_step, Integrator};

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

/// The explicit adaptive Runge-Kutta integrator (module documentation): its pair, its form
/// (classic or exponential) and its workspace, sized once.
pub struct AdaptiveRungeKutta {
    tableau: &'static Tableau,
    /// The system evaluates its reduced right-hand side in closed form (for the name).
    closed_form: bool,
    rhs: PartitionedRhs,
    control: ErrorControl,
    k: usize,
    /// Stage derivatives: `kz[s]` = z' and `kv[s]` = z'' at stage s (k each).
    kz: [Vec<f64>; 7],
    kv: [Vec<f64>; 7],
    z0: Vec<f64>,
    zd0: Vec<f64>,
    z: Vec<f64>,
    zd: Vec<f64>,
    q0: Vec<f64>,
    /// The first stage must be evaluated (the inputs may have changed at this communication
    /// point), not taken from the state's accelerations.
    fresh: bool,
    /// The exponential form ([`AdaptiveRungeKutta::exponential`]), if taken.
    exponential: Option<ExponentialForm>,
}

/// The exponential form of the RK4(3) pair and its workspace (sized once).
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
    /// [`damped_max_phase`] over the lowest oscillator's circular frequency, s, and
    /// [`axial_max_phase`] over the axial oscillators' ([`AdaptiveRungeKutta::cap_phase_on`]).
    max_step: f64,
}

/// Largest phase `w_min h` of the lowest mode over one step of the exponential form. The
/// remainder carries the modes' parametric terms (the axial stiffening moves the first mode's
/// stiffness by about 10 % on the benchmark rod), which oscillate with the modes: over longer
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

/// Largest phase `w_ax h` of an axial mode over one step of the exponential form, at the
/// local tolerance [`AXIAL_PHASE_TOLERANCE`] and above ([`axial_max_phase`]). An axial mode's
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

/// The largest phase `w_min h` of the exponential form at the local tolerance `tolerance`:
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

/// The largest phase `w_1 h` of the exponential form at the local tolerance `tolerance` on a
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

/// The name of the exponential form on minimal coordinates (it is only taken there).
const EXPONENTIAL_NAME: &str =
    "exponential Runge-Kutta 4(3) (ETDRK4, modal oscillators exact) on minimal coordinates (closed form)";

/// The same on the general partitioned evaluation (the chain on its modes).
const EXPONENTIAL_NAME_GENERAL: &str =
    "exponential Runge-Kutta 4(3) (ETDRK4, modal oscillators exact) on the modal coordinates (general evaluation)";

impl AdaptiveRungeKutta {
    /// The pair `tableau` with the error control `control` on the coordinates `independent`
    /// of `system` (classic form; [`AdaptiveRungeKutta::exponential`] for the other).
    pub fn new(
        system: &dyn DaeSystem,
        independent: Vec<usize>,
        control: ErrorControl,
        tableau: &'static Tableau,
    ) -> AdaptiveRungeKutta {
        assert!(tableau.stages <= 7 && tableau.a.len() == tableau.stages);
        let rhs = PartitionedRhs::new(system, independent);
        let k = rhs.k();
        assert_eq!(control.rate_weights.len(), k);
        let stage = || std::array::from_fn(|_| vec![0.0; k]);
        AdaptiveRungeKutta {
            tableau,
            closed_form: system.has_reduced_rhs(),
            q0: vec![0.0; system.n_coordinates()],
            rhs,
            control,
            k,
            kz: stage(),
            kv: stage(),
            z0: vec![0.0; k],
            zd0: vec![0.0; k],
            z: vec![0.0; k],
            zd: vec![0.0; k],
            fresh: true,
            exponential: None,
        }
    }

    /// The exponential form of the RK4(3) pair: the ETDRK4 method of Krogstad
    /// ([`EtdWeights`]) with each independent coordinate `a`'s linear oscillator
    /// `oscillators[a]` split off and taken exactly ([`super::exponential`]), the remainder
    /// integrated against it with the phi functions; its embedded estimate
    /// `h f3(hA) e2 (N_c - N_end)` (the classic pair's `h (k_4 - k_5) / 6` for `A -> 0`; `N_end`
    /// the remainder at the new solution, first same as last). A mode's own oscillation then
    /// costs no steps, and neither does the forced response of a stiff mode: the step
    /// follows how fast the remainder (the coupling to the rigid motion, the stiffening, the
    /// forcing) changes. Dense output by the oscillator's exact response to a quadratic
    /// remainder ([`Integrator::interpolate`]). Only for [`RK4_FSAL`].
    pub fn exponential(mut self, oscillators: Vec<Oscillator>) -> AdaptiveRungeKutta {
        assert_eq!(oscillators.len(), self.k);
        assert!(self.tableau.c == RK4_FSAL.c && self.tableau.e == RK4_FSAL.e);
        let k = self.k;
        // The lowest oscillator's phase cap, with its damping (damped_max_phase).
        let lowest = oscillators
            .iter()
            .min_by(|a, b| a.omega2.total_cmp(&b.omega2))
            .expect("at least one oscillator");
        let max_step =
            damped_max_phase(self.control.tolerance, lowest.damping_ratio()) / lowest.omega2.sqrt();
        self.exponential = Some(ExponentialForm {
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
        });
        self
    }

    /// The exponential form with the phase `w h` of oscillator `index` (an axial mode) capped
    /// at [`axial_max_phase`] too: its oscillation enters the bending modes' remainder through
    /// the axial force, and above the cap the embedded estimate loses sight of that coupling's
    /// error (the measurements at [`AXIAL_MAX_PHASE`]).
    pub fn cap_phase_on(mut self, index: usize) -> AdaptiveRungeKutta {
        let cap = axial_max_phase(self.control.tolerance);
        if let Some(form) = self.exponential.as_mut() {
            let omega = form.oscillators[index].omega2.sqrt();
            if omega > 0.0 {
                form.max_step = form.max_step.min(cap / omega);
            }
        }
        self
    }

    /// The largest step proposed: [`super::MAX_ADAPTIVE_STEP`], in the exponential form also
    /// the phase caps ([`damped_max_phase`] on the lowest oscillator, [`Self::cap_phase_on`]).
    fn max_step(&self) -> f64 {
        match &self.exponential {
            Some(form) => form.max_step.min(super::MAX_ADAPTIVE_STEP),
            None => super::MAX_ADAPTIVE_STEP,
        }
    }

    /// `err^(-1/p)`, `p` the order of the estimate (two square roots for p = 4).
    fn root(&self, err: f64) -> f64 {
        if self.tableau.estimate_order == 4.0 {
            1.0 / err.sqrt().sqrt()
        } else {
            err.powf(-1.0 / self.tableau.estimate_order)
        }
    }

    /// One try of size h from `state`; returns the error norm (the solution of the try is left
    /// in `self.z`, `self.zd` and the evaluation workspace).
    fn attempt(
        &mut self,
        system: &dyn DaeSystem,
        state: &DaeState,
        h: f64,
        work: &mut usize,
    ) -> Result<f64, StepFailure> {
        if let Some(mut form) = self.exponential.take() {
            let result = self.attempt_exponential(&mut form, system, state, h, work);
            self.exponential = Some(form);
            return result;
        }
        let k = self.k;
        let tab = self.tableau;
        let last = tab.stages - 1;
        // Start every try from the state alone (the dependent positions too): replay is exact.
        self.rhs.q.copy_from_slice(&self.q0);
        for s in 1..tab.stages {
            for a in 0..k {
                let mut dz = 0.0;
                let mut dv = 0.0;
                for (j, &w) in tab.a[s].iter().enumerate() {
                    dz += w * self.kz[j][a];
                    dv += w * self.kv[j][a];
                }
                self.z[a] = self.z0[a] + h * dz;
                self.zd[a] = self.zd0[a] + h * dv;
            }
            let t = if s == last {
                state.t + h
            } else {
                state.t + tab.c[s] * h
            };
            let (kz, kv) = (&mut self.kz, &mut self.kv);
            kz[s].copy_from_slice(&self.zd);
            self.rhs
                .evaluate_stage(system, t, &self.z, &self.zd, &mut kv[s], s == last)?;
            *work += 1;
        }
        let tol = self.local_tolerance(system, state, h);
        let mut err: f64 = 0.0;
        for a in 0..k {
            let mut ez = 0.0;
            let mut ev = 0.0;
            for (s, &w) in tab.e.iter().enumerate() {
                ez += w * self.kz[s][a];
                ev += w * self.kv[s][a];
            }
            err = err.max(self.error_ratio(a, tol, h * ez, h * ev));
        }
        if !err.is_finite() {
            return Err(StepFailure::NonFinite);
        }
        Ok(err)
    }

    /// The local tolerance of a step `h` from `state` (module documentation; error per unit
    /// step where set).
    fn local_tolerance(&self, system: &dyn DaeSystem, state: &DaeState, h: f64) -> f64 {
        let mut tol = self.control.tolerance * state.amplitude.max(self.control.amplitude_floor);
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
    fn error_ratio(&self, a: usize, tol: f64, ez: f64, ev: f64) -> f64 {
        let sc_z = tol * self.control.scales[a];
        let sc_v = self.control.rate_weights[a] * sc_z;
        (ez.abs() / sc_z).max(ev.abs() / sc_v)
    }

    /// [`AdaptiveRungeKutta::attempt`] in the exponential form ([`AdaptiveRungeKutta::exponential`]): the stages of
    /// [`EtdWeights`] at `t + h/2` (a, b), `t + h` (c) and the new solution (first same as
    /// last), the estimate `h f3 (N_c - N_end)`. Stages b and c take the change of the
    /// remainder against the oscillator by `phi_2` (Krogstad's stages): the stages of Cox and
    /// Matthews, which take the remainder at one stage as constant over the next, let the
    /// undamped benchmark rod's first mode gain 10 % of amplitude in 100 s (2,400 revolutions,
    /// 1,000 steps a second at `w_1 h = 0.87`), Krogstad's lose 0.8 %.
    fn attempt_exponential(
        &mut self,
        form: &mut ExponentialForm,
        system: &dyn DaeSystem,
        state: &DaeState,
        h: f64,
        work: &mut usize,
    ) -> Result<f64, StepFailure> {
        let k = self.k;
        if form.weights_h != h {
            std::mem::swap(&mut form.weights, &mut form.previous);
            std::mem::swap(&mut form.weights_h, &mut form.previous_h);
            if form.weights_h != h {
                for (w, osc) in form.weights.iter_mut().zip(&form.oscillators) {
                    *w = EtdWeights::new(osc, h);
                }
                form.weights_h = h;
            }
        }
        let weights = &form.weights[..k];
        let oscillators = &form.oscillators[..k];
        let (z0, zd0) = (&self.z0[..k], &self.zd0[..k]);
        for (a, free) in form.free[..k].iter_mut().enumerate() {
            form.remainders[0][a] = oscillators[a].remainder(z0[a], zd0[a], self.kv[0][a]);
            let (zh, vh) = exponential::apply(&weights[a].half, z0[a], zd0[a]);
            let (zf, vf) = exponential::apply(&weights[a].full, z0[a], zd0[a]);
            *free = [zh, vh, zf, vf];
        }
        self.rhs.q.copy_from_slice(&self.q0);
        for s in 1..5 {
            exponential_stage(
                s,
                h,
                weights,
                &form.free[..k],
                &form.remainders,
                &mut self.z[..k],
                &mut self.zd[..k],
            );
            let t = state.t + if s <= 2 { 0.5 * h } else { h };
            self.rhs
                .evaluate_stage(system, t, &self.z, &self.zd, &mut self.kv[s], s == 4)?;
            *work += 1;
            let (z, zd, kv) = (&self.z[..k], &self.zd[..k], &self.kv[s][..k]);
            for (a, n) in form.remainders[s][..k].iter_mut().enumerate() {
                *n = oscillators[a].remainder(z[a], zd[a], kv[a]);
            }
        }
        let tol = self.local_tolerance(system, state, h);
        let mut err: f64 = 0.0;
        for a in 0..k {
            let d = h * (form.remainders[3][a] - form.remainders[4][a]);
            let f3 = weights[a].f[2];
            err = err.max(self.error_ratio(a, tol, f3[0] * d, f3[1] * d));
        }
        if !err.is_finite() {
            return Err(StepFailure::NonFinite);
        }
        Ok(err)
    }
}

/// Stage `s` of the exponential form ([`EtdWeights`]; 1, 2: a, b at `t + h/2`; 3: c at
/// `t + h`; 4: the new solution) from the free responses `free` of the step's start
/// (`E(h/2) y0`, `E(h) y0`) and the remainders `n` of the stages before, into `z`, `z'`:
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

impl Integrator for AdaptiveRungeKutta {
    /// Takes one accepted step of at most `h` (the rest of the communication step): the
    /// state's proposal, stretched to `h` when within 25 % of it.
    fn step(
        &mut self,
        system: &dyn DaeSystem,
        state: &mut DaeState,
        h_max: f64,
    ) -> Result<usize, StepError> {
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
        .min(self.max_step());
        let mut h = if h_max <= 1.25 * proposal {
            h_max
        } else {
            proposal
        };
        let mut rejected = false;
        for _ in 0..=self.control.max_rejections {
            // A failed evaluation (a position solve that does not converge, a singular matrix)
            // counts as a large error: the step shrinks.
            let err = self
                .attempt(system, state, h, &mut work)
                .unwrap_or(f64::INFINITY);
            if err <= 1.0 {
                let grow = if err == 0.0 {
                    5.0
                } else {
                    (0.9 * self.root(err)).clamp(0.2, 5.0)
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
                let cap = self.max_step();
                state.step_hint = if next >= cap {
                    cap
                } else {
                    quantize_step(next)
                };
                self.fresh = false;
                return Ok(work);
            }
            rejected = true;
            let shrink = if err.is_finite() {
                (0.9 * self.root(err)).clamp(0.2, 1.0)
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

    /// The inputs may change at a communication point: the next step evaluates its first stage.
    fn forget_between_steps(&mut self) {
        self.fresh = true;
    }

    /// The inputs did not change at this communication point: the state's accelerations
    /// (the last stage of the previous step) are the first stage.
    fn reuse_first_stage(&mut self) {
        self.fresh = false;
    }

    fn name(&self) -> &'static str {
        if self.exponential.is_some() {
            if self.closed_form {
                EXPONENTIAL_NAME
            } else {
                EXPONENTIAL_NAME_GENERAL
            }
        } else if self.closed_form {
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
        self.closed_form && self.tableau.dense_output
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
        ahead.t0 = state.t;
        ahead.z0.copy_from_slice(&self.z0);
        ahead.zd0.copy_from_slice(&self.zd0);
        ahead.zdd0.copy_from_slice(&self.kv[0]);
        if let Some(form) = &self.exponential {
            // The remainder at the step's middle for the interpolant: the mean of stages a, b.
            for (m, (na, nb)) in ahead
                .nmid
                .iter_mut()
                .zip(form.remainders[1].iter().zip(&form.remainders[2]))
            {
                *m = 0.5 * (na + nb);
            }
        } else {
            ahead.nmid.fill(0.0);
        }
        ahead.held = true;
        Ok(work)
    }

    /// Quintic Hermite interpolation ([`hermite5`]) of `z` and `z'` from both ends of the held
    /// step, whose accelerations are the method's first and last stages; in the exponential
    /// form the oscillator's exact response over `tau = t - t0` to the remainder taken as the
    /// quadratic through its values at the step's start, middle ([`StepAhead::nmid`]) and end
    /// ([`Oscillator::quadratic_response`]: `E(tau)` and the polynomial particular solution),
    /// plus `tau / h` times its miss of the step's end (a local error), so that it ends on the
    /// step's solution. Then one complete evaluation at `(t, z, z')`.
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
        if let Some(form) = self.exponential.as_mut() {
            if form.interpolation_h != h {
                for (e, osc) in form.full.iter_mut().zip(&form.oscillators) {
                    *e = osc.propagator(h);
                }
                form.interpolation_h = h;
            }
            let tau = s * h;
            let inv_h = 1.0 / h;
            for (a, &i) in self.rhs.independent.iter().enumerate() {
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
                self.z[a] = z + s * (end.q[i] - z1);
                self.zd[a] = zd + s * (end.v[i] - zd1);
            }
        } else {
            self.hermite_interpolation(ahead, s, h);
        }
        // The end's dependent positions choose the assembly branch and the frame angle's turn.
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

impl AdaptiveRungeKutta {
    /// [`hermite5`] of each independent coordinate at `s` of the held step (of size `h`),
    /// into `self.z`, `self.zd`.
    fn hermite_interpolation(&mut self, ahead: &StepAhead, s: f64, h: f64) {
        let end = &ahead.end;
        for (a, &i) in self.rhs.independent.iter().enumerate() {
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
            self.z[a] = z;
            self.zd[a] = zd;
        }
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
