//! The quasi-static deflected start (`[start] deflection = "quasi_static"`): the rod
//! starts deflected by the inertia loads of its motion, without the start transient.

use flexrod::drive::communication_grid;
use flexrod::scene::{RodModelKind, StartDeflection};
use flexrod::{CrankInput, Scene, Simulation};

mod common;
use common::runs;

const W: f64 = 150.0;
const THETA0: f64 = std::f64::consts::FRAC_PI_2;

fn input(t: f64) -> CrankInput {
    CrankInput {
        angle: THETA0 + W * t,
        speed: W,
        acceleration: 0.0,
        jerk: 0.0,
    }
}

/// v_mid/L at every communication point over `revolutions`, from a start at THETA0.
fn run(scene: &Scene, revolutions: f64, dt: f64) -> Vec<f64> {
    let n = runs::steps_for(W, revolutions, dt);
    let run = runs::drive_inputs(scene, &communication_grid(0.0, dt, n), 0.0, |_, t| input(t));
    assert!(run.error.is_none(), "{}", run.error_text());
    run.deflection_rel()
}

#[test]
fn quasi_static_start_removes_the_start_transient() {
    let dt = 1e-4;
    let per_rev = (2.0 * std::f64::consts::PI / W / dt).round() as usize;
    let mut damped = Scene::benchmark();
    damped.rod.damping_ratio = 0.1;
    // The periodic steady state: 8 revolutions with 10 % modal damping, the last one kept.
    let steady_all = run(&damped, 8.0, dt);
    let steady = &steady_all[steady_all.len() - per_rev - 1..];
    let peak = steady.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let mut errors = Vec::new();
    for deflection in [StartDeflection::Undeformed, StartDeflection::QuasiStatic] {
        let mut s = damped.clone();
        s.start.deflection = deflection;
        let sim = Simulation::new(&s).unwrap();
        let mut sim0 = sim;
        sim0.start(0.0, input(0.0), 0.0).unwrap();
        let st = sim0.state();
        let elastic_acc = st.dae.qdd[3..3 + s.rod.modes]
            .iter()
            .fold(0.0f64, |m, x| m.max(x.abs()));
        let first = run(&s, 1.0, dt);
        // The steady state's revolution starts at the same crank angle (THETA0 + 2 pi k).
        let err = first
            .iter()
            .zip(steady)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
            / peak;
        println!(
            "{deflection:?} start: v_mid/L(0) = {:.4e} (steady state {:.4e}), max |elastic p''| at start {elastic_acc:.3e}, first revolution against the steady state {:.2} % of its peak",
            first[0], steady[0], 100.0 * err
        );
        errors.push((first[0], err, elastic_acc));
    }
    let (undeformed, quasi) = (errors[0], errors[1]);
    // Starts deflected, close to the steady state's deflection at that angle.
    assert!(
        (quasi.0 - steady[0]).abs() < 0.05 * peak,
        "{} vs {}",
        quasi.0,
        steady[0]
    );
    // No elastic acceleration at the start (against the undeformed start's).
    assert!(
        quasi.2 < 1e-6 * undeformed.2,
        "{} vs {}",
        quasi.2,
        undeformed.2
    );
    // The start transient is gone: 5 x closer to the steady state over the first revolution.
    assert!(
        quasi.1 < 0.2 * undeformed.1,
        "{} vs {}",
        quasi.1,
        undeformed.1
    );
}

#[test]
fn quasi_static_start_needs_the_ffr_rod() {
    let mut s = Scene::benchmark();
    s.rod.model = RodModelKind::Segments;
    s.start.deflection = StartDeflection::QuasiStatic;
    // The start state is built with the model: the error comes at once.
    let e = Simulation::new(&s)
        .err()
        .expect("quasi_static with segments is rejected");
    assert!(
        e.to_string().contains("start.deflection") && e.to_string().contains("segments"),
        "{e}"
    );
}

/// An undeformed start at speed rings a free vibration, which the mechanism estimates at the
/// start for the error estimate; a start from rest or a quasi-static start rings none. A saved
/// state carries it, and bytes with a negative one are refused.
#[test]
fn an_undeformed_start_at_speed_carries_its_free_vibration() {
    let at_rest = CrankInput {
        speed: 0.0,
        ..input(0.0)
    };
    let mut amplitudes = Vec::new();
    for (deflection, start, rings) in [
        (StartDeflection::Undeformed, input(0.0), true),
        (StartDeflection::Undeformed, at_rest, false),
        (StartDeflection::QuasiStatic, input(0.0), false),
    ] {
        let mut scene = Scene::benchmark();
        scene.start.deflection = deflection;
        let mut sim = Simulation::new(&scene).unwrap();
        sim.start(0.0, start, 0.0).unwrap();
        let amplitude = sim.state().start_vibration;
        assert_eq!(
            amplitude > 0.0,
            rings,
            "{deflection:?}, {start:?}: {amplitude}"
        );
        amplitudes.push(amplitude);
        let bytes = sim.snapshot_to_bytes();
        let mut other = Simulation::new(&scene).unwrap();
        other.start(0.0, at_rest, 0.0).unwrap();
        other.restore_from_bytes(&bytes).unwrap();
        assert_eq!(other.state().start_vibration, amplitude);
    }
    // The benchmark rod released at a quarter revolution (THETA0): the quasi-static deflection
    // there is most of the forced motion's, 1 to 2 % of L at 150 rad/s.
    assert!((3e-3..3e-2).contains(&amplitudes[0]), "{}", amplitudes[0]);
    // The amplitude's place in the bytes: after the magic, version and fingerprint (20 bytes),
    // 24 numbers (times, the two laws' inputs with their jerks, slider force, outputs, t, step
    // hint, amplitude).
    let mut sim = Simulation::new(&Scene::benchmark()).unwrap();
    sim.start(0.0, input(0.0), 0.0).unwrap();
    let mut bytes = sim.snapshot_to_bytes();
    let at = 20 + 8 * 24;
    assert_eq!(
        f64::from_le_bytes(bytes[at..at + 8].try_into().unwrap()),
        sim.state().start_vibration
    );
    bytes[at..at + 8].copy_from_slice(&(-1.0f64).to_le_bytes());
    let before = sim.state().clone();
    let error = sim.restore_from_bytes(&bytes).unwrap_err().to_string();
    assert!(error.contains("start's vibration amplitude"), "{error}");
    assert_eq!(sim.state(), &before);
}

/// A short, stiff rod with a heavy slider at speed, axial dynamics on (L = 0.2 m, a 10 x 10 mm
/// steel section, r = 0.05 m, 300 rad/s, a 0.5 kg slider): the quasi-static start converges,
/// and its pin C force is the steady one, `m r w^2 (1 + r / L)` at top dead centre to the
/// rod's own inertia.
#[test]
fn quasi_static_start_converges_with_axial_dynamics() {
    use flexrod::rod::PhysicsSwitch;
    let mut s = Scene::benchmark();
    s.crank.length = 0.05;
    s.rod.length = 0.2;
    s.rod.area = 1e-4;
    s.rod.area_moment = 1e-8 / 12.0;
    s.slider.mass = 0.5;
    s.rod.axial_dynamics = PhysicsSwitch::On;
    s.start.deflection = StartDeflection::QuasiStatic;
    let mut sim = Simulation::new(&s).unwrap();
    let start = CrankInput {
        angle: 0.0,
        speed: 300.0,
        acceleration: 0.0,
        jerk: 0.0,
    };
    sim.start(0.0, start, 0.0)
        .unwrap_or_else(|e| panic!("the quasi-static start with axial dynamics: {e}"));
    let fc = sim.outputs().pin_c_force;
    let steady = 0.5 * 0.05 * 300.0 * 300.0 * (1.0 + 0.05 / 0.2);
    println!("pin C force at the start: {fc:?}, m r w^2 (1 + r / L) = {steady} N");
    assert!((fc[0].abs() - steady).abs() < 1e-3 * steady, "{fc:?}");
}

/// The rows of `tests/data/random_rods/rods.csv` (44 random rods: L/h 8 to 60, sliders up to
/// twice the rod's mass, end bodies on half) by column name.
fn random_rods() -> Vec<std::collections::HashMap<String, String>> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/random_rods/rods.csv"
    );
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    lines
        .map(|l| {
            header
                .iter()
                .cloned()
                .zip(l.split(',').map(String::from))
                .collect()
        })
        .collect()
}

/// With axial dynamics on, the quasi-static start converges on every random rod at its speed
/// (all well below buckling), and on the automotive rod at 6000 rpm: its elastic
/// accelerations are zero to the solver's round-off.
#[test]
fn quasi_static_start_with_axial_dynamics_on_every_random_rod() {
    use flexrod::rod::PhysicsSwitch;
    let rods = random_rods();
    assert_eq!(rods.len(), 44);
    let mut scenes = Vec::new();
    for rod in &rods {
        let x = |k: &str| rod[k].parse::<f64>().unwrap();
        let mut s = Scene::benchmark();
        s.rod.model = RodModelKind::Ffr;
        s.crank.length = x("crank_length");
        s.rod.length = x("rod_length");
        s.rod.youngs_modulus = x("youngs_modulus");
        s.rod.density = x("density");
        s.rod.area = x("area");
        s.rod.area_moment = x("area_moment");
        s.rod.shear_modulus = Some(x("shear_modulus"));
        s.rod.shear_area = Some(x("shear_area"));
        s.slider.mass = x("slider_mass");
        s.rod.big_end.mass = x("big_end_mass");
        s.rod.big_end.inertia = x("big_end_inertia");
        s.rod.small_end.mass = x("small_end_mass");
        s.rod.small_end.inertia = x("small_end_inertia");
        scenes.push((format!("random rod {}", rod["id"]), s, x("W")));
    }
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/automotive_rod.toml");
    let automotive = Scene::from_file(std::path::Path::new(path)).unwrap();
    scenes.push(("automotive rod".into(), automotive, 628.3));
    for (name, mut s, speed) in scenes {
        s.rod.axial_dynamics = PhysicsSwitch::On;
        s.start.deflection = StartDeflection::QuasiStatic;
        let mut sim = Simulation::new(&s).unwrap_or_else(|e| panic!("{name}: {e}"));
        let start = CrankInput {
            angle: 0.3,
            speed,
            acceleration: 0.0,
            jerk: 0.0,
        };
        sim.start(0.0, start, 0.0)
            .unwrap_or_else(|e| panic!("{name} at {speed} rad/s: {e}"));
        assert!(sim.outputs().deflection_rel.is_finite(), "{name}");
    }
}

/// Where the quasi-static start is refused, the rod is at or above buckling: a slider force
/// pushing the rod at 0.95 of the Euler load `pi^2 E I / L^2` starts (deflected), at 1.05 times
/// it the start is refused naming buckling.
#[test]
fn quasi_static_start_is_refused_only_at_or_above_buckling() {
    use flexrod::rod::PhysicsSwitch;
    let mut s = Scene::benchmark();
    s.rod.model = RodModelKind::Ffr;
    s.rod.axial_dynamics = PhysicsSwitch::On;
    s.start.deflection = StartDeflection::QuasiStatic;
    let euler = std::f64::consts::PI.powi(2) * s.rod.youngs_modulus * s.rod.area_moment
        / s.rod.length.powi(2);
    // At crank angle 0 the slider is at +x: a force along -x compresses the rod.
    let at_rest = CrankInput {
        angle: 0.0,
        speed: 1.0,
        acceleration: 0.0,
        jerk: 0.0,
    };
    for (share, starts) in [(0.5, true), (0.95, true), (1.05, false), (1.5, false)] {
        let mut sim = Simulation::new(&s).unwrap();
        let result = sim.start(0.0, at_rest, -share * euler);
        match (starts, result) {
            (true, Ok(())) => {}
            (false, Err(e)) => assert!(e.to_string().contains("buckling"), "{e}"),
            (_, r) => panic!("{share} x the Euler load {euler:.1} N: {r:?}"),
        }
    }
}
