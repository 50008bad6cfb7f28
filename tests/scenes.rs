//! Every shipped scene parses, builds and runs two revolutions of its default experiment; the
//! seed 000 variants reproduce the seed's frequency lists.

use flexrod::{CrankInput, Scene, Simulation};

fn scenes() -> Vec<(String, Scene)> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes");
    let mut v: Vec<(String, Scene)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| (p.display().to_string(), Scene::from_file(&p).unwrap()))
        .collect();
    v.sort_by(|a, b| a.0.cmp(&b.0));
    v
}

#[test]
fn every_shipped_scene_runs_its_default_experiment() {
    for (path, scene) in scenes() {
        let mut sim = Simulation::new(&scene).unwrap();
        let e = &scene.experiment;
        let w = e.crank_speed;
        sim.start(
            e.start_time,
            CrankInput {
                angle: w * e.start_time,
                speed: w,
                acceleration: 0.0,
            },
            0.0,
        )
        .unwrap();
        let n = ((e.stop_time - e.start_time) / e.step_size).round() as usize;
        let mut peak: f64 = 0.0;
        for k in 0..n {
            let t = e.start_time + k as f64 * e.step_size;
            sim.set_input(CrankInput {
                angle: w * t,
                speed: w,
                acceleration: 0.0,
            })
            .unwrap();
            sim.advance(e.step_size).unwrap();
            peak = peak.max(sim.outputs().deflection_rel.abs());
        }
        println!("{path}: {n} steps, peak |v_mid/L| {peak:.4e}");
        assert!(
            peak.is_finite() && peak > 1e-4 && peak < 0.05,
            "{path}: {peak}"
        );
    }
}

#[test]
fn seed000_scenes_reproduce_the_seed_frequencies() {
    let table = [
        (
            "simply_supported",
            [135.80, 600.52, 1509.45, 2751.91, 4240.25, 14812.84],
        ),
        (
            "mean_axis",
            [307.31, 961.77, 2404.94, 3842.11, 9115.38, 18230.77],
        ),
        (
            "body_fixed_mid",
            [193.66, 193.66, 1908.09, 1908.09, 9115.38, 9115.38],
        ),
        (
            "cantilever",
            [48.21, 304.54, 1030.02, 2989.54, 4240.25, 14812.84],
        ),
    ];
    for (name, expected) in table {
        let path = format!("{}/scenes/seed000_{name}.toml", env!("CARGO_MANIFEST_DIR"));
        let sim = Simulation::new(&Scene::from_file(std::path::Path::new(&path)).unwrap()).unwrap();
        for (f, e) in sim.frequencies_hz().iter().zip(expected) {
            assert!(((f - e) / e).abs() < 1e-4, "{name}: {f} vs {e}");
        }
    }
}
