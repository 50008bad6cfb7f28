//! Issue 12 (speed): the FFR slider-crank on minimal coordinates in closed form
//! (`src/mechanism/minimal.rs`) against the general partitioned evaluation of the DAE
//! (`src/integrator/partitioned.rs`: Newton or closed-form dependent positions, LU solves of
//! the constraint Jacobian, the reduced mass matrix from the full one), and whole runs against
//! the constraint-based formulation at a converged step.

use faer::MatMut;
use flexrod::integrator::{DaeSystem, PartitionedRhs};
use flexrod::mechanism::dae::SliderCrankDae;
use flexrod::scene::SolverMethod;
use flexrod::{CrankInput, Scene, Simulation};

/// The same system without its closed form: the integrator takes the general path.
struct General<'a>(&'a SliderCrankDae<'a>);

impl DaeSystem for General<'_> {
    fn n_coordinates(&self) -> usize {
        self.0.n_coordinates()
    }
    fn n_constraints(&self) -> usize {
        self.0.n_constraints()
    }
    fn coordinate_scale(&self, i: usize) -> f64 {
        self.0.coordinate_scale(i)
    }
    fn mass(&self, q: &[f64], m: MatMut<'_, f64>) {
        self.0.mass(q, m)
    }
    fn forces(&self, t: f64, q: &[f64], v: &[f64], f: &mut [f64]) {
        self.0.forces(t, q, v, f)
    }
    fn constraints(&self, t: f64, q: &[f64], phi: &mut [f64]) {
        self.0.constraints(t, q, phi)
    }
    fn constraint_jacobian(&self, q: &[f64], jac: MatMut<'_, f64>) {
        self.0.constraint_jacobian(q, jac)
    }
    fn constraint_rate(&self, t: f64, q: &[f64], out: &mut [f64]) {
        self.0.constraint_rate(t, q, out)
    }
    fn constraint_acceleration_rhs(&self, t: f64, q: &[f64], v: &[f64], out: &mut [f64]) {
        self.0.constraint_acceleration_rhs(t, q, v, out)
    }
    fn solve_dependent_positions(&self, t: f64, q: &mut [f64]) -> bool {
        self.0.solve_dependent_positions(t, q)
    }
    fn add_tangent(
        &self,
        q: &[f64],
        v: &[f64],
        lambda: &[f64],
        c_k: f64,
        c_d: f64,
        out: MatMut<'_, f64>,
    ) {
        self.0.add_tangent(q, v, lambda, c_k, c_d, out)
    }
}

fn max_rel(a: &[f64], b: &[f64]) -> f64 {
    let scale = a.iter().fold(1e-300f64, |m, x| m.max(x.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs() / scale))
}

/// Scenes with every feature the closed form carries.
fn scenes() -> Vec<(&'static str, Scene)> {
    let mut out = vec![("default", Scene::benchmark())];
    let mut s = Scene::benchmark();
    s.rod.axial_stiffening = false;
    s.rod.damping_ratio = 0.02;
    s.slider.mass = 0.05;
    out.push(("no stiffening, damping, slider mass", s));
    let mut s = Scene::benchmark();
    s.mechanism.gravity = [0.0, -9.81];
    s.mechanism.slider_offset = 0.03;
    s.slider.mass = 0.1;
    s.rod.modes = 5;
    out.push(("gravity, offset, 5 modes", s));
    let mut s = Scene::benchmark();
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
            },
            7.0,
        )
        .unwrap();
        let mech = sim.mechanism();
        let state = sim.state();
        let sys = mech.system(state);
        assert!(sys.has_reduced_rhs(), "{name}: closed form available");
        let general = General(&sys);
        let n = sys.n_coordinates();
        let elastic: Vec<usize> = mech.rod.elastic_coordinates().unwrap().collect();
        let k = elastic.len();
        let mut fast = PartitionedRhs::new(&sys, elastic.clone());
        let mut slow = PartitionedRhs::new(&general, elastic.clone());
        let scale = mech.rod.coordinate_scale(elastic[0]);
        for trial in 0..5 {
            let t = 1e-3 * trial as f64;
            let z: Vec<f64> = (0..k)
                .map(|a| scale * 2e-3 * ((trial * 7 + a * 3) as f64).sin() / (1 + a) as f64)
                .collect();
            let zd: Vec<f64> = (0..k)
                .map(|a| scale * 0.5 * ((trial * 5 + a * 11) as f64).cos() / (1 + a) as f64)
                .collect();
            fast.q.copy_from_slice(&state.dae.q);
            slow.q.copy_from_slice(&state.dae.q);
            let (mut a_fast, mut a_slow) = (vec![0.0; k], vec![0.0; k]);
            fast.evaluate(&sys, t, &z, &zd, &mut a_fast).unwrap();
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
        }
    }
}
