//! Two revolutions of the default scene, repeated: a target for profilers
//! (`perf record cargo run --release --example profile_default`).

use flexrod::drive::{self, communication_grid, CrankDrive};
use flexrod::{Scene, Simulation};

fn main() {
    let scene = Scene::benchmark();
    let mut sim = Simulation::new(&scene).unwrap();
    let grid = communication_grid(0.0, 3e-4, 279);
    let law = CrankDrive::Constant { speed: 150.0 };
    let clock = std::time::Instant::now();
    let repeats: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(200);
    let mut peak = 0.0;
    for _ in 0..repeats {
        let r = drive::run(&mut sim, &law, 0.0, &grid).unwrap();
        peak = r.peak_deflection_rel();
    }
    let s = sim.stats();
    println!(
        "{:.3} ms per two revolutions; peak {peak:.5e}; {} steps, {} evaluations per run",
        clock.elapsed().as_secs_f64() * 1e3 / repeats as f64,
        s.steps,
        s.newton_iterations
    );
}
