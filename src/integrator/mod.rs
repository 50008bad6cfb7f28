//! One-step integrators for the constrained equations of motion
//! `M(q) q'' + Phi_q^T lambda = Q(t, q, q')`, `Phi(q, t) = 0` ([`DaeSystem`]):
//!
//! - [`GeneralizedAlpha`]: implicit, on the index-3 form (Arnold and Bruls 2007, "Convergence
//!   of the generalized-alpha scheme for constrained mechanical systems", Multibody System
//!   Dynamics 18), with the scaled Newton iteration of Bottasso, Dopico and Trainelli (2008);
//! - [`ExplicitRk4`]: classic Runge-Kutta on the index-1 form with coordinate projection;
//! - [`ConstrainedSolve`]: the saddle-point solve both use, and the joint-force solve of the
//!   outputs: accelerations and multipliers, projections on the constraints;
//! - [`DenseLu`]: the dense factorization behind it, on buffers sized once.
//!
//! Both integrators implement [`Integrator`], which is all the stepping driver sees.

pub mod constrained;
pub mod dense_lu;
pub mod failure;
pub mod generalized_alpha;
pub mod runge_kutta;
pub mod state;
pub mod system;

pub use constrained::ConstrainedSolve;
pub use dense_lu::DenseLu;
pub use failure::{StepError, StepFailure};
pub use generalized_alpha::GeneralizedAlpha;
pub use runge_kutta::ExplicitRk4;
pub use state::DaeState;
pub use system::DaeSystem;

/// A one-step method for a [`DaeSystem`].
pub trait Integrator: Send {
    /// Advance `state` from `state.t` by `h`. On success returns the work done (Newton
    /// iterations or matrix factorizations, see [`Integrator::work_unit`]) and overwrites
    /// `state`; on failure `state` is untouched and the error says why and what it cost.
    fn step(
        &mut self,
        system: &dyn DaeSystem,
        state: &mut DaeState,
        h: f64,
    ) -> Result<usize, StepError>;

    /// Forget anything kept between steps (a reused factorization), so that the next step
    /// depends on the state alone (a restored state then replays bit for bit).
    fn forget_between_steps(&mut self) {}

    /// The method's name, for run summaries.
    fn name(&self) -> &'static str;

    /// What the work counter of [`Integrator::step`] counts.
    fn work_unit(&self) -> &'static str;
}
