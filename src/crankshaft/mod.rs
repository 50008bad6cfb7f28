//! The crankshaft and flywheel: a second model exported by the same FMI shell as the rod
//! (its own FMU from `scenes/crankshaft.toml`), for the engine's co-simulation loop. The
//! crankshaft turns the rod's crank: its outputs `crank.angle`, `crank.speed`,
//! `crank.acceleration` feed the rod FMU's crank inputs, and the rod FMU's `crank.torque` (the
//! torque the crank needs) comes back as `load.torque`.
//!
//! One rigid body turning about the crank axis (Newton-Euler for a fixed axis):
//!
//! ```text
//! J dw/dt = T(t) - c w,   dtheta/dt = w,   T(t) = T_drive(t) - T_load(t)
//! ```
//!
//! with J the rotary inertia of crankshaft and flywheel (kg m^2), c a viscous loss
//! coefficient (N m s/rad), T_drive the torque the engine or motor applies and T_load the
//! torque the load takes (N m). Over a communication step the torques are linear in time
//! (their values and, with input derivatives, their first derivatives at the communication
//! point; held constant otherwise), and the step is integrated exactly ([`motion`]).
//!
//! - [`scene`]: the scene file (`[crankshaft]`, `[experiment]`) and its ranges;
//! - [`motion`]: the exact solution over a step, with the phi functions;
//! - [`model`]: the model as a co-simulation model: variables, hooks, saved states.

pub mod model;
pub mod motion;
pub mod scene;

pub use model::CrankshaftModel;
pub use scene::CrankshaftScene;
