//! scratch (not committed)
use flexrod::drive::{self, CrankDrive};
use flexrod::{Scene, Simulation};
fn main() {
    let reps: usize = std::env::var("REPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(200);
    let mut scene = Scene::benchmark();
    scene.experiment.crank_speed = 300.0;
    if let Ok(n) = std::env::var("N") {
        scene.rod.elements = n.parse().unwrap();
        scene.rod.model = flexrod::rod::RodModelKind::ModalSegments;
    }
    let w = 300.0;
    let revs: f64 = std::env::var("REVS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2.0);
    let grid = [0.0, revs * 2.0 * std::f64::consts::PI / w];
    let mut best = f64::INFINITY;
    let mut steps = 0;
    let mut rhs = 0;
    let mut sim0 = Simulation::new(&scene).unwrap();
    for _ in 0..reps {
        let mut sim = Simulation::new(&scene).unwrap();
        let t0 = std::time::Instant::now();
        drive::run(&mut sim, &CrankDrive::Constant { speed: w }, 0.0, &grid).unwrap();
        best = best.min(t0.elapsed().as_secs_f64());
        steps = sim.stats().steps;
        rhs = sim.stats().newton_iterations;
        sim0 = sim;
    }
    println!(
        "{:?} {} seg: best {:.3} ms stepping, {} steps, {} rhs",
        sim0.mechanism().spec.rod.model,
        sim0.mechanism().spec.rod.elements,
        best * 1e3,
        steps,
        rhs
    );
}
