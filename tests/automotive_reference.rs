//! The automotive rod (scenes/automotive_rod.toml) against an independent geometrically exact,
//! shear-deformable beam: Exudyn's `ObjectBeamGeometricallyExact2D`
//! (tests/data/exudyn_automotive_rod.csv, written by tests/data/automotive_reference.py, which
//! states the run and the reference's mesh and step). Issue 11: FFR rod and segment chain
//! against the reference pointwise, deflection and stress within 0.5 % of the peak, the pin
//! forces at the firing spike within 1 %.
//!
//! The run, the same in both: from rest, undeformed, the crank speed ramps smoothly to
//! 628.3 rad/s over 40 ms (`CrankDrive::Ramp`; a start the two models share exactly, without the
//! start-up transient that an impulsive start at full speed would ring through the undamped
//! reference), then two revolutions at 6000 rpm; a 38 kN gas-force pulse on the slider 15 degrees
//! after the first top dead centre at full speed, held over each 1e-5 s communication step at its
//! mid-step value. No damping (`rod.damping_ratio = 0`; the reference has none).

use flexrod::drive::CrankDrive;
use flexrod::scene::{RodModelKind, SolverMethod};
use flexrod::Scene;

mod common;
use common::check_generated;
use common::exudyn::read_rows;

const W: f64 = 628.3;
const T_RAMP: f64 = 0.04;
const T_STOP: f64 = 0.06;
const DT: f64 = 1e-5;
/// Reference sampling interval, s.
const SAMPLE: f64 = 2e-5;

/// The gas force of the reference (tests/data/automotive_reference.py, `gas`), N.
fn gas(theta: f64) -> f64 {
    let firing = 4.0 * std::f64::consts::PI + 15f64.to_radians();
    let d = (theta - firing) / 20f64.to_radians();
    -38.0e3 * (-d * d).exp()
}

/// Columns of the reference: t, v_mid/L, FBx, FBy, FCx, FCy, N_mid, M_mid, stress at L/2.
type Row = [f64; 9];

fn reference() -> Vec<Row> {
    reference_file("exudyn_automotive_rod.csv")
}

fn reference_file(name: &str) -> Vec<Row> {
    let rows: Vec<Row> = read_rows(name, 9)
        .into_iter()
        .map(|v| v.try_into().unwrap())
        .collect();
    for (k, r) in rows.iter().enumerate() {
        assert!(
            (r[0] - k as f64 * SAMPLE).abs() < 1e-9,
            "row {k} at {}",
            r[0]
        );
    }
    assert!((rows.last().unwrap()[0] - T_STOP).abs() < 1e-9);
    rows
}

fn scene() -> Scene {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/automotive_rod.toml");
    let mut s = Scene::from_file(std::path::Path::new(path)).unwrap();
    s.rod.damping_ratio = 0.0;
    s
}

/// Run the reference's load case, rows at the reference's sampling times.
fn run(scene: &Scene) -> (Vec<Row>, std::time::Duration, String) {
    let law = CrankDrive::Ramp {
        speed: W,
        time: T_RAMP,
    };
    // Section at L/2 (the stations are linear in between).
    let stations = &scene.rod.section;
    let half = 0.5 * scene.rod.length;
    let at = |f: &dyn Fn(&flexrod::beam::SectionStation) -> f64| {
        let k = stations.partition_point(|s| s.position <= half).max(1);
        let (a, b) = (&stations[k - 1], &stations[k]);
        let u = (half - a.position) / (b.position - a.position);
        f(a) + u * (f(b) - f(a))
    };
    let area = at(&|s| s.area);
    let moment = at(&|s| s.area_moment);
    let fibre = at(&|s| s.fibre_distance.unwrap());
    let mut sim = flexrod::Simulation::new(scene).unwrap();
    let clock = std::time::Instant::now();
    sim.start(0.0, law.at(0.0), 0.0).unwrap();
    let row = |sim: &flexrod::Simulation, t: f64| -> Row {
        let o = sim.outputs();
        let (n, m) = (o.section.axial_force_mid, o.section.bending_moment_mid);
        [
            t,
            o.deflection_rel,
            o.pin_b_force[0],
            o.pin_b_force[1],
            o.pin_c_force[0],
            o.pin_c_force[1],
            n,
            m,
            n.abs() / area + m.abs() * fibre / moment,
        ]
    };
    let mut rows = vec![row(&sim, 0.0)];
    let n = (T_STOP / DT).round() as usize;
    let every = (SAMPLE / DT).round() as usize;
    for k in 0..n {
        let t = k as f64 * DT;
        sim.set_input(law.at(t)).unwrap();
        sim.set_slider_force(gas(law.at(t + 0.5 * DT).angle))
            .unwrap();
        sim.advance(DT).unwrap_or_else(|e| panic!("step {k}: {e}"));
        if (k + 1) % every == 0 {
            rows.push(row(&sim, (k + 1) as f64 * DT));
        }
    }
    (
        rows,
        clock.elapsed(),
        format!("{:?}", sim.mechanism().integrator_name()),
    )
}

/// With FLEXROD_BLESS=1: the stress at L/2 of the shipped scene and of the reference against
/// the crank angle, `docs/figures/automotive_stress.csv` (columns: t s, crank angle deg, FFR
/// stress MPa, reference stress MPa), which `docs/figures/automotive_stress.py` plots.
fn write_stress_curve(rows: &[Row], reference: &[Row]) {
    if !common::fragments::blessing() {
        return;
    }
    let law = CrankDrive::Ramp {
        speed: W,
        time: T_RAMP,
    };
    let mut csv = String::from("t_s,crank_angle_deg,ffr_stress_mpa,reference_stress_mpa\n");
    for (a, b) in rows.iter().zip(reference) {
        csv += &format!(
            "{:.5},{:.3},{:.4},{:.4}\n",
            a[0],
            law.at(a[0]).angle.to_degrees(),
            a[8] / 1e6,
            b[8] / 1e6
        );
    }
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/docs/figures/automotive_stress.csv"
    );
    std::fs::write(path, csv).unwrap();
    println!("wrote {path}");
}

/// Pointwise errors relative to the reference's peak.
#[derive(Debug, Default)]
struct Errors {
    deflection: f64,
    stress: f64,
    axial: f64,
    moment: f64,
    /// |F_B - F_B,ref| / max |F_B,ref|, over the whole run.
    pin_b: f64,
    pin_c: f64,
    /// The same over the firing spike (from 60 degrees before to 120 degrees after it).
    pin_b_firing: f64,
    pin_c_firing: f64,
}

fn compare(run: &[Row], reference: &[Row]) -> Errors {
    assert_eq!(run.len(), reference.len());
    let peak = |f: &dyn Fn(&Row) -> f64| reference.iter().map(f).fold(0.0, f64::max);
    let worst = |f: &dyn Fn(&Row, &Row) -> f64, window: bool| {
        let fire = T_RAMP + 15f64.to_radians() / W;
        run.iter()
            .zip(reference)
            .filter(|(r, _)| {
                !window || (r[0] > fire - 60f64.to_radians() / W && r[0] < fire + 2.0 / W)
            })
            .map(|(a, b)| f(a, b))
            .fold(0.0, f64::max)
    };
    let col = |i: usize| {
        worst(&|a: &Row, b: &Row| (a[i] - b[i]).abs(), false) / peak(&|r: &Row| r[i].abs())
    };
    let pin = |i: usize, window: bool| {
        worst(
            &|a: &Row, b: &Row| (a[i] - b[i]).hypot(a[i + 1] - b[i + 1]),
            window,
        ) / peak(&|r: &Row| r[i].hypot(r[i + 1]))
    };
    Errors {
        deflection: col(1),
        stress: col(8),
        axial: col(6),
        moment: col(7),
        pin_b: pin(2, false),
        pin_c: pin(4, false),
        pin_b_firing: pin(2, true),
        pin_c_firing: pin(4, true),
    }
}

#[test]
fn automotive_rod_against_the_geometrically_exact_shear_beam() {
    let reference = reference();
    let peak = |i: usize| reference.iter().map(|r| r[i].abs()).fold(0.0, f64::max);
    println!(
        "reference peaks: |v_mid/L| {:.3e}, stress at L/2 {:.1} MPa, |N_mid| {:.1} kN, |M_mid| {:.1} N m, |FBx| {:.1} kN, |FCx| {:.1} kN",
        peak(1),
        peak(8) / 1e6,
        peak(6) / 1e3,
        peak(7),
        peak(2) / 1e3,
        peak(4) / 1e3
    );
    let ffr = |elements: usize, modes: usize, method: SolverMethod, step: f64, tol: f64| {
        let mut s = scene();
        s.solver.tolerance = tol;
        s.rod.elements = elements;
        s.rod.modes = modes;
        s.solver.method = method;
        s.solver.step = step;
        s
    };
    let chain = |n: usize| {
        let mut s = scene();
        s.rod.model = RodModelKind::Segments;
        s.rod.shear_deformation = false;
        s.rod.shear_modulus = None;
        s.rod.elements = n;
        s
    };
    // (name, scene, bounds on deflection, stress and the pin forces); None: reported only.
    let cases = [
        (
            "FFR, the scene as shipped: 8 elements, 7 modes, auto (RK4(3) on minimal coordinates), tolerance 1e-3",
            scene(),
            Some((0.005, 0.005, 0.01)),
        ),
        (
            "FFR, 8 elements, 4 modes (the previous shipped scene), auto, tolerance 1e-3",
            ffr(8, 4, SolverMethod::Auto, 1e-5, 1e-3),
            None,
        ),
        (
            "FFR, 8 elements, 1 mode (the first bending mode, 2.0 kHz)",
            ffr(8, 1, SolverMethod::Dopri5, 1e-5, 1e-3),
            None,
        ),
        (
            "FFR, 8 elements, 2 modes (two bending modes, no axial mode)",
            ffr(8, 2, SolverMethod::Dopri5, 1e-5, 1e-3),
            None,
        ),
        (
            "FFR, 8 elements, 3 modes (adds the first axial mode, 7.3 kHz)",
            ffr(8, 3, SolverMethod::Dopri5, 1e-5, 1e-3),
            None,
        ),
        (
            "FFR, 8 elements, 6 modes, Dormand-Prince, tolerance 1e-3",
            ffr(8, 6, SolverMethod::Dopri5, 1e-5, 1e-3),
            Some((0.01, 0.005, 0.01)),
        ),
        (
            "FFR, 16 elements, 8 modes, Dormand-Prince, tolerance 1e-5",
            ffr(16, 8, SolverMethod::Dopri5, 1e-5, 1e-5),
            Some((0.005, 0.005, 0.01)),
        ),
        (
            "segment chain, 32 segments (no shear deformation; axially rigid, the default)",
            chain(32),
            None,
        ),
        (
            "segment chain, 16 segments, axial springs (no shear deformation)",
            {
                let mut s = chain(16);
                s.rod.axial_springs = true;
                s
            },
            // The pin forces, not the bending (no shear deformation).
            Some((0.2, 0.01, 0.01)),
        ),
    ];
    let mut table = String::from(
        "| model (automotive rod, undamped, ramp to 6000 rpm, gas pulse) | v_mid/L | stress at L/2 | N_mid | M_mid | pin B | pin C | pin B, firing | pin C, firing |\n|---|---|---|---|---|---|---|---|---|\n",
    );
    for (k, (name, scene, bounds)) in cases.into_iter().enumerate() {
        let (rows, time, integrator) = run(&scene);
        if k == 0 {
            write_stress_curve(&rows, &reference);
        }
        let e = compare(&rows, &reference);
        println!(
            "{name} [{integrator}, {:.0} ms]: {e:?}",
            time.as_secs_f64() * 1e3
        );
        let pct = |x: f64| format!("{:.2} %", 100.0 * x);
        table += &format!(
            "| {name} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
            pct(e.deflection),
            pct(e.stress),
            pct(e.axial),
            pct(e.moment),
            pct(e.pin_b),
            pct(e.pin_c),
            pct(e.pin_b_firing),
            pct(e.pin_c_firing)
        );
        if let Some((deflection, stress, pins)) = bounds {
            assert!(
                e.deflection < deflection && e.stress < stress,
                "{name}: {e:?}"
            );
            assert!(
                e.pin_b_firing < pins && e.pin_c_firing < pins,
                "{name}: {e:?}"
            );
            assert!(e.pin_b < pins && e.pin_c < pins, "{name}: {e:?}");
        } else {
            // Without shear the chain is too flexible in bending by about 12 % of v_mid here;
            // one or two modes are a coarse rod.
            assert!(e.pin_b < 0.2 && e.pin_c < 0.2, "{name}: {e:?}");
        }
    }
    check_generated("automotive-reference", &table);
}

/// The segment chain and the FFR rod without shear deformation against the reference's
/// Euler-Bernoulli limit (tests/data/exudyn_automotive_rod_euler_bernoulli.csv: the same run,
/// shear stiffness x 1e3): what the chain misses against the shear beam is the shear.
#[test]
fn chain_against_the_euler_bernoulli_limit() {
    let reference = reference_file("exudyn_automotive_rod_euler_bernoulli.csv");
    let no_shear = |s: &mut Scene| {
        s.rod.shear_deformation = false;
        s.rod.shear_modulus = None;
    };
    let mut ffr = scene();
    no_shear(&mut ffr);
    ffr.rod.elements = 16;
    ffr.rod.modes = 8;
    ffr.solver.method = SolverMethod::Dopri5;
    ffr.solver.tolerance = 1e-5;
    let mut chain = scene();
    no_shear(&mut chain);
    chain.rod.model = RodModelKind::Segments;
    chain.rod.elements = 32;
    chain.rod.axial_springs = true;
    chain.rod.elements = 16;
    for (name, scene) in [
        ("FFR, no shear, 16 el, 8 modes, tolerance 1e-5", ffr),
        ("segment chain, 16 segments, axial springs", chain),
    ] {
        let (rows, time, integrator) = run(&scene);
        let e = compare(&rows, &reference);
        println!(
            "{name} [{integrator}, {:.0} ms]: {e:?}",
            time.as_secs_f64() * 1e3
        );
        // The deflection and the moment differ by 1.4-1.8 %: most likely the section rotary
        // inertia, which the FFR without shear and the chain leave out and the reference keeps
        // (its couple was 2.7 % of M_mid with shear; not confirmed: the reference without it
        // did not converge).
        assert!(e.deflection < 0.025 && e.moment < 0.025, "{name}: {e:?}");
        assert!(e.stress < 0.005, "{name}: {e:?}");
        assert!(e.pin_b < 0.01 && e.pin_c < 0.01, "{name}: {e:?}");
    }
}
