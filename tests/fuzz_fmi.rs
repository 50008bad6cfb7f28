//! Issue 14, 3 (partial): random call sequences through the exported C functions, in process.
//! Seeded SplitMix64; a subset of the fmi2 functions (instantiate, setup, initialization,
//! setReal/getReal with random value references and values, doStep with random steps, FMU
//! states, reset, free). Contract checks: no crash or hang, no non-finite output with fmi2OK.
//! `FLEXROD_FUZZ_SEQUENCES=N` sets the number of sequences (default 200).

use std::ffi::CString;
use std::ptr;

use flexrod::fmi::description::ModelDescription;
use flexrod::fmi::ffi::lifecycle::*;
use flexrod::fmi::ffi::states::*;
use flexrod::fmi::ffi::stepping::*;
use flexrod::fmi::ffi::values::*;
use flexrod::fmi::ffi::{fmi2CallbackFunctions, fmi2Component};
use flexrod::Scene;

struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
    fn real(&mut self) -> f64 {
        const SPECIAL: [f64; 9] = [
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            5e-324,
            1e300,
            -1e300,
            0.0,
            -1.0,
            1e-12,
        ];
        if self.below(4) == 0 {
            SPECIAL[self.below(SPECIAL.len() as u64) as usize]
        } else {
            (self.below(2_000_001) as f64 - 1e6) * 1e-3
        }
    }
}

const OK: i32 = 0;
const OUTPUT_VRS: [u32; 9] = [10, 11, 12, 13, 14, 15, 16, 17, 18];

fn instantiate(guid: &CString, callbacks: &fmi2CallbackFunctions) -> fmi2Component {
    let name = CString::new("fuzz").unwrap();
    unsafe {
        fmi2Instantiate(
            name.as_ptr(),
            1,
            guid.as_ptr(),
            ptr::null(),
            callbacks,
            0,
            0,
        )
    }
}

fn callbacks() -> fmi2CallbackFunctions {
    fmi2CallbackFunctions {
        logger: None,
        allocate_memory: None,
        free_memory: None,
        step_finished: None,
        component_environment: ptr::null_mut(),
    }
}

fn rss_kb() -> u64 {
    let s = std::fs::read_to_string("/proc/self/status").unwrap();
    let line = s.lines().find(|l| l.starts_with("VmRSS")).unwrap();
    line.split_whitespace().nth(1).unwrap().parse().unwrap()
}

#[test]
fn random_call_sequences_keep_the_contract() {
    let guid = CString::new(
        ModelDescription::for_scene(&Scene::benchmark())
            .unwrap()
            .guid,
    )
    .unwrap();
    let cb = callbacks();
    let sequences: u64 = std::env::var("FLEXROD_FUZZ_SEQUENCES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(200);
    let mut rng = SplitMix64(0x14);
    let (mut calls, mut refused, mut violations) = (0u64, 0u64, 0u64);
    let t0 = std::time::Instant::now();
    for _ in 0..sequences {
        let c = instantiate(&guid, &cb);
        assert!(!c.is_null(), "the default scene instantiates");
        let mut time = 0.0f64;
        let mut states: Vec<*mut std::ffi::c_void> = Vec::new();
        for _ in 0..(5 + rng.below(40)) {
            calls += 1;
            let status = unsafe {
                match rng.below(12) {
                    0 => fmi2SetupExperiment(c, 0, 0.0, rng.real(), 0, 0.0),
                    1 => fmi2EnterInitializationMode(c),
                    2 => fmi2ExitInitializationMode(c),
                    3..=5 => {
                        let h = if rng.below(3) == 0 { rng.real() } else { 1e-4 };
                        let t = if rng.below(8) == 0 { rng.real() } else { time };
                        let s = fmi2DoStep(c, t, h, 1);
                        if s == OK {
                            time += h;
                            let mut out = [0.0; 9];
                            if fmi2GetReal(c, OUTPUT_VRS.as_ptr(), 9, out.as_mut_ptr()) == OK
                                && out.iter().any(|x| !x.is_finite())
                            {
                                violations += 1;
                            }
                        }
                        s
                    }
                    6 => {
                        let vr = [rng.below(200) as u32];
                        let v = [rng.real()];
                        fmi2SetReal(c, vr.as_ptr(), 1, v.as_ptr())
                    }
                    7 => {
                        let vr = [rng.below(200) as u32];
                        let mut v = [0.0];
                        let s = fmi2GetReal(c, vr.as_ptr(), 1, v.as_mut_ptr());
                        if s == OK && !v[0].is_finite() {
                            violations += 1;
                        }
                        s
                    }
                    8 => {
                        let mut st: *mut std::ffi::c_void = ptr::null_mut();
                        let s = fmi2GetFMUstate(c, &mut st);
                        if s == OK {
                            states.push(st);
                        }
                        s
                    }
                    9 if !states.is_empty() => {
                        let st = states[rng.below(states.len() as u64) as usize];
                        let s = fmi2SetFMUstate(c, st);
                        if s == OK {
                            let mut t = [0.0];
                            let vr = [0u32];
                            let _ = fmi2GetReal(c, vr.as_ptr(), 0, t.as_mut_ptr());
                            time = f64::NAN; // unknown here: the next steps use a random time
                        }
                        s
                    }
                    10 => {
                        let s = fmi2Reset(c);
                        if s == OK {
                            time = 0.0;
                            states.clear(); // reset frees nothing the importer owns; drop ours
                        }
                        s
                    }
                    _ => fmi2GetReal(c, ptr::null(), 3, ptr::null_mut()),
                }
            };
            if status != OK && status != 1 {
                refused += 1;
            }
            if time.is_nan() {
                time = 0.0;
            }
        }
        unsafe { fmi2FreeInstance(c) };
    }
    println!(
        "fuzz: {sequences} sequences, {calls} calls, {refused} refused, contract violations: {violations}, {:.1} s",
        t0.elapsed().as_secs_f64()
    );
    assert_eq!(violations, 0);
}

/// RSS before and after many instantiate/free cycles stays flat.
#[test]
fn instantiate_free_cycles_do_not_leak() {
    let guid = CString::new(
        ModelDescription::for_scene(&Scene::benchmark())
            .unwrap()
            .guid,
    )
    .unwrap();
    let cb = callbacks();
    let n: usize = std::env::var("FLEXROD_FUZZ_CYCLES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2000);
    let c = instantiate(&guid, &cb);
    unsafe { fmi2FreeInstance(c) };
    let before = rss_kb();
    for _ in 0..n {
        let c = instantiate(&guid, &cb);
        assert!(!c.is_null());
        unsafe { fmi2FreeInstance(c) };
    }
    let after = rss_kb();
    println!("{n} instantiate/free cycles: VmRSS {before} kB -> {after} kB");
    assert!(after < before + 20 * 1024, "{before} -> {after} kB");
}
