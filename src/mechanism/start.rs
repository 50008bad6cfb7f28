//! Starting the slider-crank (docs/physics.md, "Initial state"): the rod undeformed
//! and moving rigidly with the crank, or deflected quasi-statically by the inertia loads of the
//! start motion; positions, velocities, accelerations and joint forces consistent.

use nalgebra::{DMatrix, DVector, Matrix4, Vector2, Vector4};

use super::crank::CrankInput;
use super::slider_crank::{Mechanism, OutputSolve};
use super::spec::StartDeflection;
use super::state::MechanismState;
use crate::error::ModelError;
use crate::integrator::{DaeState, DaeSystem, StepAhead};
use crate::modal::ReferenceKind;

/// The quasi-static start's convergence: the last correction of the elastic coordinates, over
/// their scales.
const QUASI_STATIC_TOLERANCE: f64 = 1e-13;

/// The same for the start's free vibration ([`Mechanism::start_vibration`]), an amplitude
/// estimate: a heavy slider slows the fixed point, whose correction then stays above
/// [`QUASI_STATIC_TOLERANCE`] for longer than its 60 passes.
const START_VIBRATION_TOLERANCE: f64 = 1e-6;

impl Mechanism {
    /// Consistent start: undeformed rod on the crank at angle `input.angle`, rigid velocities
    /// from the crank speed, accelerations and multipliers from the index-1 solve; with
    /// `start.deflection = "quasi_static"`, deflected as [`Mechanism::quasi_static_start`] says.
    pub fn initial_state(
        &self,
        t0: f64,
        input: CrankInput,
        slider_force: f64,
    ) -> Result<MechanismState, ModelError> {
        let nr = self.rod.n_coordinates();
        let n = nr + 1;
        let r = self.crank_length;
        let l = self.rod.length();
        // Rigid slider-crank: B on the crank, C on the slider line y = e, |C - B| = L.
        let e = self.spec.mechanism.slider_offset;
        let (s, c) = input.angle.sin_cos();
        let b = Vector2::new(r * c, r * s);
        let dy = e - b.y;
        let dx = (l * l - dy * dy).sqrt();
        let cpt = Vector2::new(b.x + dx, e);
        let vb = Vector2::new(-r * s, r * c) * input.speed;
        let omega = -vb.y / dx;
        let vc_x = vb.x - omega * (cpt.y - b.y);
        let mut q = vec![0.0; n];
        let mut v = vec![0.0; n];
        self.rod
            .place_undeformed(b, cpt, vb, omega, &mut q[..nr], &mut v[..nr]);
        q[nr] = cpt.x;
        v[nr] = vc_x;
        let mut state = MechanismState {
            time: t0,
            dae: DaeState {
                t: t0,
                q,
                v,
                ..DaeState::zeros(n, 4)
            },
            input,
            input_time: t0,
            previous_input: input,
            previous_input_time: t0,
            slider_force,
            ..Default::default()
        };
        // Sized as the mechanism's backup: the rod's elastic coordinates where the integrator
        // has dense output, none otherwise.
        state.ahead = StepAhead::sized(self.backup_ahead.z0.len(), &state.dae);
        let mut work = OutputSolve::new(n);
        if self.spec.start.deflection == StartDeflection::QuasiStatic {
            self.quasi_static_start(&mut state, &mut work)?;
        } else if self.start_vibration_estimated(input) {
            state.start_vibration = self.start_vibration(&state, input.speed, &mut work);
        }
        self.consistent_accelerations(&mut work, &state, false)?;
        state.dae.qdd.copy_from_slice(&work.solve.qdd);
        state.dae.lambda.copy_from_slice(&work.solve.lambda);
        state.dae.acc.copy_from_slice(&state.dae.qdd);
        state.outputs = self.compute_outputs(Some(&mut work), &state)?;
        // The initial outputs obey the bound of every accepted step (a heavy slider at the
        // fastest crank can ask for forces no model stands behind).
        if let Some((name, x)) = state.outputs.out_of_range() {
            return Err(ModelError::InvalidParameter {
                name: "initial state",
                value: x,
                allowed: format!(
                    "output {name} finite with |value| < {:e} in SI units at the start (lower the crank speed, the slider force or the masses)",
                    super::MAX_OUTPUT_MAGNITUDE
                ),
            });
        }
        Ok(state)
    }

    /// Whether a start with the crank input `input` gets [`Mechanism::start_vibration`]: an
    /// undeformed start at speed of the FFR rod (the segment chains are geometrically exact and
    /// take no share for large deflection) on pinned modes (`rod.reference =
    /// "simply_supported"`, the default: its elastic coordinates are the rod's own in the
    /// mechanism, its first bending mode the mechanism's).
    pub fn start_vibration_estimated(&self, input: CrankInput) -> bool {
        input.speed != 0.0
            && self.spec.start.deflection == StartDeflection::Undeformed
            && !self.physics.geometrically_exact
            && self.spec.rod.reference == ReferenceKind::SimplySupported
            && self.rod.first_bending_hz().is_some_and(|f| f > 0.0)
            && self
                .rod
                .elastic_coordinates()
                .is_some_and(|e| !e.is_empty())
    }

    /// The free vibration an undeformed start at crank speed `speed` (rad/s) rings, as an
    /// amplitude of `v_mid / L` (where [`Mechanism::start_vibration_estimated`]; 0 where the
    /// quasi-static deflection cannot be found). The rod starts at `p = 0, p' = 0` where the
    /// motion's quasi-static deflection is `p_qs(t0)` with the rate `p_qs'(t0)`: the difference
    /// rings, in the first bending mode (`w_1`) with the amplitude `sqrt(v0^2 + (v0' / w_1)^2)`
    /// of an undamped oscillator released from the offset `v0` at the rate `v0'` (A. K. Chopra,
    /// *Dynamics of Structures*, 4th ed., 2012, section 2.1; `v0`, `v0'`: the midpoint
    /// deflection of the quasi-static state and its rate, central differences over a hundredth
    /// of a radian of the crank). A start at dead centre, where the rod's transverse load is
    /// zero, rings by the rate; one at a quarter revolution by the offset. The quasi-static
    /// state stands for the forced motion where the crank turns well below the first bending
    /// mode (the random rods of docs/verification.md: up to a quarter of it).
    fn start_vibration(&self, state: &MechanismState, speed: f64, work: &mut OutputSolve) -> f64 {
        let w1 = 2.0 * std::f64::consts::PI * self.rod.first_bending_hz().unwrap_or(0.0);
        let t0 = state.time;
        let delta = 0.01 / speed.abs();
        let mut v = [0.0; 3];
        for (k, t) in [t0 - delta, t0, t0 + delta].into_iter().enumerate() {
            match self.quasi_static_at(state, t, work, START_VIBRATION_TOLERANCE) {
                Ok(probe) => v[k] = self.rod.mid_deflection(&probe.dae.q),
                Err(_) => return 0.0,
            }
        }
        let rate = (v[2] - v[0]) / (2.0 * delta);
        let amplitude = (v[1] * v[1] + (rate / w1).powi(2)).sqrt() / self.rod.length();
        if amplitude.is_finite() {
            amplitude
        } else {
            0.0
        }
    }

    /// `state` deflected quasi-statically at time `t` ([`Mechanism::quasi_static_deflection`],
    /// no elastic rates), a copy.
    fn quasi_static_at(
        &self,
        state: &MechanismState,
        t: f64,
        work: &mut OutputSolve,
        tolerance: f64,
    ) -> Result<MechanismState, ModelError> {
        let mut probe = state.clone();
        probe.time = t;
        probe.dae.t = t;
        self.quasi_static_deflection(&mut probe, work, &[], tolerance)?;
        Ok(probe)
    }

    /// Quasi-static start: the elastic coordinates follow the quasi-static deflection `p_qs(t)`
    /// of the start motion, `p = p_qs(t0)`, `p' = (p_qs(t0 + d) - p_qs(t0 - d)) / 2d`; the rigid
    /// coordinates and velocities satisfy the constraints.
    fn quasi_static_start(
        &self,
        state: &mut MechanismState,
        work: &mut OutputSolve,
    ) -> Result<(), ModelError> {
        let elastic = self.rod.elastic_coordinates().ok_or_else(|| ModelError::InvalidParameter {
            name: "start.deflection",
            value: 1.0,
            allowed: "\"undeformed\" with rod.model = segments (\"quasi_static\" needs the elastic coordinates of the FFR rod)".into(),
        })?;
        let t0 = state.time;
        let delta = 1e-6;
        let mut rate = vec![0.0; elastic.len()];
        for (sign, t) in [(-1.0, t0 - delta), (1.0, t0 + delta)] {
            let probe = self.quasi_static_at(state, t, work, QUASI_STATIC_TOLERANCE)?;
            for (i, r) in rate.iter_mut().enumerate() {
                *r += sign * probe.dae.q[elastic.start + i] / (2.0 * delta);
            }
        }
        self.quasi_static_deflection(state, work, &rate, QUASI_STATIC_TOLERANCE)
    }

    /// Deflect the rod quasi-statically at `state.time`: elastic velocities `elastic_rate` (zero
    /// if empty), elastic accelerations driven to zero by Newton's method on the constrained
    /// system, `G_e T_e dp = p''` (`T_e` the tangent stiffness's elastic columns, including the
    /// centrifugal softening; `G_e` the elastic rows of the constrained acceleration response),
    /// with the rigid
    /// coordinates re-solved on the constraints `Phi(q, t) = 0` and their velocities on
    /// `Phi_q q' = -Phi_t` at each pass, until the last correction is below `tolerance` of the
    /// coordinates' scales (60 passes at most).
    fn quasi_static_deflection(
        &self,
        state: &mut MechanismState,
        work: &mut OutputSolve,
        elastic_rate: &[f64],
        tolerance: f64,
    ) -> Result<(), ModelError> {
        let sys = self.system(state);
        let n = sys.n_coordinates();
        let t0 = state.time;
        let elastic = self.rod.elastic_coordinates().unwrap_or(0..0);
        let rigid: Vec<usize> = (0..n).filter(|i| !elastic.contains(i)).collect();
        debug_assert_eq!(rigid.len(), 4);
        let ne = elastic.len();
        let mut jac = faer::Mat::<f64>::zeros(4, n);
        let mut mass = faer::Mat::<f64>::zeros(n, n);
        let mut tangent = faer::Mat::<f64>::zeros(n, n);
        let mut phi = [0.0; 4];
        let scale = self.rod.length();
        let singular = || ModelError::StepFailed {
            time: t0,
            step: 0.0,
            reason: "quasi-static start: the constraint Jacobian is singular".into(),
        };
        for pass in 0..60 {
            // Rigid coordinates on the position constraints (Newton on the 4 x 4 block).
            for _ in 0..20 {
                sys.constraints(t0, &state.dae.q, &mut phi);
                if phi.iter().all(|x| x.abs() < 1e-15 * scale) {
                    break;
                }
                sys.constraint_jacobian(&state.dae.q, jac.as_mut());
                let a = Matrix4::from_fn(|i, j| jac[(i, rigid[j])]);
                let d = a.lu().solve(&Vector4::from(phi)).ok_or_else(singular)?;
                for (k, &i) in rigid.iter().enumerate() {
                    state.dae.q[i] -= d[k];
                }
            }
            // Velocities: elastic ones given, rigid ones on the velocity constraints.
            sys.constraint_jacobian(&state.dae.q, jac.as_mut());
            let mut rate = [0.0; 4];
            sys.constraint_rate(t0, &state.dae.q, &mut rate);
            state.dae.v.iter_mut().for_each(|x| *x = 0.0);
            for (i, &r) in elastic_rate.iter().enumerate() {
                state.dae.v[elastic.start + i] = r;
            }
            for (k, r) in rate.iter_mut().enumerate() {
                for i in elastic.clone() {
                    *r += jac[(k, i)] * state.dae.v[i];
                }
            }
            let a = Matrix4::from_fn(|i, j| jac[(i, rigid[j])]);
            let vr = a.lu().solve(&-Vector4::from(rate)).ok_or_else(singular)?;
            for (k, &i) in rigid.iter().enumerate() {
                state.dae.v[i] = vr[k];
            }
            // Accelerations and multipliers.
            self.consistent_accelerations(work, state, false)?;
            state.dae.qdd.copy_from_slice(&work.solve.qdd);
            state.dae.lambda.copy_from_slice(&work.solve.lambda);
            // K_e dp = M_ee p''.
            sys.mass(&state.dae.q, mass.as_mut());
            tangent.fill(0.0);
            sys.add_tangent(
                &state.dae.q,
                &state.dae.v,
                &state.dae.lambda,
                1.0,
                0.0,
                tangent.as_mut(),
            );
            // Newton on p''(p) = 0 for the constrained system: a change dp of the elastic
            // coordinates changes the generalized forces by -T dp (T the tangent's elastic
            // columns) and the elastic accelerations by -G_e T dp, G the response of the
            // accelerations to forces under the constraints (the top-left block of
            // [[M, Phi_q^T], [Phi_q, 0]]^-1; J. Garcia de Jalon and E. Bayo, "Kinematic and
            // Dynamic Simulation of Multibody Systems", Springer 1994, section 5.2). With a
            // heavy slider on the rod's axial mode G_e is far from M_ee^-1.
            let dim = n + 4;
            let augmented = DMatrix::from_fn(dim, dim, |i, j| match (i < n, j < n) {
                (true, true) => mass[(i, j)],
                (true, false) => jac[(j - n, i)],
                (false, true) => jac[(i - n, j)],
                (false, false) => 0.0,
            });
            let forces = DMatrix::from_fn(dim, ne, |i, j| {
                if i < n {
                    let x = tangent[(i, elastic.start + j)];
                    if x.is_finite() {
                        x
                    } else {
                        0.0
                    }
                } else {
                    0.0
                }
            });
            let response = augmented.lu().solve(&forces).ok_or_else(singular)?;
            let b = DMatrix::from_fn(ne, ne, |i, j| response[(elastic.start + i, j)]);
            let rhs = DVector::from_fn(ne, |i, _| state.dae.qdd[elastic.start + i]);
            let dp = b.lu().solve(&rhs).ok_or_else(|| ModelError::StepFailed {
                time: t0,
                step: 0.0,
                reason:
                    "quasi-static start: the elastic stiffness is singular (at or above buckling)"
                        .into(),
            })?;
            let mut change: f64 = 0.0;
            for i in 0..ne {
                state.dae.q[elastic.start + i] += dp[i];
                change = change.max((dp[i] / self.rod.coordinate_scale(elastic.start + i)).abs());
            }
            if change < tolerance {
                return stable_deflection(&tangent, elastic.clone(), t0);
            }
            if pass == 59 || !change.is_finite() {
                return Err(ModelError::StepFailed {
                    time: t0,
                    step: 0.0,
                    reason: format!("quasi-static start did not converge (last correction {change:e}); the loads may be at or above buckling"),
                });
            }
        }
        Ok(())
    }
}

/// The quasi-static deflection is an equilibrium the rod stays near: the elastic tangent
/// stiffness (its symmetric part, with the axial load's geometric stiffness and the
/// centrifugal softening) is positive definite. At or above buckling (the Euler load
/// `pi^2 E I / L^2` for the pinned rod) it has a negative eigenvalue, and the equilibrium
/// found is the unstable straight one: refused, naming buckling.
fn stable_deflection(
    tangent: &faer::Mat<f64>,
    elastic: std::ops::Range<usize>,
    time: f64,
) -> Result<(), ModelError> {
    let ne = elastic.len();
    let k = DMatrix::from_fn(ne, ne, |i, j| {
        0.5 * (tangent[(elastic.start + i, elastic.start + j)]
            + tangent[(elastic.start + j, elastic.start + i)])
    });
    // A tangent with non-finite entries (an approximation where a term is not defined) says
    // nothing about stability.
    if !k.iter().all(|x| x.is_finite()) || k.clone().cholesky().is_some() {
        return Ok(());
    }
    let least = k.symmetric_eigenvalues().min();
    Err(ModelError::StepFailed {
        time,
        step: 0.0,
        reason: format!(
            "quasi-static start: the rod is at or above buckling under these loads (the elastic tangent stiffness has the eigenvalue {least:.3e} < 0, so the deflection found is an unstable equilibrium); start undeformed, or lower the compressive load or the speed"
        ),
    })
}
