//! The engine run of the automotive rod (`scenes/automotive_rod.toml`): the crank ramps from
//! rest to full speed, then turns two revolutions while a gas-force pulse hits the slider after
//! the first top dead centre at full speed; the section forces, the stress at L/2, the pin
//! forces and the midpoint deflection are recorded on a fixed grid. The same run as the
//! independent reference `tests/data/exudyn_automotive_rod.csv` (written by
//! `tests/data/automotive_reference.py`), and [`EngineErrors`] measures a run against it:
//! `tests/automotive_reference.rs` and the report's engine section use this module.

use std::time::{Duration, Instant};

use super::law::CrankDrive;
use crate::error::ModelError;
use crate::mechanism::gas_force::GasForceTable;
use crate::scene::Scene;
use crate::simulation::Simulation;

/// One recorded row: t (s), v_mid/L, F_B x, y (N), F_C x, y (N), N_mid (N), M_mid (N m), stress
/// at L/2 (Pa, `|N| / A + |M| c / I` with the section interpolated at L/2). The reference CSV
/// has the same columns.
pub type EngineRow = [f64; 9];

/// The run: ramp, full speed, gas pulse, communication step and sampling.
#[derive(Clone, Copy, Debug)]
pub struct EngineRun {
    /// Full crank speed, rad/s.
    pub speed: f64,
    /// Length of the smooth start ramp from rest, s.
    pub ramp: f64,
    /// End of the run, s.
    pub stop: f64,
    /// Communication step, s.
    pub step: f64,
    /// Sampling interval of the rows, s (a multiple of `step`).
    pub sample: f64,
    /// Peak gas force on the slider, N (negative: towards the crank).
    pub peak_force: f64,
    /// Crank angle of the gas peak, rad (from the start), and the pulse's 1/e half-width, rad.
    pub firing_angle: f64,
    pub width: f64,
}

impl EngineRun {
    /// The automotive rod's run (tests/data/automotive_reference.py): ramp to 628.3 rad/s (6000
    /// rpm) over 40 ms, stop at 60 ms, communication step 1e-5 s, rows every 2e-5 s, a 38 kN
    /// Gaussian pulse 15 degrees after the first top dead centre at full speed (crank angle
    /// `4 pi + 15 deg`), half-width 20 degrees.
    pub fn automotive() -> EngineRun {
        EngineRun {
            speed: 628.3,
            ramp: 0.04,
            stop: 0.06,
            step: 1e-5,
            sample: 2e-5,
            peak_force: -38.0e3,
            firing_angle: 4.0 * std::f64::consts::PI + 15f64.to_radians(),
            width: 20f64.to_radians(),
        }
    }

    /// The crank law.
    pub fn law(&self) -> CrankDrive {
        CrankDrive::Ramp {
            speed: self.speed,
            time: self.ramp,
        }
    }

    /// The gas force at crank angle `theta` (rad), N: `F_peak exp(-((theta - theta_f) / w)^2)`.
    pub fn gas(&self, theta: f64) -> f64 {
        let d = (theta - self.firing_angle) / self.width;
        self.peak_force * (-d * d).exp()
    }

    /// Time of the gas peak, s (at full speed after the ramp, which turns the crank by
    /// `speed ramp / 2`).
    pub fn firing_time(&self) -> f64 {
        self.ramp + (self.firing_angle - 0.5 * self.speed * self.ramp) / self.speed
    }

    /// The gas pulse as a `[slider.gas_force]` table: [`EngineRun::gas`] sampled every half
    /// degree over a cycle of 1440 degrees (the run's four revolutions, so that the pulse comes
    /// once, at the firing angle, as in the reference).
    pub fn gas_table(&self) -> GasForceTable {
        let (cycle, spacing) = (1440.0, 0.5);
        let angle: Vec<f64> = (0..(cycle / spacing) as usize)
            .map(|i| i as f64 * spacing)
            .collect();
        GasForceTable {
            cycle,
            force: angle.iter().map(|a| self.gas(a.to_radians())).collect(),
            angle,
            scale: 1.0,
        }
    }

    /// Run `scene` (its rod needs a section table with fibre distances, or a uniform section
    /// with `[outputs] stress`): the crank input at each communication point continues the law
    /// in force ([`continued`]: the drive's speed at the points, no projection of the state),
    /// the gas force held over each communication step at its mid-step value. Returns the rows,
    /// the wall time of the run (`Simulation::new` excluded) and the integrator's name.
    pub fn run(&self, scene: &Scene) -> Result<(Vec<EngineRow>, Duration, String), ModelError> {
        self.run_on_grid(scene, self.step, self.step, self.sample, true, false)
    }

    /// The same run with the gas force inside the model, as the table [`EngineRun::gas_table`]
    /// (`[slider.gas_force]`: a function of the crank angle, followed through every internal
    /// step), on the communication step `step` (s, a divisor of the run's length), a row at
    /// every communication point.
    pub fn run_with_gas_table(
        &self,
        scene: &Scene,
        step: f64,
    ) -> Result<(Vec<EngineRow>, Duration, String), ModelError> {
        let mut scene = scene.clone();
        scene.slider.gas_force = Some(self.gas_table());
        self.run_on_grid(&scene, step, step, step, false, false)
    }

    /// The run as a co-simulation master with input derivatives drives it: the gas force inside
    /// the model as [`EngineRun::run_with_gas_table`], the crank input set every `input_step` s
    /// only (angle, speed, acceleration and jerk: [`CrankInput::continued_smoothly`], the speed following
    /// the drive through each step), and a row every `sample` s (a communication point
    /// that sets no input, so the integrator holds its steps across it). `input_step` a
    /// multiple of `sample`, both divisors of the run's length.
    pub fn run_with_sparse_input(
        &self,
        scene: &Scene,
        input_step: f64,
        sample: f64,
    ) -> Result<(Vec<EngineRow>, Duration, String), ModelError> {
        let mut scene = scene.clone();
        scene.slider.gas_force = Some(self.gas_table());
        self.run_on_grid(&scene, sample, input_step, sample, false, true)
    }

    /// The run on the communication step `step`, the crank input set every `input_step` s (a
    /// multiple of `step`), a row every `sample` s (a multiple of `step`); `held_gas`: the pulse
    /// through `slider.force`, held over each communication step at its mid-step value;
    /// `smooth`: the input continued with a jerk ([`CrankInput::continued_smoothly`]), else with a constant
    /// acceleration ([`continued`]).
    fn run_on_grid(
        &self,
        scene: &Scene,
        step: f64,
        input_step: f64,
        sample: f64,
        held_gas: bool,
        smooth: bool,
    ) -> Result<(Vec<EngineRow>, Duration, String), ModelError> {
        let law = self.law();
        let (area, moment, fibre) = section_at_half(scene);
        let mut sim = Simulation::new(scene)?;
        let clock = Instant::now();
        sim.start(0.0, law.at(0.0), 0.0)?;
        let row = |sim: &Simulation, t: f64| -> EngineRow {
            let o = sim.outputs();
            let (n, m) = (o.section.axial_force_mid, o.section.bending_moment_mid);
            [
                t,
                o.deflection_rel,
                o.pin_b_force[0],
                o.pin_b_force[1],
                o.pin_c_force[0],
                o.pin_c_force[1],
                n,
                m,
                n.abs() / area + m.abs() * fibre / moment,
            ]
        };
        let mut rows = vec![row(&sim, 0.0)];
        let n = (self.stop / step).round() as usize;
        let every = ((sample / step).round() as usize).max(1);
        let input_every = ((input_step / step).round() as usize).max(1);
        let (mut input, mut input_time) = (law.at(0.0), 0.0);
        for k in 0..n {
            let t = k as f64 * step;
            if k % input_every == 0 {
                let h = (input_every as f64 * step).min(self.stop - t);
                let (s, speed) = (sim.time() - input_time, law.at(t + h).speed);
                input = if smooth {
                    input.continued_smoothly(s, law.at(t).acceleration, speed, h)
                } else {
                    input.continued(s, speed, h)
                };
                input_time = sim.time();
                sim.set_input(input)?;
            }
            if held_gas {
                sim.set_slider_force(self.gas(law.at(t + 0.5 * step).angle))?;
            }
            sim.advance(step)?;
            if (k + 1) % every == 0 {
                rows.push(row(&sim, (k + 1) as f64 * step));
            }
        }
        let (name, _) = sim.mechanism().integrator_name();
        Ok((rows, clock.elapsed(), name.to_string()))
    }
}

/// Area, area moment and fibre distance at L/2 (linear between the scene's stations; the
/// uniform section without a table).
fn section_at_half(scene: &Scene) -> (f64, f64, f64) {
    let stations = &scene.rod.section;
    let half = 0.5 * scene.rod.length;
    if stations.len() < 2 {
        let c = stations
            .first()
            .and_then(|s| s.fibre_distance)
            .unwrap_or(0.0);
        return (scene.rod.area, scene.rod.area_moment, c);
    }
    let k = stations
        .partition_point(|s| s.position <= half)
        .clamp(1, stations.len() - 1);
    let (a, b) = (&stations[k - 1], &stations[k]);
    let u = (half - a.position) / (b.position - a.position);
    let lerp = |x: f64, y: f64| x + u * (y - x);
    (
        lerp(a.area, b.area),
        lerp(a.area_moment, b.area_moment),
        lerp(
            a.fibre_distance.unwrap_or(0.0),
            b.fibre_distance.unwrap_or(0.0),
        ),
    )
}

/// Read a reference CSV (`#` comments, a header line starting with `t`, 9 columns as
/// [`EngineRow`]), at most [`crate::limits::CSV_FILE_CAP`] bytes.
pub fn read_reference(path: &std::path::Path) -> Result<Vec<EngineRow>, String> {
    let text = crate::limits::read_text(path, crate::limits::CSV_FILE_CAP, "the reference table")?;
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with('t') && !l.trim().is_empty())
        .map(|l| {
            let v: Result<Vec<f64>, _> = l.split(',').map(|x| x.trim().parse::<f64>()).collect();
            let v =
                v.map_err(|e| format!("{}: '{}': {e}", path.display(), crate::text::echo(l)))?;
            v.try_into().map_err(|_| {
                format!(
                    "{}: '{}': expected 9 columns",
                    path.display(),
                    crate::text::echo(l)
                )
            })
        })
        .collect()
}

/// Largest pointwise differences of a run from a reference, relative to the reference's peak.
#[derive(Clone, Copy, Debug, Default)]
pub struct EngineErrors {
    pub deflection: f64,
    pub stress: f64,
    pub axial: f64,
    pub moment: f64,
    /// `|F_B - F_B,ref|` (vector) over the run / `max |F_B,ref|`.
    pub pin_b: f64,
    pub pin_c: f64,
    /// The same from 60 degrees before to 120 degrees after the gas peak.
    pub pin_b_firing: f64,
    pub pin_c_firing: f64,
}

impl EngineErrors {
    /// Compare `run` with `reference` (the same grid; panics otherwise: a programming error).
    pub fn new(run: &[EngineRow], reference: &[EngineRow], setup: &EngineRun) -> EngineErrors {
        assert_eq!(run.len(), reference.len(), "run and reference grids differ");
        let peak = |f: &dyn Fn(&EngineRow) -> f64| reference.iter().map(f).fold(0.0, f64::max);
        let fire = setup.firing_time();
        let (before, after) = (60f64.to_radians() / setup.speed, 2.0 / setup.speed);
        let worst = |f: &dyn Fn(&EngineRow, &EngineRow) -> f64, window: bool| {
            run.iter()
                .zip(reference)
                .filter(|(r, _)| !window || (r[0] > fire - before && r[0] < fire + after))
                .map(|(a, b)| f(a, b))
                .fold(0.0, f64::max)
        };
        let col = |i: usize| {
            worst(&|a, b| (a[i] - b[i]).abs(), false) / peak(&|r: &EngineRow| r[i].abs())
        };
        let pin = |i: usize, window: bool| {
            worst(&|a, b| (a[i] - b[i]).hypot(a[i + 1] - b[i + 1]), window)
                / peak(&|r: &EngineRow| r[i].hypot(r[i + 1]))
        };
        EngineErrors {
            deflection: col(1),
            stress: col(8),
            axial: col(6),
            moment: col(7),
            pin_b: pin(2, false),
            pin_c: pin(4, false),
            pin_b_firing: pin(2, true),
            pin_c_firing: pin(4, true),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanism::CrankLaw;

    /// The continued input follows the ramp: the speed at every communication point to
    /// round-off, the angle within `alpha_max h^2 / 12`; and each input starts where the law in
    /// force is at that time (the same angle and speed as `CrankLaw::kinematics`).
    #[test]
    fn continued_input_follows_the_drive() {
        let run = EngineRun::automotive();
        let law = run.law();
        let h = run.step;
        let alpha_max = 0.5 * run.speed * std::f64::consts::PI / run.ramp;
        let (mut input, mut worst_angle, mut worst_speed) = (law.at(0.0), 0.0f64, 0.0f64);
        for k in 0..(run.stop / h).round() as usize {
            let t = k as f64 * h;
            let t_input = k.saturating_sub(1) as f64 * h;
            let next = input.continued(t - t_input, law.at(t + h).speed, h);
            if k > 0 {
                let (angle, speed, _) = CrankLaw {
                    length: run.speed,
                    t_k: t_input,
                    input,
                }
                .kinematics(t);
                assert_eq!((next.angle, next.speed), (angle, speed), "t = {t}");
            }
            let exact = law.at(t);
            worst_angle = worst_angle.max((next.angle - exact.angle).abs());
            worst_speed = worst_speed.max((next.speed - exact.speed).abs());
            input = next;
        }
        assert!(worst_speed < 1e-9 * run.speed, "speed off by {worst_speed}");
        assert!(
            worst_angle <= 1.01 * alpha_max * h * h / 12.0,
            "angle off by {worst_angle}"
        );
    }
}
