//! Stiff and extreme cases (issue 6). Every test prints its numbers and asserts an explicit
//! outcome: the run ends bounded and accurate, or in a clean, documented error (a
//! `ModelError::StepFailed` with the state from before the step kept). Table of results:
//! docs/report/extreme.md.
//!
//! Run: `cargo test --release --test extreme -- --nocapture`.

use flexrod::rod::RodPoint;
use flexrod::scene::RodModelKind;
use flexrod::{CrankInput, ModelError, Outputs, Scene, Simulation};

const W: f64 = 150.0;
const REV: f64 = 2.0 * std::f64::consts::PI;

fn scene(f: impl FnOnce(&mut Scene)) -> Scene {
    let mut s = Scene::benchmark();
    f(&mut s);
    s
}

fn constant(t: f64, w: f64) -> CrankInput {
    CrankInput {
        angle: w * t,
        speed: w,
        acceleration: 0.0,
    }
}

/// A run: outputs at every communication point, the warnings, and the error that ended it.
struct Run {
    rows: Vec<(f64, Outputs)>,
    warnings: Vec<String>,
    error: Option<ModelError>,
    sim: Simulation,
}

/// Drive `scene` with `input(k, t_k)` at communication points `k dt`, k < n, slider force `force`.
fn drive(
    scene: &Scene,
    dt: f64,
    n: usize,
    force: f64,
    mut input: impl FnMut(usize, f64) -> CrankInput,
) -> Run {
    let mut sim = Simulation::new(scene).unwrap();
    sim.start(0.0, input(0, 0.0), force).unwrap();
    let mut rows = vec![(0.0, sim.outputs())];
    let mut warnings = sim.take_warnings();
    let mut error = None;
    for k in 0..n {
        let t = k as f64 * dt;
        sim.set_input(input(k, t)).unwrap();
        let before = sim.snapshot();
        match sim.advance((k + 1) as f64 * dt - sim.time()) {
            Ok(_) => rows.push((sim.time(), sim.outputs())),
            Err(e) => {
                // The contract: a failed step returns an error and keeps the previous state.
                assert!(matches!(e, ModelError::StepFailed { .. }), "{e}");
                assert!(sim.snapshot() == before, "state changed by a failed step");
                error = Some(e);
                break;
            }
        }
        warnings.extend(sim.take_warnings());
    }
    Run {
        rows,
        warnings,
        error,
        sim,
    }
}

fn peak(rows: &[(f64, Outputs)]) -> f64 {
    rows.iter()
        .map(|r| r.1.deflection_rel.abs())
        .fold(0.0, f64::max)
}

fn peak_force(rows: &[(f64, Outputs)]) -> f64 {
    rows.iter()
        .map(|r| r.1.pin_b_force[0].hypot(r.1.pin_b_force[1]))
        .fold(0.0, f64::max)
}

fn finite(rows: &[(f64, Outputs)]) -> bool {
    rows.iter().all(|(_, o)| {
        o.deflection_rel.is_finite()
            && o.pin_b_force
                .iter()
                .chain(&o.pin_c_force)
                .all(|x| x.is_finite())
    })
}

/// Max pointwise |delta v/L| / reference peak on a common grid (same dt).
fn deflection_error(rows: &[(f64, Outputs)], reference: &[(f64, Outputs)]) -> f64 {
    let d = rows
        .iter()
        .zip(reference)
        .map(|(a, b)| (a.1.deflection_rel - b.1.deflection_rel).abs())
        .fold(0.0, f64::max);
    d / peak(reference)
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

fn revolutions(w: f64, revs: f64, dt: f64) -> usize {
    (revs * REV / w / dt).round() as usize
}

// ------------------------------------------------------------------ stiffness extremes

/// E x 1000: bounded, the deflection 1/1000 of the nominal one, the forces those of the rigid rod.
#[test]
fn very_stiff_rod() {
    let dt = 1e-4;
    let n = revolutions(W, 2.0, dt);
    let nominal = drive(&Scene::benchmark(), dt, n, 0.0, |_, t| constant(t, W));
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
    assert!(stiff.error.is_none(), "{:?}", stiff.error);
    let ratio = peak(&stiff.rows) / peak(&nominal.rows);
    // Forces against the rigid rod, after the 1 ms in which the start rings the stiff modes.
    let skip = 10;
    let df = stiff.rows[skip..]
        .iter()
        .zip(&rigid.rows[skip..])
        .map(|(a, b)| {
            (a.1.pin_b_force[0] - b.1.pin_b_force[0]).hypot(a.1.pin_b_force[1] - b.1.pin_b_force[1])
        })
        .fold(0.0, f64::max)
        / peak_force(&rigid.rows);
    let st = stiff.sim.stats();
    println!(
        "E x 1000: peak |v/L| {:.3e} = {:.4e} x nominal ({:.3e}); pin B force vs rigid rod {:.2e} of peak; steps {}, Newton {}, halvings {}",
        peak(&stiff.rows), ratio, peak(&nominal.rows), df, st.steps, st.newton_iterations, st.halvings
    );
    assert!(ratio > 0.5e-3 && ratio < 2e-3, "{ratio}");
    assert!(df < 1e-2, "{df}");
    assert!(stiff.warnings.is_empty());
}

/// E / 100: the deflection leaves the small-deformation range; the simulation must say so.
#[test]
fn very_flexible_rod_warns() {
    let dt = 1e-4;
    let n = revolutions(W, 2.0, dt);
    for model in [RodModelKind::Ffr, RodModelKind::Segments] {
        let s = scene(|s| {
            s.rod.youngs_modulus /= 100.0;
            s.rod.model = model;
            if model == RodModelKind::Segments {
                s.rod.elements = 16;
            }
        });
        let run = drive(&s, dt, n, 0.0, |_, t| constant(t, W));
        let first_over = run
            .rows
            .iter()
            .find(|r| r.1.deflection_rel.abs() > 0.05)
            .map(|r| r.0);
        println!(
            "E / 100, {model:?}: ran to t = {:.4} s of {:.4} s, peak |v/L| {:.3}, first |v/L| > 0.05 at t = {:?} s, error: {}, warnings: {:?}",
            run.sim.time(),
            n as f64 * dt,
            peak(&run.rows),
            first_over,
            run.error.as_ref().map(|e| e.to_string()).unwrap_or_else(|| "none".into()),
            run.warnings
        );
        // Either way: the large-deflection warning was given, and whatever was returned is finite.
        assert!(
            !run.warnings.is_empty(),
            "no warning for |v/L| = {}",
            peak(&run.rows)
        );
        assert!(run.warnings[0].contains("small-deformation range"));
        assert!(finite(&run.rows));
        assert!(first_over.is_some());
    }
}

// ------------------------------------------------------------------ speed extremes

/// 600 rad/s (4 x the benchmark speed): the inertia loads are 16 x larger.
#[test]
fn speed_600_rad_s() {
    let w = 600.0;
    let dt = 2.5e-5;
    let n = revolutions(w, 2.0, dt);
    let ffr = drive(&scene(|s| s.solver.step = dt), dt, n, 0.0, |_, t| {
        constant(t, w)
    });
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
    for (name, run) in [
        ("FFR stiffened 8 el / 4 modes", &ffr),
        ("segments N = 32", &seg),
    ] {
        println!(
            "600 rad/s, {name}: ran to {:.4} s of {:.4} s, peak |v/L| {:.3e}, peak |F_B| {:.0} N, halvings {}, error: {}, warnings: {}",
            run.sim.time(), n as f64 * dt, peak(&run.rows), peak_force(&run.rows), run.sim.stats().halvings,
            run.error.as_ref().map(|e| e.to_string()).unwrap_or_else(|| "none".into()),
            run.warnings.len()
        );
        assert!(finite(&run.rows));
        if peak(&run.rows) > 0.05 {
            assert!(
                !run.warnings.is_empty(),
                "{name}: deflection beyond 5 % without a warning"
            );
        }
    }
    // The geometrically exact chain completes the run.
    assert!(seg.error.is_none());
    if ffr.error.is_none() {
        let e = deflection_error(&ffr.rows, &seg.rows);
        println!(
            "600 rad/s: FFR stiffened against segments N = 32: pointwise {:.1} %, peak {:+.1} %",
            100.0 * e,
            100.0 * (peak(&ffr.rows) / peak(&seg.rows) - 1.0)
        );
    }
}

/// A speed step 150 -> 300 rad/s and a reversal 150 -> -150 rad/s at a communication point
/// (the angle stays continuous; the speed jumps).
#[test]
fn speed_step_and_reversal() {
    let dt = 1e-4;
    let n1 = revolutions(W, 1.0, dt);
    for w2 in [300.0f64, -150.0] {
        let t1 = n1 as f64 * dt;
        let n = n1 + revolutions(w2.abs(), 1.0, dt);
        let run = drive(&Scene::benchmark(), dt, n, 0.0, |k, t| {
            if k < n1 {
                constant(t, W)
            } else {
                CrankInput {
                    angle: W * t1 + w2 * (t - t1),
                    speed: w2,
                    acceleration: 0.0,
                }
            }
        });
        let before = peak(&run.rows[..=n1]);
        let after = peak(&run.rows[n1..]);
        let st = run.sim.stats();
        println!(
            "speed 150 -> {w2} rad/s at t = {t1:.4} s: peak |v/L| before {before:.3e}, after {after:.3e}; peak |F_B| {:.0} N; halvings {}; error: {}; warnings {}",
            peak_force(&run.rows), st.halvings,
            run.error.as_ref().map(|e| e.to_string()).unwrap_or_else(|| "none".into()),
            run.warnings.len()
        );
        // Handled transient: the run completes and stays bounded (the velocity jump is an impulse
        // the index-3 integrator absorbs in one step).
        assert!(run.error.is_none());
        assert!(finite(&run.rows));
        // The speed jump is an impulse on the rod (v_B jumps by r |dw|): a large but bounded
        // transient, flagged by the large-deflection warning when it leaves the range.
        assert!(after < 0.5, "{after} vs {before}");
        if after > 0.05 {
            assert!(!run.warnings.is_empty());
        }
        let (db, dc) = constraint_drift(&run.sim);
        assert!(db < 1e-9 && dc < 1e-9, "{db} {dc}");
    }
}

/// Zero speed: outputs constant, deflection zero, forces zero.
#[test]
fn standstill() {
    let dt = 1e-4;
    let input = CrankInput {
        angle: 0.7,
        speed: 0.0,
        acceleration: 0.0,
    };
    let run = drive(&Scene::benchmark(), dt, 1000, 0.0, |_, _| input);
    let first = run.rows[0].1;
    let mut worst_change: f64 = 0.0;
    let mut worst_force: f64 = 0.0;
    let mut worst_deflection: f64 = 0.0;
    for (_, o) in &run.rows {
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
    println!("standstill, 1000 steps: max |v_mid| {worst_deflection:.1e} m, max |force or torque| {worst_force:.1e}, slider moved {worst_change:.1e} m, Newton {}", run.sim.stats().newton_iterations);
    assert!(run.error.is_none());
    assert!(worst_deflection < 1e-15 && worst_force < 1e-9 && worst_change < 1e-15);
}

/// The crank angle jumps +0.5 rad between communication points (an inconsistent input): a
/// clean error with the state kept, or a handled transient.
#[test]
fn crank_angle_jump() {
    let dt = 1e-4;
    let n0 = 100;
    let mut sim = Simulation::new(&Scene::benchmark()).unwrap();
    sim.start(0.0, constant(0.0, W), 0.0).unwrap();
    for k in 0..n0 {
        sim.set_input(constant(k as f64 * dt, W)).unwrap();
        sim.advance(dt).unwrap();
    }
    let t = sim.time();
    sim.set_input(CrankInput {
        angle: W * t + 0.5,
        speed: W,
        acceleration: 0.0,
    })
    .unwrap();
    let before = sim.snapshot();
    let result = sim.advance(dt);
    match &result {
        Err(e) => {
            println!("angle jump +0.5 rad at t = {t:.4} s: clean error, state kept: {e}");
            assert!(matches!(e, ModelError::StepFailed { .. }));
            assert!(sim.snapshot() == before);
            assert_eq!(sim.time(), t);
            // The importer can go on with a consistent input.
            sim.set_input(constant(t, W)).unwrap();
            sim.advance(dt).unwrap();
        }
        Ok(_) => {
            let mut p: f64 = 0.0;
            for k in 0..200 {
                sim.set_input(CrankInput {
                    angle: W * sim.time() + 0.5,
                    speed: W,
                    acceleration: 0.0,
                })
                .unwrap();
                sim.advance(dt).unwrap();
                p = p.max(sim.outputs().deflection_rel.abs());
                let _ = k;
            }
            let (db, dc) = constraint_drift(&sim);
            println!("angle jump +0.5 rad at t = {t:.4} s: handled transient; halvings {}, peak |v/L| over the next 200 steps {p:.3e}, constraint drift {db:.1e} / {dc:.1e} m, warnings {:?}", sim.stats().halvings, sim.take_warnings());
            assert!(p.is_finite() && db < 1e-9 && dc < 1e-9);
        }
    }
}

// ------------------------------------------------------------------ step extremes

/// Communication steps from 1e-7 s to 1e-2 s over the first 10 ms (solver step 1e-4 s): all
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
    let reference = fine.rows.last().unwrap().1.deflection_rel;
    let scale = peak(&fine.rows);
    for dt in [1e-7f64, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2] {
        let n = (t_end / dt).round() as usize;
        let clock = std::time::Instant::now();
        let run = drive(&Scene::benchmark(), dt, n, 0.0, |_, t| constant(t, W));
        let v = run.rows.last().unwrap().1.deflection_rel;
        let e = (v - reference).abs() / scale;
        let st = run.sim.stats();
        println!(
            "comm step {dt:.0e}: {n} calls, {} internal steps, {} Newton, {} halvings, v/L(10 ms) {v:.5e} (fine {reference:.5e}), error {:.2e} of the peak, {:.0} ms",
            st.steps, st.newton_iterations, st.halvings, e, clock.elapsed().as_secs_f64() * 1e3
        );
        assert!(run.error.is_none());
        assert!((run.sim.time() - t_end).abs() < 1e-12);
        assert!(e < 2e-2, "{dt}: {e}");
    }
}

/// 8 elements with all 24 modes (simply supported) against 4 modes and the segment chain.
#[test]
fn all_modes_kept() {
    let dt = 1e-4;
    let n = revolutions(W, 2.0, dt);
    let all = scene(|s| s.rod.modes = 24);
    let f = Simulation::new(&all).unwrap().frequencies_hz().to_vec();
    let run = drive(&all, dt, n, 0.0, |_, t| constant(t, W));
    let four = drive(&Scene::benchmark(), dt, n, 0.0, |_, t| constant(t, W));
    let d = deflection_error(&run.rows, &four.rows);
    let st = run.sim.stats();
    println!(
        "8 elements, all 24 modes (highest {:.0} Hz): peak |v/L| {:.5e} vs 4 modes {:.5e}, pointwise difference {:.2} %; steps {}, Newton {} ({:.2} per step), halvings {}",
        f[23], peak(&run.rows), peak(&four.rows), 100.0 * d, st.steps, st.newton_iterations, st.newton_iterations as f64 / st.steps as f64, st.halvings
    );
    assert!(run.error.is_none() && finite(&run.rows));
    assert!(d < 0.05, "{d}");
    assert!((peak(&run.rows) / peak(&four.rows) - 1.0).abs() < 0.02);
}

// ------------------------------------------------------------------ axial load and buckling

/// Slider force pushing on the rod at 0.8 and 1.5 times the Euler load pi^2 E I / L^2, crank at
/// 10 rad/s, for 50 ms.
#[test]
fn axial_load_near_and_above_buckling() {
    let base = Scene::benchmark();
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
    let mut below = Vec::new();
    for model in [RodModelKind::Ffr, RodModelKind::Segments] {
        let free = run_with(model, 0.0);
        let near = run_with(model, 0.8);
        let above = run_with(model, 1.5);
        let amplification = peak(&near.rows) / peak(&free.rows);
        println!(
            "{model:?}, P_cr = {p_cr:.0} N, 10 rad/s: peak |v/L| without load {:.3e}, at 0.8 P_cr {:.3e} (x {amplification:.2}; static 1/(1-0.8) = 5), warnings {}",
            peak(&free.rows), peak(&near.rows), near.warnings.len()
        );
        println!(
            "{model:?} at 1.5 P_cr: ran to t = {:.4} s of {:.4} s, peak |v/L| {:.3}, halvings {}, error: {}, warnings: {:?}",
            above.sim.time(), n as f64 * dt, peak(&above.rows), above.sim.stats().halvings,
            above.error.as_ref().map(|e| e.to_string()).unwrap_or_else(|| "none".into()),
            above.warnings
        );
        // Below buckling: bounded, no warning, and the amplification of a beam-column.
        assert!(near.error.is_none() && near.warnings.is_empty());
        assert!(
            amplification > 2.0 && amplification < 8.0,
            "{amplification}"
        );
        below.push(near.rows);
        // Above buckling: a clean StepFailed error (checked in `drive`) or a bounded large
        // deflection; either way the large-deflection warning comes first.
        assert!(finite(&above.rows));
        assert!(
            !above.warnings.is_empty(),
            "{model:?}: buckled without a warning"
        );
        if above.error.is_none() {
            assert!(peak(&above.rows) < 1.0);
        }
    }
    let d = deflection_error(&below[0], &below[1]);
    println!(
        "0.8 P_cr: FFR stiffened against segments N = 32: pointwise {:.1} % of the peak",
        100.0 * d
    );
    assert!(d < 0.25, "{d}");
}

// ------------------------------------------------------------------ long runs

/// Undamped rod (damping ratio 0; generalized-alpha rho_inf 0.8), `revs` revolutions at
/// 150 rad/s with 100 communication points per revolution. Energy T + U at the same crank
/// angle each revolution, the pin constraint drift, the peak deflection per revolution.
fn long_run(revs: usize) {
    let s = Scene::benchmark();
    let per_rev = 100usize;
    let dt = REV / W / per_rev as f64;
    let mut sim = Simulation::new(&s).unwrap();
    sim.start(0.0, constant(0.0, W), 0.0).unwrap();
    let energy = |sim: &Simulation| {
        sim.mechanism().kinetic_energy(sim.state()) + sim.mechanism().strain_energy(sim.state())
    };
    let clock = std::time::Instant::now();
    let mut energies = Vec::with_capacity(revs);
    let mut peaks = Vec::with_capacity(revs);
    let (mut drift_b, mut drift_c): (f64, f64) = (0.0, 0.0);
    let mut k = 0usize;
    for _ in 0..revs {
        let mut p: f64 = 0.0;
        for _ in 0..per_rev {
            sim.set_input(constant(k as f64 * dt, W)).unwrap();
            sim.advance((k + 1) as f64 * dt - sim.time()).unwrap();
            k += 1;
            p = p.max(sim.outputs().deflection_rel.abs());
            let (b, c) = constraint_drift(&sim);
            drift_b = drift_b.max(b);
            drift_c = drift_c.max(c);
        }
        energies.push(energy(&sim));
        peaks.push(p);
    }
    let e1 = energies[0];
    let samples: Vec<String> = [1usize, 2, 10, 100, 1000, 10_000]
        .iter()
        .filter(|&&r| r <= revs)
        .map(|&r| format!("rev {r}: {:.5e}", energies[r - 1]))
        .collect();
    let (emin, emax) = energies
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &e| (a.min(e), b.max(e)));
    println!("T + U at theta = 0: {samples:?}; min {emin:.5e}, max {emax:.5e} J; velocity drift of pin B at the end {:.2e} m/s", pin_velocity_drift(&sim));
    let spread = energies.iter().map(|e| (e - e1).abs()).fold(0.0, f64::max) / e1;
    let strain_last = sim.mechanism().strain_energy(sim.state());
    let st = sim.stats();
    println!(
        "{revs} revolutions undamped: {:.1} s wall; T + U at theta = 0: first {e1:.6e} J, last {:.6e} J, max deviation {:.3e} of the first; peak |v/L| first revolution {:.4e}, last {:.4e}, max {:.4e}; max |Phi_B| {drift_b:.2e} m, max |y_C| {drift_c:.2e} m; strain energy at the end {strain_last:.3e} J; steps {}, Newton {}, halvings {}",
        clock.elapsed().as_secs_f64(), energies[revs - 1], spread, peaks[0], peaks[revs - 1],
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
    assert!(pin_velocity_drift(&sim) < 1e-2);
    assert!(
        peaks[revs - 1] <= 1.05 * peaks[0],
        "{} vs {}",
        peaks[revs - 1],
        peaks[0]
    );
    assert!(drift_b < 1e-10 && drift_c < 1e-10, "{drift_b} {drift_c}");
}

/// |J_B v - v_crank|: the integrator's velocities against the velocity constraint of pin B
/// (index-3 generalized-alpha enforces positions only).
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
    long_run(1000);
}

/// 10^4 revolutions: about 20 s in release on the 2-core machine, under the 60 s CI budget,
/// so it runs unignored.
#[test]
fn long_run_1e4_revolutions() {
    long_run(10_000);
}
