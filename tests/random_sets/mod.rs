//! The random parameter sets of the error-control calibration, shared by
//! `tests/error_control.rs` and `examples/error_control_case.rs`: a seeded generator, the sets
//! inside the contract's ranges, a constant-speed run and its pointwise error.

use flexrod::drive::{self, communication_grid, CrankDrive, Record};
use flexrod::scene::{RodModelKind, SolverMethod};
use flexrod::{Scene, Simulation};

/// A small deterministic generator (SplitMix64), so the parameter sets are the same on every
/// machine.
pub struct Random(pub u64);

impl Random {
    pub fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn uniform(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.next()
    }
    pub fn log_uniform(&mut self, a: f64, b: f64) -> f64 {
        (a.ln() + (b.ln() - a.ln()) * self.next()).exp()
    }
    pub fn integer(&mut self, a: usize, b: usize) -> usize {
        a + ((b - a + 1) as f64 * self.next()) as usize
    }
}

/// A parameter set and the crank speed (rad/s) and communication step (s) it is run at.
pub struct Case {
    pub scene: Scene,
    pub speed: f64,
    pub dt: f64,
}

impl std::fmt::Display for Case {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let r = &self.scene.rod;
        write!(
            f,
            "{:?} n {} modes {} L {:.3} r {:.3} E {:.2e} rho {:.0} A {:.2e} I {:.2e} zeta {:.3} m_s {:.3} w {:.0} dt {:.1e} tol {:.0e}",
            r.model, r.elements, r.modes, r.length, self.scene.crank.length, r.youngs_modulus,
            r.density, r.area, r.area_moment, r.damping_ratio, self.scene.slider.mass,
            self.speed, self.dt, self.scene.solver.tolerance
        )
    }
}

/// A parameter set inside the contract's ranges whose deflection stays small (the estimate of
/// the quasi-static deflection `5 q L^4 / (384 E I)`, `q = rho A r w^2`, below 3 % of L).
pub fn random_case(rng: &mut Random) -> Case {
    loop {
        let mut s = Scene::benchmark();
        s.solver.method = SolverMethod::Auto;
        let l = rng.uniform(0.12, 0.5);
        s.rod.length = l;
        s.crank.length = l * rng.uniform(0.2, 0.5);
        s.rod.youngs_modulus = rng.uniform(7e10, 2.1e11);
        s.rod.density = rng.uniform(2700.0, 8000.0);
        let h = l * rng.log_uniform(1.0 / 60.0, 1.0 / 12.0);
        let b = h * rng.uniform(0.5, 2.0);
        s.rod.area = b * h;
        s.rod.area_moment = b * h * h * h / 12.0;
        s.rod.damping_ratio = if rng.next() < 0.3 {
            0.0
        } else {
            rng.uniform(0.0, 0.05)
        };
        let rod_mass = s.rod.density * s.rod.area * l;
        s.slider.mass = if rng.next() < 0.3 {
            0.0
        } else {
            rng.uniform(0.0, 1.0) * rod_mass
        };
        if rng.next() < 0.3 {
            s.rod.model = RodModelKind::Segments;
            s.rod.elements = rng.integer(4, 12);
        } else {
            s.rod.elements = 2 * rng.integer(2, 5);
            s.rod.modes = rng.integer(2, 4);
        }
        s.solver.tolerance = [1e-2, 3e-3, 1e-3][rng.integer(0, 2)];
        let speed = rng.uniform(50.0, 300.0);
        let dt = rng.log_uniform(1e-5, 1e-3);
        let q = s.rod.density * s.rod.area * s.crank.length * speed * speed;
        let v = 5.0 * q * l.powi(4) / (384.0 * s.rod.youngs_modulus * s.rod.area_moment);
        if v / l < 0.03 && v / l > 1e-5 {
            return Case {
                scene: s,
                speed,
                dt,
            };
        }
    }
}

/// `scene` at constant crank speed `speed` over `duration` s, a row every `dt` s.
pub fn run(scene: &Scene, speed: f64, dt: f64, duration: f64) -> Record {
    let mut sim = Simulation::new(scene).unwrap();
    let steps = (duration / dt).round().max(1.0) as usize;
    drive::run(
        &mut sim,
        &CrankDrive::Constant { speed },
        0.0,
        &communication_grid(0.0, dt, steps),
    )
    .unwrap()
}

/// `scene` at the tolerance `tolerance` with the model class its own tolerance chose (the
/// `auto` settings resolved): the reference measures the integration alone.
pub fn same_model(scene: &Scene, tolerance: f64) -> Scene {
    let mut fine = scene.clone();
    fine.rod = Simulation::new(scene).unwrap().mechanism().spec.rod.clone();
    fine.solver.tolerance = tolerance;
    fine
}

/// Largest pointwise difference of v_mid/L over the reference's peak.
pub fn error(a: &Record, reference: &Record) -> f64 {
    let peak = reference.peak_deflection_rel();
    a.outputs
        .iter()
        .zip(&reference.outputs)
        .map(|(x, y)| (x.deflection_rel - y.deflection_rel).abs())
        .fold(0.0, f64::max)
        / peak
}
