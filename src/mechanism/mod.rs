//! The planar slider-crank with a flexible rod (physics.md, "The mechanism", "Joints,
//! constraints, reaction forces", "Output definitions").

pub mod crank;
pub mod dae;
pub mod outputs;
pub mod rod_body;
pub mod slider_crank;
pub mod state;

pub use outputs::Outputs;
pub use rod_body::{RodBody, RodPoint};
pub use slider_crank::Mechanism;
pub use state::MechanismState;
