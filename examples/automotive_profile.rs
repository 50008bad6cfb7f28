//! A profiling loop for the automotive rod (scenes/automotive_rod.toml): `ENGINE=1` the engine
//! run of `flexrod::drive::engine` 20 times, else two revolutions at 628.3 rad/s in one
//! communication step 500 times (for `perf record`).
//!
//! `cargo run --release --example automotive_profile`.

use flexrod::drive::{self, CrankDrive};
use flexrod::Scene;

fn main() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/automotive_rod.toml");
    let scene = Scene::from_file(std::path::Path::new(path)).unwrap();
    let t = std::time::Instant::now();
    for _ in 0..20 {
        flexrod::Simulation::new(&scene).unwrap();
    }
    println!(
        "Simulation::new: {:.3} ms each",
        t.elapsed().as_secs_f64() * 1e3 / 20.0
    );
    let t = std::time::Instant::now();
    if std::env::var_os("ENGINE").is_some() {
        for _ in 0..20 {
            flexrod::drive::engine::EngineRun::automotive()
                .run(&scene)
                .unwrap();
        }
        println!(
            "engine run: {:.3} ms each",
            t.elapsed().as_secs_f64() * 1e3 / 20.0
        );
        return;
    }
    let mut sim = flexrod::Simulation::new(&scene).unwrap();
    let w = scene.experiment.crank_speed;
    let grid = [0.0, 4.0 * std::f64::consts::PI / w];
    for _ in 0..500 {
        drive::run(&mut sim, &CrankDrive::Constant { speed: w }, 0.0, &grid).unwrap();
    }
    println!(
        "two revolutions: {:.3} ms each",
        t.elapsed().as_secs_f64() * 1e3 / 500.0
    );
}
