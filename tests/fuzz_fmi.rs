//! The FMI C boundary fuzzed (harness in `tests/fuzz/`): FMI 2.0 call sequences, and per
//! sequence the extended generators (forged pre-initialization states, in-range extremes with a
//! wall-time oracle, freed and foreign handles, FMI 3.0 sequences; `tests/fuzz/extended.rs`).
//!
//! - `random_call_sequences_keep_the_contract`: seeded sequences of all 34 fmi2 functions in
//!   legal and illegal orders, with the continuation-equivalence oracle (a twin instance gets
//!   the legal calls only and must stay bit-identical). `FLEXROD_FUZZ_SEQUENCES=N` sets the
//!   number of sequences (default 6000, about half a minute),
//!   `FLEXROD_FUZZ_THREADS=T` runs them on T threads (default 1), `FLEXROD_FUZZ_FIRST=K`
//!   starts at sequence K (each sequence has its own seed: a failure is reproduced by its
//!   number alone).
//! - crafted serialized states (valid checksum, edited contents), instantiation arguments,
//!   absurd parameter sets, the segment-chain divergence of the issue, and RSS over
//!   instantiate/free cycles.

mod common;
mod fuzz;

use std::ffi::CStr;
use std::ptr;
use std::time::Instant;

use flexrod::fmi::ffi::lifecycle::*;
use flexrod::fmi::ffi::states::*;
use flexrod::fmi::ffi::stepping::*;
use flexrod::fmi::ffi::values::*;
use flexrod::hash::fnv1a_64;

use fuzz::fmu::{callbacks, null_state, Fmu, Log, Vars, DISCARD, ERROR, OK, WARNING};
use fuzz::hostile::{GET_TYPES_PLATFORM, GET_VERSION, INSTANTIATE};
use fuzz::oracle::{Func, Violations};
use fuzz::rng::Rng;
use fuzz::sequence::{self, Totals};

fn env_u64(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

/// The three functions without an instance, and fmi2Instantiate with bad arguments: each
/// sequence of the harness starts with one of these.
fn instance_free_calls(rng: &mut Rng, vars: &Vars, totals: &mut Totals, v: &mut Violations) {
    // SAFETY: the functions return static strings.
    let (platform, version) = unsafe {
        (
            CStr::from_ptr(fmi2GetTypesPlatform()),
            CStr::from_ptr(fmi2GetVersion()),
        )
    };
    if platform != c"default" || version != c"2.0" {
        v.add(format!(
            "fmi2GetTypesPlatform {platform:?}, fmi2GetVersion {version:?}"
        ));
    }
    totals.counts.functions[GET_TYPES_PLATFORM] += 1;
    totals.counts.functions[GET_VERSION] += 1;
    let log = Log::default();
    let cb = callbacks(&log);
    let wrong_guid = c"{00000000-0000-0000-0000-000000000000}";
    let (name, kind, guid, functions): (*const i8, i32, *const i8, *const _) = match rng.below(6) {
        0 => (ptr::null(), 1, vars.guid.as_ptr(), &cb),
        1 => (c"".as_ptr(), 1, vars.guid.as_ptr(), &cb),
        2 => (c"x".as_ptr(), 1, ptr::null(), &cb),
        3 => (c"x".as_ptr(), 1, wrong_guid.as_ptr(), &cb),
        4 => (
            c"x".as_ptr(),
            rng.pick(&[0, 2, -1, 7]),
            vars.guid.as_ptr(),
            &cb,
        ),
        _ => (c"x".as_ptr(), 1, vars.guid.as_ptr(), ptr::null()),
    };
    // SAFETY: every pointer is NULL or a valid NUL-terminated string / callbacks struct.
    let c = unsafe { fmi2Instantiate(name, kind, guid, ptr::null(), functions, 0, 0) };
    totals.counts.functions[INSTANTIATE] += 1;
    totals.counts.calls += 3;
    totals.counts.refused += 1;
    if !c.is_null() {
        v.add("fmi2Instantiate accepted bad arguments".into());
        // SAFETY: c came from fmi2Instantiate.
        unsafe { fmi2FreeInstance(c) };
    }
    // SAFETY: NULL is ignored.
    unsafe { fmi2FreeInstance(ptr::null_mut()) };
    totals.counts.functions[Func::FreeInstance as usize] += 3; // NULL, subject and twin
}

fn run_range(first: u64, n: u64, vars: &Vars) -> (Totals, Violations) {
    let mut totals = Totals::default();
    let mut violations = Violations::default();
    let mut rng = Rng::new(first);
    for seq in first..first + n {
        instance_free_calls(&mut rng, vars, &mut totals, &mut violations);
        sequence::run(seq, vars, &mut totals, &mut violations);
        fuzz::extended::run(seq, vars, &mut totals.extended, &mut violations);
    }
    (totals, violations)
}

/// Sequences of the short run in the suite (fragment `fuzz-short`).
const DEFAULT_SEQUENCES: u64 = 6000;

/// Sequences from which a run counts as the long mode (fragment `fuzz-long`).
const LONG_RUN: u64 = 500_000;

#[test]
fn random_call_sequences_keep_the_contract() {
    let vars = Vars::default_scene();
    let n = env_u64("FLEXROD_FUZZ_SEQUENCES", DEFAULT_SEQUENCES);
    let first = env_u64("FLEXROD_FUZZ_FIRST", 0);
    let threads = env_u64("FLEXROD_FUZZ_THREADS", 1).max(1);
    let t0 = Instant::now();
    let results: Vec<(Totals, Violations)> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..threads)
            .map(|k| {
                let (a, b) = (first + n * k / threads, first + n * (k + 1) / threads);
                let vars = &vars;
                s.spawn(move || run_range(a, b - a, vars))
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let mut totals = Totals::default();
    let mut violations = Violations::default();
    for (t, v) in results {
        totals.sequences += t.sequences;
        totals.counts.calls += t.counts.calls;
        totals.counts.refused += t.counts.refused;
        for k in 0..34 {
            totals.counts.functions[k] += t.counts.functions[k];
        }
        totals.legal_calls += t.legal_calls;
        totals.hostile_calls += t.hostile_calls;
        totals.steps_accepted += t.steps_accepted;
        totals.steps_discarded += t.steps_discarded;
        totals.segment_sequences += t.segment_sequences;
        totals.panics += t.panics;
        totals.unchanged_refusals += t.unchanged_refusals;
        totals.extended.add(&t.extended);
        violations.count += v.count;
        violations.first.extend(v.first);
    }
    let seconds = t0.elapsed().as_secs_f64();
    println!(
        "fuzz: {} sequences (from {first}, {threads} thread(s)), {} calls ({} legal on both instances, {} hostile), {} refused, {} steps accepted, {} discarded, {} sequences with the segment chain, {} legal steps refused with the instance unchanged (input window or work bound), {} panics caught, contract violations: {}, {seconds:.1} s",
        totals.sequences,
        totals.counts.calls,
        totals.legal_calls,
        totals.hostile_calls,
        totals.counts.refused,
        totals.steps_accepted,
        totals.steps_discarded,
        totals.segment_sequences,
        totals.unchanged_refusals,
        totals.panics,
        violations.count
    );
    println!("calls per function: {:?}", totals.counts.functions);
    println!("extended generators: {:?}", totals.extended);
    for line in &violations.first {
        println!("  {line}");
    }
    assert_eq!(violations.count, 0, "{:#?}", violations.first);
    let least = (0..34)
        .map(|k| totals.counts.functions[k])
        .min()
        .unwrap_or(0);
    let figures = format!(
        "{} sequences (seeds {first} to {}): {} calls, {} of them refused, every one of the 34 fmi2 functions called (the least called {least} times); {} legal calls on both instances of a pair and {} hostile calls on one; {} steps accepted, {} discarded, {} refused with the instance unchanged (the crank law past an input window, or the work bound); {} sequences with the segment chain; {} panics caught; **contract violations: {}**",
        totals.sequences,
        first + n - 1,
        totals.counts.calls,
        totals.counts.refused,
        totals.legal_calls,
        totals.hostile_calls,
        totals.steps_accepted,
        totals.steps_discarded,
        totals.unchanged_refusals,
        totals.segment_sequences,
        totals.panics,
        violations.count,
    );
    let x = &totals.extended;
    let figures = format!(
        "{figures}. Per sequence also: {} forged pre-initialization states ({} refused with fmi2Error and a message, {} calls on the accepted ones), {} in-range extremes (every call within {} s), {} calls on freed or foreign handles (FMI 2.0 and FMI 3.0, every one an error), {} FMI 3.0 sequences of {} calls",
        x.forged_states,
        x.forged_refused,
        x.forged_calls_after,
        x.extremes,
        fuzz::extended::WALL_LIMIT,
        x.stale_handle_calls,
        x.fmi3_sequences,
        x.fmi3_calls,
    );
    if n == DEFAULT_SEQUENCES && first == 0 {
        common::generated::check_generated("fuzz-short", &format!("{figures}.\n"));
    } else if n >= LONG_RUN && common::fragments::blessing() {
        common::generated::check_generated(
            "fuzz-long",
            &format!(
                "{figures}; {:.0} s on {threads} thread(s) ({:.2} ms per sequence and thread).\n",
                seconds,
                seconds * threads as f64 / n as f64 * 1e3,
            ),
        );
    }
    if n >= 100 {
        let missing: Vec<usize> = (0..34)
            .filter(|&k| totals.counts.functions[k] == 0)
            .collect();
        assert!(missing.is_empty(), "functions never called: {missing:?}");
        assert!(
            totals.steps_accepted > 10 * n,
            "too few legal steps: {totals:?}"
        );
        assert!(totals.segment_sequences > 0);
    }
}

/// Sequences of the range generator in the suite (a run this short writes no fragment).
const DEFAULT_RANGE_SEQUENCES: u64 = 300;

/// Sequences from which a run of the range generator counts as the long mode (fragment
/// `fuzz-ranges-long`).
const LONG_RANGE_RUN: u64 = 100_000;

/// Every parameter across its whole declared range, on the default and the automotive FMU
/// (`fuzz::ranges`): statuses and values within the contract, and every call within the
/// documented worst case of one call (`rod::cost::WORST_CALL_SECONDS`) in the long mode, which
/// measures it on an otherwise idle machine (in the suite, within the hang limit). `FLEXROD_FUZZ_RANGES=N` sets the number of sequences,
/// `FLEXROD_FUZZ_THREADS=T` the threads; the long mode (`FLEXROD_BLESS=1
/// FLEXROD_FUZZ_RANGES=100000 FLEXROD_FUZZ_THREADS=2 cargo test --release --test fuzz_fmi
/// ranges -- --nocapture`) writes the fragment `fuzz-ranges-long`.
#[test]
fn parameters_across_their_declared_ranges_take_bounded_time() {
    let n = env_u64("FLEXROD_FUZZ_RANGES", DEFAULT_RANGE_SEQUENCES);
    let first = env_u64("FLEXROD_FUZZ_FIRST", 0);
    let threads = env_u64("FLEXROD_FUZZ_THREADS", 1).max(1);
    // The documented worst case is measured by the long mode; the suite shares its machine
    // with other tests and checks for hangs only.
    let limit = if n >= LONG_RANGE_RUN {
        fuzz::ranges::WORST_CALL
    } else {
        fuzz::extended::WALL_LIMIT
    };
    let root = std::env::temp_dir().join(format!("flexrod-ranges-{}", std::process::id()));
    let targets = fuzz::ranges::Target::shipped(&root);
    let t0 = Instant::now();
    let results: Vec<(fuzz::ranges::Ranges, Violations)> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..threads)
            .map(|k| {
                let (a, b) = (first + n * k / threads, first + n * (k + 1) / threads);
                let targets = &targets;
                s.spawn(move || {
                    let mut r = fuzz::ranges::Ranges {
                        limit,
                        ..Default::default()
                    };
                    let mut v = Violations::default();
                    for seq in a..b {
                        fuzz::ranges::run(seq, targets, &mut r, &mut v);
                    }
                    (r, v)
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let _ = std::fs::remove_dir_all(&root);
    let seconds = t0.elapsed().as_secs_f64();
    let mut r = fuzz::ranges::Ranges::default();
    let mut violations = Violations::default();
    for (x, v) in results {
        r.add(&x);
        violations.count += v.count;
        violations.first.extend(v.first);
    }
    println!(
        "ranges: {r:?}, {seconds:.1} s, contract violations: {}",
        violations.count
    );
    for line in &violations.first {
        println!("  {line}");
    }
    assert_eq!(violations.count, 0, "{:#?}", violations.first);
    assert!(
        r.initialized > 0 && r.refused_at_initialization > 0,
        "{r:?}"
    );
    let figures = format!(
        "{} sequences (seeds {first} to {}) on the default and the automotive FMU: {} parameters set across their declared ranges, {} initializations completed and {} refused with a message, {} communication steps ({} of them fmi2OK or fmi2Warning, {} ended by the wall-time guard); slowest call {:.2} s (sequence {}: {}), every call within {} s; **contract violations: {}**",
        r.sequences,
        first + n - 1,
        r.parameters_set,
        r.initialized,
        r.refused_at_initialization,
        r.steps,
        r.steps_ok,
        r.guarded,
        r.slowest_call,
        r.slowest_seed,
        r.slowest_what,
        limit,
        violations.count,
    );
    if n >= LONG_RANGE_RUN && common::fragments::blessing() {
        common::generated::check_generated(
            "fuzz-ranges-long",
            &format!(
                "{figures}; {seconds:.0} s on {threads} thread(s) ({:.2} ms per sequence and thread).\n",
                seconds * threads as f64 / n as f64 * 1e3,
            ),
        );
    }
}

/// Serialized states with edited contents and a recomputed checksum (the checksum is unkeyed):
/// the FMU refuses them, or accepts a state that it can stand behind (every accepted step's
/// outputs finite and bounded).
#[test]
fn crafted_serialized_states_never_give_garbage() {
    let vars = Vars::default_scene();
    let n = env_u64("FLEXROD_FUZZ_CRAFTED", 300);
    let mut rng = Rng::new(0xc4af7);
    let (mut accepted, mut refused, mut steps_ok) = (0u64, 0u64, 0u64);
    let mut violations = Violations::default();
    for k in 0..n {
        let source = Fmu::new(&vars, "source");
        // SAFETY (all calls): live instances, valid buffers of the lengths passed.
        let bytes = unsafe {
            if rng.one_in(2) {
                let c = source.c;
                fmi2SetInteger(c, &vars.rod_model, 1, &2);
            }
            fmi2EnterInitializationMode(source.c);
            fmi2ExitInitializationMode(source.c);
            for _ in 0..rng.below(20) {
                fmi2DoStep(source.c, 0.0, 0.0, 0); // refused: wrong step, nothing changes
            }
            let mut t = 0.0;
            for _ in 0..rng.below(10) {
                if fmi2DoStep(source.c, t, 1e-4, 0) == OK {
                    t += 1e-4;
                }
            }
            let mut slot = null_state();
            assert_eq!(fmi2GetFMUstate(source.c, &mut slot), OK);
            let mut size = 0;
            assert_eq!(fmi2SerializedFMUstateSize(source.c, slot, &mut size), OK);
            let mut bytes = vec![0u8; size];
            assert_eq!(
                fmi2SerializeFMUstate(source.c, slot, bytes.as_mut_ptr().cast(), size),
                OK
            );
            bytes
        };
        let mut crafted = bytes[..bytes.len() - 8].to_vec();
        for _ in 0..1 + rng.below(4) {
            let at = rng.below(crafted.len());
            match rng.below(3) {
                0 => crafted[at] ^= 1 << rng.below(8),
                1 => crafted[at] = rng.next() as u8,
                // A whole f64 replaced by an abusive value.
                _ => {
                    let x = rng.abusive_real().to_le_bytes();
                    let end = (at + 8).min(crafted.len());
                    crafted[at..end].copy_from_slice(&x[..end - at]);
                }
            }
        }
        let sum = fnv1a_64(&crafted);
        crafted.extend_from_slice(&sum.to_le_bytes());
        let target = Fmu::new(&vars, "target");
        let mut slot = null_state();
        // SAFETY: live instance, valid buffers.
        unsafe {
            let s = fmi2DeSerializeFMUstate(
                target.c,
                crafted.as_ptr().cast(),
                crafted.len(),
                &mut slot,
            );
            if s != OK {
                refused += 1;
                if s != ERROR {
                    violations.add(format!(
                        "crafted state {k}: fmi2DeSerializeFMUstate answered {s}"
                    ));
                }
                continue;
            }
            accepted += 1;
            if fmi2SetFMUstate(target.c, slot) != OK {
                continue;
            }
            let mut t = 0.0;
            fmi2GetRealStatus(target.c, 2, &mut t);
            for _ in 0..5 {
                let s = fmi2DoStep(target.c, t, 1e-4, 0);
                let (rs, values) = {
                    let mut out = vec![0.0; vars.real_outputs.len()];
                    let rs = fmi2GetReal(
                        target.c,
                        vars.real_outputs.as_ptr(),
                        out.len(),
                        out.as_mut_ptr(),
                    );
                    (rs, out)
                };
                if s == OK || s == WARNING {
                    steps_ok += 1;
                    t += 1e-4;
                    violations.check_values(rs, &values, &format!("crafted state {k}"));
                } else if s != DISCARD && s != ERROR {
                    violations.add(format!("crafted state {k}: fmi2DoStep answered {s}"));
                }
            }
        }
    }
    println!(
        "crafted serialized states: {n} ({refused} refused, {accepted} accepted, {steps_ok} steps taken from accepted ones), contract violations: {}",
        violations.count
    );
    assert_eq!(violations.count, 0, "{:#?}", violations.first);
}

/// Absurd parameter sets: each is refused at the set call or at
/// fmi2ExitInitializationMode with fmi2Error and a message, within bounded time; after
/// fmi2Reset the instance runs the default scene exactly as a fresh instance does.
#[test]
fn absurd_parameters_are_refused_and_the_instance_recovers() {
    let vars = Vars::default_scene();
    let vr = |name: &str| {
        flexrod::fmi::description::ModelDescription::for_scene(&flexrod::Scene::benchmark())
            .unwrap()
            .table
            .by_name(name)
            .unwrap()
            .value_reference
    };
    enum P {
        R(&'static str, f64),
        I(&'static str, i32),
    }
    use P::{I, R};
    let sets: Vec<(&str, Vec<P>)> = vec![
        ("rod.modes 10000", vec![I("rod.modes", 10_000)]),
        ("rod.elements 0", vec![I("rod.elements", 0)]),
        ("rod.elements 1e6", vec![I("rod.elements", 1_000_000)]),
        ("negative rod length", vec![R("rod.length", -0.3)]),
        ("negative crank length", vec![R("crank.length", -0.15)]),
        ("crank longer than the rod", vec![R("crank.length", 0.5)]),
        ("zero Young's modulus", vec![R("rod.youngs_modulus", 0.0)]),
        ("denormal density", vec![R("rod.density", 5e-324)]),
        ("huge area", vec![R("rod.area", 1e300)]),
        ("negative damping", vec![R("rod.damping_ratio", -0.1)]),
        ("NaN slider mass", vec![R("slider.mass", f64::NAN)]),
        (
            "segments, 1e6 segments",
            vec![I("rod.model", 2), I("rod.elements", 1_000_000)],
        ),
        (
            "segments, crank longer than the rod",
            vec![I("rod.model", 2), R("crank.length", 0.5)],
        ),
        (
            "segments, zero area",
            vec![I("rod.model", 2), R("rod.area", 0.0)],
        ),
    ];
    let reference = {
        let f = Fmu::new(&vars, "reference");
        run_default(&f, &vars)
    };
    for (name, set) in sets {
        let f = Fmu::new(&vars, "absurd");
        let t0 = Instant::now();
        let errors_before = f.errors_logged();
        let mut refused = false;
        // SAFETY: live instance, arrays of length one.
        unsafe {
            for p in &set {
                let s = match *p {
                    R(n, x) => fmi2SetReal(f.c, &vr(n), 1, &x),
                    I(n, x) => fmi2SetInteger(f.c, &vr(n), 1, &x),
                };
                refused |= s == ERROR;
            }
            if !refused {
                assert_eq!(fmi2EnterInitializationMode(f.c), OK, "{name}");
                let s = fmi2ExitInitializationMode(f.c);
                assert_eq!(s, ERROR, "{name}: fmi2ExitInitializationMode answered {s}");
            }
        }
        let seconds = t0.elapsed().as_secs_f64();
        assert!(
            f.errors_logged() > errors_before,
            "{name}: refused without a message"
        );
        // SAFETY: live instance.
        assert_eq!(unsafe { fmi2Reset(f.c) }, OK, "{name}");
        let after = run_default(&f, &vars);
        assert_eq!(
            after, reference,
            "{name}: the instance differs after fmi2Reset"
        );
        println!("absurd parameters, {name}: refused in {seconds:.3} s, default run identical after fmi2Reset");
    }
}

/// Initialize with the exported start values and take 20 steps of 1e-4 s: the outputs' bits.
fn run_default(f: &Fmu, vars: &Vars) -> Vec<u64> {
    let mut bits = Vec::new();
    // SAFETY: live instance, valid buffers.
    unsafe {
        assert_eq!(fmi2EnterInitializationMode(f.c), OK);
        assert_eq!(fmi2ExitInitializationMode(f.c), OK);
        for k in 0..20 {
            assert_eq!(fmi2DoStep(f.c, k as f64 * 1e-4, 1e-4, 0), OK);
            let mut out = vec![0.0; vars.real_outputs.len()];
            fmi2GetReal(f.c, vars.real_outputs.as_ptr(), out.len(), out.as_mut_ptr());
            bits.extend(out.iter().map(|x| x.to_bits()));
        }
    }
    bits
}

/// A segment chain that diverges (NaN and 1e254 N) must not be answered with fmi2OK. The
/// reproducer, replayed through the C functions: every answer with
/// fmi2OK or fmi2Warning has finite outputs below 1e12, and a refused step keeps the state.
#[test]
fn segment_chain_divergence_reproducer_gives_no_garbage() {
    let vars = Vars::default_scene();
    let d = flexrod::fmi::description::ModelDescription::for_scene(&flexrod::Scene::benchmark())
        .unwrap();
    let vr = |name: &str| d.table.by_name(name).unwrap().value_reference;
    for policy in [1, 2, 3] {
        let f = Fmu::new(&vars, "reproducer");
        let mut violations = Violations::default();
        let mut statuses = Vec::new();
        // SAFETY: live instance, arrays of length one.
        unsafe {
            assert_eq!(fmi2SetReal(f.c, &vr("rod.area"), 1, &0.157), OK);
            assert_eq!(fmi2SetReal(f.c, &vr("rod.damping_ratio"), 1, &10.1), OK);
            assert_eq!(fmi2SetReal(f.c, &vr("slider.mass"), 1, &0.036), OK);
            assert_eq!(fmi2SetInteger(f.c, &vr("rod.model"), 1, &2), OK);
            assert_eq!(fmi2SetInteger(f.c, &vars.rod_policy, 1, &policy), OK);
            assert_eq!(fmi2EnterInitializationMode(f.c), OK);
            let init = fmi2ExitInitializationMode(f.c);
            statuses.push(init);
            if init > WARNING {
                println!("reproducer, policy {policy}: initialization answered {init}");
                continue;
            }
            assert_eq!(fmi2SetReal(f.c, &vr("crank.speed"), 1, &-1163.7), OK);
            let mut t = 0.0;
            let read = || {
                let mut out = vec![0.0; vars.real_outputs.len()];
                let rs = fmi2GetReal(f.c, vars.real_outputs.as_ptr(), out.len(), out.as_mut_ptr());
                (rs, out)
            };
            let mut before = read().1;
            for h in [1.2e-7, 2.15e-4, 2.4e-5, 1e-4, 1e-4, 1e-3] {
                let s = fmi2DoStep(f.c, t, h, 0);
                statuses.push(s);
                let (rs, out) = read();
                violations.check_values(rs, &out, &format!("policy {policy}, h = {h}"));
                if s <= WARNING {
                    t += h;
                    before = out;
                } else {
                    // Refused (discard or error): the outputs are those from before the step.
                    assert_eq!(rs, OK);
                    assert_eq!(out, before, "a refused step keeps the state (time {t})");
                    break;
                }
            }
        }
        println!("reproducer, policy {policy}: statuses {statuses:?}");
        assert_eq!(violations.count, 0, "{:#?}", violations.first);
    }
}

/// The commit the harness runs on (with "+changes" if the work tree differs from it).
fn rss_kb() -> u64 {
    let s = std::fs::read_to_string("/proc/self/status").unwrap();
    let line = s.lines().find(|l| l.starts_with("VmRSS")).unwrap();
    line.split_whitespace().nth(1).unwrap().parse().unwrap()
}

/// RSS before and after many instantiate / initialize / step / state / free cycles stays flat.
/// Measured in a child process of its own ([`rss_cycles`]): the process's RSS is shared with
/// the other tests of this binary, which run in parallel threads and allocate.
#[test]
fn instantiate_free_cycles_do_not_leak() {
    let exe = std::env::current_exe().expect("the test binary");
    let out = std::process::Command::new(exe)
        .args([
            "rss_cycles",
            "--exact",
            "--ignored",
            "--nocapture",
            "--test-threads=1",
        ])
        .output()
        .expect("run the child");
    let text = String::from_utf8_lossy(&out.stdout);
    println!("{text}");
    assert!(
        out.status.success() && text.contains("VmRSS"),
        "the child failed: {text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The cycles of [`instantiate_free_cycles_do_not_leak`], alone in their process.
#[test]
#[ignore = "run by instantiate_free_cycles_do_not_leak in a child process"]
fn rss_cycles() {
    let vars = Vars::default_scene();
    let n = env_u64("FLEXROD_FUZZ_CYCLES", 2000);
    let cycle = || {
        let f = Fmu::new(&vars, "cycle");
        // SAFETY: live instance; the state is left to fmi2FreeInstance.
        unsafe {
            fmi2EnterInitializationMode(f.c);
            fmi2ExitInitializationMode(f.c);
            fmi2DoStep(f.c, 0.0, 1e-4, 0);
            let mut slot = null_state();
            fmi2GetFMUstate(f.c, &mut slot);
        }
    };
    for _ in 0..50 {
        cycle();
    }
    let before = rss_kb();
    let t0 = Instant::now();
    for _ in 0..n {
        cycle();
    }
    let after = rss_kb();
    println!(
        "{n} instantiate/initialize/step/get-state/free cycles: VmRSS {before} kB -> {after} kB, {:.1} s",
        t0.elapsed().as_secs_f64()
    );
    assert!(after < before + 20 * 1024, "{before} -> {after} kB");
    if n >= 100_000 && common::fragments::blessing() {
        common::generated::check_generated(
            "fuzz-rss",
            &format!(
                "{n} cycles of instantiate, initialize, one step, fmi2GetFMUstate and free: VmRSS {before} kB before, {after} kB after ({:+} kB), {:.0} s.\n",
                after as i64 - before as i64,
                t0.elapsed().as_secs_f64()
            ),
        );
    }
}
