//! The variables that depend on the [`Interface`] (identifiers 150..199):
//!
//! - `time` (150, `independent`), with an independent variable;
//! - `crank.acceleration` (151, input, rad/s2), without input derivatives: the crank
//!   acceleration `alpha_k` of the input law, which an interface with input derivatives takes
//!   as the order-1 derivative of `crank.speed`, is an ordinary input here, with the same law
//!   between communication points (see [`crate::model::inputs`]);
//! - `crank.jerk` (154, input, rad/s3), without input derivatives: the crank jerk `j_k` of the
//!   input law (the order-2 derivative of `crank.speed` with input derivatives), the same way;
//! - `rod.shape` (152, output array of N = `[outputs] shape_points`), with arrays: the
//!   transverse deflection from the chord B -> C, m, at `s_i = i L / (N - 1)`, i = 0..N-1 (the
//!   same definition as `rod.deflection`, which is element `(N - 1) / 2` for odd N);
//! - `rod.frequency` (153, calculated parameter array of K), with arrays: the natural
//!   frequencies, Hz, the values declared as the scalars `rod.frequency[k]` without arrays
//!   (the element names of the array are the same: `rod.frequency[k]`, k = 1..K).

use super::builder::{real, Builder};
use super::types::{Access, InputSlot};
use super::Interface;
use crate::cosimulation::InitialDependencies;
use crate::error::ModelError;
use crate::scene::Scene;

/// Largest `[outputs] shape_points`.
pub const SHAPE_POINTS_MAX: usize = 1001;

/// `[outputs] shape_points` is 0 (no `rod.shape`) or 2..=[`SHAPE_POINTS_MAX`].
pub(super) fn check_shape_points(scene: &Scene) -> Result<(), ModelError> {
    let n = scene.outputs.shape_points;
    if n == 1 || n > SHAPE_POINTS_MAX {
        return Err(ModelError::State {
            message: format!(
                "[outputs] shape_points = {n} is out of range: allowed 0 (no rod.shape output) or 2..={SHAPE_POINTS_MAX} (points from B to C)"
            ),
        });
    }
    Ok(())
}

/// Append the variables `interface` calls for; `frequency_knowns` are the parameters the
/// frequencies depend on.
pub(super) fn add_variables(
    b: &mut Builder<'_>,
    interface: Interface,
    n_frequencies: usize,
    frequency_knowns: &'static [&'static str],
) {
    if interface.independent_variable {
        b.independent("time", 150, "Simulation time");
    }
    if !interface.input_derivatives {
        b.describe(
            "crank.speed",
            "Crank speed omega at the communication point (the crank acceleration and jerk are the inputs crank.acceleration and crank.jerk)",
        );
        b.input(
            "crank.acceleration",
            151,
            real("rad/s2"),
            0.0,
            InputSlot::CrankAcceleration,
            &format!(
                "Crank acceleration alpha of the input law from the communication point on ({} has no input derivatives): theta = theta_k + omega_k s + alpha s^2/2 + j s^3/6, omega = omega_k + alpha s + j s^2/2",
                interface.name
            ),
        );
        b.input(
            "crank.jerk",
            154,
            real("rad/s3"),
            0.0,
            InputSlot::CrankJerk,
            "Crank jerk j of the input law from the communication point on (see crank.acceleration)",
        );
    }
    if !interface.arrays {
        return;
    }
    let n_points = b.scene.outputs.shape_points;
    if n_points >= 2 {
        b.output(
            "rod.shape",
            152,
            real("m"),
            |o| o.deflection,
            InitialDependencies::None,
            "Transverse deflection from the chord B->C at s_i = i L/(N-1), i = 0..N-1, positive to the left of B->C",
        );
        b.set_access(Access::Shape);
        b.array(n_points);
    }
    if n_frequencies > 0 {
        b.calculated_parameter(
            "rod.frequency".into(),
            153,
            real("Hz"),
            Access::Frequencies,
            InitialDependencies::Named(frequency_knowns),
            "Natural frequencies of the rod under its reference conditions (retained or not), ascending".into(),
        );
        b.array(n_frequencies);
    }
}
