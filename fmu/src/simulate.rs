//! The scene's default experiment, run in-process with `flexrod::Simulation`, driving the
//! crank as an FMU importer does: at every communication point t_k the crank input
//! (theta_k, omega_k, alpha) is set, then the simulation advances to t_{k+1}.
//!
//! The communication points follow FMPy's `simulate_fmu` (and the Python tests): fixed
//! steps at `start + (k+1) dt`, the last one shortened to end at the stop time; with
//! `--steps`, t_{k+1} = t_k + h_(k mod n). Crank law from `t = 0`:
//! `theta = omega_0 t + 0.5 alpha t t`, `omega = omega_0 + alpha t`.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use flexrod::drive::{self, CrankDrive};
use flexrod::model::variables::{OutputGetter, VariableTable};
use flexrod::text::number;
use flexrod::{Outputs, Scene, Simulation, StepStats};

/// How the experiment is driven.
pub struct Options {
    /// Constant crank acceleration, rad/s^2 (supplied as the input derivative).
    pub accel: f64,
    /// Communication steps to cycle through (default: the scene's fixed step).
    pub steps: Option<Vec<f64>>,
}

/// The results at the communication points.
pub struct Run {
    pub times: Vec<f64>,
    pub outputs: Vec<Outputs>,
    pub stats: StepStats,
    pub wall_seconds: f64,
    pub frequencies_hz: Vec<f64>,
    /// The integrator used and what its iteration counter counts.
    pub integrator: (&'static str, &'static str),
    /// The rod as built and what it retains (`Simulation::rod_summary`).
    pub rod: String,
    /// The model class the `auto` settings chose, and why.
    pub model_class: String,
    /// The warnings of the run, with the communication point after which they came.
    pub warnings: Vec<(f64, String)>,
}

fn isclose(a: f64, b: f64) -> bool {
    // Python's math.isclose with its defaults, as FMPy uses it.
    a == b || (a - b).abs() <= 1e-9 * a.abs().max(b.abs())
}

/// Refuse an experiment `start..stop` whose communication points (at the fixed step `dt`, or
/// cycling through `steps`) would be more than [`flexrod::limits::MAX_POINTS`] (the check
/// `flexrod simulate` makes too); returns what sets the steps, for messages.
pub fn check_length(
    start: f64,
    stop: f64,
    dt: f64,
    steps: Option<&[f64]>,
) -> Result<String, String> {
    let span = stop - start;
    let (what, needed) = match steps {
        None => (
            format!("the scene's step_size {} s", number(dt)),
            (span / dt).ceil() + 1.0,
        ),
        Some(steps) => {
            let list: Vec<String> = steps.iter().map(|&h| number(h)).collect();
            let cycle: f64 = steps.iter().sum();
            (
                format!("--steps {}", flexrod::text::echo(&list.join(","))),
                (span / cycle).ceil() * steps.len() as f64 + 1.0,
            )
        }
    };
    flexrod::limits::check_points(
        &format!(
            "{what} over the experiment {} .. {} s",
            number(start),
            number(stop)
        ),
        needed,
    )?;
    Ok(what)
}

/// The communication points of the experiment `start..stop` as FMPy's `simulate_fmu` steps:
/// `start + (k+1) dt`, the last one shortened to end at `stop`; with `steps`,
/// `t_{k+1} = t_k + h_(k mod n)`. Refused before anything is allocated where they would be too
/// many ([`check_length`]), and where a step is too small to advance the time.
pub fn communication_points(
    start: f64,
    stop: f64,
    dt: f64,
    steps: Option<&[f64]>,
) -> Result<Vec<f64>, String> {
    let what = check_length(start, stop, dt, steps)?;
    let mut times = vec![start];
    let mut time = start;
    let mut n: usize = 0;
    while !(time > stop || isclose(time, stop)) {
        let mut next = match steps {
            None => start + (n + 1) as f64 * dt,
            Some(steps) => time + steps[n % steps.len()],
        };
        if next > stop && !isclose(next, stop) {
            next = stop;
        }
        if next <= time {
            return Err(format!(
                "{what}: the step at t = {} s does not advance the time (below its resolution there)",
                flexrod::text::time(time)
            ));
        }
        time = next;
        n += 1;
        times.push(time);
    }
    Ok(times)
}

/// Run the default experiment of `scene`: constant crank acceleration `options.accel` from
/// the scene's crank speed at `t = 0` (`flexrod::drive::CrankDrive::UniformAcceleration`).
pub fn run(scene: &Scene, options: &Options) -> Result<Run, String> {
    let e = &scene.experiment;
    let times = communication_points(
        e.start_time,
        e.stop_time,
        e.step_size,
        options.steps.as_deref(),
    )?;
    let law = CrankDrive::UniformAcceleration {
        speed: e.crank_speed,
        acceleration: options.accel,
    };
    let clock = Instant::now();
    let mut simulation = Simulation::new(scene).map_err(|e| e.to_string())?;
    let record = drive::run(&mut simulation, &law, 0.0, &times).map_err(|e| e.to_string())?;
    Ok(Run {
        times: record.times,
        outputs: record.outputs,
        stats: record.stats,
        wall_seconds: clock.elapsed().as_secs_f64(),
        frequencies_hz: simulation.frequencies_hz().to_vec(),
        integrator: simulation.mechanism().integrator_name(),
        rod: simulation.rod_summary(),
        model_class: simulation.mechanism().physics.describe(),
        warnings: record.warnings,
    })
}

/// CSV with `time` and the FMU's outputs (names from the variable table), full precision.
pub fn write_csv(path: &Path, table: &VariableTable, run: &Run) -> Result<(), String> {
    let columns: Vec<(&str, OutputGetter)> = table.outputs().collect();
    let mut text = String::from("time");
    for (name, _) in &columns {
        text.push(',');
        text.push_str(name);
    }
    text.push('\n');
    for (t, o) in run.times.iter().zip(&run.outputs) {
        let _ = write!(text, "{t:e}");
        for (_, get) in &columns {
            let _ = write!(text, ",{:e}", get(o));
        }
        text.push('\n');
    }
    std::fs::write(path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))
}

/// A few lines a user reads first.
pub fn print_summary(scene: &Scene, run: &Run, fmu: Option<&Path>) {
    let peak = |f: &dyn Fn(&Outputs) -> f64| {
        run.outputs
            .iter()
            .map(f)
            .fold(0.0_f64, |m, x| m.max(x.abs()))
    };
    let norm = |v: [f64; 2]| v[0].hypot(v[1]);
    let e = &scene.experiment;
    println!(
        "{}: t = {} .. {} s, {} communication steps, crank speed {} rad/s",
        scene.name,
        flexrod::text::time(e.start_time),
        flexrod::text::time(e.stop_time),
        run.times.len() - 1,
        e.crank_speed
    );
    let f: Vec<String> = run
        .frequencies_hz
        .iter()
        .take(3)
        .map(|f| format!("{f:.2}"))
        .collect();
    println!("  lowest natural frequencies: {} Hz", f.join(", "));
    println!(
        "  peak |v_mid / L|        = {:.4e}",
        peak(&|o| o.deflection_rel)
    );
    println!(
        "  peak |v_mid|            = {:.4e} m",
        peak(&|o| o.deflection)
    );
    println!(
        "  peak |pin B force|      = {:.4} N",
        peak(&|o| norm(o.pin_b_force))
    );
    println!(
        "  peak |pin C force|      = {:.4} N",
        peak(&|o| norm(o.pin_c_force))
    );
    println!(
        "  peak |crank torque|     = {:.4} N m",
        peak(&|o| o.crank_torque)
    );
    println!(
        "  integrator: {}, {} steps, {} {} ({:.2} per step), {} halvings",
        run.integrator.0,
        run.stats.steps,
        run.stats.newton_iterations,
        run.integrator.1,
        run.stats.newton_iterations as f64 / (run.stats.steps.max(1)) as f64,
        run.stats.halvings
    );
    println!("  rod: {}", run.rod);
    println!("  model class: {}", run.model_class);
    if let Some(last) = run.outputs.last() {
        println!(
            "  rod.error_estimate at the end: {:.2e} of the peak |v_mid / L| (solver.tolerance {:e})",
            last.error_estimate, scene.solver.tolerance
        );
    }
    for (t, w) in &run.warnings {
        println!("  warning after t = {} s: {w}", flexrod::text::time(*t));
    }
    println!("  wall time: {:.3} s", run.wall_seconds);
    if let Some(fmu) = fmu {
        println!("  FMU: {}", fmu.display());
    }
}
