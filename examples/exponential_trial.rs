//! Issue 12 trial (measured, not kept): the exponential (Lawson) form of RK4(3) on the minimal
//! coordinates, each mode's undamped/damped oscillator split off with the modal stiffness and
//! mass (`Dopri5::exponential`), against RK4(3) as `auto` runs it. Pointwise error of `v_mid / L`
//! against a converged run (RK4(3), tolerance 1e-8) on the same communication grid, relative to
//! its peak, and the cost (steps, right-hand sides). `FLEXROD_NO_LAWSON=1` selects plain
//! RK4(3); the trial switches it per run.
//!
//! `cargo run --release --example exponential_trial` (default scene, 3 modes and 1 mode; the
//! automotive rod with 7 modes at 6000 rpm).
use flexrod::drive::{self, communication_grid, CrankDrive};
use flexrod::{Scene, Simulation};

struct Case {
    label: &'static str,
    scene: &'static str,
    modes: Option<&'static str>,
    speed: f64,
    dt: f64,
    t_end: f64,
    tolerances: &'static [&'static str],
}

fn series(case: &Case, tol: &str, lawson: bool, grid: &[f64]) -> (Vec<f64>, u64, u64) {
    let mut text = std::fs::read_to_string(case.scene).unwrap();
    if let Some(m) = case.modes {
        text = text.replace("modes = 3", &format!("modes = {m}"));
    }
    text = text.replace("tolerance = 1e-3", &format!("tolerance = {tol}"));
    if lawson {
        std::env::remove_var("FLEXROD_NO_LAWSON");
    } else {
        std::env::set_var("FLEXROD_NO_LAWSON", "1");
    }
    let mut sim = Simulation::new(&Scene::from_toml_str(&text, case.scene).unwrap()).unwrap();
    let law = CrankDrive::Constant { speed: case.speed };
    let r = drive::run(&mut sim, &law, 0.0, grid).unwrap();
    let s = sim.stats();
    (r.deflection_rel(), s.steps, s.newton_iterations)
}

fn main() {
    let cases = [
        Case {
            label: "default scene (3 modes), 2 revolutions, outputs every 3e-4 s",
            scene: "scenes/benchmark.toml",
            modes: None,
            speed: 150.0,
            dt: 3e-4,
            t_end: 0.0838,
            tolerances: &["1e-4", "3e-4", "1e-3", "3e-3"],
        },
        Case {
            label: "default scene with modes = 1",
            scene: "scenes/benchmark.toml",
            modes: Some("1"),
            speed: 150.0,
            dt: 3e-4,
            t_end: 0.0838,
            tolerances: &["1e-4", "3e-4", "1e-3", "3e-3"],
        },
        Case {
            label: "automotive rod (7 modes), 2 revolutions at 628.3 rad/s, outputs every 1e-5 s",
            scene: "scenes/automotive_rod.toml",
            modes: None,
            speed: 628.3,
            dt: 1e-5,
            t_end: 0.02,
            tolerances: &["1e-4", "1e-3"],
        },
    ];
    println!("| case | tolerance | RK4(3): steps, right-hand sides, error / peak | Lawson RK4(3): steps, right-hand sides, error / peak |");
    println!("|---|---|---|---|");
    for case in &cases {
        let grid = communication_grid(0.0, case.dt, (case.t_end / case.dt) as usize);
        let (reference, _, _) = series(case, "1e-8", false, &grid);
        let peak = reference.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        for tol in case.tolerances {
            let mut cells = Vec::new();
            for lawson in [false, true] {
                let (x, steps, rhs) = series(case, tol, lawson, &grid);
                let err = x
                    .iter()
                    .zip(&reference)
                    .fold(0.0f64, |a, (x, r)| a.max((x - r).abs()))
                    / peak;
                cells.push(format!("{steps}, {rhs}, {err:.1e}"));
            }
            println!("| {} | {tol} | {} | {} |", case.label, cells[0], cells[1]);
        }
    }
}
