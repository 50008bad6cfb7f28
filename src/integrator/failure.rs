//! Why a step failed, and what it cost.

/// Why a step failed.
#[derive(Clone, Debug, PartialEq)]
pub enum StepFailure {
    /// Newton did not converge in the allowed iterations.
    NewtonDiverged {
        iterations: usize,
        last_correction: f64,
    },
    /// The iteration matrix is singular (a lost constraint, a degenerate configuration).
    SingularMatrix,
    /// A value became NaN or infinite.
    NonFinite,
    /// A held step (dense output) reached an integrator that has none (a restored state made
    /// for another integrator).
    NoDenseOutput,
}

impl std::fmt::Display for StepFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StepFailure::NewtonDiverged {
                iterations,
                last_correction,
            } => write!(
                f,
                "Newton did not converge in {iterations} iterations (last scaled correction {last_correction:e})"
            ),
            StepFailure::SingularMatrix => {
                write!(f, "the Newton matrix is singular (degenerate configuration)")
            }
            StepFailure::NonFinite => write!(f, "the solution became NaN or infinite"),
            StepFailure::NoDenseOutput => {
                write!(f, "a held internal step reached an integrator without dense output")
            }
        }
    }
}

/// A failed step: why, and the work it spent (Newton iterations or factorizations), so that
/// the counters report what was really done.
#[derive(Clone, Debug, PartialEq)]
pub struct StepError {
    pub failure: StepFailure,
    pub work: usize,
}

impl StepFailure {
    /// This failure after `work` units of work.
    pub fn after(self, work: usize) -> StepError {
        StepError {
            failure: self,
            work,
        }
    }
}
