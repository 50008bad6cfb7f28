//! The FFR rod body.
//!
//! Coordinates `q = [R_x, R_y, phi, p_1..p_n]`: frame origin R (global, m), frame angle phi
//! (rad, counter-clockwise), modal amplitudes p (unit modal mass). A material point at
//! undeformed body-frame position `xbar` is at `r = R + A(phi) (xbar + S_hat p)`.
//!
//! Mass matrix (Agrawal and Shabana 1985, eq. 3.17-3.18, in modal form eq. 6.2; docs/physics.md;
//! re-derived from `T = 1/2 int rho r'.r'` with `r' = R' + phi' A I~ ubar + A S_hat p'`):
//! `M_RR = m I`, `M_Rphi = A I~ (I1 + I2 p)`, `M_Rp = A I2`,
//! `M_phiphi = I3 + 2 I4 p + p^T M_uu p` (M_uu = M_ff without nodal rotary inertia), `M_phip = -(I5 + p^T S~) + I_rot`, `M_pp = M_ff`.
//! Quadratic velocity vector (from the velocity-product part of
//! `r'' = R'' + A(phi'' I~ ubar + S_hat p'' - phi'^2 ubar + 2 phi' I~ S_hat p')`):
//! `Qv_R = A (phi'^2 (I1 + I2 p) - 2 phi' I~ I2 p')`, `Qv_phi = -2 phi' (I4 + p^T M_ff) p'`,
//! `Qv_p = phi'^2 (I4^T + M_ff p) - 2 phi' S~ p'`.
//! Elastic and damping forces `-K p - D p'`, `K = diag(w_i^2)`, `D = diag(2 zeta w_i)`.
//!
//!
//! Material points: [`super::points`]; the axial stiffening: [`super::stiffening`].

use faer::reborrow::ReborrowMut;
use faer::MatMut;
use nalgebra::{DMatrix, Vector2};

use super::points::{rot, rotate, tilde};
use crate::modal::axial_coupling::AxialCoupling;
use crate::modal::{ComponentModes, ShapeIntegrals};
use crate::rod::body::{RodBody, RodPoint};

/// The FFR rod with its preprocessed modes.
pub struct FfrRod {
    pub modes: ComponentModes,
    pub integrals: ShapeIntegrals,
    /// Modal stiffness w_i^2 and damping 2 zeta w_i.
    pub(super) stiffness: Vec<f64>,
    pub(super) damping: Vec<f64>,
    pub(super) axial_stiffening: bool,
    /// The geometric stiffness per unit `coupling_scale e.R''` (computed once): `G_1 - L G_0`
    /// for the plain rod (`coupling_scale = rho A`), `G_a` otherwise (`coupling_scale = 1`).
    pub(super) acceleration_stiffness: DMatrix<f64>,
    pub(super) coupling_scale: f64,
    pub(super) length: f64,
    pub(super) rho_a: f64,
    pub(super) mass: f64,
    pub(super) n: usize,
    /// Mass samples and cuts of the section-force recovery.
    pub(super) sampling: super::sections::Sampling,
    /// The shape integrals in fixed-size arrays (at most `MAX_MODES` modes), for the
    /// minimal-coordinate right-hand side.
    pub(super) kernel: Option<Box<super::fixed_size_integrals::FfrKernel>>,
    /// Left-out modes whose quasi-static response the midpoint deflection adds
    /// ([`super::residual`]; empty: none).
    pub(super) residual: Vec<super::residual::ResidualMode>,
    /// Per retained mode, the factor on its error-control scale
    /// ([`crate::rod::RodBody::coordinate_scale`]): `(w_1 / w_k)^2` for an axial mode `k`
    /// with `w_1` the lowest retained bending frequency, 1 for bending modes.
    pub(super) axial_scale_ratio: Vec<f64>,
    /// The axial strain's coupling with the bending where axial modes are retained and the
    /// stiffening is on ([`crate::modal::axial_coupling`]).
    pub(super) axial_coupling: Option<AxialCoupling>,
}

/// `(w_1 / w_k)^2` for each retained axial mode `k` (`w_1`: the lowest retained bending
/// frequency; none retained: 1), 1 for the bending modes.
fn axial_scale_ratios(modes: &ComponentModes) -> Vec<f64> {
    let axial = |j: usize| modes.is_axial(modes.retained[j]);
    let count = modes.retained.len();
    let first_bending = (0..count)
        .filter(|&j| !axial(j))
        .map(|j| modes.omega2[j])
        .fold(f64::INFINITY, f64::min);
    (0..count)
        .map(|j| {
            if axial(j) && first_bending.is_finite() && modes.omega2[j] > 0.0 {
                (first_bending / modes.omega2[j]).min(1.0)
            } else {
                1.0
            }
        })
        .collect()
}

impl FfrRod {
    pub fn new(modes: ComponentModes, damping_ratio: f64, axial_stiffening: bool) -> FfrRod {
        let integrals = ShapeIntegrals::new(&modes);
        let stiffness = modes.omega2.clone();
        let damping = modes
            .omega2
            .iter()
            .map(|w2| 2.0 * damping_ratio * w2.sqrt())
            .collect();
        let section = modes.mesh.section;
        let (acceleration_stiffness, coupling_scale) = match &integrals.g_axial {
            None => (
                &integrals.g[1] - &integrals.g[0] * section.length,
                section.mass_per_length(),
            ),
            Some([g_a, _]) => (g_a.clone(), 1.0),
        };
        let mass = integrals.mass;
        let axial_scale_ratio = axial_scale_ratios(&modes);
        let axial_coupling = if axial_stiffening {
            AxialCoupling::new(&modes)
        } else {
            None
        };
        let mut rod = FfrRod {
            axial_coupling,
            axial_scale_ratio,
            sampling: super::sections::Sampling::new(&modes, integrals.x_b),
            acceleration_stiffness,
            coupling_scale,
            n: modes.n_modes(),
            integrals,
            stiffness,
            damping,
            axial_stiffening,
            length: section.length,
            rho_a: section.mass_per_length(),
            mass,
            modes,
            kernel: None,
            residual: Vec::new(),
        };
        rod.kernel = super::fixed_size_integrals::FfrKernel::new(&rod).map(Box::new);
        rod
    }

    /// With residual flexibility ([`super::residual`]): the bending modes of `all` (every
    /// mode of the rod in the same basis) left out of the retained ones add their quasi-static
    /// response to the midpoint deflection.
    pub fn with_residual_flexibility(mut self, all: &ComponentModes) -> FfrRod {
        self.residual = super::residual::residual_modes(all, &self.modes.retained);
        self
    }

    /// The left-out modes that add their quasi-static response ([`Self::with_residual_flexibility`]).
    pub fn residual_modes(&self) -> &[super::residual::ResidualMode] {
        &self.residual
    }

    /// Number of modal coordinates.
    pub fn n_modes(&self) -> usize {
        self.n
    }

    /// Mass of the rod with its end bodies, kg (the FMU's `rod.mass`).
    pub fn total_mass(&self) -> f64 {
        self.mass
    }

    /// The symmetric mass matrix of the kinetic energy.
    pub(super) fn kinetic_mass(&self, q: &[f64], mut m: MatMut<'_, f64>) {
        let n = self.n;
        let ig = &self.integrals;
        let (c, s) = rot(q[2]);
        let p = &q[3..3 + n];
        m[(0, 0)] = self.mass;
        m[(1, 1)] = self.mass;
        m[(0, 1)] = 0.0;
        m[(1, 0)] = 0.0;
        let arm = rotate(c, s, tilde(self.first_moment(q)));
        m[(0, 2)] = arm.x;
        m[(1, 2)] = arm.y;
        m[(2, 0)] = arm.x;
        m[(2, 1)] = arm.y;
        let mut m_phiphi = ig.i3;
        for i in 0..n {
            m_phiphi += 2.0 * ig.i4[i] * p[i];
            for j in 0..n {
                m_phiphi += p[i] * ig.m_uu[(i, j)] * p[j];
            }
        }
        m[(2, 2)] = m_phiphi;
        for j in 0..n {
            let col = rotate(c, s, Vector2::new(ig.i2[(0, j)], ig.i2[(1, j)]));
            m[(0, 3 + j)] = col.x;
            m[(1, 3 + j)] = col.y;
            m[(3 + j, 0)] = col.x;
            m[(3 + j, 1)] = col.y;
            let mut pst = 0.0;
            for i in 0..n {
                pst += p[i] * ig.s_tilde[(i, j)];
            }
            let mpp = -(ig.i5[j] + pst) + ig.i_rot[j];
            m[(2, 3 + j)] = mpp;
            m[(3 + j, 2)] = mpp;
            for i in 0..n {
                m[(3 + i, 3 + j)] = ig.m_ff[(i, j)];
            }
        }
    }
}

impl RodBody for FfrRod {
    fn n_coordinates(&self) -> usize {
        3 + self.n
    }

    fn extra_evaluation_cost(&self) -> f64 {
        self.axial_coupling.as_ref().map_or(0.0, |c| {
            crate::rod::cost::axial_coupling_evaluation(c.n, c.axial.len())
        })
    }

    fn coordinate_scale(&self, i: usize) -> f64 {
        match i {
            0 | 1 => self.length,
            2 => 1.0,
            // Unit modal mass: a displacement d is a modal amplitude of about d sqrt(m).
            // An axial mode moves v_mid only through the axial force it carries into bending:
            // its scale is the amplitude whose elastic force w_k^2 p matches that of the first
            // bending mode's scale, `(w_1 / w_k)^2` of it.
            k => {
                let scale = self.length * self.mass.sqrt();
                let mode = k - 3;
                match self.axial_scale_ratio.get(mode) {
                    Some(&r) => scale * r,
                    None => scale,
                }
            }
        }
    }

    fn place_undeformed(
        &self,
        b: Vector2<f64>,
        c: Vector2<f64>,
        vb: Vector2<f64>,
        omega: f64,
        q: &mut [f64],
        v: &mut [f64],
    ) {
        let d = c - b;
        let phi = d.y.atan2(d.x);
        let (cs, sn) = rot(phi);
        // R = B - A xbar_B.
        let xb = Vector2::new(self.integrals.x_b, 0.0);
        let r = b - rotate(cs, sn, xb);
        // R' = v_B - omega A I~ xbar_B.
        let rv = vb - omega * rotate(cs, sn, tilde(xb));
        q.iter_mut().for_each(|x| *x = 0.0);
        v.iter_mut().for_each(|x| *x = 0.0);
        q[0] = r.x;
        q[1] = r.y;
        q[2] = phi;
        v[0] = rv.x;
        v[1] = rv.y;
        v[2] = omega;
    }

    fn frame_coordinates(&self) -> Option<[usize; 3]> {
        Some([0, 1, 2])
    }

    fn ffr_kernel(&self) -> Option<&super::fixed_size_integrals::FfrKernel> {
        self.kernel.as_deref()
    }

    fn elastic_circular_frequencies(&self) -> Option<Vec<f64>> {
        Some(self.stiffness.iter().map(|w2| w2.sqrt()).collect())
    }

    fn axial_mode_indices(&self) -> Vec<usize> {
        (0..self.n)
            .filter(|&j| self.modes.is_axial(self.modes.retained[j]))
            .collect()
    }

    fn elastic_coordinates(&self) -> Option<std::ops::Range<usize>> {
        Some(3..3 + self.n)
    }

    fn mass(&self, q: &[f64], mut m: MatMut<'_, f64>) {
        self.kinetic_mass(q, m.rb_mut());
        if self.axial_stiffening && self.n > 0 {
            self.add_stiffening_coupling(q, m.rb_mut());
        }
        if let Some(ac) = &self.axial_coupling {
            ac.add_mass(&q[3..3 + self.n], |i, j, x| m[(3 + i, 3 + j)] += x);
        }
    }

    fn forces(&self, q: &[f64], v: &[f64], f: &mut [f64]) {
        let n = self.n;
        let ig = &self.integrals;
        let (c, s) = rot(q[2]);
        let p = &q[3..3 + n];
        let pd = &v[3..3 + n];
        let w = v[2];
        // Qv_R = A (w^2 (I1 + I2 p) - 2 w I~ I2 p').
        let mut i2pd = Vector2::zeros();
        for j in 0..n {
            i2pd.x += ig.i2[(0, j)] * pd[j];
            i2pd.y += ig.i2[(1, j)] * pd[j];
        }
        let qr = rotate(
            c,
            s,
            self.first_moment(q) * (w * w) - tilde(i2pd) * (2.0 * w),
        );
        f[0] = qr.x;
        f[1] = qr.y;
        // Qv_phi = -2 w (I4 + p^T M_ff) p'.
        let mut qphi = 0.0;
        for j in 0..n {
            let mut row = ig.i4[j];
            for i in 0..n {
                row += p[i] * ig.m_uu[(i, j)];
            }
            qphi -= 2.0 * w * row * pd[j];
        }
        f[2] = qphi;
        let kg = if self.axial_stiffening && n > 0 && ig.g_axial.is_none() {
            Some(self.axial_force_coefficients(v))
        } else {
            None
        };
        let g_velocity = match &ig.g_axial {
            Some([_, g_v]) if self.axial_stiffening => Some(g_v),
            _ => None,
        };
        for i in 0..n {
            // Qv_p = w^2 (I4 + M_ff p) - 2 w S~ p'.
            let mut fi = w * w * ig.i4[i];
            for j in 0..n {
                fi += w * w * ig.m_uu[(i, j)] * p[j] - 2.0 * w * ig.s_tilde[(i, j)] * pd[j];
            }
            fi -= self.stiffness[i] * p[i] + self.damping[i] * pd[i];
            if let Some([n0, n1, n2]) = kg {
                for j in 0..n {
                    let kij = n0 * ig.g[0][(i, j)] + n1 * ig.g[1][(i, j)] + n2 * ig.g[2][(i, j)];
                    fi -= kij * p[j];
                }
            }
            if let Some(g_v) = g_velocity {
                for j in 0..n {
                    fi -= w * w * g_v[(i, j)] * p[j];
                }
            }
            f[3 + i] = fi;
        }
        if let Some(ac) = &self.axial_coupling {
            ac.add_forces(p, pd, w, &mut f[3..3 + n]);
        }
    }

    fn add_gravity(&self, q: &[f64], g: Vector2<f64>, f: &mut [f64]) {
        // r = R + A ubar: dr/dR = I, dr/dphi = A I~ ubar, dr/dp = A S_hat; integrated with the
        // mass (rod and end bodies): Q_R = m g, Q_phi = (A I~ (I1 + I2 p)) . g,
        // Q_p = (A I2)^T g (the first block row of the mass matrix, applied to g).
        let (c, s) = rot(q[2]);
        f[0] += self.mass * g.x;
        f[1] += self.mass * g.y;
        f[2] += rotate(c, s, tilde(self.first_moment(q))).dot(&g);
        let ig = &self.integrals;
        for j in 0..self.n {
            f[3 + j] += rotate(c, s, Vector2::new(ig.i2[(0, j)], ig.i2[(1, j)])).dot(&g);
        }
    }

    fn section_loads(
        &self,
        q: &[f64],
        v: &[f64],
        qdd: &[f64],
        g: Vector2<f64>,
        force_c: Vector2<f64>,
    ) -> crate::rod::SectionLoads {
        self.section_loads_ffr(q, v, qdd, g, force_c)
    }

    fn add_tangent(&self, _q: &[f64], v: &[f64], c_k: f64, c_d: f64, mut out: MatMut<'_, f64>) {
        let n = self.n;
        let w = v[2];
        let ig = &self.integrals;
        for i in 0..n {
            out[(3 + i, 3 + i)] += c_k * self.stiffness[i] + c_d * self.damping[i];
            for j in 0..n {
                // -d(Qv_p)/dp = -w^2 M_ff (centrifugal softening); -d(Qv_p)/dp' = 2 w S~ (gyroscopic).
                out[(3 + i, 3 + j)] +=
                    -c_k * w * w * ig.m_uu[(i, j)] + c_d * 2.0 * w * ig.s_tilde[(i, j)];
            }
        }
    }

    fn point(&self, p: RodPoint, q: &[f64]) -> Vector2<f64> {
        let (c, s) = rot(q[2]);
        Vector2::new(q[0], q[1]) + rotate(c, s, self.ubar(p, q))
    }

    fn point_at(&self, s: f64, q: &[f64]) -> Vector2<f64> {
        let (c, sn) = rot(q[2]);
        Vector2::new(q[0], q[1]) + rotate(c, sn, self.ubar_at(s, q))
    }

    fn points(&self, q: &[f64]) -> [Vector2<f64>; 3] {
        let (c, s) = rot(q[2]);
        let r = Vector2::new(q[0], q[1]);
        [RodPoint::B, RodPoint::C, RodPoint::Mid].map(|p| r + rotate(c, s, self.ubar(p, q)))
    }

    /// In the body frame (`ubar` of B, C and the midpoint): the distance from the chord does
    /// not change with the frame's rotation. With the kernel, its fixed-size sums in the same
    /// order ([`super::fixed_size_integrals::FfrKernel::mid_deflection`]).
    fn mid_deflection(&self, q: &[f64]) -> f64 {
        if let Some(kernel) = &self.kernel {
            return kernel.mid_deflection(&q[3..]);
        }
        crate::rod::body::chord_distance(
            [RodPoint::B, RodPoint::C, RodPoint::Mid].map(|p| self.ubar(p, q)),
        )
    }

    /// With residual flexibility, the left-out modes' quasi-static deflection added
    /// ([`super::residual::residual_deflection`]).
    fn mid_deflection_dynamic(&self, q: &[f64], qdd: &[f64], gravity: Vector2<f64>) -> f64 {
        self.mid_deflection(q)
            + super::residual::residual_deflection(
                &self.residual,
                q[2],
                Vector2::new(qdd[0], qdd[1]),
                qdd[2],
                gravity,
            )
    }

    fn point_jacobian(&self, p: RodPoint, q: &[f64], mut out: MatMut<'_, f64>) {
        let (c, s) = rot(q[2]);
        out[(0, 0)] = 1.0;
        out[(0, 1)] = 0.0;
        out[(1, 0)] = 0.0;
        out[(1, 1)] = 1.0;
        let d = rotate(c, s, tilde(self.ubar(p, q)));
        out[(0, 2)] = d.x;
        out[(1, 2)] = d.y;
        for j in 0..self.n {
            let col = rotate(c, s, self.ubar_p(p, q, j));
            out[(0, 3 + j)] = col.x;
            out[(1, 3 + j)] = col.y;
        }
    }

    fn point_bias_acceleration(&self, p: RodPoint, q: &[f64], v: &[f64]) -> Vector2<f64> {
        // -phi'^2 A ubar + 2 phi' A I~ S_hat p'.
        let (c, s) = rot(q[2]);
        let w = v[2];
        let mut bias = self.ubar(p, q) * (-w * w) + tilde(self.shape_rate(p, q, v)) * (2.0 * w);
        if self.foreshortening(p) {
            bias.x -= self.quad(&v[3..], &v[3..]);
        }
        rotate(c, s, bias)
    }

    fn add_point_force_tangent(
        &self,
        p: RodPoint,
        q: &[f64],
        f: Vector2<f64>,
        coef: f64,
        mut out: MatMut<'_, f64>,
    ) {
        // J^T f = [f; (A I~ ubar).f; (A S_hat)^T f].
        // d/dphi (A I~ ubar).f = -(A ubar).f; d/dp (A I~ ubar).f = (A I~ S_hat)^T f = d/dphi (A S_hat)^T f.
        let (c, s) = rot(q[2]);
        let u = rotate(c, s, self.ubar(p, q));
        out[(2, 2)] += coef * (-u.dot(&f));
        for j in 0..self.n {
            let col = rotate(c, s, tilde(self.ubar_p(p, q, j)));
            let v = coef * col.dot(&f);
            out[(2, 3 + j)] += v;
            out[(3 + j, 2)] += v;
        }
        if self.foreshortening(p) {
            // d2 (f . A ubar) / dp2 = -(f . A e_x) G_0.
            let fx = rotate(c, s, Vector2::new(1.0, 0.0)).dot(&f);
            let g = &self.integrals.g[0];
            for i in 0..self.n {
                for j in 0..self.n {
                    out[(3 + i, 3 + j)] -= coef * fx * g[(i, j)];
                }
            }
        }
    }

    fn kinetic_energy(&self, q: &[f64], v: &[f64]) -> f64 {
        let nq = 3 + self.n;
        let mut m = faer::Mat::<f64>::zeros(nq, nq);
        self.kinetic_mass(q, m.as_mut());
        let mut t = 0.0;
        for i in 0..nq {
            for j in 0..nq {
                t += v[i] * m[(i, j)] * v[j];
            }
        }
        0.5 * t
    }

    fn strain_energy(&self, q: &[f64]) -> f64 {
        (0..self.n)
            .map(|i| 0.5 * self.stiffness[i] * q[3 + i] * q[3 + i])
            .sum()
    }

    fn linear_momentum(&self, q: &[f64], v: &[f64]) -> Vector2<f64> {
        let (c, s) = rot(q[2]);
        let mut p =
            Vector2::new(v[0], v[1]) * self.mass + rotate(c, s, tilde(self.first_moment(q))) * v[2];
        for j in 0..self.n {
            p += rotate(
                c,
                s,
                Vector2::new(self.integrals.i2[(0, j)], self.integrals.i2[(1, j)]),
            ) * v[3 + j];
        }
        p
    }

    fn frequencies_hz(&self) -> &[f64] {
        &self.modes.all_frequencies_hz
    }

    fn first_bending_hz(&self) -> Option<f64> {
        let all = &self.modes.all_frequencies_hz;
        (0..all.len())
            .find(|&k| !self.modes.is_axial(k))
            .map(|k| all[k])
    }

    fn describe(&self) -> String {
        let kept = format!("FFR rod, modes kept: {}", self.modes.summary());
        let hz = |w2: f64| w2.sqrt() / (2.0 * std::f64::consts::PI);
        let above = self.residual.iter().map(|r| hz(r.omega2));
        match (above.clone().reduce(f64::min), above.reduce(f64::max)) {
            (Some(lo), Some(hi)) => format!(
                "{kept}; static corrections to v_mid: {} bending modes, {lo:.0} to {hi:.0} Hz",
                self.residual.len()
            ),
            _ => kept,
        }
    }

    fn length(&self) -> f64 {
        self.length
    }

    fn total_mass(&self) -> f64 {
        self.mass
    }

    fn highest_frequency_hz(&self) -> f64 {
        self.modes
            .omega2
            .iter()
            .map(|w2| w2.sqrt() / (2.0 * std::f64::consts::PI))
            .fold(0.0, f64::max)
    }
}
