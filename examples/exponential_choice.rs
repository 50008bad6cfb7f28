//! Why `auto` takes the exponential form of the RK4(3) pair where the modes are the
//! mechanism's own oscillators (the pinned rod's modes; mass-loaded modes that carry the
//! piston) and the classic pair where free modes move the pins. For each case, `solver.method = "rk43"`
//! (the classic pair) against `"exponential"` (ETDRK4, the modal oscillators exact) at
//! tolerance 1e-3, each against a run of the classic pair at tolerance 1e-8 on the same
//! communication grid: steps / right-hand sides / pointwise error over the reference's peak of
//! `v_mid/L`, pin B x, pin B y, pin C y and the crank torque.
//!
//! `cargo run --release --example exponential_choice`; with `FLEXROD_BLESS=1` it also writes
//! `docs/generated/exponential-choice.md` (embedded in the README).

use flexrod::drive::{self, communication_grid, CrankDrive, Record};
use flexrod::scene::SolverMethod;
use flexrod::{Scene, Simulation};

fn run(scene: &Scene, method: SolverMethod, tolerance: f64, speed: f64, grid: &[f64]) -> Record {
    let mut s = scene.clone();
    s.solver.method = method;
    s.solver.tolerance = tolerance;
    let mut sim = Simulation::new(&s).unwrap();
    drive::run(&mut sim, &CrankDrive::Constant { speed }, 0.0, grid).unwrap()
}

/// The outputs compared, one series each.
fn series(r: &Record) -> [Vec<f64>; 5] {
    [
        r.outputs.iter().map(|o| o.deflection_rel).collect(),
        r.outputs.iter().map(|o| o.pin_b_force[0]).collect(),
        r.outputs.iter().map(|o| o.pin_b_force[1]).collect(),
        r.outputs.iter().map(|o| o.pin_c_force[1]).collect(),
        r.outputs.iter().map(|o| o.crank_torque).collect(),
    ]
}

fn errors(r: &Record, reference: &Record) -> String {
    series(r)
        .iter()
        .zip(series(reference).iter())
        .map(|(x, y)| {
            let peak = y.iter().fold(0.0f64, |a, b| a.max(b.abs()));
            let e = x
                .iter()
                .zip(y)
                .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
            format!("{:.1e}", e / peak)
        })
        .collect::<Vec<_>>()
        .join(", ")
}

fn main() {
    let automotive = {
        let path = "scenes/automotive_rod.toml";
        Scene::from_toml_str(&std::fs::read_to_string(path).unwrap(), path).unwrap()
    };
    let mut free = automotive.clone();
    free.rod.loaded_modes = false;
    free.rod.mode_band_hz = None;
    free.rod.modes = 7;
    // One free axial mode, given (`auto` would take the mass-loaded one for the heavy piston).
    free.rod.axial_modes = Some(1);
    let cases = [
        (
            "default scene (simply supported bending modes: pins in place), 2 revolutions at 150 rad/s, 3e-4 s grid",
            Scene::benchmark(),
            150.0,
            communication_grid(0.0, 3e-4, 279),
        ),
        (
            "automotive rod with 7 free modes (`rod.loaded_modes = false`, `rod.axial_modes = 1`: free axial modes carry the piston, pins move), 2 revolutions at 628.3 rad/s, 1e-5 s grid",
            free,
            628.3,
            communication_grid(0.0, 1e-5, 2000),
        ),
        (
            "automotive rod as shipped (mass-loaded modes to 6 kHz: the piston-rod mode is a mode, effective modal mass 1), 2 revolutions at 628.3 rad/s, 1e-5 s grid",
            automotive,
            628.3,
            communication_grid(0.0, 1e-5, 2000),
        ),
    ];
    let mut text = String::from(
        "<!-- written by `FLEXROD_BLESS=1 cargo run --release --example exponential_choice`: rerun it, do not edit -->\n| case | rk43 (classic RK4(3)) | exponential (ETDRK4) |\n|---|---|---|\n",
    );
    for (label, scene, speed, grid) in cases {
        let reference = run(&scene, SolverMethod::Rk43, 1e-8, speed, &grid);
        let cells: Vec<String> = [SolverMethod::Rk43, SolverMethod::Exponential]
            .into_iter()
            .map(|m| {
                let r = run(&scene, m, 1e-3, speed, &grid);
                format!(
                    "{} / {} / {}",
                    r.stats.steps,
                    r.stats.newton_iterations,
                    errors(&r, &reference)
                )
            })
            .collect();
        text += &format!("| {label} | {} |\n", cells.join(" | "));
    }
    text += "(each cell: steps / right-hand sides / pointwise errors of v_mid/L, pin B x, pin B y, pin C y, crank torque over their peaks; tolerance 1e-3, reference rk43 at 1e-8)\n";
    print!("{text}");
    if std::env::var_os("FLEXROD_BLESS").is_some() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/docs/generated/exponential-choice.md"
        );
        std::fs::write(path, &text).unwrap();
        println!("wrote {path}");
    }
}
