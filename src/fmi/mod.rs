//! FMI 2.0 and FMI 3.0 Co-Simulation layer: the FMU's C ABI, a generic shell over the
//! model's self-description ([`crate::model`]). It knows nothing of the mechanism (it uses
//! only `model`, `error` and `hash`, checked by `tests/layers.rs`), and the model knows nothing
//! of FMI: no FMI type, status or function name crosses into it.
//!
//! Both standards share everything but the C shells (`ffi/` for FMI 2.0, `ffi/fmi3/` for
//! FMI 3.0) and the XML writers: one instance code, one state machine and one variable table
//! (the model's), parameterized by [`Standard`]. What differs between the standards is said
//! here, generically: [`Standard::interface`] tells the model's table what the standard offers
//! (FMI 3.0's `time`, arrays, the inputs `crank.acceleration` and `crank.jerk` instead of input derivatives, and
//! the status names in descriptions); function names, type families, `instantiationToken`
//! for GUID and the XML are this layer's.
//!
//! One call, top to bottom (e.g. `fmi2DoStep` or `fmi3DoStep`):
//! 1. [`ffi`] (`ffi/`, the only module with `unsafe`): the exported `extern "C"` symbol
//!    checks and converts the C arguments and calls one method through [`Instance::run`];
//! 2. [`instance`]: `run` checks the call against the state machine ([`state_machine`], a
//!    table of allowed states per function), catches panics ([`guard`]), and the method
//!    (`Instance::do_step`, in `instance/stepping.rs`) checks what FMI defines (the
//!    communication point, the step size, the stop time) in safe Rust, returning
//!    `Result<Status, FmiError>`; failures reach the importer's logger ([`logging`]) with the
//!    offending value and range, named in the standard's terms;
//! 3. the model's hooks: [`crate::model::Model`] (`check_step`, `step`: the input law that
//!    starts at the communication point, the integration, the law's values read back; `get_real`,
//!    `set_real`, `ensure_started`, `save`, `restore`), which report
//!    [`crate::error::ModelError`]s; the instance turns them into statuses (a failed
//!    integration step or a step refused by the deflection policy is `Discard`, a refused input
//!    `Error` with the instance usable, ...);
//! 4. below the model: the simulation facade and the mechanism, which this layer never names.
//!
//! One source of truth: the model's [`VariableTable`] drives the get/set dispatch,
//! `modelDescription.xml` ([`description`]) and its GUID. At instantiation the library reads
//! `resources/scene.toml` ([`resource`]), rebuilds the table and the description, and accepts
//! the importer's GUID (FMI 3.0: `instantiationToken`) only if it matches. Saved FMU states
//! and their byte form: `fmu_state` (the model's part is the model's [`crate::model::SavedModel`]).

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
