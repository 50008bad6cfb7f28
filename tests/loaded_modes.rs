//! Mass-loaded component modes (`rod.loaded_modes`, `flexrod::modal::mass_loaded_modes`) of the automotive
//! rod (scenes/automotive_rod.toml) at the shipped mesh against exact frequencies of the same
//! continuum (the section table's linear A, I and A_s, shear deformation, the end bodies):
//!
//! - the piston-rod axial mode, rod fixed axially at B, the piston and the small end at C:
//!   `(E A(x) u')' + rho A(x) w^2 u = 0`, `u(0) = 0`, `E A(L) u'(L) = w^2 (m_slider + m_C) u(L)`
//!   (for a uniform rod `beta tan beta = m_rod / m_C`, `beta = w L / c`; e.g. Timoshenko,
//!   Young and Weaver, *Vibration Problems in Engineering*, 4th ed., 1974, section 5.2, the bar
//!   with a mass at its end), solved by shooting;
//! - the bending modes, pinned at B and C, with the end bodies' rotary inertias `J_B`, `J_C`:
//!   Timoshenko's equations `(G A_s (w' - psi))' + rho A w^2 w = 0`,
//!   `(E I psi')' + G A_s (w' - psi) + rho I w^2 psi = 0`, `w(0) = w(L) = 0`,
//!   `E I psi'(0) = -w^2 J_B psi(0)`, `E I psi'(L) = w^2 J_C psi(L)` (the natural boundary
//!   conditions of the end bodies' kinetic energy `J psi'^2 / 2`), solved by shooting.
//!
//! Shooting: the first-order system in `(u, N)` or `(w, psi, M, V)` integrated by classic RK4
//! on 4000 steps per station interval (the properties are linear in each), the frequency
//! equation's roots bracketed by a scan and bisected to 1e-12 relative.
//!
//! Each case prints its row (`--nocapture`).

use flexrod::beam::SectionTable;
use flexrod::modal::mass_loaded_modes::{axial_coordinate_at_c, AddedMass};
use flexrod::modal::{ComponentModes, ModeSelection, ReferenceConditions};
use flexrod::Scene;
use std::f64::consts::PI;

fn scene() -> Scene {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/automotive_rod.toml");
    Scene::from_file(std::path::Path::new(path)).unwrap()
}

/// The rod's continuum: section table, E, G, rho, end bodies.
struct Continuum {
    table: SectionTable,
    e: f64,
    g: f64,
    rho: f64,
    length: f64,
    j_b: f64,
    j_c: f64,
    m_c: f64,
}

fn continuum(s: &Scene) -> Continuum {
    let def = s.rod.definition().unwrap();
    Continuum {
        table: def.section_table(),
        e: s.rod.youngs_modulus,
        g: s.rod.effective_shear_modulus().unwrap(),
        rho: s.rod.density,
        length: s.rod.length,
        j_b: s.rod.big_end.inertia,
        j_c: s.rod.small_end.inertia,
        m_c: s.rod.small_end.mass,
    }
}

/// Classic RK4 of `y' = f(x, y)` over [0, L], 4000 steps per station interval.
fn integrate<const N: usize>(
    c: &Continuum,
    mut y: [f64; N],
    f: impl Fn(f64, &[f64; N]) -> [f64; N],
) -> [f64; N] {
    let mut knots = vec![0.0];
    knots.extend(c.table.stations().iter().map(|s| s.position));
    knots.push(c.length);
    knots.dedup();
    for w in knots.windows(2) {
        let n = 4000;
        let h = (w[1] - w[0]) / n as f64;
        for k in 0..n {
            let x = w[0] + k as f64 * h;
            let add = |a: &[f64; N], b: &[f64; N], s: f64| -> [f64; N] {
                std::array::from_fn(|i| a[i] + s * b[i])
            };
            let k1 = f(x, &y);
            let k2 = f(x + 0.5 * h, &add(&y, &k1, 0.5 * h));
            let k3 = f(x + 0.5 * h, &add(&y, &k2, 0.5 * h));
            let k4 = f(x + h, &add(&y, &k3, h));
            y = std::array::from_fn(|i| {
                y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
            });
        }
    }
    y
}

/// The axial frequency equation's residual at `w` (rad/s): `N(L) - w^2 m_C u(L)` from
/// `u(0) = 0`, `N(0) = 1`.
fn axial_residual(c: &Continuum, m_end: f64, w: f64) -> f64 {
    let y = integrate(c, [0.0, 1.0], |x, y| {
        let a = c.table.at(x).area;
        [y[1] / (c.e * a), -c.rho * a * w * w * y[0]]
    });
    y[1] - w * w * m_end * y[0]
}

/// The bending frequency determinant at `w` (rad/s): two shots from B (`psi = 1`,
/// `M = -w^2 J_B`, `V = 0`; and `V = 1`), at C the rows `w(L)` and `M(L) - w^2 J_C psi(L)`.
fn bending_residual(c: &Continuum, w: f64) -> f64 {
    let w2 = w * w;
    let f = |x: f64, y: &[f64; 4]| {
        let s = c.table.at(x);
        [
            y[1] + y[3] / (c.g * s.shear_area),
            y[2] / (c.e * s.area_moment),
            -y[3] - c.rho * s.area_moment * w2 * y[1],
            -c.rho * s.area * w2 * y[0],
        ]
    };
    let a = integrate(c, [0.0, 1.0, -w2 * c.j_b, 0.0], f);
    let b = integrate(c, [0.0, 0.0, 0.0, 1.0], f);
    let row = |y: &[f64; 4]| (y[0], y[2] - w2 * c.j_c * y[1]);
    let (a0, a1) = row(&a);
    let (b0, b1) = row(&b);
    // Scaled so that the determinant stays O(1) across the scan.
    (a0 * b1 - a1 * b0)
        / (a0.abs() + a1.abs() * 1e-4 + 1e-30).max(1e-30)
        / (b0.abs() + b1.abs() * 1e-4 + 1e-30)
}

/// Roots in Hz of `f` (of w in rad/s) between `lo` and `hi` Hz: a scan in steps of `step` Hz,
/// then bisection to 1e-12 relative.
fn roots(f: impl Fn(f64) -> f64, lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let g = |hz: f64| f(2.0 * PI * hz);
    let mut out = Vec::new();
    let (mut a, mut fa) = (lo, g(lo));
    while a < hi {
        let b = a + step;
        let fb = g(b);
        if fa.is_finite() && fb.is_finite() && fa * fb < 0.0 {
            let (mut x0, mut x1, mut f0) = (a, b, fa);
            while (x1 - x0) > 1e-12 * x1 {
                let m = 0.5 * (x0 + x1);
                let fm = g(m);
                if fm * f0 <= 0.0 {
                    x1 = m;
                } else {
                    x0 = m;
                    f0 = fm;
                }
            }
            out.push(0.5 * (x0 + x1));
        }
        a = b;
        fa = fb;
    }
    out
}

fn loaded_modes(s: &Scene) -> ComponentModes {
    ComponentModes::from_definition_loaded(
        s.rod.definition().unwrap(),
        s.rod.elements,
        ReferenceConditions::from_kind(s.rod.reference, s.rod.elements).unwrap(),
        s.rod.mass,
        &ModeSelection::Cutoff { max_hz: 30e3 },
        &[AddedMass {
            coordinate: axial_coordinate_at_c(s.rod.elements),
            mass: s.slider.mass,
        }],
    )
    .unwrap()
}

#[test]
fn piston_rod_axial_mode_at_the_shipped_mesh_against_shooting() {
    let s = scene();
    let c = continuum(&s);
    let m_end = s.slider.mass + c.m_c;
    let exact = roots(|w| axial_residual(&c, m_end, w), 100.0, 30e3, 50.0);
    // Uniform-rod check of the shooting: beta tan beta = m_rod / m_end.
    let modes = loaded_modes(&s);
    let axial: Vec<f64> = modes
        .all_frequencies_hz
        .iter()
        .zip(&modes.all_axial_shares)
        .filter(|(_, &sh)| sh > 0.5)
        .map(|(&f, _)| f)
        .collect();
    println!("axial, piston and small end at C: exact {exact:.2?} Hz; loaded modes, {} elements: {axial:.2?} Hz", s.rod.elements);
    let rel = (axial[0] - exact[0]).abs() / exact[0];
    println!(
        "  first: {:.3} Hz against {:.3} Hz, {rel:.2e}",
        axial[0], exact[0]
    );
    assert!((3200.0..3350.0).contains(&exact[0]), "{}", exact[0]);
    assert!(rel < 5e-4, "{rel:e}");
    // The first axial mode is retained by a 30 kHz band, and it moves C.
    let k = modes
        .retained
        .iter()
        .position(|&i| modes.is_axial(i))
        .unwrap();
    assert!(modes.shapes[(axial_coordinate_at_c(s.rod.elements), k)].abs() > 0.1);
}

#[test]
fn axial_shooting_is_the_closed_form_for_a_uniform_bar() {
    // beta tan beta = m_rod / m_end (uniform bar fixed at one end, mass at the other).
    let (l, e, rho, a, m_end) = (0.15, 2e11, 7800.0, 2e-4, 0.5);
    let c = Continuum {
        table: SectionTable::uniform(l, a, 1e-8),
        e,
        g: 8e10,
        rho,
        length: l,
        j_b: 0.0,
        j_c: 0.0,
        m_c: 0.0,
    };
    let shot = roots(|w| axial_residual(&c, m_end, w), 100.0, 10e3, 50.0)[0];
    let ratio = rho * a * l / m_end;
    let beta = roots(
        |b| b.tan() * b - ratio,
        1e-6 / (2.0 * PI),
        1.5 / (2.0 * PI),
        1e-4,
    )[0] * 2.0
        * PI;
    let exact = beta / l * (e / rho).sqrt() / (2.0 * PI);
    println!("uniform bar: shooting {shot:.6} Hz, beta tan beta: {exact:.6} Hz");
    assert!((shot - exact).abs() < 1e-9 * exact);
}

#[test]
fn bending_modes_with_end_bodies_at_the_shipped_mesh_against_shooting() {
    let s = scene();
    let c = continuum(&s);
    let exact = roots(|w| bending_residual(&c, w), 200.0, 25e3, 25.0);
    let modes = loaded_modes(&s);
    let bending: Vec<f64> = modes
        .all_frequencies_hz
        .iter()
        .zip(&modes.all_axial_shares)
        .filter(|(_, &sh)| sh <= 0.5)
        .map(|(&f, _)| f)
        .collect();
    println!("bending, pinned, end bodies: exact {exact:.2?} Hz");
    for (k, x) in exact.iter().enumerate() {
        let rel = (bending[k] - x).abs() / x;
        println!(
            "  mode {}: {:.3} Hz at {} elements against {x:.3} Hz, {rel:.2e}",
            k + 1,
            bending[k],
            s.rod.elements
        );
        // The modes of the excited band and above (to 11 kHz) within 5e-4.
        if *x < 11e3 {
            assert!(rel < 5e-4, "mode {}: {rel:e}", k + 1);
        }
    }
    assert!(exact.len() >= 3);
}
