//! Long runs: the default scene (undamped) at 150 rad/s for many revolutions, at the default
//! tolerance on the scene's communication step (1e-4 s) and on a 1e-3 s step, against a
//! converged run (tolerance 1e-7). For each, the largest per-revolution peak of `|v_mid/L|`
//! over 100 revolutions at the start, the middle and the end of the run, and its difference
//! from the converged run's on the same communication points (the converged run is sampled on
//! the 1e-4 s grid and on every tenth point of it). The largest of 100 per-revolution peaks is
//! the amplitude of the motion there, whatever the phase of the rod's free vibration.
//!
//! `cargo run --release --example long_run [REVOLUTIONS]` (default 100,000: about 4,200 s of
//! simulated time) prints the table; with `FLEXROD_BLESS=1` it also writes
//! `docs/generated/long-run.md` (embedded in docs/solvers.md). Also prints the steps and
//! right-hand sides per revolution of each run, and a second table: the amplitude's drift
//! over 10,000 revolutions (1e-3 s step) at tolerances 1e-2, 3e-3 and 1e-3 with the
//! exponential form's phase cap at each (`exponential_max_phase`), against a converged run.

use flexrod::drive::CrankDrive;
use flexrod::mechanism::integrator_choice::{exponential_max_phase, LOCAL_TOLERANCE_FACTOR_RK4};
use flexrod::{Scene, Simulation};

const SPEED: f64 = 150.0;
/// Revolutions in each window of the table.
const WINDOW: usize = 100;
/// Revolutions of the runs of the second table (the drift against the tolerance).
const REVOLUTIONS_BY_TOLERANCE: usize = 10_000;

/// The per-revolution peaks of `|v_mid/L|` on the communication grid `dt` (and, where
/// `every > 1`, also on every `every`-th point of it), with the integrator's steps and
/// right-hand sides.
struct LongRun {
    peaks: Vec<f64>,
    coarse_peaks: Vec<f64>,
    steps: u64,
    rhs: u64,
}

fn long_run(tolerance: f64, dt: f64, every: usize, revolutions: usize) -> LongRun {
    // The default scene's model class (shear deformation on at its tolerance, 1e-3), kept at
    // every tolerance: the runs measure the integration's drift, not a change of the physics.
    let mut scene = Scene::benchmark();
    scene.rod.shear_deformation = flexrod::rod::PhysicsSwitch::On;
    scene.rod.damping_ratio = 0.0;
    scene.solver.tolerance = tolerance;
    let mut sim = Simulation::new(&scene).unwrap();
    let law = CrankDrive::Constant { speed: SPEED };
    sim.start(0.0, law.at(0.0), 0.0).unwrap();
    let period = std::f64::consts::TAU / SPEED;
    let n = (revolutions as f64 * period / dt).floor() as usize;
    let mut peaks = vec![0.0f64; revolutions];
    let mut coarse_peaks = vec![0.0f64; revolutions];
    for k in 0..n {
        let t = k as f64 * dt;
        sim.set_input(law.at(t)).unwrap();
        sim.advance((k + 1) as f64 * dt - sim.time()).unwrap();
        let j = (((k + 1) as f64 * dt) / period) as usize;
        let v = sim.outputs().deflection_rel.abs();
        if j < revolutions {
            peaks[j] = peaks[j].max(v);
            if (k + 1) % every == 0 {
                coarse_peaks[j] = coarse_peaks[j].max(v);
            }
        }
    }
    let s = sim.stats();
    LongRun {
        peaks,
        coarse_peaks,
        steps: s.steps,
        rhs: s.newton_iterations,
    }
}

/// The largest peak in the windows at the start (revolutions 1 to 100: the first, with the
/// start, left out), the middle and the end (the last complete revolutions).
fn windows(peaks: &[f64]) -> [f64; 3] {
    let n = peaks.len();
    let max = |a: usize| peaks[a..a + WINDOW].iter().copied().fold(0.0, f64::max);
    [max(1), max(n / 2 - WINDOW / 2), max(n - 1 - WINDOW)]
}

fn main() {
    let revolutions: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(100_000);
    assert!(revolutions >= 4 * WINDOW);
    let reference = long_run(1e-7, 1e-4, 10, revolutions);
    let fine = long_run(1e-3, 1e-4, 1, revolutions);
    let coarse = long_run(1e-3, 1e-3, 1, revolutions);
    let mut text = format!(
        "<!-- written by `FLEXROD_BLESS=1 cargo run --release --example long_run`: rerun it, do not edit -->\n\
         | default scene undamped, {revolutions} revolutions at 150 rad/s, tolerance 1e-3 | revolutions 2-{} | middle | last {WINDOW} | steps / right-hand sides a revolution |\n|---|---|---|---|---|\n",
        WINDOW + 1
    );
    let rows = [
        ("1e-4 s", &fine, &reference.peaks),
        ("1e-3 s", &coarse, &reference.coarse_peaks),
    ];
    for (label, run, converged) in rows {
        let (w, r) = (windows(&run.peaks), windows(converged));
        let cells: Vec<String> = (0..3)
            .map(|i| format!("{:.5} ({:+.2} %)", w[i], 100.0 * (w[i] - r[i]) / r[i]))
            .collect();
        text += &format!(
            "| communication step {label} | {} | {:.1} / {:.1} |\n",
            cells.join(" | "),
            run.steps as f64 / revolutions as f64,
            run.rhs as f64 / revolutions as f64
        );
    }
    let r = windows(&reference.peaks);
    text += &format!(
        "(each cell: the largest per-revolution peak of |v_mid/L| over {WINDOW} revolutions, and its difference from the converged run's, tolerance 1e-7 ({:.5}, {:.5}, {:.5} on the 1e-4 s grid; {:.1} steps a revolution), on the same communication points)\n",
        r[0],
        r[1],
        r[2],
        reference.steps as f64 / revolutions as f64
    );
    // The drift against the tolerance: 10,000 revolutions on the 1e-3 s grid.
    let short = REVOLUTIONS_BY_TOLERANCE.min(revolutions);
    let converged = long_run(1e-7, 1e-4, 10, short).coarse_peaks;
    let r = windows(&converged);
    text += &format!(
        "\n| tolerance ({short} revolutions, 1e-3 s communication step) | largest w_1 h | steps a revolution | amplitude of the last {WINDOW} revolutions against the converged run's |\n|---|---|---|---|\n"
    );
    for tolerance in [1e-2, 3e-3, 1e-3] {
        let run = long_run(tolerance, 1e-3, 1, short);
        let w = windows(&run.peaks);
        text += &format!(
            "| {tolerance:e} | {:.2} | {:.1} | {:+.3} % |\n",
            exponential_max_phase(tolerance * LOCAL_TOLERANCE_FACTOR_RK4),
            run.steps as f64 / short as f64,
            100.0 * (w[2] - r[2]) / r[2]
        );
    }
    print!("{text}");
    if std::env::var_os("FLEXROD_BLESS").is_some() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/generated/long-run.md");
        std::fs::write(path, &text).unwrap();
        println!("wrote {path}");
    }
}
