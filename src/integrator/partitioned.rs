//! The equations of motion on independent coordinates: coordinate partitioning (Wehage and
//! Haug 1982, "Generalized coordinate partitioning for dimension reduction in analysis of
//! constrained dynamic systems", J. Mech. Des. 104; Haug, *Computer-Aided Kinematics and
//! Dynamics of Mechanical Systems*, 1989, section 11.4).
//!
//! The coordinates `q` split into independent ones `z = q_I` (k of them) and dependent ones
//! `q_D` (m, one per constraint), with `Phi_D = dPhi/dq_D` invertible. Given `(t, z, z')`:
//! - positions: `Phi(q_D; z, t) = 0` by Newton on `Phi_D` (from the last solution);
//! - velocities: `Phi_D q_D' = -(Phi_I z' + Phi_t)`;
//! - accelerations: `q'' = G z'' + b` with `G_D = -Phi_D^-1 Phi_I`, `G_I = 1`,
//!   `b_D = Phi_D^-1 gamma`, `b_I = 0` (`Phi_q q'' = gamma`);
//! - the reduced equations `(G^T M G) z'' = G^T (Q - M b)` (k x k);
//! - the multipliers from the dependent rows of `M q'' + Phi_q^T lambda = Q`:
//!   `Phi_D^T lambda = (Q - M q'')_D`, so joint forces come from the same evaluation.
//!
//! For the prescribed-crank slider-crank with the FFR rod, `z` are the rod's modal
//! coordinates and `q_D` the frame `(R, phi)` and the slider: the mechanism's own degrees of
//! freedom. Where the system has all of this in closed form ([`DaeSystem::reduced_rhs`]:
//! the FFR slider-crank, `mechanism::minimal`), an evaluation is that one call and nothing
//! here is factored. Every buffer is sized once.

use faer::Mat;

use super::failure::StepFailure;
use super::small_lu::SmallLu;
use super::system::DaeSystem;

/// Workspace of the reduced right-hand side.
pub struct PartitionedRhs {
    n: usize,
    m: usize,
    /// Independent coordinates (indices into q).
    pub independent: Vec<usize>,
    /// Dependent coordinates (indices into q), one per constraint.
    pub dependent: Vec<usize>,
    mass: Mat<f64>,
    jac: Mat<f64>,
    /// `Phi_D`, factored.
    jac_d: SmallLu,
    /// `G_D` (m x k, row-major).
    g_d: Vec<f64>,
    /// `b_D` (m).
    b_d: Vec<f64>,
    /// `M G` (n x k, row-major).
    mg: Vec<f64>,
    reduced: SmallLu,
    force: Vec<f64>,
    phi: Vec<f64>,
    rhs_m: Vec<f64>,
    rhs_k: Vec<f64>,
    work: Vec<f64>,
    /// Positions, velocities and accelerations of the last evaluation (full coordinates).
    pub q: Vec<f64>,
    pub v: Vec<f64>,
    pub qdd: Vec<f64>,
    /// Multipliers of the last [`PartitionedRhs::multipliers`].
    pub lambda: Vec<f64>,
    /// Position tolerance of the Newton solve on each constraint (its unit).
    pub position_tolerance: f64,
    /// The last evaluation came from the system's closed form
    /// ([`DaeSystem::reduced_rhs`]), which wrote the multipliers too.
    closed_form: bool,
    /// The independent coordinates are `q[start..start + k]` (the common case: the modal
    /// coordinates after the frame): copied as ranges.
    contiguous_from: Option<usize>,
}

impl PartitionedRhs {
    /// For `system` with the independent coordinates `independent` (the others dependent:
    /// exactly one per constraint).
    pub fn new(system: &dyn DaeSystem, independent: Vec<usize>) -> PartitionedRhs {
        let n = system.n_coordinates();
        let m = system.n_constraints();
        let dependent: Vec<usize> = (0..n).filter(|i| !independent.contains(i)).collect();
        assert_eq!(
            dependent.len(),
            m,
            "one dependent coordinate per constraint"
        );
        let k = independent.len();
        let contiguous_from = independent
            .first()
            .copied()
            .filter(|&start| independent.iter().enumerate().all(|(a, &i)| i == start + a));
        PartitionedRhs {
            n,
            m,
            independent,
            dependent,
            mass: Mat::zeros(n, n),
            jac: Mat::zeros(m, n),
            jac_d: SmallLu::new(m),
            g_d: vec![0.0; m * k],
            b_d: vec![0.0; m],
            mg: vec![0.0; n * k],
            reduced: SmallLu::new(k),
            force: vec![0.0; n],
            phi: vec![0.0; m],
            rhs_m: vec![0.0; m],
            rhs_k: vec![0.0; k],
            work: vec![0.0; n.max(m).max(k)],
            q: vec![0.0; n],
            v: vec![0.0; n],
            qdd: vec![0.0; n],
            lambda: vec![0.0; m],
            position_tolerance: 1e-14 * system.coordinate_scale(0).max(1e-300),
            closed_form: false,
            contiguous_from,
        }
    }

    /// Number of independent coordinates k.
    pub fn k(&self) -> usize {
        self.independent.len()
    }

    /// Dependent positions on `Phi = 0` for the independent ones `z` at `t` (Newton from the
    /// dependent positions in `self.q`), then `Phi_q` at the solution factored.
    fn solve_positions(
        &mut self,
        system: &dyn DaeSystem,
        t: f64,
        z: &[f64],
    ) -> Result<(), StepFailure> {
        let m = self.m;
        for (a, &i) in self.independent.iter().enumerate() {
            self.q[i] = z[a];
        }
        if system.solve_dependent_positions(t, &mut self.q) {
            system.constraints(t, &self.q, &mut self.phi);
            let residual = self.phi.iter().fold(0.0f64, |r, x| r.max(x.abs()));
            if residual <= 1e3 * self.position_tolerance {
                return self.factor_jacobian(system);
            }
        }
        let mut converged = false;
        for _ in 0..12 {
            system.constraints(t, &self.q, &mut self.phi);
            let residual = self.phi.iter().fold(0.0f64, |r, x| r.max(x.abs()));
            if !residual.is_finite() {
                return Err(StepFailure::NonFinite);
            }
            self.factor_jacobian(system)?;
            if residual <= self.position_tolerance {
                converged = true;
                break;
            }
            self.rhs_m.copy_from_slice(&self.phi);
            self.jac_d.solve(&mut self.rhs_m, &mut self.work);
            for (c, &i) in self.dependent.iter().enumerate() {
                self.q[i] -= self.rhs_m[c];
            }
        }
        if !converged {
            // Stagnation at round-off is fine; a real failure is far above the tolerance.
            let residual = self.phi.iter().fold(0.0f64, |r, x| r.max(x.abs()));
            if residual > 1e3 * self.position_tolerance {
                return Err(StepFailure::NewtonDiverged {
                    iterations: 12,
                    last_correction: residual,
                });
            }
        }
        debug_assert_eq!(self.phi.len(), m);
        Ok(())
    }

    fn factor_jacobian(&mut self, system: &dyn DaeSystem) -> Result<(), StepFailure> {
        system.constraint_jacobian(&self.q, self.jac.as_mut());
        for (r, _) in (0..self.m).enumerate() {
            for (c, &j) in self.dependent.iter().enumerate() {
                self.jac_d.set(r, c, self.jac[(r, j)]);
            }
        }
        if self.jac_d.factor() {
            Ok(())
        } else {
            Err(StepFailure::SingularMatrix)
        }
    }

    /// `z`, `z'` into `q`, `v` at the independent coordinates.
    fn scatter(&mut self, z: &[f64], zd: &[f64]) {
        if let Some(start) = self.contiguous_from {
            let k = self.independent.len();
            let (q, v) = (&mut self.q[start..start + k], &mut self.v[start..start + k]);
            for ((q, v), (z, zd)) in q.iter_mut().zip(v).zip(z.iter().zip(zd)) {
                *q = *z;
                *v = *zd;
            }
        } else {
            for (a, &i) in self.independent.iter().enumerate() {
                self.q[i] = z[a];
                self.v[i] = zd[a];
            }
        }
    }

    /// `z''` from `q''` at the independent coordinates into `zdd`.
    fn gather_accelerations(&self, zdd: &mut [f64]) {
        if let Some(start) = self.contiguous_from {
            let k = self.independent.len();
            for (zdd, qdd) in zdd.iter_mut().zip(&self.qdd[start..start + k]) {
                *zdd = *qdd;
            }
        } else {
            for (a, &i) in self.independent.iter().enumerate() {
                zdd[a] = self.qdd[i];
            }
        }
    }

    /// `z''` at `(t, z, z')` into `zdd`; leaves `q, v, qdd` (full) of this evaluation.
    pub fn evaluate(
        &mut self,
        system: &dyn DaeSystem,
        t: f64,
        z: &[f64],
        zd: &[f64],
        zdd: &mut [f64],
    ) -> Result<(), StepFailure> {
        self.evaluate_stage(system, t, z, zd, zdd, true)
    }

    /// [`PartitionedRhs::evaluate`] for an intermediate stage (`complete = false`): a system
    /// with a closed form may then leave the multipliers and the dependent coordinates that
    /// no acceleration needs ([`DaeSystem::reduced_rhs`]); the general path computes all.
    pub fn evaluate_stage(
        &mut self,
        system: &dyn DaeSystem,
        t: f64,
        z: &[f64],
        zd: &[f64],
        zdd: &mut [f64],
        complete: bool,
    ) -> Result<(), StepFailure> {
        let (n, m, k) = (self.n, self.m, self.k());
        self.scatter(z, zd);
        let lambda = if complete {
            Some(&mut self.lambda[..])
        } else {
            None
        };
        let closed = system.reduced_rhs(t, &mut self.q, &mut self.v, &mut self.qdd, lambda);
        self.closed_form = closed.is_some();
        if let Some(result) = closed {
            result?;
            self.gather_accelerations(zdd);
            return Ok(());
        }
        self.solve_positions(system, t, z)?;
        // Velocities.
        for (a, &i) in self.independent.iter().enumerate() {
            self.v[i] = zd[a];
        }
        system.constraint_rate(t, &self.q, &mut self.rhs_m);
        for r in 0..m {
            let mut s = self.rhs_m[r];
            for (a, &i) in self.independent.iter().enumerate() {
                s += self.jac[(r, i)] * zd[a];
            }
            self.rhs_m[r] = -s;
        }
        self.jac_d.solve(&mut self.rhs_m, &mut self.work);
        for (c, &i) in self.dependent.iter().enumerate() {
            self.v[i] = self.rhs_m[c];
        }
        // G_D = -Phi_D^-1 Phi_I (column by column), b_D = Phi_D^-1 gamma.
        for (a, &i) in self.independent.iter().enumerate() {
            for r in 0..m {
                self.rhs_m[r] = -self.jac[(r, i)];
            }
            self.jac_d.solve(&mut self.rhs_m, &mut self.work);
            for c in 0..m {
                self.g_d[c * k + a] = self.rhs_m[c];
            }
        }
        system.constraint_acceleration_rhs(t, &self.q, &self.v, &mut self.b_d);
        self.jac_d.solve(&mut self.b_d, &mut self.work);
        // M, Q; M G (n x k) and the reduced system.
        system.mass(&self.q, self.mass.as_mut());
        system.forces(t, &self.q, &self.v, &mut self.force);
        for i in 0..n {
            for a in 0..k {
                let mut s = self.mass[(i, self.independent[a])];
                for (c, &j) in self.dependent.iter().enumerate() {
                    s += self.mass[(i, j)] * self.g_d[c * k + a];
                }
                self.mg[i * k + a] = s;
            }
            // Q - M b (b has dependent entries only), kept in `force`.
            let mut mb = 0.0;
            for (c, &j) in self.dependent.iter().enumerate() {
                mb += self.mass[(i, j)] * self.b_d[c];
            }
            self.force[i] -= mb;
        }
        for a in 0..k {
            let ia = self.independent[a];
            for b in 0..k {
                let mut s = self.mg[ia * k + b];
                for (c, &j) in self.dependent.iter().enumerate() {
                    s += self.g_d[c * k + a] * self.mg[j * k + b];
                }
                self.reduced.set(a, b, s);
            }
            let mut f = self.force[ia];
            for (c, &j) in self.dependent.iter().enumerate() {
                f += self.g_d[c * k + a] * self.force[j];
            }
            self.rhs_k[a] = f;
        }
        if !self.reduced.factor() {
            return Err(StepFailure::SingularMatrix);
        }
        self.reduced.solve(&mut self.rhs_k, &mut self.work);
        if self.rhs_k.iter().any(|x| !x.is_finite()) {
            return Err(StepFailure::NonFinite);
        }
        zdd.copy_from_slice(&self.rhs_k);
        for (a, &i) in self.independent.iter().enumerate() {
            self.qdd[i] = zdd[a];
        }
        for (c, &j) in self.dependent.iter().enumerate() {
            let mut s = self.b_d[c];
            for a in 0..k {
                s += self.g_d[c * k + a] * zdd[a];
            }
            self.qdd[j] = s;
        }
        Ok(())
    }

    /// Multipliers of the last evaluation: `Phi_D^T lambda = (Q - M q'')_D` (with `Q - M b`
    /// kept by [`PartitionedRhs::evaluate`], `(Q - M q'')_D = (Q - M b)_D - (M G z'')_D`).
    pub fn multipliers(&mut self) {
        if self.closed_form {
            return;
        }
        let k = self.k();
        for (c, &j) in self.dependent.iter().enumerate() {
            let mut s = self.force[j];
            for (a, &i) in self.independent.iter().enumerate() {
                s -= self.mg[j * k + a] * self.qdd[i];
            }
            self.lambda[c] = s;
        }
        self.jac_d.solve_transpose(&mut self.lambda, &mut self.work);
    }
}
