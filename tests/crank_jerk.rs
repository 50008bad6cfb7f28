//! The crank jerk of the input law (`theta_k + omega_k s + alpha_k s^2 / 2 + j_k s^3 / 6`):
//! a master that sets the crank sparsely with its jerk drives the model as the same
//! piecewise-cubic motion set densely does, including the rows read between its input points
//! (communication points that set no input, where the integrator holds a step past the point).

use flexrod::mechanism::CrankLaw;
use flexrod::{CrankInput, Scene, Simulation};

/// A smooth crank speed, rad/s: 150 rad/s with a 20 rad/s ripple at 25 Hz.
fn speed(t: f64) -> f64 {
    150.0 + 20.0 * (2.0 * std::f64::consts::PI * 25.0 * t).sin()
}

/// The outputs every `row` s over `stop` s with the crank set every `input_step` s: with its
/// jerk (`smooth`), or held at the acceleration that reaches the next speed. Also returns the
/// laws set, with their times.
fn sparse_run(
    scene: &Scene,
    input_step: f64,
    row: f64,
    stop: f64,
    smooth: bool,
) -> (Vec<[f64; 4]>, Vec<(f64, CrankInput)>) {
    let mut sim = Simulation::new(scene).unwrap();
    let mut input = CrankInput {
        speed: speed(0.0),
        ..Default::default()
    };
    sim.start(0.0, input, 0.0).unwrap();
    let (n, every) = (
        (stop / row).round() as usize,
        (input_step / row).round() as usize,
    );
    let (mut rows, mut laws, mut input_time) = (vec![], vec![], 0.0);
    for k in 0..n {
        let t = k as f64 * row;
        if k % every == 0 {
            let s = t - input_time;
            input = if smooth {
                input.continued_smoothly(
                    s,
                    exact(t).acceleration,
                    speed(t + input_step),
                    input_step,
                )
            } else {
                let (angle, omega, _) = input.after(s);
                CrankInput {
                    angle,
                    speed: omega,
                    acceleration: (speed(t + input_step) - omega) / input_step,
                    jerk: 0.0,
                }
            };
            input_time = t;
            laws.push((t, input));
            sim.set_input(input).unwrap();
        }
        sim.advance(row).unwrap();
        rows.push(outputs(&sim));
    }
    (rows, laws)
}

/// The same motion as `laws` (piecewise cubic) set densely, every `fine` s, as angle, speed
/// and acceleration (no jerk), rows every `row` s.
fn dense_run(
    scene: &Scene,
    laws: &[(f64, CrankInput)],
    fine: f64,
    row: f64,
    stop: f64,
) -> Vec<[f64; 4]> {
    let at = |t: f64| {
        let i = laws.partition_point(|(t_k, _)| *t_k <= t + 1e-12).max(1) - 1;
        let (t_k, input) = laws[i];
        let (angle, speed, acceleration) = CrankLaw {
            length: 0.0,
            t_k,
            input,
        }
        .kinematics(t);
        CrankInput {
            angle,
            speed,
            acceleration,
            jerk: 0.0,
        }
    };
    let mut sim = Simulation::new(scene).unwrap();
    sim.start(0.0, at(0.0), 0.0).unwrap();
    let (n, every) = (
        (stop / fine).round() as usize,
        (row / fine).round() as usize,
    );
    let mut rows = vec![];
    for k in 0..n {
        sim.set_input(at(k as f64 * fine)).unwrap();
        sim.advance(fine).unwrap();
        if (k + 1) % every == 0 {
            rows.push(outputs(&sim));
        }
    }
    rows
}

/// The compared outputs now: `v_mid/L`, pin B's x force, pin C's y force, the crank torque.
fn outputs(sim: &Simulation) -> [f64; 4] {
    let o = sim.outputs();
    [
        o.deflection_rel,
        o.pin_b_force[0],
        o.pin_c_force[1],
        o.crank_torque,
    ]
}

/// Largest difference of each column relative to the column's peak in `b`.
fn worst(a: &[[f64; 4]], b: &[[f64; 4]]) -> f64 {
    (0..4)
        .map(|c| {
            let peak = b.iter().fold(0.0f64, |m, r| m.max(r[c].abs()));
            let diff = a
                .iter()
                .zip(b)
                .fold(0.0f64, |m, (x, y)| m.max((x[c] - y[c]).abs()));
            diff / peak
        })
        .fold(0.0, f64::max)
}

/// The ripple's motion exactly: angle, speed, acceleration and jerk at `t`.
fn exact(t: f64) -> CrankInput {
    let w = 2.0 * std::f64::consts::PI * 25.0;
    CrankInput {
        angle: 150.0 * t + 20.0 / w * (1.0 - (w * t).cos()),
        speed: speed(t),
        acceleration: 20.0 * w * (w * t).cos(),
        jerk: -20.0 * w * w * (w * t).sin(),
    }
}

/// The default scene at a tight tolerance, the crank set every 2 ms with its jerk, rows every
/// 0.2 ms (communication points that set no input): the piecewise-cubic motion it sets, set
/// densely as angle, speed and acceleration pieces, converges to it as the pieces shrink
/// (their acceleration steps ring the rod in proportion to the piece), to within 1e-3 of the
/// peaks at 2e-6 s pieces. A jerk the model dropped past a communication point would stay.
#[test]
fn sparse_crank_with_jerk_is_the_limit_of_its_motion_set_densely() {
    let mut scene = Scene::benchmark();
    scene.solver.tolerance = 1e-6;
    let (stop, input_step, row) = (0.04, 2e-3, 2e-4);
    let (smooth, laws) = sparse_run(&scene, input_step, row, stop, true);
    let coarse = worst(&smooth, &dense_run(&scene, &laws, 1e-5, row, stop));
    let fine = worst(&smooth, &dense_run(&scene, &laws, 2e-6, row, stop));
    println!(
        "against the motion set every 1e-5 s: {coarse:.2e} of the peaks; every 2e-6 s: {fine:.2e}"
    );
    assert!(fine < 1e-3 && fine < coarse / 3.0, "{coarse:e} {fine:e}");
}

/// The crank's ripple set every 2 ms: with its jerk (the acceleration continuous) the outputs
/// stay within 1 % of the peaks of the exact motion's (set every 1e-5 s with its exact jerk);
/// with the acceleration held over each 2 ms (a step of `h alpha'` at every input point
/// instead of `h^2 alpha'' / 6`) the rod rings ten times as far off.
#[test]
fn jerk_keeps_a_sparsely_set_crank_from_ringing_the_rod() {
    let mut scene = Scene::benchmark();
    scene.solver.tolerance = 1e-6;
    let (stop, input_step, row): (f64, f64, f64) = (0.04, 2e-3, 2e-4);
    let mut sim = Simulation::new(&scene).unwrap();
    sim.start(0.0, exact(0.0), 0.0).unwrap();
    let fine = 1e-5;
    let every = (row / fine).round() as usize;
    let mut reference = vec![];
    for k in 0..(stop / fine).round() as usize {
        sim.set_input(exact(k as f64 * fine)).unwrap();
        sim.advance(fine).unwrap();
        if (k + 1) % every == 0 {
            reference.push(outputs(&sim));
        }
    }
    let smooth = worst(
        &sparse_run(&scene, input_step, row, stop, true).0,
        &reference,
    );
    let held = worst(
        &sparse_run(&scene, input_step, row, stop, false).0,
        &reference,
    );
    println!("against the exact motion: with the jerk {smooth:.2e} of the peaks, the acceleration held {held:.2e}");
    assert!(smooth < 1e-2, "{smooth:e}");
    assert!(held > 10.0 * smooth, "{held:e} {smooth:e}");
}

/// A new jerk alone (the angle, speed and acceleration continue the law) at a communication
/// point past which the integrator holds a step: the held step, taken under the old law, is
/// dropped, and the run equals one whose acceleration there differs by 1e-9 relative (which
/// restarts the integration on the new law), within 1e-8 of the peaks; set twice there, the
/// same run bit for bit. A held step reused
/// would carry the old law's acceleration (here 40 % off) past the point: 5e-3 of the peaks.
/// (The FFR rod on its closed form; the integrators that hold no step have nothing to drop.)
#[test]
fn a_new_jerk_alone_drops_a_step_held_past_the_point() {
    let mut scene = Scene::benchmark();
    scene.rod.model = flexrod::scene::RodModelKind::Ffr;
    let bound = 1e-8;
    let law = CrankInput {
        angle: 0.0,
        speed: 150.0,
        acceleration: 500.0,
        jerk: 0.0,
    };
    let row = 1e-4;
    // The rows, and whether a step was held past the point where the jerk changes: at the
    // first row from the tenth on that holds one (`switch_at`: that row).
    let run = |nudge: f64, switch_at: Option<usize>, twice: bool| {
        let mut sim = Simulation::new(&scene).unwrap();
        sim.start(0.0, law, 0.0).unwrap();
        let (mut rows, mut switched) = (vec![], None);
        for k in 0..60 {
            let held = sim.state().ahead.held;
            let now = match switch_at {
                Some(at) => k == at,
                None => switched.is_none() && k >= 10 && held,
            };
            if now {
                switched = Some((k, held));
                let (angle, speed, acceleration) = law.after(sim.time());
                let new = CrankInput {
                    angle,
                    speed,
                    acceleration: acceleration * (1.0 + nudge),
                    jerk: 2.0e6,
                };
                sim.set_input(new).unwrap();
                if twice {
                    sim.set_input(new).unwrap();
                }
            }
            sim.advance(row).unwrap();
            rows.push(outputs(&sim));
        }
        (rows, switched)
    };
    let (jerk_alone, switched) = run(0.0, None, false);
    let (at, held) = switched.expect("a row from the tenth on holds a step past it");
    let (restarted, _) = run(1e-9, Some(at), false);
    // The same law set twice at the point: the law the state followed is still the one
    // before (so the held step is dropped as well).
    let (set_twice, _) = run(0.0, Some(at), true);
    assert_eq!(set_twice, jerk_alone);
    let difference = worst(&jerk_alone, &restarted);
    println!(
        "{:?}: jerk set at row {at} (a step held past it: {held}), difference {difference:.1e}",
        scene.rod.model
    );
    assert!(held);
    assert!(difference < bound, "{difference:e}");
}
