//! The model's self-description, for an interface layer that knows nothing of the mechanism
//! (the FMU's C ABI, `fmi`), while the model knows nothing of the interface.
//!
//! - [`variables`]: the variable table, the one source of truth for the variables (name,
//!   causality, variability, unit, start, bounds, description, and where the value lives:
//!   accessors on the simulation's outputs and on the scene), its enumeration types, and the
//!   [`Interface`] a table is declared for (arrays or scalars, input derivatives or an input
//!   of their own, an independent variable, the interface's words in descriptions);
//! - [`inputs`]: the crank input law between communication points,
//!   `theta_k + omega_k s + alpha_k s^2 / 2 + j_k s^3 / 6`, its state and its byte form;
//! - [`binding`]: a saved state's scene is this model's, with only declared parameters
//!   changed;
//! - [`instance`]: one model instance as an importer drives it ([`Model`]: parameters,
//!   inputs, the simulation built from them, its validity checks with messages naming the
//!   value and its allowed range, saved states).
//!
//! Everything here reports failures as [`crate::error::ModelError`] or as text; how an
//! interface turns them into statuses is its own concern.

pub mod binding;
mod cosimulation;
pub mod inputs;
pub mod instance;
mod saved_state;
pub mod variables;

pub use inputs::{AccelerationSource, Inputs};
pub use instance::{RodModel, SavedModel, StepError};
pub use variables::{Interface, VariableId, VariableTable};
