//! The amplitude of a long undamped run: the default scene (undamped, 150 rad/s) for 2,000
//! revolutions (84 s) at the default tolerance, on the scene's communication step (1e-4 s) and
//! on a 1e-3 s step, against a converged run (tolerance 1e-7) on the same communication points.
//! The largest per-revolution peak of `|v_mid/L|` over 100 revolutions at the start, the middle
//! and the end of the run (the motion's amplitude there, whatever the phase of the rod's free
//! vibration) is within 0.05 % of the converged run's (measured: 0.01 % at most). With the
//! exponential form's phase cap at `w_1 h = 1` whatever the tolerance (instead of
//! `exponential_max_phase` in src/mechanism/integrator_choice.rs) the amplitude drifts by
//! 1 % in these 2,000 revolutions, and by 10 % in 2,400 with the stages of Cox and Matthews
//! instead of Krogstad's (the cause: docs/solvers.md, "Long runs"). The 100,000-revolution
//! table: `cargo run --release --example long_run` (docs/generated/long-run.md).

mod common;
use common::runs;

use flexrod::drive::CrankDrive;
use flexrod::mechanism::integrator_choice::{
    damped_max_phase, DRIFT_PER_PERIOD, EXPONENTIAL_MAX_PHASE,
};
use flexrod::{Scene, Simulation};

const SPEED: f64 = 150.0;
const REVOLUTIONS: usize = 2000;
const WINDOW: usize = 100;
/// Largest relative difference of a window's amplitude from the converged run's.
const BOUND: f64 = 5e-4;

/// Per-revolution peaks of `|v_mid/L|` on the grid `dt`, and on every tenth point of it.
fn peaks(tolerance: f64, dt: f64) -> (Vec<f64>, Vec<f64>) {
    peaks_damped(tolerance, dt, 0.0, REVOLUTIONS)
}

/// The same with the damping ratio `zeta` over `revolutions`.
fn peaks_damped(tolerance: f64, dt: f64, zeta: f64, revolutions: usize) -> (Vec<f64>, Vec<f64>) {
    let mut scene = Scene::benchmark();
    scene.rod.damping_ratio = zeta;
    scene.solver.tolerance = tolerance;
    let mut sim = Simulation::new(&scene).unwrap();
    let law = CrankDrive::Constant { speed: SPEED };
    sim.start(0.0, law.at(0.0), 0.0).unwrap();
    let period = std::f64::consts::TAU / SPEED;
    let n = (revolutions as f64 * period / dt).floor() as usize;
    let (mut all, mut tenth) = (vec![0.0f64; revolutions], vec![0.0f64; revolutions]);
    for k in 0..n {
        sim.set_input(law.at(k as f64 * dt)).unwrap();
        sim.advance((k + 1) as f64 * dt - sim.time()).unwrap();
        let j = ((k + 1) as f64 * dt / period) as usize;
        let v = sim.outputs().deflection_rel.abs();
        if j < revolutions {
            all[j] = all[j].max(v);
            if (k + 1) % 10 == 0 {
                tenth[j] = tenth[j].max(v);
            }
        }
    }
    (all, tenth)
}

fn windows(p: &[f64]) -> [f64; 3] {
    let n = p.len();
    let max = |a: usize| p[a..a + WINDOW].iter().copied().fold(0.0, f64::max);
    [max(1), max(n / 2 - WINDOW / 2), max(n - 1 - WINDOW)]
}

#[test]
fn undamped_amplitude_holds_over_two_thousand_revolutions() {
    let (reference, reference_coarse) = peaks(1e-7, 1e-4);
    let (fine, _) = peaks(1e-3, 1e-4);
    let (coarse, _) = peaks(1e-3, 1e-3);
    for (label, run, converged) in [
        ("1e-4 s", &fine, &reference),
        ("1e-3 s", &coarse, &reference_coarse),
    ] {
        let (w, r) = (windows(run), windows(converged));
        for i in 0..3 {
            let d = (w[i] - r[i]) / r[i];
            println!(
                "grid {label}, window {i}: {:.5} vs {:.5} ({:+.2} %)",
                w[i],
                r[i],
                100.0 * d
            );
            assert!(d.abs() < BOUND, "grid {label}, window {i}: {d}");
        }
    }
}

/// A damped rod steps at the phase cap its damping lifts (`damped_max_phase`: the default
/// scene with 3 % damping at the default tolerance, `w_1 h = 1.02` instead of 0.36, and with
/// 8.3 % at the full cap `EXPONENTIAL_MAX_PHASE`): over 300 revolutions its per-revolution
/// peaks stay within a fifth of the tolerance of a converged run's, at the start and at the end
/// (measured: 6.8e-5 and 1.0e-4 of the peak; 3.9e-5 with 8.3 % at `w_1 h = 1`: the local error,
/// fourth order in the step).
#[test]
fn damped_rod_at_its_lifted_phase_cap() {
    let revolutions = 300;
    for (zeta, cap) in [(0.03, 1.021), (0.083, EXPONENTIAL_MAX_PHASE)] {
        assert!((damped_max_phase(3e-5, zeta) - cap).abs() < 1e-3);
        let (reference, _) = peaks_damped(1e-7, 1e-4, zeta, revolutions);
        let (run, _) = peaks_damped(1e-3, 1e-4, zeta, revolutions);
        let worst = runs::max_diff(&run, &reference) / runs::peak(&reference);
        println!(
            "{:.1} % damping (w_1 h = {cap:.3}), {revolutions} revolutions: largest per-revolution peak difference {worst:.2e} of the peak",
            zeta * 100.0
        );
        assert!(worst < 2e-4, "{zeta}: {worst}");
    }
}

/// `DRIFT_PER_PERIOD` bounds the drift that the long-run table (docs/generated/long-run.md,
/// 10,000 undamped revolutions of the default scene at three tolerances) measured, extrapolated
/// to `w_1 h = 1` along the table's own steepest slope: the drift per first-mode period at the
/// largest phase, times `(1 / w_1 h)^m` with `m` the exponent between the smallest and the
/// largest phase (at least 5, so that `DRIFT_PER_PERIOD (w_1 h)^5` bounds it below 1 too).
#[test]
fn drift_per_period_bounds_the_long_run_table() {
    let table = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/docs/generated/long-run.md"
    ))
    .unwrap();
    let revolutions = 10_000.0;
    let f1 = Simulation::new(&Scene::benchmark())
        .unwrap()
        .mechanism()
        .frequencies_hz()[0];
    let periods = revolutions * f1 * std::f64::consts::TAU / SPEED;
    // Rows `| tolerance | largest w_1 h | steps | amplitude % |`.
    let mut rows: Vec<(f64, f64)> = table
        .lines()
        .filter(|l| l.starts_with("| 1e-") || l.starts_with("| 3e-"))
        .map(|l| {
            let cells: Vec<&str> = l.split('|').map(str::trim).collect();
            let phase: f64 = cells[2].parse().unwrap();
            let drift: f64 = cells[4]
                .trim_end_matches(" %")
                .parse::<f64>()
                .unwrap()
                .abs()
                / 100.0;
            (phase, drift / periods)
        })
        .collect();
    assert_eq!(rows.len(), 3, "{table}");
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    let ((p0, d0), (p1, d1)) = (rows[0], rows[2]);
    let slope = (d1 / d0).ln() / (p1 / p0).ln();
    let at_one = d1 * p1.powf(-slope);
    println!(
        "drift per period: {rows:?}, slope {slope:.2}, extrapolated to w_1 h = 1: {at_one:.2e}"
    );
    assert!(slope >= 5.0, "{slope}");
    assert!(DRIFT_PER_PERIOD >= at_one, "{at_one:e}");
    assert!(
        DRIFT_PER_PERIOD <= 1.5 * at_one,
        "{at_one:e}: the constant is stale"
    );
}
