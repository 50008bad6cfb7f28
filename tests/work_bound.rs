//! The time of one call at the declared maxima, measured: the initialization (building the
//! model and its start) and one communication step (what `fmi2DoStep` / `fmi3DoStep` runs)
//! of the largest models, with a communication step long enough to use up the work budget
//! (`flexrod::mechanism::WORK_BUDGET`). Machine-dependent, so ignored in the suite:
//! `FLEXROD_BLESS=1 cargo test --release --test work_bound -- --ignored --nocapture` writes the
//! fragment `worst-case-time` (docs/fmu.md, "Time per call"); without `FLEXROD_BLESS` it
//! prints the table. A second test (in the suite) checks that the budget refuses such a step
//! with the state kept.

mod common;

use std::time::Instant;

use common::runs::{automotive_with, start_at};
use flexrod::beam::section_table::MAX_STATIONS;
use flexrod::beam::SectionStation;
use flexrod::mechanism::stepping::evaluations_allowed;
use flexrod::scene::{RodModelKind, SolverMethod};
use flexrod::{ModelError, Scene, Simulation};

/// The largest FFR rod: 128 elements, every mode retained, soft and heavy (many internal steps).
fn largest_ffr() -> Scene {
    let mut s = Scene::benchmark();
    s.rod.model = flexrod::rod::RodModelKind::Ffr;
    s.rod.elements = flexrod::beam::mesh::MAX_ELEMENTS;
    s.rod.modes = 3 * s.rod.elements;
    s.rod.youngs_modulus = 1e6;
    s.rod.density = 1e5;
    s
}

/// The largest segment chain: 128 segments, the stiffest rod.
fn largest_segments() -> Scene {
    let mut s = Scene::benchmark();
    s.rod.model = RodModelKind::Segments;
    s.rod.elements = flexrod::rod::segments::SEGMENT_RANGE.1;
    s.solver.method = SolverMethod::GeneralizedAlpha;
    s.rod.youngs_modulus = 1e17;
    s.rod.density = 10.0;
    s
}

/// `scene` with the most `[[rod.section]]` stations (the uniform section, tapered slightly).
fn with_most_stations(mut s: Scene) -> Scene {
    let (area, moment, length) = (s.rod.area, s.rod.area_moment, s.rod.length);
    s.rod.section = (0..MAX_STATIONS)
        .map(|k| {
            let f = 1.0 + 0.1 * (k % 3) as f64;
            SectionStation {
                position: length * k as f64 / (MAX_STATIONS - 1) as f64,
                area: area * f,
                area_moment: moment * f,
                shear_area: None,
                fibre_distance: None,
            }
        })
        .collect();
    s.rod.area = 0.0;
    s.rod.area_moment = 0.0;
    s
}

/// Seconds of one communication step of `h`, and its outcome.
fn one_step(sim: &mut Simulation, h: f64) -> (f64, Result<(), ModelError>) {
    let t0 = Instant::now();
    let r = sim.advance(h).map(|_| ());
    (t0.elapsed().as_secs_f64(), r)
}

/// One row of the worst-case table: build and start `scene`, then one communication step of
/// `h`; (row, initialization s, step s).
fn measure(label: &str, scene: &Scene, h: f64, speed: f64) -> (String, f64, f64) {
    let t0 = Instant::now();
    let built = Simulation::new(scene);
    let mut sim = match built {
        Ok(sim) => sim,
        Err(e) => {
            let init = t0.elapsed().as_secs_f64();
            println!("{label}: refused after {init:.2} s: {e}");
            let why = match e {
                ModelError::TooCostly { .. } => "refused by the cost model",
                _ => "refused",
            };
            return (
                format!("| {label} | - | - | {init:.2} ({why}) | - |"),
                init,
                0.0,
            );
        }
    };
    start_at(&mut sim, speed);
    let init = t0.elapsed().as_secs_f64();
    let n = sim.mechanism().work_coordinates();
    let cost = sim.mechanism().evaluation_cost();
    let (step, outcome) = one_step(&mut sim, h);
    let outcome = match outcome {
        Ok(()) => "completed".to_string(),
        Err(ModelError::TooMuchWork { .. }) => "refused at the work budget".to_string(),
        Err(e) => {
            println!("{label}: {e}");
            "failed, the state kept".to_string()
        }
    };
    println!("{label}: n = {n}, init {init:.2} s, step {step:.2} s, {outcome}");
    (
        format!(
            "| {label} | {n} | {} | {init:.2} | {step:.2} (h = {h} s: {outcome}) |",
            evaluations_allowed(cost)
        ),
        init,
        step,
    )
}

#[test]
#[ignore]
fn worst_case_time_per_call() {
    let mut mid = largest_ffr();
    mid.rod.elements = 48;
    mid.rod.modes = 3 * 48;
    let mut widest = largest_ffr();
    widest.rod.modes = 192;
    let mut stations = with_most_stations(largest_ffr());
    stations.rod.modes = 96;
    let mut fine = Scene::benchmark();
    fine.solver.tolerance = 1e-10;
    let mut soft_segments = largest_segments();
    soft_segments.rod.youngs_modulus = 1e5;
    soft_segments.rod.density = 1e5;
    soft_segments.rod.deflection_policy = flexrod::scene::DeflectionPolicy::Warn;
    let mut soft_tight = automotive_with(1e5, 8, "simply_supported");
    soft_tight.solver.tolerance = 1.4e-6;
    let cases = [
        ("default scene", Scene::benchmark(), 0.5, 150.0),
        ("default scene, solver.tolerance = 1e-10", fine, 0.5, 150.0),
        ("FFR, 48 elements, 144 modes", mid, 1e-2, 150.0),
        ("FFR, 128 elements, 192 modes", widest, 1e-2, 150.0),
        ("FFR, 128 elements, 384 modes", largest_ffr(), 1e-2, 150.0),
        (
            "FFR, 128 elements, 96 modes, 256 stations",
            stations,
            1e-2,
            150.0,
        ),
        (
            "automotive, E = 2e8 Pa, 24 elements (43 modes in the band, 11 axial)",
            automotive_with(2e8, 24, "simply_supported"),
            1e-2,
            628.3,
        ),
        (
            "automotive, E = 1e5 Pa, solver.tolerance = 1.4e-6",
            soft_tight,
            1e-2,
            628.3,
        ),
        (
            "automotive, E = 7.95e6 Pa, 52 elements, mean_axis",
            automotive_with(7.95e6, 52, "mean_axis"),
            1e-4,
            628.3,
        ),
        (
            "automotive, E = 7.95e6 Pa, 128 elements, mean_axis",
            automotive_with(7.95e6, 128, "mean_axis"),
            1e-4,
            628.3,
        ),
        ("segments, 128", largest_segments(), 1e-2, 150.0),
        ("segments, 128, soft and heavy", soft_segments, 1e-2, 150.0),
        (
            "segments, 128, 256 stations",
            with_most_stations(largest_segments()),
            1e-2,
            150.0,
        ),
    ];
    let mut rows = Vec::new();
    let (mut worst_init, mut worst_step) = (0.0f64, 0.0f64);
    for (label, scene, h, speed) in cases {
        let (row, init, step) = measure(label, &scene, h, speed);
        rows.push(row);
        worst_init = worst_init.max(init);
        worst_step = worst_step.max(step);
    }
    let markdown = format!(
        "| model at the declared maxima | coordinates n | evaluations per call (budget) | initialization, s | one communication step h, s |\n|---|---:|---:|---:|---|\n{}\n\nWorst case measured: initialization {worst_init:.1} s, one communication step {worst_step:.1} s, against the bound of {} s per call (one thread, release build; `FLEXROD_BLESS=1 cargo test --release --test work_bound -- --ignored --nocapture`).\n",
        rows.join("\n"),
        flexrod::rod::cost::WORST_CALL_SECONDS
    );
    print!("{markdown}");
    assert!(worst_init.max(worst_step) <= flexrod::rod::cost::WORST_CALL_SECONDS);
    if common::blessing() {
        common::check_generated("worst-case-time", &markdown);
    }
}

/// A communication step that needs more than the work budget is refused within the budget's
/// time with the state kept, and smaller steps go on from the same state.
#[test]
fn the_work_budget_refuses_a_long_step_of_a_large_model_with_the_state_kept() {
    let mut scene = largest_ffr();
    scene.rod.elements = 48;
    scene.rod.modes = 3 * 48;
    let mut sim = Simulation::new(&scene).unwrap();
    start_at(&mut sim, 150.0);
    let n = sim.state().dae.q.len();
    let t0 = Instant::now();
    let e = sim.advance(1.0).expect_err("over the budget");
    let took = t0.elapsed().as_secs_f64();
    println!(
        "n = {n}, {} evaluations allowed: refused after {took:.2} s: {e}",
        evaluations_allowed(sim.mechanism().evaluation_cost())
    );
    assert!(matches!(e, ModelError::TooMuchWork { .. }), "{e}");
    assert!(e.to_string().contains("work budget"), "{e}");
    assert_eq!(sim.time(), 0.0);
    assert!(took < 20.0, "{took} s");
    sim.advance(1e-4).expect("a small step goes on");
}

/// The chain on its modes through the projection of the chain's own functions (axial dynamics
/// on, 64 segments with shear slides: the chain's own coordinates, not the reduced ones, set
/// what an evaluation costs): a long communication step is refused by the work budget, which
/// counts the chain's coordinates (`RodBody::work_coordinates`), with the state kept.
#[test]
fn the_work_budget_counts_the_chain_behind_its_modes() {
    let mut scene = Scene::benchmark();
    scene.rod.model = RodModelKind::ModalSegments;
    scene.rod.elements = 64;
    scene.rod.axial_dynamics = flexrod::rod::PhysicsSwitch::On;
    scene.slider.mass = 0.1;
    scene.solver.tolerance = 1e-8;
    let mut sim = Simulation::new(&scene).unwrap();
    start_at(&mut sim, 150.0);
    let n = sim.mechanism().work_coordinates();
    assert!(n > 4 * sim.state().dae.q.len(), "{n}");
    let t0 = Instant::now();
    let e = sim.advance(1.0).expect_err("over the budget");
    let took = t0.elapsed().as_secs_f64();
    println!(
        "work coordinates {n} ({} reduced), {} evaluations allowed: refused after {took:.2} s: {e}",
        sim.state().dae.q.len(),
        evaluations_allowed(sim.mechanism().evaluation_cost())
    );
    assert!(matches!(e, ModelError::TooMuchWork { .. }), "{e}");
    assert_eq!(sim.time(), 0.0);
    assert!(took < 20.0, "{took} s");
    sim.advance(1e-4).expect("a small step goes on");
}

/// The limits of docs/robustness.md, "Limits", from the constants of the code (fragment
/// `limits`): a changed constant fails this test until the fragment is blessed.
#[test]
fn limits() {
    use flexrod::rod::cost;
    let mib = |bytes: f64| bytes / 1048576.0;
    let rows = [
        (
            "time of one call (initialization or one communication step)".to_string(),
            format!("{} s on one core of the reference machine", cost::WORST_CALL_SECONDS),
            "`rod::cost::WORST_CALL_SECONDS`",
        ),
        (
            "work of one communication step".to_string(),
            format!(
                "{:.1e} work units (an evaluation of `n` coordinates: `n^2 (n + 100)` + {:.0e}, plus the FFR rod's axial coupling, {} `na n^2 (na + 3)`)",
                flexrod::mechanism::stepping::WORK_BUDGET,
                cost::EVALUATION_OVERHEAD,
                cost::AXIAL_COUPLING_TERM
            ),
            "`mechanism::stepping::WORK_BUDGET`",
        ),
        (
            "internal steps of one communication step".to_string(),
            format!("{}", flexrod::mechanism::MAX_INTERNAL_STEPS),
            "`mechanism::MAX_INTERNAL_STEPS`",
        ),
        (
            "one evaluation of a model".to_string(),
            format!(
                "at most 1/{} of the work of one communication step, else refused at initialization",
                cost::MIN_EVALUATIONS_PER_CALL
            ),
            "`rod::cost::MIN_EVALUATIONS_PER_CALL`",
        ),
        (
            "building the FFR rod's axial coupling".to_string(),
            format!(
                "{:.1e} work units ({} `4 E na n^2 (na + 1)`), else refused at initialization",
                cost::BUILD_BUDGET,
                cost::AXIAL_BUILD_TERM
            ),
            "`rod::cost::BUILD_BUDGET`",
        ),
        (
            "memory of one rod's precomputed tensors".to_string(),
            format!("{:.0} MiB, else refused at initialization", mib(cost::MAX_MODEL_BYTES)),
            "`rod::cost::MAX_MODEL_BYTES`",
        ),
        (
            "elements (`rod.elements`)".to_string(),
            format!("{}", flexrod::beam::mesh::MAX_ELEMENTS),
            "`beam::mesh::MAX_ELEMENTS`",
        ),
        (
            "`[[rod.section]]` stations".to_string(),
            format!("{MAX_STATIONS}"),
            "`beam::section_table::MAX_STATIONS`",
        ),
        (
            "step halvings (`solver.max_halvings`)".to_string(),
            format!("{}", flexrod::mechanism::stepping::MAX_HALVINGS),
            "`mechanism::stepping::MAX_HALVINGS`",
        ),
        (
            "communication points of one run (`flexrod simulate`, `fmu --simulate`), rows of an `--input` table".to_string(),
            format!("{}", flexrod::limits::MAX_POINTS),
            "`limits::MAX_POINTS`",
        ),
        (
            "a scene file (the command line, the packager, the FMU's `resources/scene.toml`)".to_string(),
            format!("{:.0} MiB", mib(flexrod::limits::SCENE_FILE_CAP as f64)),
            "`limits::SCENE_FILE_CAP`",
        ),
        (
            "an `--input` CSV table, a reference table".to_string(),
            format!("{:.0} MiB", mib(flexrod::limits::CSV_FILE_CAP as f64)),
            "`limits::CSV_FILE_CAP`",
        ),
        (
            "input quoted in a message (a TOML or CSV line, a key, a path, a flag value)".to_string(),
            format!("{} characters, then `... (N bytes)`", flexrod::text::ECHO_CHARS),
            "`text::ECHO_CHARS`",
        ),
        (
            "lowest retained natural frequency of an FFR rod".to_string(),
            format!(
                "at least {:e} of the highest of its eigenproblem",
                flexrod::rod::MIN_RESOLVED_FREQUENCY_RATIO
            ),
            "`rod::MIN_RESOLVED_FREQUENCY_RATIO`",
        ),
    ];
    let mut markdown = String::from("| limit | value | constant |\n|---|---|---|\n");
    for (what, value, constant) in rows {
        markdown += &format!("| {what} | {value} | {constant} |\n");
    }
    common::check_generated("limits", &markdown);
}
