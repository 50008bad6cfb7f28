//! Benchmarks: preprocessing of a 64-element rod; two revolutions of the benchmark
//! slider-crank at 150 rad/s with the settings that meet 0.5 % peak-deflection accuracy.
//! One right-hand side on the minimal coordinates against the general partitioned evaluation.
//! Run: `cargo bench --bench core`.

use criterion::{criterion_group, criterion_main, Criterion};
use flexrod::beam::RodProperties;
use flexrod::drive::{self, communication_grid, CrankDrive};
use flexrod::integrator::{GeneralPath, PartitionedRhs};
use flexrod::modal::{ComponentModes, ModeSelection, ReferenceConditions};
use flexrod::rod::ffr::FfrRod;
use flexrod::scene::{MassKind, SolverMethod};
use flexrod::{Scene, Simulation};
use std::hint::black_box;

fn preprocessing(c: &mut Criterion) {
    c.bench_function(
        "preprocess 64 elements (modes + shape integrals, 8 modes)",
        |b| {
            b.iter(|| {
                let m = ComponentModes::new(
                    RodProperties::cdi_benchmark(),
                    black_box(64),
                    ReferenceConditions::SimplySupported,
                    MassKind::Consistent,
                    &ModeSelection::Count(8),
                )
                .unwrap();
                black_box(FfrRod::new(m, 0.0, true))
            })
        },
    );
}

fn two_revolutions(c: &mut Criterion, name: &str, scene: Scene, comm_step: f64) {
    let w = 150.0;
    let stop = 4.0 * std::f64::consts::PI / w;
    let grid = communication_grid(0.0, comm_step, (stop / comm_step).round() as usize);
    let law = CrankDrive::Constant { speed: w };
    let mut sim = Simulation::new(&scene).unwrap();
    c.bench_function(name, |b| {
        b.iter(|| {
            let record = drive::run(&mut sim, &law, 0.0, &grid).unwrap();
            black_box(record.peak_deflection_rel())
        })
    });
}

fn revolutions(c: &mut Criterion) {
    let with = |method: SolverMethod, h: f64| {
        let mut s = Scene::benchmark();
        s.solver.method = method;
        s.rod.modes = 3;
        s.solver.step = h;
        s
    };
    let fast = with(SolverMethod::GeneralizedAlpha, 3e-4);
    two_revolutions(
        c,
        "2 revolutions at 150 rad/s, generalized-alpha, 8 el, 3 modes, h 3e-4 (peak 0.3 %, pointwise 9 %)",
        fast.clone(),
        3e-4,
    );
    two_revolutions(
        c,
        "2 revolutions at 150 rad/s, same, outputs only at the end",
        fast,
        4.0 * std::f64::consts::PI / 150.0,
    );
    two_revolutions(
        c,
        "2 revolutions at 150 rad/s, default scene: auto (exponential RK4(3), ETDRK4, on minimal coordinates, tolerance 1e-3), 8 el, 3 modes, outputs every 3e-4",
        Scene::benchmark(),
        3e-4,
    );
    for (name, method) in [
        (
            "2 revolutions at 150 rad/s, rk43 (the classic RK4(3) pair on minimal coordinates), tolerance 1e-3, outputs every 3e-4",
            SolverMethod::Rk43,
        ),
        (
            "2 revolutions at 150 rad/s, Dormand-Prince on minimal coordinates, tolerance 1e-3, outputs every 3e-4",
            SolverMethod::Dopri5,
        ),
    ] {
        let mut scene = Scene::benchmark();
        scene.solver.method = method;
        two_revolutions(c, name, scene, 3e-4);
    }
    two_revolutions(
        c,
        "2 revolutions at 150 rad/s, RK4 (fixed step, projected), 8 el, 3 modes, h 3e-4, outputs every 3e-4",
        with(SolverMethod::Rk4, 3e-4),
        3e-4,
    );
    two_revolutions(
        c,
        "2 revolutions at 150 rad/s, generalized-alpha, 8 el, 3 modes, h 5e-5 (pointwise 0.35 %)",
        with(SolverMethod::GeneralizedAlpha, 5e-5),
        1e-4,
    );
}

/// One right-hand side of the default scene on its modal coordinates: the closed form
/// (intermediate stage and last stage with the frame angle and multipliers) and the general
/// partitioned evaluation.
fn right_hand_side(c: &mut Criterion) {
    let scene = Scene::benchmark();
    let mut sim = Simulation::new(&scene).unwrap();
    let input = flexrod::CrankInput {
        angle: 0.3,
        speed: 150.0,
        acceleration: 0.0,
        jerk: 0.0,
    };
    sim.start(0.0, input, 0.0).unwrap();
    let mech = sim.mechanism();
    let sys = mech.system(sim.state());
    let general = GeneralPath(&sys);
    let elastic: Vec<usize> = mech.rod.elastic_coordinates().unwrap().collect();
    let z = [1e-4, -2e-5, 1e-6];
    let zd = [1e-2, 1e-3, -1e-3];
    let mut zdd = [0.0; 3];
    let mut rhs = PartitionedRhs::new(&sys, elastic.clone());
    rhs.q.copy_from_slice(&sim.state().dae.q);
    for (name, complete) in [
        (
            "right-hand side, minimal coordinates (intermediate stage)",
            false,
        ),
        (
            "right-hand side, minimal coordinates (last stage: angle and multipliers)",
            true,
        ),
    ] {
        c.bench_function(name, |b| {
            b.iter(|| {
                rhs.evaluate_stage(&sys, black_box(1e-3), &z, &zd, &mut zdd, complete)
                    .unwrap();
                if complete {
                    rhs.multipliers();
                }
                black_box(zdd[0])
            })
        });
    }
    let mut rhs = PartitionedRhs::new(&general, elastic);
    rhs.q.copy_from_slice(&sim.state().dae.q);
    c.bench_function(
        "right-hand side, general partitioned evaluation (no closed form)",
        |b| {
            b.iter(|| {
                rhs.evaluate(&general, black_box(1e-3), &z, &zd, &mut zdd)
                    .unwrap();
                rhs.multipliers();
                black_box(zdd[0])
            })
        },
    );
}

criterion_group!(benches, preprocessing, revolutions, right_hand_side);
criterion_main!(benches);
