//! The outputs of the slider-crank (docs/physics.md, "Output definitions and sign conventions").

/// Outputs at one time. Forces in the global frame, N; lengths in m.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Outputs {
    /// Midpoint deflection v_mid, m: transverse displacement of the material midpoint from the
    /// chord B->C, positive to the left of B->C.
    pub deflection: f64,
    /// v_mid / L.
    pub deflection_rel: f64,
    /// Force of the rod on the crank pin B, (x, y), N.
    pub pin_b_force: [f64; 2],
    /// Force of the rod on the slider at C, (x, y), N.
    pub pin_c_force: [f64; 2],
    /// Drive torque about A that imposes the crank motion, `-(r_B x F_B)_z`, N m.
    pub crank_torque: f64,
    /// Slider position x_C, m.
    pub slider_position: f64,
    /// Slider velocity, m/s.
    pub slider_velocity: f64,
    /// Section forces and stress (`rod.axial_force_mid`, `rod.bending_moment_mid`,
    /// `rod.stress_max`, `rod.stress_max_position`); zero unless the spec asks for them
    /// (`MechanismSpec::section_loads`).
    pub section: crate::rod::SectionLoads,
    /// `rod.error_estimate`: the estimated error of `v_mid / L` relative to its peak so far
    /// ([`crate::rod::PhysicsChoice::error_estimate`]); filled in by
    /// [`crate::Simulation::outputs`].
    pub error_estimate: f64,
}

impl Outputs {
    /// The first output outside the range of every accepted step: finite with
    /// |value| < [`super::MAX_OUTPUT_MAGNITUDE`] in SI units (`rod.stress_max` and its position
    /// may be NaN, where the rod has no fibre distances). One check for an accepted step, the
    /// start and a saved state.
    pub fn out_of_range(&self) -> Option<(&'static str, f64)> {
        let bounded = |x: f64| x.is_finite() && x.abs() < super::MAX_OUTPUT_MAGNITUDE;
        let s = &self.section;
        let section = [
            ("rod.axial_force_mid", s.axial_force_mid, false),
            ("rod.bending_moment_mid", s.bending_moment_mid, false),
            ("rod.stress_max", s.stress_max, true),
            ("rod.stress_max_position", s.stress_max_position, true),
        ];
        self.named()
            .into_iter()
            .map(|(name, x)| (name, x, false))
            .chain(section)
            .find(|&(_, x, nan_allowed)| !(bounded(x) || (nan_allowed && x.is_nan())))
            .map(|(name, x, _)| (name, x))
    }

    /// The scalar outputs with their FMU names (the section loads excepted), in one order for
    /// every check and record that lists them.
    pub fn named(&self) -> [(&'static str, f64); 9] {
        [
            ("rod.deflection", self.deflection),
            ("rod.deflection_rel", self.deflection_rel),
            ("pinB.force_x", self.pin_b_force[0]),
            ("pinB.force_y", self.pin_b_force[1]),
            ("pinC.force_x", self.pin_c_force[0]),
            ("pinC.force_y", self.pin_c_force[1]),
            ("crank.torque", self.crank_torque),
            ("slider.position", self.slider_position),
            ("slider.velocity", self.slider_velocity),
        ]
    }
}

use super::crank::CrankLaw;
use super::dae::PinAt;
use super::slider_crank::{Mechanism, OutputSolve};
use super::state::MechanismState;
use crate::error::ModelError;
use crate::integrator::{DaeSystem, StepFailure};

impl Mechanism {
    fn gravity(&self) -> nalgebra::Vector2<f64> {
        nalgebra::Vector2::from(self.spec.mechanism.gravity)
    }

    /// The transverse deflection of the rod from the chord B -> C, m, positive to the left of
    /// B -> C, at `out.len()` = N equally spaced points `s_i = i L / (N - 1)` (the definition
    /// of `v_mid`, docs/physics.md "Output definitions"; the ends are 0 by definition, and
    /// the middle point of an odd N is the material midpoint: there the cached output `v_mid`
    /// itself). From the positions alone; no allocation. N < 2 writes zeros.
    pub fn deflection_shape(&self, state: &MechanismState, out: &mut [f64]) {
        let q = &state.dae.q;
        let [rb, rc, _] = self.rod.points(q);
        let chord = rc - rb;
        let length = chord.norm();
        let n = out.len();
        for (i, v) in out.iter_mut().enumerate() {
            *v = 0.0;
            if n < 2 || i == 0 || i + 1 == n {
                continue;
            }
            if 2 * i + 1 == n {
                // The output itself (cached with the state), so that the two agree to the last
                // bit whatever accelerations the output's evaluation took.
                *v = state.outputs.deflection;
                continue;
            }
            if length == 0.0 {
                continue;
            }
            let r = self
                .rod
                .point_at(i as f64 * self.rod.length() / (n - 1) as f64, q);
            let d = r - rb;
            *v = (chord.x * d.y - chord.y * d.x) / length;
        }
    }

    /// Factor the saddle-point matrix at `state`'s positions, project the velocities on the
    /// constraints if `project` (into `work.v`; else `work.v` = the state's velocities), and
    /// solve for the accelerations and multipliers (into `work.solve`).
    pub(super) fn consistent_accelerations(
        &self,
        work: &mut OutputSolve,
        state: &MechanismState,
        project: bool,
    ) -> Result<(), ModelError> {
        let sys = self.system(state);
        let (q, t) = (&state.dae.q, state.time);
        let failed = |failure: StepFailure| ModelError::StepFailed {
            time: t,
            step: 0.0,
            reason: match failure {
                StepFailure::SingularMatrix => {
                    "the constraint Jacobian is singular (degenerate configuration)".into()
                }
                _ => "the joint forces are not finite".into(),
            },
        };
        work.solve.factor(&sys, q).map_err(failed)?;
        work.v.copy_from_slice(&state.dae.v);
        if project {
            work.solve.project_velocities(&sys, t, q, &mut work.v);
        }
        work.solve
            .accelerations(&sys, t, q, &work.v)
            .map_err(failed)?;
        debug_assert_eq!(sys.n_constraints(), 4);
        Ok(())
    }

    /// Whether the state is consistent as it stands: after a step of an integrator that leaves
    /// it so (velocities on the constraints, multipliers from the same solve), the outputs need
    /// no solve of their own ([`Mechanism::compute_outputs`] without workspace).
    pub(super) fn state_is_consistent(&self, state: &MechanismState) -> bool {
        self.integrator.consistent_outputs() && state.stats.steps > 0
    }

    /// Outputs at the state's time (docs/physics.md, "Outputs"): of a consistent state
    /// ([`Mechanism::state_is_consistent`]) as it stands, else from the index-1 solve at the
    /// state with its velocities projected on the constraints (into `work`, which must then be
    /// given), so that the joint forces are consistent with the state to round-off.
    pub(super) fn compute_outputs(
        &self,
        work: Option<&mut OutputSolve>,
        state: &MechanismState,
    ) -> Result<Outputs, ModelError> {
        let reuse = self.state_is_consistent(state);
        // Velocities, accelerations and multipliers: the state's own, or the solve's.
        let (v, qdd, lambda) = match work {
            Some(work) if !reuse => {
                self.consistent_accelerations(work, state, true)?;
                (&work.v, &work.solve.qdd, &work.solve.lambda)
            }
            _ => (&state.dae.v, &state.dae.qdd, &state.dae.lambda),
        };
        let nr = self.rod.n_coordinates();
        let q = &state.dae.q;
        let deflection = self.rod.mid_deflection_dynamic(q, qdd, self.gravity());
        let fb = [lambda[0], lambda[1]];
        let fc = [lambda[2], lambda[3]];
        let law = CrankLaw {
            length: self.crank_length,
            t_k: state.input_time,
            input: state.input,
        };
        let (pin, _, _) = PinAt::pin(&self.pin_cache, &law, state.time);
        let torque = -(pin.x * fb[1] - pin.y * fb[0]);
        let section = if self.spec.section_loads {
            self.rod.section_loads(
                &q[..nr],
                &v[..nr],
                &qdd[..nr],
                nalgebra::Vector2::from(self.spec.mechanism.gravity),
                -nalgebra::Vector2::new(fc[0], fc[1]),
            )
        } else {
            Default::default()
        };
        Ok(Outputs {
            deflection,
            deflection_rel: deflection / self.rod.length(),
            pin_b_force: fb,
            pin_c_force: fc,
            crank_torque: torque,
            slider_position: q[nr],
            slider_velocity: v[nr],
            section,
            error_estimate: 0.0,
        })
    }
}
