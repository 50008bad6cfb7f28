//! A flexible connecting rod in a planar slider-crank, for export as an FMI 2.0
//! Co-Simulation FMU.
//!
//! Layers, bottom up (each folder one concept):
//! - [`beam`]: planar Euler-Bernoulli beam element and the assembly of a straight rod;
//! - [`modal`]: reference conditions, the eigenproblem, mode selection, inertia shape integrals;
//! - [`ffr`]: the floating-frame-of-reference rod body built on the modes;
//! - [`segments`]: the finite segment rod (seed 002);
//! - [`mechanism`]: the slider-crank (prescribed crank, pins, slider), outputs;
//! - [`integrator`]: generalized-alpha for index-3 DAEs;
//! - [`simulation`]: the facade the tools and the FMI layer use;
//! - [`fmi`]: the FMI 2.0 C ABI (the only place with `unsafe`).
//!
//! Physics: `../shared/design/physics.md`; sources: the seeds in `../shared/seeds/`.

// Index loops are the natural notation for the matrix formulas of the papers.
#![allow(clippy::needless_range_loop)]
// `unsafe` lives in one file, the C boundary (`fmi/ffi.rs`, allowed there alone).
#![deny(unsafe_code)]

pub mod beam;
pub mod drive;
pub mod error;
pub mod fmi;
pub mod hash;
pub mod integrator;
pub mod mechanism;
pub mod modal;
pub mod rod;
pub mod scene;
pub mod simulation;

pub use error::ModelError;
pub use mechanism::Outputs;
pub use scene::Scene;
pub use simulation::{CrankInput, Simulation, Snapshot, StepStats};
