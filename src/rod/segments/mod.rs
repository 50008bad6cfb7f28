//! The finite segment rod (seed 002, `002_e6c2c81d944c25fc.txt`; docs/physics.md,
//! "Rod model 2: finite segments"): `N` rigid segments joined by revolute joints with
//! rotational springs and dampers, optionally with prismatic joints carrying axial springs.
//!
//! - [`rod`]: the body ([`SegmentRod`]): coordinates, mass matrix, quadratic velocity vector,
//!   joint forces, points, energies (the derivation is in its module documentation);
//! - [`linear`]: the chain linearized about the straight configuration: pinned-pinned
//!   bending and axial frequencies, and the free-free axial chain of seed 002's convergence
//!   table ([`axial_chain_frequencies_hz`]).

pub mod body;
pub mod kinematics;
pub mod linear;
pub mod rod;

pub use linear::axial_chain_frequencies_hz;
pub use rod::SegmentRod;

use crate::error::ModelError;

/// Smallest and largest number of segments (`rod.elements`) the segment rod accepts
/// (issue 14: the chain failed from 130 segments; 128 run the benchmark, `tests/abuse.rs`).
pub const SEGMENT_RANGE: (usize, usize) = (1, 128);

/// Check the number of segments `n` (`rod.elements`) against [`SEGMENT_RANGE`].
pub fn validate_segments(n: usize) -> Result<(), ModelError> {
    let (lo, hi) = SEGMENT_RANGE;
    if (lo..=hi).contains(&n) {
        Ok(())
    } else {
        Err(ModelError::InvalidParameter {
            name: "rod.elements",
            value: n as f64,
            allowed: format!("{lo}..={hi} rigid segments (rod.model = \"segments\")"),
        })
    }
}
