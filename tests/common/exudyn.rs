//! The geometrically exact reference: `tests/data/exudyn_ancf_150rad_s.csv`, the benchmark rod
//! of the CDI parametric study at a constant 150 rad/s from t = 0, undeformed start, computed once with Exudyn
//! ANCF cable elements (32 and 64 elements agree to < 1e-5 of the peak v_mid/L), sampled every
//! 1e-4 s over two revolutions. [`read_rows`] reads any reference file under tests/data (also
//! `exudyn_automotive_rod.csv`, tests/automotive_reference.rs).

use flexrod::drive::Record;

/// Crank speed of the reference, rad/s.
pub const SPEED: f64 = 150.0;
/// Sampling interval of the reference, s.
pub const DT: f64 = 1e-4;

/// One row of the reference.
#[derive(Clone, Copy, Debug)]
pub struct Sample {
    pub time: f64,
    pub deflection_rel: f64,
    pub pin_b_force: [f64; 2],
    pub pin_c_force: [f64; 2],
}

/// The numeric rows of a reference file under tests/data (comment lines `#`, the header line
/// starting with `t` and blank lines skipped), each with exactly `columns` values.
pub fn read_rows(name: &str, columns: usize) -> Vec<Vec<f64>> {
    let path = format!("{}/tests/data/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with('t') && !l.trim().is_empty())
        .map(|l| {
            let v: Vec<f64> = l
                .split(',')
                .map(|x| x.trim().parse().unwrap_or_else(|_| panic!("{path}: '{l}'")))
                .collect();
            assert_eq!(v.len(), columns, "{path}: '{l}'");
            v
        })
        .collect()
}

/// The reference rows (every row checked to lie on the 1e-4 s grid).
pub fn samples() -> Vec<Sample> {
    samples_of("exudyn_ancf_150rad_s.csv")
}

/// The same run with Exudyn's geometrically exact shear beam (ObjectBeamGeometricallyExact2D,
/// 512 elements; `tests/data/benchmark_shear_reference.py`): the physics of the default scene,
/// whose `auto` takes shear deformation and rotary inertia into the benchmark rod.
pub fn shear_beam_samples() -> Vec<Sample> {
    samples_of("exudyn_shear_beam_150rad_s.csv")
}

/// The rows of a reference file of this run's format under tests/data.
pub fn samples_of(name: &str) -> Vec<Sample> {
    let path = format!("tests/data/{name}");
    let rows: Vec<Sample> = read_rows(name, 6)
        .into_iter()
        .map(|v| Sample {
            time: v[0],
            deflection_rel: v[1],
            pin_b_force: [v[2], v[3]],
            pin_c_force: [v[4], v[5]],
        })
        .collect();
    assert!(rows.len() > 100, "{path}: {} rows", rows.len());
    for (k, r) in rows.iter().enumerate() {
        assert!(
            (r.time - k as f64 * DT).abs() < 1e-9,
            "{path}: row {k} at {}",
            r.time
        );
    }
    rows
}

/// Peak |v_mid/L| of the reference.
pub fn peak(samples: &[Sample]) -> f64 {
    samples
        .iter()
        .map(|s| s.deflection_rel.abs())
        .fold(0.0, f64::max)
}

/// A run against the reference.
#[derive(Clone, Copy, Debug)]
pub struct Comparison {
    /// Peak |v_mid/L| of the run / the reference's - 1.
    pub peak_error: f64,
    /// Largest |delta v_mid/L| at the common times, relative to the reference's peak.
    pub pointwise: f64,
    /// Number of common times compared.
    pub compared: usize,
}

/// Compare a run (any communication step that is a multiple of 1e-4 s, from t = 0) with the
/// reference at the times both have; the peaks are those of each full record.
pub fn compare(record: &Record, samples: &[Sample]) -> Comparison {
    let reference_peak = peak(samples);
    let mut worst: f64 = 0.0;
    let mut compared = 0;
    for (t, o) in record.times.iter().zip(&record.outputs) {
        let k = (t / DT).round() as usize;
        if let Some(s) = samples.get(k) {
            if (s.time - t).abs() < 1e-9 {
                worst = worst.max((o.deflection_rel - s.deflection_rel).abs());
                compared += 1;
            }
        }
    }
    assert!(
        compared * 4 >= record.times.len().min(samples.len()),
        "only {compared} of {} points on the reference's grid",
        record.times.len()
    );
    Comparison {
        peak_error: record.peak_deflection_rel() / reference_peak - 1.0,
        pointwise: worst / reference_peak,
        compared,
    }
}
