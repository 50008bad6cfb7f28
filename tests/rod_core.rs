//! Rod core invariants, convergence under refinement and bad input.

use flexrod::beam::{RodMesh, RodProperties};
use flexrod::error::ModelError;
use flexrod::modal::{ComponentModes, ModeSelection, ReferenceConditions, ShapeIntegrals};
use flexrod::rod::ffr::FfrRod;
use flexrod::rod::RodBody;
use flexrod::scene::MassKind;
use nalgebra::Vector2;

fn bench() -> RodProperties {
    RodProperties::cdi_benchmark()
}

fn modes(n: usize, reference: ReferenceConditions, kind: MassKind, count: usize) -> ComponentModes {
    ComponentModes::new(bench(), n, reference, kind, &ModeSelection::Count(count)).unwrap()
}

fn all_modes(n: usize, reference: ReferenceConditions) -> ComponentModes {
    ComponentModes::new(
        bench(),
        n,
        reference,
        MassKind::Consistent,
        &ModeSelection::Cutoff {
            max_hz: f64::INFINITY,
        },
    )
    .unwrap()
}

/// A tiny deterministic generator for property tests (xorshift).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

#[test]
fn invariants_mass_first_and_second_moments() {
    for reference in [
        ReferenceConditions::SimplySupported,
        ReferenceConditions::MeanAxis,
        ReferenceConditions::BodyFixed { node: 3 },
        ReferenceConditions::BodyFixed { node: 0 },
    ] {
        let m = modes(6, reference.clone(), MassKind::Consistent, 5);
        let ig = ShapeIntegrals::new(&m);
        let p = bench();
        let (l, xb) = (p.length, ig.x_b);
        assert!((ig.mass - p.density * p.area * l).abs() < 1e-15);
        // I1 = m (x_b + L/2), I3 = rho A ((x_b + L)^3 - x_b^3) / 3.
        assert!(
            (ig.i1[0] - ig.mass * (xb + 0.5 * l)).abs() < 1e-15,
            "{reference:?}"
        );
        assert!(ig.i1[1].abs() < 1e-18);
        let i3 = p.mass_per_length() * ((xb + l).powi(3) - xb.powi(3)) / 3.0;
        assert!(
            (ig.i3 - i3).abs() < 1e-14 * i3,
            "{reference:?}: {} vs {i3}",
            ig.i3
        );
        // M_ff = I for mass-normalized modes; S~ skew.
        let n = ig.m_ff.nrows();
        for i in 0..n {
            for j in 0..n {
                let id = if i == j { 1.0 } else { 0.0 };
                assert!(
                    (ig.m_ff[(i, j)] - id).abs() < 1e-10,
                    "M_ff[{i},{j}] = {}",
                    ig.m_ff[(i, j)]
                );
                assert!((ig.s_tilde[(i, j)] + ig.s_tilde[(j, i)]).abs() < 1e-14);
            }
        }
    }
}

#[test]
fn mean_axis_modes_carry_no_momentum_of_deformation() {
    let m = modes(8, ReferenceConditions::MeanAxis, MassKind::Consistent, 10);
    let ig = ShapeIntegrals::new(&m);
    // Linear momentum of deformation int rho S_hat p' = I2 p'; angular about the frame origin
    // (the centre of mass) int rho xbar x S_hat p' = -I5 p' (+ higher order in p).
    let scale = ig.mass.sqrt() * bench().length;
    let i2max = ig.i2.abs().max();
    let i5max = ig.i5.abs().max();
    println!("mean axis: max |I2| = {i2max:e}, max |I5| = {i5max:e} (scale {scale:e})");
    assert!(i2max < 1e-12 * scale && i5max < 1e-12 * scale * bench().length);
}

#[test]
fn kinetic_energy_of_mass_matrix_equals_direct_quadrature() {
    let mut rng = Rng(0x9e3779b97f4a7c15);
    for (reference, kind) in [
        (ReferenceConditions::SimplySupported, MassKind::Consistent),
        (ReferenceConditions::MeanAxis, MassKind::Consistent),
        (
            ReferenceConditions::BodyFixed { node: 2 },
            MassKind::Consistent,
        ),
        (ReferenceConditions::SimplySupported, MassKind::Lumped),
    ] {
        let cm = modes(4, reference.clone(), kind, 6);
        let rod = FfrRod::new(cm.clone(), 0.0, false);
        let n = rod.n_coordinates();
        for _ in 0..20 {
            let q: Vec<f64> = (0..n)
                .map(|i| if i < 3 { rng.next() } else { 1e-3 * rng.next() })
                .collect();
            let v: Vec<f64> = (0..n).map(|_| 10.0 * rng.next()).collect();
            let t_ffr = rod.kinetic_energy(&q, &v);
            let t_direct = direct_kinetic_energy(&cm, kind, &q, &v);
            assert!(
                (t_ffr - t_direct).abs() < 1e-12 * t_direct,
                "{reference:?} {kind:?}: {t_ffr} vs {t_direct}"
            );
        }
    }
}

/// 1/2 sum rho |r'|^2 over mass points (Gauss points for consistent mass, nodes plus rotary
/// inertia for lumped), with r' = R' + phi' A I~ ubar + A S_hat p'.
fn direct_kinetic_energy(cm: &ComponentModes, kind: MassKind, q: &[f64], v: &[f64]) -> f64 {
    let mesh: &RodMesh = &cm.mesh;
    let el = mesh.element();
    let l = el.length;
    let rho_a = mesh.section.mass_per_length();
    let (c, s) = (q[2].cos(), q[2].sin());
    let rot = |x: Vector2<f64>| Vector2::new(c * x.x - s * x.y, s * x.x + c * x.y);
    let n = cm.n_modes();
    let mut t = 0.0;
    for e in 0..mesh.n_elements {
        let tm = cm.element_shapes(e);
        let points: Vec<(f64, f64)> = match kind {
            MassKind::Consistent => flexrod::beam::quadrature::GAUSS4
                .iter()
                .map(|&(xi, w)| (xi, w * l * rho_a))
                .collect(),
            MassKind::Lumped => vec![(0.0, 0.5 * rho_a * l), (1.0, 0.5 * rho_a * l)],
        };
        for (xi, w) in points {
            let sh = el.shape(xi) * &tm;
            let mut u = Vector2::new(mesh.x_b + (e as f64 + xi) * l, 0.0);
            let mut ud = Vector2::zeros();
            for j in 0..n {
                u += Vector2::new(sh[(0, j)], sh[(1, j)]) * q[3 + j];
                ud += Vector2::new(sh[(0, j)], sh[(1, j)]) * v[3 + j];
            }
            let rd = Vector2::new(v[0], v[1]) + rot(Vector2::new(-u.y, u.x)) * v[2] + rot(ud);
            t += 0.5 * w * rd.norm_squared();
            if kind == MassKind::Lumped {
                // Rotary inertia m l^2/78 per node about the section: angular speed phi' + theta'.
                let row = if xi == 0.0 { 2 } else { 5 };
                let theta_dot: f64 = (0..n).map(|j| tm[(row, j)] * v[3 + j]).sum();
                t += 0.5 * rho_a * l * l * l / 78.0 * (v[2] + theta_dot).powi(2);
            }
        }
    }
    t
}

/// Observed order from errors at successive doublings.
fn orders(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

#[test]
fn pinned_pinned_bending_converges_at_fourth_order() {
    let p = bench();
    let exact = |k: f64| {
        k * k * std::f64::consts::PI / (2.0 * p.length.powi(2))
            * (p.bending_rigidity() / p.mass_per_length()).sqrt()
    };
    for mode in 1..=3 {
        let mut errors = Vec::new();
        for n in [4usize, 8, 16, 32] {
            let m = all_modes(n, ReferenceConditions::SimplySupported);
            let bending = bending_frequencies(&m);
            errors.push((bending[mode - 1] - exact(mode as f64)).abs() / exact(mode as f64));
        }
        let o = orders(&errors);
        println!("pinned-pinned bending mode {mode}: relative errors {errors:?}, observed orders {o:.2?}");
        assert!(o.iter().all(|&x| x > 3.7), "mode {mode}: orders {o:?}");
        assert!(errors[3] < 1e-5);
    }
}

#[test]
fn fixed_free_axial_converges_at_second_order() {
    let p = bench();
    let exact = |k: f64| (2.0 * k - 1.0) / (4.0 * p.length) * (p.youngs_modulus / p.density).sqrt();
    for mode in 1..=2 {
        let mut errors = Vec::new();
        for n in [4usize, 8, 16, 32] {
            // Simply supported: u = 0 at B only, so the axial modes are fixed-free.
            let m = all_modes(n, ReferenceConditions::SimplySupported);
            let axial = axial_frequencies(&m);
            errors.push((axial[mode - 1] - exact(mode as f64)).abs() / exact(mode as f64));
        }
        let o = orders(&errors);
        println!(
            "fixed-free axial mode {mode}: relative errors {errors:?}, observed orders {o:.2?}"
        );
        assert!(
            o.iter().all(|&x| (x - 2.0).abs() < 0.1),
            "mode {mode}: orders {o:?}"
        );
    }
}

/// Split modes into axial and bending by where their modal mass sits.
fn classify(m: &ComponentModes) -> (Vec<f64>, Vec<f64>) {
    let (k, mm) = m.mesh.assemble(MassKind::Consistent);
    let _ = k;
    let n = m.shapes.nrows();
    let (mut axial, mut bending) = (Vec::new(), Vec::new());
    for j in 0..m.n_modes() {
        let mut ax = 0.0;
        for a in (0..n).step_by(3) {
            for b in (0..n).step_by(3) {
                ax += m.shapes[(a, j)] * mm[(a, b)] * m.shapes[(b, j)];
            }
        }
        let f = m.all_frequencies_hz[m.retained[j]];
        if ax > 0.5 {
            axial.push(f)
        } else {
            bending.push(f)
        }
    }
    (axial, bending)
}

fn axial_frequencies(m: &ComponentModes) -> Vec<f64> {
    classify(m).0
}

fn bending_frequencies(m: &ComponentModes) -> Vec<f64> {
    classify(m).1
}

#[test]
fn bad_input_gives_typed_errors_naming_the_value() {
    let p = bench();
    for (name, props) in [
        (
            "rod.youngs_modulus",
            RodProperties {
                youngs_modulus: 0.0,
                ..p
            },
        ),
        ("rod.density", RodProperties { density: -1.0, ..p }),
        (
            "rod.area",
            RodProperties {
                area: f64::NAN,
                ..p
            },
        ),
        (
            "rod.area_moment",
            RodProperties {
                area_moment: -3.0,
                ..p
            },
        ),
        ("rod.length", RodProperties { length: 0.0, ..p }),
    ] {
        let e = ComponentModes::new(
            props,
            4,
            ReferenceConditions::SimplySupported,
            MassKind::Consistent,
            &ModeSelection::Count(2),
        )
        .unwrap_err();
        assert!(matches!(e, ModelError::InvalidParameter { .. }), "{e}");
        let text = e.to_string();
        assert!(text.contains(name) && text.contains("allowed"), "{text}");
    }
    let e = ComponentModes::new(
        p,
        0,
        ReferenceConditions::SimplySupported,
        MassKind::Consistent,
        &ModeSelection::Count(2),
    )
    .unwrap_err();
    assert!(e.to_string().contains("rod.elements"), "{e}");
    let e = ComponentModes::new(
        p,
        2,
        ReferenceConditions::SimplySupported,
        MassKind::Consistent,
        &ModeSelection::Count(7),
    )
    .unwrap_err();
    assert_eq!(
        e,
        ModelError::TooManyModes {
            requested: 7,
            available: 6
        }
    );
    assert!(e.to_string().contains("0..=6"));
    let e = ReferenceConditions::parse("clamped_both", 4).unwrap_err();
    assert!(
        e.to_string().contains("clamped_both") && e.to_string().contains("simply_supported"),
        "{e}"
    );
    let e = ReferenceConditions::parse("body_fixed_mid", 3).unwrap_err();
    assert!(e.to_string().contains("even"), "{e}");
}

#[test]
fn general_constraint_sets_are_checked() {
    let p = bench();
    let build = |c: Vec<usize>| {
        ComponentModes::new(
            p,
            4,
            ReferenceConditions::Constrained { coordinates: c },
            MassKind::Consistent,
            &ModeSelection::Count(2),
        )
    };
    // u_B, v_B, v_C: the simply supported set, accepted; same frequencies as the named one.
    let general = build(vec![0, 1, 13]).unwrap();
    let named = all_modes(4, ReferenceConditions::SimplySupported);
    assert!((general.all_frequencies_hz[0] - named.all_frequencies_hz[0]).abs() < 1e-9);
    // Two coordinates leave a rigid-body mode in.
    let e = build(vec![0, 1]).unwrap_err();
    assert!(e.to_string().contains("leave 1 rigid-body mode"), "{e}");
    // u_B, u_C, v_B: rotation left in and axial stretch removed.
    let e = build(vec![0, 12, 1]).unwrap_err();
    assert!(
        e.to_string().contains("rigid-body") && e.to_string().contains("over-constrain"),
        "{e}"
    );
    // Four independent constraints over-constrain.
    let e = build(vec![0, 1, 13, 2]).unwrap_err();
    assert!(e.to_string().contains("over-constrain"), "{e}");
    // Out of range.
    let e = build(vec![0, 1, 99]).unwrap_err();
    assert!(e.to_string().contains("0..=14"), "{e}");
}

/// Selecting from every mode gives what solving with the selection gives (the same shapes and
/// frequencies to rounding), and the first-order shape integrals of many modes are the full
/// integrals' linear part: for the plain rod and for a rod with shear and end bodies.
#[test]
fn selecting_from_every_mode_matches_solving_with_the_selection() {
    use flexrod::beam::{EndBody, RodDefinition};
    let mut general = RodDefinition::uniform(bench());
    general.shear_modulus = Some(bench().youngs_modulus / 2.6);
    general.small_end = EndBody {
        mass: 0.3 * bench().mass_per_length() * bench().length,
        inertia: 1e-6,
    };
    for definition in [RodDefinition::uniform(bench()), general] {
        for reference in [
            ReferenceConditions::SimplySupported,
            ReferenceConditions::BodyFixed { node: 0 },
            ReferenceConditions::MeanAxis,
        ] {
            let solve = |selection: &ModeSelection| {
                ComponentModes::from_definition(
                    definition.clone(),
                    10,
                    reference.clone(),
                    MassKind::Consistent,
                    selection,
                )
                .unwrap()
            };
            let all = solve(&ModeSelection::Cutoff {
                max_hz: f64::INFINITY,
            });
            for selection in [
                ModeSelection::Count(4),
                ModeSelection::CountWithAxial { count: 3, axial: 1 },
                ModeSelection::Cutoff { max_hz: 5e3 },
            ] {
                let direct = solve(&selection);
                let picked = all.select(&selection).unwrap();
                assert_eq!(picked.retained, direct.retained, "{selection:?}");
                for (a, b) in picked.omega2.iter().zip(&direct.omega2) {
                    assert!((a - b).abs() <= 1e-12 * b.abs().max(1.0), "{a} {b}");
                }
                for i in 0..direct.shapes.nrows() {
                    for j in 0..direct.shapes.ncols() {
                        let (a, b) = (picked.shapes[(i, j)], direct.shapes[(i, j)]);
                        assert!((a - b).abs() <= 1e-9 * (1.0 + b.abs()), "{i} {j}: {a} {b}");
                    }
                }
            }
            let full = ShapeIntegrals::new(&all);
            let first = ShapeIntegrals::first_order(&all);
            assert_eq!(first.m_ff.nrows(), 0);
            assert_eq!(first.i2, full.i2);
            assert_eq!(first.i5, full.i5);
            assert_eq!(first.i_rot, full.i_rot);
            assert_eq!(first.s_mid, full.s_mid);
            assert_eq!((first.mass, first.i3), (full.mass, full.i3));
        }
    }
}

/// The shear-deformable rod's foreshortening against the closed form of the simply supported
/// Timoshenko beam's first mode, `v = a sin(k s)`, `psi = b cos(k s)`, `k = pi / L`: from the
/// transverse equation `-rho A w^2 v = G A_s (v'' - psi')`, `b = a (k^2 - rho A w^2 / (G A_s)) / k`;
/// unit modal mass `rho A a^2 L / 2 + rho I b^2 L / 2 = 1`. Reissner's strain along the section
/// normal gives `G_0 = int (2 v' psi - psi^2) = L / 2 (2 k a b - b^2)`, not `int v'^2 = L k^2 a^2
/// / 2` (docs/physics.md, "The shear-deformable rod").
#[test]
fn shear_rod_foreshortening_is_reissners() {
    use flexrod::beam::RodDefinition;
    // A stubby steel rod, L/h = 8: shear takes a few percent of the first mode's slope.
    let p = RodProperties {
        length: 0.2,
        youngs_modulus: 2.1e11,
        density: 7850.0,
        area: 25e-3 * 20e-3,
        area_moment: 20e-3 * 25e-3f64.powi(3) / 12.0,
    };
    let g = p.youngs_modulus / 2.6;
    let shear_area = p.area / 1.2;
    let mut definition = RodDefinition::uniform(p);
    definition.shear_modulus = Some(g);
    let modes = ComponentModes::from_definition(
        definition,
        32,
        ReferenceConditions::SimplySupported,
        MassKind::Consistent,
        &ModeSelection::Count(1),
    )
    .unwrap();
    let ig = ShapeIntegrals::new(&modes);
    let (l, rho_a, rho_i) = (p.length, p.mass_per_length(), p.density * p.area_moment);
    let k = std::f64::consts::PI / l;
    let w2 = modes.omega2[0];
    let ratio = (k * k - rho_a * w2 / (g * shear_area)) / k; // b / a
    let a = (2.0 / (l * (rho_a + rho_i * ratio * ratio))).sqrt();
    let b = ratio * a;
    let reissner = 0.5 * l * (2.0 * k * a * b - b * b);
    let slope_squared = 0.5 * l * k * k * a * a;
    let g0 = ig.g[0][(0, 0)];
    assert!(
        (g0 - reissner).abs() < 1e-6 * reissner,
        "G_0 {g0} against Reissner's {reissner}"
    );
    // The difference is the shear strain's share, large enough to tell the two apart.
    assert!((slope_squared - reissner) / reissner > 1e-3);
}
