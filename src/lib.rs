//! A flexible connecting rod in a planar slider-crank, for export as an FMI 2.0
//! Co-Simulation FMU.
//!
//! Layers, bottom up; each uses only the layers below it (checked by `tests/layers.rs`):
//! 0. [`error`], [`hash`]: typed errors; FNV hashes;
//! 1. [`beam`]: the planar Euler-Bernoulli element and the straight rod's mesh;
//!    [`integrator`]: one-step methods (generalized-alpha, RK4) on any [`integrator::DaeSystem`];
//! 2. [`modal`]: reference conditions, the eigenproblem, mode selection, shape integrals;
//! 3. [`rod`]: the [`rod::RodBody`] trait, the FFR rod on component modes, the segment chain;
//! 4. [`mechanism`]: the slider-crank DAE (prescribed crank, pins, slider), its start,
//!    stepping and outputs;
//! 5. [`scene`]: the TOML scene, composed of each layer's own spec types;
//! 6. [`simulation`]: the facade: a mechanism built from a scene, its state and snapshots;
//! 7. [`drive`]: crank laws and the run loop; [`fmi`]: the FMI 2.0 C ABI (the only place with
//!    `unsafe`).
//!
//! Physics and equations: `docs/physics.md`; the FMU's contract: `docs/fmu.md`. The source
//! papers are cited by file name (`000_c3718bcf5d527da5.txt`, `001_300b657b5809bf4a.txt`,
//! `002_e6c2c81d944c25fc.txt`); `docs/physics.md` lists them.

// Index loops are the natural notation for the matrix formulas of the papers.
#![allow(clippy::needless_range_loop)]
// `unsafe` lives in one module, the C boundary (`fmi/ffi/`, allowed there alone).
#![deny(unsafe_code)]

pub mod beam;
pub mod drive;
pub mod error;
pub mod fmi;
pub mod hash;
pub mod integrator;
pub mod mechanism;
pub mod modal;
pub mod model;
pub mod rod;
pub mod scene;
pub mod simulation;
pub mod trig;

pub use error::ModelError;
pub use mechanism::Outputs;
pub use scene::Scene;
pub use simulation::{CrankInput, Simulation, Snapshot, StepStats};
