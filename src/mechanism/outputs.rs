//! The outputs of the slider-crank (physics.md, "Output definitions and sign conventions").

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
}
