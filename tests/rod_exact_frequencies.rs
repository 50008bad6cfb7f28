//! Rods beyond the uniform Euler-Bernoulli bar against exact frequencies (docs/real-rods.md):
//!
//! - a stepped rod, pinned-pinned: transfer-matrix method with the closed-form field transfer
//!   matrix of a uniform Euler-Bernoulli segment (Krylov-Duncan functions; e.g. Pestel and
//!   Leckie, *Matrix Methods in Elastomechanics*, 1963), roots of the boundary determinant
//!   bracketed by a scan and bisected to 1e-12;
//! - a stubby pinned-pinned Timoshenko beam: for simply supported ends the modes are
//!   `sin(n pi x / L)` and `w^2` solves the quadratic
//!   `rho A rho I w^4 - (rho I G A_s k^2 + rho A E I k^2 + rho A G A_s) w^2 + G A_s E I k^4 = 0`,
//!   `k = n pi / L` (Han, Benaroya and Wei 1999, "Dynamics of transversely vibrating beams using
//!   four engineering theories", J. Sound Vib. 225(5), section 6, simply supported Timoshenko
//!   beam; the lower root is the bending branch);
//! - a cantilever with a tip mass `M` and tip rotary inertia `J`: with `beta^4 = rho A w^2 L^4 /
//!   (E I)`, `alpha = M / (rho A L)`, `eta = J / (rho A L^3)`, the Euler-Bernoulli frequency
//!   equation (from `w'' = 0`... boundary conditions `E I w''(L) = J w^2 w'(L)`,
//!   `E I w'''(L) = -M w^2 w(L)`; e.g. Blevins, *Formulas for Natural Frequency and Mode Shape*,
//!   table 8-8; Laura, Pombo and Susemihl 1974, J. Sound Vib. 37)
//!   `1 + cos b cosh b + alpha b (cos b sinh b - sin b cosh b)
//!    - eta b^3 (cosh b sin b + sinh b cos b) + alpha eta b^4 (1 - cos b cosh b) = 0`;
//! - the uniform rod through the station-table path against the closed-form path (1e-12);
//! - statics of the stubby Timoshenko rod under a triangular load against the closed form
//!   (nodal deflections, and the curvature with the element's interior part).
//!
//! Each case prints its verification row (run with `--nocapture`).

use flexrod::beam::{
    EndBody, MassKind, RodDefinition, RodProperties, SectionStation, SectionTable,
};
use flexrod::modal::{ComponentModes, ModeSelection, ReferenceConditions, ShapeIntegrals};
use flexrod::rod::segments::SegmentRod;
use std::f64::consts::PI;

fn station(position: f64, area: f64, area_moment: f64) -> SectionStation {
    SectionStation {
        position,
        area,
        area_moment,
        shear_area: None,
        fibre_distance: None,
    }
}

/// All modes of a rod; the transverse (bending) frequencies in Hz, ascending: modes whose
/// axial nodal components vanish (the straight beam's axial and transverse motions decouple).
fn bending_hz(def: RodDefinition, n: usize, reference: ReferenceConditions) -> Vec<f64> {
    let modes = ComponentModes::from_definition(
        def,
        n,
        reference,
        MassKind::Consistent,
        &ModeSelection::Cutoff {
            max_hz: f64::INFINITY,
        },
    )
    .unwrap();
    let shapes = &modes.shapes;
    (0..modes.n_modes())
        .filter(|&j| {
            let (mut u, mut rest) = (0.0, 0.0);
            for i in 0..shapes.nrows() {
                let x = shapes[(i, j)] * shapes[(i, j)];
                if modes.mesh.is_axial_coordinate(i) {
                    u += x;
                } else {
                    rest += x;
                }
            }
            u < 1e-6 * rest
        })
        .map(|j| modes.omega2[j].sqrt() / (2.0 * PI))
        .collect()
}

/// The computed frequency nearest to `exact`.
fn nearest(computed: &[f64], exact: f64) -> f64 {
    computed
        .iter()
        .copied()
        .min_by(|a, b| (a - exact).abs().total_cmp(&(b - exact).abs()))
        .unwrap()
}

fn report(case: &str, mesh: &str, exact: &[f64], computed: &[f64], tol: f64) {
    for (k, (&e, &c)) in exact.iter().zip(computed).enumerate() {
        let rel = (c - e).abs() / e;
        println!(
            "| {case}, mode {} | {e:.6} | {c:.6} | {rel:.1e} | {mesh} |",
            k + 1
        );
        assert!(
            rel < tol,
            "{case} mode {}: {c} vs exact {e} ({rel:e})",
            k + 1
        );
    }
}

/// Root of `f` in `[a, b]` (a sign change) by bisection to `1e-12` relative.
fn bisect<F: Fn(f64) -> f64>(f: &F, mut a: f64, mut b: f64) -> f64 {
    let mut fa = f(a);
    while (b - a) > 1e-12 * b.abs() {
        let m = 0.5 * (a + b);
        let fm = f(m);
        if (fm < 0.0) == (fa < 0.0) {
            a = m;
            fa = fm;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

/// The first `count` roots of `f` above `start`, scanning with step `step`.
fn roots<F: Fn(f64) -> f64>(f: F, start: f64, step: f64, count: usize) -> Vec<f64> {
    let mut out = Vec::new();
    let mut x = start;
    let mut fx = f(x);
    while out.len() < count {
        let y = x + step;
        let fy = f(y);
        if (fx < 0.0) != (fy < 0.0) {
            out.push(bisect(&f, x, y));
        }
        x = y;
        fx = fy;
    }
    out
}

type M4 = [[f64; 4]; 4];

fn mul(a: &M4, b: &M4) -> M4 {
    let mut c = [[0.0; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            for (k, bk) in b.iter().enumerate() {
                c[i][j] += a[i][k] * bk[j];
            }
        }
    }
    c
}

/// Field transfer matrix of a uniform Euler-Bernoulli segment (length `l`, `E I`, `rho A`) at
/// circular frequency `w`, on the state `[w, w', M = E I w'', V = E I w''']`.
fn field(l: f64, ei: f64, rho_a: f64, w: f64) -> M4 {
    let b = (rho_a * w * w / ei).powf(0.25);
    let x = b * l;
    let (ch, sh, c, s) = (x.cosh(), x.sinh(), x.cos(), x.sin());
    let (ks, kt, ku, kv) = (
        0.5 * (ch + c),
        0.5 * (sh + s),
        0.5 * (ch - c),
        0.5 * (sh - s),
    );
    // On [w, w', w'', w''']: Krylov-Duncan functions.
    let f = [
        [ks, kt / b, ku / (b * b), kv / (b * b * b)],
        [b * kv, ks, kt / b, ku / (b * b)],
        [b * b * ku, b * kv, ks, kt / b],
        [b * b * b * kt, b * b * ku, b * kv, ks],
    ];
    // To [w, w', E I w'', E I w''']: D F D^-1, D = diag(1, 1, EI, EI).
    let d = [1.0, 1.0, ei, ei];
    let mut t = [[0.0; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            t[i][j] = d[i] * f[i][j] / d[j];
        }
    }
    t
}

/// Stepped rod: the section (A1, I1) on [0, L/2], (A2, I2) on [L/2, L]; pinned-pinned.
#[test]
fn stepped_rod_pinned_pinned_against_transfer_matrix() {
    let (l, e, rho) = (1.0, 2.1e11, 7800.0);
    let (a1, i1, a2, i2) = (6e-4, 2.0e-8, 3e-4, 0.6e-8);
    // Pinned at both ends: w = M = 0; the unknowns at B are (w', V).
    let det = |w: f64| {
        let t = mul(
            &field(0.5 * l, e * i2, rho * a2, w),
            &field(0.5 * l, e * i1, rho * a1, w),
        );
        t[0][1] * t[2][3] - t[0][3] * t[2][1]
    };
    let w_ref = (PI / l).powi(2) * (e * i2 / (rho * a1)).sqrt();
    let exact: Vec<f64> = roots(det, 0.05 * w_ref, 0.01 * w_ref, 3)
        .iter()
        .map(|w| w / (2.0 * PI))
        .collect();
    let props = properties(l, e, rho, a1, i1);
    let n = 32;
    let table = SectionTable::new(
        l,
        &[
            station(0.0, a1, i1),
            station(0.5 * l, a1, i1),
            station(0.5 * l, a2, i2),
            station(l, a2, i2),
        ],
    )
    .unwrap();
    let def = RodDefinition::with_table(props, table);
    let fe = bending_hz(def, n, ReferenceConditions::SimplySupported);
    let computed: Vec<f64> = exact.iter().map(|&x| nearest(&fe, x)).collect();
    // The three lowest bending frequencies are the three lowest computed ones.
    assert_eq!(&computed[..], &fe[..3]);
    report(
        "stepped rod, pinned-pinned",
        "32 EB elements",
        &exact,
        &computed,
        1e-4,
    );
}

/// Uniform rod properties: length m, Young's modulus Pa, density kg/m^3, area m^2, area
/// moment m^4.
fn properties(
    length: f64,
    youngs_modulus: f64,
    density: f64,
    area: f64,
    area_moment: f64,
) -> RodProperties {
    RodProperties {
        length,
        youngs_modulus,
        density,
        area,
        area_moment,
    }
}

/// The stubby rod of the Timoshenko checks (L / h = 5, steel): `(L, E, rho, A, I, G, A_s)`
/// and its definition with a section table and the shear modulus.
fn stubby_rod() -> ([f64; 7], RodDefinition) {
    let (l, e, rho) = (0.1, 2.1e11, 7800.0);
    let (b, h) = (0.01, 0.02);
    let (a, i) = (b * h, b * h * h * h / 12.0);
    let (g, a_s) = (e / 2.6, a / 1.2);
    let props = properties(l, e, rho, a, i);
    let mut def = RodDefinition::uniform(props);
    def.table = Some(SectionTable::uniform(l, a, i));
    def.shear_modulus = Some(g);
    ([l, e, rho, a, i, g, a_s], def)
}

/// A stubby rod, L / h = 5, pinned-pinned, Timoshenko: several percent below
/// Euler-Bernoulli. The hierarchical element (v in P3, psi in P2: the IIE's nodal functions
/// plus three integrated-Legendre interior functions per element, docs/real-rods.md) has a
/// linear shear strain and curvature per element, and its frequencies converge at fourth order
/// (observed 3.96 to 4.02): 1.5e-5, 1.9e-4, 7.7e-4 at 8 elements; 9.4e-7, 1.2e-5, 4.9e-5 at
/// 16; 5.9e-8, 7.7e-7, 3.1e-6 at 32. The 1e-4 target for all three modes holds from 16
/// elements. (The IIE alone, shear strain constant per element, converged at second order:
/// 3.6e-5, 4.2e-4, 1.5e-3 at 32 elements, 1e-4 for all three only at 128.)
#[test]
fn stubby_timoshenko_pinned_pinned_against_closed_form() {
    let ([l, e, rho, a, i, g, a_s], def) = stubby_rod();
    let props = def.properties;
    let exact: Vec<f64> = (1..=3)
        .map(|n| {
            let k = n as f64 * PI / l;
            let c2 = rho * a * rho * i;
            let c1 = rho * i * g * a_s * k * k + rho * a * e * i * k * k + rho * a * g * a_s;
            let c0 = g * a_s * e * i * k.powi(4);
            // Lower root of c2 x^2 - c1 x + c0 = 0, in the cancellation-free form.
            let x = 2.0 * c0 / (c1 + (c1 * c1 - 4.0 * c2 * c0).sqrt());
            x.sqrt() / (2.0 * PI)
        })
        .collect();
    let euler: Vec<f64> = (1..=3)
        .map(|n| {
            let k = n as f64 * PI / l;
            k * k * (e * i / (rho * a)).sqrt() / (2.0 * PI)
        })
        .collect();
    for (t, eb) in exact.iter().zip(&euler) {
        println!("Timoshenko / Euler-Bernoulli = {:.4}", t / eb);
    }
    assert!(
        exact[0] / euler[0] < 0.97,
        "first mode drops by several percent"
    );
    let errors = |n: usize| -> Vec<f64> {
        let fe = bending_hz(def.clone(), n, ReferenceConditions::SimplySupported);
        exact.iter().map(|&x| (nearest(&fe, x) - x) / x).collect()
    };
    let (e8, e16, e32) = (errors(8), errors(16), errors(32));
    for k in 0..3 {
        let order = [(e8[k] / e16[k]).log2(), (e16[k] / e32[k]).log2()];
        println!(
            "Timoshenko mode {}: errors at 8/16/32 elements {:.2e} {:.2e} {:.2e}, order {:.2} {:.2}",
            k + 1,
            e8[k],
            e16[k],
            e32[k],
            order[0],
            order[1]
        );
        // Fourth order, from above (consistent mass, conforming element).
        assert!(
            e32[k] > 0.0 && order.iter().all(|o| (3.8..4.2).contains(o)),
            "mode {}: order {order:?}",
            k + 1
        );
        assert!(e16[k] < 1e-4, "mode {}: {} at 16 elements", k + 1, e16[k]);
    }
    let n = 16;
    let fe = bending_hz(def, n, ReferenceConditions::SimplySupported);
    let computed: Vec<f64> = exact.iter().map(|&x| nearest(&fe, x)).collect();
    report(
        "Timoshenko, L/h = 5, pinned-pinned",
        "16 elements (v P3, psi P2)",
        &exact,
        &computed,
        1e-4,
    );
    let n = 32;
    // Euler-Bernoulli of the same rod: the closed form, not the Timoshenko values.
    let eb = bending_hz(
        RodDefinition::uniform(props),
        n,
        ReferenceConditions::SimplySupported,
    );
    report(
        "Euler-Bernoulli, same rod, pinned-pinned",
        "32 EB elements",
        &euler,
        &eb[..3],
        1e-4,
    );
}

/// G -> infinity: the shear-deformable rod's frequencies tend to those of the Rayleigh beam
/// (Euler-Bernoulli plus rotary inertia), `w^2 = E I k^4 / (rho A + rho I k^2)`.
#[test]
fn timoshenko_with_rigid_shear_is_the_rayleigh_beam() {
    let (l, e, rho) = (0.1, 2.1e11, 7800.0);
    let (a, i) = (2e-4, 6.0e-9);
    let props = properties(l, e, rho, a, i);
    let mut def = RodDefinition::uniform(props);
    def.shear_modulus = Some(e * 1e9);
    let fe = bending_hz(def, 32, ReferenceConditions::SimplySupported);
    let exact: Vec<f64> = (1..=3)
        .map(|n| {
            let k = n as f64 * PI / l;
            (e * i * k.powi(4) / (rho * a + rho * i * k * k)).sqrt() / (2.0 * PI)
        })
        .collect();
    let computed: Vec<f64> = exact.iter().map(|&x| nearest(&fe, x)).collect();
    report(
        "Rayleigh limit (G = 1e9 E), pinned-pinned",
        "32 elements (v P3, psi P2)",
        &exact,
        &computed,
        1e-4,
    );
}

/// Cantilever with tip mass and tip rotary inertia (the small end at C), clamped at B.
#[test]
fn cantilever_with_tip_mass_and_inertia_against_frequency_equation() {
    let props = RodProperties::cdi_benchmark();
    let (l, rho_a, ei) = (
        props.length,
        props.mass_per_length(),
        props.bending_rigidity(),
    );
    let (alpha, eta) = (0.5, 0.02);
    let tip = EndBody {
        mass: alpha * rho_a * l,
        inertia: eta * rho_a * l * l * l,
    };
    let eq = |b: f64| {
        let (c, s, ch, sh) = (b.cos(), b.sin(), b.cosh(), b.sinh());
        1.0 + c * ch + alpha * b * (c * sh - s * ch) - eta * b.powi(3) * (ch * s + sh * c)
            + alpha * eta * b.powi(4) * (1.0 - c * ch)
    };
    // Limits of the equation: alpha = eta = 0 gives the cantilever root 1.8751.
    let exact: Vec<f64> = roots(eq, 0.1, 1e-3, 3)
        .iter()
        .map(|b| b * b / (l * l) * (ei / rho_a).sqrt() / (2.0 * PI))
        .collect();
    let mut def = RodDefinition::uniform(props);
    def.small_end = tip;
    let n = 32;
    let fe = bending_hz(def, n, ReferenceConditions::BodyFixed { node: 0 });
    let computed: Vec<f64> = exact.iter().map(|&x| nearest(&fe, x)).collect();
    assert_eq!(&computed[..], &fe[..3]);
    report(
        "cantilever, tip mass 0.5 m_rod, tip inertia 0.02 m_rod L^2",
        "32 EB elements",
        &exact,
        &computed,
        1e-4,
    );
}

/// A pinned-pinned rod with end bodies (the mechanism's end conditions): point masses and
/// rotary inertias `J_B`, `J_C` at both pins. The pins hold the ends transversely, so the masses
/// do not enter the bending modes; the inertias turn with the end slopes. Hamilton's principle
/// gives the moment conditions `E I w''(0) = -J_B w^2 w'(0)`, `E I w''(L) = J_C w^2 w'(L)`
/// (and `w = 0` at both ends); with the field transfer matrix `T` of the uniform segment on
/// `[w, w', E I w'', E I w''']` the unknowns at B are `(w'(0), V(0))`, and the frequency equation
/// is the 2 x 2 determinant of the two conditions at C. Limits: `J = 0` gives the pinned-pinned
/// rod (checked: `(n pi / L)^2 sqrt(E I / rho A)`).
#[test]
fn pinned_rod_with_end_bodies_against_frequency_equation() {
    let props = RodProperties::cdi_benchmark();
    let (l, rho_a, ei) = (
        props.length,
        props.mass_per_length(),
        props.bending_rigidity(),
    );
    let m_rod = rho_a * l;
    let (j_b, j_c) = (0.05 * m_rod * l * l, 0.01 * m_rod * l * l);
    let det = |jb: f64, jc: f64| {
        move |w: f64| {
            let t = field(l, ei, rho_a, w);
            let w2 = w * w;
            let a11 = t[0][1] - jb * w2 * t[0][2];
            let a12 = t[0][3];
            let a21 = (t[2][1] - jb * w2 * t[2][2]) - jc * w2 * (t[1][1] - jb * w2 * t[1][2]);
            let a22 = t[2][3] - jc * w2 * t[1][3];
            a11 * a22 - a12 * a21
        }
    };
    let w1 = (PI / l).powi(2) * (ei / rho_a).sqrt();
    // The limit J = 0: the pinned-pinned rod.
    let plain = roots(det(0.0, 0.0), 0.05 * w1, 0.01 * w1, 3);
    for (k, w) in plain.iter().enumerate() {
        let n = (k + 1) as f64;
        assert!((w / (n * n * w1) - 1.0).abs() < 1e-9, "mode {}: {w}", k + 1);
    }
    let exact: Vec<f64> = roots(det(j_b, j_c), 0.05 * w1, 0.01 * w1, 3)
        .iter()
        .map(|w| w / (2.0 * PI))
        .collect();
    let mut def = RodDefinition::uniform(props);
    def.big_end = EndBody {
        mass: 0.4 * m_rod,
        inertia: j_b,
    };
    def.small_end = EndBody {
        mass: 0.2 * m_rod,
        inertia: j_c,
    };
    let n = 32;
    let fe = bending_hz(def.clone(), n, ReferenceConditions::SimplySupported);
    let computed: Vec<f64> = exact.iter().map(|&x| nearest(&fe, x)).collect();
    assert_eq!(&computed[..], &fe[..3]);
    // The segment chain (end bodies at the pins, their inertias on rotations of their own):
    // second order in the segment length.
    let mut previous: Option<Vec<f64>> = None;
    for n_seg in [32, 64, 128] {
        let chain = SegmentRod::from_definition(&def, n_seg, 0.0, false).unwrap();
        let f = chain.bending_frequencies_hz();
        let err: Vec<f64> = (0..3).map(|k| (f[k] - exact[k]) / exact[k]).collect();
        println!("segment chain N = {n_seg}: relative errors {err:?}");
        if let Some(p) = &previous {
            for k in 0..3 {
                let order = (p[k] / err[k]).abs().log2();
                assert!(
                    (1.8..2.2).contains(&order),
                    "chain mode {}: order {order}",
                    k + 1
                );
            }
        }
        if n_seg == 128 {
            assert!(err.iter().all(|e| e.abs() < 2e-4), "{err:?}");
        }
        previous = Some(err);
    }
    // The inertias lower every frequency (more kinetic energy, Rayleigh).
    for (k, f) in exact.iter().enumerate() {
        assert!(*f < plain[k] / (2.0 * PI));
    }
    report(
        "pinned-pinned, end masses 0.4 / 0.2 m_rod, end inertias 0.05 / 0.01 m_rod L^2",
        "32 EB elements",
        &exact,
        &computed,
        1e-4,
    );
}

/// The uniform rod through the station table (quadrature path) gives the closed-form path's
/// frequencies; FFR and segment chain.
#[test]
fn uniform_rod_through_the_table_equals_the_closed_form_path() {
    let props = RodProperties::cdi_benchmark();
    let table = SectionTable::new(
        props.length,
        &[
            station(0.0, props.area, props.area_moment),
            station(props.length, props.area, props.area_moment),
        ],
    )
    .unwrap();
    let def = RodDefinition::with_table(props, table);
    assert!(!def.is_plain());
    for reference in [
        ReferenceConditions::SimplySupported,
        ReferenceConditions::MeanAxis,
        ReferenceConditions::BodyFixed { node: 4 },
    ] {
        let all = ModeSelection::Cutoff {
            max_hz: f64::INFINITY,
        };
        let old =
            ComponentModes::new(props, 8, reference.clone(), MassKind::Consistent, &all).unwrap();
        let new = ComponentModes::from_definition(
            def.clone(),
            8,
            reference.clone(),
            MassKind::Consistent,
            &all,
        )
        .unwrap();
        // The element matrices agree to a few ulps; an eigenvalue's relative sensitivity to
        // that is about eps (w_max / w)^2 (the axial stiffness E A / l dominates the norm of
        // K): (w_max / w_1)^2 eps ~ 5e-11 on the first bending mode. Bound 1e-10: 1e-12 is
        // beyond the round-off of two different but equal formulas for the lowest mode.
        let diffs: Vec<f64> = old
            .all_frequencies_hz
            .iter()
            .zip(&new.all_frequencies_hz)
            .map(|(a, b)| (a - b).abs() / a)
            .collect();
        let low = diffs[..12].iter().cloned().fold(0.0, f64::max);
        let all = diffs.iter().cloned().fold(0.0, f64::max);
        println!("uniform via table, {reference:?}: largest relative difference {low:.1e} (lowest 12), {all:.1e} (all {})", diffs.len());
        assert!(low < 1e-10 && all < 1e-10, "{reference:?}: {low:e} {all:e}");
        // Shape integrals agree too, and M_ff is the identity.
        let (a, b) = (ShapeIntegrals::new(&old), ShapeIntegrals::new(&new));
        assert!((a.mass - b.mass).abs() < 1e-15 * a.mass);
        assert!((a.i3 - b.i3).abs() < 1e-12 * a.i3);
        let n = b.m_ff.nrows();
        let eye = nalgebra::DMatrix::<f64>::identity(n, n);
        assert!((&b.m_ff - eye).abs().max() < 1e-10);
    }
    let old = SegmentRod::new(props, 16, 0.0, true).unwrap();
    let new = SegmentRod::from_definition(&def, 16, 0.0, true).unwrap();
    use flexrod::rod::RodBody;
    let worst = old
        .frequencies_hz()
        .iter()
        .zip(new.frequencies_hz())
        .map(|(a, b)| (a - b).abs() / a)
        .fold(0.0, f64::max);
    println!("uniform via table, segment chain: largest relative difference {worst:.1e}");
    // Joint springs from the ln form of int ds / (E I) and quadrature masses: round-off.
    assert!(worst < 1e-10, "{worst:e}");
}

/// End bodies and a tapered section: masses, centre of mass, momentum-free mean-axis modes,
/// unit modal mass, and the segment chain's mass properties.
#[test]
fn end_bodies_and_taper_in_the_shape_integrals_and_the_chain() {
    let props = RodProperties::cdi_benchmark();
    let l = props.length;
    let table = SectionTable::new(
        l,
        &[
            station(0.0, 2.0 * props.area, 3.0 * props.area_moment),
            station(l, props.area, props.area_moment),
        ],
    )
    .unwrap();
    let mut def = RodDefinition::with_table(props, table);
    def.big_end = EndBody {
        mass: 0.03,
        inertia: 2e-6,
    };
    def.small_end = EndBody {
        mass: 0.01,
        inertia: 5e-7,
    };
    def.shear_modulus = Some(props.youngs_modulus / 2.6);
    // int rho A = rho A0 L (2 + 1) / 2.
    let rod_mass = props.density * props.area * l * 1.5;
    assert!((def.rod_mass() - rod_mass).abs() < 1e-14);
    assert!((def.total_mass() - rod_mass - 0.04).abs() < 1e-14);
    let modes = ComponentModes::from_definition(
        def.clone(),
        8,
        ReferenceConditions::MeanAxis,
        MassKind::Consistent,
        &ModeSelection::Count(6),
    )
    .unwrap();
    let ig = ShapeIntegrals::new(&modes);
    assert!((ig.mass - def.total_mass()).abs() < 1e-15);
    // The frame is at the centre of mass: I1 = 0; mean-axis modes carry no momentum.
    assert!(ig.i1.norm() < 1e-15, "{}", ig.i1);
    // With rotary inertia the rigid rotation is orthogonal to the modes through
    // `I_rot - I5` (the M_phip coupling at p = 0), not through I5 alone.
    assert!(ig.i2.abs().max() < 1e-12, "{}", ig.i2);
    assert!(
        (&ig.i_rot - &ig.i5).abs().max() < 1e-12,
        "{}",
        &ig.i_rot - &ig.i5
    );
    let eye = nalgebra::DMatrix::<f64>::identity(6, 6);
    assert!((&ig.m_ff - eye).abs().max() < 1e-10);
    // Segment chain (no shear): total mass and first moment about B (the shank's segments and
    // the end bodies at the pins).
    def.shear_modulus = None;
    let chain = SegmentRod::from_definition(&def, 10, 0.0, false).unwrap();
    let (m, c, _) = chain.segment_masses();
    let ([m_b, m_c], _) = chain.end_bodies();
    let seg_l = l / 10.0;
    let total: f64 = m.iter().sum::<f64>() + m_b + m_c;
    assert!((total - def.total_mass()).abs() < 1e-14);
    let first: f64 = (0..10)
        .map(|k| m[k] * (k as f64 * seg_l + c[k]))
        .sum::<f64>()
        + m_c * l;
    assert!((first / total - def.centre_of_mass()).abs() < 1e-14);
    assert!((chain.total_mass() - def.total_mass()).abs() < 1e-15);
}

/// Statics of the stubby shear-deformable rod, pinned-pinned under a triangular load
/// `q(x) = q0 x / L`, against the closed-form Timoshenko solution: `M = E I psi' =
/// -q0 x (L^2 - x^2) / (6 L)`, `v(x) = q0 x (7 L^4 - 10 L^2 x^2 + 3 x^4) / (360 L E I)
/// + q0 x (L^2 - x^2) / (6 L G A_s)`. The load varies along every element, so all three
/// interior coordinates carry part of the solution, among them the `psi` bubble, and the
/// curvature `psi'` recovered through `RodMesh::curvature` must include them. Measured and
/// asserted: nodal deflections exact (the nodal functions solve the homogeneous equations, so
/// the nodal values are those of the exact solution); `E I psi'` (linear per element) equals
/// the element-wise L2 projection of the exact cubic moment onto linear functions, to round-off;
/// without the interior part of `psi'` it does not (printed).
#[test]
fn stubby_timoshenko_static_triangular_load_against_closed_form() {
    use flexrod::beam::RodMesh;
    let ([l, e, _, _, i, g, a_s], def) = stubby_rod();
    let q0 = 1.0e5; // N/m at C
    let v_exact = |x: f64| {
        q0 * x * (7.0 * l.powi(4) - 10.0 * l * l * x * x + 3.0 * x.powi(4)) / (360.0 * l * e * i)
            + q0 * x * (l * l - x * x) / (6.0 * l * g * a_s)
    };
    let m_exact = |x: f64| -q0 * x * (l * l - x * x) / (6.0 * l);
    let m_peak = q0 * l * l / (9.0 * 3f64.sqrt());
    // 3-point Gauss on [0, 1]: exact to degree 5.
    let r = 0.5 * 0.6f64.sqrt();
    let gauss = [
        (0.5 - r, 5.0 / 18.0),
        (0.5, 8.0 / 18.0),
        (0.5 + r, 5.0 / 18.0),
    ];
    for n in [8usize, 16] {
        let mesh = RodMesh::from_definition(def.clone(), n, 0.0).unwrap();
        assert_eq!(mesh.n_bubbles(), 3);
        let (k, _) = mesh.assemble(MassKind::Consistent);
        let nc = mesh.n_coordinates();
        let le = l / n as f64;
        // Consistent load int q S_v^T dx (degree 4).
        let mut f = nalgebra::DVector::zeros(nc);
        for el in 0..n {
            let dofs = mesh.element_dofs(el);
            for (xi, w) in gauss {
                let s = mesh.shape(el, xi);
                let qx = q0 * (el as f64 + xi) * le / l;
                for (c, &d) in dofs.iter().enumerate() {
                    f[d] += qx * s[(1, c)] * w * le;
                }
            }
        }
        let fixed = [0usize, 1, 3 * n + 1];
        let free: Vec<usize> = (0..nc).filter(|i| !fixed.contains(i)).collect();
        let kr = nalgebra::DMatrix::from_fn(free.len(), free.len(), |r, c| k[(free[r], free[c])]);
        let fr = nalgebra::DVector::from_fn(free.len(), |r, _| f[free[r]]);
        let xr = kr.cholesky().expect("K_rr definite").solve(&fr);
        let mut x = nalgebra::DVector::zeros(nc);
        for (r, &d) in free.iter().enumerate() {
            x[d] = xr[r];
        }
        let v_mid = v_exact(0.5 * l);
        let nodal = (0..=n)
            .map(|node| (x[3 * node + 1] - v_exact(node as f64 * le)).abs())
            .fold(0.0, f64::max)
            / v_mid;
        // psi bubbles: the last interior coordinate of each element.
        let psi_bubble = (0..n)
            .map(|el| x[3 * (n + 1) + 3 * el + 2].abs())
            .fold(0.0, f64::max);
        // E I psi' against the L2 projection of M onto linear functions on each element:
        // P M = m0 + m1 (2 xi - 1), m0 = mean, m1 = 3 int M (2 xi - 1) dxi.
        let (mut with, mut without) = (0.0f64, 0.0f64);
        for el in 0..n {
            let dofs = mesh.element_dofs(el);
            let (mut m0, mut m1) = (0.0, 0.0);
            for (xi, w) in gauss {
                let mx = m_exact((el as f64 + xi) * le);
                m0 += w * mx;
                m1 += 3.0 * w * mx * (2.0 * xi - 1.0);
            }
            for xi in [0.0, 0.5, 1.0] {
                let c = mesh.curvature(el, xi);
                let (mut full, mut nodal_only) = (0.0, 0.0);
                for (col, &d) in dofs.iter().enumerate() {
                    full += c[(0, col)] * x[d];
                    if col < 6 {
                        nodal_only += c[(0, col)] * x[d];
                    }
                }
                let projected = m0 + m1 * (2.0 * xi - 1.0);
                with = with.max((e * i * full - projected).abs() / m_peak);
                without = without.max((e * i * nodal_only - projected).abs() / m_peak);
            }
        }
        println!(
            "triangular load, {n} elements: nodal v {nodal:.1e} of v(L/2); largest psi bubble {psi_bubble:.1e} rad; E I psi' against the element-wise L2 projection of the exact moment {with:.1e} of the peak ({without:.1e} without the interior part)"
        );
        assert!(nodal < 1e-9, "{nodal}");
        assert!(psi_bubble > 0.0);
        assert!(with < 1e-9 && without > 1e3 * with, "{with} {without}");
    }
}
