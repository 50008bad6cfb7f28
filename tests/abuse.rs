//! Trustworthy under abuse: the core refuses what it cannot do well, with the state
//! kept and a message naming the value and the limit.

mod common;

use std::time::Instant;

use flexrod::scene::{RodModelKind, SolverMethod};
use flexrod::{ModelError, Scene, Simulation};

fn started(scene: &Scene, speed: f64) -> Simulation {
    let mut sim = Simulation::new(scene).expect("model builds");
    common::runs::start_at(&mut sim, speed);
    sim
}

fn scene(model: RodModelKind, elements: usize) -> Scene {
    let mut s = Scene::benchmark();
    s.rod.model = model;
    s.rod.elements = elements;
    if model == RodModelKind::Segments {
        s.solver.method = SolverMethod::GeneralizedAlpha;
    }
    s
}

/// The declared range of `rod.elements` works (built and run at the limit, in
/// bounded time and memory); limit + 1 is refused naming the value and the range.
#[test]
fn element_limits_work_and_limit_plus_one_is_refused() {
    let ffr = flexrod::beam::mesh::MAX_ELEMENTS;
    let seg = flexrod::rod::segments::SEGMENT_RANGE.1;
    assert_eq!((ffr, seg), (128, 128));
    for (model, n) in [(RodModelKind::Ffr, ffr), (RodModelKind::Segments, seg)] {
        let t0 = Instant::now();
        let mut sim = started(&scene(model, n), 150.0);
        for _ in 0..40 {
            sim.advance(1e-3).expect("the limit runs");
        }
        let took = t0.elapsed().as_secs_f64();
        let status = std::fs::read_to_string("/proc/self/status").unwrap();
        let hwm = status.lines().find(|l| l.starts_with("VmHWM")).unwrap();
        println!("{model:?} rod.elements = {n}: build + 40 ms of motion in {took:.3} s, {hwm}");
        assert!(took < 10.0, "{took} s");
        let err = Simulation::new(&scene(model, n + 1))
            .err()
            .expect("refused");
        let text = err.to_string();
        println!("{model:?} {}: {text}", n + 1);
        assert!(
            text.contains("rod.elements")
                && text.contains(&format!("rod.elements = {} ", n + 1))
                && text.contains(&format!("1..={n}")),
            "{text}"
        );
    }
}

/// A communication step needing more than `MAX_INTERNAL_STEPS` internal steps is
/// refused within seconds, the state kept; continuing with legal steps gives the outputs of a run
/// that never tried.
#[test]
fn huge_communication_steps_are_refused_with_the_state_kept() {
    let mut fixed = Scene::benchmark();
    fixed.solver.method = SolverMethod::Rk4;
    fixed.solver.step = 3e-4;
    for (label, s) in [
        ("default (adaptive)", Scene::benchmark()),
        ("rk4 3e-4 s", fixed),
    ] {
        for h in [1e3, 1e9] {
            let mut sim = started(&s, 150.0);
            sim.advance(1e-3).unwrap();
            let mut reference = started(&s, 150.0);
            reference.advance(1e-3).unwrap();
            let before = sim.state().clone();
            let t0 = Instant::now();
            let err = sim.advance(h).expect_err("refused");
            let took = t0.elapsed().as_secs_f64();
            println!("{label}, h = {h:e} s: refused in {took:.2} s: {err}");
            assert!(matches!(err, ModelError::TooMuchWork { .. }), "{err}");
            assert!(took < 20.0, "{took} s");
            let text = err.to_string();
            assert!(
                text.contains(&format!("{}", flexrod::mechanism::MAX_INTERNAL_STEPS)),
                "{text}"
            );
            assert_eq!(sim.state(), &before);
            for _ in 0..5 {
                sim.advance(1e-3).unwrap();
                reference.advance(1e-3).unwrap();
                assert_eq!(sim.outputs(), reference.outputs());
            }
        }
    }
}

/// Core state bytes with a correct header and fingerprint but fields out of range
/// are rejected, the state unchanged (offsets: 20 header bytes, then f64 fields in the order of
/// `MechanismState::write_bytes`).
#[test]
fn crafted_state_bytes_are_rejected_field_by_field() {
    let mut sim = started(&Scene::benchmark(), 150.0);
    for _ in 0..3 {
        sim.advance(1e-3).unwrap();
    }
    let good = sim.snapshot_to_bytes();
    let before = sim.state().clone();
    let f = |k: usize| 20 + 8 * k;
    let cases: [(&str, usize, f64, &str); 12] = [
        ("time NaN", f(0), f64::NAN, "the time is NaN"),
        ("input time after time", f(1), 1.0, "input law starts"),
        (
            "NaN previous jerk",
            f(6),
            f64::NAN,
            "the previous crank jerk is NaN",
        ),
        ("infinite speed", f(8), f64::INFINITY, "crank.speed is inf"),
        ("NaN jerk", f(10), f64::NAN, "the crank jerk is NaN"),
        ("jerk beyond its window", f(10), 2e12, "crank jerk"),
        ("NaN slider force", f(11), f64::NAN, "slider.force"),
        ("NaN output", f(14), f64::NAN, "pinB.force_x is NaN"),
        ("integrator time differs", f(21), 0.5, "integrator time"),
        ("negative step proposal", f(22), -1e-4, "step proposal"),
        (
            "negative start vibration",
            f(24),
            -1.0,
            "start's vibration amplitude",
        ),
        ("NaN coordinate", f(25), f64::NAN, "a coordinate is NaN"),
    ];
    for (label, at, x, expected) in cases {
        let mut bytes = good.clone();
        bytes[at..at + 8].copy_from_slice(&x.to_le_bytes());
        let e = sim.restore_from_bytes(&bytes).expect_err(label).to_string();
        println!("{label}: {e}");
        assert!(e.contains(expected), "{label}: {e}");
        assert_eq!(sim.state(), &before);
    }
    // The held-step flag: the last byte, or the byte before the held step's values (the
    // communication step's last internal step may reach past it, `steps_past_is_cheaper`).
    let st = sim.state();
    let held_len = if st.ahead.held {
        8 * (3 + 4 * st.ahead.z0.len() + 4 * st.dae.q.len() + st.dae.lambda.len())
    } else {
        0
    };
    let mut flag = good.clone();
    let at = flag.len() - 1 - held_len;
    assert_eq!(flag[at], st.ahead.held as u8);
    flag[at] = 7;
    let e = sim.restore_from_bytes(&flag).expect_err("flag 7");
    assert!(e.to_string().contains("held-step flag is 7"), "{e}");
    assert_eq!(sim.state(), &before);
    sim.restore_from_bytes(&good)
        .expect("the original bytes are accepted");
}

/// The deflection policy in the core. Beyond `rod.deflection_limit`: warn continues
/// with one warning; discard and error refuse the step with the state from before it kept.
#[test]
fn deflection_policy_warn_discard_error() {
    use flexrod::scene::DeflectionPolicy;
    let run = |policy: DeflectionPolicy, limit: f64| {
        let mut s = Scene::benchmark();
        s.rod.deflection_policy = policy;
        s.rod.deflection_limit = Some(limit);
        let mut sim = started(&s, 150.0);
        let mut rows = vec![sim.outputs()];
        let mut warnings = 0;
        for _ in 0..150 {
            let before = sim.state().clone();
            match sim.advance(1e-4) {
                Ok(_) => rows.push(sim.outputs()),
                Err(e) => {
                    assert_eq!(sim.state(), &before, "state kept");
                    return (rows, warnings, Some(e));
                }
            }
            // The deflection limit's warnings (the error estimate's may come too).
            warnings += sim
                .take_warnings()
                .iter()
                .filter(|w| w.contains("exceeds rod.deflection_limit"))
                .count();
        }
        (rows, warnings, None)
    };
    let (reference, w, e) = run(DeflectionPolicy::Warn, 1.0);
    assert!(e.is_none() && w == 0);
    let peak = reference
        .iter()
        .map(|o| o.deflection_rel.abs())
        .fold(0.0, f64::max);
    let limit = 0.5 * peak;
    let first = reference
        .iter()
        .position(|o| o.deflection_rel.abs() > limit)
        .unwrap();
    let (rows, w, e) = run(DeflectionPolicy::Warn, limit);
    assert!(e.is_none() && w == 1 && rows == reference);
    for policy in [DeflectionPolicy::Discard, DeflectionPolicy::Error] {
        let (rows, _, e) = run(policy, limit);
        let e = e.expect("refused");
        println!("{policy:?}: {e}");
        assert!(matches!(e, ModelError::DeflectionLimit { .. }));
        assert!(e.to_string().contains("rod.deflection_limit"));
        assert_eq!(rows.len(), first);
        assert_eq!(rows[..], reference[..first]);
    }
}
