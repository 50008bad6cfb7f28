//! Every `rod.elements` value the FMU declares (1 to [`MAX_ELEMENTS`]), every reference
//! condition and both rod models, against the closed-form frequencies of the uniform
//! Euler-Bernoulli beam (the benchmark rod of scenes/benchmark.toml).
//!
//! Closed forms: `f_k = (beta_k L)^2 / (2 pi) sqrt(E I / (rho A L^4))` with, from the frequency
//! equations of R. D. Blevins, *Formulas for Natural Frequency and Mode Shape* (1979), table
//! 8-1:
//! - pinned-pinned (`simply_supported`): `beta_k L = k pi`;
//! - free-free (`mean_axis`: the elastic modes of the free rod): `cos b cosh b = 1`,
//!   `beta L = 4.73004, 7.85320, 10.99561`;
//! - clamped-free (`cantilever`): `cos b cosh b = -1`, `beta L = 1.87510, 4.69409, 7.85476`;
//! - `body_fixed_mid`: `u = v = slope = 0` at the middle node clamps the rod there, which
//!   leaves two clamped-free rods of length `L/2` that do not interact: the clamped-free
//!   spectrum of `L/2`, every frequency twice (`beta L = 2 x 1.87510` twice, then
//!   `2 x 4.69409`).
//!
//! FFR, consistent mass (Hermite cubic elements: the frequencies converge at fourth order in
//! the element length and, by Rayleigh-Ritz, from above). Rule: mode `k` is within 0.5 % of
//! the closed form when the mesh has at least two elements per half wave,
//! `N >= 2 beta_k L / pi` (so `N >= 2` for the first simply supported mode, 4 and 6 for the
//! next; 3, 5, 7 free-free; 2, 3, 5 clamped-free; 2, 2, 6 body-fixed); at every `N` each
//! bending frequency is finite, positive and not below the closed form (Ritz; 1e-5 for
//! round-off). FFR, lumped mass (second order): within `2 (beta_k L / (pi N))^2` at every `N`.
//! The segment chain (pinned-pinned, the mechanism's end conditions): `N - 1` bending
//! frequencies, all below the closed form and within `0.25 (k / N)^4` of it (fourth order in
//! `k / N`: 0.73 % for the one mode of 2 segments, 0.11 % for the first of 3); one segment has
//! no joint and no frequency (a rigid rod: an FMU that declares `rod.frequency[k]` refuses it at
//! initialization). Refusals (`body_fixed_mid` with an odd count) must name `rod.elements`.
//!
//! Each test prints the worst error per reference condition (`--nocapture`).

mod common;

use flexrod::beam::mesh::{least_elements, MAX_ELEMENTS};
use flexrod::beam::{MassKind, RodProperties};
use flexrod::modal::{ComponentModes, ModeSelection, ReferenceConditions, ReferenceKind};
use flexrod::rod::segments::{least_segments, SegmentRod, SEGMENT_RANGE};
use flexrod::scene::RodModelKind;
use flexrod::Simulation;
use std::f64::consts::PI;

/// `beta_k L` of the first three bending modes (Blevins 1979, table 8-1; body-fixed mid: the
/// clamped-free values of `L/2` times 2, each twice).
fn beta_l(kind: ReferenceKind) -> [f64; 3] {
    const FREE_FREE: [f64; 3] = [4.730_040_745, 7.853_204_624, 10.995_607_838];
    const CLAMPED_FREE: [f64; 3] = [1.875_104_069, 4.694_091_133, 7.854_757_438];
    match kind {
        ReferenceKind::SimplySupported => [PI, 2.0 * PI, 3.0 * PI],
        ReferenceKind::MeanAxis => FREE_FREE,
        ReferenceKind::Cantilever => CLAMPED_FREE,
        ReferenceKind::BodyFixedMid => [
            2.0 * CLAMPED_FREE[0],
            2.0 * CLAMPED_FREE[0],
            2.0 * CLAMPED_FREE[1],
        ],
    }
}

fn rod() -> RodProperties {
    RodProperties::cdi_benchmark()
}

/// `f = (beta L)^2 / (2 pi) sqrt(E I / (rho A L^4))`, Hz.
fn closed_form(p: &RodProperties, beta_l: f64) -> f64 {
    let scale = (p.youngs_modulus * p.area_moment / (p.density * p.area * p.length.powi(4))).sqrt();
    beta_l * beta_l * scale / (2.0 * PI)
}

/// The bending frequencies of the FFR rod (all modes, the axial ones left out), Hz, or the
/// refusal's message.
fn ffr_bending_hz(kind: ReferenceKind, n: usize, mass: MassKind) -> Result<Vec<f64>, String> {
    let reference = ReferenceConditions::from_kind(kind, n).map_err(|e| e.to_string())?;
    let modes = ComponentModes::new(rod(), n, reference, mass, &ModeSelection::Count(0))
        .map_err(|e| e.to_string())?;
    for &f in &modes.all_frequencies_hz {
        assert!(
            f.is_finite() && f > 0.0,
            "{kind:?} N = {n}: frequency {f} reported as valid"
        );
    }
    Ok((0..modes.all_frequencies_hz.len())
        .filter(|&k| !modes.is_axial(k))
        .map(|k| modes.all_frequencies_hz[k])
        .collect())
}

/// Every element count for one reference condition, consistent mass; returns the worst
/// relative error among the modes the rule checks, with its mode and count.
fn ffr_consistent(kind: ReferenceKind) -> (f64, usize, usize) {
    let p = rod();
    let beta = beta_l(kind);
    let exact = beta.map(|b| closed_form(&p, b));
    let mut worst = (0.0, 0, 0);
    for n in 1..=MAX_ELEMENTS {
        let bending = match ffr_bending_hz(kind, n, MassKind::Consistent) {
            Ok(f) => f,
            Err(message) => {
                assert!(
                    kind == ReferenceKind::BodyFixedMid && n % 2 == 1,
                    "{kind:?} N = {n} refused: {message}"
                );
                assert!(message.contains("rod.elements"), "{message}");
                continue;
            }
        };
        for (k, (&f, &e)) in bending.iter().zip(&exact).enumerate() {
            let rel = f / e - 1.0;
            assert!(
                rel > -1e-5,
                "{kind:?} N = {n} mode {}: {f} Hz below the closed form {e} Hz ({rel:e})",
                k + 1
            );
            if n as f64 >= 2.0 * beta[k] / PI {
                assert!(
                    rel < 5e-3,
                    "{kind:?} N = {n} mode {}: {f} Hz against {e} Hz ({rel:e})",
                    k + 1
                );
                if rel.abs() > worst.0 {
                    worst = (rel.abs(), k + 1, n);
                }
            }
        }
        // At least the first three bending modes exist from 2 elements on.
        assert!(n < 2 || bending.len() >= 3, "{kind:?} N = {n}: {bending:?}");
    }
    println!(
        "FFR consistent {:>16}: worst error {:.2e} (mode {}, N = {}) over N = 1..={MAX_ELEMENTS}, first three bending modes where N >= 2 beta_k L / pi",
        kind.name(),
        worst.0,
        worst.1,
        worst.2
    );
    worst
}

#[test]
fn ffr_simply_supported_every_count() {
    ffr_consistent(ReferenceKind::SimplySupported);
}

#[test]
fn ffr_mean_axis_every_count() {
    ffr_consistent(ReferenceKind::MeanAxis);
}

#[test]
fn ffr_body_fixed_mid_every_count() {
    ffr_consistent(ReferenceKind::BodyFixedMid);
}

#[test]
fn ffr_cantilever_every_count() {
    ffr_consistent(ReferenceKind::Cantilever);
}

/// Lumped mass: second order, `|f / f_exact - 1| <= 2 (beta_k L / (pi N))^2` at every count.
#[test]
fn ffr_lumped_mass_every_count() {
    let p = rod();
    for kind in ReferenceKind::ALL {
        let beta = beta_l(kind);
        let exact = beta.map(|b| closed_form(&p, b));
        let mut worst: f64 = 0.0;
        for n in 2..=MAX_ELEMENTS {
            if kind == ReferenceKind::BodyFixedMid && n % 2 == 1 {
                continue;
            }
            let bending = ffr_bending_hz(kind, n, MassKind::Lumped).unwrap();
            for (k, (&f, &e)) in bending.iter().zip(&exact).enumerate() {
                let rel = (f / e - 1.0).abs();
                let bound = 2.0 * (beta[k] / (PI * n as f64)).powi(2);
                assert!(
                    rel <= bound,
                    "lumped {kind:?} N = {n} mode {}: {f} Hz against {e} Hz ({rel:e} > {bound:e})",
                    k + 1
                );
                worst = worst.max(rel / bound);
            }
        }
        println!(
            "FFR lumped {:>16}: worst error / 2 (beta L / (pi N))^2 = {worst:.3}",
            kind.name()
        );
    }
}

/// The frequencies the FMU reports (`Simulation::frequencies_hz`) on fine meshes (86 to 128
/// elements: a divide-and-conquer eigensolver loses the lowest modes there, see
/// `flexrod::modal::eigen`), for every reference condition.
#[test]
fn simulation_reports_the_closed_form_at_fine_meshes() {
    let p = rod();
    for kind in ReferenceKind::ALL {
        let first = closed_form(&p, beta_l(kind)[0]);
        for n in [86, 100, 104, 110, 120, 127, 128] {
            let mut scene = common::euler_bernoulli_benchmark();
            scene.rod.reference = kind;
            scene.rod.elements = n;
            if kind == ReferenceKind::BodyFixedMid {
                // Every frequency twice: three modes would keep half of the second pair.
                scene.rod.modes = 4;
            }
            match Simulation::new(&scene) {
                Ok(sim) => {
                    let f = sim.frequencies_hz()[0];
                    let rel = f / first - 1.0;
                    assert!(
                        (-1e-5..1e-4).contains(&rel),
                        "{kind:?} N = {n}: first frequency {f} Hz against {first} Hz"
                    );
                }
                Err(e) => {
                    assert!(
                        kind == ReferenceKind::BodyFixedMid && n % 2 == 1,
                        "{kind:?} N = {n}: {e}"
                    );
                    assert!(e.to_string().contains("rod.elements"), "{e}");
                }
            }
        }
    }
}

/// Physically soft but in range (E 1e5 Pa, I 1e-22 m^4): small positive frequencies at the
/// closed form, never 0 Hz, at 2 and 128 elements and every reference condition.
#[test]
fn soft_and_slender_rods_give_small_positive_frequencies() {
    for (e, i) in [(1e5, 1e-22), (1e5, 7.981e-11), (2.068e11, 1e-22)] {
        let p = RodProperties {
            youngs_modulus: e,
            area_moment: i,
            ..rod()
        };
        for kind in ReferenceKind::ALL {
            let exact = closed_form(&p, beta_l(kind)[0]);
            for n in [2, 8, 128] {
                let reference = ReferenceConditions::from_kind(kind, n).unwrap();
                let modes = ComponentModes::new(
                    p,
                    n,
                    reference,
                    MassKind::Consistent,
                    &ModeSelection::Count(0),
                )
                .unwrap();
                let f = modes.all_frequencies_hz[0];
                let rel = f / exact - 1.0;
                assert!(
                    (-1e-5..5e-3).contains(&rel),
                    "E {e} I {i} {kind:?} N = {n}: {f} Hz against {exact} Hz"
                );
            }
        }
    }
}

/// The segment chain, pinned-pinned: every count of its range, with and without axial
/// springs.
#[test]
fn segment_chain_every_count() {
    let p = rod();
    let exact: Vec<f64> = (1..=3).map(|k| closed_form(&p, k as f64 * PI)).collect();
    let (lo, hi) = SEGMENT_RANGE;
    let mut worst: f64 = 0.0;
    for axial in [false, true] {
        for n in lo..=hi {
            let chain = SegmentRod::new(p, n, 0.0, axial).unwrap();
            let bending = chain.bending_frequencies_hz();
            assert_eq!(bending.len(), n - 1, "N = {n}");
            for &f in chain
                .bending_frequencies_hz()
                .iter()
                .chain(chain.axial_frequencies_hz())
            {
                assert!(f.is_finite() && f > 0.0, "N = {n}: {f} Hz");
            }
            for (k, (&f, &e)) in bending.iter().zip(&exact).enumerate() {
                let rel = f / e - 1.0;
                let bound = 0.25 * ((k + 1) as f64 / n as f64).powi(4);
                assert!(
                    rel < 0.0 && -rel <= bound,
                    "segments N = {n} mode {}: {f} Hz against {e} Hz ({rel:e}, bound {bound:e})",
                    k + 1
                );
                worst = worst.max(-rel / bound);
            }
        }
    }
    // One segment: a rigid rod, no frequency; the model says so through an empty list.
    let mut scene = common::euler_bernoulli_benchmark();
    scene.rod.model = RodModelKind::Segments;
    scene.rod.elements = 1;
    assert!(Simulation::new(&scene).unwrap().frequencies_hz().is_empty());
    println!(
        "segments N = {lo}..={hi}: worst error / 0.25 (k/N)^4 = {worst:.3} (first three bending modes)"
    );
}

/// `body_fixed_mid` has every frequency twice (the two halves, clamped at the midpoint, vibrate
/// alike): a mode count that keeps half of a pair keeps an arbitrary shape and is refused,
/// naming `rod.modes`; whole pairs give the closed form.
#[test]
fn body_fixed_mid_keeps_pairs_whole() {
    let p = rod();
    let exact = closed_form(&p, beta_l(ReferenceKind::BodyFixedMid)[0]);
    for n in [2, 8, 64, 128] {
        for modes in 1..=4 {
            let mut scene = common::euler_bernoulli_benchmark();
            scene.rod.reference = ReferenceKind::BodyFixedMid;
            scene.rod.elements = n;
            scene.rod.modes = modes;
            match Simulation::new(&scene) {
                Ok(sim) => {
                    assert!(modes % 2 == 0, "N = {n}, {modes} modes accepted");
                    let f = sim.frequencies_hz();
                    assert!((f[0] / exact - 1.0).abs() < 5e-3 && (f[1] / f[0] - 1.0).abs() < 1e-6);
                }
                Err(e) => {
                    let text = e.to_string();
                    assert!(modes % 2 == 1, "N = {n}, {modes} modes: {text}");
                    assert!(
                        text.contains("rod.modes") && text.contains("equal frequency"),
                        "{text}"
                    );
                }
            }
        }
    }
}

/// The least counts that leave `K` natural frequencies (what an FMU declaring
/// `rod.frequency[1..K]` needs): `least_elements` for the FFR rod under every reference
/// condition, `least_segments` for the chain, against the models' own lists.
#[test]
fn least_counts_leave_the_declared_frequencies() {
    let p = rod();
    for k in 0..=12 {
        let n = least_elements(k);
        for kind in ReferenceKind::ALL {
            let count = |n: usize| {
                ReferenceConditions::from_kind(kind, n)
                    .and_then(|r| {
                        ComponentModes::new(p, n, r, MassKind::Consistent, &ModeSelection::Count(0))
                    })
                    .map(|m| m.all_frequencies_hz.len())
            };
            if let Ok(c) = count(n) {
                assert!(c >= k, "{kind:?} K = {k}: {n} elements leave {c}");
            }
            if n > 1 {
                if let Ok(c) = count(n - 1) {
                    assert!(c < k, "{kind:?} K = {k}: {} elements leave {c}", n - 1);
                }
            }
        }
        for axial in [false, true] {
            let n = least_segments(k, axial);
            let count = |n: usize| {
                let chain = SegmentRod::new(p, n, 0.0, axial).unwrap();
                chain.bending_frequencies_hz().len() + chain.axial_frequencies_hz().len()
            };
            assert!(count(n) >= k, "segments K = {k}: {n} leave {}", count(n));
            assert!(
                n == 1 || count(n - 1) < k,
                "segments K = {k}: {} suffice",
                n - 1
            );
        }
    }
    assert_eq!(
        (
            least_elements(6),
            least_segments(6, false),
            least_segments(6, true)
        ),
        (2, 7, 5)
    );
}
