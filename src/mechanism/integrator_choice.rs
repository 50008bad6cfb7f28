//! Which integrator a mechanism gets: [`choose`] decides from the solver settings and the facts
//! of the mechanism it needs ([`MechanismFacts`], from [`super::MechanismParts`]); the caller
//! passes the [`IntegratorChoice`] to [`super::Mechanism::new`], which makes the integrator
//! with [`build`].
//!
//! - `solver.method = "auto"`: error-controlled steps. On the FFR rod's modal coordinates
//!   while the explicit stability step `2.5 / |lambda|_max` of the retained modes is at least
//!   [`AUTO_EXPLICIT_MIN_STEP`]: ETDRK4 ([`ExponentialRungeKutta`]: Krogstad's stages, 2005,
//!   with the weights of Cox and Matthews 2002) where the modes are the mechanism's own
//!   oscillators ([`modes_are_oscillators`]) on the closed-form minimal coordinates, the
//!   RK4(3) pair ([`AdaptiveRungeKutta`]) elsewhere. Else (the segment chain, many or very
//!   stiff modes) the adaptive generalized-alpha method.
//! - `"dopri5"`, `"rk43"`: that pair on the modal coordinates; refused without them (the
//!   segment chain).
//! - The chain on its modes ([`RodBody::modal_oscillators`]): `auto` takes ETDRK4 on its modal
//!   coordinates (the general partitioned evaluation), its pinned bending modes and loaded
//!   axial mode the mechanism's own oscillators.
//! - `"exponential"`: ETDRK4 wherever the closed form exists (an FFR rod of 1 to
//!   [`crate::rod::ffr::MAX_MODES`] modes), also where `auto` would not take it; refused
//!   elsewhere.
//! - `"rk4"`: the fixed-step classic RK4 with projection, its step capped at the stability
//!   step; `"generalized_alpha"`: fixed steps of `solver.step`.
//!
//! Why ETDRK4 only where the modes are the mechanism's own oscillators
//! ([`modes_are_oscillators`]): the modes of the pinned rod are the mechanism's linear
//! oscillators (the reduced mass is `M_ff` at the undeformed configuration, whatever the crank
//! angle and the slider mass), and so are the mass-loaded modes that carry the slider
//! (`crate::modal::mass_loaded_modes`) on the dead centres, and nearly so in between (the slider's share
//! of the reduced mass grows as `1 / cos^2` of the rod's angle to its line). Split off with their
//! effective modal mass ([`effective_modal_mass`]), the remainder is smooth and the step is set
//! by the accuracy of the response. Free axial modes that carry the piston couple through the
//! constraints instead: their split-off oscillators are not the mechanism's, and ETDRK4 took
//! twice the steps of the RK4(3) pair on the automotive rod with free modes (`cargo run
//! --release --example exponential_choice`).
//!
//! ETDRK4's steps are bounded by phase caps measured on this product's rods, which the
//! integrator receives as its largest step ([`exponential_max_step`]): `w_1 h` of the lowest
//! mode at most [`EXPONENTIAL_MAX_PHASE`], tighter at tight tolerances against the drift of a
//! long undamped run ([`exponential_max_phase`]) and as loose as the damping lets that drift
//! settle ([`damped_max_phase`]), and `w_ax h` of the axial modes at most [`axial_max_phase`].

use super::spec::{SolverMethod, SolverSpec};
use crate::error::ModelError;
use crate::integrator::exponential::Oscillator;
use crate::integrator::generalized_alpha::AlphaErrorControl;
use crate::integrator::{
    AdaptiveRungeKutta, DaeSystem, ErrorControl, ExplicitRk4, ExponentialRungeKutta,
    GeneralizedAlpha, Integrator, Tableau, DORMAND_PRINCE, RK4_FSAL,
};
use crate::rod::RodBody;

/// Local error tolerance of the adaptive explicit pair per unit of `solver.tolerance`: the
/// local errors of a run's steps add up, so each step aims below the stated global accuracy
/// (calibrated by `tests/error_control.rs` over random parameter sets: the global error is
/// proportional to the local tolerance).
pub const LOCAL_TOLERANCE_FACTOR: f64 = 0.01;

/// The same for the embedded RK4(3) pair that `auto` takes on the closed-form minimal
/// coordinates (calibrated the same way), at most: it is also held to
/// [`ERROR_PER_UNIT_STEP_RK4`].
pub const LOCAL_TOLERANCE_FACTOR_RK4: f64 = 0.03;

/// Error per unit step of the explicit pairs, RK4(3) and Dormand-Prince
/// ([`ErrorControl::per_unit_step`]): the local tolerance of a step `h` is at most
/// `solver.tolerance c h / T` with `T` one crank revolution, so that the local errors of a
/// revolution's steps add up to a bounded error however many steps it takes. Measured in
/// docs/solvers.md, "Dense output and the error per unit step".
pub const ERROR_PER_UNIT_STEP_RK4: f64 = 2.5;

/// The same for the adaptive generalized-alpha method (second order: its global error goes
/// with the local tolerance to the power 2/3).
pub const LOCAL_TOLERANCE_FACTOR_IMPLICIT: f64 = 0.0025;

/// Smallest deflection amplitude `|v_mid / L|` the error control refers to (before the motion
/// has built up, and for rods that hardly deflect).
pub const AMPLITUDE_FLOOR: f64 = 1e-5;

/// `auto` takes the explicit pair when its stability limit `2.5 / w_max` of the highest
/// retained mode is at least this step, s (modes up to about 80 kHz), else adaptive
/// generalized-alpha. Measured on the automotive rod in docs/physics.md, "Sub-steps, halving
/// and the choice of method".
pub const AUTO_EXPLICIT_MIN_STEP: f64 = 5e-6;

/// Rejected tries of one step of the error-controlled methods before it counts as failed.
const MAX_REJECTIONS: usize = 40;

/// Largest phase `w_min h` of the lowest mode over one step of ETDRK4
/// ([`ExponentialRungeKutta`]): the remainder carries the modes' parametric terms, which
/// oscillate with the modes, and over longer steps the stages no longer resolve them and the
/// embedded estimate misses their error. A step landing on a communication point may stretch to
/// 1.25 times it ([`Integrator::step`]); below a local tolerance of
/// [`EXPONENTIAL_DRIFT_TOLERANCE`] the cap is tighter ([`exponential_max_phase`]), and on a
/// damped rod it is [`damped_max_phase`]. Measured on the random parameter sets of
/// `tests/error_control.rs` in docs/solvers.md, "The exponential integrator" (the limits on its
/// steps).
pub const EXPONENTIAL_MAX_PHASE: f64 = 1.25;

/// Largest phase `w_ax h` of an axial mode over one step of ETDRK4
/// ([`ExponentialRungeKutta`]), at the local tolerance [`AXIAL_PHASE_TOLERANCE`] and above
/// ([`axial_max_phase`]): an axial mode's oscillation enters the bending modes' remainder
/// through the axial force, and over longer steps the stages sample that coupling too coarsely
/// for the embedded estimate to see its error, an error that does not shrink with the
/// tolerance. Measured on the random parameter sets of `tests/error_control.rs` and the
/// automotive rod in docs/solvers.md, "The exponential integrator" (the limits on its steps).
pub const AXIAL_MAX_PHASE: f64 = 2.0;

/// The local tolerance (that of `solver.tolerance = 1e-2` in the RK4(3) pair) at and above
/// which the axial modes' cap is [`AXIAL_MAX_PHASE`] ([`axial_max_phase`]).
pub const AXIAL_PHASE_TOLERANCE: f64 = 3e-4;

/// Smallest phase cap of an axial mode ([`axial_max_phase`] at tight tolerances), at which the
/// random FFR sets stay within a fraction of their tolerance (docs/solvers.md, "The exponential
/// integrator").
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

/// The local tolerance (relative to the amplitude scale) at which the undamped drift cap of
/// ETDRK4 is `w_1 h = 1`; at other tolerances it is
/// `(tolerance / EXPONENTIAL_DRIFT_TOLERANCE)^(1/5)` ([`exponential_max_phase`];
/// docs/solvers.md, "Long runs").
pub const EXPONENTIAL_DRIFT_TOLERANCE: f64 = 4.9e-3;

/// The largest phase `w_min h` of ETDRK4 at the local tolerance `tolerance`:
/// `(tolerance / EXPONENTIAL_DRIFT_TOLERANCE)^(1/5)`, at most [`EXPONENTIAL_MAX_PHASE`]. Over a
/// long undamped run the local errors of the remainder's parametric and coupling terms do not
/// cancel: they add up to a drift of the free vibration's amplitude that grows with the number
/// of steps (a method that is not symmetric has no bounded energy error on a nearly integrable
/// oscillatory system: Hairer, Lubich and Wanner, *Geometric Numerical Integration*, 2nd ed.,
/// 2006, chapters X and XI), and the error estimate, which sees the local error's phase part
/// far more than its amplitude part, does not see it. The drift per revolution goes with
/// `(w_1 h)^5`, so this cap makes it proportional to the tolerance (docs/solvers.md, "Long
/// runs", where the drift is measured).
pub fn exponential_max_phase(tolerance: f64) -> f64 {
    (tolerance / EXPONENTIAL_DRIFT_TOLERANCE)
        .powf(0.2)
        .min(EXPONENTIAL_MAX_PHASE)
}

/// Relative drift of the lowest mode's free-vibration amplitude per period of that mode at the
/// phase `w_1 h = 1`, an upper bound: `DRIFT_PER_PERIOD (w_1 h)^5` bounds the drift per period
/// below `w_1 h = 1` and extrapolates it above (damped rods only). From the long-run table of
/// docs/solvers.md, "Long runs", extrapolated along its own slope; `tests/long_run.rs`
/// (`drift_per_period_bounds_the_long_run_table`) checks it against the table.
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

/// What the choice needs to know of the mechanism.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MechanismFacts {
    /// The number of modal coordinates of the FFR rod; `None` for a rod without them (the
    /// segment chain).
    pub modes: Option<usize>,
    /// Highest retained natural frequency, Hz.
    pub highest_frequency_hz: f64,
    /// The rod's modal damping ratio `zeta` (one ratio for every mode).
    pub damping_ratio: f64,
    /// The system evaluates its equations on minimal coordinates in closed form
    /// ([`DaeSystem::has_reduced_rhs`]).
    pub closed_form: bool,
    /// The FFR rod's closed form exists ([`RodBody::ffr_kernel`]: 1 to
    /// [`crate::rod::ffr::MAX_MODES`] modes), and whether its modes are the mechanism's own
    /// oscillators at the dead centres ([`modes_are_oscillators`]).
    pub kernel_oscillators: Option<bool>,
    /// The slider's mass, kg: it moves with C's axial displacement, so it adds to the modal
    /// mass of the modes that move C ([`effective_modal_mass`]).
    pub slider_mass: f64,
    /// The rod gives its elastic coordinates as the mechanism's own oscillators
    /// ([`RodBody::modal_oscillators`]: the chain on its pinned modes).
    pub modal_oscillators: bool,
}

impl MechanismFacts {
    /// The facts of `rod` with damping ratio `damping_ratio` in the mechanism `system`.
    pub fn of(
        rod: &dyn RodBody,
        damping_ratio: f64,
        slider_mass: f64,
        system: &dyn DaeSystem,
    ) -> MechanismFacts {
        MechanismFacts {
            modes: rod
                .elastic_coordinates()
                .filter(|_| rod.elastic_circular_frequencies().is_some())
                .map(|e| e.len()),
            highest_frequency_hz: rod.highest_frequency_hz(),
            damping_ratio,
            closed_form: system.has_reduced_rhs(),
            kernel_oscillators: rod
                .ffr_kernel()
                .map(|k| modes_are_oscillators(k, slider_mass)),
            slider_mass,
            modal_oscillators: rod.modal_oscillators().is_some(),
        }
    }

    /// The explicit stability step, s: RK4 is stable for `|lambda| h < 2.78`, so its step is
    /// capped at `2.5 / |lambda|_max`, the fastest eigenvalue of the retained modes: `w_max`
    /// for a damping ratio `zeta <= 1`, and `w_max (zeta + sqrt(zeta^2 - 1))` for an
    /// overdamped one (modal damping with one ratio, docs/physics.md "Elastic and damping
    /// forces").
    pub fn explicit_limit(&self) -> f64 {
        let zeta = self.damping_ratio;
        let overdamping = if zeta > 1.0 {
            zeta + (zeta * zeta - 1.0).sqrt()
        } else {
            1.0
        };
        2.5 / (2.0 * std::f64::consts::PI * self.highest_frequency_hz * overdamping).max(1e-300)
    }
}

/// The embedded pair of the explicit adaptive Runge-Kutta integrator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pair {
    /// Dormand-Prince 5(4) ([`DORMAND_PRINCE`]).
    DormandPrince,
    /// The classic RK4 with an embedded third-order estimate ([`RK4_FSAL`]).
    Rk43,
}

/// The integrator chosen, with its settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum IntegratorChoice {
    /// [`AdaptiveRungeKutta`] on the modal coordinates with `pair`.
    AdaptiveRungeKutta { pair: Pair },
    /// [`ExponentialRungeKutta`] (ETDRK4) on the modal coordinates, with the local tolerance of
    /// the RK4(3) pair.
    ExponentialRungeKutta,
    /// [`ExplicitRk4`] with fixed steps of at most `max_step`, s.
    ExplicitRk4 { max_step: f64 },
    /// [`GeneralizedAlpha`]: error-controlled steps with `adaptive`, else fixed steps of
    /// `solver.step`.
    GeneralizedAlpha { adaptive: bool },
}

impl IntegratorChoice {
    /// The largest internal step of the fixed-step methods, s: the stepping driver splits a
    /// communication step into equal steps no larger (the error-controlled methods choose
    /// their own steps and do not use it: unbounded for the explicit pairs, `solver.step` for
    /// generalized-alpha either way).
    pub fn max_step(&self, solver: &SolverSpec) -> f64 {
        match *self {
            IntegratorChoice::AdaptiveRungeKutta { .. }
            | IntegratorChoice::ExponentialRungeKutta => f64::INFINITY,
            IntegratorChoice::ExplicitRk4 { max_step } => max_step,
            IntegratorChoice::GeneralizedAlpha { .. } => solver.step,
        }
    }
}

/// `auto` takes ETDRK4 whatever the stability step of the explicit pair: the
/// closed form exists, its modes are the mechanism's own oscillators
/// ([`modes_are_oscillators`]) and not overdamped (their propagator is exact, so the stiffest
/// mode does not hold the step). Measured on the automotive rod with E and G times 1e4
/// (tests/automotive_rigid_limit.rs): pin forces and crank torque within 3e-6 of the rigid
/// mechanism's peaks, where adaptive generalized-alpha was 1.3 to 3.4 % off.
fn exact_oscillators(facts: &MechanismFacts) -> bool {
    (facts.closed_form && facts.kernel_oscillators == Some(true) || facts.modal_oscillators)
        && facts.damping_ratio <= 1.0
}

/// The refusal of an explicit error-controlled method on a rod without modal coordinates.
fn no_modal_coordinates() -> ModelError {
    ModelError::InvalidParameter {
        name: "solver.method",
        value: 0.0,
        allowed: "generalized_alpha, rk4 or auto with rod.model = segments (dopri5, rk43 and exponential integrate the FFR rod's modal coordinates)".into(),
    }
}

/// Whether the rod gives its modal coordinates as oscillators for ETDRK4: the FFR rod's closed
/// form exists, or the rod gives its modes ([`RodBody::modal_oscillators`]).
fn has_oscillators(facts: &MechanismFacts) -> bool {
    facts.kernel_oscillators.is_some() || facts.modal_oscillators
}

/// The refusal of ETDRK4 on a rod of `modes` modal coordinates without oscillators
/// ([`has_oscillators`]).
fn no_oscillators(modes: usize) -> ModelError {
    ModelError::InvalidInteger {
        name: "solver.method",
        value: modes as i64,
        allowed: format!(
            "exponential with an FFR rod of 1 to {} modes (its closed form; this rod has more) or the chain on its modes, or auto, rk43, dopri5",
            crate::rod::ffr::MAX_MODES
        ),
    }
}

/// The integrator for `solver` on a mechanism with `facts` (module documentation), or why
/// the method asked for does not apply.
pub fn choose(solver: &SolverSpec, facts: &MechanismFacts) -> Result<IntegratorChoice, ModelError> {
    let explicit_limit = facts.explicit_limit();
    let auto = solver.method == SolverMethod::Auto;
    let method = match solver.method {
        SolverMethod::Auto
            if facts.modes.is_some()
                && (explicit_limit >= AUTO_EXPLICIT_MIN_STEP || exact_oscillators(facts)) =>
        {
            SolverMethod::Rk43
        }
        SolverMethod::Auto => return Ok(IntegratorChoice::GeneralizedAlpha { adaptive: true }),
        m => m,
    };
    match method {
        SolverMethod::Dopri5 | SolverMethod::Rk43 | SolverMethod::Exponential => {
            let Some(modes) = facts.modes else {
                return Err(no_modal_coordinates());
            };
            let forced = method == SolverMethod::Exponential;
            if forced && !has_oscillators(facts) {
                return Err(no_oscillators(modes));
            }
            if method == SolverMethod::Dopri5 {
                return Ok(IntegratorChoice::AdaptiveRungeKutta {
                    pair: Pair::DormandPrince,
                });
            }
            let minimal = auto && facts.closed_form;
            let exponential = match facts.kernel_oscillators {
                Some(pinned) => forced || minimal && pinned,
                None => (forced || auto) && facts.modal_oscillators,
            };
            Ok(if exponential {
                IntegratorChoice::ExponentialRungeKutta
            } else {
                IntegratorChoice::AdaptiveRungeKutta { pair: Pair::Rk43 }
            })
        }
        SolverMethod::Rk4 => Ok(IntegratorChoice::ExplicitRk4 {
            max_step: solver.step.min(explicit_limit),
        }),
        SolverMethod::GeneralizedAlpha => {
            Ok(IntegratorChoice::GeneralizedAlpha { adaptive: false })
        }
        SolverMethod::Auto => unreachable!("auto resolved above"),
    }
}

/// The integrator of `choice` for `rod` (with `facts`) in the mechanism `system`, with the
/// settings of `solver`; refused, as [`choose`] refuses it, where the choice does not apply to
/// the rod (the explicit error-controlled methods without modal coordinates, ETDRK4 without
/// their oscillators).
pub fn build(
    choice: IntegratorChoice,
    solver: &SolverSpec,
    facts: &MechanismFacts,
    rod: &dyn RodBody,
    system: &dyn DaeSystem,
) -> Result<Box<dyn Integrator>, ModelError> {
    if let IntegratorChoice::AdaptiveRungeKutta { .. } | IntegratorChoice::ExponentialRungeKutta =
        choice
    {
        let Some(modes) = facts.modes else {
            return Err(no_modal_coordinates());
        };
        if choice == IntegratorChoice::ExponentialRungeKutta && !has_oscillators(facts) {
            return Err(no_oscillators(modes));
        }
    }
    Ok(match choice {
        IntegratorChoice::AdaptiveRungeKutta { pair } => {
            // The RK4(3) pair: four evaluations a step and 2.8 times the stable step on the
            // stiff mode (module documentation of `crate::integrator::adaptive_runge_kutta`).
            let (tableau, factor): (&'static Tableau, f64) = match pair {
                Pair::Rk43 => (&RK4_FSAL, LOCAL_TOLERANCE_FACTOR_RK4),
                Pair::DormandPrince => (&DORMAND_PRINCE, LOCAL_TOLERANCE_FACTOR),
            };
            let (independent, control) = explicit_control(solver, rod, factor);
            Box::new(AdaptiveRungeKutta::new(
                system,
                independent,
                control,
                tableau,
            ))
        }
        IntegratorChoice::ExponentialRungeKutta => {
            let (independent, control) = explicit_control(solver, rod, LOCAL_TOLERANCE_FACTOR_RK4);
            let oscillators: Vec<Oscillator> = match (rod.ffr_kernel(), rod.modal_oscillators()) {
                (Some(kernel), _) => (0..kernel.n)
                    .map(|i| {
                        let mass = effective_modal_mass(kernel, facts.slider_mass, i);
                        Oscillator::new(kernel.stiffness[i] / mass, kernel.damping[i] / mass)
                    })
                    .collect(),
                (None, Some(modes)) => modes
                    .into_iter()
                    .map(|(omega2, damping)| Oscillator::new(omega2, damping))
                    .collect(),
                (None, None) => unreachable!("ETDRK4 needs the rod's oscillators"),
            };
            let max_step =
                exponential_max_step(&oscillators, &rod.axial_mode_indices(), control.tolerance);
            Box::new(ExponentialRungeKutta::new(
                system,
                independent,
                control,
                oscillators,
                max_step,
            ))
        }
        IntegratorChoice::ExplicitRk4 { .. } => Box::new(ExplicitRk4::new(system)),
        IntegratorChoice::GeneralizedAlpha { adaptive } => {
            let mut alpha = GeneralizedAlpha::new(
                system,
                solver.rho_inf,
                solver.newton_tolerance,
                solver.max_newton_iterations,
            );
            if adaptive {
                alpha.adaptive = Some(AlphaErrorControl {
                    tolerance: solver.tolerance * LOCAL_TOLERANCE_FACTOR_IMPLICIT,
                    amplitude_floor: AMPLITUDE_FLOOR,
                    initial_step: solver.step,
                    max_rejections: MAX_REJECTIONS,
                });
            }
            Box::new(alpha)
        }
    })
}

/// The largest step of ETDRK4 on `oscillators` at the local tolerance `tolerance`, s: the
/// lowest oscillator's phase cap with its damping ([`damped_max_phase`] over its circular
/// frequency) and, on the axial oscillators at the indices `axial`, [`axial_max_phase`] over
/// theirs.
fn exponential_max_step(oscillators: &[Oscillator], axial: &[usize], tolerance: f64) -> f64 {
    let lowest = oscillators
        .iter()
        .min_by(|a, b| a.omega2.total_cmp(&b.omega2))
        .expect("at least one oscillator");
    let mut max_step = damped_max_phase(tolerance, lowest.damping_ratio()) / lowest.omega2.sqrt();
    let cap = axial_max_phase(tolerance);
    for &index in axial {
        let omega = oscillators[index].omega2.sqrt();
        if omega > 0.0 {
            max_step = max_step.min(cap / omega);
        }
    }
    max_step
}

/// The independent coordinates of the explicit error-controlled integrators (the rod's modal
/// coordinates) and their error control: the local tolerance `solver.tolerance factor`, each
/// coordinate's scale and its rate weighted by its circular frequency (at least 1 rad/s), error
/// per unit step ([`ERROR_PER_UNIT_STEP_RK4`]).
fn explicit_control(
    solver: &SolverSpec,
    rod: &dyn RodBody,
    factor: f64,
) -> (Vec<usize>, ErrorControl) {
    let elastic = rod.elastic_coordinates().expect("modal coordinates");
    let omega = rod
        .elastic_circular_frequencies()
        .expect("modal frequencies");
    let control = ErrorControl {
        tolerance: solver.tolerance * factor,
        amplitude_floor: AMPLITUDE_FLOOR,
        scales: elastic.clone().map(|i| rod.coordinate_scale(i)).collect(),
        rate_weights: omega.iter().map(|w| w.max(1.0)).collect(),
        initial_step: solver.step,
        max_rejections: MAX_REJECTIONS,
        per_unit_step: Some(ERROR_PER_UNIT_STEP_RK4 / factor),
    };
    (elastic.collect(), control)
}

/// The modal mass of mode `i` in the mechanism at the dead centres, where the rod lies on the
/// slider's line: the rod's own `M_ff,ii` and the slider, which moves with C's axial
/// displacement, `m_s S_C,x,i^2` (the diagonal of the reduced mass `T^T M T` of
/// `crate::mechanism::minimal` at the undeformed configuration there). For mass-loaded modes
/// (`crate::modal::mass_loaded_modes`, the slider's mass added at C's axial coordinate) it is 1; for the
/// modes of the pinned rod `M_ff,ii` (the slider does not move with them).
pub fn effective_modal_mass(
    kernel: &crate::rod::ffr::FfrKernel,
    slider_mass: f64,
    i: usize,
) -> f64 {
    kernel.m_ff[i][i] + slider_mass * kernel.s_c[0][i] * kernel.s_c[0][i]
}

/// Whether the kernel's modes are the mechanism's own linear oscillators at the undeformed
/// configuration on the dead centres (reduced mass the identity there): the modes of the
/// pinned rod ([`crate::rod::ffr::FfrKernel::pinned`]), and the modes whose
/// [`effective_modal_mass`] is 1 (to 1e-6), the mass-loaded modes of `crate::modal::mass_loaded_modes`
/// that carry the slider.
pub fn modes_are_oscillators(kernel: &crate::rod::ffr::FfrKernel, slider_mass: f64) -> bool {
    kernel.pinned
        || (0..kernel.n).all(|i| (effective_modal_mass(kernel, slider_mass, i) - 1.0).abs() < 1e-6)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An FFR rod of three modes up to `f_max` Hz, damping ratio 0.02, in closed form.
    fn ffr(f_max: f64, pinned: bool) -> MechanismFacts {
        MechanismFacts {
            modes: Some(3),
            highest_frequency_hz: f_max,
            damping_ratio: 0.02,
            closed_form: true,
            kernel_oscillators: Some(pinned),
            slider_mass: 0.5,
            modal_oscillators: false,
        }
    }

    /// The chain on its modes: modal coordinates that are the mechanism's own oscillators,
    /// evaluated on the general partitioned path.
    fn modal_chain(f_max: f64) -> MechanismFacts {
        MechanismFacts {
            closed_form: false,
            kernel_oscillators: None,
            modal_oscillators: true,
            ..ffr(f_max, false)
        }
    }

    /// An FFR rod of more modes than the closed form takes (general partitioned evaluation).
    fn ffr_general(f_max: f64) -> MechanismFacts {
        MechanismFacts {
            modes: Some(crate::rod::ffr::MAX_MODES + 2),
            closed_form: false,
            kernel_oscillators: None,
            ..ffr(f_max, false)
        }
    }

    /// The segment chain: no modal coordinates.
    fn segments(f_max: f64) -> MechanismFacts {
        MechanismFacts {
            modes: None,
            closed_form: false,
            kernel_oscillators: None,
            ..ffr(f_max, false)
        }
    }

    fn solver(method: SolverMethod) -> SolverSpec {
        SolverSpec {
            method,
            ..SolverSpec::default()
        }
    }

    fn adaptive_rk(pair: Pair) -> IntegratorChoice {
        IntegratorChoice::AdaptiveRungeKutta { pair }
    }

    const ETDRK4: IntegratorChoice = IntegratorChoice::ExponentialRungeKutta;

    /// A frequency whose stability step is just above / below [`AUTO_EXPLICIT_MIN_STEP`].
    fn f_at_limit(factor: f64) -> f64 {
        2.5 / (2.0 * std::f64::consts::PI * AUTO_EXPLICIT_MIN_STEP) * factor
    }

    #[test]
    fn auto_takes_the_exponential_form_where_the_modes_leave_the_pins() {
        let choice = choose(&solver(SolverMethod::Auto), &ffr(2000.0, true)).unwrap();
        assert_eq!(choice, ETDRK4);
        assert_eq!(choice.max_step(&SolverSpec::default()), f64::INFINITY);
    }

    #[test]
    fn auto_takes_the_classic_pair_where_the_modes_move_the_pins_or_without_closed_form() {
        let auto = solver(SolverMethod::Auto);
        assert_eq!(
            choose(&auto, &ffr(2000.0, false)).unwrap(),
            adaptive_rk(Pair::Rk43)
        );
        assert_eq!(
            choose(&auto, &ffr_general(2000.0)).unwrap(),
            adaptive_rk(Pair::Rk43)
        );
    }

    /// Up to the stability step [`AUTO_EXPLICIT_MIN_STEP`] the explicit pair, beyond it (and
    /// for an overdamped rod, whose fastest eigenvalue is above its frequency) adaptive
    /// generalized-alpha, as for the segment chain; ETDRK4 at any stiffness
    /// where the modes are the mechanism's oscillators.
    #[test]
    fn auto_takes_adaptive_generalized_alpha_for_stiff_rods_and_the_segment_chain() {
        let auto = solver(SolverMethod::Auto);
        let alpha = IntegratorChoice::GeneralizedAlpha { adaptive: true };
        assert_eq!(
            choose(&auto, &ffr(f_at_limit(0.999), false)).unwrap(),
            adaptive_rk(Pair::Rk43)
        );
        assert_eq!(
            choose(&auto, &ffr(f_at_limit(1.001), false)).unwrap(),
            alpha
        );
        assert_eq!(
            choose(&auto, &ffr(f_at_limit(100.0), true)).unwrap(),
            ETDRK4
        );
        let overdamped = MechanismFacts {
            damping_ratio: 1.5,
            ..ffr(f_at_limit(0.999), true)
        };
        assert!(overdamped.explicit_limit() < AUTO_EXPLICIT_MIN_STEP);
        assert_eq!(choose(&auto, &overdamped).unwrap(), alpha);
        assert_eq!(choose(&auto, &segments(100.0)).unwrap(), alpha);
        assert_eq!(alpha.max_step(&auto), auto.step);
        // The chain on its modes: ETDRK4 at any stiffness of its modes.
        for f in [100.0, f_at_limit(100.0)] {
            assert_eq!(choose(&auto, &modal_chain(f)).unwrap(), ETDRK4);
        }
    }

    /// `dopri5` and `rk43` are the classic pairs wherever there are modal coordinates, also
    /// where `auto` would take ETDRK4 or the implicit method.
    #[test]
    fn forced_pairs_are_classic() {
        for facts in [ffr(2000.0, true), ffr(1e6, true), ffr_general(2000.0)] {
            assert_eq!(
                choose(&solver(SolverMethod::Dopri5), &facts).unwrap(),
                adaptive_rk(Pair::DormandPrince)
            );
            assert_eq!(
                choose(&solver(SolverMethod::Rk43), &facts).unwrap(),
                adaptive_rk(Pair::Rk43)
            );
        }
    }

    /// `exponential` wherever the closed form exists, pinned or not.
    #[test]
    fn forced_exponential_form_where_the_closed_form_exists() {
        for pinned in [true, false] {
            assert_eq!(
                choose(&solver(SolverMethod::Exponential), &ffr(2000.0, pinned)).unwrap(),
                ETDRK4
            );
        }
    }

    /// The refusals name the parameter and say what would be allowed.
    #[test]
    fn refusals_say_why() {
        let Err(ModelError::InvalidInteger {
            name,
            value,
            allowed,
        }) = choose(&solver(SolverMethod::Exponential), &ffr_general(2000.0))
        else {
            panic!("exponential without the closed form accepted")
        };
        assert_eq!(name, "solver.method");
        assert_eq!(value, (crate::rod::ffr::MAX_MODES + 2) as i64);
        assert!(
            allowed.contains("exponential with an FFR rod of 1 to"),
            "{allowed}"
        );
        for method in [
            SolverMethod::Dopri5,
            SolverMethod::Rk43,
            SolverMethod::Exponential,
        ] {
            let Err(ModelError::InvalidParameter { name, allowed, .. }) =
                choose(&solver(method), &segments(100.0))
            else {
                panic!("{method:?} on the segment chain accepted")
            };
            assert_eq!(name, "solver.method");
            assert!(allowed.contains("integrate the FFR rod's modal coordinates"));
        }
    }

    /// The fixed-step methods: RK4 capped at its stability step, generalized-alpha at
    /// `solver.step`, on either rod model.
    #[test]
    fn fixed_step_methods() {
        let rk4 = solver(SolverMethod::Rk4);
        for facts in [ffr(100.0, true), segments(100.0)] {
            assert_eq!(
                choose(&rk4, &facts).unwrap(),
                IntegratorChoice::ExplicitRk4 { max_step: rk4.step }
            );
        }
        let stiff = ffr(1e5, true);
        let choice = choose(&rk4, &stiff).unwrap();
        assert_eq!(
            choice,
            IntegratorChoice::ExplicitRk4 {
                max_step: stiff.explicit_limit()
            }
        );
        assert!(choice.max_step(&rk4) < rk4.step);
        let alpha = solver(SolverMethod::GeneralizedAlpha);
        for facts in [ffr(1e5, true), segments(100.0)] {
            let choice = choose(&alpha, &facts).unwrap();
            assert_eq!(
                choice,
                IntegratorChoice::GeneralizedAlpha { adaptive: false }
            );
            assert_eq!(choice.max_step(&alpha), alpha.step);
        }
    }

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
