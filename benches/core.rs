//! Benchmarks (issue 2, 3): preprocessing of a 64-element rod; two revolutions of the benchmark
//! slider-crank at 150 rad/s with the settings that meet 0.5 % peak-deflection accuracy.
//! Run: `cargo bench --bench core`.

use criterion::{criterion_group, criterion_main, Criterion};
use flexrod::beam::RodProperties;
use flexrod::drive::{self, communication_grid, CrankDrive};
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
                    RodProperties::seed001_benchmark(),
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
        "2 revolutions at 150 rad/s, default scene: auto (Dormand-Prince, tolerance 1e-3), 8 el, 3 modes, outputs every 3e-4",
        Scene::benchmark(),
        3e-4,
    );
    two_revolutions(
        c,
        "2 revolutions at 150 rad/s, RK4, 8 el, 3 modes, h 3e-4 (the previous default), outputs every 3e-4",
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

criterion_group!(benches, preprocessing, revolutions);
criterion_main!(benches);
