//! The floating frame of reference rod: rigid frame `(R, phi)` plus modal coordinates `p`
//! (seed 000, sections 4-5; docs/physics.md, "Rod model 1").

pub mod kernel;
pub mod points;
pub mod rod;
pub mod sections;
pub mod stiffening;

pub use kernel::{FfrKernel, MAX_MODES};
pub use rod::FfrRod;
