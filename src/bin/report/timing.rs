//! Running a setting on a case through the library's run loop ([`flexrod::drive::run`]) and
//! timing it: the median wall time of repeated in-process runs on one thread.

use std::time::Instant;

use flexrod::drive::{communication_grid, run};
use flexrod::{ModelError, Simulation, StepStats};

use crate::cases::Case;
use crate::metrics::Series;
use crate::settings::Setting;

/// A timed setting: what the last run recorded, and the median wall time of all runs.
pub struct Timed {
    pub series: Series,
    /// Median wall time of one run, s.
    pub seconds: f64,
    pub repeats: usize,
    /// The integrator's counters of one run.
    pub stats: StepStats,
}

/// Stop repeating once the runs took this long in total, s (after the minimum of repeats).
const TIME_BUDGET: f64 = 0.3;
/// Most repeats of one setting.
const MAX_REPEATS: usize = 30;

/// Run `setting` on `case` at least `min_repeats` times (more, up to [`MAX_REPEATS`], while
/// the total stays under [`TIME_BUDGET`]): communication step = solver step (3e-4 s for the
/// error-controlled settings, whose internal steps the tolerance chooses), from t = 0 for
/// the case's duration (two revolutions of the final speed after the start). Each run is
/// `drive::run`: `Simulation::start`, then per communication point `set_input`, `advance` and
/// the outputs read and recorded; `Simulation::new` (the preprocessing) is not timed.
pub fn timed_runs(setting: &Setting, case: &Case, min_repeats: usize) -> Result<Timed, ModelError> {
    let h = setting.communication_step();
    let mut simulation = Simulation::new(&setting.scene(case))?;
    let steps = (case.duration() / h * (1.0 + 1e-12)).floor() as usize;
    let grid = communication_grid(0.0, h, steps);
    let mut seconds = Vec::new();
    let mut total = 0.0;
    let mut last = None;
    while seconds.len() < min_repeats || (total < TIME_BUDGET && seconds.len() < MAX_REPEATS) {
        let clock = Instant::now();
        let record = run(&mut simulation, &case.drive, 0.0, &grid)?;
        let t = clock.elapsed().as_secs_f64();
        seconds.push(t);
        total += t;
        last = Some(record);
    }
    let record = last.expect("at least one run");
    Ok(Timed {
        series: Series::new(&record, h),
        repeats: seconds.len(),
        seconds: median(&mut seconds),
        stats: record.stats,
    })
}

/// The median (of a non-empty list; sorts it).
fn median(x: &mut [f64]) -> f64 {
    x.sort_by(f64::total_cmp);
    let m = x.len();
    if m % 2 == 1 {
        x[m / 2]
    } else {
        0.5 * (x[m / 2 - 1] + x[m / 2])
    }
}
