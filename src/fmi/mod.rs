//! FMI 2.0 and FMI 3.0 Co-Simulation layer: the FMU's C ABI around [`crate::Simulation`].
//!
//! Both standards share everything but the C shells (`ffi/` for FMI 2.0, `ffi/fmi3/` for
//! FMI 3.0) and the XML writers: one instance code, one state machine and one variable table,
//! parameterized by [`Standard`].
//!
//! One call, top to bottom (e.g. `fmi2DoStep`):
//! 1. [`ffi`] (`ffi/`, the only module with `unsafe`): the exported `extern "C"` symbol
//!    checks and converts the C arguments and calls one method through [`Instance::run`];
//! 2. [`instance`]: `run` checks the call against the state machine ([`state_machine`], a
//!    table of allowed states per function), catches panics ([`guard`]), and the method
//!    (`Instance::do_step`, in `instance/stepping.rs`) does the work in safe Rust,
//!    returning `Result<Status, FmiError>`;
//!    failures reach the importer's logger ([`logging`]) with the offending value and range;
//! 3. the core: [`crate::Simulation`] (`set_input`, `advance`, `outputs`, `snapshot`).
//!
//! One source of truth: [`variables::VariableTable`] (built from a [`crate::Scene`]) drives
//! the get/set dispatch, `modelDescription.xml` ([`description`]) and its GUID. At
//! `fmi2Instantiate` the library reads `resources/scene.toml` ([`resource`]), rebuilds the
//! table and the description, and accepts the importer's GUID only if it matches.
//! The inputs and their law between communication points: [`inputs`]; saved states and
//! their byte form: `fmu_state`.

pub mod description;
pub mod experiment;
#[allow(unsafe_code)]
pub mod ffi;
mod fmu_state;
mod guard;
pub mod instance;
pub mod logging;
pub mod resource;
pub mod standard;
pub mod state_machine;
pub mod status;
pub mod variables;

pub use description::ModelDescription;
pub use instance::Instance;
pub use standard::Standard;
pub use status::{FmiError, Status};
pub use variables::VariableTable;
