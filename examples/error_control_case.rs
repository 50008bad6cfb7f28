//! One random parameter set of the error-control calibration (`tests/error_control.rs`) at
//! every tolerance from 1e-2 to 1e-5 and under fixed-step generalized-alpha, against a run of
//! the same model converged to tolerance 1e-8: the pointwise error of `v_mid / L` over its
//! peak, the steps and the work of each.
//!
//! `cargo run --release --example error_control_case -- K [DT]`: set K (0 is the first of the
//! calibration's 30), optionally at the communication step DT (s) instead of its own.

#[path = "../tests/random_sets/mod.rs"]
mod random_sets;

use flexrod::scene::SolverMethod;
use random_sets::{error, random_case, run, same_model, Random};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = "usage: error_control_case K [DT]  (K: the set, 0 to 29 in the calibration; DT: a communication step > 0, s)";
    let Some(index) = args.first().and_then(|k| k.parse::<usize>().ok()) else {
        eprintln!("{usage}");
        std::process::exit(2);
    };
    let dt = match args.get(1).map(|d| d.parse::<f64>()) {
        None => None,
        Some(Ok(d)) if d.is_finite() && d > 0.0 && d <= 1.0 => Some(d),
        Some(_) => {
            eprintln!("{usage}");
            std::process::exit(2);
        }
    };
    let mut rng = Random(12);
    let mut case = random_case(&mut rng);
    for _ in 0..index {
        case = random_case(&mut rng);
    }
    if let Some(dt) = dt {
        case.dt = dt;
    }
    let duration = (2.0 * std::f64::consts::PI / case.speed).max(40.0 * case.dt);
    let reference = run(
        &same_model(&case.scene, 1e-8),
        case.speed,
        case.dt,
        duration,
    );
    println!(
        "set {index}: {case}; reference {} steps",
        reference.stats.steps
    );
    let mut ga = case.scene.clone();
    ga.solver.method = SolverMethod::GeneralizedAlpha;
    ga.solver.step = 1e-6;
    let r = run(&ga, case.speed, case.dt, duration);
    println!(
        "generalized-alpha, h 1e-6: error {:.2e}",
        error(&r, &reference)
    );
    for tol in [1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 1e-5] {
        let mut s = case.scene.clone();
        s.solver.tolerance = tol;
        let r = run(&s, case.speed, case.dt, duration);
        println!(
            "tolerance {tol:.0e}: error {:.2e}, {} steps, {} work",
            error(&r, &reference),
            r.stats.steps,
            r.stats.newton_iterations
        );
    }
}
