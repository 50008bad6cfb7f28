//! Speed: the FFR slider-crank on minimal coordinates in closed form
//! (`src/mechanism/minimal.rs`) against the general partitioned evaluation of the DAE
//! (`src/integrator/partitioned.rs`: Newton or closed-form dependent positions, LU solves of
//! the constraint Jacobian, the reduced mass matrix from the full one), and whole runs against
//! the constraint-based formulation at a converged step; the chain on its modes in closed form on
//! its frame (`src/mechanism/frame_coordinates_closed_form.rs`) against the same general evaluation.

mod common;

use flexrod::drive::{self, communication_grid, CrankDrive, Record};
use flexrod::integrator::{DaeSystem, GeneralPath, PartitionedRhs};
use flexrod::scene::SolverMethod;
use flexrod::{CrankInput, Scene, Simulation};

fn max_rel(a: &[f64], b: &[f64]) -> f64 {
    let scale = a.iter().fold(1e-300f64, |m, x| m.max(x.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs() / scale))
}

/// Scenes with every feature the closed form carries.
fn scenes() -> Vec<(&'static str, Scene)> {
    let mut out = vec![("default", common::euler_bernoulli_benchmark())];
    let mut s = common::euler_bernoulli_benchmark();
    s.rod.axial_stiffening = false;
    s.rod.damping_ratio = 0.02;
    s.slider.mass = 0.05;
    out.push(("no stiffening, damping, slider mass", s));
    let mut s = common::euler_bernoulli_benchmark();
    s.mechanism.gravity = [0.0, -9.81];
    s.mechanism.slider_offset = 0.03;
    s.slider.mass = 0.1;
    s.rod.modes = 5;
    out.push(("gravity, offset, 5 modes", s));
    let mut s = common::euler_bernoulli_benchmark();
    s.rod.reference = flexrod::modal::ReferenceKind::MeanAxis;
    s.rod.mass = flexrod::beam::MassKind::Lumped;
    s.rod.modes = 4;
    out.push(("mean axis, lumped, 4 modes", s));
    let mut s = Scene::from_file(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenes/automotive_rod.toml"
    )))
    .unwrap();
    s.mechanism.gravity = [0.0, -9.81];
    out.push(("automotive rod (section table, end masses), gravity", s));
    out
}

#[test]
fn closed_form_equals_general_evaluation() {
    for (name, mut scene) in scenes() {
        scene.solver.method = SolverMethod::Dopri5;
        let mut sim = Simulation::new(&scene).unwrap();
        let w = 150.0;
        sim.start(
            0.0,
            CrankInput {
                angle: 0.3,
                speed: w,
                acceleration: 40.0,
                jerk: 0.0,
            },
            7.0,
        )
        .unwrap();
        let mech = sim.mechanism();
        let state = sim.state();
        let sys = mech.system(state);
        assert!(sys.has_reduced_rhs(), "{name}: closed form available");
        compare_with_general(name, &sys, mech.rod.as_ref(), &state.dae.q, 2e-3, 0.5);
    }
}

/// The closed form of `sys` (the system of `rod`, dependent positions starting from `q0`)
/// against its general partitioned evaluation at five sets of independent coordinates (the
/// elastic ones, `amplitude` and `rate` times the first one's scale, rad/s for the rates):
/// positions, velocities, accelerations and multipliers to 1e-10 relative.
fn compare_with_general(
    name: &str,
    sys: &dyn DaeSystem,
    rod: &dyn flexrod::rod::RodBody,
    q0: &[f64],
    amplitude: f64,
    rate: f64,
) {
    let general = GeneralPath(sys);
    let n = sys.n_coordinates();
    let elastic: Vec<usize> = rod.elastic_coordinates().unwrap().collect();
    let k = elastic.len();
    let mut fast = PartitionedRhs::new(sys, elastic.clone());
    let mut slow = PartitionedRhs::new(&general, elastic.clone());
    let scale = rod.coordinate_scale(elastic[0]);
    for trial in 0..5 {
        let t = 1e-3 * trial as f64;
        let z: Vec<f64> = (0..k)
            .map(|a| scale * amplitude * ((trial * 7 + a * 3) as f64).sin() / (1 + a) as f64)
            .collect();
        let zd: Vec<f64> = (0..k)
            .map(|a| scale * rate * ((trial * 5 + a * 11) as f64).cos() / (1 + a) as f64)
            .collect();
        fast.q.copy_from_slice(q0);
        slow.q.copy_from_slice(q0);
        let (mut a_fast, mut a_slow) = (vec![0.0; k], vec![0.0; k]);
        fast.evaluate(sys, t, &z, &zd, &mut a_fast).unwrap();
        slow.evaluate(&general, t, &z, &zd, &mut a_slow).unwrap();
        fast.multipliers();
        slow.multipliers();
        let e = [
            max_rel(&slow.q, &fast.q),
            max_rel(&slow.v, &fast.v),
            max_rel(&slow.qdd, &fast.qdd),
            max_rel(&slow.lambda, &fast.lambda),
        ];
        println!("{name}, trial {trial}: relative differences q, v, qdd, lambda {e:?}");
        assert!(
            e.iter().all(|x| *x < 1e-10),
            "{name}, trial {trial}: {e:?}\nq {:?}\n  {:?}\nqdd {:?}\n    {:?}\nlambda {:?}\n       {:?}",
            slow.q,
            fast.q,
            slow.qdd,
            fast.qdd,
            slow.lambda,
            fast.lambda
        );
        assert_eq!(fast.q.len(), n);
        assert!(fast.q.iter().all(|x| x.is_finite()));
    }
}

/// The chain on its modes: its closed form on the frame (`src/mechanism/frame_coordinates_closed_form.rs`)
/// against the general partitioned evaluation, with shear slides, end bodies (with and
/// without rotation: the direct evaluation and the projection), a slider mass, gravity and an
/// offset.
#[test]
fn frame_form_equals_general_evaluation() {
    let modal = |f: &dyn Fn(&mut Scene)| {
        let mut s = Scene::benchmark();
        s.rod.model = flexrod::rod::RodModelKind::ModalSegments;
        s.rod.elements = 24;
        f(&mut s);
        s
    };
    let scenes = [
        ("shear (auto)", modal(&|_| {})),
        (
            "no shear, slider, gravity, offset",
            modal(&|s| {
                s.rod.shear_deformation = flexrod::rod::PhysicsSwitch::Off;
                s.slider.mass = 0.05;
                s.mechanism.gravity = [0.0, -9.81];
                s.mechanism.slider_offset = 0.02;
            }),
        ),
        (
            "end bodies with rotation (projection), axial dynamics",
            modal(&|s| {
                s.rod.big_end.mass = 0.02;
                s.rod.big_end.inertia = 1e-5;
                s.rod.small_end.mass = 0.01;
                s.rod.small_end.inertia = 5e-6;
                s.rod.axial_dynamics = flexrod::rod::PhysicsSwitch::On;
                s.slider.mass = 0.1;
            }),
        ),
    ];
    for (name, scene) in scenes {
        let mut sim = Simulation::new(&scene).unwrap();
        let w = 300.0;
        sim.start(
            0.0,
            CrankInput {
                angle: 0.7,
                speed: w,
                acceleration: 40.0,
                jerk: 0.0,
            },
            7.0,
        )
        .unwrap();
        let mech = sim.mechanism();
        assert_eq!(
            mech.spec.rod.model,
            flexrod::rod::RodModelKind::ModalSegments
        );
        let state = sim.state();
        let sys = mech.system(state);
        assert_eq!(
            mech.rod.elastic_coordinates(),
            Some(3..sys.n_coordinates() - 1)
        );
        compare_with_general(name, &sys, mech.rod.as_ref(), &state.dae.q, 2e-2, 5.0);
    }
}

fn run(scene: &Scene, dt: f64, duration: f64) -> (Record, String) {
    let mut sim = Simulation::new(scene).unwrap();
    let steps = (duration / dt).round().max(1.0) as usize;
    let record = drive::run(
        &mut sim,
        &CrankDrive::Constant { speed: 150.0 },
        0.0,
        &communication_grid(0.0, dt, steps),
    )
    .unwrap();
    (record, sim.mechanism().integrator_name().0.to_string())
}

fn fields(o: &flexrod::Outputs) -> [f64; 8] {
    [
        o.deflection_rel,
        o.pin_b_force[0],
        o.pin_b_force[1],
        o.pin_c_force[0],
        o.pin_c_force[1],
        o.crank_torque,
        o.slider_position,
        o.slider_velocity,
    ]
}

/// Largest difference of each output over the reference's peak of that output.
fn differences(a: &Record, reference: &Record) -> [f64; 8] {
    std::array::from_fn(|j| {
        let peak = reference
            .outputs
            .iter()
            .map(|o| fields(o)[j].abs())
            .fold(0.0, f64::max);
        let diff = a
            .outputs
            .iter()
            .zip(&reference.outputs)
            .map(|(x, y)| (fields(x)[j] - fields(y)[j]).abs())
            .fold(0.0, f64::max);
        if peak == 0.0 {
            diff
        } else {
            diff / peak
        }
    })
}

/// Whole runs: both pairs on the closed-form minimal coordinates (`auto`: RK4(3); `dopri5`:
/// Dormand-Prince) at a converged tolerance against the constraint-based index-1 formulation
/// (fixed-step RK4 with projection, h = 6.25e-7; `src/integrator/runge_kutta.rs`), a quarter
/// revolution at 150 rad/s from the undeformed start, every output within 1e-6 of its peak,
/// on every scene of [`scenes`] (default, no stiffening with damping and slider mass, gravity
/// with offset and 5 modes, mean axis with lumped mass, the automotive rod with its section
/// table and end masses under gravity). Measured: at most 1.3e-7 of the peak.
#[test]
fn runs_equal_the_constraint_based_formulation_at_a_converged_step() {
    let duration = 0.25 * 2.0 * std::f64::consts::PI / 150.0;
    for (name, scene) in scenes() {
        let mut old = scene.clone();
        old.solver.method = SolverMethod::Rk4;
        // Converged for every scene here (1e-5 left 1.6e-5 of the peak in the pin forces of
        // the 5-mode scene and 2.8e-6 at 2.5e-6 for the stiff automotive rod: the reference's
        // own error).
        old.solver.step = 6.25e-7;
        let (reference, old_name) = run(&old, 1e-4, duration);
        for method in [SolverMethod::Auto, SolverMethod::Dopri5] {
            let mut new = scene.clone();
            new.solver.method = method;
            new.solver.tolerance = 1e-9;
            let (record, new_name) = run(&new, 1e-4, duration);
            assert!(
                new_name.contains("minimal coordinates"),
                "{name}: {new_name}"
            );
            let d = differences(&record, &reference);
            let worst = d.iter().cloned().fold(0.0, f64::max);
            println!(
                "{name}: {new_name} ({} steps) vs {old_name}: largest difference {worst:.1e} of the peak ({d:?})",
                record.stats.steps
            );
            assert!(worst <= 1e-6, "{name}, {new_name}: {d:?}");
        }
    }
}

/// `auto` reports its choice: the closed form on the FFR rod (the exponential form where the
/// modes are the mechanism's own oscillators: they leave the pins in place, or they carry the
/// piston as mass-loaded modes, as the shipped automotive rod's; the classic pair where free
/// modes move the pins, as the automotive rod's free axial modes move the piston), the general
/// path otherwise.
#[test]
fn auto_reports_the_path_it_takes() {
    let sim = Simulation::new(&common::euler_bernoulli_benchmark()).unwrap();
    assert_eq!(
        sim.mechanism().integrator_name().0,
        "exponential Runge-Kutta 4(3) (ETDRK4, modal oscillators exact) on minimal coordinates (closed form)"
    );
    let text = std::fs::read_to_string("scenes/automotive_rod.toml").unwrap();
    let automotive = Scene::from_toml_str(&text, "scenes/automotive_rod.toml").unwrap();
    let sim = Simulation::new(&automotive).unwrap();
    assert_eq!(
        sim.mechanism().integrator_name().0,
        "exponential Runge-Kutta 4(3) (ETDRK4, modal oscillators exact) on minimal coordinates (closed form)"
    );
    let mut free_modes = automotive.clone();
    free_modes.rod.loaded_modes = false;
    free_modes.rod.mode_band_hz = None;
    free_modes.rod.modes = 7;
    // The free axial mode, not the mass-loaded one `auto` takes for the heavy piston.
    free_modes.rod.axial_dynamics = flexrod::rod::PhysicsSwitch::Off;
    free_modes.rod.axial_modes = Some(1);
    let sim = Simulation::new(&free_modes).unwrap();
    assert_eq!(
        sim.mechanism().integrator_name().0,
        "Runge-Kutta 4(3) on minimal coordinates (closed form)"
    );
    let mut forced = free_modes.clone();
    forced.solver.method = flexrod::scene::SolverMethod::Exponential;
    let sim = Simulation::new(&forced).unwrap();
    assert!(sim
        .mechanism()
        .integrator_name()
        .0
        .starts_with("exponential"));
    let mut too_many = common::euler_bernoulli_benchmark();
    too_many.rod.modes = 9;
    too_many.rod.elements = 16;
    too_many.solver.method = flexrod::scene::SolverMethod::Exponential;
    let error = Simulation::new(&too_many)
        .err()
        .expect("refused")
        .to_string();
    assert!(
        error.contains("solver.method") && error.contains("1 to 8 modes"),
        "{error}"
    );
    let mut classic = common::euler_bernoulli_benchmark();
    classic.solver.method = flexrod::scene::SolverMethod::Rk43;
    let sim = Simulation::new(&classic).unwrap();
    assert_eq!(
        sim.mechanism().integrator_name().0,
        "Runge-Kutta 4(3) on minimal coordinates (closed form)"
    );
    let mut many = common::euler_bernoulli_benchmark();
    many.rod.modes = 9;
    many.rod.elements = 16;
    let sim = Simulation::new(&many).unwrap();
    let name = sim.mechanism().integrator_name().0;
    assert!(!name.contains("closed form"), "{name}");
    let mut chain = common::euler_bernoulli_benchmark();
    chain.rod.model = flexrod::scene::RodModelKind::Segments;
    let sim = Simulation::new(&chain).unwrap();
    let name = sim.mechanism().integrator_name().0;
    assert!(!name.contains("closed form"), "{name}");
}

/// A smooth start sampled at the communication points (the crank law changes at every one):
/// `auto` on minimal coordinates follows the constraint-based RK4 at a fine step. Regression:
/// a restart that kept the modal coordinates and rates at each law change drifted 0.54 % of
/// the peak deflection.
#[test]
fn sampled_ramp_matches_the_constraint_based_rk4() {
    use flexrod::drive::{self, communication_grid, CrankDrive};
    use flexrod::scene::SolverMethod;
    use flexrod::Simulation;
    let drive = CrankDrive::Ramp {
        speed: 150.0,
        time: 0.02,
    };
    let grid = communication_grid(0.0, 1e-4, 600);
    let run = |method: SolverMethod, tolerance: f64, step: f64| {
        let mut s = common::euler_bernoulli_benchmark();
        s.solver.method = method;
        s.solver.tolerance = tolerance;
        s.solver.step = step;
        let mut sim = Simulation::new(&s).unwrap();
        let record = drive::run(&mut sim, &drive, 0.0, &grid).unwrap();
        record
            .outputs
            .iter()
            .map(|o| o.deflection_rel)
            .collect::<Vec<f64>>()
    };
    let reference = run(SolverMethod::Rk4, 1e-3, 1e-5);
    let peak = common::runs::peak(&reference);
    for method in [SolverMethod::Auto, SolverMethod::Dopri5] {
        let x = run(method, 1e-5, 1e-4);
        let worst = common::runs::max_diff(&x, &reference) / peak;
        println!("{method:?}: {worst:.3e} of peak");
        assert!(worst < 2e-4, "{method:?}: {worst:e}");
    }
}
