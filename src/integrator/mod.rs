//! One-step integrators for the constrained equations of motion of a planar mechanism
//! ([`DaeSystem`]):
//!
//! `M(q) q'' + Phi_q(q)^T lambda = Q(t, q, q')`, `Phi(q, t) = 0`,
//!
//! with `n` coordinates `q`, `m` constraints and their multipliers `lambda`. Each integrator
//! implements [`Integrator`], which is all the stepping driver sees; which one a scene gets is
//! chosen from its solver settings by `mechanism::integrator_choice`, and the choice is passed
//! to the mechanism when it is built.
//!
//! - [`GeneralizedAlpha`] ([`generalized_alpha`]): implicit, on the index-3 form, fixed steps or
//!   adaptive ones. The method of Chung and Hulbert 1993 ("A time integration algorithm for
//!   structural dynamics with improved numerical dissipation: the generalized-alpha method",
//!   J. Appl. Mech. 60) in the DAE form of Arnold and Bruls 2007 ("Convergence of the
//!   generalized-alpha scheme for constrained mechanical systems", Multibody System Dynamics
//!   18), with the scaled Newton iteration of Bottasso, Dopico and Trainelli 2008 ("On the
//!   optimal scaling of index three DAEs in multibody dynamics", Multibody System Dynamics 19)
//!   and the error estimate of Zienkiewicz and Xie 1991 (Earthquake Eng. Struct. Dyn. 20).
//! - [`ExplicitRk4`] ([`runge_kutta`]): the classic fourth-order Runge-Kutta method, fixed
//!   steps, on the index-1 form with coordinate projection (Hairer and Wanner, *Solving ODEs
//!   II*, section VII.2; Eich-Soellner and Fuhrer, *Numerical Methods in Multibody Dynamics*,
//!   section 5.3).
//! - [`AdaptiveRungeKutta`] ([`adaptive_runge_kutta`]): explicit embedded Runge-Kutta pairs
//!   with error control on the independent coordinates of a partitioned system
//!   ([`PartitionedRhs`]: Wehage and Haug 1982, the mechanism's own degrees of freedom), one
//!   integrator parameterized by its [`Tableau`]:
//!   - [`DORMAND_PRINCE`], the 5(4) pair of Dormand and Prince 1980 ("A family of embedded
//!     Runge-Kutta formulae", J. Comput. Appl. Math. 6);
//!   - [`RK4_FSAL`], the classic RK4 (Kutta 1901) with an embedded third-order estimate.
//! - [`ExponentialRungeKutta`] ([`exponential_runge_kutta`]): ETDRK4 (Cox and Matthews 2002,
//!   "Exponential time differencing for stiff systems", J. Comput. Phys. 176, in the stages of
//!   Krogstad 2005) on the same independent coordinates with the modal oscillators taken
//!   exactly ([`exponential`]; Hochbruck and Ostermann 2010, "Exponential integrators", Acta
//!   Numerica 19), its embedded estimate that of the RK4(3) pair.
//!
//! Shared parts: [`step_control`], the step-size control, error norm and stage workspace of
//! the two error-controlled explicit integrators ([`ErrorControl`]); [`ConstrainedSolve`], the
//! saddle-point solve (accelerations and multipliers, projections on the constraints, the joint
//! forces of the outputs); [`DenseLu`] and [`SmallLu`], the dense factorizations behind it and
//! behind the partitioned evaluation, on buffers sized once; [`DaeState`] and [`StepAhead`],
//! the state and the held step of dense output.

pub mod adaptive_runge_kutta;
pub mod constrained;
pub mod dense_lu;
pub mod exponential;
pub mod exponential_runge_kutta;
pub mod failure;
pub mod generalized_alpha;
pub mod partitioned;
pub mod runge_kutta;
pub mod small_lu;
pub mod state;
pub mod step_control;
pub mod system;

pub use adaptive_runge_kutta::{AdaptiveRungeKutta, Tableau, DORMAND_PRINCE, RK4_FSAL};
pub use constrained::ConstrainedSolve;
pub use dense_lu::DenseLu;
pub use exponential_runge_kutta::ExponentialRungeKutta;
pub use failure::{StepError, StepFailure};
pub use generalized_alpha::GeneralizedAlpha;
pub use partitioned::PartitionedRhs;
pub use runge_kutta::ExplicitRk4;
pub use small_lu::SmallLu;
pub use state::{hermite5, DaeState, StepAhead};
pub use step_control::ErrorControl;
pub use system::{DaeSystem, GeneralPath};

/// Largest internal step the error-controlled integrators propose, s (a step may be stretched by
/// 25 % to land on the communication point). It makes the work of a communication step
/// bounded from below by `h / (1.25 MAX_ADAPTIVE_STEP)` steps, so a step beyond the work limit
/// is refused before it starts, and keeps the crank law's evaluations far from
/// overflow. At 300 rad/s it is 3 rad of crank: accuracy bounds the step long before it.
pub const MAX_ADAPTIVE_STEP: f64 = 1e-2;

/// A step size rounded down to the grid `2^(k/8)` (eight steps per octave): adaptive step
/// choices then do not follow round-off-level differences in the error estimate, so the same
/// run driven by different importers (communication points computed in other ways, Newton
/// iterations stopping one iteration apart) takes the same steps.
pub fn quantize_step(h: f64) -> f64 {
    // Zero, negative, non-finite and subnormal (below 2e-308 s: no step) sizes pass through.
    if !(h.is_finite() && h >= f64::MIN_POSITIVE) {
        return h;
    }
    // h = m 2^e with m in [1, 2) from the bits (no libm call on the stepping path); the
    // largest level 2^(j/8) <= m.
    const LEVELS: [f64; 8] = [
        1.0,
        1.090_507_732_665_257_7,
        1.189_207_115_002_721,
        1.296_839_554_651_009_6,
        std::f64::consts::SQRT_2,
        1.542_210_825_407_940_7,
        1.681_792_830_507_429,
        1.834_008_086_409_342_4,
    ];
    let bits = h.to_bits();
    let exponent = bits & (0x7ff << 52);
    let m = f64::from_bits((bits & !(0x7ff << 52)) | (0x3ff << 52));
    let j = LEVELS.iter().rposition(|&l| l <= m).unwrap_or(0);
    f64::from_bits(LEVELS[j].to_bits() - (0x3ff << 52) + exponent)
}

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

    /// The amplitude `A` of the motion the error control's accuracy refers to, for the next
    /// steps (dimensionless, like `v_mid / L`; the caller keeps the largest so far). Methods
    /// without error control ignore it.
    fn set_amplitude(&mut self, _amplitude: f64) {}

    /// Forget anything kept between steps (a reused factorization), so that the next step
    /// depends on the state alone (a restored state then replays bit for bit).
    fn forget_between_steps(&mut self) {}

    /// After [`Integrator::forget_between_steps`]: the state's accelerations are consistent
    /// with the inputs in force (the caller checked), so a method that reuses the last
    /// evaluation as the next step's first stage (first same as last) may take them.
    fn reuse_first_stage(&mut self) {}

    /// The method's name, for run summaries.
    fn name(&self) -> &'static str;

    /// What the work counter of [`Integrator::step`] counts.
    fn work_unit(&self) -> &'static str;

    /// Whether the method chooses its own steps: then [`Integrator::step`] takes one accepted
    /// step of at most `h` (and the driver calls it until the communication point), else
    /// exactly `h`.
    fn is_adaptive(&self) -> bool {
        false
    }

    /// Whether the method has dense output: [`Integrator::step_ahead`] and
    /// [`Integrator::interpolate`] (then the driver may take steps past a communication point
    /// and give the state there by interpolation, so that the internal step does not depend
    /// on the communication step).
    fn dense_output(&self) -> bool {
        false
    }

    /// One accepted step of the method's own size from `state` (not cut at a communication
    /// point): the step's start goes into `ahead` (`t0`, `z0`, `zd0`, `zdd0`), its end into
    /// `ahead.end`, and `ahead.held` is set. `state` is untouched. Returns the work done.
    fn step_ahead(
        &mut self,
        _system: &dyn DaeSystem,
        _state: &DaeState,
        _ahead: &mut StepAhead,
    ) -> Result<usize, StepError> {
        Err(StepFailure::NoDenseOutput.after(0))
    }

    /// The state at `t` inside the held step of `ahead` into `out`: the independent
    /// coordinates and rates by interpolation, the dependent ones, the accelerations and the
    /// multipliers by one complete evaluation (so they are consistent with each other).
    /// Returns the work done.
    fn interpolate(
        &mut self,
        _system: &dyn DaeSystem,
        _ahead: &StepAhead,
        _t: f64,
        _out: &mut DaeState,
    ) -> Result<usize, StepFailure> {
        Err(StepFailure::NoDenseOutput)
    }

    /// Whether an accepted step leaves the state's velocities on the velocity constraints and
    /// its accelerations and multipliers consistent with them, so that the outputs need no
    /// solve of their own.
    fn consistent_outputs(&self) -> bool {
        false
    }
}

#[cfg(test)]
mod quantize_tests {
    /// The bit form is the grid `2^(k/8)` rounded down, as `exp2(floor(8 log2 h) / 8)`.
    #[test]
    fn quantize_step_is_the_eighth_octave_grid() {
        let mut h = 1e-9;
        while h < 10.0 {
            let q = super::quantize_step(h);
            let reference = ((h.log2() * 8.0).floor() / 8.0).exp2();
            assert!(
                q <= h && (q - reference).abs() <= 2.0 * f64::EPSILON * q,
                "{h}: {q} vs {reference}"
            );
            h *= 1.0137;
        }
        assert_eq!(super::quantize_step(0.0), 0.0);
        assert!(super::quantize_step(f64::NAN).is_nan());
        assert_eq!(super::quantize_step(1.0), 1.0);
    }
}
