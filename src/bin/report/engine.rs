//! The report's engine section: the automotive rod (`scenes/automotive_rod.toml`,
//! undamped) in its engine run ([`flexrod::drive::engine`]: ramp to 6000 rpm, two revolutions,
//! a 38 kN gas pulse) against the independent geometrically exact shear beam
//! (`tests/data/exudyn_automotive_rod.csv`), for both rod models and several tolerances: the
//! largest pointwise errors of deflection, stress at L/2 and pin forces (relative to the
//! reference's peaks), against the median wall time of the run.

use std::fmt::Write as _;
use std::path::Path;

use flexrod::drive::engine::{read_reference, EngineErrors, EngineRun};
use flexrod::scene::{RodModelKind, SolverMethod};
use flexrod::Scene;

use crate::markdown::pct;

/// One setting of the automotive rod, measured.
pub struct EngineRow {
    pub label: String,
    pub errors: EngineErrors,
    /// Median wall time of the run, s.
    pub seconds: f64,
    pub integrator: String,
}

/// A setting's label, from its scene: model, elements, the modes (mass-loaded or free; a band
/// with static corrections above it, or a count), method and tolerance.
fn label(s: &Scene) -> String {
    if s.rod.model == RodModelKind::Segments {
        return format!(
            "segments N = {}, shear slides, axial springs",
            s.rod.elements
        );
    }
    let kind = if s.rod.loaded_modes {
        "mass-loaded"
    } else {
        "free"
    };
    let modes = match s.rod.mode_band_hz {
        Some(band) => format!("{kind} modes to {band} Hz, static corrections above"),
        None => format!("{} {kind} modes", s.rod.modes),
    };
    let method = match s.solver.method {
        SolverMethod::Auto => "auto",
        SolverMethod::Dopri5 => "Dormand-Prince",
        _ => "other",
    };
    format!(
        "FFR {} el, {modes}, {method}, tolerance {:e}",
        s.rod.elements, s.solver.tolerance
    )
}

/// The settings: the scene's own, its tolerance, band and mode count varied (a count replaces
/// the band: `mode_band_hz` absent), and the segment chain with shear slides and axial springs.
/// `quick`: the scene's own and the 16-segment chain.
fn settings(quick: bool) -> Result<Vec<(String, Scene)>, String> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/automotive_rod.toml");
    let base = Scene::from_file(&path).map_err(|e| e.to_string())?;
    let with = |f: &dyn Fn(&mut Scene)| {
        let mut s = base.clone();
        s.rod.damping_ratio = 0.0;
        f(&mut s);
        s
    };
    let band = |band_hz: f64, tolerance: f64| {
        with(&|s| {
            s.rod.mode_band_hz = Some(band_hz);
            s.solver.tolerance = tolerance;
        })
    };
    let count = |elements: usize, modes: usize, method: SolverMethod, tolerance: f64| {
        with(&|s| {
            s.rod.elements = elements;
            s.rod.modes = modes;
            s.rod.mode_band_hz = None;
            s.solver.method = method;
            s.solver.tolerance = tolerance;
        })
    };
    let chain = |n: usize| {
        with(&|s| {
            s.rod.model = RodModelKind::Segments;
            s.rod.elements = n;
            s.rod.axial_springs = true;
        })
    };
    let own = with(&|_| {});
    let mut list = vec![(format!("{} (the scene's settings)", label(&own)), own)];
    if !quick {
        let shipped = base.rod.mode_band_hz.unwrap_or(6000.0);
        for tol in [1e-3, 1e-4] {
            list.push((String::new(), band(shipped, tol)));
        }
        list.push((String::new(), band(2.0 * shipped, base.solver.tolerance)));
        list.push((String::new(), count(8, 7, SolverMethod::Auto, 1e-3)));
        list.push((String::new(), count(8, 4, SolverMethod::Auto, 1e-3)));
        list.push((String::new(), count(16, 8, SolverMethod::Dopri5, 1e-5)));
    }
    list.push((String::new(), chain(16)));
    if !quick {
        list.push((String::new(), chain(32)));
    }
    Ok(list
        .into_iter()
        .map(|(l, s)| (if l.is_empty() { label(&s) } else { l }, s))
        .collect())
}

/// Run every setting `repeats` times (median wall time) and compare it with the reference.
pub fn measure(quick: bool) -> Result<Vec<EngineRow>, String> {
    let reference = read_reference(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/exudyn_automotive_rod.csv"),
    )?;
    let setup = EngineRun::automotive();
    let repeats = if quick { 1 } else { 3 };
    let mut rows = Vec::new();
    for (label, scene) in settings(quick)? {
        let mut times = Vec::new();
        let mut last = None;
        for _ in 0..repeats {
            let (record, time, integrator) =
                setup.run(&scene).map_err(|e| format!("{label}: {e}"))?;
            times.push(time.as_secs_f64());
            last = Some((record, integrator));
        }
        let (record, integrator) = last.expect("at least one run");
        times.sort_by(f64::total_cmp);
        rows.push(EngineRow {
            label,
            errors: EngineErrors::new(&record, &reference, &setup),
            seconds: times[times.len() / 2],
            integrator,
        });
    }
    rows.push(as_a_master_drives_it(&reference, &setup, repeats)?);
    Ok(rows)
}

/// The scene's settings as a co-simulation master with input derivatives drives them
/// ([`EngineRun::run_with_sparse_input`]): the gas pulse as the scene's table, the crank's
/// angle, speed, acceleration and jerk set every 1 ms, a row every 0.1 ms, against every fifth
/// row of the reference (its rows are 0.02 ms apart).
fn as_a_master_drives_it(
    reference: &[flexrod::drive::engine::EngineRow],
    setup: &EngineRun,
    repeats: usize,
) -> Result<EngineRow, String> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/automotive_rod.toml");
    let mut scene = Scene::from_file(&path).map_err(|e| e.to_string())?;
    scene.rod.damping_ratio = 0.0;
    let (input_step, sample) = (1e-3, 1e-4);
    let every = (sample / setup.sample).round() as usize;
    let sampled: Vec<_> = reference.iter().step_by(every).copied().collect();
    let mut times = Vec::new();
    let mut last = None;
    for _ in 0..repeats.max(3) {
        let (record, time, integrator) = setup
            .run_with_sparse_input(&scene, input_step, sample)
            .map_err(|e| format!("crank set every 1 ms: {e}"))?;
        times.push(time.as_secs_f64());
        last = Some((record, integrator));
    }
    let (record, integrator) = last.expect("at least one run");
    times.sort_by(f64::total_cmp);
    Ok(EngineRow {
        label: format!(
            "{} as a master drives it: the gas pulse as the scene's table, the crank set every 1 ms (angle, speed, acceleration and jerk as input derivatives), a row every 0.1 ms (against the reference there)",
            label(&scene)
        ),
        errors: EngineErrors::new(&record, &sampled, setup),
        seconds: times[times.len() / 2],
        integrator,
    })
}

/// The section's table: errors against run time (ms per simulated second, real-time factor).
pub fn table(rows: &[EngineRow]) -> String {
    let stop = EngineRun::automotive().stop;
    let mut s = String::from(
        "| automotive rod, engine run (60 ms) | v_mid/L | stress at L/2 | pin B, firing | pin C, firing | wall time | ms per simulated s | real-time factor | integrator |\n|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let e = &r.errors;
        writeln!(
            s,
            "| {} | {} | {} | {} | {} | {:.*} ms | {:.0} | {:.2} | {} |",
            r.label,
            pct(e.deflection),
            pct(e.stress),
            pct(e.pin_b_firing),
            pct(e.pin_c_firing),
            if r.seconds < 0.01 { 2 } else { 0 },
            r.seconds * 1e3,
            r.seconds / stop * 1e3,
            stop / r.seconds,
            r.integrator
        )
        .unwrap();
    }
    s
}
