//! Parameters drawn across their whole declared ranges, through the FMI 2.0 C functions, with a
//! wall-time oracle per call.
//!
//! Each sequence takes the default scene's FMU or the automotive scene's (its resources in a
//! temporary folder), sets each parameter with probability 1/2 to a value drawn across its
//! whole range (the physical ranges of docs/fmu.md, "Parameters and their allowed ranges",
//! log-uniform where they span decades: soft and stiff rods, light and heavy ones, every
//! element count, mode counts and mode bands, the tightest tolerance, every enumeration item),
//! initializes, and takes communication steps of 1e-6 to 1e-2 s. Oracle: every call ends within
//! the wall-time limit it is given ([`WORST_CALL`], the documented worst case of one call, in
//! the long mode, which measures it; a hang detector in the suite, whose machine is shared),
//! answers a status of fmi2OK to fmi2Error, and no value read with fmi2OK is non-finite or
//! beyond 1e12.

use std::ffi::CString;
use std::time::Instant;

use flexrod::fmi::description::ModelDescription;
use flexrod::fmi::ffi::lifecycle::*;
use flexrod::fmi::ffi::stepping::*;
use flexrod::fmi::ffi::values::*;
use flexrod::fmi::standard::Standard;
use flexrod::fmi::variables::{Causality, Family, Value};
use flexrod::Scene;

use super::fmu::{callbacks, Log, ERROR, OK, WARNING};
use super::oracle::Violations;
use super::rng::Rng;

/// The documented worst case of one call, s (docs/fmu.md, "Time per call"): initialization
/// and one communication step each, on the reference machine with one thread per core.
pub const WORST_CALL: f64 = flexrod::rod::cost::WORST_CALL_SECONDS;

/// One parameter of an exported FMU.
struct Parameter {
    name: String,
    vr: u32,
    real: bool,
    min: f64,
    max: f64,
}

/// An exported FMU: its GUID, resource location, parameters and outputs.
pub struct Target {
    label: &'static str,
    guid: CString,
    resources: CString,
    parameters: Vec<Parameter>,
    outputs: Vec<u32>,
}

impl Target {
    /// The FMU of `scene` with `scene.toml` written into `folder` (its resources).
    fn new(label: &'static str, scene_text: &str, folder: &std::path::Path) -> Target {
        let scene = Scene::from_toml_str(scene_text, label).expect("a shipped scene");
        std::fs::create_dir_all(folder).unwrap();
        std::fs::write(folder.join("scene.toml"), scene_text).unwrap();
        let d = ModelDescription::for_scene(&scene).expect("describes");
        let number = |v: &Option<Value>, default: f64| match v {
            Some(Value::Real(r)) => *r,
            Some(Value::Integer(i)) => *i as f64,
            _ => default,
        };
        let mut parameters = Vec::new();
        let mut outputs = Vec::new();
        for x in d.table.variables() {
            let real = Family::of(x.value_type, Standard::Fmi2) == Family::Real;
            match x.causality {
                Causality::Parameter => parameters.push(Parameter {
                    name: x.name.clone(),
                    vr: x.value_reference,
                    real,
                    min: number(&x.min, 0.0),
                    max: number(&x.max, 1.0),
                }),
                Causality::Output if real => outputs.push(x.value_reference),
                _ => {}
            }
        }
        Target {
            label,
            guid: CString::new(d.guid.clone()).unwrap(),
            resources: CString::new(format!("file://{}", folder.display())).unwrap(),
            parameters,
            outputs,
        }
    }

    /// The default scene's FMU and the automotive scene's, their resources under `root`.
    pub fn shipped(root: &std::path::Path) -> [Target; 2] {
        let automotive = std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/automotive_rod.toml"),
        )
        .unwrap();
        [
            Target::new(
                "default",
                flexrod::scene::DEFAULT_SCENE_TOML,
                &root.join("default"),
            ),
            Target::new("automotive", &automotive, &root.join("automotive")),
        ]
    }
}

/// Whether `FLEXROD_FUZZ_VERBOSE=1` asks for every parameter a sequence sets (to replay one
/// with `FLEXROD_FUZZ_FIRST=K FLEXROD_FUZZ_RANGES=1`).
fn verbose() -> bool {
    std::env::var_os("FLEXROD_FUZZ_VERBOSE").is_some_and(|v| v == "1")
}

/// Log-uniform in `[a, b]` (`0 < a < b`).
fn log_uniform(rng: &mut Rng, a: f64, b: f64) -> f64 {
    (rng.uniform(a.ln(), b.ln())).exp().clamp(a, b)
}

/// A value of parameter `p` across its whole range; `rod_length` and `area` are the values
/// drawn so far (for the keys bounded by them).
fn draw(rng: &mut Rng, p: &Parameter, rod_length: f64, area: f64) -> f64 {
    let zero_or = |rng: &mut Rng, a: f64, b: f64| {
        if rng.one_in(3) {
            0.0
        } else {
            log_uniform(rng, a, b)
        }
    };
    match p.name.as_str() {
        "rod.length" => log_uniform(rng, 1e-3, 100.0),
        "crank.length" => rod_length * log_uniform(rng, 1e-3, 1.0),
        "rod.youngs_modulus" => log_uniform(rng, 1e5, 1e17),
        "rod.density" => log_uniform(rng, 10.0, 1e5),
        "rod.area" => log_uniform(rng, 1e-10, 1.0),
        "rod.area_moment" => log_uniform(rng, 1e-22, (area * rod_length * rod_length).min(1.0)),
        "rod.damping_ratio" => zero_or(rng, 1e-4, 100.0),
        "slider.mass" => zero_or(rng, 1e-4, 1e6),
        "solver.tolerance" => log_uniform(rng, 1e-10, 0.1),
        "rod.mode_band_hz" => log_uniform(rng, 1.0, 1e6),
        "rod.shear_modulus" => log_uniform(rng, 1e4, 1e17),
        "rod.shear_area" => area * log_uniform(rng, 1e-6, 1.0),
        "rod.big_end.mass" | "rod.small_end.mass" => zero_or(rng, 1e-6, 1e6),
        "rod.big_end.inertia" | "rod.small_end.inertia" => zero_or(rng, 1e-9, 1e6),
        "slider.gas_force_scale" => rng.uniform(0.0, 100.0),
        "rod.deflection_limit" => log_uniform(rng, 1e-6, 1.0),
        "rod.elements" => log_uniform(rng, p.min.max(1.0), p.max + 0.999).floor(),
        "rod.modes" => rng.below(385) as f64,
        _ if !p.real => (p.min + rng.below((p.max - p.min) as usize + 1) as f64).min(p.max),
        _ => f64::NAN,
    }
}

/// Counts of the range generator, and its wall-time limit per call, s.
#[derive(Default, Debug, Clone)]
pub struct Ranges {
    pub limit: f64,
    pub sequences: u64,
    pub parameters_set: u64,
    pub initialized: u64,
    pub refused_at_initialization: u64,
    pub steps: u64,
    pub steps_ok: u64,
    /// Steps refused at the wall-time guard (`WALL_GUARD_SECONDS`) rather than the work budget.
    pub guarded: u64,
    pub slowest_call: f64,
    pub slowest_seed: u64,
    /// The slowest call and the FMU it was made on.
    pub slowest_what: String,
}

impl Ranges {
    pub fn add(&mut self, o: &Ranges) {
        self.sequences += o.sequences;
        self.parameters_set += o.parameters_set;
        self.initialized += o.initialized;
        self.refused_at_initialization += o.refused_at_initialization;
        self.steps += o.steps;
        self.steps_ok += o.steps_ok;
        self.guarded += o.guarded;
        if o.slowest_call > self.slowest_call {
            self.slowest_call = o.slowest_call;
            self.slowest_seed = o.slowest_seed;
            self.slowest_what.clone_from(&o.slowest_what);
        }
    }
}

/// Time `call`; a call past `r.limit` seconds is a violation.
fn timed(
    r: &mut Ranges,
    v: &mut Violations,
    seq: u64,
    what: &str,
    call: impl FnOnce() -> i32,
) -> i32 {
    let t0 = Instant::now();
    let status = call();
    let took = t0.elapsed().as_secs_f64();
    if took > r.slowest_call {
        r.slowest_call = took;
        r.slowest_seed = seq;
        r.slowest_what = what.to_string();
    }
    if took > r.limit {
        v.add(format!(
            "sequence {seq}: {what} took {took:.2} s, past the limit of {} s",
            r.limit
        ));
    }
    if !(OK..=ERROR).contains(&status) {
        v.add(format!("sequence {seq}: {what} answered {status}"));
    }
    status
}

/// One sequence: parameters across their ranges, initialization, steps.
pub fn run(seq: u64, targets: &[Target; 2], r: &mut Ranges, v: &mut Violations) {
    let mut rng = Rng::new(0x5a_0000_0000 ^ seq.wrapping_mul(0x9e37_79b9_7f4a_7c15));
    let target = &targets[rng.below(2)];
    let log = Box::<Log>::default();
    let cb = callbacks(&*log);
    let name = CString::new(target.label).unwrap();
    r.sequences += 1;
    // SAFETY (all calls): strings and buffers valid for the lengths passed; `c` is live until
    // the free at the end.
    unsafe {
        let c = fmi2Instantiate(
            name.as_ptr(),
            1,
            target.guid.as_ptr(),
            target.resources.as_ptr(),
            &cb,
            0,
            0,
        );
        if c.is_null() {
            v.add(format!(
                "sequence {seq}: {} did not instantiate",
                target.label
            ));
            return;
        }
        let mut rod_length = 0.3;
        let mut area = 3e-5;
        // The lengths and the area first: the keys bounded by them follow.
        let order = ["rod.length", "rod.area"];
        let mut params: Vec<&Parameter> = target.parameters.iter().collect();
        params.sort_by_key(|p| !order.contains(&p.name.as_str()));
        for p in params {
            if !rng.one_in(2) {
                continue;
            }
            let x = draw(&mut rng, p, rod_length, area);
            if x.is_nan() {
                continue;
            }
            match p.name.as_str() {
                "rod.length" => rod_length = x,
                "rod.area" => area = x,
                _ => {}
            }
            r.parameters_set += 1;
            let what = format!("setting {} = {x:e}", p.name);
            if verbose() {
                println!("sequence {seq} ({}): {what}", target.label);
            }
            timed(r, v, seq, &what, || {
                if p.real {
                    fmi2SetReal(c, &p.vr, 1, &x)
                } else {
                    let i = x as i32;
                    fmi2SetInteger(c, &p.vr, 1, &i)
                }
            });
        }
        fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0);
        fmi2EnterInitializationMode(c);
        let status = timed(r, v, seq, "fmi2ExitInitializationMode", || {
            fmi2ExitInitializationMode(c)
        });
        if status == OK || status == WARNING {
            r.initialized += 1;
            let mut t = 0.0;
            for _ in 0..3 {
                let h = log_uniform(&mut rng, 1e-6, 1e-2);
                let t0 = Instant::now();
                let s = timed(r, v, seq, &format!("fmi2DoStep(h = {h:e})"), || {
                    fmi2DoStep(c, t, h, 1)
                });
                r.steps += 1;
                if s == ERROR
                    && t0.elapsed().as_secs_f64()
                        >= flexrod::mechanism::stepping::WALL_GUARD_SECONDS
                {
                    r.guarded += 1;
                }
                if s != OK && s != WARNING {
                    break;
                }
                r.steps_ok += 1;
                t += h;
                let mut out = vec![0.0; target.outputs.len()];
                let rs = fmi2GetReal(c, target.outputs.as_ptr(), out.len(), out.as_mut_ptr());
                v.check_values(rs, &out, &format!("sequence {seq}: outputs"));
            }
        } else {
            r.refused_at_initialization += 1;
        }
        fmi2FreeInstance(c);
    }
}
