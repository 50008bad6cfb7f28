//! The planar slider-crank with a flexible rod (docs/physics.md, "The mechanism", "Joints,
//! constraints, reaction forces", "Output definitions").

pub mod crank;
pub mod dae;
pub mod frame_coordinates_closed_form;
pub mod gas_force;
pub mod integrator_choice;
pub mod minimal;
pub mod outputs;
pub mod slider_crank;
pub mod spec;
pub mod start;
pub mod state;
pub mod stepping;

pub use crank::{CrankInput, CrankLaw};
pub use integrator_choice::{IntegratorChoice, MechanismFacts, AUTO_EXPLICIT_MIN_STEP};
pub use outputs::Outputs;
pub use slider_crank::{Mechanism, MechanismParts};
pub use spec::{MechanismSpec, DESIGN_SPEED_MAX};
pub use state::{MechanismState, StepStats};
pub use stepping::{LARGE_DEFLECTION_WARNING, MAX_INTERNAL_STEPS, MAX_OUTPUT_MAGNITUDE};
