//! The coupling of the rod's axial strain with its bending, for rods whose retained modes
//! include axial ones (docs/physics.md, "What linear modes miss", part 3).
//!
//! The axial stiffening carries the foreshortening kinematically: the material point at arc
//! length `s` sits at `x = x_b + s + u(s) - delta(s)` along the frame's x axis and `v(s)`
//! across it, `delta' = v'^2 / 2` (Euler-Bernoulli) or `v' psi - psi^2 / 2` (shear-deformable
//! rod, Reissner's form). With axial modes the rod also stretches, by `u' = A p`, and two terms
//! of the same order as the stiffening follow from that kinematics.
//!
//! **Elastic energy.** Reissner's strains of these fields (E. Reissner, ZAMP 23, 1972) are,
//! to the order kept, `eps = u' - u' psi^2 / 2`, `gamma = v' - psi - u' psi`, `kappa = psi'`
//! (shear-deformable rod) and `eps = u' - u' v'^2 / 2`, `kappa = v'' (1 - u') - u'' v'`
//! (Euler-Bernoulli, `psi = atan(v' / (1 + u'))`). The linear modes keep `1/2 E A u'^2 +
//! 1/2 G A_s (v' - psi)^2 + 1/2 E I psi'^2`; the rest is
//!
//! ```text
//! U = -int c u' B ds - 1/2 int E A u'^2 R ds
//!   shear-deformable: c B = G A_s psi gamma,  R = psi^2
//!   Euler-Bernoulli:  c B = E I v''^2 (+ E I u'' v' v'', at the nodes where the
//!                     element-wise constant u' jumps),  R = v'^2
//! ```
//!
//! a stretched rod bends more easily and a compressed one less (the bending stiffness per unit
//! transverse deflection scales with `1 - 2 u'`), and the axial force's geometric stiffness
//! turns from `N` into `N (1 - u')`. For a pinned-pinned rod under an end load `P` this
//! gives the extensible rod's buckling load, `P (1 + eps) + P^2 / (G A_s) = P_E` to first
//! order in `eps = -P / E A`, where the linear modes give Haringx's `P + P^2 / (G A_s) = P_E`.
//!
//! **Inertia.** The axial elastic motion of the material carries an axial inertia force
//! through the foreshortening, as the rigid motion's does (parts 1 and 2 of the stiffening):
//! with `Z_ijk = int dm S_x,i(s) Gamma_jk(s)` (`Gamma(s) = int_0^s D^T D`, the integrand of
//! [`super::ShapeIntegrals::g`], `dm` the rod's mass and the small end's at C), the kinetic
//! energy's part in `delta` gives, in the p rows,
//!
//! ```text
//! M_pp += -sum_l (Z_ijl + Z_jil) p_l                                      (symmetric)
//! Q_p,i += sum_jk Z_ijk (p'_j p'_k - 1/2 phi'^2 p_j p_k) - phi'^2 Z_kij p_j p_k
//! ```
//!
//! (`Z_ijk p'_j p'_k`: the foreshortening's own axial inertia on the axial modes; `Z_kij`:
//! the axial force of the axial modes' relative and centripetal acceleration, `u'' -
//! phi'^2 u`, on the bending).
//!
//! Both parts are needed together: against the geometrically exact beam, each alone moves
//! the FFR rod away from it (docs/physics.md). Bending modes of a straight rod have no axial
//! displacement, so every tensor is zero without axial modes, and the rod is then built
//! without this coupling.

use nalgebra::DMatrix;

use super::component_modes::ComponentModes;
use super::shape_integrals::point_shape;
use crate::beam::quadrature::GAUSS4;

/// Sub-intervals per element of the quadrature of `Z` (the mass beyond `s` is of a higher
/// degree than one 4-point rule integrates exactly against `D^T D` on a section table).
const SUBDIVISIONS: usize = 4;

/// The tensors of the coupling (module documentation) for `n` retained modes, of which the
/// axial ones are `axial` (`na` of them): only their rows are stored, so the cost is
/// `na n^2` per evaluation, not `n^4` (a rod of a few hundred modes keeps one or two axial).
/// Index `(a n + i) n + j` for `T` and `Z` (`a` the position in `axial`), `((a na + b) n +
/// i) n + j` for `F`.
#[derive(Clone, Debug, PartialEq)]
pub struct AxialCoupling {
    pub n: usize,
    /// The retained axial modes (indices of the modal coordinates).
    pub axial: Vec<usize>,
    /// `T_aij = int c A_a B_ij` (`U3 = -T_aij p_a p_i p_j`).
    pub t3: Vec<f64>,
    /// `F_abij = int E A A_a A_b R_ij` (`U4 = -1/2 F_abij p_a p_b p_i p_j`).
    pub t4: Vec<f64>,
    /// `Z_ajk = int dm S_x,a Gamma_jk = int mu_a D^T D_jk ds`, `mu_a(s) = int_s^L dm S_x,a`.
    pub z: Vec<f64>,
}

impl AxialCoupling {
    /// The coupling of the retained modes of `modes`, or `None` where no retained mode is an
    /// axial one (the bending modes' axial displacements are zero but for the eigensolver's
    /// round-off, and they are left out of the sums).
    pub fn new(modes: &ComponentModes) -> Option<AxialCoupling> {
        let axial: Vec<usize> = (0..modes.n_modes())
            .filter(|&j| modes.is_axial(modes.retained[j]))
            .collect();
        (!axial.is_empty()).then(|| Self::compute(modes, axial))
    }

    fn compute(modes: &ComponentModes, axial: Vec<usize>) -> AxialCoupling {
        let mesh = &modes.mesh;
        let def = &mesh.definition;
        let n = modes.n_modes();
        let na = axial.len();
        let l = mesh.element_length();
        let props = mesh.section;
        let shear = def.shear_modulus.is_some();
        let n2 = n * n;
        let mut t3 = vec![0.0; na * n2];
        let mut t4 = vec![0.0; na * na * n2];
        // Axial strain of the axial modes in element e (the axial interpolation is linear).
        let strain = |e: usize| -> Vec<f64> {
            let t = modes.element_shapes(e);
            axial.iter().map(|&k| (t[(3, k)] - t[(0, k)]) / l).collect()
        };
        let mut cb = vec![0.0; n2];
        let mut ear = vec![0.0; n2];
        for e in 0..mesh.n_elements {
            let t = modes.element_shapes(e);
            let el = mesh.section_element(e);
            let a = strain(e);
            for (xi, w) in GAUSS4 {
                let (ea, ei, gas) = match &el {
                    Some(el) => {
                        let v = el.section_at(xi);
                        (
                            el.youngs_modulus * v.area,
                            el.youngs_modulus * v.area_moment,
                            el.shear_modulus.unwrap_or(0.0) * v.shear_area,
                        )
                    }
                    None => (props.axial_rigidity(), props.bending_rigidity(), 0.0),
                };
                // Per point: c B_ij and E A R_ij.
                match (&el, shear) {
                    (Some(el), true) => {
                        let psi = el.rotation_full(xi) * &t;
                        let gam = el.shear_strain_full(xi) * &t;
                        for i in 0..n {
                            for j in 0..n {
                                cb[i * n + j] = gas
                                    * 0.5
                                    * (psi[(0, i)] * gam[(0, j)] + psi[(0, j)] * gam[(0, i)]);
                                ear[i * n + j] = ea * psi[(0, i)] * psi[(0, j)];
                            }
                        }
                    }
                    _ => {
                        let kap = mesh.curvature(e, xi) * &t;
                        let sl = mesh.slope(e, xi) * &t;
                        for i in 0..n {
                            for j in 0..n {
                                cb[i * n + j] = ei * kap[(0, i)] * kap[(0, j)];
                                ear[i * n + j] = ea * sl[(0, i)] * sl[(0, j)];
                            }
                        }
                    }
                }
                let dw = w * l;
                for ka in 0..na {
                    for ij in 0..n2 {
                        t3[ka * n2 + ij] += dw * a[ka] * cb[ij];
                    }
                    for kb in 0..na {
                        for ij in 0..n2 {
                            t4[(ka * na + kb) * n2 + ij] += dw * a[ka] * a[kb] * ear[ij];
                        }
                    }
                }
            }
        }
        // Euler-Bernoulli: `- E I u'' v' v''` with `u''` the jumps of the element-wise constant
        // axial strain at the interior nodes (`v''` averaged over the node's two sides).
        if !shear {
            for node in 1..mesh.n_elements {
                let (left, right) = (node - 1, node);
                let (al, ar) = (strain(left), strain(right));
                let ei = match mesh.section_element(right) {
                    Some(el) => el.youngs_modulus * el.section_at(0.0).area_moment,
                    None => props.bending_rigidity(),
                };
                let (tl, tr) = (modes.element_shapes(left), modes.element_shapes(right));
                let slope = mesh.slope(right, 0.0) * &tr;
                let kap =
                    (mesh.curvature(left, 1.0) * &tl + mesh.curvature(right, 0.0) * &tr) * 0.5;
                for ka in 0..na {
                    let jump = ar[ka] - al[ka];
                    for i in 0..n {
                        for j in 0..n {
                            let b =
                                0.5 * (slope[(0, i)] * kap[(0, j)] + slope[(0, j)] * kap[(0, i)]);
                            t3[ka * n2 + i * n + j] += ei * jump * b;
                        }
                    }
                }
            }
        }
        let z = foreshortening_inertia(modes, &axial);
        AxialCoupling {
            n,
            axial,
            t3,
            t4,
            z,
        }
    }

    /// The generalized forces on the p rows without the accelerations' terms (module
    /// documentation): `-dU/dp` plus the inertia's `Q_p`, at modal coordinates `p`, rates `pd`
    /// and frame angular velocity `w`, added to `out`.
    pub fn add_forces(&self, p: &[f64], pd: &[f64], w: f64, out: &mut [f64]) {
        let n = self.n;
        let n2 = n * n;
        let na = self.axial.len();
        let w2 = w * w;
        for (ka, &a) in self.axial.iter().enumerate() {
            let t = &self.t3[ka * n2..(ka + 1) * n2];
            let z = &self.z[ka * n2..(ka + 1) * n2];
            // The axial mode's own row: T_aij p_i p_j (U3), F_abij p_b p_i p_j (U4), and the
            // foreshortening's axial inertia Z_aij (p'_i p'_j - 1/2 w^2 p_i p_j).
            let mut own = 0.0;
            for i in 0..n {
                for j in 0..n {
                    let pij = p[i] * p[j];
                    own += t[i * n + j] * pij + z[i * n + j] * (pd[i] * pd[j] - 0.5 * w2 * pij);
                    for (kb, &b) in self.axial.iter().enumerate() {
                        own += self.t4[(ka * na + kb) * n2 + i * n + j] * p[b] * pij;
                    }
                }
            }
            out[a] += own;
            // Every row m: 2 T_amj p_a p_j (U3), F_abmj p_a p_b p_j (U4), and the axial
            // force of the axial mode's acceleration terms, -w^2 Z_amj p_a p_j.
            for m in 0..n {
                let mut f = 0.0;
                for j in 0..n {
                    let mut fourth = 0.0;
                    for (kb, &b) in self.axial.iter().enumerate() {
                        fourth += self.t4[(ka * na + kb) * n2 + m * n + j] * p[b];
                    }
                    f += (2.0 * t[m * n + j] - w2 * z[m * n + j] + fourth) * p[j];
                }
                out[m] += f * p[a];
            }
        }
    }

    /// The mass matrix's part `M_pp[i][j] = -sum_l (Z_ijl + Z_jil) p_l` (only an axial mode
    /// `i` or `j` has a `Z` row), via `add(i, j, x)`.
    pub fn add_mass(&self, p: &[f64], mut add: impl FnMut(usize, usize, f64)) {
        let n = self.n;
        let n2 = n * n;
        for (ka, &a) in self.axial.iter().enumerate() {
            let z = &self.z[ka * n2..(ka + 1) * n2];
            for j in 0..n {
                let mut x = 0.0;
                for l in 0..n {
                    x -= z[j * n + l] * p[l];
                }
                add(a, j, x);
                add(j, a, x);
            }
        }
    }

    /// The energy `U` of the module documentation at `p` (for tests).
    pub fn energy(&self, p: &[f64]) -> f64 {
        let n = self.n;
        let n2 = n * n;
        let na = self.axial.len();
        let mut u = 0.0;
        for (ka, &a) in self.axial.iter().enumerate() {
            for i in 0..n {
                for j in 0..n {
                    let pij = p[i] * p[j];
                    u -= self.t3[ka * n2 + i * n + j] * p[a] * pij;
                    for (kb, &b) in self.axial.iter().enumerate() {
                        u -= 0.5 * self.t4[(ka * na + kb) * n2 + i * n + j] * p[a] * p[b] * pij;
                    }
                }
            }
        }
        u
    }
}

/// `Z_ajk = int mu_a(s) (D^T D)_jk ds` (Reissner's integrand for the shear-deformable rod),
/// `mu_a(s) = int_s^L rho A S_x,a + m_C S_x,a(L)`: by parts the same as `int dm S_x,a
/// Gamma_jk`, `Gamma(s) = int_0^s D^T D`.
fn foreshortening_inertia(modes: &ComponentModes, axial: &[usize]) -> Vec<f64> {
    let mesh = &modes.mesh;
    let def = &mesh.definition;
    let n = modes.n_modes();
    let na = axial.len();
    let length = mesh.section.length;
    let rho = mesh.section.density;
    let rho_a = |s: f64| match mesh.section_table() {
        Some(table) => rho * table.at(s).area,
        None => mesh.section.mass_per_length(),
    };
    let shear = def.shear_modulus.is_some();
    let s_b = point_shape(modes, 0.0);
    let s_c = point_shape(modes, length);
    let chord: Vec<f64> = (0..n)
        .map(|j| (s_c[(1, j)] - s_b[(1, j)]) / length)
        .collect();
    // `int_a^b rho A S_x` of the axial modes (Gauss on [a, b], inside one element).
    let mass_moment = |a: f64, b: f64| -> Vec<f64> {
        let mut out = vec![0.0; na];
        for (xi, w) in GAUSS4 {
            let s = a + xi * (b - a);
            let sh = point_shape(modes, s);
            let dm = w * (b - a) * rho_a(s);
            for (ka, &k) in axial.iter().enumerate() {
                out[ka] += dm * sh[(0, k)];
            }
        }
        out
    };
    let le = mesh.element_length();
    let bounds = |e: usize, sub: usize| {
        let a = (e as f64 + sub as f64 / SUBDIVISIONS as f64) * le;
        let b = (e as f64 + (sub + 1) as f64 / SUBDIVISIONS as f64) * le;
        (a, b)
    };
    // The mass moment beyond each sub-interval, from C backwards.
    let pieces = mesh.n_elements * SUBDIVISIONS;
    let mut beyond = vec![vec![0.0; na]; pieces + 1];
    for (ka, &k) in axial.iter().enumerate() {
        beyond[pieces][ka] = def.small_end.mass * s_c[(0, k)];
    }
    for piece in (0..pieces).rev() {
        let (a, b) = bounds(piece / SUBDIVISIONS, piece % SUBDIVISIONS);
        let m = mass_moment(a, b);
        for ka in 0..na {
            beyond[piece][ka] = beyond[piece + 1][ka] + m[ka];
        }
    }
    let n2 = n * n;
    let mut z = vec![0.0; na * n2];
    for piece in 0..pieces {
        let e = piece / SUBDIVISIONS;
        let (a, b) = bounds(e, piece % SUBDIVISIONS);
        let t = modes.element_shapes(e);
        for (xi, w) in GAUSS4 {
            let s = a + xi * (b - a);
            let (_, xe) = mesh.locate(s);
            let slope = mesh.slope(e, xe) * &t;
            let d = DMatrix::from_fn(1, n, |_, j| slope[(0, j)] - chord[j]);
            let dtd = if shear {
                let psi = mesh.rotation(e, xe) * &t;
                let dpsi = DMatrix::from_fn(1, n, |_, j| psi[(0, j)] - chord[j]);
                let cross = d.transpose() * &dpsi;
                &cross + cross.transpose() - dpsi.transpose() * &dpsi
            } else {
                d.transpose() * &d
            };
            let tail = mass_moment(s, b);
            let dw = w * (b - a);
            for ka in 0..na {
                let mu = beyond[piece + 1][ka] + tail[ka];
                for j in 0..n {
                    for k in 0..n {
                        z[ka * n2 + j * n + k] += dw * mu * dtd[(j, k)];
                    }
                }
            }
        }
    }
    z
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beam::MassKind;
    use crate::modal::mass_loaded_modes::{axial_coordinate_at_c, AddedMass};
    use crate::modal::{ModeSelection, ReferenceConditions, ReferenceKind};

    /// A steel rod, 0.15 m, with a small end; `slider` kg at C in the eigenproblem (2 kg
    /// brings the slider-rod axial mode to about 1.8 kHz, below the first bending mode).
    fn modes(shear: bool, slider: f64, count: usize) -> ComponentModes {
        let mut def = crate::modal::mass_loaded_modes::tests::rod();
        if shear {
            def.shear_modulus = Some(2e11 / 2.6);
        }
        ComponentModes::from_definition_loaded(
            def,
            8,
            ReferenceConditions::from_kind(ReferenceKind::SimplySupported, 8).unwrap(),
            MassKind::Consistent,
            &ModeSelection::Count(count),
            &[AddedMass {
                coordinate: axial_coordinate_at_c(8),
                mass: slider,
            }],
        )
        .unwrap()
    }

    #[test]
    fn bending_modes_alone_have_no_coupling() {
        let m = modes(false, 0.0, 1);
        assert!(!m.is_axial(m.retained[0]));
        assert!(AxialCoupling::new(&m).is_none());
    }

    /// With the rates and the frame's turning zero, the forces are minus the gradient of the
    /// energy; the mass part is symmetric and not zero.
    #[test]
    fn forces_are_the_energy_gradient_and_the_mass_is_symmetric() {
        for shear in [false, true] {
            let m = modes(shear, 2.0, 3);
            assert!(m.retained.iter().any(|&k| m.is_axial(k)), "an axial mode");
            let c = AxialCoupling::new(&m).unwrap();
            // Amplitudes of unit modal mass, about 1e-3 of the rod's length in deflection.
            let p = [2.1e-4, -1.3e-4, 0.8e-4];
            let mut f = [0.0; 3];
            c.add_forces(&p, &[0.0; 3], 0.0, &mut f);
            for k in 0..3 {
                let h = 1e-7;
                let (mut a, mut b) = (p, p);
                a[k] += h;
                b[k] -= h;
                let grad = (c.energy(&a) - c.energy(&b)) / (2.0 * h);
                let scale = f.iter().fold(0.0f64, |s, x| s.max(x.abs()));
                assert!(scale > 0.0);
                assert!(
                    (f[k] + grad).abs() < 1e-6 * scale,
                    "shear {shear}, p{k}: force {} against -dU/dp {}",
                    f[k],
                    -grad
                );
            }
            let mut mm = [[0.0; 3]; 3];
            c.add_mass(&p, |i, j, x| mm[i][j] += x);
            let largest = mm.iter().flatten().fold(0.0f64, |s, x| s.max(x.abs()));
            assert!(largest > 0.0);
            for i in 0..3 {
                for j in 0..3 {
                    assert!((mm[i][j] - mm[j][i]).abs() <= 1e-12 * largest);
                }
            }
        }
    }

    /// Euler-Bernoulli: an axial strain `eps` changes a bending mode's stiffness by
    /// `-2 eps w_b^2` (the curvature `v'' (1 - eps)`): `T_abb = eps_a w_b^2`, `eps_a` the
    /// mean strain of the axial mode per unit amplitude (the heavy slider makes it nearly
    /// uniform).
    #[test]
    fn a_stretched_rod_bends_more_easily() {
        let m = modes(false, 2.0, 3);
        let c = AxialCoupling::new(&m).unwrap();
        let a = c.axial[0];
        let length = m.mesh.section.length;
        let mean_strain = (point_shape(&m, length)[(0, a)] - point_shape(&m, 0.0)[(0, a)]) / length;
        for b in (0..3).filter(|&j| j != a) {
            let t = c.t3[b * 3 + b];
            let expected = mean_strain * m.omega2[b];
            assert!(
                (t / expected - 1.0).abs() < 0.05,
                "mode {b}: T_abb {t:.4e} against eps_a w_b^2 {expected:.4e}"
            );
        }
    }
}
