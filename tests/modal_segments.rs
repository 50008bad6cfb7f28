//! The segment chain on its lowest bending modes (`rod.model = "modal_segments"`,
//! `flexrod::rod::segments::ModalSegmentRod`): with every mode it is the chain itself; with a
//! few it converges to the geometrically exact beam as the chain is refined, and it stays exact
//! at the deflections where the FFR rod's linear elastic field does not (300 rad/s).
//!
//! Run with `cargo test --release --test modal_segments -- --nocapture` to see the numbers.

use flexrod::scene::{RodModelKind, SolverMethod};
use flexrod::{Scene, Simulation};

mod common;
use common::exudyn;
use common::generated::{percent, Fragment};
use common::runs::{self, max_diff, peak};

/// docs/physics.md, "Rod model 3": what the tests below measure (generated fragment
/// `modal-segments`).
static MEASURED: Fragment = Fragment::new(
    "modal-segments",
    "Measured (`cargo test --release --test modal_segments -- --nocapture`):\n\n",
    &[
        "chain",
        "convergence",
        "high-load",
        "discretization",
        "limit",
        "folding",
        "collapse",
        "axial",
    ],
);

/// The Euler-Bernoulli benchmark rod as the chain on `modes` modes of `segments` segments.
fn modal(segments: usize, modes: usize) -> Scene {
    let mut s = common::euler_bernoulli_benchmark();
    s.rod.model = RodModelKind::ModalSegments;
    s.rod.elements = segments;
    s.rod.modes = modes;
    s
}

fn pin_b(record: &flexrod::drive::Record) -> Vec<f64> {
    record
        .outputs
        .iter()
        .map(|o| o.pin_b_force[0].hypot(o.pin_b_force[1]))
        .collect()
}

/// With all `N - 1` bending modes the basis spans the chain's coordinates: the same motion as
/// the chain, to the integrator's Newton tolerance (same method and step).
#[test]
fn every_mode_is_the_chain() {
    let fixed = |mut s: Scene| {
        s.solver.method = SolverMethod::GeneralizedAlpha;
        s.solver.step = 2e-5;
        s
    };
    // Bending only on both sides (the chain of 6 segments would take 5 axial slides in).
    let mut chain = common::euler_bernoulli_benchmark();
    chain.rod.axial_dynamics = flexrod::rod::PhysicsSwitch::Off;
    chain.rod.model = RodModelKind::Segments;
    chain.rod.elements = 6;
    let (a, _) = runs::constant(&fixed(chain), 150.0, 1e-4, 1.0);
    let mut every = modal(6, 5);
    every.rod.axial_dynamics = flexrod::rod::PhysicsSwitch::Off;
    let (b, _) = runs::constant(&fixed(every), 150.0, 1e-4, 1.0);
    let (x, y) = (a.deflection_rel(), b.deflection_rel());
    let d = max_diff(&x, &y) / peak(&x);
    let f = max_diff(&pin_b(&a), &pin_b(&b)) / peak(&pin_b(&a));
    println!("6 segments, 5 modes against the chain: v_mid {d:.2e}, pin B {f:.2e} of the peaks");
    assert!(d < 1e-6 && f < 1e-6, "{d:e} {f:e}");
    MEASURED.add(
        "chain",
        format!(
            "- 6 segments on all 5 bending modes against the chain itself (150 rad/s, one revolution,\n  \
             generalized-alpha at 2e-5 s): `v_mid` and pin B differ by {} of their peaks.",
            common::generated::under(d.max(f), 1e-10)
        ),
    );
}

/// At 150 rad/s, 16 to 128 segments (`rod.modes = 3`: the band keeps 4): the differences between successive
/// refinements fall as `1 / N^2` (the chain's order, measured), and the Richardson limit lies
/// within 0.2 % of the ANCF cable (Euler-Bernoulli, converged) pointwise, as the plain chain and
/// the FFR rod do.
#[test]
fn converges_to_the_exact_beam_as_the_chain_is_refined() {
    let reference = exudyn::samples();
    let runs: Vec<Vec<f64>> = [16, 32, 64, 128]
        .iter()
        .map(|&n| {
            let mut s = modal(n, 3);
            s.solver.tolerance = 1e-6;
            let (record, _) = runs::constant(&s, exudyn::SPEED, exudyn::DT, 2.0);
            let c = exudyn::compare(&record, &reference);
            println!(
                "{n} segments, 4 modes, tolerance 1e-6: v_mid {:.4} % of the ANCF peak pointwise, peak {:+.4} %",
                100.0 * c.pointwise,
                100.0 * c.peak_error
            );
            record.deflection_rel()
        })
        .collect();
    let p = peak(&runs[3]);
    let steps: Vec<f64> = runs
        .windows(2)
        .map(|w| max_diff(&w[0], &w[1]) / p)
        .collect();
    let orders: Vec<f64> = steps.windows(2).map(|e| (e[0] / e[1]).log2()).collect();
    let limit: Vec<f64> = runs[3]
        .iter()
        .zip(&runs[2])
        .map(|(fine, coarse)| fine + (fine - coarse) / 3.0)
        .collect();
    let exact: Vec<f64> = reference.iter().map(|r| r.deflection_rel).collect();
    let n = exact.len().min(limit.len());
    let gap = max_diff(&limit[..n], &exact[..n]) / exudyn::peak(&reference);
    println!(
        "successive differences {:?}, orders {orders:.2?}; limit against ANCF {:.3} %",
        steps.iter().map(|d| format!("{d:.1e}")).collect::<Vec<_>>(),
        100.0 * gap
    );
    for p in &orders {
        assert!((1.7..2.4).contains(p), "order {p}");
    }
    assert!(gap < 2e-3, "{gap:e}");
    MEASURED.add(
        "convergence",
        format!(
            "- 150 rad/s, 4 modes, 16 / 32 / 64 / 128 segments: successive differences {}\n  \
             of the peak, order {:.2} and {:.2}; the Richardson limit lies {} of the peak from the ANCF cable\n  \
             pointwise (the plain chain and the FFR rod lie as far from it).",
            steps.iter().map(|d| percent(*d, 2)).collect::<Vec<_>>().join(" / "),
            orders[0],
            orders[1],
            percent(gap, 2)
        ),
    );
}

/// Two revolutions at 300 rad/s (peak `|v_mid / L|` 0.07, abrupt start): the benchmark scene
/// with its defaults (`rod.model = auto` takes the chain on its modes, with the segments the
/// tolerance asks for; the band keeps the 4 bending modes up to 20 times the first; `auto` takes
/// shear in) against Exudyn's geometrically exact shear beam (512 elements, converged to
/// 8e-5 of the peak; tests/data/exudyn_shear_beam_300rad_s.csv): `v_mid` pointwise. The exact
/// beam's pin forces carry its axial ringing after the abrupt start (not converged pointwise:
/// 5 to 7 % of the peak between its own refinements), which the inextensible chain has not:
/// the pin forces are compared with the full chain of 64 segments with shear slides
/// (generalized-alpha at 5e-6 s). The FFR rod is 3.4 % off here
/// (tests/segments.rs, `ffr_levels_off_at_300_rad_s`).
#[test]
fn exact_at_300_rad_s() {
    let omega = 300.0;
    let exact = exudyn::samples_of("exudyn_shear_beam_300rad_s.csv");
    let mut chain = flexrod::Scene::benchmark();
    chain.rod.model = RodModelKind::Segments;
    chain.rod.elements = 64;
    chain.rod.shear_deformation = flexrod::rod::PhysicsSwitch::On;
    chain.solver.method = SolverMethod::GeneralizedAlpha;
    chain.solver.step = 5e-6;
    let (reference, _) = runs::constant(&chain, omega, 1e-4, 2.0);
    // The FMU's defaults, only the crank speed set: `rod.model = auto` takes the chain on its
    // modes for the load, with the segments the tolerance asks for.
    let s = flexrod::Scene::benchmark();
    assert_eq!(s.rod.model, RodModelKind::Auto);
    let (record, sim) = runs::constant(&s, omega, 1e-4, 2.0);
    let built = &sim.mechanism().spec.rod;
    assert_eq!(built.model, RodModelKind::ModalSegments);
    let (segments, modes) = (built.elements, sim.mechanism().rod.n_coordinates() - 3);
    let c = exudyn::compare(&record, &exact);
    let forces = |r: &flexrod::drive::Record, pin: usize| -> Vec<f64> {
        r.outputs
            .iter()
            .map(|o| {
                let f = if pin == 0 {
                    o.pin_b_force
                } else {
                    o.pin_c_force
                };
                f[0].hypot(f[1])
            })
            .collect()
    };
    let force_error = |pin: usize| {
        let (a, b) = (forces(&record, pin), forces(&reference, pin));
        max_diff(&a, &b) / peak(&b)
    };
    let (fb, fc) = (force_error(0), force_error(1));
    println!(
        "300 rad/s, the defaults (auto: {segments} segments on {modes} modes): v_mid {:.3} % of the exact beam's peak pointwise (peak {:+.3} %); pins B, C {:.3} %, {:.3} % of the chain's peaks; {} steps; warnings {:?}",
        100.0 * c.pointwise,
        100.0 * c.peak_error,
        100.0 * fb,
        100.0 * fc,
        sim.stats().steps,
        record.warnings
    );
    assert!(exudyn::peak(&exact) > 0.06);
    assert!(c.pointwise < 3e-3, "{c:?}");
    assert!(fb < 1e-2 && fc < 1e-2, "{fb:e} {fc:e}");
    // Within the tolerance: no warning that the estimate passed it.
    assert!(record.warnings.is_empty(), "{:?}", record.warnings);
    // The error estimate (the chain's discretization share 1.4 / N^2 with the integration's)
    // is within a factor 3 of the measured error.
    let estimate = record.outputs.last().unwrap().error_estimate;
    let ratio = estimate / c.pointwise;
    println!("rod.error_estimate {estimate:.2e}: {ratio:.2} times the measured error");
    assert!((1.0 / 3.0..3.0).contains(&ratio), "{ratio}");
    MEASURED.add(
        "high-load",
        format!(
            "- 300 rad/s (abrupt start, two revolutions, peak `|v_mid/L|` {:.3}): the benchmark scene\n  \
             with only the crank speed set (`rod.model = auto` takes the chain on its modes: {segments}\n  \
             segments on {modes} modes at tolerance 1e-3, shear by `auto`) within {} of the peak `v_mid`\n  \
             of Exudyn's geometrically exact shear beam pointwise (the FFR rod: 3.4 %), pin forces B\n  \
             and C within {} and {} of the full chain of 64 segments, in {} steps;\n  \
             `rod.error_estimate` {:.1e}, {:.1} times the measured error.",
            exudyn::peak(&exact),
            percent(c.pointwise, 2),
            percent(fb, 2),
            percent(fc, 2),
            sim.stats().steps,
            estimate,
            ratio
        ),
    );
}

/// The chains' discretization share of the error estimate, `C / N^2`
/// (`flexrod::rod::physics_choice::CHAIN_DISCRETIZATION_COEFFICIENT`): at 300 rad/s against the
/// exact beam, 8, 16 and 24 segments, `C_N = (e_N - 0.1 %) N^2` (the other shares taken off)
/// stays below the coefficient, and the estimate within a factor 3 of the measured error.
#[test]
fn discretization_share_of_the_estimate() {
    let exact = exudyn::samples_of("exudyn_shear_beam_300rad_s.csv");
    let c = flexrod::rod::physics_choice::CHAIN_DISCRETIZATION_COEFFICIENT;
    let mut rows = Vec::new();
    for n in [8usize, 16, 24] {
        let mut s = flexrod::Scene::benchmark();
        s.rod.model = RodModelKind::ModalSegments;
        s.rod.elements = n;
        let (record, _) = runs::constant(&s, 300.0, exudyn::DT, 2.0);
        let e = exudyn::compare(&record, &exact).pointwise;
        let estimate = record.outputs.last().unwrap().error_estimate;
        let c_n = (e - 1e-3) * (n * n) as f64;
        println!(
            "{n} segments: {:.3} % of the exact peak, C_N {c_n:.2}, estimate / error {:.2}",
            100.0 * e,
            estimate / e
        );
        assert!(c_n > 0.5 && c_n < c, "{n}: {c_n}");
        assert!(
            (1.0 / 3.0..3.0).contains(&(estimate / e)),
            "{n}: {estimate} vs {e}"
        );
        rows.push((n, e, c_n));
    }
    MEASURED.add(
        "discretization",
        format!(
            "- The chains' discretization share of `rod.error_estimate`, {c} / N^2: at 300 rad/s 8, 16, 24\n  \
             segments are {} off the exact beam (`C_N` = {:.2}, {:.2}, {:.2} with 0.1 % for the other shares).",
            rows.iter().map(|r| percent(r.1, 2)).collect::<Vec<_>>().join(", "),
            rows[0].2,
            rows[1].2,
            rows[2].2
        ),
    );
}

/// The deflection limit follows the model: at 450 rad/s (peak `|v_mid / L|` 0.18) the chain on
/// its modes runs through under the default policy (discard) within 0.1 % of the chain of 64
/// segments, where the FFR rod's step past 0.05 is refused with a message that names
/// `modal_segments`.
#[test]
fn deflection_limit_follows_the_model() {
    let omega = 450.0;
    let mut chain = common::euler_bernoulli_benchmark();
    chain.rod.model = RodModelKind::Segments;
    chain.rod.elements = 64;
    chain.solver.method = SolverMethod::GeneralizedAlpha;
    chain.solver.step = 5e-6;
    let (reference, _) = runs::constant(&chain, omega, 1e-4, 2.0);
    let s = modal(64, 3);
    assert_eq!(s.rod.deflection_limit(), 0.25);
    let (record, sim) = runs::constant(&s, omega, 1e-4, 2.0);
    let (x, r) = (record.deflection_rel(), reference.deflection_rel());
    let d = max_diff(&x, &r) / peak(&r);
    let f = max_diff(&pin_b(&record), &pin_b(&reference)) / peak(&pin_b(&reference));
    println!(
        "450 rad/s: peak |v/L| {:.3}; 64 segments on 4 modes: v_mid {:.3} %, pin B {:.3} %, {} steps",
        peak(&r),
        100.0 * d,
        100.0 * f,
        sim.stats().steps
    );
    assert!(peak(&r) > 0.15 && d < 1e-3 && f < 2e-3, "{d:e} {f:e}");
    let ffr = common::euler_bernoulli_benchmark();
    assert_eq!(ffr.rod.deflection_limit(), 0.05);
    let message = match flexrod::drive::run_constant(&ffr, omega, 1e-4, 2.0) {
        Err(e) => e.to_string(),
        Ok(_) => panic!("the FFR rod's step past 0.05 is accepted"),
    };
    assert!(message.contains("rod.deflection_limit = 0.05"), "{message}");
    assert!(message.contains("rod.model = modal_segments"), "{message}");
    MEASURED.add(
        "limit",
        format!(
            "- 450 rad/s (peak `|v_mid/L|` {:.2}): 64 segments on 4 modes within {} (`v_mid`) and {}\n  \
             (pin B) of the chain of 64 segments; the chains' `rod.deflection_limit` is 0.25, the FFR\n  \
             rod's 0.05.",
            peak(&r),
            percent(d, 2),
            percent(f, 2)
        ),
    );
}

/// 600 rad/s (the exact beam buckles and folds: peak `|v_mid / L|` 0.41, the chord shrinks to
/// a quarter of the rod; tests/data/exudyn_shear_beam_600rad_s.csv, converged to 2e-4 of its
/// peak): with the default policy (discard) every accepted step of either model is within 1 %
/// of the exact beam's peak, and the step past the model's limit is refused with the reason
/// (the FFR rod at 0.05, the chain on its modes at 0.25).
/// Drive `s` at `w` rad/s from the undeformed start against `exact` (its time grid): the
/// largest error of an accepted step relative to `peak`, and the refused step's end time and
/// message.
fn follow(s: &Scene, w: f64, exact: &[exudyn::Sample], peak: f64) -> (f64, f64, String) {
    let mut sim = Simulation::new(s).unwrap();
    let input = |t: f64| flexrod::CrankInput {
        angle: w * t,
        speed: w,
        ..Default::default()
    };
    sim.start(0.0, input(0.0), 0.0).unwrap();
    let mut worst: f64 = 0.0;
    for k in 0..exact.len() - 1 {
        let t = k as f64 * exudyn::DT;
        sim.set_input(input(t)).unwrap();
        match sim.advance(exudyn::DT) {
            Ok(_) => {
                let d = sim.outputs().deflection_rel - exact[k + 1].deflection_rel;
                worst = worst.max(d.abs() / peak);
            }
            Err(e) => return (worst, t + exudyn::DT, e.to_string()),
        }
    }
    panic!("not refused before the reference ends: worst {worst}");
}

#[test]
fn exact_or_refused_at_600_rad_s() {
    let exact = exudyn::samples_of("exudyn_shear_beam_600rad_s.csv");
    let p = exudyn::peak(&exact);
    let w = 600.0;
    let mut rows = Vec::new();
    // The FFR rod set, and the defaults (`auto` takes the chain on its modes).
    for model in [RodModelKind::Ffr, RodModelKind::Auto] {
        let mut s = flexrod::Scene::benchmark();
        s.rod.model = model;
        s.crank.design_speed = w;
        let built = Simulation::new(&s).unwrap().mechanism().spec.rod.clone();
        let (worst, t, message) = follow(&s, w, &exact, p);
        println!("600 rad/s, {model:?} ({:?}, {} elements): accepted steps within {:.3} % of the exact peak; refused at t = {t:.4} s: {message}", built.model, built.elements, 100.0 * worst);
        let limit = built.deflection_limit();
        assert!(worst < 1e-2, "{model:?}: {worst}");
        assert!(
            message.contains(&format!("rod.deflection_limit = {limit}")),
            "{message}"
        );
        rows.push((worst, t, limit));
    }
    MEASURED.add(
        "folding",
        format!(
            "- 600 rad/s (the exact beam buckles and folds, peak `|v_mid/L|` {p:.2}): the FFR rod's\n  \
             steps are within {} of the exact beam's peak until the step past 0.05 (t = {:.1} ms) is\n  \
             refused; with the defaults (`auto` takes the chain on its modes) within {} until the\n  \
             step past 0.25 (t = {:.1} ms) is refused; neither hands out a number beyond its range.",
            percent(rows[0].0, 2),
            1e3 * rows[0].1,
            percent(rows[1].0, 2),
            1e3 * rows[1].1
        ),
    );
}

/// E / 100 at 150 rad/s: the rod collapses (the exact beam's first maximum `|v_mid/L|` 0.35
/// at 15 ms; over two revolutions the exact beam's own refinements part, so the reference,
/// tests/data/exudyn_shear_beam_e100_150rad_s.csv, covers 0 to 16 ms, converged to 1e-4 of its
/// peak). With the defaults `auto` predicts past resonance and takes the chain on its modes:
/// every accepted step within 1 % of the exact beam's peak, the step past its limit 0.25
/// refused with the reason.
#[test]
fn exact_or_refused_at_e_over_100() {
    let exact = exudyn::samples_of("exudyn_shear_beam_e100_150rad_s.csv");
    let p = exudyn::peak(&exact);
    let mut s = flexrod::Scene::benchmark();
    s.rod.youngs_modulus /= 100.0;
    let built = Simulation::new(&s).unwrap();
    let rod = &built.mechanism().spec.rod;
    assert_eq!(rod.model, RodModelKind::ModalSegments);
    let segments = rod.elements;
    let (worst, t, message) = follow(&s, 150.0, &exact, p);
    println!(
        "E / 100, 150 rad/s, the defaults ({segments} segments): accepted steps within {:.3} % of the exact peak {p:.3}; refused at t = {t:.4} s: {message}",
        100.0 * worst
    );
    assert!(worst < 1e-2, "{worst}");
    assert!(message.contains("rod.deflection_limit = 0.25"), "{message}");
    // The exact beam passes 0.25 between 10.3 and 10.4 ms: refused there, not before.
    assert!((0.0103..=0.0105).contains(&t), "{t}");
    MEASURED.add(
        "collapse",
        format!(
            "- 150 rad/s with E / 100 (the rod collapses: the exact beam's first maximum `|v_mid/L|`\n  \
             {p:.2} at 15 ms): with the defaults `auto` takes the chain on its modes ({segments} segments);\n  \
             its steps are within {} of the exact beam's peak until the step past 0.25 (t = {:.1} ms)\n  \
             is refused.",
            percent(worst, 2),
            1e3 * t
        ),
    );
}

/// The slider-rod axial mode of the chain on its modes (rod held at B, the slider's mass `M`
/// at C) against the transcendental frequency equation of a bar with a tip mass,
/// `beta tan(beta) = m / M`, `f = beta c / (2 pi L)` (S. S. Rao, *Vibration of Continuous
/// Systems*, 2007, section 9.4): the end springs take the half segments at the pins, so the
/// chain's static axial compliance is the rod's and the frequency converges at second order.
#[test]
fn loaded_axial_mode_converges_to_the_frequency_equation() {
    let mut rows = Vec::new();
    for ratio in [0.25, 1.0, 2.0] {
        let mut errors = Vec::new();
        for segments in [16usize, 32, 64] {
            let mut s = flexrod::Scene::benchmark();
            s.rod.model = RodModelKind::ModalSegments;
            s.rod.elements = segments;
            s.rod.axial_dynamics = flexrod::rod::PhysicsSwitch::On;
            s.rod.shear_deformation = flexrod::rod::PhysicsSwitch::Off;
            let rod_mass = s.rod.density * s.rod.area * s.rod.length;
            s.slider.mass = ratio * rod_mass;
            let sim = Simulation::new(&s).unwrap();
            let omega = sim.mechanism().rod.elastic_circular_frequencies().unwrap();
            let axial = *omega.last().unwrap() / (2.0 * std::f64::consts::PI);
            // beta tan beta = m / M on (0, pi/2) by bisection.
            let (mut lo, mut hi) = (0.0f64, std::f64::consts::FRAC_PI_2);
            for _ in 0..80 {
                let mid = 0.5 * (lo + hi);
                if mid * mid.tan() < 1.0 / ratio {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let c = (s.rod.youngs_modulus / s.rod.density).sqrt();
            let exact = 0.5 * (lo + hi) * c / (2.0 * std::f64::consts::PI * s.rod.length);
            errors.push((segments, axial / exact - 1.0));
        }
        let order = (errors[1].1 / errors[2].1).abs().log2();
        println!("M / m = {ratio}: relative errors {errors:?}, order {order:.2}");
        assert!(errors[2].1.abs() < 5e-4, "{errors:?}");
        assert!(order > 1.8, "{ratio}: order {order}");
        rows.push((ratio, errors[2].1, order));
    }
    MEASURED.add(
        "axial",
        format!(
            "- The slider-rod axial mode (held at B, the slider at C, `M / m` = 0.25, 1, 2) against\n  \
             `beta tan(beta) = m / M`: at 64 segments within {}, {} and {}, order {:.2} to {:.2}.",
            percent(rows[0].1.abs(), 3),
            percent(rows[1].1.abs(), 3),
            percent(rows[2].1.abs(), 3),
            rows.iter().map(|r| r.2).fold(f64::INFINITY, f64::min),
            rows.iter().map(|r| r.2).fold(0.0, f64::max),
        ),
    );
}

/// What the model cannot take is refused by name.
#[test]
fn refusals_name_the_setting() {
    let message = |s: &Scene| match Simulation::new(s) {
        Err(e) => e.to_string(),
        Ok(_) => panic!("accepted"),
    };
    let s = modal(4, 4);
    let text = message(&s);
    assert!(text.contains("4 modes asked for, it has 3"), "{text}");
    let text = message(&modal(1, 1));
    println!("1 segment: {text}");
    assert!(!text.contains("inf"), "{text}");
}
