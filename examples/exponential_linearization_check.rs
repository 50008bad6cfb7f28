//! Issue 12 trial: the per-step linear part of the exponential trial (`DaeSystem::modal_linearization`:
//! the diagonal of the reduced stiffness, with the axial stiffening, over the reduced mass) against
//! central finite differences of `-dz_a'' / dz_a` of the closed-form right-hand side, at five crank
//! angles from a consistent start. `cargo run --release --example exponential_linearization_check`
//! (default scene), `SCENE=scenes/automotive_rod.toml W=628.3 ...` (automotive rod).
use flexrod::integrator::{DaeSystem, PartitionedRhs};
use flexrod::{CrankInput, Scene, Simulation};
fn main() {
    let text =
        std::fs::read_to_string(std::env::var("SCENE").unwrap_or("scenes/benchmark.toml".into()))
            .unwrap();
    let mut sim = Simulation::new(&Scene::from_toml_str(&text, "x").unwrap()).unwrap();
    let w: f64 = std::env::var("W")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(150.0);
    for angle in [0.0, 0.8, 1.6, 2.4, 3.14] {
        let input = CrankInput {
            angle,
            speed: w,
            acceleration: 0.0,
        };
        sim.start(0.0, input, 0.0).unwrap();
        let mech = sim.mechanism();
        let sys = mech.system(sim.state());
        let elastic: Vec<usize> = mech.rod.elastic_coordinates().unwrap().collect();
        let k = elastic.len();
        let mut rhs = PartitionedRhs::new(&sys, elastic.clone());
        let st = sim.state();
        let mut lin = vec![0.0; 2 * k];
        let ok = sys.modal_linearization(0.0, &st.dae.q, &st.dae.v, &mut lin);
        let z0: Vec<f64> = elastic.iter().map(|&i| st.dae.q[i]).collect();
        let zd0: Vec<f64> = elastic.iter().map(|&i| st.dae.v[i]).collect();
        let mut line = format!("angle {angle}: ok {ok}");
        for a in 0..k {
            let mut f = |dz: f64| {
                let mut z = z0.clone();
                z[a] += dz;
                let mut zdd = vec![0.0; k];
                rhs.q.copy_from_slice(&st.dae.q);
                rhs.evaluate_stage(&sys, 0.0, &z, &zd0, &mut zdd, false)
                    .unwrap();
                zdd[a]
            };
            let d = 1e-7;
            let fd = -(f(d) - f(-d)) / (2.0 * d);
            line += &format!(
                " | mode {a}: fd w2 {fd:.6e} lin {:.6e} ratio {:.4}",
                lin[2 * a],
                lin[2 * a] / fd
            );
        }
        println!("{line}");
    }
}
