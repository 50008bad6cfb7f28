//! Issue 12 trial (measured, not kept): the exponential (Lawson) form of RK4(3) on the minimal
//! coordinates, each mode's oscillator split off with the modal stiffness, mass and damping
//! (`Dopri5::exponential`), against RK4(3) as `auto` runs it. Pointwise error of `v_mid / L`
//! against a converged run (RK4(3), tolerance 1e-8) on the same communication grid, relative to
//! its peak, and the cost (steps, right-hand sides). Variants, switched per run by environment
//! variables read by the trial code:
//! - `FLEXROD_NO_LAWSON`: plain RK4(3) (`auto`);
//! - default: Lawson, dense output by cubic Hermite interpolation of the rotating variables;
//! - `FLEXROD_Q5`: Lawson, dense output by the quintic Hermite of `z` (as RK4(3));
//! - `FLEXROD_ETD`: Lawson, dense output by the exponential interpolant: the oscillator's exact
//!   response to the remainder taken as the quadratic through its values at the step's start,
//!   the stages' midpoint and the end;
//! - `FLEXROD_NODENSE`: Lawson landing on every communication point (no dense output);
//! - `FLEXROD_FROZEN`: Lawson with each step's own linear part (the diagonal of the axial
//!   stiffening and of the reduced mass at the step's start), cubic Hermite dense output.
//!
//! `cargo run --release --example exponential_trial`.
use flexrod::drive::{self, communication_grid, CrankDrive};
use flexrod::{Scene, Simulation};

#[derive(Clone, Copy)]
struct Case {
    label: &'static str,
    scene: &'static str,
    modes: Option<&'static str>,
    speed: f64,
    dt: f64,
    t_end: f64,
    tolerances: &'static [&'static str],
}

const SWITCHES: [&str; 5] = [
    "FLEXROD_NO_LAWSON",
    "FLEXROD_ETD",
    "FLEXROD_Q5",
    "FLEXROD_NODENSE",
    "FLEXROD_FROZEN",
];

fn series(case: &Case, tol: &str, switch: Option<&str>, grid: &[f64]) -> (Vec<f64>, u64, u64) {
    let mut text = std::fs::read_to_string(case.scene).unwrap();
    if let Some(m) = case.modes {
        text = text.replace("modes = 3", &format!("modes = {m}"));
    }
    text = text.replace("tolerance = 1e-3", &format!("tolerance = {tol}"));
    for s in SWITCHES {
        std::env::remove_var(s);
    }
    if let Some(s) = switch {
        std::env::set_var(s, "1");
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
            label: "default scene (3 modes), 2 revolutions, 3e-4 s grid",
            scene: "scenes/benchmark.toml",
            modes: None,
            speed: 150.0,
            dt: 3e-4,
            t_end: 0.0838,
            tolerances: &["1e-4", "1e-3"],
        },
        Case {
            label: "the same with modes = 1",
            scene: "scenes/benchmark.toml",
            modes: Some("1"),
            speed: 150.0,
            dt: 3e-4,
            t_end: 0.0838,
            tolerances: &["1e-4", "1e-3"],
        },
        Case {
            label: "automotive rod (7 modes), 2 revolutions at 628.3 rad/s, 1e-5 s grid",
            scene: "scenes/automotive_rod.toml",
            modes: None,
            speed: 628.3,
            dt: 1e-5,
            t_end: 0.02,
            tolerances: &["1e-3"],
        },
    ];
    println!("| case | tolerance | RK4(3) (`auto`) | Lawson, dense output cubic in the rotating variables | Lawson, dense output quintic in z | Lawson, dense output exponential (ETD, quadratic remainder) | Lawson, landing on every point | Lawson, each step's own linear part |");
    println!("|---|---|---|---|---|---|---|---|");
    for case in &cases {
        let grid = communication_grid(0.0, case.dt, (case.t_end / case.dt) as usize);
        let (reference, _, _) = series(case, "1e-8", Some("FLEXROD_NO_LAWSON"), &grid);
        let peak = reference.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        for tol in case.tolerances {
            let mut cells = Vec::new();
            for switch in [
                Some("FLEXROD_NO_LAWSON"),
                None,
                Some("FLEXROD_Q5"),
                Some("FLEXROD_ETD"),
                Some("FLEXROD_NODENSE"),
                Some("FLEXROD_FROZEN"),
            ] {
                let (x, steps, rhs) = series(case, tol, switch, &grid);
                let err = x
                    .iter()
                    .zip(&reference)
                    .fold(0.0f64, |a, (x, r)| a.max((x - r).abs()))
                    / peak;
                cells.push(format!("{steps} / {rhs} / {err:.1e}"));
            }
            println!("| {} | {tol} | {} |", case.label, cells.join(" | "));
        }
    }
    println!("(each cell: steps / right-hand sides / pointwise error of v_mid/L over its peak)");
}
