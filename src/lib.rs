//! A flexible connecting rod in a planar slider-crank, for export as an FMI 2.0 and FMI 3.0
//! Co-Simulation FMU.
//!
//! Layers, bottom up; each uses only the layers below it (checked by `tests/layers.rs`):
//! 0. [`error`], [`hash`], [`trig`]: typed errors; FNV hashes; `sin_cos` of the hot path;
//! 1. [`beam`]: the planar Euler-Bernoulli element and the straight rod's mesh;
//!    [`integrator`]: one-step methods (generalized-alpha, fixed-step RK4, the adaptive explicit
//!    Runge-Kutta pairs Dormand-Prince 5(4) and RK4(3), ETDRK4) on any [`integrator::DaeSystem`];
//! 2. [`modal`]: reference conditions, the eigenproblem, mode selection, shape integrals;
//! 3. [`rod`]: the [`rod::RodBody`] trait, the FFR rod on component modes, the segment chain;
//! 4. [`mechanism`]: the slider-crank DAE (prescribed crank, pins, slider), its start,
//!    stepping and outputs;
//! 5. [`scene`]: the TOML scene, composed of each layer's own spec types;
//! 6. [`simulation`]: the facade: a mechanism built from a scene, its state and snapshots;
//! 7. [`drive`]: crank laws and the run loop; [`model`]: the rod's model as a co-simulation
//!    model (the variable table, the crank input law between communication points, the hooks
//!    with their validity checks, its saved state), knowing nothing of FMI; [`crankshaft`]: the
//!    crankshaft and flywheel, a second co-simulation model;
//! 8. [`fmi`]: the FMI 2.0 / FMI 3.0 C ABI, a generic shell over any
//!    [`cosimulation::CoSimulationModel`] (the only place with `unsafe`).
//!
//! Below them: [`cosimulation`], the contract between a model and an interface (declarations,
//! hooks, step outcomes); [`bytes`], the byte forms of saved states.
//!
//! Physics and equations: `docs/physics.md`; the FMU's contract: `docs/fmu.md`. The sources,
//! listed in `docs/physics.md`: O. P. Agrawal and A. A. Shabana, "Dynamic analysis of
//! multibody systems using component modes", Computers & Structures 21(6), 1985; J. O'Shea
//! (Computational Dynamics Inc.), "CDI Parametric Study: Analysis of the Small-Deformation
//! Connecting Rod: Slider Crank Mechanism"; R. L. Huston, "Computer methods in flexible
//! multibody dynamics", IJNME 32, 1991.

// Index loops are the natural notation for the matrix formulas of the papers.
#![allow(clippy::needless_range_loop)]
// `unsafe` lives in one module, the C boundary (`fmi/ffi/`, allowed there alone).
#![deny(unsafe_code)]

pub mod beam;
pub mod bytes;
pub mod cosimulation;
pub mod crankshaft;
pub mod drive;
pub mod error;
pub mod fmi;
pub mod hash;
pub mod integrator;
pub mod limits;
pub mod mechanism;
pub mod modal;
pub mod model;
pub mod rod;
pub mod scene;
pub mod simulation;
pub mod text;
pub mod trig;

pub use error::ModelError;
pub use mechanism::Outputs;
pub use scene::Scene;
pub use simulation::{CrankInput, Simulation, Snapshot, StepStats};
