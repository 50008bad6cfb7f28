//! What each real-rod feature costs: the automotive rod (scenes/automotive_rod.toml), two
//! revolutions at 6000 rpm (2000 communication steps of 1e-5 s) with the 38 kN gas pulse of
//! tests/real_rod_mechanics.rs, run with and without each feature; the median wall time of
//! several repeats. `cargo run --release --example rod_feature_costs` prints the table;
//! `-- --write` (or `FLEXROD_BLESS=1`) also writes docs/generated/rod-feature-costs.md (embedded
//! in docs/performance.md). Times depend on the machine and its load: a reader reruns the
//! command. The internal steps do not: `tests/rod_feature_costs.rs` (which includes this file
//! for [`cases`] and [`run`]) recomputes them and fails when the fragment's differ.

use flexrod::scene::{RodModelKind, SolverMethod};
use flexrod::{CrankInput, Scene, Simulation};

fn gas(theta: f64) -> f64 {
    let d = (theta - 15f64.to_radians()) / 20f64.to_radians();
    -38.0e3 * (-d * d).exp()
}

/// The fragment this example writes.
pub const FRAGMENT: &str = "docs/generated/rod-feature-costs.md";

/// One run; (seconds, internal steps).
pub fn run(scene: &Scene) -> (f64, u64) {
    let w = scene.experiment.crank_speed;
    let dt = scene.experiment.step_size;
    let n = ((scene.experiment.stop_time - scene.experiment.start_time) / dt).round() as usize;
    let input = |t: f64| CrankInput {
        angle: w * t,
        speed: w,
        acceleration: 0.0,
        jerk: 0.0,
    };
    let clock = std::time::Instant::now();
    let mut sim = Simulation::new(scene).unwrap();
    sim.start(0.0, input(0.0), gas(0.0)).unwrap();
    for k in 0..n {
        let t = k as f64 * dt;
        sim.set_input(input(t)).unwrap();
        sim.set_slider_force(gas(w * (t + 0.5 * dt))).unwrap();
        sim.advance(dt).unwrap();
    }
    (clock.elapsed().as_secs_f64(), sim.stats().steps)
}

/// The rows of the table: (name, scene), the shipped automotive rod first.
pub fn cases() -> Vec<(&'static str, Scene)> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/automotive_rod.toml");
    let base = Scene::from_file(std::path::Path::new(path)).unwrap();
    let with = |f: &dyn Fn(&mut Scene)| {
        let mut s = base.clone();
        f(&mut s);
        s
    };
    let uniform = |s: &mut Scene| {
        // The table's length means as a uniform rod (no table, so no fibre distances).
        let p = s.rod.properties();
        s.rod.section.clear();
        s.rod.area = p.area;
        s.rod.area_moment = p.area_moment;
        s.outputs.stress = false;
    };
    let cases: Vec<(&str, Scene)> = vec![
        (
            "as shipped: table (3 stations), shear, end bodies, stress outputs; FFR 8 el, mass-loaded modes to 6 kHz (3), residual flexibility above",
            base.clone(),
        ),
        (
            "without the stress outputs",
            with(&|s| s.outputs.stress = false),
        ),
        (
            "without shear deformation",
            with(&|s| {
                s.rod.shear_deformation = flexrod::rod::PhysicsSwitch::Off;
                s.rod.shear_modulus = None;
            }),
        ),
        (
            "without end bodies",
            with(&|s| {
                s.rod.big_end = Default::default();
                s.rod.small_end = Default::default();
            }),
        ),
        (
            "uniform section instead of the table (stress off)",
            with(&uniform),
        ),
        (
            "stress off and uniform, no shear, no end bodies (the plain rod)",
            with(&|s| {
                uniform(s);
                s.rod.shear_deformation = flexrod::rod::PhysicsSwitch::Off;
                s.rod.shear_modulus = None;
                s.rod.big_end = Default::default();
                s.rod.small_end = Default::default();
            }),
        ),
        (
            "7 mass-loaded modes (to 22 kHz) instead of the band, no residual flexibility",
            with(&|s| {
                s.rod.mode_band_hz = None;
                s.rod.modes = 7;
                s.rod.axial_modes = Some(1);
            }),
        ),
        (
            "16 elements, 8 modes, tolerance 1e-5 (all targets of tests/automotive_reference.rs)",
            with(&|s| {
                s.rod.elements = 16;
                s.rod.mode_band_hz = None;
                s.rod.modes = 8;
                s.rod.axial_modes = Some(1);
                s.solver.method = SolverMethod::Dopri5;
                s.solver.tolerance = 1e-5;
            }),
        ),
        (
            "segment chain, 32 segments, shear slides and axial springs (within 0.5 % of the shear beam)",
            with(&|s| {
                s.rod.model = RodModelKind::Segments;
                s.rod.elements = 32;
                s.rod.axial_springs = true;
            }),
        ),
        (
            "segment chain, 32 segments, shear slides, axially rigid",
            with(&|s| {
                s.rod.model = RodModelKind::Segments;
                s.rod.elements = 32;
                s.rod.axial_dynamics = flexrod::rod::PhysicsSwitch::Off;
            }),
        ),
        (
            "segment chain, 32 segments, no shear slides, axially rigid",
            with(&|s| {
                s.rod.model = RodModelKind::Segments;
                s.rod.elements = 32;
                s.rod.axial_dynamics = flexrod::rod::PhysicsSwitch::Off;
                s.rod.shear_deformation = flexrod::rod::PhysicsSwitch::Off;
                s.rod.shear_modulus = None;
            }),
        ),
    ];
    cases
}

fn main() {
    let write = std::env::args().any(|a| a == "--write")
        || std::env::var_os("FLEXROD_BLESS").is_some_and(|v| v == "1");
    let cases = cases();
    let mut table = String::from(
        "| automotive rod, 2 revolutions at 6000 rpm with the gas pulse | wall time (median of 5) | relative | internal steps |\n|---|---|---|---|\n",
    );
    let mut reference = None;
    for (name, scene) in &cases {
        let mut times: Vec<f64> = Vec::new();
        let mut steps = 0;
        for _ in 0..5 {
            let (t, s) = run(scene);
            times.push(t);
            steps = s;
        }
        times.sort_by(f64::total_cmp);
        let median = times[2];
        let r = *reference.get_or_insert(median);
        let row = format!(
            "| {name} | {:.0} ms | {:.2} | {steps} |\n",
            median * 1e3,
            median / r
        );
        print!("{row}");
        table += &row;
    }
    if write {
        let out = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(FRAGMENT);
        std::fs::write(&out, &table).unwrap();
        println!("wrote {}", out.display());
    }
}
