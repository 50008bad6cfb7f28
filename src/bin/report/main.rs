//! `report`: error against run time of the rod models and solver settings (issue 6).
//!
//! ```sh
//! cargo run --release --bin report            # full matrix, writes docs/report/
//! cargo run --release --bin report -- --quick # reduced matrix (also run by `cargo test --bin report`)
//! cargo run --release --bin report -- --out DIR
//! ```
//!
//! For each benchmark case (constant 150 rad/s from an undeformed start; a smooth start to
//! 150 rad/s; constant 300 rad/s; 150 rad/s with a 0.03 kg slider) and each setting (rod
//! model, elements, modes, reference conditions, solver step h, rho_inf) it runs the case for
//! two revolutions of the final speed after its start, with the communication step equal to
//! the solver step, and measures against the case's reference (finite segments, N = 64,
//! h = 1e-5 s; physics.md, "How error is measured"):
//! - deflection error: max |v_mid/L - v_ref/L| over the setting's communication points (a
//!   subset of the reference's grid) / max |v_ref/L|; and the peak error max|v|/max|v_ref| - 1;
//! - pin B force error: max |F_B - F_B,ref| (vector norm) / max |F_B,ref|; on the smooth start
//!   directly, on the abrupt starts after a zero-phase 4th-order Butterworth low-pass at 2 kHz
//!   ([`filter`]) applied to both signals on the reference's grid (the setting's forces
//!   interpolated linearly onto it), ignoring 1 ms at both ends;
//! - run time: median of at least 5 in-process repeats on one thread (`Simulation::start`
//!   excluded, the loop of `set_input` + `advance` + reading the outputs included), as ms per
//!   simulated second and real-time factor (simulated time / wall time);
//! - internal steps, Newton iterations, step halvings.
//!
//! Outputs: `report.csv`, `report.md`, `error_vs_runtime.svg` in the output folder.

// Index loops are the natural notation for the filter and plot formulas.
#![allow(clippy::needless_range_loop)]

mod filter;
mod svg;

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use flexrod::scene::{ReferenceKind, RodModelKind, SolverMethod};
use flexrod::{CrankInput, ModelError, Scene, Simulation, StepStats};

// ------------------------------------------------------------------ cases

/// A benchmark case: how the crank is driven.
#[derive(Clone, Debug)]
struct Case {
    key: &'static str,
    title: &'static str,
    /// Final crank speed, rad/s.
    speed: f64,
    /// Smooth start from rest over this time, s (None: constant speed from t = 0).
    ramp: Option<f64>,
    slider_mass: f64,
}

impl Case {
    /// Two revolutions of the final speed after the start (after the ramp, if any).
    fn duration(&self) -> f64 {
        self.ramp.unwrap_or(0.0) + 4.0 * std::f64::consts::PI / self.speed
    }

    /// Abrupt start: the axial modes ring, so forces are compared after the low-pass.
    fn abrupt(&self) -> bool {
        self.ramp.is_none()
    }

    /// Crank angle, speed and acceleration at time t:
    /// `w(t) = W (1 - cos(pi t / T)) / 2`, `theta = W/2 (t - T/pi sin(pi t / T))`,
    /// `alpha = W pi / (2 T) sin(pi t / T)` for t < T; then constant speed W.
    fn input(&self, t: f64) -> CrankInput {
        let w = self.speed;
        match self.ramp {
            Some(tr) if t < tr => {
                let x = std::f64::consts::PI * t / tr;
                CrankInput {
                    angle: 0.5 * w * (t - tr / std::f64::consts::PI * x.sin()),
                    speed: 0.5 * w * (1.0 - x.cos()),
                    acceleration: 0.5 * w * std::f64::consts::PI / tr * x.sin(),
                }
            }
            Some(tr) => CrankInput {
                angle: 0.5 * w * tr + w * (t - tr),
                speed: w,
                acceleration: 0.0,
            },
            None => CrankInput {
                angle: w * t,
                speed: w,
                acceleration: 0.0,
            },
        }
    }
}

fn cases() -> Vec<Case> {
    vec![
        Case {
            key: "a",
            title: "(a) constant 150 rad/s from t = 0, undeformed",
            speed: 150.0,
            ramp: None,
            slider_mass: 0.0,
        },
        Case {
            key: "b",
            title: "(b) smooth start from rest to 150 rad/s in T = 0.02 s",
            speed: 150.0,
            ramp: Some(0.02),
            slider_mass: 0.0,
        },
        Case {
            key: "c",
            title: "(c) constant 300 rad/s",
            speed: 300.0,
            ramp: None,
            slider_mass: 0.0,
        },
        Case {
            key: "d",
            title: "(d) 150 rad/s, slider mass 0.03 kg",
            speed: 150.0,
            ramp: None,
            slider_mass: 0.03,
        },
    ]
}

// ------------------------------------------------------------------ settings

#[derive(Clone, Copy, Debug, PartialEq)]
enum Model {
    FfrLinear,
    FfrStiffened,
    Segments,
    /// FFR with axial stiffening, explicit RK4 with projection (`solver.method = "rk4"`).
    FfrRk4,
}

impl Model {
    fn name(self) -> &'static str {
        match self {
            Model::FfrLinear => "ffr_linear",
            Model::FfrStiffened => "ffr_stiffened",
            Model::Segments => "segments",
            Model::FfrRk4 => "ffr_stiffened_rk4",
        }
    }
    fn index(self) -> usize {
        self as usize
    }
}

#[derive(Clone, Copy, Debug)]
struct Setting {
    model: Model,
    elements: usize,
    modes: usize,
    reference: ReferenceKind,
    h: f64,
    rho_inf: f64,
}

fn reference_name(r: ReferenceKind) -> &'static str {
    match r {
        ReferenceKind::SimplySupported => "simply_supported",
        ReferenceKind::MeanAxis => "mean_axis",
        ReferenceKind::BodyFixedMid => "body_fixed_mid",
        ReferenceKind::Cantilever => "cantilever",
    }
}

impl Setting {
    fn ffr(stiff: bool, elements: usize, modes: usize, h: f64) -> Setting {
        Setting {
            model: if stiff {
                Model::FfrStiffened
            } else {
                Model::FfrLinear
            },
            elements,
            modes,
            reference: ReferenceKind::SimplySupported,
            h,
            rho_inf: 0.8,
        }
    }
    fn rk4(elements: usize, modes: usize, h: f64) -> Setting {
        Setting {
            model: Model::FfrRk4,
            ..Setting::ffr(true, elements, modes, h)
        }
    }
    fn seg(n: usize, h: f64) -> Setting {
        Setting {
            model: Model::Segments,
            elements: n,
            modes: 0,
            reference: ReferenceKind::SimplySupported,
            h,
            rho_inf: 0.8,
        }
    }
    fn rho(mut self, rho: f64) -> Setting {
        self.rho_inf = rho;
        self
    }
    fn with_reference(mut self, r: ReferenceKind) -> Setting {
        self.reference = r;
        self
    }

    fn label(&self) -> String {
        match self.model {
            Model::Segments => format!(
                "segments N={} h={:.0e} rho={}",
                self.elements, self.h, self.rho_inf
            ),
            m => {
                let r = match self.reference {
                    ReferenceKind::SimplySupported => "ss",
                    ReferenceKind::MeanAxis => "mean-axis",
                    ReferenceKind::BodyFixedMid => "fixed-mid",
                    ReferenceKind::Cantilever => "cantilever",
                };
                match m {
                    Model::FfrRk4 => format!(
                        "FFR stiffened RK4 {}el/{}m {r} h={:.1e}",
                        self.elements, self.modes, self.h
                    ),
                    _ => {
                        let kind = if m == Model::FfrLinear {
                            "FFR linear"
                        } else {
                            "FFR stiffened"
                        };
                        format!(
                            "{kind} {}el/{}m {r} h={:.0e} rho={}",
                            self.elements, self.modes, self.h, self.rho_inf
                        )
                    }
                }
            }
        }
    }

    fn scene(&self, case: &Case) -> Scene {
        let mut s = Scene::benchmark();
        s.slider.mass = case.slider_mass;
        s.experiment.crank_speed = case.speed;
        s.rod.elements = self.elements;
        s.solver.step = self.h;
        s.solver.rho_inf = self.rho_inf;
        // Each setting names its integrator (the benchmark scene's own is `auto`).
        s.solver.method = SolverMethod::GeneralizedAlpha;
        match self.model {
            Model::Segments => s.rod.model = RodModelKind::Segments,
            m => {
                s.rod.model = RodModelKind::Ffr;
                s.rod.modes = self.modes;
                s.rod.reference = self.reference;
                s.rod.axial_stiffening = m != Model::FfrLinear;
                if m == Model::FfrRk4 {
                    s.solver.method = SolverMethod::Rk4;
                }
            }
        }
        s
    }
}

/// The reference setting of every case: the most complete model at its finest setting.
fn reference_setting(quick: bool) -> Setting {
    if quick {
        Setting::seg(32, 5e-5)
    } else {
        Setting::seg(64, 1e-5)
    }
}

fn matrix(quick: bool) -> Vec<Setting> {
    use ReferenceKind::*;
    let mut v = Vec::new();
    if quick {
        v.push(Setting::ffr(false, 8, 4, 1e-4));
        v.push(Setting::ffr(true, 8, 3, 3e-4));
        v.push(Setting::ffr(true, 8, 4, 1e-4));
        v.push(Setting::seg(16, 1e-4));
        v.push(Setting::rk4(8, 3, 3e-4));
        v.push(reference_setting(true));
        return v;
    }
    // FFR with axial stiffening: modes and step on 8 elements, then mesh, reference
    // conditions, numerical damping.
    for modes in [2, 3, 4, 6] {
        for h in [2e-5, 5e-5, 1e-4, 2e-4, 3e-4, 5e-4] {
            v.push(Setting::ffr(true, 8, modes, h));
        }
    }
    for (el, modes) in [(4, 3), (4, 4), (16, 4), (16, 8)] {
        for h in [5e-5, 1e-4, 3e-4] {
            v.push(Setting::ffr(true, el, modes, h));
        }
    }
    v.push(Setting::ffr(true, 16, 8, 1e-5));
    for r in [MeanAxis, BodyFixedMid] {
        v.push(Setting::ffr(true, 8, 4, 1e-4).with_reference(r));
        v.push(Setting::ffr(true, 8, 4, 3e-4).with_reference(r));
    }
    for rho in [0.0, 0.5, 1.0] {
        v.push(Setting::ffr(true, 8, 3, 3e-4).rho(rho));
        v.push(Setting::ffr(true, 8, 4, 1e-4).rho(rho));
    }
    // The explicit path: RK4 with projection, up to its stability limit (w_max h < 2.78).
    for (modes, steps) in [
        (2, &[2e-4, 3e-4, 4e-4, 5e-4, 6e-4, 7e-4][..]),
        (3, &[1e-4, 2e-4, 2.5e-4, 3e-4, 3.5e-4][..]),
        (4, &[5e-5, 1e-4, 1.5e-4][..]),
    ] {
        for &h in steps {
            v.push(Setting::rk4(8, modes, h));
        }
    }
    v.push(Setting::rk4(4, 3, 3e-4));
    // Linear FFR modes (1985).
    for (el, modes) in [(8, 3), (8, 4)] {
        for h in [1e-4, 3e-4] {
            v.push(Setting::ffr(false, el, modes, h));
        }
    }
    v.push(Setting::ffr(false, 16, 8, 1e-5));
    // Finite segments.
    for n in [4, 8, 16, 32] {
        for h in [2e-5, 5e-5, 1e-4, 2e-4, 3e-4] {
            v.push(Setting::seg(n, h));
        }
    }
    v.push(Setting::seg(16, 1e-4).rho(0.5));
    v.push(Setting::seg(16, 1e-4).rho(1.0));
    // The reference's own convergence, and the reference.
    v.push(Setting::seg(32, 1e-5));
    v.push(Setting::seg(64, 2e-5));
    v.push(reference_setting(false));
    v
}

// ------------------------------------------------------------------ running

/// Outputs at the communication points `k h`, k = 0..=n.
#[derive(Clone, Debug, Default)]
struct Record {
    h: f64,
    v: Vec<f64>,
    fx: Vec<f64>,
    fy: Vec<f64>,
}

impl Record {
    fn clear(&mut self) {
        self.v.clear();
        self.fx.clear();
        self.fy.clear();
    }
    fn push(&mut self, sim: &Simulation) {
        let o = sim.outputs();
        self.v.push(o.deflection_rel);
        self.fx.push(o.pin_b_force[0]);
        self.fy.push(o.pin_b_force[1]);
    }
    fn end_time(&self) -> f64 {
        (self.v.len() - 1) as f64 * self.h
    }
}

/// One run of `case` with communication step `h`: start (not timed), then the loop (timed).
fn run_once(
    sim: &mut Simulation,
    case: &Case,
    h: f64,
    rec: &mut Record,
) -> Result<(f64, StepStats), ModelError> {
    let n = (case.duration() / h * (1.0 + 1e-12)).floor() as usize;
    rec.clear();
    rec.h = h;
    sim.start(0.0, case.input(0.0), 0.0)?;
    let clock = Instant::now();
    rec.push(sim);
    for k in 0..n {
        sim.set_input(case.input(k as f64 * h))?;
        sim.advance((k + 1) as f64 * h - sim.time())?;
        rec.push(sim);
    }
    Ok((clock.elapsed().as_secs_f64(), sim.stats()))
}

struct Timed {
    record: Record,
    seconds: f64,
    repeats: usize,
    stats: StepStats,
}

/// Median of at least `min_repeats` runs (more, up to 30, while the total stays under 0.3 s).
fn timed_runs(setting: &Setting, case: &Case, min_repeats: usize) -> Result<Timed, ModelError> {
    let scene = setting.scene(case);
    let mut sim = Simulation::new(&scene)?;
    let mut record = Record::default();
    let mut times = Vec::new();
    let mut stats = StepStats::default();
    let mut total = 0.0;
    while times.len() < min_repeats || (total < 0.3 && times.len() < 30) {
        let (t, s) = run_once(&mut sim, case, setting.h, &mut record)?;
        times.push(t);
        total += t;
        stats = s;
    }
    times.sort_by(f64::total_cmp);
    let m = times.len();
    let seconds = if m % 2 == 1 {
        times[m / 2]
    } else {
        0.5 * (times[m / 2 - 1] + times[m / 2])
    };
    Ok(Timed {
        record,
        seconds,
        repeats: m,
        stats,
    })
}

// ------------------------------------------------------------------ errors

fn peak(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |a, b| a.max(b.abs()))
}

/// Stride of the run's grid in the reference's grid (h a multiple of the reference step).
fn stride(run: &Record, reference: &Record) -> usize {
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
fn deflection_error(run: &Record, reference: &Record) -> (f64, f64) {
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

const FILTER_CUTOFF: f64 = 2e3;
const EDGE: f64 = 1e-3;

/// Pin B force error (vector norm) / reference peak; filtered on abrupt starts.
fn force_error(run: &Record, reference: &Record, abrupt: bool) -> f64 {
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
fn exudyn() -> Vec<(f64, f64)> {
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
fn exudyn_error(run: &Record, data: &[(f64, f64)]) -> Option<(f64, f64)> {
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

// ------------------------------------------------------------------ rows

#[derive(Clone, Debug)]
struct Row {
    case: &'static str,
    setting: Setting,
    is_reference: bool,
    status: String,
    error: f64,
    peak_error: f64,
    force_error: f64,
    exudyn: Option<(f64, f64)>,
    ms_per_s: f64,
    rtf: f64,
    repeats: usize,
    stats: StepStats,
    pareto: bool,
}

impl Row {
    fn ok(&self) -> bool {
        self.status == "ok"
    }
}

fn mark_pareto(rows: &mut [Row]) {
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

// ------------------------------------------------------------------ progress

struct Progress {
    total: usize,
    done: usize,
    start: Instant,
}

impl Progress {
    fn tick(&mut self, what: &str) {
        self.done += 1;
        let width = 30;
        let filled = width * self.done / self.total.max(1);
        let bar: String = "#".repeat(filled) + &"-".repeat(width - filled);
        let mut err = std::io::stderr().lock();
        let _ = write!(
            err,
            "\r[{bar}] {}/{} {:>5.0} s  {:<60}",
            self.done,
            self.total,
            self.start.elapsed().as_secs_f64(),
            what.chars().take(60).collect::<String>()
        );
        let _ = err.flush();
    }
}

// ------------------------------------------------------------------ the report

struct Options {
    quick: bool,
    out: PathBuf,
}

fn parse_args() -> Result<Options, String> {
    let mut quick = false;
    let mut out = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/report"));
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--quick" => quick = true,
            "--out" => out = PathBuf::from(args.next().ok_or("--out needs a folder")?),
            "-h" | "--help" => {
                return Err(
                    "usage: report [--quick] [--out DIR]  (default DIR: docs/report)".into(),
                )
            }
            other => {
                return Err(format!(
                    "unknown argument {other}; usage: report [--quick] [--out DIR]"
                ))
            }
        }
    }
    Ok(Options { quick, out })
}

/// Run the matrix and write the report files into `out`. Returns the rows.
fn run_report(quick: bool, out: &Path) -> Result<Vec<Row>, String> {
    let clock = Instant::now();
    let all_cases = cases();
    let settings = matrix(quick);
    let reference = reference_setting(quick);
    let min_repeats = if quick { 3 } else { 5 };
    let exudyn_data = exudyn();
    let mut progress = Progress {
        total: all_cases.len() * settings.len(),
        done: 0,
        start: Instant::now(),
    };
    let mut rows: Vec<Row> = Vec::new();
    let mut reference_peaks = Vec::new();
    for case in &all_cases {
        // The reference first (its record is what every other setting is compared with).
        let ref_run = timed_runs(&reference, case, min_repeats)
            .map_err(|e| format!("case {}: the reference run failed: {e}", case.key))?;
        reference_peaks.push((case.key, peak(&ref_run.record.v)));
        let mut case_rows = Vec::new();
        for s in &settings {
            let is_reference = s.model == reference.model
                && s.elements == reference.elements
                && s.h == reference.h
                && s.rho_inf == reference.rho_inf;
            progress.tick(&format!("case {}: {}", case.key, s.label()));
            let result = if is_reference {
                Ok(None)
            } else {
                timed_runs(s, case, min_repeats).map(Some)
            };
            let row = match result {
                Ok(timed) => {
                    let t = timed.as_ref().unwrap_or(&ref_run);
                    let (error, peak_error) = deflection_error(&t.record, &ref_run.record);
                    let force_error = force_error(&t.record, &ref_run.record, case.abrupt());
                    let exudyn = (case.key == "a")
                        .then(|| exudyn_error(&t.record, &exudyn_data))
                        .flatten();
                    let sim_seconds = t.record.end_time();
                    Row {
                        case: case.key,
                        setting: *s,
                        is_reference,
                        status: "ok".into(),
                        error,
                        peak_error,
                        force_error,
                        exudyn,
                        ms_per_s: 1e3 * t.seconds / sim_seconds,
                        rtf: sim_seconds / t.seconds,
                        repeats: t.repeats,
                        stats: t.stats,
                        pareto: false,
                    }
                }
                Err(e) => Row {
                    case: case.key,
                    setting: *s,
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
                },
            };
            case_rows.push(row);
        }
        mark_pareto(&mut case_rows);
        rows.extend(case_rows);
    }
    eprintln!();
    std::fs::create_dir_all(out).map_err(|e| format!("cannot create {}: {e}", out.display()))?;
    let write = |name: &str, text: &str| {
        std::fs::write(out.join(name), text)
            .map_err(|e| format!("cannot write {}: {e}", out.join(name).display()))
    };
    write("report.csv", &csv(&rows))?;
    write(
        "report.md",
        &markdown(
            &rows,
            &all_cases,
            &reference,
            &reference_peaks,
            quick,
            clock.elapsed().as_secs_f64(),
        ),
    )?;
    let panels: Vec<svg::Panel> = all_cases
        .iter()
        .map(|c| svg::Panel {
            title: c.title.to_string(),
            points: rows
                .iter()
                .filter(|r| r.case == c.key && r.ok() && !r.is_reference)
                .map(|r| svg::Point {
                    time: r.ms_per_s,
                    error: r.error,
                    model: r.setting.model.index(),
                    pareto: r.pareto,
                })
                .collect(),
        })
        .collect();
    write(
        "error_vs_runtime.svg",
        &svg::error_vs_runtime(
            "Deflection error against run time (reference: segments N = 64, h = 1e-5 s)",
            &panels,
        ),
    )?;
    Ok(rows)
}

fn f(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.4e}")
    } else {
        String::new()
    }
}

fn csv(rows: &[Row]) -> String {
    let mut s = String::from("case,model,elements,modes,reference,h,rho_inf,status,error,peak_error,force_error,exudyn_error,exudyn_peak_error,ms_per_simulated_s,real_time_factor,repeats,steps,newton_iterations,halvings,pareto,is_reference\n");
    for r in rows {
        let st = &r.setting;
        let (ex, exp) = r.exudyn.map(|(a, b)| (f(a), f(b))).unwrap_or_default();
        let _ = writeln!(
            s,
            "{},{},{},{},{},{:e},{},\"{}\",{},{},{},{},{},{},{},{},{},{},{},{},{}",
            r.case,
            st.model.name(),
            st.elements,
            if st.model == Model::Segments {
                String::new()
            } else {
                st.modes.to_string()
            },
            if st.model == Model::Segments {
                ""
            } else {
                reference_name(st.reference)
            },
            st.h,
            st.rho_inf,
            r.status.replace('"', "'"),
            f(r.error),
            f(r.peak_error),
            f(r.force_error),
            ex,
            exp,
            f(r.ms_per_s),
            f(r.rtf),
            r.repeats,
            r.stats.steps,
            r.stats.newton_iterations,
            r.stats.halvings,
            r.pareto,
            r.is_reference
        );
    }
    s
}

fn pct(x: f64) -> String {
    if x.is_finite() {
        format!("{:.3} %", 100.0 * x)
    } else {
        "-".into()
    }
}

fn pct_signed(x: f64) -> String {
    if x.is_finite() {
        format!("{:+.3} %", 100.0 * x)
    } else {
        "-".into()
    }
}

/// The fastest setting meeting `tol` in both pointwise and peak deflection error.
fn fastest_within(rows: &[Row], case: &str, tol: f64) -> Option<Row> {
    rows.iter()
        .filter(|r| {
            r.case == case
                && r.ok()
                && !r.is_reference
                && r.error <= tol
                && r.peak_error.abs() <= tol
        })
        .min_by(|a, b| a.ms_per_s.total_cmp(&b.ms_per_s))
        .cloned()
}

fn fastest_model_within(rows: &[Row], case: &str, tol: f64, model: Model) -> Option<Row> {
    rows.iter()
        .filter(|r| {
            r.case == case
                && r.ok()
                && r.setting.model == model
                && r.error <= tol
                && r.peak_error.abs() <= tol
        })
        .min_by(|a, b| a.ms_per_s.total_cmp(&b.ms_per_s))
        .cloned()
}

fn markdown(
    rows: &[Row],
    cases: &[Case],
    reference: &Setting,
    peaks: &[(&str, f64)],
    quick: bool,
    seconds: f64,
) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# Error against run time (issue 6)\n");
    let _ = writeln!(
        s,
        "Generated by `cargo run --release --bin report{}` in {seconds:.0} s ({} matrix). Benchmark rod of seed 001; every case runs two revolutions of its final speed after its start, communication step = solver step h, generalized-alpha with the given rho_inf, Newton tolerance 1e-9.\n",
        if quick { " -- --quick" } else { "" },
        if quick { "reduced" } else { "full" }
    );
    let _ = writeln!(s, "- **Reference** of each case: {} (the most complete model at its finest setting). Its own convergence is in the rows `segments N=32 h=1e-5` (mesh) and `segments N=64 h=2e-5` (step) of each table.", reference.label());
    let _ = writeln!(s, "- **error**: max over the setting's communication points (a subset of the reference's 1e-5 s grid) of |v_mid/L - v_ref/L|, divided by the reference peak |v_mid/L| (physics.md, \"How error is measured\"). **peak**: max|v_mid/L| / reference peak - 1.");
    let _ = writeln!(s, "- **force error**: pin B force, max |F_B - F_B,ref| (vector) / max |F_B,ref|. Smooth start (b): directly. Abrupt starts (a, c, d): both signals on the reference's 1e-5 s grid (the setting's linearly interpolated), zero-phase 4th-order Butterworth low-pass at 2 kHz forwards and backwards (src/bin/report/filter.rs), 1 ms at both ends ignored.");
    let _ = writeln!(s, "- **ms/s**: median wall time (>= 5 in-process repeats, one thread, `Simulation::start` excluded; outputs read at every communication point) per simulated second; **RTF** = simulated time / wall time. **steps**, **Newton**: internal steps and Newton iterations of one run. The machine has 2 cores shared with other work, so times carry some noise (a few %).");
    let _ = writeln!(s, "- **Pareto**: no other setting of the case is both faster and more accurate (pointwise error). Figure: `error_vs_runtime.svg`.\n");
    for (k, p) in peaks {
        let _ = writeln!(s, "Reference peak |v_mid/L|, case ({k}): {p:.5e}  ");
    }
    let _ = writeln!(s);

    // Fastest settings.
    let _ = writeln!(
        s,
        "## Fastest setting reaching 0.5 % deflection error (pointwise and peak)\n"
    );
    let _ = writeln!(
        s,
        "Against the case's reference, the reference itself excluded.\n"
    );
    let _ = writeln!(s, "| case | fastest overall | error | peak | ms/s | RTF | fastest FFR stiffened (error) | fastest FFR linear |");
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|");
    for c in cases {
        let best = fastest_within(rows, c.key, 5e-3);
        let ffr = fastest_model_within(rows, c.key, 5e-3, Model::FfrStiffened);
        let lin = fastest_model_within(rows, c.key, 5e-3, Model::FfrLinear);
        let desc = |r: &Option<Row>| {
            r.as_ref()
                .map(|r| {
                    format!(
                        "{} ({}, {:.0} ms/s)",
                        r.setting.label(),
                        pct(r.error),
                        r.ms_per_s
                    )
                })
                .unwrap_or_else(|| "none in the matrix".into())
        };
        match &best {
            Some(r) => {
                let _ = writeln!(
                    s,
                    "| {} | {} | {} | {} | {:.1} | {:.1} | {} | {} |",
                    c.title,
                    r.setting.label(),
                    pct(r.error),
                    pct_signed(r.peak_error),
                    r.ms_per_s,
                    r.rtf,
                    desc(&ffr),
                    desc(&lin)
                );
            }
            None => {
                let _ = writeln!(
                    s,
                    "| {} | none | | | | | {} | {} |",
                    c.title,
                    desc(&ffr),
                    desc(&lin)
                );
            }
        }
    }
    let _ = writeln!(s);
    // Best FFR stiffened by pointwise error, for context.
    let _ = writeln!(s, "Most accurate FFR stiffened setting per case:\n");
    for c in cases {
        if let Some(r) = rows
            .iter()
            .filter(|r| r.case == c.key && r.ok() && r.setting.model == Model::FfrStiffened)
            .min_by(|a, b| a.error.total_cmp(&b.error))
        {
            let _ = writeln!(
                s,
                "- {}: {} — error {}, peak {}",
                c.title,
                r.setting.label(),
                pct(r.error),
                pct_signed(r.peak_error)
            );
        }
    }
    let _ = writeln!(s);

    // Exudyn.
    let _ = writeln!(
        s,
        "## Against the independent geometrically exact beam (Exudyn ANCF, case a)\n"
    );
    let _ = writeln!(s, "tests/data/exudyn_ancf_150rad_s.csv, 1e-4 s grid, compared at the times common to both grids. Sorted by the error against Exudyn (best 12), then the default and benchmark FFR settings and linear modes.\n");
    let _ = writeln!(
        s,
        "| setting | error vs Exudyn | peak vs Exudyn | error vs segment reference |"
    );
    let _ = writeln!(s, "|---|---|---|---|");
    let mut ex_rows: Vec<&Row> = rows
        .iter()
        .filter(|r| {
            r.case == "a" && r.ok() && r.exudyn.is_some() && r.setting.model != Model::FfrLinear
        })
        .collect();
    ex_rows.sort_by(|a, b| a.exudyn.unwrap().0.total_cmp(&b.exudyn.unwrap().0));
    for r in ex_rows.iter().take(12) {
        let (e, p) = r.exudyn.unwrap();
        let _ = writeln!(
            s,
            "| {}{} | {} | {} | {} |",
            r.setting.label(),
            if r.is_reference { " (reference)" } else { "" },
            pct(e),
            pct_signed(p),
            pct(r.error)
        );
    }
    for r in rows
        .iter()
        .filter(|r| r.case == "a" && r.ok() && r.exudyn.is_some())
    {
        let l = &r.setting;
        let notable = (l.model == Model::FfrStiffened
            && l.elements == 8
            && ((l.modes == 4 && l.h == 1e-4) || (l.modes == 3 && l.h == 3e-4))
            && l.rho_inf == 0.8
            && l.reference == ReferenceKind::SimplySupported)
            || (l.model == Model::FfrLinear && l.elements == 8 && l.modes == 4 && l.h == 1e-4);
        if notable && !ex_rows.iter().take(12).any(|x| std::ptr::eq(*x, r)) {
            let (e, p) = r.exudyn.unwrap();
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} |",
                l.label(),
                pct(e),
                pct_signed(p),
                pct(r.error)
            );
        }
    }
    let _ = writeln!(s);

    for c in cases {
        let _ = writeln!(s, "## Case {}\n", c.title);
        let _ = writeln!(
            s,
            "| setting | error | peak | force error | ms/s | RTF | steps | Newton | Pareto |"
        );
        let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|");
        let mut cr: Vec<&Row> = rows.iter().filter(|r| r.case == c.key).collect();
        cr.sort_by(|a, b| a.ms_per_s.total_cmp(&b.ms_per_s));
        for r in cr {
            if r.ok() {
                let _ = writeln!(
                    s,
                    "| {}{} | {} | {} | {} | {:.1} | {:.2} | {} | {} | {} |",
                    r.setting.label(),
                    if r.is_reference { " (reference)" } else { "" },
                    pct(r.error),
                    pct_signed(r.peak_error),
                    pct(r.force_error),
                    r.ms_per_s,
                    r.rtf,
                    r.stats.steps,
                    r.stats.newton_iterations,
                    if r.pareto { "yes" } else { "no" }
                );
            } else {
                let _ = writeln!(
                    s,
                    "| {} | {} | | | | | | | no |",
                    r.setting.label(),
                    r.status
                );
            }
        }
        let _ = writeln!(s);
    }
    s
}

fn main() {
    let options = match parse_args() {
        Ok(o) => o,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(2);
        }
    };
    match run_report(options.quick, &options.out) {
        Ok(rows) => {
            let cases = cases();
            for c in &cases {
                match fastest_within(&rows, c.key, 5e-3) {
                    Some(r) => println!(
                        "case {}: fastest within 0.5 %: {} ({}, {:.1} ms/s, RTF {:.1})",
                        c.key,
                        r.setting.label(),
                        pct(r.error),
                        r.ms_per_s,
                        r.rtf
                    ),
                    None => println!("case {}: no setting within 0.5 %", c.key),
                }
            }
            println!(
                "wrote {}/report.csv, report.md, error_vs_runtime.svg",
                options.out.display()
            );
        }
        Err(e) => {
            eprintln!("report failed: {e}");
            std::process::exit(1);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smooth_start_input_is_consistent() {
        let c = &cases()[1];
        let h = 1e-6;
        for t in [0.001, 0.01, 0.019, 0.025] {
            let (a, b, m) = (c.input(t - h), c.input(t + h), c.input(t));
            assert!(((b.angle - a.angle) / (2.0 * h) - m.speed).abs() < 1e-6);
            assert!(((b.speed - a.speed) / (2.0 * h) - m.acceleration).abs() < 1e-3);
        }
        assert!((c.input(0.02).speed - 150.0).abs() < 1e-12);
    }

    /// The quick matrix end to end (exercises the whole report in CI, well under 60 s).
    #[test]
    fn quick_report_runs() {
        let out = std::env::temp_dir().join(format!("flexrod-report-quick-{}", std::process::id()));
        let rows = run_report(true, &out).unwrap();
        assert!(
            rows.iter().all(|r| r.ok()),
            "{:?}",
            rows.iter()
                .filter(|r| !r.ok())
                .map(|r| &r.status)
                .collect::<Vec<_>>()
        );
        for name in ["report.csv", "report.md", "error_vs_runtime.svg"] {
            let text = std::fs::read_to_string(out.join(name)).unwrap();
            assert!(text.len() > 200, "{name}");
        }
        // The reference has zero error; some setting is on each case's front.
        for c in cases() {
            assert!(rows
                .iter()
                .any(|r| r.case == c.key && r.is_reference && r.error == 0.0));
            assert!(rows.iter().any(|r| r.case == c.key && r.pareto));
        }
        let _ = std::fs::remove_dir_all(&out);
    }
}
