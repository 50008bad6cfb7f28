//! Implicit integration of the index-3 DAE `M(q) q'' + Phi_q^T lambda = Q(t, q, q', q'', lambda)`,
//! `Phi(q, t) = 0` by the generalized-alpha method of Arnold and Bruls (2007), "Convergence of
//! the generalized-alpha scheme for constrained mechanical systems", Multibody System Dynamics
//! 18, with the scaled Newton iteration of Bottasso, Dopico and Trainelli (2008).

pub mod dense_lu;
pub mod generalized_alpha;
pub mod runge_kutta;
pub mod system;

pub use generalized_alpha::{GeneralizedAlpha, StepFailure};
pub use runge_kutta::ExplicitRk4;
pub use system::DaeSystem;
