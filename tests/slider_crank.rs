//! Slider-crank dynamics with the FFR rod: rigid limit, energy, momentum,
//! convergence in step, elements and modes, reference conditions, stiff stability.

use flexrod::drive::{communication_grid, CrankDrive, Record};
use flexrod::scene::{ReferenceKind, Scene, SolverMethod};
use flexrod::Simulation;
use nalgebra::{Matrix3, Vector2, Vector3};

mod common;
use common::generated::{percent, sci, sig, Fragment};
use common::runs;

const W: f64 = 150.0;

/// docs/verification.md, "Dynamics of the slider-crank": the table of these checks, one part per test (generated fragment
/// `dynamics-checks`, written with FLEXROD_BLESS=1 when the whole file runs).
static DYNAMICS: Fragment = Fragment::new(
    "dynamics-checks",
    "| check | result |\n|---|---|\n",
    &[
        "rigid",
        "energy",
        "momentum",
        "step",
        "discretization",
        "stiff",
    ],
);

// Rigid limit tolerances: the rigid rod (no modes) meets 1e-6 to round-off; a stiff flexible rod
// meets 1e-5 at h = 2e-5 s, limited by the integrator's O(h^2) accelerations.

/// The benchmark scene (Euler-Bernoulli, as the closed forms and the convergence orders here)
/// with generalized-alpha (this file tests the implicit integrator; the explicit path has
/// tests/explicit_rk4.rs).
fn scene(f: impl FnOnce(&mut Scene)) -> Scene {
    let mut s = common::euler_bernoulli_benchmark();
    s.solver.method = SolverMethod::GeneralizedAlpha;
    s.solver.step = 5e-5;
    f(&mut s);
    s
}

/// Run at constant speed with communication step `dt` for `revolutions`.
fn run(scene: &Scene, w: f64, dt: f64, revolutions: f64) -> (Record, Simulation) {
    runs::constant(scene, w, dt, revolutions)
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
    let mut rigid = f64::NAN;
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
        let (record, _) = run(&s, W, 2e-4, 1.0);
        let m = s.rod.density * s.rod.area * s.rod.length;
        let mut worst: f64 = 0.0;
        let mut scale: f64 = 0.0;
        let skip = if modes == 0 { 0 } else { 10 };
        for (t, o) in record.times.iter().zip(&record.outputs).skip(skip) {
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
            rigid = rel;
        } else {
            stiff_errors.push(rel);
        }
    }
    assert!(stiff_errors.iter().all(|&e| e < 1e-5), "{stiff_errors:?}");
    DYNAMICS.add(
        "rigid",
        format!(
            "| rigid rod (no modes) against the closed-form inverse dynamics | {} relative (round-off) |\n\
             | stiff rod (E x 1e4, 1e5), h = 2e-5 | {}, {} relative |",
            common::generated::below(rigid, 1e-12),
            sci(stiff_errors[0], 2),
            sci(stiff_errors[1], 2)
        ),
    );
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
    let n = runs::steps_for(W, 2.0, dt);
    let energy = |sim: &Simulation| {
        sim.mechanism().kinetic_energy(sim.state()) + sim.mechanism().strain_energy(sim.state())
    };
    let mut energies = Vec::new();
    let run = runs::drive_visit(
        &s,
        &communication_grid(0.0, dt, n),
        0.0,
        |_, t| CrankDrive::Constant { speed: W }.at(t),
        |sim| energies.push(energy(sim)),
    );
    assert!(run.error.is_none(), "{}", run.error_text());
    let power: Vec<f64> = run
        .record
        .outputs
        .iter()
        .map(|o| o.crank_torque * W)
        .collect();
    let exchanged: f64 = power
        .windows(2)
        .map(|p| 0.5 * (p[0].abs() + p[1].abs()) * dt)
        .sum();
    // Simpson's rule over an even number of intervals.
    let mut work = 0.0;
    for k in (0..n - 1).step_by(2) {
        work += dt / 3.0 * (power[k] + 4.0 * power[k + 1] + power[k + 2]);
    }
    let change = energies[n] - energies[0];
    let rel = (work - change).abs() / exchanged;
    println!("energy: crank work {work:.6e} J, change of T + U {change:.6e} J, energy exchanged {exchanged:.4e} J, mismatch {rel:.2e} of it");
    assert!(rel < 1e-4, "{rel}");
    DYNAMICS.add(
        "energy",
        format!(
            "| energy balance, undamped, no stiffening, 2 revolutions, h = 1e-5 | crank work against the change of T + U: mismatch {} of the energy exchanged |",
            sci(rel, 2)
        ),
    );
}

/// The sum of the pin forces on the rod equals the rate of its linear momentum.
#[test]
fn rod_momentum_balance() {
    let s = scene(|s| s.solver.step = 1e-5);
    let dt = 1e-5;
    let momentum = |sim: &Simulation| {
        let nr = sim.mechanism().rod.n_coordinates();
        let st = sim.state();
        sim.mechanism()
            .rod
            .linear_momentum(&st.dae.q[..nr], &st.dae.v[..nr])
    };
    let mut p = Vec::new();
    let run = runs::drive_visit(
        &s,
        &communication_grid(0.0, dt, 2000),
        0.0,
        |_, t| CrankDrive::Constant { speed: W }.at(t),
        |sim| p.push(momentum(sim)),
    );
    assert!(run.error.is_none(), "{}", run.error_text());
    let f = &run.record.outputs;
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
    let rel = worst / scale;
    println!("momentum balance: max |dP/dt - sum F| = {worst:.3e} N of {scale:.1} N ({rel:.2e})");
    // Measured 5.7e-6: the central difference's O(dt^2) error of dP/dt.
    assert!(rel < 2e-5, "{rel}");
    DYNAMICS.add(
        "momentum",
        format!(
            "| rod momentum balance, h = 1e-5, 20 ms | max \\|dP/dt - (F_B + F_C)\\| = {} of the peak force (central differences) |",
            sci(rel, 2)
        ),
    );
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
        .map(|&h| runs::deflection_error(&at(h), &reference))
        .collect();
    let orders: Vec<f64> = errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
    println!("step convergence: h = {steps:?}, errors {errors:?}, observed orders {orders:?}");
    assert!(orders.iter().all(|&o| o > 1.7 && o < 2.5), "{orders:?}");
    DYNAMICS.add(
        "step",
        format!(
            "| step convergence (generalized-alpha, rho_inf 0.8), h = 8e-5 ... 1e-5 against 2.5e-6 | observed order {} |",
            orders.iter().map(|o| sig(*o, 2)).collect::<Vec<_>>().join(", ")
        ),
    );
}

#[test]
fn converges_in_elements_and_modes_and_reference_conditions_agree() {
    // The fine reference: 16 elements, 12 modes (same step: the comparison measures the
    // discretization of the rod).
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
    let error_with = |elements: usize, modes: usize| {
        let rows = run(
            &scene(|s| {
                s.rod.elements = elements;
                s.rod.modes = modes;
            }),
            W,
            1e-4,
            2.0,
        )
        .0;
        let e = runs::deflection_error(&rows, &reference);
        println!(
            "{elements} elements, {modes} modes: peak |v/L| {:.5e}, error against 16 elements {e:.3e}",
            rows.peak_deflection_rel()
        );
        e
    };
    // The CDI benchmark note, Fig. 5: 2, 4, 6 elements (all modes of 2 elements = 6; here 6 modes each).
    let by_elements: Vec<f64> = [2usize, 4, 6].iter().map(|&n| error_with(n, 6)).collect();
    assert!(
        by_elements.windows(2).all(|w| w[1] < 0.5 * w[0]),
        "no convergence in elements: {by_elements:?}"
    );
    // Modes of 8 elements (simply supported: odd modes symmetric, even ones antisymmetric, with
    // no midpoint deflection of their own), the modes left out as static corrections: the error
    // against the fine rod never grows by more than 10 % with a mode added (the 4th,
    // antisymmetric mode leaves it), falls by at least a third with the 2nd mode and with modes
    // 5 to 8, and the default scene's 3 modes are within 0.2 % of the peak. Measured: 2.7e-3,
    // 1.1e-3, 1.1e-3, 1.1e-3, 5.3e-4.
    let modes = [1usize, 2, 3, 4, 8];
    let by_modes: Vec<f64> = modes.iter().map(|&m| error_with(8, m)).collect();
    assert!(
        by_modes.windows(2).all(|w| w[1] <= 1.1 * w[0]),
        "error grows with a mode added: {by_modes:?}"
    );
    assert!(
        by_modes[1] < 0.67 * by_modes[0] && by_modes[4] < 0.67 * by_modes[3],
        "{by_modes:?}"
    );
    assert!(by_modes[2] < 2e-3, "3 modes: {}", by_modes[2]);
    // Agrawal and Shabana 1985, Figs. 6-8: simply supported, mean axis, body-fixed at the
    // midpoint agree; the cantilever does not. 4 elements, 6 modes, linear modes (as in the
    // paper).
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
        let d = runs::deflection_error(&rows, &ss);
        println!(
            "{r:?} against simply supported: peak {:.5e} vs {:.5e}, pointwise difference {d:.3e}",
            rows.peak_deflection_rel(),
            ss.peak_deflection_rel()
        );
        diffs.push(d);
    }
    assert!(diffs[0] < 0.03 && diffs[1] < 0.03, "{diffs:?}");
    assert!(diffs[2] > 10.0 * diffs[0].max(diffs[1]), "{diffs:?}");
    let list = |x: &[f64]| x.iter().map(|e| sci(*e, 2)).collect::<Vec<_>>().join(", ");
    DYNAMICS.add(
        "discretization",
        format!(
            "| 2, 4, 6 elements (6 modes) against 16 elements (12 modes) | {} |\n\
             | 1, 2, 3, 4, 8 modes (8 elements) against 16 elements (12 modes) | {} |\n\
             | mean axis / body-fixed mid / cantilever against simply supported (4 elements, 6 linear modes) | {} / {} / {} pointwise |",
            list(&by_elements),
            list(&by_modes),
            percent(diffs[0], 2),
            percent(diffs[1], 2),
            percent(diffs[2], 2)
        ),
    );
}

/// 6 elements with every mode (to about 15 kHz at 2 elements; higher here), h = 1e-4 s, 100 revolutions.
#[test]
fn stiff_all_modes_stay_bounded() {
    let s = scene(|s| {
        s.rod.elements = 6;
        s.rod.modes = 18;
        s.solver.step = 1e-4;
    });
    let f_max = Simulation::new(&s).unwrap().frequencies_hz()[17];
    println!("highest retained frequency {f_max:.0} Hz");
    let (rows, sim) = run(&s, W, 1e-3, 100.0);
    let v = rows.deflection_rel();
    let p_first = runs::peak(&v[..v.len() / 50]);
    let p_last = runs::peak(&v[v.len() * 49 / 50..]);
    let stats = sim.stats();
    println!("100 revolutions: peak |v/L| first 2 revs {p_first:.4e}, last 2 revs {p_last:.4e}; {} steps, {} Newton iterations, {} halvings", stats.steps, stats.newton_iterations, stats.halvings);
    assert!(v.iter().all(|x| x.is_finite()));
    assert!(p_last < 1.5 * p_first, "{p_last} vs {p_first}");
    assert_eq!(stats.halvings, 0);
    DYNAMICS.add(
        "stiff",
        format!(
            "| 6 elements, all 18 modes (to {} kHz), h = 1e-4, 100 revolutions | bounded: peak \\|v/L\\| of the last 2 revolutions {} x the first 2; {} halvings |",
            sig(f_max / 1e3, 2),
            sig(p_last / p_first, 3),
            stats.halvings
        ),
    );
}
