//! Stiff and extreme cases. Every test prints its numbers and asserts an explicit
//! outcome: the run ends bounded and accurate, or in a clean, documented error (a
//! `ModelError::StepFailed` with the state from before the step kept, checked for every failed
//! step by `common::runs::drive_visit`).
//!
//! The table of results in docs/robustness.md and docs/report/extreme.md is generated from these tests
//! (fragment `extreme-cases`, each test measures its rows; checked, or written with
//! `FLEXROD_BLESS=1`, when the whole file runs):
//! `cargo test --release --test extreme -- --nocapture`.

use flexrod::drive::{communication_grid, CrankDrive};
use flexrod::rod::RodPoint;
use flexrod::scene::{DeflectionPolicy, RodModelKind, SolverMethod};
use flexrod::{CrankInput, ModelError, Scene, Simulation};

mod common;
use common::generated::{below, percent, sci, sig, under, Fragment};
use common::runs::{self, max_diff, Run, REV};

const W: f64 = 150.0;

static TABLE: Fragment = Fragment::new(
    "extreme-cases",
    "| case | outcome | numbers |\n|---|---|---|\n",
    &[
        "stiff",
        "flexible",
        "speed600",
        "buckling",
        "speed_step",
        "standstill",
        "angle_jump",
        "communication_steps",
        "all_modes",
        "long_1e3",
        "long_1e4",
        "deflection_policy",
    ],
);

/// The benchmark scene with the fixed-step explicit path (RK4, h 3e-4 s): the integrator
/// these extreme cases were first characterized with, kept so that the table compares like with
/// like. What the default `auto` integrator (error-controlled RK4(3) on minimal coordinates) does beyond the
/// model's range is tested by `default_integrator_refuses_out_of_range_steps`.
fn scene(f: impl FnOnce(&mut Scene)) -> Scene {
    let mut s = benchmark_rk4();
    f(&mut s);
    if s.rod.model == RodModelKind::Segments && s.solver.method == SolverMethod::Rk4 {
        // The segment chain's joints are stiff: generalized-alpha (fixed steps), as before.
        s.solver.method = SolverMethod::GeneralizedAlpha;
    }
    s
}

fn benchmark_rk4() -> Scene {
    let mut s = Scene::benchmark();
    // These cases characterize the model beyond its small-deformation range: warn, continue.
    s.rod.deflection_policy = DeflectionPolicy::Warn;
    s.solver.method = SolverMethod::Rk4;
    s.solver.step = 3e-4;
    s
}

fn constant(t: f64, w: f64) -> CrankInput {
    CrankDrive::Constant { speed: w }.at(t)
}

/// Drive `scene` with `input(k, t_k)` at communication points `k dt`, k <= n, slider force
/// `force`; a failed step ends the run (its contract checked).
fn drive(
    scene: &Scene,
    dt: f64,
    n: usize,
    force: f64,
    input: impl FnMut(usize, f64) -> CrankInput,
) -> Run {
    runs::drive_inputs(scene, &communication_grid(0.0, dt, n), force, input)
}

/// Pin B constraint violation |r_B(q) - r_crank(t)| and |y_C - 0|, m.
fn constraint_drift(sim: &Simulation) -> (f64, f64) {
    let mech = sim.mechanism();
    let st = sim.state();
    let q = &st.dae.q;
    let (pin, _, _) = mech.crank_law(st).pin(st.time);
    let b = mech.rod.point(RodPoint::B, q) - pin;
    let c = mech.rod.point(RodPoint::C, q);
    (b.norm(), c.y.abs())
}

/// Newton iterations (generalized-alpha) or factorizations (RK4) per internal step.
fn per_step(run: &Run) -> f64 {
    let s = run.record.stats;
    s.newton_iterations as f64 / s.steps as f64
}

/// "N" or "1.6 kN".
fn force(f: f64) -> String {
    if f >= 1e3 {
        format!("{} kN", sig(f / 1e3, 2))
    } else {
        format!("{} N", sig(f, 2))
    }
}

/// "5.5 ms", "1.375 ms" (to the microsecond: the times are communication points).
fn ms(t: f64) -> String {
    format!("{} ms", (t * 1e6).round() / 1e3)
}

/// The failure-tolerant loop of `common::runs` is the library's `drive::run`: same outputs, bit
/// for bit, and the same counters.
#[test]
fn helper_loop_is_the_library_loop() {
    let s = benchmark_rk4();
    let (library, _) = runs::constant(&s, W, 1e-4, 0.25);
    let ours = runs::drive_constant(&s, W, 1e-4, library.times.len() - 1, 0.0);
    assert!(ours.error.is_none());
    assert_eq!(library.times, ours.record.times);
    assert_eq!(library.outputs, ours.record.outputs);
    assert_eq!(library.inputs, ours.record.inputs);
    assert_eq!(library.stats, ours.record.stats);
}

// ------------------------------------------------------------------ stiffness extremes

/// E x 1000: bounded, the deflection 1/1000 of the nominal one, the forces those of the rigid rod.
#[test]
fn very_stiff_rod() {
    let dt = 1e-4;
    let n = runs::steps_for(W, 2.0, dt);
    let nominal = drive(&benchmark_rk4(), dt, n, 0.0, |_, t| constant(t, W));
    let stiff = drive(
        &scene(|s| s.rod.youngs_modulus *= 1000.0),
        dt,
        n,
        0.0,
        |_, t| constant(t, W),
    );
    let rigid = drive(&scene(|s| s.rod.modes = 0), dt, n, 0.0, |_, t| {
        constant(t, W)
    });
    assert!(stiff.error.is_none(), "{}", stiff.error_text());
    let ratio = stiff.peak() / nominal.peak();
    // Forces against the rigid rod, after the 1 ms in which the start rings the stiff modes.
    let skip = 10;
    let df = stiff.record.outputs[skip..]
        .iter()
        .zip(&rigid.record.outputs[skip..])
        .map(|(a, b)| {
            (a.pin_b_force[0] - b.pin_b_force[0]).hypot(a.pin_b_force[1] - b.pin_b_force[1])
        })
        .fold(0.0, f64::max)
        / rigid.peak_pin_b_force();
    let st = stiff.record.stats;
    println!(
        "E x 1000: peak |v/L| {:.3e} = {:.4e} x nominal ({:.3e}); pin B force vs rigid rod {:.2e} of peak; steps {}, Newton {}, halvings {}",
        stiff.peak(), ratio, nominal.peak(), df, st.steps, st.newton_iterations, st.halvings
    );
    assert!(ratio > 0.5e-3 && ratio < 2e-3, "{ratio}");
    assert!(df < 1e-2, "{df}");
    assert!(stiff.record.warnings.is_empty());
    assert_eq!(st.halvings, 0);
    TABLE.add(
        "stiff",
        format!(
            "| very stiff rod, E x 1000 (generalized-alpha by `auto`) | bounded, accurate | peak v/L = {} x nominal (1/E scaling ~1e-3); pin B force within {} of the rigid rod; {} Newton/step; {} halvings |",
            sci(ratio, 2),
            percent(df, 2),
            sig(per_step(&stiff), 3),
            st.halvings
        ),
    );
}

/// E / 100: the deflection leaves the small-deformation range; the simulation must say so.
#[test]
fn very_flexible_rod_warns() {
    let dt = 1e-4;
    let n = runs::steps_for(W, 2.0, dt);
    let mut rows = Vec::new();
    for model in [RodModelKind::Ffr, RodModelKind::Segments] {
        let s = scene(|s| {
            s.rod.youngs_modulus /= 100.0;
            s.rod.model = model;
            if model == RodModelKind::Segments {
                s.rod.elements = 16;
            }
        });
        let run = drive(&s, dt, n, 0.0, |_, t| constant(t, W));
        // The model's own limit: 0.05 for the FFR rod, 0.25 for the chain.
        let limit = s.rod.deflection_limit();
        let first_over = run
            .record
            .times
            .iter()
            .zip(&run.record.outputs)
            .find(|(_, o)| o.deflection_rel.abs() > limit)
            .map(|(t, _)| *t);
        println!(
            "E / 100, {model:?}: ran to t = {:.4} s of {:.4} s, peak |v/L| {:.3}, first |v/L| > 0.05 at t = {:?} s, error: {}, warnings: {:?}",
            run.sim.time(),
            n as f64 * dt,
            run.peak(),
            first_over,
            run.error_text(),
            run.record.warnings
        );
        // Both complete, warn at the first communication point beyond the range, and stay
        // finite; the segment chain (geometrically exact) bounds the deflection below the
        // FFR rod's linear modes (measured 0.44 against 0.83).
        assert!(run.error.is_none(), "{model:?}: {}", run.error_text());
        assert!(run.finite());
        assert_eq!(run.deflection_warnings().count(), 1, "{model:?}");
        assert_eq!(run.first_warning(), first_over, "{model:?}");
        // The error estimate (its nonlinear share grows with the deflection) passed the
        // tolerance before the deflection passed its limit, and said so once.
        let estimate_warning = run
            .error_estimate_warning()
            .expect("an error-estimate warning");
        assert!(estimate_warning <= first_over.unwrap(), "{model:?}");
        assert_eq!(
            run.record.warnings.len(),
            2,
            "{model:?}: {:?}",
            run.record.warnings
        );
        rows.push((run.peak(), first_over.unwrap()));
    }
    assert!(rows[1].0 < 0.5 && rows[0].0 > rows[1].0, "{rows:?}");
    TABLE.add(
        "flexible",
        format!(
            "| very flexible rod, E / 100, FFR | warning, then out of range | warning at t = {} (v/L > 0.05, the FFR rod's limit); completes with v/L up to {}: linear modes beyond their range, flagged, not to be trusted |\n\
             | very flexible rod, E / 100, segments N = 16 | warning, bounded large deflection | warning at t = {} (v/L > 0.25, the chain's limit); completes 2 revolutions, peak v/L = {} |",
            ms(rows[0].1),
            sig(rows[0].0, 2),
            ms(rows[1].1),
            sig(rows[1].0, 2)
        ),
    );
}

// ------------------------------------------------------------------ speed extremes

/// 600 rad/s (4 x the benchmark speed): the inertia loads are 16 x larger. The segment chain
/// (geometrically exact) completes with step halvings; the FFR rod leaves its range, and must
/// say so before it leaves the chain's answer.
#[test]
fn speed_600_rad_s() {
    let w = 600.0;
    let dt = 2.5e-5;
    let n = runs::steps_for(w, 2.0, dt);
    let ffr_scene = scene(|s| s.solver.step = dt);
    let ffr = drive(&ffr_scene, dt, n, 0.0, |_, t| constant(t, w));
    let seg = drive(
        &scene(|s| {
            s.rod.model = RodModelKind::Segments;
            s.rod.elements = 32;
            s.solver.step = dt;
        }),
        dt,
        n,
        0.0,
        |_, t| constant(t, w),
    );
    let ffr_name = format!("FFR stiffened 8 el / {} modes", ffr_scene.rod.modes);
    // Each model's own limit: 0.05 for the FFR rod, 0.25 for the chain.
    for (name, run, limit) in [
        (ffr_name.as_str(), &ffr, 0.05),
        ("segments N = 32", &seg, 0.25),
    ] {
        println!(
            "600 rad/s, {name}: ran to {:.4} s of {:.4} s, peak |v/L| {:.3e}, peak |F_B| {:.0} N, halvings {}, {:.2} Newton/step, error: {}, first warning at {:?} s",
            run.sim.time(), n as f64 * dt, run.peak(), run.peak_pin_b_force(), run.record.stats.halvings,
            per_step(run), run.error_text(), run.first_warning()
        );
        assert!(run.error.is_none(), "{name}: {}", run.error_text());
        assert!(run.finite(), "{name}");
        // Beyond the limit: warned at the first communication point past it.
        assert!(run.peak() > limit, "{name}");
        let first_over = run
            .record
            .outputs
            .iter()
            .position(|o| o.deflection_rel.abs() > limit)
            .map(|k| run.record.times[k]);
        assert_eq!(run.first_warning(), first_over, "{name}");
    }
    // The FFR rod against the chain: within its range it follows the chain (to 0.1 % of L
    // until the warning, measured 2.7e-4); beyond it its linear modes run away (measured:
    // peak 1.19 against 0.41), flagged.
    let (xf, xs) = (ffr.deflection_rel(), seg.deflection_rel());
    let t_warn = ffr.first_warning().unwrap();
    let k_warn = ffr.record.times.iter().position(|&t| t == t_warn).unwrap();
    let before = max_diff(&xf[..k_warn], &xs[..k_warn]);
    let after = max_diff(&xf, &xs) / seg.peak();
    println!(
        "600 rad/s: FFR against segments N = 32 before the FFR's warning (t = {t_warn:.5} s): max |delta v/L| {before:.3e}; over the run {:.0} % of the chain's peak, peak {:+.0} %",
        100.0 * after,
        100.0 * (ffr.peak() / seg.peak() - 1.0)
    );
    assert!(before < 1e-3, "{before}");
    assert!(
        ffr.peak() > 2.0 * seg.peak(),
        "{} vs {}",
        ffr.peak(),
        seg.peak()
    );
    assert!(seg.peak() < 0.5, "{}", seg.peak());
    TABLE.add(
        "speed600",
        format!(
            "| 600 rad/s, FFR stiffened, h = 2.5e-5 | warning, then out of range | warning at t = {}; v/L within {} of the segment chain's until then; completes with peak v/L {} against {} for the chain: beyond the FFR range, flagged |\n\
             | 600 rad/s, segments N = 32, h = 2.5e-5 | warning, bounded large deflection | warning at t = {}; completes, peak v/L = {}, peak F_B {}, {} halvings, {} Newton/step |",
            ms(t_warn),
            sci(before, 2),
            sig(ffr.peak(), 2),
            sig(seg.peak(), 2),
            ms(seg.first_warning().unwrap()),
            sig(seg.peak(), 2),
            force(seg.peak_pin_b_force()),
            seg.record.stats.halvings,
            sig(per_step(&seg), 3)
        ),
    );
}

/// A speed step 150 -> 300 rad/s and a reversal 150 -> -150 rad/s at a communication point
/// (the angle stays continuous; the speed jumps).
#[test]
fn speed_step_and_reversal() {
    let dt = 1e-4;
    let n1 = runs::steps_for(W, 1.0, dt);
    let mut rows = Vec::new();
    for w2 in [300.0f64, -150.0] {
        let t1 = n1 as f64 * dt;
        let n = n1 + runs::steps_for(w2, 1.0, dt);
        let run = drive(&benchmark_rk4(), dt, n, 0.0, |k, t| {
            if k < n1 {
                constant(t, W)
            } else {
                CrankInput {
                    angle: W * t1 + w2 * (t - t1),
                    speed: w2,
                    acceleration: 0.0,
                    jerk: 0.0,
                }
            }
        });
        let x = run.deflection_rel();
        let before = runs::peak(&x[..=n1]);
        let after = runs::peak(&x[n1..]);
        let st = run.record.stats;
        println!(
            "speed 150 -> {w2} rad/s at t = {t1:.4} s: peak |v/L| before {before:.3e}, after {after:.3e}; peak |F_B| {:.0} N; halvings {}; error: {}; warnings {:?}",
            run.peak_pin_b_force(), st.halvings, run.error_text(), run.record.warnings
        );
        // Handled transient: the run completes and stays bounded (the velocity jump is an impulse
        // the integrator absorbs in one step).
        assert!(run.error.is_none(), "{}", run.error_text());
        assert!(run.finite());
        // The speed jump is an impulse on the rod (v_B jumps by r |dw|): a large but bounded
        // transient, flagged by the large-deflection warning after the jump.
        assert!(
            before < 0.05 && after > 0.05 && after < 0.5,
            "{after} vs {before}"
        );
        assert!(run.first_warning().unwrap() > t1);
        let (db, dc) = constraint_drift(&run.sim);
        assert!(db < 1e-9 && dc < 1e-9, "{db} {dc}");
        rows.push((before, after, run.peak_pin_b_force(), st.halvings));
    }
    TABLE.add(
        "speed_step",
        format!(
            "| speed step 150 -> 300 rad/s at a communication point | handled transient, bounded | peak v/L {} before, {} after (impulse r dw on pin B), peak F_B {}, warning, {} halvings |\n\
             | speed reversal 150 -> -150 rad/s | handled transient, bounded | peak v/L {} after, peak F_B {}, warning, {} halvings |",
            sci(rows[0].0, 2),
            sig(rows[0].1, 2),
            force(rows[0].2),
            rows[0].3,
            sig(rows[1].1, 2),
            force(rows[1].2),
            rows[1].3
        ),
    );
}

/// Zero speed: outputs constant, deflection zero, forces zero.
#[test]
fn standstill() {
    let dt = 1e-4;
    let input = CrankInput {
        angle: 0.7,
        speed: 0.0,
        acceleration: 0.0,
        jerk: 0.0,
    };
    let run = drive(&benchmark_rk4(), dt, 1000, 0.0, |_, _| input);
    let first = run.record.outputs[0];
    let mut worst_change: f64 = 0.0;
    let mut worst_force: f64 = 0.0;
    let mut worst_deflection: f64 = 0.0;
    for o in &run.record.outputs {
        worst_change = worst_change.max((o.slider_position - first.slider_position).abs());
        worst_deflection = worst_deflection.max(o.deflection.abs());
        for f in o
            .pin_b_force
            .iter()
            .chain(&o.pin_c_force)
            .chain(std::iter::once(&o.crank_torque))
        {
            worst_force = worst_force.max(f.abs());
        }
    }
    println!("standstill, 1000 steps: max |v_mid| {worst_deflection:.1e} m, max |force or torque| {worst_force:.1e}, slider moved {worst_change:.1e} m, Newton {}", run.record.stats.newton_iterations);
    assert!(run.error.is_none());
    assert!(worst_deflection < 1e-15 && worst_force < 1e-9 && worst_change < 1e-15);
    TABLE.add(
        "standstill",
        format!(
            "| standstill (speed 0, angle 0.7 rad), 1000 steps | exact | max v_mid {} m, max force/torque {}, slider moved {} m |",
            under(worst_deflection, 1e-15),
            under(worst_force, 1e-9),
            under(worst_change, 1e-15)
        ),
    );
}

/// The crank angle jumps +0.5 rad between communication points: a legal but violent input (an
/// inconsistent crank position). The contract (bad input never silently corrupts the state):
/// either the run continues bounded, flagged by the large-deflection warning, or the step fails
/// cleanly with StepFailed and the state kept. What each integrator does:
/// - RK4 (the default scene's, by `auto`): its projection puts the rod on the jumped crank; the
///   run continues with the warning at the jump, bounded, the constraints held at the new crank;
/// - generalized-alpha: Newton cannot reach the jumped crank from the old state even with
///   halved steps: StepFailed, the state kept; the importer goes on with a consistent input
///   and the run is exactly the one without the jump.
#[test]
fn crank_angle_jump() {
    let dt = 1e-4;
    let (n0, n1) = (100usize, 200usize);
    let t_jump = n0 as f64 * dt;
    let jumped = |k: usize, t: f64| {
        let mut i = constant(t, W);
        if k >= n0 {
            i.angle += 0.5;
        }
        i
    };
    // RK4: continues.
    let rk4 = drive(&benchmark_rk4(), dt, n0 + n1, 0.0, jumped);
    let after = runs::peak(&rk4.deflection_rel()[n0 + 1..]);
    let (db, dc) = constraint_drift(&rk4.sim);
    println!(
        "angle jump +0.5 rad at t = {t_jump:.4} s, RK4: error: {}; halvings {}, peak |v/L| over the next {n1} steps {after:.3e}, constraint drift at the jumped crank {db:.1e} / {dc:.1e} m, warnings {:?}",
        rk4.error_text(), rk4.record.stats.halvings, rk4.record.warnings
    );
    assert!(rk4.error.is_none(), "{}", rk4.error_text());
    assert!(rk4.finite());
    assert!(after > 0.05 && after < 0.5, "{after}");
    let first = rk4.first_warning().unwrap();
    assert!((first - (t_jump + dt)).abs() < 1e-12, "warning at {first}");
    assert!(db < 1e-9 && dc < 1e-9, "{db} {dc}");
    // Generalized-alpha: a clean StepFailed at the jump (state kept: checked by the loop).
    let ga_scene = scene(|s| s.solver.method = SolverMethod::GeneralizedAlpha);
    let ga = drive(&ga_scene, dt, n0 + n1, 0.0, jumped);
    let error = ga
        .error
        .clone()
        .expect("generalized-alpha: StepFailed at the jump");
    println!("angle jump, generalized-alpha: {error}");
    let ModelError::StepFailed { time, .. } = error else {
        unreachable!()
    };
    assert_eq!(ga.sim.time(), t_jump);
    assert_eq!(ga.record.times.len(), n0 + 1);
    assert!(time >= t_jump && time < t_jump + dt, "{time}");
    assert!(ga.first_warning().is_none());
    // Going on with the consistent input: bit for bit the run that never saw the jump.
    let mut sim = ga.sim;
    let mut continued = Vec::new();
    for k in n0..n0 + n1 {
        sim.set_input(constant(k as f64 * dt, W)).unwrap();
        sim.advance((k + 1) as f64 * dt - sim.time()).unwrap();
        continued.push(sim.outputs());
    }
    let clean = drive(&ga_scene, dt, n0 + n1, 0.0, |_, t| constant(t, W));
    assert!(clean.error.is_none());
    assert_eq!(&clean.record.outputs[n0 + 1..], &continued[..]);
    let halvings = error_halvings(&ga_scene);
    TABLE.add(
        "angle_jump",
        format!(
            "| crank angle jump +0.5 rad, RK4 (the default scene's) | handled transient, bounded | the projection puts the rod on the jumped crank: warning at the jump, v/L up to {}, pin B held at the new crank to {} m, {} halvings |\n\
             | crank angle jump +0.5 rad, generalized-alpha | clean StepFailed | StepFailed after {halvings} halvings, state kept; continuing with the consistent input gives the run without the jump bit for bit |",
            sig(after, 2),
            under(db, 1e-12),
            rk4.record.stats.halvings
        ),
    );
}

/// The number of halvings a failed step tries (the scene's `solver.max_halvings`).
fn error_halvings(scene: &Scene) -> usize {
    scene.solver.max_halvings
}

// ------------------------------------------------------------------ step extremes

/// Communication steps from 1e-7 s to 1e-2 s over the first 10 ms (solver step 3e-4 s): all
/// complete, and v_mid/L at t = 10 ms agrees with a fine run.
#[test]
fn communication_steps_from_1e_7_to_1e_2() {
    let t_end = 1e-2;
    let fine = drive(
        &scene(|s| s.solver.step = 1e-6),
        1e-6,
        10_000,
        0.0,
        |_, t| constant(t, W),
    );
    let reference = fine.record.outputs.last().unwrap().deflection_rel;
    let scale = fine.peak();
    let mut cells = Vec::new();
    for dt in [1e-7f64, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2] {
        let n = (t_end / dt).round() as usize;
        let run = drive(&benchmark_rk4(), dt, n, 0.0, |_, t| constant(t, W));
        let v = run.record.outputs.last().unwrap().deflection_rel;
        let e = (v - reference).abs() / scale;
        let st = run.record.stats;
        println!(
            "comm step {dt:.0e}: {n} calls, {} internal steps, {} Newton, {} halvings, v/L(10 ms) {v:.5e} (fine {reference:.5e}), error {:.2e} of the peak",
            st.steps, st.newton_iterations, st.halvings, e
        );
        assert!(run.error.is_none());
        assert!((run.sim.time() - t_end).abs() < 1e-12);
        assert!(e < 2e-2, "{dt}: {e}");
        assert_eq!(st.halvings, 0);
        cells.push(format!("{} ({dt:.0e})", below(e, 1e-10)));
    }
    TABLE.add(
        "communication_steps",
        format!(
            "| communication steps 1e-7 ... 1e-2 s (first 10 ms) | all complete, accurate | v/L(10 ms) against a run at h = 1e-6: {} of the peak; 0 halvings; 1e-7: 1e5 calls |",
            cells.join(", ")
        ),
    );
}

/// 8 elements with all 24 modes (simply supported) against the default scene's 3 modes.
#[test]
fn all_modes_kept() {
    let dt = 1e-4;
    let n = runs::steps_for(W, 2.0, dt);
    // The lowest 24 modes whatever their kind (`rod.axial_modes` given: every mode counts).
    let all = scene(|s| {
        s.rod.modes = 24;
        s.rod.axial_modes = Some(1);
    });
    let f = Simulation::new(&all).unwrap().frequencies_hz().to_vec();
    let run = drive(&all, dt, n, 0.0, |_, t| constant(t, W));
    let base = drive(&benchmark_rk4(), dt, n, 0.0, |_, t| constant(t, W));
    let d = runs::deflection_error(&run.record, &base.record);
    let st = run.record.stats;
    let modes = benchmark_rk4().rod.modes;
    println!(
        "8 elements, all 24 modes (highest {:.0} Hz): peak |v/L| {:.5e} vs {modes} modes {:.5e}, pointwise difference {:.2} %; steps {}, Newton {} ({:.2} per step), halvings {}",
        f[23], run.peak(), base.peak(), 100.0 * d, st.steps, st.newton_iterations, per_step(&run), st.halvings
    );
    assert!(run.error.is_none() && run.finite());
    assert!(d < 0.05, "{d}");
    assert!((run.peak() / base.peak() - 1.0).abs() < 0.02);
    assert_eq!(st.halvings, 0);
    TABLE.add(
        "all_modes",
        format!(
            "| all modes kept: 8 el, 24 modes (to {} kHz; generalized-alpha by `auto`) | bounded, accurate | peak v/L {} against {modes} modes (RK4): {}, {} pointwise (the implicit step's phase); {} Newton/step; {} halvings |",
            sig(f[23] / 1e3, 2),
            sci(run.peak(), 3),
            common::generated::signed_percent(run.peak() / base.peak() - 1.0, 2),
            percent(d, 2),
            sig(per_step(&run), 3),
            st.halvings
        ),
    );
}

// ------------------------------------------------------------------ axial load and buckling

/// Slider force pushing on the rod at 0.8 and 1.5 times the Euler load pi^2 E I / L^2, crank at
/// 10 rad/s, for 50 ms.
#[test]
fn axial_load_near_and_above_buckling() {
    let base = benchmark_rk4();
    let p_cr = std::f64::consts::PI.powi(2) * base.rod.youngs_modulus * base.rod.area_moment
        / base.rod.length.powi(2);
    let w = 10.0;
    let dt = 1e-4;
    let n = 500;
    let run_with = |model: RodModelKind, factor: f64| {
        let s = scene(|s| {
            s.rod.model = model;
            if model == RodModelKind::Segments {
                s.rod.elements = 32;
            }
        });
        drive(&s, dt, n, -factor * p_cr, |_, t| constant(t, w))
    };
    let mut below_buckling = Vec::new();
    let mut amplifications = Vec::new();
    let mut above_buckling = Vec::new();
    for model in [RodModelKind::Ffr, RodModelKind::Segments] {
        let free = run_with(model, 0.0);
        let near = run_with(model, 0.8);
        let above = run_with(model, 1.5);
        let amplification = near.peak() / free.peak();
        println!(
            "{model:?}, P_cr = {p_cr:.0} N, 10 rad/s: peak |v/L| without load {:.3e}, at 0.8 P_cr {:.3e} (x {amplification:.2}; static 1/(1-0.8) = 5), warnings {}",
            free.peak(), near.peak(), near.record.warnings.len()
        );
        println!(
            "{model:?} at 1.5 P_cr: ran to t = {:.4} s of {:.4} s, peak |v/L| {:.3}, halvings {}, error: {}, warnings: {:?}",
            above.sim.time(), n as f64 * dt, above.peak(), above.record.stats.halvings,
            above.error_text(), above.record.warnings
        );
        // Below buckling: bounded, no warning, and the amplification of a beam-column.
        assert!(near.error.is_none() && near.first_warning().is_none());
        assert!(
            amplification > 4.0 && amplification < 7.0,
            "{amplification}"
        );
        // Above buckling: the large-deflection warning first; the FFR rod's linear modes run
        // on beyond their range (bounded by 1.0), the chain ends in a clean StepFailed in the
        // snap-through (checked by the loop).
        assert!(above.finite());
        assert!(
            !above.record.warnings.is_empty(),
            "{model:?}: buckled without a warning"
        );
        match model {
            RodModelKind::Ffr => {
                assert!(above.error.is_none(), "{}", above.error_text());
                assert!(above.peak() < 1.0);
            }
            _ => {
                assert!(above.error.is_some());
                assert!(above.first_warning().unwrap() < above.sim.time());
            }
        }
        amplifications.push(amplification);
        below_buckling.push(near.record);
        above_buckling.push(above);
    }
    let d = runs::deflection_error(&below_buckling[0], &below_buckling[1]);
    println!(
        "0.8 P_cr: FFR stiffened against segments N = 32: pointwise {:.1} % of the peak",
        100.0 * d
    );
    assert!(d < 0.02, "{d}");
    let (ffr, seg) = (&above_buckling[0], &above_buckling[1]);
    TABLE.add(
        "buckling",
        format!(
            "| slider force -0.8 P_cr (P_cr = {} N), 10 rad/s | bounded, accurate | amplification of v/L: {} (FFR), {} (segments) vs static 1/(1-0.8) = 5; FFR vs segments {} pointwise |\n\
             | slider force -1.5 P_cr, FFR | warning, then out of range | warning at {}; completes with v/L {} (post-buckling is beyond a small-deformation rod) |\n\
             | slider force -1.5 P_cr, segments N = 32 | warning, then clean StepFailed | warning at {}, StepFailed in the communication step from {} (v/L {}; Newton stalls in the snap-through), state kept |",
            sig(p_cr, 4),
            sig(amplifications[0], 3),
            sig(amplifications[1], 3),
            percent(d, 1),
            ms(ffr.first_warning().unwrap()),
            sig(ffr.peak(), 2),
            ms(seg.first_warning().unwrap()),
            ms(seg.sim.time()),
            sig(seg.peak(), 2)
        ),
    );
}

// ------------------------------------------------------------------ long runs

/// Undamped rod (damping ratio 0), `revs` revolutions at 150 rad/s with 100 communication
/// points per revolution. Energy T + U at the same crank angle each revolution, the pin
/// constraint drift, the peak deflection per revolution.
fn long_run(revs: usize) -> String {
    let s = benchmark_rk4();
    let per_rev = 100usize;
    let dt = REV / W / per_rev as f64;
    let energy = |sim: &Simulation| {
        sim.mechanism().kinetic_energy(sim.state()) + sim.mechanism().strain_energy(sim.state())
    };
    let mut energies = Vec::with_capacity(revs);
    let mut peaks = vec![0.0f64; revs];
    let (mut drift_b, mut drift_c): (f64, f64) = (0.0, 0.0);
    let mut k = 0usize;
    // 1e6 points: visit each, record none (100 MB).
    let run = runs::visit_only(
        &s,
        &communication_grid(0.0, dt, revs * per_rev),
        0.0,
        |_, t| constant(t, W),
        |sim| {
            if k > 0 {
                let rev = (k - 1) / per_rev;
                peaks[rev] = peaks[rev].max(sim.outputs().deflection_rel.abs());
                let (b, c) = constraint_drift(sim);
                drift_b = drift_b.max(b);
                drift_c = drift_c.max(c);
                if k.is_multiple_of(per_rev) {
                    energies.push(energy(sim));
                }
            }
            k += 1;
        },
    );
    assert!(run.error.is_none(), "{}", run.error_text());
    let sim = &run.sim;
    let e1 = energies[0];
    let samples: Vec<String> = [1usize, 2, 10, 100, 1000, 10_000]
        .iter()
        .filter(|&&r| r <= revs)
        .map(|&r| format!("rev {r}: {:.5e}", energies[r - 1]))
        .collect();
    let velocity_drift = pin_velocity_drift(sim);
    println!("T + U at theta = 0: {samples:?}; velocity drift of pin B at the end {velocity_drift:.2e} m/s");
    let spread = energies.iter().map(|e| (e - e1).abs()).fold(0.0, f64::max) / e1;
    let st = sim.stats();
    println!(
        "{revs} revolutions undamped: T + U at theta = 0: first {e1:.6e} J, last {:.6e} J, max deviation {:.3e} of the first; peak |v/L| first revolution {:.4e}, last {:.4e}, max {:.4e}; max |Phi_B| {drift_b:.2e} m, max |y_C| {drift_c:.2e} m; steps {}, Newton {}, halvings {}",
        energies[revs - 1], spread, peaks[0], peaks[revs - 1],
        peaks.iter().cloned().fold(0.0, f64::max), st.steps, st.newton_iterations, st.halvings
    );
    // T + U at a fixed crank angle is not an invariant of the driven mechanism: the crank
    // does work, and the rigid-elastic cross terms of T (~ sqrt(T_rigid T_elastic), ~0.3 J
    // here) swing with the phase of the rod's vibration. Bounded means: within 15 % of the
    // first revolution's value, and no trend (means of the first and last tenth within 2 %).
    let tenth = (revs / 10).max(1);
    let mean_first = energies[..tenth].iter().sum::<f64>() / tenth as f64;
    let mean_last = energies[revs - tenth..].iter().sum::<f64>() / tenth as f64;
    let trend = (mean_last - mean_first).abs() / mean_first;
    println!("energy: mean of the first tenth {mean_first:.5e} J, of the last tenth {mean_last:.5e} J, trend {trend:.2e}");
    assert_eq!(st.halvings, 0);
    assert!(spread < 0.15, "{spread}");
    assert!(trend < 0.02, "{trend}");
    assert!(velocity_drift < 1e-2);
    assert!(
        peaks[revs - 1] <= 1.05 * peaks[0],
        "{} vs {}",
        peaks[revs - 1],
        peaks[0]
    );
    assert!(drift_b < 1e-10 && drift_c < 1e-10, "{drift_b} {drift_c}");
    format!(
        "T+U at theta = 0 within {} of the first revolution (the rigid-elastic cross terms swing with the vibration phase), trend (first vs last tenth) {}; Phi_B {} m, y_C {} m, pin B velocity drift {} m/s (RK4 projects); {} steps, {} halvings",
        percent(spread, 2),
        sci(trend, 2),
        under(drift_b, 1e-15),
        under(drift_c, 1e-15),
        under(velocity_drift, 1e-15),
        sci(st.steps as f64, 1),
        st.halvings
    )
}

/// |J_B v - v_crank|: the integrator's velocities against the velocity constraint of pin B.
fn pin_velocity_drift(sim: &Simulation) -> f64 {
    let mech = sim.mechanism();
    let st = sim.state();
    let nr = mech.rod.n_coordinates();
    let mut j = faer::Mat::<f64>::zeros(2, nr);
    mech.rod
        .point_jacobian(RodPoint::B, &st.dae.q[..nr], j.as_mut());
    let (_, vel, _) = mech.crank_law(st).pin(st.time);
    let mut vb = [0.0; 2];
    for r in 0..2 {
        for c in 0..nr {
            vb[r] += j[(r, c)] * st.dae.v[c];
        }
    }
    (vb[0] - vel.x).hypot(vb[1] - vel.y)
}

#[test]
fn long_run_1e3_revolutions() {
    let numbers = long_run(1000);
    TABLE.add(
        "long_1e3",
        format!("| 10^3 revolutions undamped | bounded | {numbers} |"),
    );
}

/// 10^4 revolutions: about 20 s in release on the 2-core machine, under the 60 s CI budget,
/// so it runs unignored.
#[test]
fn long_run_1e4_revolutions() {
    let numbers = long_run(10_000);
    TABLE.add(
        "long_1e4",
        format!("| 10^4 revolutions undamped | bounded | {numbers} |"),
    );
}

/// The default integrator (`auto`: the RK4(3) pair on the modal coordinates) beyond the FFR
/// rod's range: at E / 100 the deflection passes 5 % of L (warned at the first communication
/// point past it), and as it grows towards a third of L the reduced mass matrix of the
/// stiffened linear modes degenerates: the step fails cleanly (StepFailed, the state before
/// the step kept) instead of handing out numbers the model cannot stand behind.
#[test]
fn default_integrator_refuses_out_of_range_steps() {
    let dt = 1e-4;
    let n = runs::steps_for(W, 2.0, dt);
    let mut s = Scene::benchmark();
    s.rod.model = RodModelKind::Ffr;
    s.rod.deflection_policy = DeflectionPolicy::Warn;
    s.rod.youngs_modulus /= 100.0;
    let run = drive(&s, dt, n, 0.0, |_, t| constant(t, W));
    println!(
        "E / 100, default integrator: ran to t = {:.4} s, peak |v/L| {:.3}, error: {}, warnings: {:?}",
        run.sim.time(),
        run.peak(),
        run.error_text(),
        run.record.warnings
    );
    let error = run
        .error
        .clone()
        .expect("a clean StepFailed beyond the range");
    assert!(matches!(error, ModelError::StepFailed { .. }), "{error}");
    let first_over = run
        .record
        .times
        .iter()
        .zip(&run.record.outputs)
        .find(|(_, o)| o.deflection_rel.abs() > 0.05)
        .map(|(t, _)| *t);
    assert!(first_over.is_some());
    assert_eq!(run.first_warning(), first_over);
    assert!(run.first_warning().unwrap() < run.sim.time());
    assert!(run.finite());
    // Where exactly the degenerate reduced mass stops it depends on the step sequence (the
    // classic pair stopped below 0.5, the exponential form at 0.59): the numbers before are
    // finite, warned about, and below one rod length.
    assert!(run.peak() > 0.05 && run.peak() < 1.0, "{}", run.peak());
}

/// The deflection policy on the very flexible rod (E / 100, 150 rad/s, fixed-step
/// RK4 3e-4 s, communication step 1e-4 s): warn continues, discard and error refuse the first
/// step beyond `rod.deflection_limit` = 0.05 with the state from before it kept.
#[test]
fn deflection_policy_at_work() {
    let dt = 1e-4;
    let mut cells = Vec::new();
    for policy in [
        DeflectionPolicy::Warn,
        DeflectionPolicy::Discard,
        DeflectionPolicy::Error,
    ] {
        let s = scene(|s| {
            s.rod.model = RodModelKind::Ffr;
            s.rod.youngs_modulus /= 100.0;
            s.rod.deflection_policy = policy;
        });
        let mut sim = Simulation::new(&s).unwrap();
        sim.start(0.0, constant(0.0, W), 0.0).unwrap();
        let mut outcome = String::new();
        for _ in 0..runs::steps_for(W, 1.0, dt) {
            let before = sim.state().clone();
            match sim.advance(dt) {
                Ok(_) => {
                    let w = sim.take_warnings();
                    let deflection = w.iter().any(|w| w.contains("exceeds rod.deflection_limit"));
                    if outcome.is_empty() && deflection {
                        outcome = format!("warning at t = {}, run continues", ms(sim.time()));
                    }
                }
                Err(e) => {
                    assert!(matches!(e, ModelError::DeflectionLimit { .. }), "{e}");
                    assert_eq!(sim.state(), &before, "state kept");
                    let ModelError::DeflectionLimit { deflection, .. } = e else {
                        unreachable!()
                    };
                    outcome = format!(
                        "step to t = {} refused at v/L = {}, state at t = {} kept",
                        ms(sim.time() + dt),
                        sig(deflection, 3),
                        ms(sim.time())
                    );
                    break;
                }
            }
        }
        println!("{}: {outcome}", policy.name());
        assert!(!outcome.is_empty());
        cells.push(format!("{}: {outcome}", policy.name()));
    }
    TABLE.add(
        "deflection_policy",
        format!(
            "| E / 100 at 150 rad/s, rod.deflection_limit 0.05, each rod.deflection_policy | warn continues; discard / error refuse the step | {} |",
            cells.join("; ")
        ),
    );
}
