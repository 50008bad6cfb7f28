//! The run loop: start the simulation at the first communication point, then at each point
//! `t_k` set the crank input `drive.at(t_k)` and advance to `t_{k+1}`, recording the outputs.

use super::law::CrankDrive;
use crate::error::ModelError;
use crate::mechanism::{CrankInput, Outputs, StepStats};
use crate::scene::Scene;
use crate::simulation::Simulation;

/// What a run recorded, one entry per communication point (the start included).
#[derive(Clone, Debug, Default)]
pub struct Record {
    /// Communication points, s.
    pub times: Vec<f64>,
    /// The crank input at each point.
    pub inputs: Vec<CrankInput>,
    /// The outputs at each point.
    pub outputs: Vec<Outputs>,
    /// The integrator's counters at the end.
    pub stats: StepStats,
    /// Warnings, with the communication point after which they were raised.
    pub warnings: Vec<(f64, String)>,
}

impl Record {
    /// Largest `|v_mid / L|` over the record.
    pub fn peak_deflection_rel(&self) -> f64 {
        self.outputs
            .iter()
            .map(|o| o.deflection_rel.abs())
            .fold(0.0, f64::max)
    }

    /// `v_mid / L` at each point.
    pub fn deflection_rel(&self) -> Vec<f64> {
        self.outputs.iter().map(|o| o.deflection_rel).collect()
    }
}

/// `t0, t0 + dt, ..., t0 + steps dt` (each point computed from `t0`, no accumulation).
pub fn communication_grid(t0: f64, dt: f64, steps: usize) -> Vec<f64> {
    (0..=steps).map(|k| t0 + k as f64 * dt).collect()
}

/// Drive `simulation` by `drive` over the communication points `times` (at least one), with a
/// constant slider force: start at `times[0]`, then step from point to point. A failed step
/// ends the run with its error (the simulation keeps the state before that step).
pub fn run(
    simulation: &mut Simulation,
    drive: &CrankDrive,
    slider_force: f64,
    times: &[f64],
) -> Result<Record, ModelError> {
    let t0 = *times.first().ok_or_else(|| ModelError::InvalidParameter {
        name: "communication points",
        value: 0.0,
        allowed: "at least one".into(),
    })?;
    simulation.start(t0, drive.at(t0), slider_force)?;
    // Sized once: the record grows without reallocating.
    let mut record = Record {
        times: Vec::with_capacity(times.len()),
        inputs: Vec::with_capacity(times.len()),
        outputs: Vec::with_capacity(times.len()),
        ..Default::default()
    };
    record.times.push(t0);
    record.inputs.push(drive.at(t0));
    record.outputs.push(simulation.outputs());
    for pair in times.windows(2) {
        let t_next = pair[1];
        // The input at t_k, recorded at the end of the previous step (or the start).
        let input = *record.inputs.last().expect("the start is recorded");
        simulation.set_input(input)?;
        simulation.advance(t_next - simulation.time())?;
        for w in simulation.take_warnings() {
            record.warnings.push((t_next, w));
        }
        record.times.push(t_next);
        record.inputs.push(drive.at(t_next));
        record.outputs.push(simulation.outputs());
    }
    record.stats = simulation.stats();
    Ok(record)
}

/// Build `scene`'s simulation and run it at constant crank speed `speed` from `t = 0` for
/// `revolutions` crank revolutions at communication step `dt` (the number of steps rounded);
/// `rod.model = auto` chooses for `speed` where the scene gives no `crank.design_speed`.
pub fn run_constant(
    scene: &Scene,
    speed: f64,
    dt: f64,
    revolutions: f64,
) -> Result<(Record, Simulation), ModelError> {
    // `rod.model = auto` chooses for this speed unless the scene names its design speed.
    let mut scene = scene.clone();
    scene.take_design_speed(speed);
    let mut simulation = Simulation::new(&scene)?;
    let steps = (revolutions * 2.0 * std::f64::consts::PI / speed.abs() / dt).round() as usize;
    let record = run(
        &mut simulation,
        &CrankDrive::Constant { speed },
        0.0,
        &communication_grid(0.0, dt, steps),
    )?;
    Ok((record, simulation))
}
