//! The floating frame of reference rod: rigid frame `(R, phi)` plus modal coordinates `p`
//! (O. P. Agrawal and A. A. Shabana, "Dynamic analysis of multibody systems using component
//! modes", Computers & Structures 21(6), 1985, sections 4-5; docs/physics.md, "Rod model 1").

pub mod fixed_size_integrals;
pub mod points;
pub mod residual;
pub mod rod;
pub mod sections;
pub mod stiffening;

pub use fixed_size_integrals::{rate_rows, stacked_rows, FfrKernel, Stacked, MAX_MODES};
pub use rod::FfrRod;
