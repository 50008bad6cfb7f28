//! The error-against-run-time front of each case, and the fastest settings within an error.

use crate::rows::Row;
use crate::settings::Model;

/// Mark the rows (of one case) on the front: no other successful row is both at least as fast
/// and at least as accurate (pointwise error), and better in one of the two.
pub fn mark_pareto(rows: &mut [Row]) {
    let snapshot: Vec<(f64, f64, bool)> =
        rows.iter().map(|r| (r.ms_per_s, r.error, r.ok())).collect();
    for (i, r) in rows.iter_mut().enumerate() {
        if !r.ok() {
            continue;
        }
        let (t, e, _) = snapshot[i];
        r.pareto = !snapshot
            .iter()
            .enumerate()
            .any(|(j, &(tj, ej, ok))| j != i && ok && tj <= t && ej <= e && (tj < t || ej < e));
    }
}

/// The fastest of `rows` (successful, of `case`) that `keep` accepts.
fn fastest<'a>(rows: &'a [Row], case: &str, keep: impl Fn(&Row) -> bool) -> Option<&'a Row> {
    rows.iter()
        .filter(|r| r.case == case && r.ok() && keep(r))
        .min_by(|a, b| a.ms_per_s.total_cmp(&b.ms_per_s))
}

/// The fastest setting (the reference excluded) meeting `tol` in both pointwise and peak
/// deflection error.
pub fn fastest_within(rows: &[Row], case: &str, tol: f64) -> Option<Row> {
    fastest(rows, case, |r| {
        !r.is_reference && r.error <= tol && r.peak_error.abs() <= tol
    })
    .cloned()
}

/// The fastest setting of `model` meeting `tol` in both pointwise and peak deflection error.
pub fn fastest_model_within(rows: &[Row], case: &str, tol: f64, model: Model) -> Option<Row> {
    fastest(rows, case, |r| {
        r.setting.model == model && r.error <= tol && r.peak_error.abs() <= tol
    })
    .cloned()
}

/// The fastest setting (the reference excluded) with pointwise error at most `tol`: the
/// front's setting at that error.
pub fn front_at(rows: &[Row], case: &str, tol: f64) -> Option<Row> {
    fastest(rows, case, |r| !r.is_reference && r.error <= tol).cloned()
}

/// The most accurate (pointwise) setting of `model`.
pub fn most_accurate(rows: &[Row], case: &str, model: Model) -> Option<Row> {
    rows.iter()
        .filter(|r| r.case == case && r.ok() && r.setting.model == model)
        .min_by(|a, b| a.error.total_cmp(&b.error))
        .cloned()
}
