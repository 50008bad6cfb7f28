//! `flexrod`: the command-line tool of the core.
//!
//! - `flexrod modes [SCENE] [--csv FILE]`: the rod's frequency table and mode shapes: the modes
//!   the simulation uses (mass-loaded or free), which are retained and which are static
//!   corrections.
//! - `flexrod simulate [SCENE] [--speed W] [--revolutions N] [--ramp T] [--step H] [--input CSV]
//!   [--out CSV] [--plot PREFIX]`: simulate the slider-crank, write every output at each
//!   communication point, and plot v_mid/L and the pin forces against the crank angle in
//!   degrees (PREFIX_deflection.svg, PREFIX_forces.svg).
//!
//! `flexrod --help` and `flexrod COMMAND --help` describe every option. Exit codes: 0 done,
//! 1 the model or a file failed, 2 a bad command line (unknown option, value out of range).

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::error::ErrorKind;
use clap::{CommandFactory, Parser, Subcommand};

mod svg_plot;

use flexrod::drive::{self, communication_grid, CrankDrive};
use flexrod::limits::{self, CSV_FILE_CAP};
use flexrod::modal::shape_integrals::point_shape;
use flexrod::modal::{ComponentModes, ModeSelection, ReferenceConditions};
use flexrod::rod::ffr::residual::residual_indices;
use flexrod::rod::ffr_mode_choice;
use flexrod::scene::{RodModelKind, Scene};
use flexrod::text::{number, time};
use flexrod::Simulation;

#[derive(Parser)]
#[command(
    name = "flexrod",
    version,
    about = "The flexible connecting rod in a planar slider-crank: mode tables and simulations of a scene",
    long_about = None,
    after_help = "SCENE is a scene file (TOML, see scenes/); without one the built-in benchmark scene is used.\n\
                  Exit codes: 0 done, 1 the model or a file failed, 2 a bad command line."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Print the rod's natural frequencies as the simulation uses them (mass-loaded or free;
    /// bending or axial; retained, static correction or left out) and write its mode shapes.
    Modes(ModesArgs),
    /// Simulate the slider-crank: print a summary, write every output at each communication
    /// point, plot v_mid/L and the pin forces against the crank angle.
    Simulate(SimulateArgs),
}

#[derive(clap::Args)]
struct ModesArgs {
    /// Scene file (TOML); default: the built-in benchmark scene.
    scene: Option<PathBuf>,
    /// Write the mode shapes (unit modal mass, body frame) to FILE: columns s_m, then
    /// axial_K, transverse_K for each mode K.
    #[arg(long, value_name = "FILE")]
    csv: Option<PathBuf>,
}

#[derive(clap::Args)]
#[command(
    allow_negative_numbers = true,
    after_help = "The run starts at the scene's start_time and ends at its stop_time, or after N crank \
                  revolutions at the --speed (counted from t = 0, the --ramp's slower start included) with \
                  --revolutions; it records at most \
                  10^7 communication points ((stop - start) / step). With --input the table drives the \
                  crank: --speed, --revolutions and --ramp are refused with it. Files read: a scene of at \
                  most 16 MiB, an --input table of at most 256 MiB and 10^7 rows."
)]
struct SimulateArgs {
    /// Scene file (TOML); default: the built-in benchmark scene.
    scene: Option<PathBuf>,
    /// Crank speed W, rad/s, any finite value (default: the scene's experiment crank_speed).
    /// Not with --input, whose table gives the speed.
    #[arg(long, value_name = "RAD_PER_S", value_parser = finite, conflicts_with = "input")]
    speed: Option<f64>,
    /// Stop after N crank revolutions at the --speed (N > 0, finite; default: the scene's
    /// stop_time). Not with --input: the run ends at the scene's stop_time, the table
    /// gives the crank's turns.
    #[arg(long, value_name = "N", value_parser = positive, conflicts_with = "input")]
    revolutions: Option<f64>,
    /// Start from rest and ramp the crank speed smoothly up to W over SECONDS (> 0, finite):
    /// omega = W (1 - cos(pi t / T)) / 2. Default: constant speed W from the start.
    #[arg(long, value_name = "SECONDS", value_parser = positive, conflicts_with = "input")]
    ramp: Option<f64>,
    /// Communication step, s (> 0, finite; default: the scene's step_size).
    #[arg(long, value_name = "SECONDS", value_parser = positive)]
    step: Option<f64>,
    /// Drive the crank by a table: CSV rows t (s), angle (rad), speed (rad/s), linear between
    /// rows; before the first row and after the last the crank turns at that row's speed (a
    /// warning says so: extend the table over the whole run).
    #[arg(long, value_name = "CSV")]
    input: Option<PathBuf>,
    /// Write the outputs at each communication point to CSV: time, crank_angle, crank_speed,
    /// deflection, deflection_rel, pinB_force_x, pinB_force_y, pinC_force_x, pinC_force_y,
    /// crank_torque, slider_position, slider_velocity, and with the scene's [outputs]
    /// stress = true also axial_force_mid (N), bending_moment_mid (N m), stress_max (Pa),
    /// stress_max_position (m from B).
    #[arg(long, value_name = "CSV")]
    out: Option<PathBuf>,
    /// Write the plots PREFIX_deflection.svg and PREFIX_forces.svg (against the crank angle,
    /// degrees).
    #[arg(long, value_name = "PREFIX")]
    plot: Option<String>,
}

/// A number that is finite.
fn finite(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err("not finite: allowed any finite number".into()),
        Err(_) => Err("not a number: allowed any finite number".into()),
    }
}

/// A number that is finite and > 0.
fn positive(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        Ok(_) => Err("out of range: allowed a finite number > 0".into()),
        Err(_) => Err("not a number: allowed a finite number > 0".into()),
    }
}

/// Why a command failed: its command line (exit code 2) or the run (exit code 1).
enum Failure {
    Usage(String),
    Run(String),
}

impl From<String> for Failure {
    fn from(message: String) -> Self {
        Failure::Run(message)
    }
}

/// The command line, or exit: help and version to stdout with exit code 0, a bad command line
/// to stderr with exit code 2, each line of the message cut to a bounded echo (a value
/// quoted from the command line).
fn parse() -> Cli {
    Cli::try_parse().unwrap_or_else(|e| {
        let text = e.render().to_string();
        if e.use_stderr() {
            eprintln!("{}", flexrod::text::echo_lines(text.trim_end()));
        } else {
            print!("{text}");
        }
        std::process::exit(e.exit_code())
    })
}

fn main() -> ExitCode {
    let cli = parse();
    let (name, result) = match &cli.command {
        Command::Modes(args) => ("modes", modes(args)),
        Command::Simulate(args) => ("simulate", simulate(args)),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Usage(message)) => {
            let mut command = Cli::command();
            // Built, so that the usage line names the binary with the subcommand.
            command.build();
            let command = command
                .find_subcommand_mut(name)
                .expect("the subcommand exists");
            command.error(ErrorKind::ValueValidation, message).exit()
        }
        Err(Failure::Run(message)) => {
            eprintln!("flexrod {name}: error: {message}");
            ExitCode::FAILURE
        }
    }
}

fn load_scene(path: Option<&Path>) -> Result<Scene, String> {
    match path {
        Some(path) => Scene::from_file(path).map_err(|e| e.to_string()),
        None => Ok(Scene::benchmark()),
    }
}

fn modes(args: &ModesArgs) -> Result<(), Failure> {
    let scene = load_scene(args.scene.as_deref())?;
    let spec = scene.mechanism_spec();
    spec.validate().map_err(|e| e.to_string())?;
    // The rod as the model builds it: the `auto` settings resolved (the rod model for the
    // design speed too), section table, shear deformation and end bodies included.
    let (rod, choice) = spec.choose_physics().map_err(|e| e.to_string())?;
    if rod.model != RodModelKind::Ffr {
        let sim = Simulation::new(&scene).map_err(|e| e.to_string())?;
        println!("{}", choice.describe());
        println!("mode  frequency_hz");
        for (k, f) in sim.frequencies_hz().iter().enumerate() {
            println!("{:>4}  {f:.4}", k + 1);
        }
        return Ok(());
    }
    println!("{}", choice.describe());
    let definition = rod.definition().map_err(|e| e.to_string())?;
    let reference =
        ReferenceConditions::from_kind(rod.reference, rod.elements).map_err(|e| e.to_string())?;
    // The modes the simulation uses: the same eigenproblem (mass-loaded with rod.loaded_modes)
    // and the same selection (the band rod.mode_band_hz, else rod.modes lowest plus
    // rod.axial_modes), the bending modes left out as static corrections.
    let (selection, added) = ffr_mode_choice(&rod, scene.slider.mass);
    let all = ComponentModes::from_definition_loaded(
        definition,
        rod.elements,
        reference,
        rod.mass,
        &ModeSelection::Cutoff {
            max_hz: f64::INFINITY,
        },
        &added,
    )
    .map_err(|e| e.to_string())?;
    let kept = selection
        .select_classified(&all.all_frequencies_hz, &all.all_axial_shares)
        .map_err(|e| e.to_string())?;
    let corrections = residual_indices(&all, &kept);
    let eigenproblem = match rod.loaded_modes {
        true => format!(
            "mass-loaded modes (rod.loaded_modes: slider.mass = {} kg at C in the eigenproblem)",
            scene.slider.mass
        ),
        false => "free modes".to_string(),
    };
    let chosen = match rod.mode_band_hz {
        Some(band) => format!(
            "every mode up to rod.mode_band_hz = {band} Hz; {} bending modes above it as static corrections to v_mid",
            corrections.len()
        ),
        None if rod.axial_in_addition => format!(
            "rod.modes = {} bending modes, the axial modes in their band and at least {} axial in addition; {} bending modes left out as static corrections to v_mid",
            rod.modes,
            rod.min_axial_modes(scene.slider.mass),
            corrections.len()
        ),
        None => format!(
            "rod.modes = {}, at least {} axial; {} bending modes left out as static corrections to v_mid",
            rod.modes,
            rod.min_axial_modes(scene.slider.mass),
            corrections.len()
        ),
    };
    println!(
        "scene {}: rod.elements = {}, rod.reference = {}, rod.mass = {}, {eigenproblem}; {} modes retained of {} ({chosen})",
        scene.name,
        rod.elements,
        rod.reference.name(),
        rod.mass.name(),
        kept.len(),
        all.all_frequencies_hz.len(),
    );
    println!("mode  frequency_hz  kind     axial_share  used");
    for (k, f) in all.all_frequencies_hz.iter().enumerate() {
        let used = if kept.contains(&k) {
            "retained"
        } else if corrections.contains(&k) {
            "static correction"
        } else {
            "no"
        };
        println!(
            "{:>4}  {f:>12.4}  {:<7}  {:>11.3}  {used}",
            k + 1,
            if all.is_axial(k) { "axial" } else { "bending" },
            all.all_axial_shares[k],
        );
    }
    if let Some(path) = &args.csv {
        let failed = |e: std::io::Error| format!("{}: {e}", path.display());
        let mut out = std::io::BufWriter::new(std::fs::File::create(path).map_err(failed)?);
        let n = all.n_modes();
        let mut text = String::from("s_m");
        for k in 0..n {
            text += &format!(",axial_{},transverse_{}", k + 1, k + 1);
        }
        writeln!(out, "{text}").map_err(failed)?;
        let samples = 20 * scene.rod.elements;
        for i in 0..=samples {
            let s = scene.rod.length * i as f64 / samples as f64;
            let sh = point_shape(&all, s);
            let mut line = format!("{s:.6}");
            for k in 0..n {
                line += &format!(",{:.9e},{:.9e}", sh[(0, k)], sh[(1, k)]);
            }
            writeln!(out, "{line}").map_err(failed)?;
        }
        out.flush().map_err(failed)?;
        println!(
            "mode shapes (unit modal mass, body frame) written to {}",
            path.display()
        );
    }
    Ok(())
}

/// The time at which the crank, turning from t = 0 at `speed` (ramped up over `ramp` seconds
/// where given, as [`CrankDrive::Ramp`]), has turned `revolutions` revolutions: the law's own
/// angle, so that a ramp's slower start is counted.
fn revolutions_end(revolutions: f64, speed: f64, ramp: Option<f64>) -> f64 {
    let angle = 2.0 * std::f64::consts::PI * revolutions;
    let Some(time) = ramp else {
        return angle / speed.abs();
    };
    let law = CrankDrive::Ramp { speed, time };
    let turned = |t: f64| (law.at(t).angle - law.at(0.0).angle).abs();
    // Past the ramp the crank has lost W T / 2 of angle against the constant speed: the end
    // lies below angle / |W| + T / 2 (and is that where the ramp is over).
    let (mut low, mut high) = (0.0, angle / speed.abs() + time);
    for _ in 0..200 {
        let mid = 0.5 * (low + high);
        if turned(mid) < angle {
            low = mid;
        } else {
            high = mid;
        }
    }
    high
}

/// The run's stop time and number of communication steps, or why the command line gives none.
fn run_length(
    args: &SimulateArgs,
    scene: &Scene,
    speed: f64,
    dt: f64,
) -> Result<(f64, usize), Failure> {
    let t0 = scene.experiment.start_time;
    let stop = match args.revolutions {
        Some(revolutions) => {
            if speed == 0.0 {
                return Err(Failure::Usage(format!(
                    "--revolutions {revolutions} at crank speed 0 rad/s never ends: give --speed W with W != 0"
                )));
            }
            revolutions_end(revolutions, speed, args.ramp)
        }
        None => scene.experiment.stop_time,
    };
    let what = match args.revolutions {
        Some(n) => format!("--revolutions {} at {} rad/s", number(n), number(speed)),
        None => "the scene's stop_time".to_string(),
    };
    if !stop.is_finite() {
        return Err(Failure::Usage(format!(
            "{what}: no finite stop time ({} s)",
            number(stop)
        )));
    }
    if stop <= t0 {
        return Err(Failure::Usage(format!(
            "the stop time {} s ({what}) is not after the start time {} s",
            number(stop),
            number(t0)
        )));
    }
    let steps = ((stop - t0) / dt).round().max(1.0);
    let step = match args.step {
        Some(h) => format!("--step {} s", number(h)),
        None => format!("the scene's step_size {} s", number(dt)),
    };
    limits::check_points(
        &format!("{what} ({} s) at {step}", number(stop - t0)),
        steps + 1.0,
    )
    .map_err(Failure::Usage)?;
    Ok((stop, steps as usize))
}

fn simulate(args: &SimulateArgs) -> Result<(), Failure> {
    let mut scene = load_scene(args.scene.as_deref())?;
    let speed = args.speed.unwrap_or(scene.experiment.crank_speed);
    let dt = args.step.unwrap_or(scene.experiment.step_size);
    let (stop, n) = run_length(args, &scene, speed, dt)?;
    let t0 = scene.experiment.start_time;
    let drive = if let Some(path) = &args.input {
        let text = limits::read_text(path, CSV_FILE_CAP, "the --input table")?;
        let origin = flexrod::text::echo(&path.display().to_string());
        let drive = CrankDrive::table_from_csv(&text, &origin).map_err(|e| match e {
            // The table's errors come as scene errors: name the file as the input table.
            flexrod::ModelError::Scene { origin, message } => {
                format!("--input table {origin}: {message}")
            }
            other => other.to_string(),
        })?;
        if let CrankDrive::Table(rows) = &drive {
            let (first, last) = (rows[0], rows[rows.len() - 1]);
            if first[0] > t0 {
                eprintln!(
                    "warning: the --input table {} starts at t = {} s, after the run's start {} s: before it the crank turns at the first row's speed (angle {} rad, speed {} rad/s at the first row); start the table at the run's start to prescribe the motion there",
                    path.display(), time(first[0]), time(t0), first[1], first[2]
                );
            }
            if last[0] < stop {
                eprintln!(
                    "warning: the --input table {} ends at t = {} s, before the run's stop time {} s: past it the crank turns on at the last row's speed (angle {} rad, speed {} rad/s at the last row); extend the table to the stop time to prescribe the motion there",
                    path.display(), time(last[0]), time(stop), last[1], last[2]
                );
            }
        }
        drive
    } else if let Some(time) = args.ramp {
        CrankDrive::Ramp { speed, time }
    } else {
        CrankDrive::Constant { speed }
    };
    // `rod.model = auto` chooses for the run's highest crank speed (the scene's
    // `[crank] design_speed` where given).
    scene.take_design_speed(match &drive {
        CrankDrive::Table(rows) => rows.iter().map(|r| r[2].abs()).fold(0.0, f64::max),
        _ => speed,
    });
    let mut sim = Simulation::new(&scene).map_err(|e| e.to_string())?;
    let wall = Instant::now();
    let record = drive::run(&mut sim, &drive, 0.0, &communication_grid(t0, dt, n))
        .map_err(|e| e.to_string())?;
    let elapsed = wall.elapsed().as_secs_f64();
    for (t, w) in &record.warnings {
        eprintln!("warning after t = {} s: {w}", time(*t));
    }
    let stats = record.stats;
    let peak = record.peak_deflection_rel();
    let magnitude = |f: [f64; 2]| f[0].hypot(f[1]);
    let peak_b = record
        .outputs
        .iter()
        .map(|o| magnitude(o.pin_b_force))
        .fold(0.0, f64::max);
    let peak_c = record
        .outputs
        .iter()
        .map(|o| magnitude(o.pin_c_force))
        .fold(0.0, f64::max);
    let chosen = match scene.rod.model {
        RodModelKind::Auto => format!(
            " (rod.model = auto at {} rad/s)",
            number(scene.crank.design_speed)
        ),
        _ => String::new(),
    };
    println!("scene {}{chosen}: {}", scene.name, sim.rod_summary());
    let (integrator, counted) = sim.mechanism().integrator_name();
    // The revolutions the crank turned, from the recorded crank angles (whatever drove it).
    let ran = record.times.last().map_or(0.0, |t| t - t0);
    let turned = match (record.inputs.first(), record.inputs.last()) {
        (Some(first), Some(last)) => (last.angle - first.angle).abs(),
        _ => 0.0,
    };
    println!("simulated {} s ({:.2} revolutions of the crank) in {:.2} ms wall with {integrator}: {} steps, {} {counted}, {} halvings", time(ran), turned / (2.0 * std::f64::consts::PI), elapsed * 1e3, stats.steps, stats.newton_iterations, stats.halvings);
    println!("peak |v_mid/L| = {peak:.5e}, peak |F_B| = {peak_b:.2} N, peak |F_C| = {peak_c:.2} N");
    if let Some(path) = &args.out {
        write_csv(path, &record, scene.outputs.stress)?;
        println!("outputs written to {}", path.display());
    }
    if let Some(prefix) = &args.plot {
        for (name, svg) in plots(&scene.name, &record) {
            let path = format!("{prefix}_{name}.svg");
            std::fs::write(&path, svg).map_err(|e| format!("{path}: {e}"))?;
            println!("plot written to {path}");
        }
    }
    Ok(())
}

/// The outputs at each communication point as CSV; the section forces and stress with
/// `stress` (the scene's `[outputs] stress`).
fn write_csv(path: &Path, record: &drive::Record, stress: bool) -> Result<(), String> {
    let failed = |e: std::io::Error| format!("{}: {e}", path.display());
    let mut out = std::io::BufWriter::new(std::fs::File::create(path).map_err(failed)?);
    let mut header = String::from("time,crank_angle,crank_speed,deflection,deflection_rel,pinB_force_x,pinB_force_y,pinC_force_x,pinC_force_y,crank_torque,slider_position,slider_velocity");
    if stress {
        header += ",axial_force_mid,bending_moment_mid,stress_max,stress_max_position";
    }
    writeln!(out, "{header}").map_err(failed)?;
    for ((t, input), o) in record.times.iter().zip(&record.inputs).zip(&record.outputs) {
        let mut values = vec![
            *t,
            input.angle,
            input.speed,
            o.deflection,
            o.deflection_rel,
            o.pin_b_force[0],
            o.pin_b_force[1],
            o.pin_c_force[0],
            o.pin_c_force[1],
            o.crank_torque,
            o.slider_position,
            o.slider_velocity,
        ];
        if stress {
            let s = &o.section;
            values.extend([
                s.axial_force_mid,
                s.bending_moment_mid,
                s.stress_max,
                s.stress_max_position,
            ]);
        }
        let line: Vec<String> = values.iter().map(|x| format!("{x:.9e}")).collect();
        writeln!(out, "{}", line.join(",")).map_err(failed)?;
    }
    out.flush().map_err(failed)
}

/// The two plots, (name, SVG): v_mid/L and the pin forces against the crank angle in degrees.
fn plots(scene: &str, record: &drive::Record) -> [(&'static str, String); 2] {
    use svg_plot::{line_plot, Axis, Curve};
    let pts = |f: &dyn Fn(&flexrod::Outputs) -> f64| {
        record
            .inputs
            .iter()
            .zip(&record.outputs)
            .map(|(i, o)| (i.angle.to_degrees(), f(o)))
            .collect::<Vec<_>>()
    };
    let angle = Axis {
        label: "crank angle",
        unit: "deg",
        degrees: true,
    };
    let deflection = line_plot(
        &format!("{scene}: midpoint deflection"),
        &angle,
        &Axis {
            label: "v_mid / L",
            unit: "",
            degrees: false,
        },
        &[Curve {
            label: "v_mid/L",
            colour: "#1f77b4",
            points: pts(&|o| o.deflection_rel),
        }],
    );
    let forces = line_plot(
        &format!("{scene}: pin forces (rod on pin)"),
        &angle,
        &Axis {
            label: "force",
            unit: "N",
            degrees: false,
        },
        &[
            Curve {
                label: "pin B x",
                colour: "#1f77b4",
                points: pts(&|o| o.pin_b_force[0]),
            },
            Curve {
                label: "pin B y",
                colour: "#ff7f0e",
                points: pts(&|o| o.pin_b_force[1]),
            },
            Curve {
                label: "pin C x",
                colour: "#2ca02c",
                points: pts(&|o| o.pin_c_force[0]),
            },
            Curve {
                label: "pin C y",
                colour: "#d62728",
                points: pts(&|o| o.pin_c_force[1]),
            },
        ],
    );
    [("deflection", deflection), ("forces", forces)]
}
