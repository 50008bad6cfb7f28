//! One row of the report: a setting on a case, measured against the case's reference.

use flexrod::{ModelError, StepStats};

use crate::cases::Case;
use crate::metrics::{deflection_error, exudyn_error, force_error};
use crate::settings::Setting;
use crate::timing::Timed;

#[derive(Clone, Debug)]
pub struct Row {
    pub case: &'static str,
    pub setting: Setting,
    pub is_reference: bool,
    /// "ok" or "failed: <reason>".
    pub status: String,
    /// Pointwise deflection error / reference peak.
    pub error: f64,
    /// Peak deflection / reference peak - 1.
    pub peak_error: f64,
    pub force_error: f64,
    /// (pointwise, peak) error against the Exudyn beam (case a only).
    pub exudyn: Option<(f64, f64)>,
    /// Median wall time per simulated second, ms.
    pub ms_per_s: f64,
    /// Real-time factor: simulated time / wall time.
    pub rtf: f64,
    pub repeats: usize,
    pub stats: StepStats,
    /// On the case's error-against-run-time front (set by [`crate::pareto::mark_pareto`]).
    pub pareto: bool,
}

impl Row {
    pub fn ok(&self) -> bool {
        self.status == "ok"
    }

    /// The row of `timed` (a run of `setting` on `case`) against the reference run `reference`;
    /// `exudyn_data` is compared on case a.
    pub fn measured(
        case: &Case,
        setting: &Setting,
        is_reference: bool,
        timed: &Timed,
        reference: &Timed,
        exudyn_data: &[(f64, f64)],
    ) -> Row {
        let (error, peak_error) = deflection_error(&timed.series, &reference.series);
        let force_error = force_error(&timed.series, &reference.series, case.abrupt());
        let exudyn = (case.key == "a")
            .then(|| exudyn_error(&timed.series, exudyn_data))
            .flatten();
        let sim_seconds = timed.series.end_time();
        Row {
            case: case.key,
            setting: *setting,
            is_reference,
            status: "ok".into(),
            error,
            peak_error,
            force_error,
            exudyn,
            ms_per_s: 1e3 * timed.seconds / sim_seconds,
            rtf: sim_seconds / timed.seconds,
            repeats: timed.repeats,
            stats: timed.stats,
            pareto: false,
        }
    }

    /// The row of a setting whose run failed.
    pub fn failed(case: &Case, setting: &Setting, is_reference: bool, e: &ModelError) -> Row {
        Row {
            case: case.key,
            setting: *setting,
            is_reference,
            status: format!("failed: {e}"),
            error: f64::NAN,
            peak_error: f64::NAN,
            force_error: f64::NAN,
            exudyn: None,
            ms_per_s: f64::NAN,
            rtf: f64::NAN,
            repeats: 0,
            stats: StepStats::default(),
            pareto: false,
        }
    }
}
