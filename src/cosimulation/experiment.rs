//! The time range of an experiment, one check for every interface and scene file.

use crate::error::{require_within, ModelError};
use crate::limits::EXPERIMENT_TIME_LIMIT;

/// `[experiment]` step_size range, s.
pub const EXPERIMENT_STEP_RANGE: (f64, f64) = (1e-9, 1.0);

/// The experiment's start and stop time, one check for scene files (`[experiment]`), the
/// experiment of `fmi2SetupExperiment` / `fmi3EnterInitializationMode` and serialized states:
/// the start finite in `[-EXPERIMENT_TIME_LIMIT, EXPERIMENT_TIME_LIMIT - 1]` s (room for a
/// stop), the stop (where given) finite, at least the smallest step (1e-9 s) after the start
/// and at most `EXPERIMENT_TIME_LIMIT` s. `names` are the start's
/// and the stop's names in messages (the scene keys, or the arguments of the FMI call).
pub fn check_experiment_times(
    start_time: f64,
    stop_time: Option<f64>,
    names: [&'static str; 2],
) -> Result<(), ModelError> {
    let limit = EXPERIMENT_TIME_LIMIT;
    let (low, high) = EXPERIMENT_STEP_RANGE;
    let [start_name, stop_name] = names;
    // The start leaves room for a stop time up to the limit.
    require_within(start_name, start_time, -limit, limit - high, "s")?;
    let Some(stop) = stop_time else {
        return Ok(());
    };
    // The least stop time, rounded up where start + 1e-9 s rounds below it.
    let mut least = start_time + low;
    if least - start_time < low {
        least = least.next_up();
    }
    if stop.is_finite() && stop >= least && stop <= limit {
        return Ok(());
    }
    Err(ModelError::InvalidParameter {
        name: stop_name,
        value: stop,
        allowed: format!(
            "a finite value in [{start_name} + {low:e}, {limit:e}] = [{}, {limit:e}] s ({start_name} = {} s; the run holds at least one step of the smallest step size {low:e} s)",
            crate::text::number(least),
            crate::text::number(start_time)
        ),
    })
}
