//! Residual flexibility of the FFR rod: the bending modes left out of the dynamics (above the
//! retained band, `rod.mode_band_hz`) respond quasi-statically to the loads the motion puts on
//! them, and their static response is added to the midpoint deflection output (the
//! mode-acceleration method: Craig and Kurdila, *Fundamentals of Structural Dynamics*, 2nd ed.,
//! 2006, section 11.5; for component modes, residual flexibility / residual attachment modes,
//! ibid. section 18.4, and R. R. Craig and M. C. C. Bampton, "Coupling of substructures for
//! dynamic analyses", AIAA Journal 6(7), 1968).
//!
//! Left-out mode h (unit modal mass, frequency `w_h`) of the rod's equations (Agrawal and
//! Shabana 1985, eq. 3.17-3.18, 6.2; [`super::rod`]) without its own inertia and damping:
//! `w_h^2 p_h = I2_h . A^T (g - R'') - (I_rot,h - I5_h) phi''`, the frame's acceleration and
//! gravity loading the mode through its transverse inertia integral `I2_h` and the frame's
//! angular acceleration through `M_phi,h = -I5_h + I_rot,h`. Left out as small: the terms in the
//! retained modes' coordinates and rates (`phi'^2 M_uu p`, `2 phi' S~ p'`, of relative size
//! `phi'^2 / w_h^2` and `2 phi' w_k / w_h^2`, below 1e-3 on the automotive rod at 6000 rpm) and
//! the couplings `M_ff,hk` (zero: the left-out modes taken are bending modes, which leave the
//! pins in place and so are orthogonal to the retained ones in the rod's own mass too).
//! Only the left-out modes that leave the pins in place enter (bending modes of the pinned
//! rod): their deflection is transverse to the chord, `v_mid += S_mid,y,h p_h`.

use nalgebra::Vector2;

use super::fixed_size_integrals::PINNED_MOBILITY;
use crate::modal::{ComponentModes, ShapeIntegrals};

/// One left-out mode's data.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ResidualMode {
    /// `w_h^2`, (rad/s)^2.
    pub omega2: f64,
    /// `I2_h` (body frame x, y), kg m^(1/2) at unit modal mass.
    pub i2: [f64; 2],
    /// `M_phi,h = -I5_h + I_rot,h`.
    pub m_phi: f64,
    /// Body-frame transverse displacement of the midpoint per unit `p_h`.
    pub s_mid_y: f64,
}

/// The left-out bending modes of `all` (every mode of the rod, in the basis the retained ones
/// come from) that are not among `retained` (indices into `all.all_frequencies_hz`).
pub fn residual_modes(all: &ComponentModes, retained: &[usize]) -> Vec<ResidualMode> {
    let ig = ShapeIntegrals::first_order(all);
    residual_columns(all, &ig, retained)
        .map(|j| ResidualMode {
            omega2: all.omega2[j],
            i2: [ig.i2[(0, j)], ig.i2[(1, j)]],
            m_phi: -ig.i5[j] + ig.i_rot[j],
            s_mid_y: ig.s_mid[(1, j)],
        })
        .collect()
}

/// The columns of `all` that are static corrections: left out of `retained`, bending, and
/// leaving the pins in place.
fn residual_columns<'a>(
    all: &'a ComponentModes,
    ig: &'a ShapeIntegrals,
    retained: &'a [usize],
) -> impl Iterator<Item = usize> + 'a {
    let scale = ig.mass.sqrt();
    (0..all.n_modes()).filter(move |&j| {
        let k = all.retained[j];
        let pins = [
            ig.s_b[(0, j)],
            ig.s_b[(1, j)],
            ig.s_c[(0, j)],
            ig.s_c[(1, j)],
        ]
        .iter()
        .fold(0.0f64, |a, x| a.max(x.abs()));
        !retained.contains(&k) && !all.is_axial(k) && pins * scale <= PINNED_MOBILITY
    })
}

/// The modes [`residual_modes`] takes as static corrections, as indices into
/// `all.all_frequencies_hz` (what `flexrod modes` lists).
pub fn residual_indices(all: &ComponentModes, retained: &[usize]) -> Vec<usize> {
    let ig = ShapeIntegrals::first_order(all);
    residual_columns(all, &ig, retained)
        .map(|j| all.retained[j])
        .collect()
}

/// The left-out modes' quasi-static midpoint deflection, m, at frame angle `phi` (rad), frame
/// acceleration `r_dd` (global, m/s^2), angular acceleration `phi_dd` (rad/s^2) and gravity `g`.
pub fn residual_deflection(
    modes: &[ResidualMode],
    phi: f64,
    r_dd: Vector2<f64>,
    phi_dd: f64,
    g: Vector2<f64>,
) -> f64 {
    if modes.is_empty() {
        return 0.0;
    }
    let (s, c) = phi.sin_cos();
    let a = g - r_dd;
    let body = [c * a.x + s * a.y, -s * a.x + c * a.y];
    modes
        .iter()
        .map(|m| {
            let f = m.i2[0] * body[0] + m.i2[1] * body[1] - m.m_phi * phi_dd;
            m.s_mid_y * f / m.omega2
        })
        .sum()
}
