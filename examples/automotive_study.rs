//! The automotive rod (scenes/automotive_rod.toml) on its default experiment (6000 rpm from
//! t = 0, undeformed, 1e-5 s communication step, two revolutions): time, steps and the error of
//! each output relative to its peak against a converged run of the same model (32 elements,
//! every mode to 120 kHz, Dormand-Prince at tolerance 1e-7), for the settings in `CASES`.
//!
//! `cargo run --release --example automotive_study [FILTER]`.

use std::time::Instant;

use flexrod::drive::{self, communication_grid, CrankDrive};
use flexrod::scene::SolverMethod;
use flexrod::Scene;

fn scene() -> Scene {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/automotive_rod.toml");
    let mut s = Scene::from_file(std::path::Path::new(path)).unwrap();
    if std::env::var("DAMPED").is_err() {
        s.rod.damping_ratio = 0.0;
    }
    s
}

/// Outputs per communication point: v_mid/L, FBx, FBy, FCx, FCy, torque, stress.
fn run(s: &Scene, reps: usize) -> (Vec<[f64; 7]>, f64, u64, u64, String) {
    let w = s.experiment.crank_speed;
    let grid = match std::env::var("ONE_STEP") {
        Ok(_) => vec![0.0, 0.02],
        Err(_) => communication_grid(0.0, 1e-5, 2000),
    };
    let mut sim = flexrod::Simulation::new(s).unwrap();
    let mut times = Vec::new();
    let mut rec = None;
    for _ in 0..reps {
        let t = Instant::now();
        rec = Some(drive::run(&mut sim, &CrankDrive::Constant { speed: w }, 0.0, &grid).unwrap());
        times.push(t.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    let rec = rec.unwrap();
    let rows = rec
        .outputs
        .iter()
        .map(|o| {
            [
                o.deflection_rel,
                o.pin_b_force[0],
                o.pin_b_force[1],
                o.pin_c_force[0],
                o.pin_c_force[1],
                o.crank_torque,
                o.section.stress_max,
            ]
        })
        .collect();
    let (name, _) = sim.mechanism().integrator_name();
    let summary = format!("{name}; {}", sim.mechanism().rod.describe());
    (
        rows,
        times[reps / 2] * 1e3,
        rec.stats.steps,
        rec.stats.newton_iterations,
        summary,
    )
}

fn errors(a: &[[f64; 7]], r: &[[f64; 7]]) -> [f64; 7] {
    let r = if a.len() < r.len() {
        &[r[0], *r.last().unwrap()][..]
    } else {
        r
    };
    let skip: usize = std::env::var("SKIP")
        .map(|s| s.parse().unwrap())
        .unwrap_or(0);
    std::array::from_fn(|i| {
        let peak = r.iter().map(|x| x[i].abs()).fold(0.0, f64::max);
        a.iter()
            .zip(r)
            .skip(skip)
            .map(|(x, y)| (x[i] - y[i]).abs())
            .fold(0.0, f64::max)
            / peak
    })
}

fn main() {
    let filter = std::env::args().nth(1).unwrap_or_default();
    let mut reference = scene();
    reference.rod.elements = 32;
    reference.rod.mode_band_hz = Some(120e3);
    reference.rod.loaded_modes = std::env::var("FREE_REFERENCE").is_err();
    reference.solver.method = SolverMethod::Dopri5;
    reference.solver.tolerance = 1e-7;
    let t = Instant::now();
    let (r, _, steps, _, _) = run(&reference, 1);
    println!(
        "reference: {steps} steps, {:.1} s",
        t.elapsed().as_secs_f64()
    );
    type Case = (&'static str, Box<dyn Fn(&mut Scene)>);
    let cases: Vec<Case> = vec![
        ("shipped", Box::new(|_| {})),
        (
            "loaded, 7 modes",
            Box::new(|s| {
                s.rod.loaded_modes = true;
            }),
        ),
        (
            "loaded, 7 modes, exponential",
            Box::new(|s| {
                s.rod.loaded_modes = true;
                s.solver.method = SolverMethod::Exponential;
            }),
        ),
        (
            "loaded, band 25 kHz, exponential",
            Box::new(|s| {
                s.rod.loaded_modes = true;
                s.rod.mode_band_hz = Some(25e3);
                s.solver.method = SolverMethod::Exponential;
            }),
        ),
        (
            "loaded, band 25 kHz, rk43",
            Box::new(|s| {
                s.rod.loaded_modes = true;
                s.rod.mode_band_hz = Some(25e3);
                s.solver.method = SolverMethod::Rk43;
            }),
        ),
        (
            "loaded, 7 modes, exponential, tol 1e-2",
            Box::new(|s| {
                s.rod.loaded_modes = true;
                s.solver.method = SolverMethod::Exponential;
                s.solver.tolerance = 1e-2;
            }),
        ),
        (
            "loaded, 8 el, band 60 kHz, rk43",
            Box::new(|s| {
                s.rod.loaded_modes = true;
                s.rod.mode_band_hz = Some(60e3);
                s.solver.method = SolverMethod::Rk43;
            }),
        ),
        (
            "loaded, 16 el, band 40 kHz, rk43",
            Box::new(|s| {
                s.rod.loaded_modes = true;
                s.rod.elements = 16;
                s.rod.mode_band_hz = Some(40e3);
                s.solver.method = SolverMethod::Rk43;
            }),
        ),
        (
            "free, 16 el, band 40 kHz, rk43",
            Box::new(|s| {
                s.rod.elements = 16;
                s.rod.mode_band_hz = Some(40e3);
                s.solver.method = SolverMethod::Rk43;
            }),
        ),
        (
            "loaded, band 4 kHz, rk43",
            Box::new(|s| {
                s.rod.loaded_modes = true;
                s.rod.mode_band_hz = Some(4e3);
                s.solver.method = SolverMethod::Rk43;
            }),
        ),
        (
            "loaded, band 4 kHz, exponential",
            Box::new(|s| {
                s.rod.loaded_modes = true;
                s.rod.mode_band_hz = Some(4e3);
                s.solver.method = SolverMethod::Exponential;
            }),
        ),
        (
            "loaded, band 6 kHz, rk43",
            Box::new(|s| {
                s.rod.loaded_modes = true;
                s.rod.mode_band_hz = Some(6e3);
                s.solver.method = SolverMethod::Rk43;
            }),
        ),
        (
            "loaded, band 6 kHz, exponential",
            Box::new(|s| {
                s.rod.loaded_modes = true;
                s.rod.mode_band_hz = Some(6e3);
                s.solver.method = SolverMethod::Exponential;
            }),
        ),
        (
            "loaded, band 12 kHz, rk43",
            Box::new(|s| {
                s.rod.loaded_modes = true;
                s.rod.mode_band_hz = Some(12e3);
                s.solver.method = SolverMethod::Rk43;
            }),
        ),
        (
            "loaded, band 12 kHz, exponential",
            Box::new(|s| {
                s.rod.loaded_modes = true;
                s.rod.mode_band_hz = Some(12e3);
                s.solver.method = SolverMethod::Exponential;
            }),
        ),
        ("shipped", Box::new(|_| {})),
        ("shipped, tol 1e-2", Box::new(|s| s.solver.tolerance = 1e-2)),
        ("shipped, tol 3e-3", Box::new(|s| s.solver.tolerance = 3e-3)),
    ];
    println!("| case | ms | steps | rhs | v_mid | FBx | FBy | FCx | FCy | torque | stress |");
    for (name, f) in cases {
        if !name.contains(&filter) {
            continue;
        }
        let mut s = scene();
        f(&mut s);
        let (a, ms, steps, rhs, integ) = run(&s, 5);
        let e = errors(&a, &r);
        println!(
            "| {name} ({integ}) | {ms:.2} | {steps} | {rhs} | {} |",
            e.iter()
                .map(|x| format!("{:.3} %", 100.0 * x))
                .collect::<Vec<_>>()
                .join(" | ")
        );
    }
}
