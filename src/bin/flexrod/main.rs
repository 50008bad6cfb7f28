//! `flexrod`: the command-line tool of the core.
//!
//! - `flexrod modes [SCENE] [--csv FILE]`: the rod's frequency table and mode shapes.
//! - `flexrod simulate [SCENE] [--speed W] [--revolutions N] [--ramp T] [--input CSV] [--out CSV] [--plot PREFIX]`:
//!   simulate the slider-crank, write every output at each communication step, and plot
//!   v_mid/L and the pin forces against the crank angle (PREFIX_deflection.svg, PREFIX_forces.svg).

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

mod svg_plot;

use flexrod::modal::shape_integrals::point_shape;
use flexrod::modal::{ComponentModes, ModeSelection, ReferenceConditions};
use flexrod::scene::{RodModelKind, Scene};
use flexrod::{CrankInput, Simulation};

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("modes") => modes(&args[1..]),
        Some("simulate") => simulate(&args[1..]),
        _ => Err("usage: flexrod modes [SCENE.toml] [--csv FILE] | flexrod simulate [SCENE.toml] [--speed RAD_PER_S] [--revolutions N] [--ramp SECONDS] [--input CSV] [--out CSV] [--plot PREFIX]".to_string()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("flexrod: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Positional scene path (first argument not starting with --) and the flag values.
fn parse(args: &[String]) -> Result<(Scene, Vec<(String, String)>), String> {
    let mut scene = None;
    let mut flags = Vec::new();
    let mut i = 0;
    while i < args.len() {
        if let Some(name) = args[i].strip_prefix("--") {
            let value = args.get(i + 1).ok_or(format!("--{name} needs a value"))?;
            flags.push((name.to_string(), value.clone()));
            i += 2;
        } else {
            scene = Some(Scene::from_file(&PathBuf::from(&args[i])).map_err(|e| e.to_string())?);
            i += 1;
        }
    }
    Ok((scene.unwrap_or_else(Scene::benchmark), flags))
}

fn flag<'a>(flags: &'a [(String, String)], name: &str) -> Option<&'a str> {
    flags
        .iter()
        .find(|(n, _)| n == name)
        .map(|(_, v)| v.as_str())
}

fn number(flags: &[(String, String)], name: &str, default: f64) -> Result<f64, String> {
    match flag(flags, name) {
        None => Ok(default),
        Some(v) => v.parse().map_err(|_| format!("--{name} {v}: not a number")),
    }
}

fn modes(args: &[String]) -> Result<(), String> {
    let (scene, flags) = parse(args)?;
    if scene.rod.model != RodModelKind::Ffr {
        let sim = Simulation::new(&scene).map_err(|e| e.to_string())?;
        println!("mode  frequency_hz");
        for (k, f) in sim.frequencies_hz().iter().enumerate() {
            println!("{:>4}  {f:.4}", k + 1);
        }
        return Ok(());
    }
    let spec = scene.mechanism_spec();
    spec.validate().map_err(|e| e.to_string())?;
    let props = spec.rod.properties();
    let reference = ReferenceConditions::from_kind(scene.rod.reference, scene.rod.elements)
        .map_err(|e| e.to_string())?;
    let all = ComponentModes::new(
        props,
        scene.rod.elements,
        reference,
        scene.rod.mass,
        &ModeSelection::Cutoff {
            max_hz: f64::INFINITY,
        },
    )
    .map_err(|e| e.to_string())?;
    println!(
        "scene {}: {} elements, {:?} reference conditions, {:?} mass; {} modes retained of {}",
        scene.name,
        scene.rod.elements,
        scene.rod.reference,
        scene.rod.mass,
        scene.rod.modes.min(all.all_frequencies_hz.len()),
        all.all_frequencies_hz.len()
    );
    println!("mode  frequency_hz  retained");
    for (k, f) in all.all_frequencies_hz.iter().enumerate() {
        println!(
            "{:>4}  {f:>12.4}  {}",
            k + 1,
            if k < scene.rod.modes { "yes" } else { "no" }
        );
    }
    if let Some(path) = flag(&flags, "csv") {
        let mut out = std::fs::File::create(path).map_err(|e| format!("{path}: {e}"))?;
        let n = all.n_modes();
        write!(out, "s_m").unwrap();
        for k in 0..n {
            write!(out, ",axial_{},transverse_{}", k + 1, k + 1).unwrap();
        }
        writeln!(out).unwrap();
        let samples = 20 * scene.rod.elements;
        for i in 0..=samples {
            let s = scene.rod.length * i as f64 / samples as f64;
            let sh = point_shape(&all, s);
            write!(out, "{s:.6}").unwrap();
            for k in 0..n {
                write!(out, ",{:.9e},{:.9e}", sh[(0, k)], sh[(1, k)]).unwrap();
            }
            writeln!(out).unwrap();
        }
        println!("mode shapes (unit modal mass, body frame) written to {path}");
    }
    Ok(())
}

/// The crank motion: constant speed, a smooth start ramp, or a CSV of (t, angle, speed).
enum Drive {
    Constant(f64),
    /// Speed rises as w (1 - cos(pi t / T)) / 2 over T seconds.
    Ramp {
        speed: f64,
        time: f64,
    },
    Table(Vec<[f64; 3]>),
}

impl Drive {
    fn at(&self, t: f64) -> CrankInput {
        match self {
            Drive::Constant(w) => CrankInput {
                angle: w * t,
                speed: *w,
                acceleration: 0.0,
            },
            Drive::Ramp { speed, time } => {
                if t >= *time {
                    let angle0 = 0.5 * speed * time;
                    CrankInput {
                        angle: angle0 + speed * (t - time),
                        speed: *speed,
                        acceleration: 0.0,
                    }
                } else {
                    let k = std::f64::consts::PI / time;
                    CrankInput {
                        angle: 0.5 * speed * (t - (k * t).sin() / k),
                        speed: 0.5 * speed * (1.0 - (k * t).cos()),
                        acceleration: 0.5 * speed * k * (k * t).sin(),
                    }
                }
            }
            Drive::Table(rows) => {
                let i = rows.partition_point(|r| r[0] <= t).clamp(1, rows.len() - 1);
                let (a, b) = (rows[i - 1], rows[i]);
                let u = ((t - a[0]) / (b[0] - a[0])).clamp(0.0, 1.0);
                CrankInput {
                    angle: a[1] + u * (b[1] - a[1]),
                    speed: a[2] + u * (b[2] - a[2]),
                    acceleration: (b[2] - a[2]) / (b[0] - a[0]),
                }
            }
        }
    }
}

fn simulate(args: &[String]) -> Result<(), String> {
    let (scene, flags) = parse(args)?;
    let speed = number(&flags, "speed", scene.experiment.crank_speed)?;
    let dt = number(&flags, "step", scene.experiment.step_size)?;
    let drive = if let Some(path) = flag(&flags, "input") {
        let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
        let rows: Vec<[f64; 3]> = text
            .lines()
            .filter(|l| {
                l.chars()
                    .next()
                    .is_some_and(|c| c.is_ascii_digit() || c == '-' || c == '.')
            })
            .map(|l| {
                let v: Vec<f64> = l.split(',').filter_map(|x| x.trim().parse().ok()).collect();
                if v.len() >= 3 {
                    Ok([v[0], v[1], v[2]])
                } else {
                    Err(format!("{path}: a row needs t, angle, speed: {l}"))
                }
            })
            .collect::<Result<_, _>>()?;
        if rows.len() < 2 {
            return Err(format!(
                "{path}: needs at least two rows of t, angle, speed"
            ));
        }
        Drive::Table(rows)
    } else if let Some(t) = flag(&flags, "ramp") {
        Drive::Ramp {
            speed,
            time: t.parse().map_err(|_| "--ramp: not a number")?,
        }
    } else {
        Drive::Constant(speed)
    };
    let revolutions = number(&flags, "revolutions", 0.0)?;
    let stop = if revolutions > 0.0 {
        2.0 * std::f64::consts::PI * revolutions / speed.abs().max(1e-9)
    } else {
        scene.experiment.stop_time
    };
    let mut sim = Simulation::new(&scene).map_err(|e| e.to_string())?;
    let t0 = scene.experiment.start_time;
    sim.start(t0, drive.at(t0), 0.0)
        .map_err(|e| e.to_string())?;
    let mut rows = vec![(t0, drive.at(t0), sim.outputs())];
    let n = ((stop - t0) / dt).round().max(1.0) as usize;
    let wall = Instant::now();
    for k in 0..n {
        let t = t0 + k as f64 * dt;
        sim.set_input(drive.at(t)).map_err(|e| e.to_string())?;
        sim.advance(t0 + (k + 1) as f64 * dt - sim.time())
            .map_err(|e| e.to_string())?;
        for w in sim.take_warnings() {
            eprintln!("warning: {w}");
        }
        rows.push((sim.time(), drive.at(sim.time()), sim.outputs()));
    }
    let elapsed = wall.elapsed().as_secs_f64();
    let stats = sim.stats();
    let peak = rows
        .iter()
        .map(|r| r.2.deflection_rel.abs())
        .fold(0.0, f64::max);
    let peak_b = rows
        .iter()
        .map(|r| r.2.pin_b_force[0].hypot(r.2.pin_b_force[1]))
        .fold(0.0, f64::max);
    let peak_c = rows
        .iter()
        .map(|r| r.2.pin_c_force[0].hypot(r.2.pin_c_force[1]))
        .fold(0.0, f64::max);
    println!(
        "scene {}: {:?} rod, {} elements, {} modes, {:?}",
        scene.name, scene.rod.model, scene.rod.elements, scene.rod.modes, scene.rod.reference
    );
    let (integrator, counted) = sim.mechanism().integrator_name();
    println!("simulated {:.4} s ({:.2} revolutions) in {:.2} ms wall with {integrator}: {} steps, {} {counted}, {} halvings", stop - t0, (stop - t0) * speed / (2.0 * std::f64::consts::PI), elapsed * 1e3, stats.steps, stats.newton_iterations, stats.halvings);
    println!("peak |v_mid/L| = {peak:.5e}, peak |F_B| = {peak_b:.2} N, peak |F_C| = {peak_c:.2} N");
    if let Some(path) = flag(&flags, "out") {
        let mut out = std::fs::File::create(path).map_err(|e| format!("{path}: {e}"))?;
        writeln!(out, "time,crank_angle,crank_speed,deflection,deflection_rel,pinB_force_x,pinB_force_y,pinC_force_x,pinC_force_y,crank_torque,slider_position,slider_velocity").unwrap();
        for (t, input, o) in &rows {
            writeln!(
                out,
                "{t:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e}",
                input.angle, input.speed, o.deflection, o.deflection_rel, o.pin_b_force[0], o.pin_b_force[1], o.pin_c_force[0], o.pin_c_force[1], o.crank_torque, o.slider_position, o.slider_velocity
            )
            .unwrap();
        }
        println!("outputs written to {path}");
    }
    if let Some(prefix) = flag(&flags, "plot") {
        use svg_plot::{line_plot, Curve};
        let pts = |f: &dyn Fn(&flexrod::Outputs) -> f64| {
            rows.iter()
                .map(|(_, i, o)| (i.angle, f(o)))
                .collect::<Vec<_>>()
        };
        let deflection = line_plot(
            &format!("{}: midpoint deflection", scene.name),
            "crank angle (rad)",
            "v_mid / L",
            &[Curve {
                label: "v_mid/L",
                colour: "#1f77b4",
                points: pts(&|o| o.deflection_rel),
            }],
        );
        let forces = line_plot(
            &format!("{}: pin forces (rod on pin)", scene.name),
            "crank angle (rad)",
            "force (N)",
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
        for (name, svg) in [("deflection", deflection), ("forces", forces)] {
            let path = format!("{prefix}_{name}.svg");
            std::fs::write(&path, svg).map_err(|e| format!("{path}: {e}"))?;
            println!("plot written to {path}");
        }
    }
    Ok(())
}
