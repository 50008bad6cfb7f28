//! What a rod model costs, predicted from the model actually built: the work of one evaluation
//! of its equations (a right-hand side or a Newton iteration) and the work and memory of
//! building it, in work units.
//!
//! A work unit is one term of a dense evaluation on `n` coordinates, which costs `n^2 (n +
//! 100)` of them (a dense product, `n^2`, and a dense solve, `n^3`, measured about equal at
//! `n = 100`) plus [`EVALUATION_OVERHEAD`]. The per-call budget of the mechanism
//! (`mechanism::stepping::WORK_BUDGET`) and the build limit here ([`BUILD_BUDGET`]) are in
//! these units, so that they bound time, not counts: the FFR rod's coupling of axial and
//! bending modes ([`crate::modal::axial_coupling`]) costs `na n^2 (na + 3)` terms per
//! evaluation and `4 E na n^2 (na + 1)` to build (`n` retained modes, `na` of them axial, `E`
//! elements), far more than the dense part once a soft rod puts dozens of axial modes into its
//! mode band. The weights are measured: `cargo run --release --example cost_calibration`
//! prints the time per unit of each term on a range of models (docs/robustness.md,
//! "Limits").

use crate::error::ModelError;

/// The work one communication step may do, in work units (this module's): each counted
/// evaluation (a Newton iteration or a right-hand-side evaluation, accepted or not, plus one
/// per internal step and one per halving) costs `Mechanism::evaluation_cost`, the dense terms
/// of its coordinates and what the rod adds (the FFR rod's axial coupling). The budget so
/// bounds the time of one call about equally at every model size (docs/fmu.md, "Time per
/// call", gives the measured worst case). A communication step that would need more is
/// refused with the state kept.
pub const WORK_BUDGET: f64 = 2.5e10;

/// Work units of one evaluation beyond its dense terms (the constraint rows, the crank law,
/// the bookkeeping of a step, the segment chain's kinematics per segment), calibrated by
/// `examples/cost_calibration.rs` on small models (docs/robustness.md, "Limits").
pub const EVALUATION_OVERHEAD: f64 = 4.0e4;

/// Work units per term of the axial coupling's evaluation (`na n^2 (na + 3)` terms): the
/// fourth-order tensor is read with a stride of `n^2` per axial mode, one cache line per
/// term (measured with `examples/cost_calibration.rs`).
pub const AXIAL_COUPLING_TERM: f64 = 50.0;

/// Work units per term of building the axial coupling (`4 E na n^2 (na + 1)` terms:
/// four Gauss points per element, each adding `n^2` entries per pair of axial modes).
pub const AXIAL_BUILD_TERM: f64 = 13.0;

/// The most work units building one rod may take: about 2 s on one core of the reference
/// machine (docs/robustness.md, "Limits"). A rod whose build is predicted above it is refused
/// before the work starts, with the reason.
pub const BUILD_BUDGET: f64 = 2.5e10;

/// The most memory the precomputed tensors of one rod may take, bytes (256 MiB): the FFR
/// rod's section sampling and axial coupling, the only parts that grow faster than `n^2`.
pub const MAX_MODEL_BYTES: f64 = 268_435_456.0;

/// The bound on the wall time of one call that the limits here and the per-call budget keep,
/// s: initialization or one communication step, on one core of the reference machine (2
/// cores, x86-64). Measured worst cases are in docs/fmu.md, "Time per call"; the fuzz
/// harness's range generator checks every call against it.
pub const WORST_CALL_SECONDS: f64 = 5.0;

/// The fewest evaluations one communication step must be able to afford within the
/// per-call budget: a model whose evaluation costs more than `WORK_BUDGET /
/// MIN_EVALUATIONS_PER_CALL` could take only a handful of internal steps per call, and is
/// refused at initialization.
pub const MIN_EVALUATIONS_PER_CALL: f64 = 200.0;

/// Work units of one dense evaluation on `n` coordinates.
pub fn dense_evaluation(n: usize) -> f64 {
    let n = n as f64;
    n * n * (n + 100.0) + EVALUATION_OVERHEAD
}

/// Work units of one evaluation of the axial coupling of `n` retained modes, `na` axial.
pub fn axial_coupling_evaluation(n: usize, na: usize) -> f64 {
    let (n, na) = (n as f64, na as f64);
    AXIAL_COUPLING_TERM * na * n * n * (na + 3.0)
}

/// Work units of building the axial coupling of `n` retained modes, `na` axial, on
/// `elements` elements.
pub fn axial_coupling_build(n: usize, na: usize, elements: usize) -> f64 {
    let (n, na, e) = (n as f64, na as f64, elements as f64);
    AXIAL_BUILD_TERM * 4.0 * e * na * n * n * (na + 1.0)
}

/// Bytes of the axial coupling's tensors: `T` and `Z` (`na n^2` each) and `F` (`na^2 n^2`).
pub fn axial_coupling_bytes(n: usize, na: usize) -> f64 {
    let (n, na) = (n as f64, na as f64);
    8.0 * n * n * na * (na + 2.0)
}

/// Bytes of the FFR rod's section sampling (`rod::ffr::sections`): `4 + 4 n + 2 n^2` numbers
/// at each of its cuts (`2 E + 1` element ends and midpoints, the rod's midpoint and the
/// `stations` of a section table).
pub fn section_sampling_bytes(n: usize, elements: usize, stations: usize) -> f64 {
    let n = n as f64;
    let cuts = (2 * elements + 2 + stations) as f64;
    8.0 * cuts * (4.0 + 4.0 * n + 2.0 * n * n)
}

/// What building and evaluating an FFR rod of `n` retained modes (`na` of them axial, with
/// axial stiffening on; else 0) on `elements` elements with `stations` section stations will
/// cost, checked against the limits before anything is built: a refusal names the modes, the
/// predicted cost and the keys that lower it.
pub fn check_ffr(n: usize, na: usize, elements: usize, stations: usize) -> Result<(), ModelError> {
    let build = axial_coupling_build(n, na, elements);
    let bytes = axial_coupling_bytes(n, na) + section_sampling_bytes(n, elements, stations);
    let evaluation = axial_coupling_evaluation(n, na) + dense_evaluation(n + 4);
    let per_call = WORK_BUDGET / MIN_EVALUATIONS_PER_CALL;
    let what = if build > BUILD_BUDGET {
        format!(
            "building its axial coupling (na^2 n^2 terms) takes {build:.2e} work units, more than the {BUILD_BUDGET:.1e} allowed (about 2 s)"
        )
    } else if bytes > MAX_MODEL_BYTES {
        format!(
            "its precomputed tensors (section sampling, 2 n^2 numbers per cut, and axial coupling) take {:.0} MiB, more than the {:.0} MiB allowed per instance",
            bytes / 1048576.0,
            MAX_MODEL_BYTES / 1048576.0
        )
    } else if evaluation > per_call {
        format!(
            "one evaluation takes {evaluation:.2e} work units (its axial coupling na^2 n^2 terms), more than the {per_call:.2e} that leave a communication step {MIN_EVALUATIONS_PER_CALL} evaluations within the work budget of one call"
        )
    } else {
        return Ok(());
    };
    Err(ModelError::TooCostly {
        message: format!(
            "the FFR rod retains {n} modes, {na} of them axial, on {elements} elements: {what}; retain fewer modes (a lower rod.mode_band_hz or rod.modes: a soft rod puts many axial modes into a band), take fewer rod.elements, set rod.axial_stiffening = false, or take rod.model = \"segments\""
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shipped_sizes_pass_and_a_band_full_of_axial_modes_is_refused() {
        // The automotive rod: 3 modes, 1 axial, 8 elements.
        assert!(check_ffr(3, 1, 8, 3).is_ok());
        // The soft automotive rod on 52 elements: 103 modes in its band, 51 axial.
        let e = check_ffr(103, 51, 52, 3).unwrap_err().to_string();
        assert!(e.contains("103 modes, 51 of them axial"), "{e}");
        assert!(e.contains("rod.mode_band_hz"), "{e}");
        // Without axial modes there is no coupling to pay for, but the section sampling of
        // 384 modes on 128 elements takes about 600 MB.
        assert!(check_ffr(192, 0, 128, 0).is_ok());
        let e = check_ffr(384, 0, 128, 0).unwrap_err().to_string();
        assert!(e.contains("MiB"), "{e}");
    }
}
