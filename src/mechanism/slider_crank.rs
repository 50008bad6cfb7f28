//! The slider-crank model: the rod, the prescribed crank, the slider, and its integrator.
//! [`MechanismParts`] is the mechanism before its integrator (the rod built and preprocessed,
//! and the facts the integrator choice needs); the caller chooses the integrator
//! ([`super::integrator_choice::choose`]) and [`Mechanism::new`] puts the two together.
//! Starting is in [`super::start`], stepping in [`super::stepping`], the outputs in
//! [`super::outputs`].

use std::cell::Cell;

use nalgebra::Vector2;

use super::crank::{CrankInput, CrankLaw};
use super::dae::{PinAt, SliderCrankDae};
use super::gas_force::GasForce;
use super::integrator_choice::{self, IntegratorChoice, MechanismFacts};
use super::spec::MechanismSpec;
use super::state::MechanismState;
use crate::error::ModelError;
use crate::integrator::{ConstrainedSolve, DaeState, DaeSystem, Integrator, StepAhead};
use crate::rod::{PhysicsChoice, RodBody};

/// The slider-crank and its preprocessed rod.
pub struct Mechanism {
    /// The spec with the rod's `auto` settings resolved ([`crate::rod::physics_choice`]).
    pub spec: MechanismSpec,
    /// What the `auto` settings chose, and the model's share of the error estimate.
    pub physics: PhysicsChoice,
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
    /// The force of `[slider.gas_force]`, preprocessed.
    pub(super) gas: Option<GasForce>,
    /// When the communication step in progress must end at the latest
    /// ([`super::stepping::WALL_GUARD_SECONDS`] after it started).
    pub(super) call_deadline: std::time::Instant,
    /// Work units of one evaluation, for the work budget ([`evaluation_cost`]), once.
    pub(super) evaluation_cost: f64,
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
    gas: Option<&'a GasForce>,
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
        gas,
        slider_offset: spec.mechanism.slider_offset,
        gravity: Vector2::from(spec.mechanism.gravity),
        pin_cache,
    }
}

/// The work units of one evaluation of `rod` with the slider ([`crate::rod::cost`]): the dense
/// terms of its [`RodBody::work_coordinates`] and the slider, and what the rod adds
/// ([`RodBody::extra_evaluation_cost`]). A rod one evaluation of which costs more than a
/// communication step can afford [`crate::rod::cost::MIN_EVALUATIONS_PER_CALL`] times within
/// the work budget of one call (`stepping::WORK_BUDGET`) is refused: every call would be
/// refused or nearly so.
fn evaluation_cost(rod: &dyn RodBody) -> Result<f64, ModelError> {
    use crate::rod::cost::{dense_evaluation, MIN_EVALUATIONS_PER_CALL};
    let n = rod.work_coordinates() + 1;
    let cost = dense_evaluation(n) + rod.extra_evaluation_cost();
    let allowed = super::stepping::WORK_BUDGET / MIN_EVALUATIONS_PER_CALL;
    if cost <= allowed {
        return Ok(cost);
    }
    Err(ModelError::TooCostly {
        message: format!(
            "one evaluation of this rod ({n} coordinates) takes {cost:.2e} work units, more than the {allowed:.2e} that leave a communication step {MIN_EVALUATIONS_PER_CALL} evaluations within the work budget of one call; retain fewer modes or take fewer rod.elements"
        ),
    })
}

/// A mechanism before its integrator: the spec with the rod's `auto` settings resolved, the
/// rod built and preprocessed, and what the integrator choice needs to know of it.
pub struct MechanismParts {
    /// The spec with the rod's `auto` settings resolved ([`crate::rod::physics_choice`]).
    spec: MechanismSpec,
    /// What the `auto` settings chose, and the model's share of the error estimate.
    physics: PhysicsChoice,
    rod: Box<dyn RodBody>,
    /// What [`integrator_choice::choose`] needs to know of the mechanism.
    facts: MechanismFacts,
    /// Work units of one evaluation ([`evaluation_cost`]).
    evaluation_cost: f64,
}

/// The mechanism's DAE for probing its shape and facts: the rod with the crank at rest at
/// time 0, no slider force, no gas force.
fn probe<'a>(
    rod: &'a dyn RodBody,
    spec: &MechanismSpec,
    pins: &'a Cell<PinAt>,
) -> SliderCrankDae<'a> {
    SliderCrankDae {
        rod,
        crank: CrankLaw {
            length: spec.crank.length,
            t_k: 0.0,
            input: CrankInput::default(),
        },
        slider_mass: spec.slider.mass,
        slider_force: 0.0,
        gas: None,
        slider_offset: spec.mechanism.slider_offset,
        gravity: Vector2::from(spec.mechanism.gravity),
        pin_cache: pins,
    }
}

impl MechanismParts {
    /// Validate `spec`, build and preprocess the rod, and collect the facts of the mechanism
    /// the integrator choice needs ([`MechanismFacts::of`]).
    pub fn new(spec: &MechanismSpec) -> Result<MechanismParts, ModelError> {
        spec.validate()?;
        let (rod_spec, physics) = spec.choose_physics()?;
        let spec = MechanismSpec {
            rod: rod_spec,
            ..spec.clone()
        };
        let rod = crate::rod::build(&spec.rod, spec.slider.mass)?;
        let evaluation_cost = evaluation_cost(rod.as_ref())?;
        let probe_pins = Cell::default();
        let facts = MechanismFacts::of(
            rod.as_ref(),
            spec.rod.damping_ratio,
            spec.slider.mass,
            &probe(rod.as_ref(), &spec, &probe_pins),
        );
        Ok(MechanismParts {
            spec,
            physics,
            rod,
            facts,
            evaluation_cost,
        })
    }

    /// The spec with the rod's `auto` settings resolved (its `solver` is what the integrator
    /// choice takes).
    pub fn spec(&self) -> &MechanismSpec {
        &self.spec
    }

    /// What the integrator choice needs to know of the mechanism.
    pub fn facts(&self) -> &MechanismFacts {
        &self.facts
    }
}

impl Mechanism {
    /// The mechanism of `parts` with the integrator `choice` (made by the caller, usually
    /// [`integrator_choice::choose`] on the solver settings of [`MechanismParts::spec`] and
    /// [`MechanismParts::facts`]), built with those solver settings. Refused where the choice does not apply to the rod
    /// ([`integrator_choice::build`]) or the gas force is invalid.
    pub fn new(parts: MechanismParts, choice: IntegratorChoice) -> Result<Mechanism, ModelError> {
        let MechanismParts {
            spec,
            physics,
            rod,
            facts,
            evaluation_cost,
        } = parts;
        let n = rod.n_coordinates() + 1;
        let probe_pins = Cell::default();
        let probe = probe(rod.as_ref(), &spec, &probe_pins);
        let integrator =
            integrator_choice::build(choice, &spec.solver, &facts, rod.as_ref(), &probe)?;
        let max_step = choice.max_step(&spec.solver);
        let m = probe.n_constraints();
        let backup = DaeState::zeros(n, m);
        // The held step of dense output: sized only for an integrator that has it, so that a
        // restored state cannot bring one to another.
        let k = if integrator.dense_output() {
            rod.elastic_coordinates().map_or(0, |e| e.count())
        } else {
            0
        };
        let gas = spec
            .slider
            .gas_force
            .as_ref()
            .map(GasForce::new)
            .transpose()?;
        Ok(Mechanism {
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
            gas,
            call_deadline: std::time::Instant::now(),
            evaluation_cost,
            spec,
            physics,
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
        dae_context(
            self.rod.as_ref(),
            self.gas.as_ref(),
            &self.spec,
            state,
            &self.pin_cache,
        )
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
