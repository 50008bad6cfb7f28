//! Error measures against the case's reference (docs/physics.md, "How error is measured"):
//! pointwise and peak deflection error, the pin B force error (low-passed on abrupt starts,
//! [`crate::filter`]), and the deflection error against the independent Exudyn beam.

use flexrod::drive::Record;

use crate::filter;

/// The signals compared, at the communication points `k h`, k = 0..=n.
#[derive(Clone, Debug, Default)]
pub struct Series {
    pub h: f64,
    /// `v_mid / L`.
    pub v: Vec<f64>,
    /// Pin B force, x and y, N.
    pub fx: Vec<f64>,
    pub fy: Vec<f64>,
}

impl Series {
    /// The series of a run recorded on the grid `k h` from t = 0.
    pub fn new(record: &Record, h: f64) -> Series {
        Series {
            h,
            v: record.outputs.iter().map(|o| o.deflection_rel).collect(),
            fx: record.outputs.iter().map(|o| o.pin_b_force[0]).collect(),
            fy: record.outputs.iter().map(|o| o.pin_b_force[1]).collect(),
        }
    }

    /// Simulated time, s.
    pub fn end_time(&self) -> f64 {
        (self.v.len() - 1) as f64 * self.h
    }
}

/// max |x|.
pub fn peak(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |a, b| a.max(b.abs()))
}

/// Stride of the run's grid in the reference's grid (h a multiple of the reference step).
fn stride(run: &Series, reference: &Series) -> usize {
    let s = run.h / reference.h;
    let k = s.round();
    assert!(
        (s - k).abs() < 1e-6 && k >= 1.0,
        "h = {} is not a multiple of the reference step {}",
        run.h,
        reference.h
    );
    k as usize
}

/// (pointwise deflection error, peak error) against the reference.
pub fn deflection_error(run: &Series, reference: &Series) -> (f64, f64) {
    let st = stride(run, reference);
    let ref_peak = peak(&reference.v);
    let mut worst: f64 = 0.0;
    for (k, v) in run.v.iter().enumerate() {
        if let Some(r) = reference.v.get(k * st) {
            worst = worst.max((v - r).abs());
        }
    }
    (worst / ref_peak, peak(&run.v) / ref_peak - 1.0)
}

/// Cutoff of the force low-pass on abrupt starts, Hz.
const FILTER_CUTOFF: f64 = 2e3;
/// Time ignored at both ends of the filtered forces, s.
const EDGE: f64 = 1e-3;

/// Pin B force error (vector norm) / reference peak; filtered on abrupt starts.
pub fn force_error(run: &Series, reference: &Series, abrupt: bool) -> f64 {
    if !abrupt {
        let st = stride(run, reference);
        let mut worst: f64 = 0.0;
        let mut scale: f64 = 0.0;
        for k in 0..run.v.len() {
            let Some(i) = Some(k * st).filter(|&i| i < reference.v.len()) else {
                break;
            };
            worst = worst.max((run.fx[k] - reference.fx[i]).hypot(run.fy[k] - reference.fy[i]));
        }
        for i in 0..reference.v.len() {
            scale = scale.max(reference.fx[i].hypot(reference.fy[i]));
        }
        return worst / scale;
    }
    // On the reference grid, over the common span.
    let href = reference.h;
    let n = ((run.end_time().min(reference.end_time())) / href + 1e-9).floor() as usize + 1;
    let interp = |x: &[f64], t: f64| -> f64 {
        let s = t / run.h;
        let k = (s.floor() as usize).min(x.len() - 2);
        let f = s - k as f64;
        x[k] * (1.0 - f) + x[k + 1] * f
    };
    let (mut rx, mut ry) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for i in 0..n {
        let t = i as f64 * href;
        rx.push(interp(&run.fx, t));
        ry.push(interp(&run.fy, t));
    }
    let fs = 1.0 / href;
    let (rx, ry) = (
        filter::filtfilt(&rx, FILTER_CUTOFF, fs),
        filter::filtfilt(&ry, FILTER_CUTOFF, fs),
    );
    let gx = filter::filtfilt(&reference.fx[..n], FILTER_CUTOFF, fs);
    let gy = filter::filtfilt(&reference.fy[..n], FILTER_CUTOFF, fs);
    let (mut worst, mut scale): (f64, f64) = (0.0, 0.0);
    let t_end = (n - 1) as f64 * href;
    for i in 0..n {
        let t = i as f64 * href;
        if t < EDGE || t > t_end - EDGE {
            continue;
        }
        worst = worst.max((rx[i] - gx[i]).hypot(ry[i] - gy[i]));
        scale = scale.max(gx[i].hypot(gy[i]));
    }
    worst / scale
}

/// The Exudyn ANCF data: v_mid/L on a 1e-4 s grid (case a).
pub fn exudyn() -> Vec<(f64, f64)> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/exudyn_ancf_150rad_s.csv"
    );
    let text = std::fs::read_to_string(path).unwrap_or_default();
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with('t') && !l.trim().is_empty())
        .filter_map(|l| {
            let v: Vec<f64> = l.split(',').filter_map(|x| x.trim().parse().ok()).collect();
            (v.len() >= 2).then(|| (v[0], v[1]))
        })
        .collect()
}

/// (pointwise error, peak error) against the Exudyn data, at the common times.
pub fn exudyn_error(run: &Series, data: &[(f64, f64)]) -> Option<(f64, f64)> {
    if data.is_empty() {
        return None;
    }
    let ref_peak = data.iter().fold(0.0f64, |a, r| a.max(r.1.abs()));
    let mut worst: f64 = 0.0;
    let mut count = 0;
    for &(t, v) in data {
        let s = t / run.h;
        let k = s.round();
        if (s - k).abs() < 1e-6 {
            if let Some(x) = run.v.get(k as usize) {
                worst = worst.max((x - v).abs());
                count += 1;
            }
        }
    }
    // The run's own peak over the span of the data.
    let t_last = data.last().unwrap().0;
    let kmax = ((t_last / run.h).floor() as usize).min(run.v.len() - 1);
    let p = peak(&run.v[..=kmax]);
    (count > 0).then(|| (worst / ref_peak, p / ref_peak - 1.0))
}
