//! The explicit path (`solver.method = "rk4"`): fourth order in the step, constraints
//! held by projection, the same answer as generalized-alpha.

use flexrod::drive::{communication_grid, CrankDrive};
use flexrod::rod::RodPoint;
use flexrod::scene::SolverMethod;
use flexrod::Scene;

mod common;
use common::runs;

const W: f64 = 150.0;

fn rk4(h: f64) -> Scene {
    let mut s = Scene::benchmark();
    s.solver.method = SolverMethod::Rk4;
    s.solver.step = h;
    s
}

/// v_mid/L at t = k * 6e-4 s over one revolution, and the largest pin position error.
fn run(scene: &Scene) -> (Vec<f64>, f64) {
    let dt = 6e-4;
    let n = (2.0 * std::f64::consts::PI / W / dt).floor() as usize;
    let mut drift: f64 = 0.0;
    let run = runs::drive_visit(
        scene,
        &communication_grid(0.0, dt, n),
        0.0,
        |_, t| CrankDrive::Constant { speed: W }.at(t),
        |sim| {
            let st = sim.state();
            let nr = sim.mechanism().rod.n_coordinates();
            let b = sim.mechanism().rod.point(RodPoint::B, &st.dae.q[..nr]);
            let th = W * sim.time();
            let r = sim.mechanism().crank_length();
            drift = drift
                .max((b.x - r * th.cos()).abs())
                .max((b.y - r * th.sin()).abs());
        },
    );
    assert!(run.error.is_none(), "{}", run.error_text());
    (run.deflection_rel(), drift)
}

#[test]
fn rk4_converges_at_fourth_order_and_keeps_the_constraints() {
    let (reference, _) = run(&rk4(5e-6));
    let peak = reference.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    // In the asymptotic range: w h <= 0.6 for the highest retained mode (1243 Hz).
    let steps = [8e-5, 4e-5, 2e-5];
    let mut errors = Vec::new();
    for h in steps {
        let (v, drift) = run(&rk4(h));
        let e = runs::max_diff(&v, &reference) / peak;
        println!("rk4 h = {h:e}: error {e:.3e} of the peak, pin B drift {drift:.1e} m");
        assert!(drift < 1e-12, "{drift}");
        errors.push(e);
    }
    let orders: Vec<f64> = errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
    println!("observed orders {orders:.2?}");
    // Fourth order approached as w h -> 0 (3.5 then 3.9 here).
    assert!(
        orders.iter().all(|&o| o > 3.3) && orders[orders.len() - 1] > 3.7,
        "{orders:?}"
    );
}

#[test]
fn rk4_agrees_with_generalized_alpha() {
    let (explicit, _) = run(&rk4(1e-4));
    let mut implicit_scene = Scene::benchmark();
    implicit_scene.solver.step = 1e-5;
    let (implicit, _) = run(&implicit_scene);
    let peak = implicit.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let d = runs::max_diff(&explicit, &implicit) / peak;
    println!(
        "rk4 (h 1e-4) against generalized-alpha (h 1e-5): {:.3} % of the peak",
        100.0 * d
    );
    assert!(d < 2e-3, "{d}");
}

/// With many modes the explicit step is capped at its stability limit (2.5 / w_max of the
/// highest retained mode): all 24 modes of 8 elements (to 73 kHz) with a scene step of 3e-4 s
/// run stably, without a single step halving.
#[test]
fn rk4_caps_its_step_at_the_stability_limit() {
    let mut s = rk4(3e-4);
    s.rod.modes = 24;
    let f_max = flexrod::Simulation::new(&s)
        .unwrap()
        .mechanism()
        .rod
        .highest_frequency_hz();
    let (record, sim) = runs::completed(
        &s,
        &CrankDrive::Constant { speed: W },
        0.0,
        &communication_grid(0.0, 1e-3, 20),
    );
    let peak = record.peak_deflection_rel();
    let st = sim.stats();
    println!(
        "24 modes (to {f_max:.0} Hz): {} steps in 20 ms, {} halvings, peak |v/L| {peak:.4e}",
        st.steps, st.halvings
    );
    assert_eq!(st.halvings, 0);
    assert!(peak.is_finite() && peak < 0.02 && peak > 0.005, "{peak}");
    // The cap: 2.5 / (2 pi f_max) per step.
    let expected = (0.02 / (2.5 / (2.0 * std::f64::consts::PI * f_max))).ceil() as u64;
    assert!(
        st.steps >= expected && st.steps <= expected + 20,
        "{} vs {expected}",
        st.steps
    );
}
