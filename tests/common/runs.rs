//! Driving a scene and measuring the run, on top of `flexrod::drive`.
//!
//! Runs that must complete go through `flexrod::drive::run` itself ([`constant`],
//! [`completed`]). Runs that may end in a failed step, or that look at the state at every
//! communication point, go through [`drive_visit`]: the same loop (start at the first point;
//! at each point `t_k` set the input, advance by `t_{k+1} - time()`, record), which keeps the
//! record up to a failed step and checks the contract of a failure (`ModelError::StepFailed`,
//! the state from before the step kept). `drive::run` drops the record on a failure; with an
//! accessor for it there, `drive_visit` would shrink to the visiting.

use flexrod::drive::{self, communication_grid, CrankDrive, Record};
use flexrod::{CrankInput, ModelError, Scene, Simulation};

pub const REV: f64 = 2.0 * std::f64::consts::PI;

/// Communication steps of `dt` in `revolutions` crank revolutions at `speed` (rounded).
pub fn steps_for(speed: f64, revolutions: f64, dt: f64) -> usize {
    (revolutions * REV / speed.abs() / dt).round() as usize
}

/// Constant crank speed from t = 0 (`drive::run_constant`); panics naming the error.
pub fn constant(scene: &Scene, speed: f64, dt: f64, revolutions: f64) -> (Record, Simulation) {
    drive::run_constant(scene, speed, dt, revolutions)
        .unwrap_or_else(|e| panic!("{speed} rad/s, dt {dt}: {e}"))
}

/// A crank law over `times` (`drive::run`); panics naming the error.
pub fn completed(
    scene: &Scene,
    law: &CrankDrive,
    slider_force: f64,
    times: &[f64],
) -> (Record, Simulation) {
    let mut sim = Simulation::new(scene).unwrap_or_else(|e| panic!("{e}"));
    let record =
        drive::run(&mut sim, law, slider_force, times).unwrap_or_else(|e| panic!("{law:?}: {e}"));
    (record, sim)
}

/// A run that may have ended in a failed step.
pub struct Run {
    /// Everything up to the last completed communication point.
    pub record: Record,
    /// The error of the failed step, if one failed.
    pub error: Option<ModelError>,
    pub sim: Simulation,
}

impl Run {
    pub fn deflection_rel(&self) -> Vec<f64> {
        self.record.deflection_rel()
    }

    pub fn peak(&self) -> f64 {
        self.record.peak_deflection_rel()
    }

    /// Largest |F_B|, N.
    pub fn peak_pin_b_force(&self) -> f64 {
        peak_pin_b_force(&self.record)
    }

    /// Every recorded output is finite.
    pub fn finite(&self) -> bool {
        self.record.outputs.iter().all(|o| {
            [
                o.deflection,
                o.deflection_rel,
                o.pin_b_force[0],
                o.pin_b_force[1],
                o.pin_c_force[0],
                o.pin_c_force[1],
                o.crank_torque,
                o.slider_position,
                o.slider_velocity,
            ]
            .iter()
            .all(|x| x.is_finite())
        })
    }

    /// Time of the first warning that the deflection passed `rod.deflection_limit`, s.
    pub fn first_warning(&self) -> Option<f64> {
        self.deflection_warnings().next().map(|w| w.0)
    }

    /// The warnings that the deflection passed `rod.deflection_limit` (time, text).
    pub fn deflection_warnings(&self) -> impl Iterator<Item = &(f64, String)> {
        self.record
            .warnings
            .iter()
            .filter(|w| w.1.contains("exceeds rod.deflection_limit"))
    }

    /// Time of the warning that `rod.error_estimate` passed `solver.tolerance`, s.
    pub fn error_estimate_warning(&self) -> Option<f64> {
        self.record
            .warnings
            .iter()
            .find(|w| w.1.starts_with("rod.error_estimate"))
            .map(|w| w.0)
    }

    /// The error as text, "none" without one.
    pub fn error_text(&self) -> String {
        self.error
            .as_ref()
            .map_or_else(|| "none".to_string(), |e| e.to_string())
    }
}

/// Drive `scene` over the communication points `times` with `input(k, t_k)` at point k and a
/// constant slider force; `visit` sees the simulation at every point (the start included).
/// Ends at the first failed step, after checking that it returned `StepFailed` and kept the
/// state from before the step.
pub fn drive_visit(
    scene: &Scene,
    times: &[f64],
    slider_force: f64,
    input: impl FnMut(usize, f64) -> CrankInput,
    visit: impl FnMut(&Simulation),
) -> Run {
    drive_loop(scene, times, slider_force, input, visit, true)
}

/// [`drive_visit`] for long runs: the record keeps only the first and the last point (and
/// every warning); the visitor sees every point.
pub fn visit_only(
    scene: &Scene,
    times: &[f64],
    slider_force: f64,
    input: impl FnMut(usize, f64) -> CrankInput,
    visit: impl FnMut(&Simulation),
) -> Run {
    drive_loop(scene, times, slider_force, input, visit, false)
}

fn drive_loop(
    scene: &Scene,
    times: &[f64],
    slider_force: f64,
    mut input: impl FnMut(usize, f64) -> CrankInput,
    mut visit: impl FnMut(&Simulation),
    keep_all: bool,
) -> Run {
    let mut sim = Simulation::new(scene).unwrap_or_else(|e| panic!("{e}"));
    let t0 = times[0];
    sim.start(t0, input(0, t0), slider_force)
        .unwrap_or_else(|e| panic!("start: {e}"));
    visit(&sim);
    let mut record = Record {
        times: vec![t0],
        inputs: vec![input(0, t0)],
        outputs: vec![sim.outputs()],
        ..Default::default()
    };
    let mut error = None;
    for (k, pair) in times.windows(2).enumerate() {
        let (t_k, t_next) = (pair[0], pair[1]);
        sim.set_input(input(k, t_k))
            .unwrap_or_else(|e| panic!("input at {t_k}: {e}"));
        let before = sim.snapshot();
        if let Err(e) = sim.advance(t_next - sim.time()) {
            // The contract: a failed step is a StepFailed and keeps the state before the step.
            assert!(matches!(e, ModelError::StepFailed { .. }), "{e}");
            assert!(
                sim.snapshot() == before,
                "state changed by a failed step: {e}"
            );
            error = Some(e);
            break;
        }
        for w in sim.take_warnings() {
            record.warnings.push((t_next, w));
        }
        visit(&sim);
        if !keep_all && record.times.len() > 1 {
            record.times.pop();
            record.inputs.pop();
            record.outputs.pop();
        }
        record.times.push(t_next);
        record.inputs.push(input(k + 1, t_next));
        record.outputs.push(sim.outputs());
    }
    record.stats = sim.stats();
    Run { record, error, sim }
}

/// [`drive_visit`] without a visitor.
pub fn drive_inputs(
    scene: &Scene,
    times: &[f64],
    slider_force: f64,
    input: impl FnMut(usize, f64) -> CrankInput,
) -> Run {
    drive_visit(scene, times, slider_force, input, |_| {})
}

/// [`drive_visit`] with a crank law.
pub fn drive_law(scene: &Scene, law: &CrankDrive, slider_force: f64, times: &[f64]) -> Run {
    drive_inputs(scene, times, slider_force, |_, t| law.at(t))
}

/// Constant speed from t = 0 over `steps` communication steps of `dt`, failures allowed.
pub fn drive_constant(scene: &Scene, speed: f64, dt: f64, steps: usize, slider_force: f64) -> Run {
    drive_law(
        scene,
        &CrankDrive::Constant { speed },
        slider_force,
        &communication_grid(0.0, dt, steps),
    )
}

/// Largest |x|.
pub fn peak(x: &[f64]) -> f64 {
    x.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

/// Largest |a_i - b_i| (same length).
pub fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len(), "series of different length");
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

/// Largest pointwise |delta v_mid/L| relative to the reference's peak (docs/physics.md, "How error
/// is measured"), on the same communication points.
pub fn deflection_error(record: &Record, reference: &Record) -> f64 {
    assert_eq!(record.times.len(), reference.times.len(), "different grids");
    max_diff(&record.deflection_rel(), &reference.deflection_rel())
        / reference.peak_deflection_rel()
}

/// Largest |F_B|, N.
pub fn peak_pin_b_force(record: &Record) -> f64 {
    record
        .outputs
        .iter()
        .map(|o| o.pin_b_force[0].hypot(o.pin_b_force[1]))
        .fold(0.0, f64::max)
}

/// Start `sim` at constant crank speed `speed`, rad/s, from angle 0 at t = 0.
pub fn start_at(sim: &mut Simulation, speed: f64) {
    sim.start(
        0.0,
        CrankInput {
            angle: 0.0,
            speed,
            acceleration: 0.0,
            jerk: 0.0,
        },
        0.0,
    )
    .expect("starts");
}

/// The automotive scene with Young's modulus (shear modulus `E / 2.6`), element count and
/// reference conditions changed, each within its declared range: a soft rod puts many modes,
/// axial ones among them, into its 6 kHz mode band.
pub fn automotive_with(youngs_modulus: f64, elements: usize, reference: &str) -> Scene {
    let path = super::fragments::repository().join("scenes/automotive_rod.toml");
    let text = std::fs::read_to_string(path).unwrap().replace(
        "reference = \"simply_supported\"",
        &format!("reference = \"{reference}\""),
    );
    let mut s = Scene::from_toml_str(&text, "automotive").unwrap();
    s.rod.youngs_modulus = youngs_modulus;
    s.rod.shear_modulus = Some(youngs_modulus / 2.6);
    s.rod.elements = elements;
    s
}
