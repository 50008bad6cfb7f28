//! The rigid limit of the automotive rod (scenes/automotive_rod.toml): with E and G times 1e4
//! the flexible rod must give the rigid mechanism's pin forces and crank torque. Reference: the
//! closed-form inverse dynamics of the rigid slider-crank (tests/real_rod_mechanics.rs, the same
//! formulas: crank angle, speed; rod mass, centre of mass, inertia about it; slider mass), with
//! the tapered rod's mass properties integrated from its section table:
//! `m = rho int A + m_B + m_C`, `m s_cm = rho int A x + m_C L`,
//! `J_B = rho int (A x^2 + I) + J_B,end + J_C,end + m_C L^2` (the sections' own rotary inertia
//! `rho I` enters with shear deformation on, as in the FFR rod's `I3`), `j_cm = J_B - m s_cm^2`.
//!
//! The run: the scene's default experiment (6000 rpm from t = 0, undeformed, communication
//! step 1e-5 s, two revolutions), compared after the first 1 ms (the start-up ringing of the
//! stiff rod, damped at the rod's 2 % modal damping).

use flexrod::drive::{self, communication_grid, CrankDrive};
use flexrod::scene::SolverMethod;
use flexrod::Scene;
use nalgebra::Vector2;

fn scene() -> Scene {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/automotive_rod.toml");
    Scene::from_file(std::path::Path::new(path)).unwrap()
}

/// Closed-form inverse dynamics of the rigid slider-crank (tests/real_rod_mechanics.rs).
fn rigid_inverse_dynamics(
    (r, l, e): (f64, f64, f64),
    (m, s_cm, j_cm): (f64, f64, f64),
    ms: f64,
    (th, w): (f64, f64),
) -> (Vector2<f64>, Vector2<f64>, f64) {
    let al = 0.0;
    let (s, c) = th.sin_cos();
    let b = Vector2::new(r * c, r * s);
    let beta = ((e - r * s) / l).asin();
    let (sb, cb) = beta.sin_cos();
    let d = Vector2::new(cb, sb);
    let bd = -r * c * w / (l * cb);
    let bdd = (r * s * w * w - r * c * al + l * sb * bd * bd) / (l * cb);
    let ab = Vector2::new(-s * al - c * w * w, c * al - s * w * w) * r;
    let perp = |v: Vector2<f64>| Vector2::new(-v.y, v.x);
    let ag = ab + perp(d) * (s_cm * bdd) - d * (s_cm * bd * bd);
    let ac_x = ab.x - l * (sb * bdd + cb * bd * bd);
    let lcx = ms * ac_x;
    let p = -ag * m;
    let u = -d * s_cm;
    let cross = |a: Vector2<f64>, b: Vector2<f64>| a.x * b.y - a.y * b.x;
    let ld = d * l;
    let lcy = (-cross(u, p) - j_cm * bdd + ld.y * lcx) / ld.x;
    let lc = Vector2::new(lcx, lcy);
    let lb = p - lc;
    (lb, lc, -cross(b, lb))
}

/// (m, s_cm, j_cm) of the rod with its end bodies, by Simpson's rule on 2000 intervals (the
/// table is linear between stations, the integrands cubic at most: exact to round-off).
fn mass_properties(s: &Scene) -> (f64, f64, f64) {
    let def = s.rod.definition().unwrap();
    let t = def.section_table();
    let (l, rho) = (s.rod.length, s.rod.density);
    let n = 2000;
    let h = l / n as f64;
    let (mut m0, mut m1, mut m2) = (0.0, 0.0, 0.0);
    for k in 0..=n {
        let x = k as f64 * h;
        let w = if k == 0 || k == n {
            1.0
        } else if k % 2 == 1 {
            4.0
        } else {
            2.0
        } * h
            / 3.0;
        let v = t.at(x);
        m0 += w * rho * v.area;
        m1 += w * rho * v.area * x;
        m2 += w * rho * (v.area * x * x + v.area_moment);
    }
    let (mb, mc) = (s.rod.big_end.mass, s.rod.small_end.mass);
    let m = m0 + mb + mc;
    let s_cm = (m1 + mc * l) / m;
    let j_b = m2 + s.rod.big_end.inertia + s.rod.small_end.inertia + mc * l * l;
    (m, s_cm, j_b - m * s_cm * s_cm)
}

/// Largest deviation from the rigid mechanism after 1 ms, relative to the rigid peak:
/// [pin B, pin C, torque], and the run's internal steps.
fn rigid_errors(s: &Scene) -> ([f64; 3], u64) {
    let w = s.experiment.crank_speed;
    let grid = communication_grid(0.0, 1e-5, 2000);
    let mut sim = flexrod::Simulation::new(s).unwrap();
    let rec = drive::run(&mut sim, &CrankDrive::Constant { speed: w }, 0.0, &grid).unwrap();
    let props = mass_properties(s);
    let geometry = (s.crank.length, s.rod.length, s.mechanism.slider_offset);
    let rigid: Vec<_> = rec
        .inputs
        .iter()
        .map(|i| rigid_inverse_dynamics(geometry, props, s.slider.mass, (i.angle, i.speed)))
        .collect();
    let peak_b = rigid.iter().map(|r| r.0.norm()).fold(0.0, f64::max);
    let peak_c = rigid.iter().map(|r| r.1.norm()).fold(0.0, f64::max);
    let peak_t = rigid.iter().map(|r| r.2.abs()).fold(0.0, f64::max);
    let mut e = [0.0f64; 3];
    for (k, (o, r)) in rec.outputs.iter().zip(&rigid).enumerate() {
        if rec.times[k] < 1e-3 {
            continue;
        }
        e[0] = e[0].max((Vector2::from(o.pin_b_force) - r.0).norm() / peak_b);
        e[1] = e[1].max((Vector2::from(o.pin_c_force) - r.1).norm() / peak_c);
        e[2] = e[2].max((o.crank_torque - r.2).abs() / peak_t);
    }
    (e, rec.stats.steps)
}

fn stiff(method: SolverMethod) -> Scene {
    let mut s = scene();
    s.rod.mode_band_hz = s.rod.mode_band_hz.map(|b| b * 100.0);
    s.rod.youngs_modulus *= 1e4;
    s.rod.shear_modulus = s.rod.shear_modulus.map(|g| g * 1e4);
    s.solver.method = method;
    s
}

/// The same with fixed steps (1e-5 s) of generalized-alpha, reported (its numerical damping
/// takes the 0.2 to 2 MHz start-up ringing out, its second-order error stays).
#[test]
fn stiff_rod_with_generalized_alpha_reported() {
    let (e, steps) = rigid_errors(&stiff(SolverMethod::GeneralizedAlpha));
    println!(
        "E x 1e4, generalized-alpha (fixed 1e-5 s): pin B {:.2e}, pin C {:.2e}, torque {:.2e} ({steps} steps)",
        e[0], e[1], e[2]
    );
    assert!(e.iter().all(|&x| x < 1e-2), "{e:?}");
}

/// The closed form against the model's own rigid rod (`rod.modes = 0`).
#[test]
fn closed_form_is_the_rigid_ffr_rod() {
    let mut s = scene();
    s.rod.modes = 0;
    s.rod.mode_band_hz = None;
    s.rod.loaded_modes = false;
    s.rod.axial_modes = Some(0);
    let (e, _) = rigid_errors(&s);
    println!("rigid FFR rod (no modes) against the closed form: pin B {:.2e}, pin C {:.2e}, torque {:.2e}", e[0], e[1], e[2]);
    assert!(e.iter().all(|&x| x < 1e-9), "{e:?}");
}

#[test]
fn stiff_rod_converges_to_the_rigid_mechanism() {
    // As shipped with the band scaled as the frequencies (600 kHz: the same three modes, at 201
    // to 516 kHz, the bending modes above as residual flexibility); and with the 7 lowest
    // mass-loaded modes (201 kHz to 2.2 MHz) in the dynamics, under the exponential form.
    let mut seven = stiff(SolverMethod::Auto);
    seven.rod.mode_band_hz = None;
    seven.rod.modes = 7;
    seven.rod.axial_modes = Some(1);
    for (label, s) in [
        ("band 600 kHz", stiff(SolverMethod::Auto)),
        ("7 modes", seven),
    ] {
        let (e, steps) = rigid_errors(&s);
        let name = flexrod::Simulation::new(&s)
            .unwrap()
            .mechanism()
            .integrator_name()
            .0;
        println!(
            "E x 1e4, {label}, auto ({name}): pin B {:.2e}, pin C {:.2e}, torque {:.2e} of the rigid peaks ({steps} steps)",
            e[0], e[1], e[2]
        );
        assert!(e.iter().all(|&x| x < 1e-4), "{label}: {e:?}");
    }
}
