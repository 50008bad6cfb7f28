//! The finite segment rod (R. L. Huston, "Computer methods in flexible multibody dynamics",
//! International Journal for Numerical Methods in Engineering 32, 1991; docs/physics.md, "Rod
//! model 2: finite segments"): `N` rigid segments joined by revolute joints with
//! rotational springs and dampers, optionally with prismatic joints carrying axial springs.
//!
//! - [`rod`]: the chain's data and construction ([`SegmentRod`]); [`kinematics`]: its points;
//!   [`dynamics`]: mass matrix, quadratic velocity vector, joint forces, energies (the derivation
//!   follows below);
//! - [`linear`]: the chain linearized about the straight configuration: pinned-pinned
//!   bending and axial frequencies, and the free-free axial chain of Huston's convergence
//!   table ([`axial_chain_frequencies_hz`]).
//!
//! # The derivation (Huston 1991, "Flexibility effects" and "Illustrations/convergence")
//!
//! # Model
//! The rod of length `L` (m) is cut into `N` rigid segments `k = 0..N-1` (0-based here; Huston
//! counts from 1) of length `l = L/N`, mass `m = rho A l` (kg) and centroidal inertia
//! `I_c = m l^2 / 12` (kg m^2). Segment `k` and `k+1` meet in joint `k` (`k = 0..N-2`): a
//! revolute joint with a rotational spring `k_r` (N m/rad) and damper `c_r` (N m s/rad) and,
//! with `rod.axial_springs`, a prismatic joint along segment `k` with an axial spring
//! `k_a = E A / l` (N/m) and damper `c_a` (N s/m). As in Huston 1991, flexibility and damping live
//! in the joints only ("a lumped parameter method with the flexibility and damping modelled at
//! the joints"); planar, so one angle per segment and no Euler parameters (Huston says so).
//!
//! # Coordinates
//! `q = [x_B, y_B, theta_0, .., theta_{N-1}, s_0, .., s_{N-2}]`: the free end B of segment 0
//! (global, m), the absolute segment angles (rad, counter-clockwise from global x), and with
//! axial springs the slide `s_j` (m) of joint `j` (its extension); then the shear slides and
//! the end body rotations, where present (sections "Shear deformation" and "End bodies"). With
//! `e_k = (cos theta_k, sin theta_k)`, `n_k = (-sin theta_k, cos theta_k)` and the joint-to-joint
//! lengths `L_j = l + s_j` (`L_j = l` without axial springs), the material point at distance
//! `xi` in `[0, l]` from the start of segment `k` is
//! `r_k(xi) = B + sum_{j<k} L_j e_j + xi e_k`.
//! B is `r_0(0)`, C is `r_{N-1}(l)`, the midpoint is the material point at arc length `L/2`
//! (the centre of the middle segment for odd `N`, the start of segment `N/2` for even `N`).
//!
//! Huston uses relative coordinates (the joint rotations `phi_k = theta_k - theta_{k-1}`) as
//! generalized speeds with Kane's equations. Absolute angles are the linear change
//! `theta = T phi` (`T` lower triangular of ones); Kane's equations in the relative speeds are
//! `T^T` times the equations here, so the dynamics are the same. The joint springs, single
//! entries in relative coordinates (Huston's decoupling), are tridiagonal here; in exchange
//! the mass matrix stays as well conditioned as the chain itself and the pin constraint rows
//! are plain.
//!
//! # Equations (Lagrange, equivalently Kane)
//! The centroid of segment `k` is `g_k = r_k(l/2)`, its velocity `g_k' = J_k q'` with the
//! columns of the partial velocities `J_k` (Kane's `v_{kl}`):
//! `d g_k / d(x_B, y_B) = I`, `d g_k / d theta_j = L_j n_j` (`j < k`), `= (l/2) n_k` (`j = k`),
//! `d g_k / d s_j = e_j` (`j < k`), zero otherwise; the partial angular velocity of segment `k`
//! is the unit vector of `theta_k`. Kinetic energy
//! `T = 1/2 sum_k (m |g_k'|^2 + I_c theta_k'^2) = 1/2 q'^T M q'` with
//! `M = sum_k (m J_k^T J_k + I_c u_k u_k^T)`, dense in the angles. With `a_j = m (N - 1 - j)`
//! (mass beyond segment `j`), `h_j = m l / 2 + a_j L_j` and `c_ij = cos(theta_i - theta_j)`:
//! - `M_BB = N m I`, `M_{B theta_j} = h_j n_j`, `M_{B s_j} = a_j e_j`;
//! - `M_{theta_i theta_i} = m l^2 / 3 + a_i L_i^2`, `M_{theta_i theta_j} = L_i h_j c_ij` (`i < j`);
//! - `M_{theta_i s_j} = a_j L_i sin(theta_j - theta_i)` (`i < j`), `0` (`i = j`),
//!   `h_i sin(theta_j - theta_i)` (`i > j`);
//! - `M_{s_i s_j} = a_{max(i,j)} c_ij`.
//!
//! Quadratic velocity vector (Kane's generalized inertia force minus its `M q''` part):
//! `Q_v = -sum_k m J_k^T gamma_k`, with the velocity-product acceleration of the centroid
//! `gamma_k = (J_k' q') = sum_{j<k} (2 s_j' theta_j' n_j - L_j theta_j'^2 e_j) - (l/2) theta_k'^2 e_k`
//! (a rigid planar segment has no gyroscopic moment). With the downstream sums
//! `G_i = sum_{k>i} gamma_k`:
//! `Q_v,B = -m sum_k gamma_k`, `Q_v,theta_i = -m n_i . ((l/2) gamma_i + L_i G_i)`,
//! `Q_v,s_j = -m e_j . G_j`, computed in O(N). It equals `-(M' q' - dT/dq)` of Lagrange's
//! equations (checked in tests/segments.rs).
//!
//! Joint forces (Huston, eq. 33-36: one spring or damper component per generalized force in
//! relative coordinates): the moment of joint `j` on segment `j`,
//! `tau_j = k_r (theta_{j+1} - theta_j) + c_r (theta_{j+1}' - theta_j')`, enters
//! `Q_theta_j += tau_j`, `Q_theta_{j+1} -= tau_j`; the axial force `-(k_a s_j + c_a s_j')`
//! enters `Q_s_j`. Strain energy
//! `U = sum_j (k_r (theta_{j+1} - theta_j)^2 + k_a s_j^2) / 2`.
//!
//! # Spring and damper constants
//! `k_r = E I / l` (docs/physics.md): the joint rotation `theta_{j+1} - theta_j` is the curvature
//! integrated over the length `l` a joint stands for, so `k_r (Delta theta)^2 / 2 =
//! E I (Delta theta / l)^2 l / 2` is the beam's bending energy of that length. With the joint
//! deflections `w_j`, the joint rotations are the central second difference of `w` times `l`,
//! and the segments' kinetic energy is the consistent mass of a piecewise linear `w`; the
//! errors of the two cancel at second order. Pinned-pinned, the modes are sinusoidal and
//! `omega_n^2 = 48 E I sin^4(n pi / 2N) / (rho A l^4 (2 + cos(n pi / N)))
//! = (n pi / L)^4 E I / (rho A) (1 + O((n pi / N)^4))`: fourth order in `l` (tests/segments.rs
//! checks the closed form and the order), so no other spring constant is needed. A clamped end
//! (not used by the mechanism, whose ends are pinned) needs a root spring `2 E I / l` to the
//! support for second order (mirror ghost segment; tests/segments.rs, rotating cantilever).
//! `k_a = E A / l` is the exact stiffness of a bar of length `l`; the end springs also take the
//! half segments at B and C (`E A / (1.5 l)`), so the static axial compliance between the pins
//! is the rod's `L / (E A)` and the slider-rod axial mode converges at second order.
//!
//! Dampers are stiffness proportional, `c_r = beta_r k_r`, `c_a = beta_a k_a`. In the
//! linearized chain `C = beta K`, so mode `n` has damping ratio `beta omega_n / 2`; choosing
//! `beta_r = 2 zeta / omega_1` (first pinned-pinned bending mode of the chain, computed in
//! [`SegmentRod::new`]) gives that mode exactly `rod.damping_ratio = zeta`, and the higher modes
//! more (as in a material with Kelvin-Voigt damping). `beta_a = 2 zeta / omega_a1` with the first
//! free-free axial mode of the chain (the closed form of [`super::axial_chain_frequencies_hz`]).
//!
//! # Shear deformation (shear-deformable rods, `rod.shear_deformation`)
//! A Timoshenko rod's sections turn by `psi`, not by the slope `w'`; the difference is the shear
//! strain `gamma = w' - psi` (Timoshenko beam: bending energy `E I psi'^2 / 2`, shear energy
//! `kappa G A gamma^2 / 2`, kinetic `rho A w_t^2 / 2 + rho I psi_t^2 / 2` per length; Han,
//! Benaroya and Wei, J. Sound Vib. 225 (1999) 935-988). The chain lumps it as it lumps bending
//! (rigid segments, springs in the joints): the segments' angles are the section rotations
//! `psi`, and every joint gets a *shear slide* `t_j`
//! across segment `j`, so the joint offset becomes `d_j = L_j e_j + t_j n_j`; small-angle,
//! `t_j ~ gamma l`, and the spring `k_s = kappa G A / l` (`1 / int ds / (G A_s)` over the length
//! the joint stands for) stores `kappa G A gamma^2 l / 2`, the shear energy of that length.
//! The section's rotary inertia `int rho I ds` is added to each segment's inertia.
//!
//! Shear force is largest at pinned ends, so the half segment between each pin and its
//! segment's middle needs its shear compliance too: the pins sit across *end slides*,
//! `B = S_0 - t_B n_0` and `C = S_{N-1} + l e_{N-1} + t_C n_{N-1}` (`S_k` the start of segment
//! `k`; `(q_0, q_1) = S_0`), with springs `1 / int ds / (G A_s)` over the half segments. Without
//! them the error in the frequencies is first order in `l` (a third of a percent in mode 1 of
//! the automotive rod at 32 segments); with them second order, e.g. 1.4e-5 (tests/segments.rs,
//! `pinned_pinned_timoshenko_convergence`, against the closed form). Coordinates:
//! `t_B, t_0 .. t_{N-2}, t_C` after the axial slides (`N + 1`). The end slides carry no mass;
//! the pin constraints fix them (`t_B` moves `S_0` across the crank pin), so the mechanism's
//! saddle-point system stays regular. For even `N` the midpoint (a joint) is halfway across the
//! joint's slides (`SegmentRod::locate`).
//!
//! With all offsets generalized, the mass matrix reads `M_{B theta_j} = H_j = f_j n_j + a_j
//! perp(d_j)`, `M_{theta_j theta_j} = J_j + a_j |d_j|^2`, `M_{theta_i theta_j} = perp(d_i) . H_j`
//! (`i < j`), and for a slide of joint `j` along `u` (`e_j` axial, `n_j` shear)
//! `M_{B u} = a_j u`, `M_{theta_i u} = a_j perp(d_i) . u` (`i <= j`), `H_i . u` (`i > j`),
//! `M_{u w} = a_{max(i, j)} u . w`; `perp(d) = L n - t e = d d / d theta`. The velocity-product
//! term of joint `j` is `b_j = 2 theta_j' (s_j' n_j - t_j' e_j) - theta_j'^2 d_j`. Without shear
//! these are the expressions above (`t = 0`).
//!
//! # End bodies (`[rod.big_end]`, `[rod.small_end]`)
//! Point masses at the pins B and C (`m J_P^T J_P` in the mass matrix, `-m J_P^T (J_P' q')` in
//! the forces, through the pins' Jacobians, end slides included), and each inertia `J` on a
//! rotation coordinate of its own, `phi_B` or `phi_C`, joined to the end segment by a rotational
//! spring over the half segment next to the pin, `1 / int ds / (E I)` (stiffness-proportional
//! damper). A body lumped into the end segment would turn with the segment's middle, not with
//! the section at the pin, and push its inertia force through the half segment's shear and
//! bending springs instead of straight into the pin: errors first order in `l` (1.6 % in `v_mid`
//! of the automotive rod at 32 segments, against 0.2 % with the rotation coordinates). Coordinates after the shear slides:
//! `phi_B` if the big end has an inertia, then `phi_C` if the small end has one.
//!
//! Geometric exactness: the segments move rigidly with the exact kinematics, so the axial
//! force in the chain (carried by the joints) acts on bending by itself: [`RodBody::forces`]
//! ignores its `a` and `end_force_c` arguments.
//!
//! No allocation in the per-iteration methods: everything is precomputed in [`SegmentRod::new`]
//! and the loops recompute `cos`/`sin` of the angles on the fly.

pub mod dynamics;
pub mod kinematics;
pub mod linear;
pub mod modal;
mod modal_direct_evaluation;
pub mod rod;

pub use linear::axial_chain_frequencies_hz;
pub use modal::ModalSegmentRod;
pub use rod::SegmentRod;

use crate::error::ModelError;

/// Smallest and largest number of segments (`rod.elements`) the segment rod accepts. One
/// segment is the rigid rod: no joint, no natural frequency (an FMU that declares
/// `rod.frequency[k]` refuses it at initialization; [`least_segments`] gives the count that
/// leaves `K` frequencies). The largest is the FFR mesh's too (one declared range for
/// `rod.elements`); tests/abuse.rs builds and runs it (docs/robustness.md, "Limits").
pub const SEGMENT_RANGE: (usize, usize) = (1, 128);

/// The least number of segments whose uniform chain (no shear slides, no end bodies, which add
/// modes) has at least `frequencies` pinned-pinned natural frequencies: `N - 1` bending ones,
/// and with axial springs `N - 2` axial ones more (from 3 segments). For the six frequencies of
/// the default scene: 7, or 5 with axial springs.
pub fn least_segments(frequencies: usize, axial_springs: bool) -> usize {
    let count = |n: usize| {
        let axial = if axial_springs && n >= 3 { n - 2 } else { 0 };
        n - 1 + axial
    };
    (SEGMENT_RANGE.0..)
        .find(|&n| count(n) >= frequencies)
        .unwrap_or(SEGMENT_RANGE.0)
}

/// Check the number of segments `n` (`rod.elements`) against [`SEGMENT_RANGE`].
pub fn validate_segments(n: usize) -> Result<(), ModelError> {
    let (lo, hi) = SEGMENT_RANGE;
    if (lo..=hi).contains(&n) {
        Ok(())
    } else {
        Err(ModelError::InvalidInteger {
            name: "rod.elements",
            value: n as i64,
            allowed: format!("{lo}..={hi} rigid segments (rod.model = \"segments\")"),
        })
    }
}
