//! The slider-crank model: the rod, the prescribed crank, the slider, and the integrator the
//! solver settings choose. Starting is in [`super::start`], stepping in [`super::stepping`],
//! the outputs in [`super::outputs`].

use std::cell::Cell;

use nalgebra::Vector2;

use super::crank::{CrankInput, CrankLaw};
use super::dae::{PinAt, SliderCrankDae};
use super::spec::{MechanismSpec, SolverMethod};
use super::state::MechanismState;
use crate::error::ModelError;
use crate::integrator::exponential::Oscillator;
use crate::integrator::generalized_alpha::AlphaErrorControl;
use crate::integrator::{
    AdaptiveRungeKutta, ConstrainedSolve, DaeState, DaeSystem, ErrorControl, ExplicitRk4,
    GeneralizedAlpha, Integrator, StepAhead, DORMAND_PRINCE, RK4_FSAL,
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

/// Error per unit step of the explicit pairs ([`ErrorControl::per_unit_step`]; RK4(3) and,
/// with the same constant, Dormand-Prince, whose free-running steps on the automotive rod
/// otherwise added 0.4 % of the peak deflection at tolerance 1e-3): the local
/// tolerance of a step `h` is at most `solver.tolerance c h / T` with `T` one crank
/// revolution. Without it (error per step alone) a rod whose accuracy needs many small steps
/// per revolution (an undamped stiff fourth mode: 1160 steps in one revolution) collected
/// 6.8 times the stated tolerance (tests/error_control.rs, `explore_case` with CASE=19).
pub const ERROR_PER_UNIT_STEP_RK4: f64 = 2.5;

/// The same for the adaptive generalized-alpha method (second order: its global error goes
/// with the local tolerance to the power 2/3).
pub const LOCAL_TOLERANCE_FACTOR_IMPLICIT: f64 = 0.0025;

/// Smallest deflection amplitude `|v_mid / L|` the error control refers to (before the motion
/// has built up, and for rods that hardly deflect).
pub const AMPLITUDE_FLOOR: f64 = 1e-5;

/// `auto` takes the explicit pair when its stability limit `2.5 / w_max` of the highest
/// retained mode is at least this step, s (modes up to about 80 kHz). Measured on the
/// automotive rod (tests/automotive_reference.rs): with 6 to 8 modes (16 to 32 kHz) the
/// explicit pair is within 0.3 % of the shear beam for deflection, stress and pin forces at
/// 90 to 130 ms, where the adaptive generalized-alpha method it replaced there was 0.9 to
/// 1.4 % off, the same at tolerances 1e-3 and 1e-4 (it was 2e-5 s, modes up to 20 kHz).
pub const AUTO_EXPLICIT_MIN_STEP: f64 = 5e-6;

/// The slider-crank and its preprocessed rod.
pub struct Mechanism {
    pub spec: MechanismSpec,
    pub rod: Box<dyn RodBody>,
    pub(super) crank_length: f64,
    pub(super) slider_mass: f64,
    /// Largest internal step, s.
    pub(super) max_step: f64,
    pub(super) max_halvings: usize,
    pub(super) integrator: Box<dyn Integrator>,
    /// Workspace of the start and of the output solve (taken out while in use).
    pub(super) output_solve: Option<OutputSolve>,
    /// The state before the communication step in progress.
    pub(super) backup: DaeState,
    /// The held step ahead before the communication step (restored with `backup`), saved
    /// only once something would overwrite it ([`AheadBackup`]).
    pub(super) backup_ahead: StepAhead,
    pub(super) ahead_backup: AheadBackup,
    /// The crank pin's motion last computed ([`PinAt::pin`]), shared by the evaluation
    /// contexts and the outputs.
    pub(super) pin_cache: Cell<PinAt>,
}

/// What restores the state's held step ([`StepAhead`]) when a communication step fails: most
/// communication steps inside a held step only read it, so it is copied only before an
/// internal step would overwrite it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum AheadBackup {
    /// No step was held before the communication step (the buffers are workspace).
    NoneHeld,
    /// A step was held and its buffers are as they were (only `held` may have changed).
    Untouched,
    /// A step was held and is saved in `Mechanism::backup_ahead`.
    Saved,
}

/// The saddle-point solve of the outputs and the start, with the projected velocities.
pub(super) struct OutputSolve {
    pub solve: ConstrainedSolve,
    /// Velocities projected on the constraints.
    pub v: Vec<f64>,
}

impl OutputSolve {
    pub fn new(n: usize) -> OutputSolve {
        OutputSolve {
            solve: ConstrainedSolve::new(n, SliderCrankDae::N_CONSTRAINTS),
            v: vec![0.0; n],
        }
    }
}

/// The DAE evaluation context of `state`: the rod, the crank law in force, the slider.
pub(super) fn dae_context<'a>(
    rod: &'a dyn RodBody,
    spec: &MechanismSpec,
    state: &MechanismState,
    pin_cache: &'a Cell<PinAt>,
) -> SliderCrankDae<'a> {
    SliderCrankDae {
        rod,
        crank: CrankLaw {
            length: spec.crank.length,
            t_k: state.input_time,
            input: state.input,
        },
        slider_mass: spec.slider.mass,
        slider_force: state.slider_force,
        slider_offset: spec.mechanism.slider_offset,
        gravity: Vector2::from(spec.mechanism.gravity),
        pin_cache,
    }
}

impl Mechanism {
    /// Validate `spec`, build and preprocess the rod, choose the integrator
    /// (`solver.method = "auto"`: on the modal coordinates while the explicit stability step
    /// `2.5 / w_max` is at least [`AUTO_EXPLICIT_MIN_STEP`], the exponential form of the
    /// RK4(3) pair where the modes leave the pins in place
    /// ([`crate::rod::ffr::FfrKernel::pinned`]) and the classic pair elsewhere; else adaptive
    /// generalized-alpha).
    ///
    /// Why only there: the modes of the pinned rod are the mechanism's own linear oscillators
    /// (the reduced mass is `M_ff` at the undeformed configuration, whatever the crank angle and
    /// the slider mass). Where the modes move the pins (axial modes carrying the slider, modes
    /// of other reference conditions) they couple through the constraints and the split-off
    /// oscillators are not the mechanism's: on the automotive rod, whose axial modes carry the
    /// piston, the exponential form takes twice the steps of the classic pair
    /// (`cargo run --release --example exponential_choice`: 6388 against 3204 for two
    /// revolutions at 628.3 rad/s).
    pub fn new(spec: &MechanismSpec) -> Result<Mechanism, ModelError> {
        spec.validate()?;
        let rod = crate::rod::build(&spec.rod, spec.slider.mass)?;
        let n = rod.n_coordinates() + 1;
        // RK4 is stable for |lambda| h < 2.78: its step is capped at 2.5 / |lambda|_max, the
        // fastest eigenvalue of the retained modes: w_max for a damping ratio zeta <= 1, and
        // w_max (zeta + sqrt(zeta^2 - 1)) for an overdamped one (modal damping with one ratio,
        // docs/physics.md "Elastic and damping forces").
        let zeta = spec.rod.damping_ratio;
        let overdamping = if zeta > 1.0 {
            zeta + (zeta * zeta - 1.0).sqrt()
        } else {
            1.0
        };
        let explicit_limit = 2.5
            / (2.0 * std::f64::consts::PI * rod.highest_frequency_hz() * overdamping).max(1e-300);
        // `auto`: error-controlled steps; the explicit pair on the modal coordinates where
        // its stability limit leaves a useful step, else the implicit method (the segment
        // chain, many or very stiff modes).
        let auto_explicit =
            rod.elastic_coordinates().is_some() && explicit_limit >= AUTO_EXPLICIT_MIN_STEP;
        let (method, adaptive_alpha) = match spec.solver.method {
            SolverMethod::Auto if auto_explicit => (SolverMethod::Dopri5, false),
            SolverMethod::Auto => (SolverMethod::GeneralizedAlpha, true),
            m => (m, false),
        };
        let probe_pins = Cell::default();
        let probe = SliderCrankDae {
            rod: rod.as_ref(),
            crank: CrankLaw {
                length: spec.crank.length,
                t_k: 0.0,
                input: CrankInput::default(),
            },
            slider_mass: spec.slider.mass,
            slider_force: 0.0,
            slider_offset: spec.mechanism.slider_offset,
            gravity: Vector2::from(spec.mechanism.gravity),
            pin_cache: &probe_pins,
        };
        let (integrator, max_step): (Box<dyn Integrator>, f64) = match method {
            SolverMethod::Dopri5 | SolverMethod::Rk43 | SolverMethod::Exponential => {
                let (Some(elastic), Some(omega)) = (
                    rod.elastic_coordinates(),
                    rod.elastic_circular_frequencies(),
                ) else {
                    return Err(ModelError::InvalidParameter {
                        name: "solver.method",
                        value: 0.0,
                        allowed: "generalized_alpha, rk4 or auto with rod.model = segments (dopri5, rk43 and exponential integrate the FFR rod's modal coordinates)".into(),
                    });
                };
                // `auto` with the closed-form minimal coordinates: the RK4(3) pair (module
                // documentation of `crate::integrator::adaptive_runge_kutta`: four evaluations a step and
                // 2.8 times the stable step on the stiff mode); `dopri5` as asked.
                let rk43 = spec.solver.method != SolverMethod::Dopri5;
                let minimal = spec.solver.method == SolverMethod::Auto && probe.has_reduced_rhs();
                let (tableau, factor, per_unit_step) = if rk43 {
                    (
                        &RK4_FSAL,
                        LOCAL_TOLERANCE_FACTOR_RK4,
                        Some(ERROR_PER_UNIT_STEP_RK4 / LOCAL_TOLERANCE_FACTOR_RK4),
                    )
                } else {
                    (
                        &DORMAND_PRINCE,
                        LOCAL_TOLERANCE_FACTOR,
                        Some(ERROR_PER_UNIT_STEP_RK4 / LOCAL_TOLERANCE_FACTOR),
                    )
                };
                let control = ErrorControl {
                    tolerance: spec.solver.tolerance * factor,
                    amplitude_floor: AMPLITUDE_FLOOR,
                    scales: elastic.clone().map(|i| rod.coordinate_scale(i)).collect(),
                    rate_weights: omega.iter().map(|w| w.max(1.0)).collect(),
                    initial_step: spec.solver.step,
                    max_rejections: 40,
                    per_unit_step,
                };
                let forced = spec.solver.method == SolverMethod::Exponential;
                if forced && rod.ffr_kernel().is_none() {
                    return Err(ModelError::InvalidParameter {
                        name: "solver.method",
                        value: rod.n_coordinates() as f64 - 3.0,
                        allowed: format!(
                            "exponential with an FFR rod of 1 to {} modes (its closed form; this rod has more), or auto, rk43, dopri5",
                            crate::rod::ffr::MAX_MODES
                        ),
                    });
                }
                let mut pair = AdaptiveRungeKutta::new(&probe, elastic.collect(), control, tableau);
                if let Some(kernel) = rod.ffr_kernel().filter(|k| forced || minimal && k.pinned) {
                    let oscillators = (0..kernel.n)
                        .map(|i| {
                            Oscillator::new(
                                kernel.stiffness[i] / kernel.m_ff[i][i],
                                kernel.damping[i] / kernel.m_ff[i][i],
                            )
                        })
                        .collect();
                    pair = pair.exponential(oscillators);
                }
                (Box::new(pair), f64::INFINITY)
            }
            SolverMethod::Rk4 => (
                Box::new(ExplicitRk4::new(&probe)),
                spec.solver.step.min(explicit_limit),
            ),
            _ => {
                let mut alpha = GeneralizedAlpha::new(
                    &probe,
                    spec.solver.rho_inf,
                    spec.solver.newton_tolerance,
                    spec.solver.max_newton_iterations,
                );
                if adaptive_alpha {
                    alpha.adaptive = Some(AlphaErrorControl {
                        tolerance: spec.solver.tolerance * LOCAL_TOLERANCE_FACTOR_IMPLICIT,
                        amplitude_floor: AMPLITUDE_FLOOR,
                        initial_step: spec.solver.step,
                        max_rejections: 40,
                    });
                }
                (Box::new(alpha), spec.solver.step)
            }
        };
        let m = probe.n_constraints();
        let backup = DaeState::zeros(n, m);
        // The held step of dense output: sized only for an integrator that has it, so that a
        // restored state cannot bring one to another.
        let k = if integrator.dense_output() {
            rod.elastic_coordinates().map_or(0, |e| e.count())
        } else {
            0
        };
        Ok(Mechanism {
            spec: spec.clone(),
            crank_length: spec.crank.length,
            slider_mass: spec.slider.mass,
            max_step,
            max_halvings: spec.solver.max_halvings,
            integrator,
            output_solve: Some(OutputSolve::new(n)),
            backup_ahead: StepAhead::sized(k, &backup),
            ahead_backup: AheadBackup::NoneHeld,
            backup,
            rod,
            pin_cache: Cell::default(),
        })
    }

    /// Natural frequencies of the rod, Hz.
    pub fn frequencies_hz(&self) -> &[f64] {
        self.rod.frequencies_hz()
    }

    /// The integrator in use (after `auto` resolved it), and what its work counter counts.
    pub fn integrator_name(&self) -> (&'static str, &'static str) {
        (self.integrator.name(), self.integrator.work_unit())
    }

    pub fn crank_length(&self) -> f64 {
        self.crank_length
    }

    /// The DAE of `state` (the crank law in force, the slider force).
    pub fn system(&self, state: &MechanismState) -> SliderCrankDae<'_> {
        dae_context(self.rod.as_ref(), &self.spec, state, &self.pin_cache)
    }

    /// The crank law in force in `state`.
    pub fn crank_law(&self, state: &MechanismState) -> CrankLaw {
        self.system(state).crank
    }

    /// Kinetic energy of rod and slider, J.
    pub fn kinetic_energy(&self, state: &MechanismState) -> f64 {
        let nr = self.rod.n_coordinates();
        let v = &state.dae.v;
        self.rod.kinetic_energy(&state.dae.q[..nr], &v[..nr])
            + 0.5 * self.slider_mass * v[nr] * v[nr]
    }

    /// Strain energy of the rod, J.
    pub fn strain_energy(&self, state: &MechanismState) -> f64 {
        self.rod
            .strain_energy(&state.dae.q[..self.rod.n_coordinates()])
    }
}
