//! The slider-crank model: the rod, the prescribed crank, the slider, and the integrator the
//! solver settings choose. Starting is in [`super::start`], stepping in [`super::stepping`],
//! the outputs in [`super::outputs`].

use super::crank::{CrankInput, CrankLaw};
use super::dae::SliderCrankDae;
use super::spec::{MechanismSpec, SolverMethod};
use super::state::MechanismState;
use crate::error::ModelError;
use crate::integrator::{
    ConstrainedSolve, DaeState, DaeSystem, ExplicitRk4, GeneralizedAlpha, Integrator,
};
use crate::rod::RodBody;

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
    crank_length: f64,
    slider_mass: f64,
    state: &MechanismState,
) -> SliderCrankDae<'a> {
    SliderCrankDae {
        rod,
        crank: CrankLaw {
            length: crank_length,
            t_k: state.input_time,
            input: state.input,
        },
        slider_mass,
        slider_force: state.slider_force,
    }
}

impl Mechanism {
    /// Validate `spec`, build and preprocess the rod, choose the integrator
    /// (`solver.method = "auto"`: RK4 while the step is within its stability limit
    /// `2 pi f_max h <= 2.5`, else generalized-alpha).
    pub fn new(spec: &MechanismSpec) -> Result<Mechanism, ModelError> {
        spec.validate()?;
        let rod = crate::rod::build(&spec.rod)?;
        let n = rod.n_coordinates() + 1;
        // RK4 is stable for w h < 2.78: its step is capped at 2.5 / w_max of the highest mode.
        let explicit_limit =
            2.5 / (2.0 * std::f64::consts::PI * rod.highest_frequency_hz()).max(1e-300);
        let method = match spec.solver.method {
            SolverMethod::Auto if spec.solver.step <= explicit_limit => SolverMethod::Rk4,
            SolverMethod::Auto => SolverMethod::GeneralizedAlpha,
            m => m,
        };
        let probe = SliderCrankDae {
            rod: rod.as_ref(),
            crank: CrankLaw {
                length: spec.crank.length,
                t_k: 0.0,
                input: CrankInput::default(),
            },
            slider_mass: spec.slider.mass,
            slider_force: 0.0,
        };
        let (integrator, max_step): (Box<dyn Integrator>, f64) = match method {
            SolverMethod::Rk4 => (
                Box::new(ExplicitRk4::new(&probe)),
                spec.solver.step.min(explicit_limit),
            ),
            _ => (
                Box::new(GeneralizedAlpha::new(
                    &probe,
                    spec.solver.rho_inf,
                    spec.solver.newton_tolerance,
                    spec.solver.max_newton_iterations,
                )),
                spec.solver.step,
            ),
        };
        let m = probe.n_constraints();
        Ok(Mechanism {
            spec: spec.clone(),
            crank_length: spec.crank.length,
            slider_mass: spec.slider.mass,
            max_step,
            max_halvings: spec.solver.max_halvings,
            integrator,
            output_solve: Some(OutputSolve::new(n)),
            backup: DaeState {
                t: 0.0,
                q: vec![0.0; n],
                v: vec![0.0; n],
                qdd: vec![0.0; n],
                acc: vec![0.0; n],
                lambda: vec![0.0; m],
            },
            rod,
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
            self.crank_length,
            self.slider_mass,
            state,
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
