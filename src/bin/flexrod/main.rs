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

use flexrod::drive::{self, communication_grid, CrankDrive};
use flexrod::modal::shape_integrals::point_shape;
use flexrod::modal::{ComponentModes, ModeSelection, ReferenceConditions};
use flexrod::scene::{RodModelKind, Scene};
use flexrod::Simulation;

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
    // The rod as the model builds it: section table, shear deformation and end bodies included
    // (the uniform equivalent `spec.rod.properties()` only for a plain rod).
    let definition = spec.rod.definition().map_err(|e| e.to_string())?;
    let reference = ReferenceConditions::from_kind(scene.rod.reference, scene.rod.elements)
        .map_err(|e| e.to_string())?;
    let all = ComponentModes::from_definition(
        definition,
        scene.rod.elements,
        reference,
        scene.rod.mass,
        &ModeSelection::Cutoff {
            max_hz: f64::INFINITY,
        },
    )
    .map_err(|e| e.to_string())?;
    // The selection the model makes (rod.modes lowest, plus axial modes: rod.axial_modes).
    let kept = ModeSelection::CountWithAxial {
        count: scene.rod.modes,
        axial: scene.rod.min_axial_modes(scene.slider.mass),
    }
    .select_classified(&all.all_frequencies_hz, &all.all_axial_shares)
    .map_err(|e| e.to_string())?;
    println!(
        "scene {}: {} elements, {:?} reference conditions, {:?} mass; {} modes retained of {} (rod.modes = {}, at least {} axial)",
        scene.name,
        scene.rod.elements,
        scene.rod.reference,
        scene.rod.mass,
        kept.len(),
        all.all_frequencies_hz.len(),
        scene.rod.modes,
        scene.rod.min_axial_modes(scene.slider.mass)
    );
    println!("mode  frequency_hz  kind     axial_share  retained");
    for (k, f) in all.all_frequencies_hz.iter().enumerate() {
        println!(
            "{:>4}  {f:>12.4}  {:<7}  {:>11.3}  {}",
            k + 1,
            if all.is_axial(k) { "axial" } else { "bending" },
            all.all_axial_shares[k],
            if kept.contains(&k) { "yes" } else { "no" }
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

fn simulate(args: &[String]) -> Result<(), String> {
    let (scene, flags) = parse(args)?;
    let speed = number(&flags, "speed", scene.experiment.crank_speed)?;
    let dt = number(&flags, "step", scene.experiment.step_size)?;
    let drive = if let Some(path) = flag(&flags, "input") {
        let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
        CrankDrive::table_from_csv(&text, path).map_err(|e| e.to_string())?
    } else if let Some(t) = flag(&flags, "ramp") {
        CrankDrive::Ramp {
            speed,
            time: t.parse().map_err(|_| "--ramp: not a number")?,
        }
    } else {
        CrankDrive::Constant { speed }
    };
    let revolutions = number(&flags, "revolutions", 0.0)?;
    let stop = if revolutions > 0.0 {
        2.0 * std::f64::consts::PI * revolutions / speed.abs().max(1e-9)
    } else {
        scene.experiment.stop_time
    };
    let mut sim = Simulation::new(&scene).map_err(|e| e.to_string())?;
    let t0 = scene.experiment.start_time;
    let n = ((stop - t0) / dt).round().max(1.0) as usize;
    let wall = Instant::now();
    let record = drive::run(&mut sim, &drive, 0.0, &communication_grid(t0, dt, n))
        .map_err(|e| e.to_string())?;
    let elapsed = wall.elapsed().as_secs_f64();
    for (t, w) in &record.warnings {
        eprintln!("warning after t = {t} s: {w}");
    }
    let stats = record.stats;
    let rows: Vec<_> = (0..record.times.len())
        .map(|k| (record.times[k], record.inputs[k], record.outputs[k]))
        .collect();
    let peak = record.peak_deflection_rel();
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
