//! Scratch: step counts of the default scene's error control with and without communication
//! points, at a few tolerances.
use flexrod::drive::{self, communication_grid, CrankDrive};
use flexrod::{Scene, Simulation};

fn main() {
    rhs_cost();
    if std::env::args().count() < 2 {
        return;
    }
    for tol in [1e-3, 3e-3, 1e-2] {
        for (dt, n) in [(3e-4, 279usize), (0.0837, 1)] {
            let mut scene = Scene::benchmark();
            scene.solver.tolerance = tol;
            let mut sim = Simulation::new(&scene).unwrap();
            let grid = communication_grid(0.0, dt, n);
            let law = CrankDrive::Constant { speed: 150.0 };
            let r = drive::run(&mut sim, &law, 0.0, &grid).unwrap();
            let s = sim.stats();
            println!(
                "tol {tol:e} dt {dt:e}: {} steps {} rhs peak {:.5e}",
                s.steps,
                s.newton_iterations,
                r.peak_deflection_rel()
            );
        }
    }
}

#[allow(dead_code)]
fn rhs_cost() {
    use flexrod::integrator::{DaeSystem, PartitionedRhs};
    let scene = Scene::benchmark();
    let mut sim = Simulation::new(&scene).unwrap();
    sim.start(
        0.0,
        flexrod::CrankInput {
            angle: 0.0,
            speed: 150.0,
            acceleration: 0.0,
        },
        0.0,
    )
    .unwrap();
    let mech = sim.mechanism();
    let sys = mech.system(sim.state());
    let elastic: Vec<usize> = mech.rod.elastic_coordinates().unwrap().collect();
    let mut rhs = PartitionedRhs::new(&sys, elastic);
    rhs.q.copy_from_slice(&sim.state().dae.q);
    let z = [1e-4, -2e-5, 1e-6];
    let zd = [1e-2, 1e-3, -1e-3];
    let mut zdd = [0.0; 3];
    let n = 2_000_000;
    let t0 = std::time::Instant::now();
    for i in 0..n {
        rhs.evaluate(&sys, 1e-9 * i as f64, &z, &zd, &mut zdd)
            .unwrap();
    }
    println!(
        "{:.1} ns per RHS ({})",
        t0.elapsed().as_secs_f64() * 1e9 / n as f64,
        sys.has_reduced_rhs()
    );
}
