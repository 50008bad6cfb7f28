//! Helpers shared by the integration tests (each test file includes them with `mod common;`).
//!
//! - [`runs`]: driving a scene through `flexrod::drive` and measuring a run (peaks, pointwise
//!   differences), including runs that may end in a failed step;
//! - [`exudyn`]: the geometrically exact reference, `tests/data/exudyn_ancf_150rad_s.csv`;
//! - [`seeds`]: the frequency tables of seeds 000 and 001;
//! - [`generated`]: README fragments written by the tests that measure their numbers
//!   (`docs/generated/<id>.md`, checked by [`generated::check_generated`]).

// Not every test file uses every helper.
#![allow(dead_code)]

pub mod exudyn;
pub mod generated;
pub mod runs;
pub mod seeds;

#[allow(unused_imports)]
pub use generated::check_generated;
