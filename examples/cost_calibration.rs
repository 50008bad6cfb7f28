//! The cost model of `flexrod::rod::cost` against the clock: for a range of models (small and
//! large, with and without the FFR rod's axial coupling), the predicted work units of building
//! the model and of one evaluation, and the measured seconds, as nanoseconds per work unit.
//! The per-call budget and the build limit bound time only while these ratios stay within a
//! small factor of each other.
//!
//! `cargo run --release --example cost_calibration` (one thread; run it on an idle machine).

use std::time::Instant;

use flexrod::mechanism::stepping::evaluations_allowed;
use flexrod::rod::cost;
use flexrod::scene::RodModelKind;
use flexrod::{CrankInput, ModelError, Scene, Simulation};

fn automotive(youngs_modulus: f64, elements: usize) -> Scene {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/automotive_rod.toml");
    let text = std::fs::read_to_string(path).expect("the automotive scene");
    let mut s = Scene::from_toml_str(&text, path).expect("parses");
    s.rod.youngs_modulus = youngs_modulus;
    s.rod.shear_modulus = Some(youngs_modulus / 2.6);
    s.rod.elements = elements;
    s
}

fn soft_ffr(elements: usize, modes: usize, stiffening: bool) -> Scene {
    let mut s = Scene::benchmark();
    s.rod.model = RodModelKind::Ffr;
    s.rod.elements = elements;
    s.rod.modes = modes;
    s.rod.youngs_modulus = 1e6;
    s.rod.density = 1e5;
    s.rod.axial_stiffening = stiffening;
    s
}

fn main() {
    let cases: Vec<(String, Scene, f64)> = vec![
        ("default scene".into(), Scene::benchmark(), 0.05),
        (
            "FFR 16 el, 48 modes, soft".into(),
            soft_ffr(16, 48, true),
            1e-2,
        ),
        (
            "FFR 48 el, 144 modes, soft".into(),
            soft_ffr(48, 144, true),
            1e-2,
        ),
        (
            "FFR 128 el, 384 modes, soft, no stiffening".into(),
            soft_ffr(128, 384, false),
            1e-2,
        ),
        (
            "segments 8, soft, heavy small end".into(),
            {
                let mut s = Scene::benchmark();
                s.rod.model = RodModelKind::Segments;
                s.rod.density = 4e4;
                s.rod.damping_ratio = 0.5;
                s.rod.small_end.inertia = 6e5;
                s.solver.tolerance = 1e-4;
                s
            },
            1.0,
        ),
        (
            "segments 32".into(),
            {
                let mut s = Scene::benchmark();
                s.rod.model = RodModelKind::Segments;
                s.rod.elements = 32;
                s
            },
            1.0,
        ),
        (
            "modal segments 32".into(),
            {
                let mut s = Scene::benchmark();
                s.rod.model = RodModelKind::ModalSegments;
                s.rod.elements = 32;
                s.solver.tolerance = 1e-8;
                s
            },
            1.0,
        ),
        ("automotive".into(), automotive(2e11, 8), 0.02),
        ("automotive E 2e9, 24 el".into(), automotive(2e9, 24), 1e-3),
        ("automotive E 2e8, 24 el".into(), automotive(2e8, 24), 1e-3),
        ("automotive E 5e7, 32 el".into(), automotive(5e7, 32), 1e-3),
        ("automotive E 2e7, 40 el".into(), automotive(2e7, 40), 1e-4),
        (
            "automotive E 1e5, tolerance 1.4e-6".into(),
            {
                let mut s = automotive(1e5, 8);
                s.solver.tolerance = 1.4e-6;
                s
            },
            1e-3,
        ),
    ];
    println!("| model | n | axial | build units | build s | ns/unit | evaluation units | evaluations | step s | ns/unit |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for (label, scene, h) in cases {
        let t0 = Instant::now();
        let sim = Simulation::new(&scene);
        let build_s = t0.elapsed().as_secs_f64();
        let mut sim = match sim {
            Ok(sim) => sim,
            Err(e) => {
                println!("| {label} | refused: {e} |");
                continue;
            }
        };
        let n = sim
            .mechanism()
            .rod
            .elastic_coordinates()
            .map_or(0, |e| e.count());
        let axial = axial_modes(&sim);
        let build_units = cost::axial_coupling_build(n, axial, scene.rod.elements);
        sim.start(
            0.0,
            CrankInput {
                angle: 0.0,
                speed: scene.experiment.crank_speed,
                acceleration: 0.0,
                jerk: 0.0,
            },
            0.0,
        )
        .expect("starts");
        let before = sim.state().stats;
        let t1 = Instant::now();
        let outcome = sim.advance(h);
        let step_s = t1.elapsed().as_secs_f64();
        let after = sim.state().stats;
        let unit = sim.mechanism().evaluation_cost();
        // A refused step restores the statistics: it used up the budget.
        let evaluations = match outcome {
            Err(ModelError::TooMuchWork { .. }) => evaluations_allowed(unit) + 1,
            _ => {
                (after.newton_iterations - before.newton_iterations)
                    + (after.steps - before.steps)
                    + (after.halvings - before.halvings)
            }
        };
        let per_build = if build_units > 0.0 {
            format!("{:.3}", 1e9 * build_s / build_units)
        } else {
            "-".into()
        };
        println!(
            "| {label} | {n} | {axial} | {build_units:.2e} | {build_s:.3} | {per_build} | {unit:.3e} | {evaluations} | {step_s:.3} | {:.4} |",
            1e9 * step_s / (evaluations as f64 * unit)
        );
    }
}

/// The retained axial modes of an FFR rod (0 for other models), from its frequency kinds.
fn axial_modes(sim: &Simulation) -> usize {
    let rod = &sim.mechanism().rod;
    let extra = rod.extra_evaluation_cost();
    if extra == 0.0 {
        return 0;
    }
    let n = rod.elastic_coordinates().map_or(0, |e| e.count());
    // Invert `AXIAL_COUPLING_TERM na n^2 (na + 3)` for na.
    let c = extra / (cost::AXIAL_COUPLING_TERM * (n * n) as f64);
    ((-3.0 + (9.0 + 4.0 * c).sqrt()) / 2.0).round() as usize
}
