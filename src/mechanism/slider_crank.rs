//! The slider-crank model: builds the rod from a scene, starts consistently, advances with
//! sub-stepping and step halving, and computes the outputs.
//!
//! Outputs are computed at the communication points from an index-1 solve at the current
//! state (velocities projected on the velocity constraints, then
//! `[M Phi_q^T; Phi_q 0] [q''; lambda] = [Q; gamma]`), so joint forces are consistent with the
//! state to round-off instead of carrying the integrator's multiplier error.

use nalgebra::Vector2;

use super::crank::CrankLaw;
use super::dae::SliderCrankDae;
use super::outputs::Outputs;
use super::rod_body::{RodBody, RodPoint};
use super::state::MechanismState;
use crate::beam::RodProperties;
use crate::error::{require_non_negative, require_positive, ModelError};
use crate::ffr::FfrRod;
use crate::integrator::dense_lu::DenseLu;
use crate::integrator::generalized_alpha::DaeState;
use crate::integrator::{DaeSystem, ExplicitRk4, GeneralizedAlpha};
use crate::modal::{ComponentModes, ModeSelection, ReferenceConditions};
use crate::scene::{RodModelKind, Scene, SolverMethod, StartDeflection};
use crate::simulation::CrankInput;

/// |v_mid| / L above which the small-deformation assumption is flagged.
pub const LARGE_DEFLECTION_WARNING: f64 = 0.05;

/// The slider-crank and its preprocessed rod.
pub struct Mechanism {
    pub scene: Scene,
    pub rod: Box<dyn RodBody>,
    crank_length: f64,
    slider_mass: f64,
    max_step: f64,
    max_halvings: usize,
    integrator: GeneralizedAlpha,
    /// The explicit path, when the scene asks for it (`solver.method = "rk4"`).
    explicit: Option<ExplicitRk4>,
    fingerprint: u64,
    /// Workspace of the output solve (taken out while in use).
    output_work: Option<OutputWork>,
    backup: DaeState,
}

/// Validate the scene's physical and solver parameters (named, with their ranges).
pub fn validate_scene(scene: &Scene) -> Result<RodProperties, ModelError> {
    let rod = &scene.rod;
    let props = RodProperties {
        length: rod.length,
        youngs_modulus: rod.youngs_modulus,
        density: rod.density,
        area: rod.area,
        area_moment: rod.area_moment,
    };
    props.validate()?;
    require_positive("crank.length", scene.crank.length)?;
    if scene.crank.length >= rod.length {
        return Err(ModelError::InvalidParameter {
            name: "crank.length",
            value: scene.crank.length,
            allowed: format!(
                "0 < crank.length < rod.length = {} m (a longer crank cannot turn the mechanism)",
                rod.length
            ),
        });
    }
    require_non_negative("rod.damping_ratio", rod.damping_ratio)?;
    require_non_negative("slider.mass", scene.slider.mass)?;
    require_positive("solver.step", scene.solver.step)?;
    let rho = scene.solver.rho_inf;
    if !(rho.is_finite() && (0.0..=1.0).contains(&rho)) {
        return Err(ModelError::InvalidParameter {
            name: "solver.rho_inf",
            value: rho,
            allowed: "[0, 1]".into(),
        });
    }
    require_positive("solver.newton_tolerance", scene.solver.newton_tolerance)?;
    if scene.solver.max_newton_iterations == 0 {
        return Err(ModelError::InvalidParameter {
            name: "solver.max_newton_iterations",
            value: 0.0,
            allowed: ">= 1".into(),
        });
    }
    Ok(props)
}

/// Build the rod model the scene asks for.
pub fn build_rod(scene: &Scene, props: RodProperties) -> Result<Box<dyn RodBody>, ModelError> {
    let rod = &scene.rod;
    match rod.model {
        RodModelKind::Ffr => {
            let reference = ReferenceConditions::from_kind(rod.reference, rod.elements)?;
            let modes = ComponentModes::new(
                props,
                rod.elements,
                reference,
                rod.mass,
                &ModeSelection::Count(rod.modes),
            )?;
            Ok(Box::new(FfrRod::new(
                modes,
                rod.damping_ratio,
                rod.axial_stiffening,
            )))
        }
        RodModelKind::Segments => crate::segments::build(scene, props),
    }
}

/// The DAE evaluation context of `state`: the rod, the crank law in force, the slider.
fn dae_context<'a>(
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

/// FNV-1a 64 of the model-defining part of the scene.
fn fingerprint(scene: &Scene) -> u64 {
    let mut s = scene.clone();
    s.name.clear();
    s.description.clear();
    s.outputs = Default::default();
    s.experiment = Default::default();
    let text = s.to_toml();
    let mut h: u64 = 0xcbf29ce484222325;
    for b in text.bytes() {
        h ^= b as u64;
        h = h.wrapping_mul(0x100000001b3);
    }
    h
}

impl Mechanism {
    pub fn new(scene: &Scene) -> Result<Mechanism, ModelError> {
        let props = validate_scene(scene)?;
        let rod = build_rod(scene, props)?;
        let nr = rod.n_coordinates();
        let n = nr + 1;
        let m = 4;
        // RK4 is stable for w h < 2.78: its step is capped at 2.5 / w_max of the highest mode;
        // `auto` takes RK4 only where the scene's step is within that limit.
        let explicit_limit =
            2.5 / (2.0 * std::f64::consts::PI * rod.highest_frequency_hz()).max(1e-300);
        let method = match scene.solver.method {
            SolverMethod::Auto if scene.solver.step <= explicit_limit => SolverMethod::Rk4,
            SolverMethod::Auto => SolverMethod::GeneralizedAlpha,
            m => m,
        };
        let max_step = match method {
            SolverMethod::Rk4 => scene.solver.step.min(explicit_limit),
            _ => scene.solver.step,
        };
        let integrator = {
            let probe = SliderCrankDae {
                rod: rod.as_ref(),
                crank: CrankLaw {
                    length: scene.crank.length,
                    t_k: 0.0,
                    input: CrankInput::default(),
                },
                slider_mass: scene.slider.mass,
                slider_force: 0.0,
            };
            let explicit = match method {
                SolverMethod::Rk4 => Some(ExplicitRk4::new(&probe)),
                _ => None,
            };
            (
                GeneralizedAlpha::new(
                    &probe,
                    scene.solver.rho_inf,
                    scene.solver.newton_tolerance,
                    scene.solver.max_newton_iterations,
                ),
                explicit,
            )
        };
        let (integrator, explicit) = integrator;
        Ok(Mechanism {
            fingerprint: fingerprint(scene),
            scene: scene.clone(),
            crank_length: scene.crank.length,
            slider_mass: scene.slider.mass,
            max_step,
            max_halvings: scene.solver.max_halvings,
            integrator,
            explicit,
            output_work: Some(OutputWork::new(n)),
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

    /// The integrator in use (after `auto` resolved it), and what its iteration counter counts.
    pub fn integrator_name(&self) -> (&'static str, &'static str) {
        if self.explicit.is_some() {
            ("RK4 (explicit, projected)", "factorizations")
        } else {
            ("generalized-alpha", "Newton iterations")
        }
    }

    /// Identifies the model (for serialized states).
    pub fn fingerprint(&self) -> u64 {
        self.fingerprint
    }

    pub fn crank_length(&self) -> f64 {
        self.crank_length
    }

    fn system(&self, state: &MechanismState) -> SliderCrankDae<'_> {
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

    /// Consistent start: undeformed rod on the crank at angle `input.angle`, rigid velocities
    /// from the crank speed, accelerations and multipliers from the index-1 solve.
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
        let (s, c) = input.angle.sin_cos();
        let b = Vector2::new(r * c, r * s);
        let dx = (l * l - r * r * s * s).sqrt();
        let cpt = Vector2::new(b.x + dx, 0.0);
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
                qdd: vec![0.0; n],
                acc: vec![0.0; n],
                lambda: vec![0.0; 4],
            },
            input,
            input_time: t0,
            slider_force,
            ..Default::default()
        };
        let mut work = self.output_workspace();
        if self.scene.start.deflection == StartDeflection::QuasiStatic {
            self.quasi_static_start(&mut state, &mut work)?;
        }
        // The stiffening forces depend on q'' and lambda: a few fixed-point passes.
        for _ in 0..4 {
            let (qdd, lambda) = work.consistent_accelerations(self, &state, false)?;
            state.dae.qdd.copy_from_slice(qdd);
            state.dae.lambda.copy_from_slice(&lambda);
        }
        state.dae.acc.copy_from_slice(&state.dae.qdd);
        state.outputs = self.compute_outputs(&mut work, &state)?;
        Ok(state)
    }

    /// Quasi-static start: the elastic coordinates follow the quasi-static deflection `p_qs(t)`
    /// of the start motion, `p = p_qs(t0)`, `p' = (p_qs(t0 + d) - p_qs(t0 - d)) / 2d`; the rigid
    /// coordinates and velocities satisfy the constraints.
    fn quasi_static_start(
        &self,
        state: &mut MechanismState,
        work: &mut OutputWork,
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
            let mut probe = state.clone();
            probe.time = t;
            probe.dae.t = t;
            self.quasi_static_deflection(&mut probe, work, &[])?;
            for (i, r) in rate.iter_mut().enumerate() {
                *r += sign * probe.dae.q[elastic.start + i] / (2.0 * delta);
            }
        }
        self.quasi_static_deflection(state, work, &rate)
    }

    /// Deflect the rod quasi-statically at `state.time`: elastic velocities `elastic_rate` (zero
    /// if empty), elastic accelerations driven to zero by `K_e dp = M_ee p''` (fixed point; `K_e`
    /// the elastic tangent stiffness including the centrifugal softening), with the rigid
    /// coordinates re-solved on the constraints `Phi(q, t) = 0` and their velocities on
    /// `Phi_q q' = -Phi_t` at each pass.
    fn quasi_static_deflection(
        &self,
        state: &mut MechanismState,
        work: &mut OutputWork,
        elastic_rate: &[f64],
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
        for pass in 0..60 {
            // Rigid coordinates on the position constraints (Newton on the 4 x 4 block).
            for _ in 0..20 {
                sys.constraints(t0, &state.dae.q, &mut phi);
                if phi.iter().all(|x| x.abs() < 1e-15 * scale) {
                    break;
                }
                sys.constraint_jacobian(&state.dae.q, jac.as_mut());
                let a = nalgebra::Matrix4::from_fn(|i, j| jac[(i, rigid[j])]);
                let d = a.lu().solve(&nalgebra::Vector4::from(phi)).ok_or_else(|| {
                    ModelError::StepFailed {
                        time: t0,
                        step: 0.0,
                        reason: "quasi-static start: the constraint Jacobian is singular".into(),
                    }
                })?;
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
            let a = nalgebra::Matrix4::from_fn(|i, j| jac[(i, rigid[j])]);
            let vr = a
                .lu()
                .solve(&-nalgebra::Vector4::from(rate))
                .ok_or_else(|| ModelError::StepFailed {
                    time: t0,
                    step: 0.0,
                    reason: "quasi-static start: the constraint Jacobian is singular".into(),
                })?;
            for (k, &i) in rigid.iter().enumerate() {
                state.dae.v[i] = vr[k];
            }
            // Accelerations and multipliers (stiffening needs them: two passes).
            for _ in 0..2 {
                let (qdd, lambda) = work.consistent_accelerations(self, state, false)?;
                state.dae.qdd.copy_from_slice(qdd);
                state.dae.lambda.copy_from_slice(&lambda);
            }
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
            let mut k = nalgebra::DMatrix::from_fn(ne, ne, |i, j| {
                tangent[(elastic.start + i, elastic.start + j)]
            });
            let rhs = nalgebra::DVector::from_fn(ne, |i, _| {
                (0..ne)
                    .map(|j| {
                        mass[(elastic.start + i, elastic.start + j)]
                            * state.dae.qdd[elastic.start + j]
                    })
                    .sum::<f64>()
            });
            k.iter_mut()
                .for_each(|x| *x = if x.is_finite() { *x } else { 0.0 });
            let dp = k.lu().solve(&rhs).ok_or_else(|| ModelError::StepFailed {
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
            if change < 1e-13 {
                return Ok(());
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

    fn output_workspace(&self) -> OutputWork {
        OutputWork::new(self.rod.n_coordinates() + 1)
    }

    /// Integrate `state` over `[t, t + h]`; on failure `state` is restored and the error says why.
    pub fn advance(&mut self, state: &mut MechanismState, h: f64) -> Result<(), ModelError> {
        self.backup.clone_from(&state.dae);
        self.integrator.forget_factorization();
        let backup_stats = state.stats;
        let t_start = state.time;
        let t_end = t_start + h;
        let n_sub = ((h / self.max_step) * (1.0 - 1e-12)).ceil().max(1.0) as usize;
        let result = (|| {
            for k in 0..n_sub {
                let target = if k + 1 == n_sub {
                    t_end
                } else {
                    t_start + h * (k + 1) as f64 / n_sub as f64
                };
                self.step_with_halving(state, target, 0)?;
            }
            Ok(())
        })();
        match result {
            Ok(()) => {
                state.time = t_end;
                state.dae.t = t_end;
                let mut work = self
                    .output_work
                    .take()
                    .unwrap_or_else(|| OutputWork::new(self.rod.n_coordinates() + 1));
                let outputs = self.compute_outputs(&mut work, state);
                self.output_work = Some(work);
                match outputs {
                    Ok(o) => {
                        state.outputs = o;
                        self.check_large_deflection(state);
                        Ok(())
                    }
                    Err(e) => {
                        state.dae.clone_from(&self.backup);
                        state.time = t_start;
                        state.stats = backup_stats;
                        Err(e)
                    }
                }
            }
            Err((t_fail, h_fail, reason)) => {
                state.dae.clone_from(&self.backup);
                state.time = t_start;
                state.stats = backup_stats;
                Err(ModelError::StepFailed {
                    time: t_fail,
                    step: h_fail,
                    reason: format!(
                        "{reason} (after {} step halvings; the communication step started at t = {t_start} s)",
                        self.max_halvings
                    ),
                })
            }
        }
    }

    fn step_with_halving(
        &mut self,
        state: &mut MechanismState,
        target: f64,
        depth: usize,
    ) -> Result<(), (f64, f64, String)> {
        let h = target - state.dae.t;
        let sys = dae_context(
            self.rod.as_ref(),
            self.crank_length,
            self.slider_mass,
            state,
        );
        let result = match self.explicit.as_mut() {
            Some(rk4) => rk4.step(&sys, &mut state.dae, h),
            None => self.integrator.step(&sys, &mut state.dae, h),
        };
        match result {
            Ok(iterations) => {
                state.dae.t = target;
                state.stats.steps += 1;
                state.stats.newton_iterations += iterations as u64;
                Ok(())
            }
            Err(failure) => {
                state.stats.newton_iterations += self.integrator.max_iterations as u64;
                if depth >= self.max_halvings {
                    return Err((state.dae.t, h, failure.to_string()));
                }
                state.stats.halvings += 1;
                let mid = state.dae.t + 0.5 * h;
                self.step_with_halving(state, mid, depth + 1)?;
                self.step_with_halving(state, target, depth + 1)
            }
        }
    }

    fn check_large_deflection(&self, state: &mut MechanismState) {
        let d = state.outputs.deflection_rel.abs();
        if d > LARGE_DEFLECTION_WARNING && !state.large_deflection_warned {
            state.large_deflection_warned = true;
            state.warnings.push(format!(
                "rod deflection |v_mid/L| = {d:.3e} at t = {} s exceeds {LARGE_DEFLECTION_WARNING} (the small-deformation range of the rod model); results beyond it are not accurate",
                state.time
            ));
        }
    }

    /// Outputs at the state's time (physics.md, "Output definitions and sign conventions").
    fn compute_outputs(
        &self,
        work: &mut OutputWork,
        state: &MechanismState,
    ) -> Result<Outputs, ModelError> {
        let (_, lambda) = work.consistent_accelerations(self, state, true)?;
        let nr = self.rod.n_coordinates();
        let q = &state.dae.q;
        let rb = self.rod.point(RodPoint::B, q);
        let rc = self.rod.point(RodPoint::C, q);
        let rm = self.rod.point(RodPoint::Mid, q);
        let chord = rc - rb;
        let d = rm - rb;
        let deflection = (chord.x * d.y - chord.y * d.x) / chord.norm();
        let fb = [lambda[0], lambda[1]];
        let fc = [lambda[2], lambda[3]];
        let (pin, _, _) = self.crank_law(state).pin(state.time);
        let torque = -(pin.x * fb[1] - pin.y * fb[0]);
        Ok(Outputs {
            deflection,
            deflection_rel: deflection / self.rod.length(),
            pin_b_force: fb,
            pin_c_force: fc,
            crank_torque: torque,
            slider_position: q[nr],
            slider_velocity: work.v[nr],
        })
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

/// Scratch for the index-1 solve.
struct OutputWork {
    lu: DenseLu,
    mass: faer::Mat<f64>,
    jac: faer::Mat<f64>,
    rhs: Vec<f64>,
    /// Projected velocities.
    v: Vec<f64>,
    f: Vec<f64>,
    /// Consistent accelerations from the last solve.
    qdd: Vec<f64>,
}

impl OutputWork {
    fn new(n: usize) -> OutputWork {
        OutputWork {
            lu: DenseLu::new(n + 4),
            mass: faer::Mat::zeros(n, n),
            jac: faer::Mat::zeros(4, n),
            rhs: vec![0.0; n + 4],
            v: vec![0.0; n],
            f: vec![0.0; n],
            qdd: vec![0.0; n],
        }
    }

    /// Project the velocities on `Phi_q v + Phi_t = 0` (M-weighted) and solve for the
    /// accelerations and multipliers. Returns (q'', lambda); the projected v stays in `self.v`.
    fn consistent_accelerations(
        &mut self,
        mech: &Mechanism,
        state: &MechanismState,
        project: bool,
    ) -> Result<(&[f64], [f64; 4]), ModelError> {
        let sys = mech.system(state);
        let n = sys.n_coordinates();
        let m = 4;
        let (q, t) = (&state.dae.q, state.time);
        sys.mass(q, self.mass.as_mut());
        sys.constraint_jacobian(q, self.jac.as_mut());
        self.lu.set_saddle_point(&self.mass, 1.0, &self.jac);
        if !self.lu.factor() {
            return Err(ModelError::StepFailed {
                time: t,
                step: 0.0,
                reason: "the constraint Jacobian is singular (degenerate configuration)".into(),
            });
        }
        self.v.copy_from_slice(&state.dae.v);
        if project {
            for i in 0..n {
                self.rhs[i] = (0..n).map(|j| self.mass[(i, j)] * state.dae.v[j]).sum();
            }
            let mut rate = [0.0; 4];
            sys.constraint_rate(t, q, &mut rate);
            for k in 0..m {
                self.rhs[n + k] = -rate[k];
            }
            self.lu.solve(&mut self.rhs);
            self.v.copy_from_slice(&self.rhs[..n]);
        }
        sys.forces(
            t,
            q,
            &self.v,
            &state.dae.qdd,
            &state.dae.lambda,
            &mut self.f,
        );
        let mut gamma = [0.0; 4];
        sys.constraint_acceleration_rhs(t, q, &self.v, &mut gamma);
        self.rhs[..n].copy_from_slice(&self.f);
        self.rhs[n..n + m].copy_from_slice(&gamma);
        self.lu.solve(&mut self.rhs);
        if self.rhs.iter().any(|x| !x.is_finite()) {
            return Err(ModelError::StepFailed {
                time: t,
                step: 0.0,
                reason: "the joint forces are not finite".into(),
            });
        }
        self.qdd.copy_from_slice(&self.rhs[..n]);
        Ok((
            &self.qdd,
            [
                self.rhs[n],
                self.rhs[n + 1],
                self.rhs[n + 2],
                self.rhs[n + 3],
            ],
        ))
    }
}
