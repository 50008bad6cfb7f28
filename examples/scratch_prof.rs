//! scratch (not committed)
use flexrod::drive::{self, CrankDrive};
use flexrod::{Scene, Simulation};
fn main() {
    let n: usize = std::env::var("N")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(32);
    let reps: usize = std::env::var("REPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(200);
    let mut scene = Scene::benchmark();
    scene.rod.model = flexrod::rod::RodModelKind::ModalSegments;
    scene.rod.elements = n;
    scene.rod.modes = 3;
    let w = 300.0;
    let grid = [0.0, 4.0 * std::f64::consts::PI / w];
    let t0 = std::time::Instant::now();
    let mut steps = 0;
    for _ in 0..reps {
        let mut sim = Simulation::new(&scene).unwrap();
        drive::run(&mut sim, &CrankDrive::Constant { speed: w }, 0.0, &grid).unwrap();
        steps = sim.stats().steps;
    }
    println!(
        "{} ms per run incl. init, {} steps",
        t0.elapsed().as_secs_f64() * 1e3 / reps as f64,
        steps
    );
}
