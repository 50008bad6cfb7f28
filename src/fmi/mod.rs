//! FMI 2.0 and FMI 3.0 Co-Simulation layer: the FMU's C ABI, a generic shell over any
//! co-simulation model ([`crate::cosimulation::CoSimulationModel`]). Its files use only the
//! contract `cosimulation` and the utilities `bytes`, `error`, `hash`, `limits` and `text`; one
//! file, [`registry`], names the models this library exports (the rod, the crankshaft) and
//! instantiates them (checked by `tests/layers.rs`). The models know nothing of FMI.
//!
//! Both standards share everything but the C shells (`ffi/` for FMI 2.0, `ffi/fmi3/` for
//! FMI 3.0) and the XML writers: one instance code, one state machine, parameterized by
//! [`Standard`]; [`Standard::interface`] tells a model what the standard offers (FMI 3.0's
//! `time`, arrays, no input derivatives, the status names in descriptions).
//!
//! One call, top to bottom (e.g. `fmi2DoStep` or `fmi3DoStep`):
//! 1. [`ffi`] (`ffi/`, the only module with `unsafe`): the exported `extern "C"` symbol
//!    checks and converts the C arguments and calls one method through [`Instance::run`];
//! 2. [`instance`]: `run` checks the call against the state machine ([`state_machine`]),
//!    catches panics ([`guard`]), and the method checks what FMI defines (the communication
//!    point, the step size, the stop time), returning `Result<Status, FmiError>`; failures
//!    reach the importer's logger ([`logging`]) with the offending value and range;
//! 3. the model's hooks (`step`, `get_real`, `set_real`, `save`, ...), which answer with texts
//!    and step outcomes (done, refused, discarded with a remedy, failed) that the instance turns
//!    into statuses.
//!
//! The model's declarations drive the get/set dispatch, `modelDescription.xml`
//! ([`description`]) and its GUID. At instantiation the library reads `resources/scene.toml`
//! ([`resource`]), builds the model it describes ([`registry`]) and its description, and
//! accepts the importer's GUID (FMI 3.0: `instantiationToken`) only if it matches. Saved FMU
//! states: `fmu_state`, the shell's header around the model's own bytes.

pub mod description;
pub mod experiment;
#[allow(unsafe_code)]
pub mod ffi;
mod fmu_state;
mod guard;
pub mod instance;
pub mod logging;
pub mod registry;
pub mod resource;
pub mod standard;
pub mod state_machine;
pub mod status;
pub mod variables;

pub use description::ModelDescription;
pub use instance::Instance;
pub use standard::Standard;
pub use status::{FmiError, Status};
