//! Driving a [`Simulation`] the way an importer does: a crank law sampled at communication
//! points, one `advance` per communication step, outputs recorded at each point.
//!
//! - [`law`]: the crank motions ([`CrankDrive`]: constant speed, uniform acceleration, a smooth
//!   start ramp, a table of time, angle and speed);
//! - [`run`]: the run loop ([`run`], [`run_constant`]) and what it records ([`Record`]).
//!
//! The packager's `--simulate`, the command-line tool, the report, the benchmarks and the
//! tests all drive the model through this module.

pub mod engine;
pub mod law;
pub mod run;

pub use law::CrankDrive;
pub use run::{communication_grid, run, run_constant, Record};
