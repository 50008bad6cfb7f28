//! Slider-crank dynamics with the FFR rod (issue 3): rigid limit, energy, momentum,
//! convergence in step, elements and modes, reference conditions, stiff stability.

use flexrod::scene::{ReferenceKind, Scene, SolverMethod};
use flexrod::{CrankInput, Outputs, Simulation};
use nalgebra::{Matrix3, Vector2, Vector3};

const W: f64 = 150.0;

// Rigid limit tolerances: the rigid rod (no modes) meets 1e-6 to round-off; a stiff flexible rod
// meets 1e-5 at h = 2e-5 s, limited by the integrator's O(h^2) accelerations.

/// The benchmark scene with generalized-alpha (this file tests the implicit integrator; the
/// explicit path has tests/explicit_rk4.rs).
fn scene(f: impl FnOnce(&mut Scene)) -> Scene {
    let mut s = Scene::benchmark();
    s.solver.method = SolverMethod::GeneralizedAlpha;
    s.solver.step = 5e-5;
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

/// Run at constant speed with communication step `dt` for `revolutions`; returns (t, outputs).
fn run(scene: &Scene, w: f64, dt: f64, revolutions: f64) -> (Vec<(f64, Outputs)>, Simulation) {
    let mut sim = Simulation::new(scene).unwrap();
    sim.start(0.0, constant(0.0, w), 0.0).unwrap();
    let n = (revolutions * 2.0 * std::f64::consts::PI / w / dt).round() as usize;
    let mut out = vec![(0.0, sim.outputs())];
    for k in 0..n {
        sim.set_input(constant(k as f64 * dt, w)).unwrap();
        sim.advance((k + 1) as f64 * dt - sim.time()).unwrap();
        out.push((sim.time(), sim.outputs()));
    }
    (out, sim)
}

fn peak(rows: &[(f64, Outputs)]) -> f64 {
    rows.iter()
        .map(|r| r.1.deflection_rel.abs())
        .fold(0.0, f64::max)
}

/// Largest pointwise |delta v_mid/L| relative to the reference's peak (docs/physics.md, "How error is measured").
fn deflection_error(rows: &[(f64, Outputs)], reference: &[(f64, Outputs)]) -> f64 {
    assert_eq!(rows.len(), reference.len());
    let d = rows
        .iter()
        .zip(reference)
        .map(|(a, b)| (a.1.deflection_rel - b.1.deflection_rel).abs())
        .fold(0.0, f64::max);
    d / peak(reference)
}

/// Closed-form inverse dynamics of the rigid slider-crank (massless slider, no slider force):
/// returns (force of rod on crank pin, force of rod on slider, crank torque).
fn rigid_inverse_dynamics(
    r: f64,
    l: f64,
    m: f64,
    th: f64,
    w: f64,
) -> (Vector2<f64>, Vector2<f64>, f64) {
    let (s, c) = th.sin_cos();
    let b = Vector2::new(r * c, r * s);
    let phi = (-r * s / l).asin();
    let e = Vector2::new(phi.cos(), phi.sin());
    let cpt = b + e * l;
    let g = (b + cpt) * 0.5;
    let phid = -r * w * c / (l * phi.cos());
    let phidd = (r * w * w * s + l * phi.sin() * phid * phid) / (l * phi.cos());
    let ab = -b * (w * w);
    let gb = g - b;
    let ag = ab + Vector2::new(-gb.y, gb.x) * phidd - gb * (phid * phid);
    let jg = m * l * l / 12.0;
    // Unknowns: F_B on rod (x, y), N (slider's vertical force on rod).
    // m a_G = F_B + (0, N); J phi'' = (B - G) x F_B + (C - G) x (0, N).
    let (bg, cg) = (b - g, cpt - g);
    let a = Matrix3::new(1.0, 0.0, 0.0, 0.0, 1.0, 1.0, -bg.y, bg.x, cg.x);
    let rhs = Vector3::new(m * ag.x, m * ag.y, jg * phidd);
    let x = a.lu().solve(&rhs).unwrap();
    let fb_on_pin = -Vector2::new(x[0], x[1]);
    let fc_on_slider = -Vector2::new(0.0, x[2]);
    let torque = -(b.x * fb_on_pin.y - b.y * fb_on_pin.x);
    (fb_on_pin, fc_on_slider, torque)
}

#[test]
fn rigid_limit_matches_closed_form_inverse_dynamics() {
    // (modes, stiffness factor on E): no modes is the rigid rod exactly (positions are fixed by
    // the constraints); a stiff flexible rod approaches it up to the elastic effect (~1/E) and
    // the O(h^2) error of the integrator.
    let mut stiff_errors = Vec::new();
    for (modes, factor) in [(0usize, 1.0), (4, 1e4), (4, 1e5)] {
        let s = scene(|s| {
            s.rod.modes = modes;
            s.rod.youngs_modulus *= factor;
            if modes > 0 {
                // A modal error dp shows up in the forces as K dp: tight Newton tolerance.
                s.solver.newton_tolerance = 1e-14;
                // The abrupt start rings the stiff modes with an amplitude of the quasi-static
                // load (K p ~ inertia load): annihilate it (rho_inf = 0) and skip its first steps.
                s.solver.rho_inf = 0.0;
                // What remains is the O(h^2) error of the integrator's accelerations.
                s.solver.step = 2e-5;
            }
        });
        let (rows, _) = run(&s, W, 2e-4, 1.0);
        let m = s.rod.density * s.rod.area * s.rod.length;
        let mut worst: f64 = 0.0;
        let mut scale: f64 = 0.0;
        let skip = if modes == 0 { 0 } else { 10 };
        for (t, o) in &rows[skip..] {
            let (fb, fc, tq) = rigid_inverse_dynamics(s.crank.length, s.rod.length, m, W * t, W);
            worst = worst
                .max((o.pin_b_force[0] - fb.x).abs())
                .max((o.pin_b_force[1] - fb.y).abs())
                .max((o.pin_c_force[0] - fc.x).abs())
                .max((o.pin_c_force[1] - fc.y).abs())
                .max((o.crank_torque - tq).abs() / s.crank.length);
            scale = scale.max(fb.norm());
        }
        let rel = worst / scale;
        println!("rigid limit, {modes} modes, E x {factor:e}: max force/torque difference {worst:.3e} N of peak {scale:.1} N ({rel:.2e} relative)");
        if modes == 0 {
            assert!(rel < 1e-6, "{rel}");
        } else {
            stiff_errors.push(rel);
        }
    }
    assert!(stiff_errors.iter().all(|&e| e < 1e-5), "{stiff_errors:?}");
}

/// Undamped, no stiffening: the crank's work equals the change of kinetic plus strain energy.
#[test]
fn energy_balance_undamped() {
    let s = scene(|s| {
        s.rod.axial_stiffening = false;
        s.solver.rho_inf = 1.0;
        s.solver.step = 1e-5;
    });
    let dt = 1e-5;
    let mut sim = Simulation::new(&s).unwrap();
    sim.start(0.0, constant(0.0, W), 0.0).unwrap();
    let energy = |sim: &Simulation| {
        sim.mechanism().kinetic_energy(sim.state()) + sim.mechanism().strain_energy(sim.state())
    };
    let e0 = energy(&sim);
    let n = (2.0 * 2.0 * std::f64::consts::PI / W / dt).round() as usize;
    let mut power = vec![sim.outputs().crank_torque * W];
    let mut exchanged = 0.0;
    for k in 0..n {
        sim.set_input(constant(k as f64 * dt, W)).unwrap();
        sim.advance(dt).unwrap();
        power.push(sim.outputs().crank_torque * W);
        exchanged += 0.5 * (power[k].abs() + power[k + 1].abs()) * dt;
    }
    // Simpson's rule over an even number of intervals.
    let mut work = 0.0;
    for k in (0..n - 1).step_by(2) {
        work += dt / 3.0 * (power[k] + 4.0 * power[k + 1] + power[k + 2]);
    }
    let change = energy(&sim) - e0;
    let rel = (work - change).abs() / exchanged;
    println!("energy: crank work {work:.6e} J, change of T + U {change:.6e} J, energy exchanged {exchanged:.4e} J, mismatch {rel:.2e} of it");
    assert!(rel < 1e-4, "{rel}");
}

/// The sum of the pin forces on the rod equals the rate of its linear momentum.
#[test]
fn rod_momentum_balance() {
    let s = scene(|s| s.solver.step = 1e-5);
    let dt = 1e-5;
    let mut sim = Simulation::new(&s).unwrap();
    sim.start(0.0, constant(0.0, W), 0.0).unwrap();
    let momentum = |sim: &Simulation| {
        let nr = sim.mechanism().rod.n_coordinates();
        let st = sim.state();
        sim.mechanism()
            .rod
            .linear_momentum(&st.dae.q[..nr], &st.dae.v[..nr])
    };
    let mut p = vec![momentum(&sim)];
    let mut f = vec![sim.outputs()];
    for k in 0..2000 {
        sim.set_input(constant(k as f64 * dt, W)).unwrap();
        sim.advance(dt).unwrap();
        p.push(momentum(&sim));
        f.push(sim.outputs());
    }
    let mut worst: f64 = 0.0;
    let mut scale: f64 = 0.0;
    for k in 1..p.len() - 1 {
        let rate = (p[k + 1] - p[k - 1]) / (2.0 * dt);
        let o = f[k];
        let on_rod = -Vector2::new(
            o.pin_b_force[0] + o.pin_c_force[0],
            o.pin_b_force[1] + o.pin_c_force[1],
        );
        worst = worst.max((rate - on_rod).norm());
        scale = scale.max(on_rod.norm());
    }
    println!("momentum balance: max |dP/dt - sum F| = {worst:.3e} N of {scale:.1} N");
    assert!(worst / scale < 2e-3, "{}", worst / scale);
}

#[test]
fn converges_in_the_step_at_second_order() {
    let base = scene(|s| s.solver.rho_inf = 0.8);
    let dt = 4e-4;
    let at = |h: f64| {
        let s = scene(|s| {
            *s = base.clone();
            s.solver.step = h;
            // Newton errors add up over many small steps: measure the discretization error only.
            s.solver.newton_tolerance = 1e-14;
        });
        run(&s, W, dt, 1.0).0
    };
    let reference = at(2.5e-6);
    let steps = [8e-5, 4e-5, 2e-5, 1e-5];
    let errors: Vec<f64> = steps
        .iter()
        .map(|&h| deflection_error(&at(h), &reference))
        .collect();
    let orders: Vec<f64> = errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
    println!("step convergence: h = {steps:?}, errors {errors:?}, observed orders {orders:?}");
    assert!(orders.iter().all(|&o| o > 1.7 && o < 2.5), "{orders:?}");
}

#[test]
fn converges_in_elements_and_modes_and_reference_conditions_agree() {
    // Seed 001 Fig. 5: 2, 4, 6 elements (all modes of 2 elements = 6; here 6 modes each).
    let reference = run(
        &scene(|s| {
            s.rod.elements = 16;
            s.rod.modes = 12;
        }),
        W,
        1e-4,
        2.0,
    )
    .0;
    let mut last = f64::INFINITY;
    for n in [2usize, 4, 6] {
        let rows = run(
            &scene(|s| {
                s.rod.elements = n;
                s.rod.modes = 6;
            }),
            W,
            1e-4,
            2.0,
        )
        .0;
        let e = deflection_error(&rows, &reference);
        println!(
            "{n} elements, 6 modes: peak |v/L| {:.5e}, error against 16 elements {e:.3e}",
            peak(&rows)
        );
        assert!(e < last);
        last = e;
    }
    for m in [1usize, 2, 4, 8] {
        let rows = run(
            &scene(|s| {
                s.rod.elements = 8;
                s.rod.modes = m;
            }),
            W,
            1e-4,
            2.0,
        )
        .0;
        println!(
            "8 elements, {m} modes: peak |v/L| {:.5e}, error against 16 elements {:.3e}",
            peak(&rows),
            deflection_error(&rows, &reference)
        );
    }
    // Seed 000 Figs. 6-8: simply supported, mean axis, body-fixed at the midpoint agree; the
    // cantilever does not. 4 elements, 6 modes, linear modes (as in 1985).
    let by = |r: ReferenceKind| {
        run(
            &scene(|s| {
                s.rod.elements = 4;
                s.rod.modes = 6;
                s.rod.reference = r;
                s.rod.axial_stiffening = false;
            }),
            W,
            1e-4,
            2.0,
        )
        .0
    };
    let ss = by(ReferenceKind::SimplySupported);
    let mut diffs = Vec::new();
    for r in [
        ReferenceKind::MeanAxis,
        ReferenceKind::BodyFixedMid,
        ReferenceKind::Cantilever,
    ] {
        let rows = by(r);
        let d = deflection_error(&rows, &ss);
        println!(
            "{r:?} against simply supported: peak {:.5e} vs {:.5e}, pointwise difference {d:.3e}",
            peak(&rows),
            peak(&ss)
        );
        diffs.push(d);
    }
    assert!(diffs[0] < 0.1 && diffs[1] < 0.1, "{diffs:?}");
    assert!(diffs[2] > 3.0 * diffs[0].max(diffs[1]), "{diffs:?}");
}

/// 6 elements with every mode (to about 15 kHz at 2 elements; higher here), h = 1e-4 s, 100 revolutions.
#[test]
fn stiff_all_modes_stay_bounded() {
    let s = scene(|s| {
        s.rod.elements = 6;
        s.rod.modes = 18;
        s.solver.step = 1e-4;
    });
    let sim = Simulation::new(&s).unwrap();
    println!(
        "highest retained frequency {:.0} Hz",
        sim.frequencies_hz()[17]
    );
    let (rows, sim) = run(&s, W, 1e-3, 100.0);
    let p_first = rows[..rows.len() / 50]
        .iter()
        .map(|r| r.1.deflection_rel.abs())
        .fold(0.0, f64::max);
    let p_last = rows[rows.len() * 49 / 50..]
        .iter()
        .map(|r| r.1.deflection_rel.abs())
        .fold(0.0, f64::max);
    let stats = sim.stats();
    println!("100 revolutions: peak |v/L| first 2 revs {p_first:.4e}, last 2 revs {p_last:.4e}; {} steps, {} Newton iterations, {} halvings", stats.steps, stats.newton_iterations, stats.halvings);
    assert!(rows.iter().all(|r| r.1.deflection_rel.is_finite()));
    assert!(p_last < 1.5 * p_first, "{p_last} vs {p_first}");
}
