//! The calls a hostile or careless master makes, made on the subject instance only (its twin
//! never sees them): every one is either refused (the oracle says `fmi2Error`, or at least not
//! `fmi2OK`) or a query without side effects. The lockstep comparison after the next legal call
//! shows whether any of them changed the instance.

use std::ffi::{c_char, c_int};
use std::ptr;

use flexrod::fmi::ffi::lifecycle::*;
use flexrod::fmi::ffi::states::*;
use flexrod::fmi::ffi::stepping::*;
use flexrod::fmi::ffi::values::*;
use flexrod::fmi::ffi::{fmi2FMUstate, fmi2Status, fmi2String};

use super::fmu::{null_state, Fmu, Vars, ERROR, OK};
use super::oracle::{allowed, Func, State, Violations, RESTRICTED};
use super::rng::Rng;

/// What the contract says of a call.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Expect {
    /// `fmi2Error` with a message through the logger.
    Error,
    /// Anything but `fmi2OK` and `fmi2Warning`.
    Refused,
    /// A query: any status, no side effect.
    Query,
}

/// The subject's FMU states that the twin does not share, and stale copies of freed handles.
#[derive(Default)]
pub struct OwnStates {
    pub live: Vec<fmi2FMUstate>,
    pub freed: Vec<fmi2FMUstate>,
    /// Serialized bytes of a state of this instance (for corruption).
    pub bytes: Vec<u8>,
}

/// What the hostile call needs to know of the sequence.
pub struct Context<'a> {
    pub vars: &'a Vars,
    pub subject: &'a Fmu,
    pub state: State,
    /// The subject's time (for wrong communication points).
    pub time: f64,
    /// Handles of the twin instance (foreign to the subject).
    pub twin_states: &'a [fmi2FMUstate],
}

/// Counts of one run.
#[derive(Debug, Clone, Copy)]
pub struct Counts {
    pub calls: u64,
    pub refused: u64,
    pub functions: [u64; 34],
}

impl Default for Counts {
    fn default() -> Counts {
        Counts {
            calls: 0,
            refused: 0,
            functions: [0; 34],
        }
    }
}

/// Index of each function in [`Counts::functions`] (the 31 of [`Func`], then
/// `fmi2GetTypesPlatform`, `fmi2GetVersion`, `fmi2Instantiate`).
pub fn index(f: Func) -> usize {
    f as usize
}
pub const GET_TYPES_PLATFORM: usize = 31;
pub const GET_VERSION: usize = 32;
pub const INSTANTIATE: usize = 33;

const VALUES: usize = 4;

/// One hostile call on `cx.subject`; returns the function, its status and what the contract
/// says of it.
pub fn call(rng: &mut Rng, cx: &Context<'_>, own: &mut OwnStates) -> (Func, fmi2Status, Expect) {
    let c = cx.subject.c;
    let vars = cx.vars;
    let mut reals = [0.0f64; VALUES];
    let mut ints = [0 as c_int; VALUES];
    let mut status_out: fmi2Status = 0;
    // SAFETY (every call below): a live instance; pointers are NULL where the case says so and
    // otherwise valid for the lengths passed.
    unsafe {
        match rng.below(24) {
            // A call the current state does not allow, with otherwise valid arguments.
            0..=3 => {
                let candidates: Vec<Func> = RESTRICTED
                    .iter()
                    .copied()
                    .filter(|&f| !allowed(f, cx.state))
                    .collect();
                let f = rng.pick(&candidates);
                (f, call_in_wrong_state(f, c, cx.time), Expect::Error)
            }
            // NULL where an array is needed.
            4 => {
                let vr = [vars.real_outputs[0]; 2];
                let (f, s) = match rng.below(8) {
                    0 => (
                        Func::GetReal,
                        fmi2GetReal(c, ptr::null(), 2, reals.as_mut_ptr()),
                    ),
                    1 => (
                        Func::GetReal,
                        fmi2GetReal(c, vr.as_ptr(), 2, ptr::null_mut()),
                    ),
                    2 => (
                        Func::SetReal,
                        fmi2SetReal(c, ptr::null(), 2, reals.as_ptr()),
                    ),
                    3 => (Func::SetReal, fmi2SetReal(c, vr.as_ptr(), 2, ptr::null())),
                    4 => (
                        Func::GetInteger,
                        fmi2GetInteger(c, ptr::null(), 1, ints.as_mut_ptr()),
                    ),
                    5 => (
                        Func::SetInteger,
                        fmi2SetInteger(c, vr.as_ptr(), 1, ptr::null()),
                    ),
                    6 => (
                        Func::GetBoolean,
                        fmi2GetBoolean(c, vr.as_ptr(), 1, ptr::null_mut()),
                    ),
                    _ => (
                        Func::SetString,
                        fmi2SetString(c, vr.as_ptr(), 1, ptr::null()),
                    ),
                };
                (f, s, Expect::Error)
            }
            // Unknown value references and wrong type families.
            5 => {
                let vr = [unknown_vr(rng, vars)];
                let (f, s) = match rng.below(6) {
                    0 => (
                        Func::GetReal,
                        fmi2GetReal(c, vr.as_ptr(), 1, reals.as_mut_ptr()),
                    ),
                    1 => (
                        Func::SetReal,
                        fmi2SetReal(c, vr.as_ptr(), 1, [0.1].as_ptr()),
                    ),
                    2 => (
                        Func::GetInteger,
                        fmi2GetInteger(c, vr.as_ptr(), 1, ints.as_mut_ptr()),
                    ),
                    3 => (
                        Func::SetInteger,
                        fmi2SetInteger(c, vr.as_ptr(), 1, [1].as_ptr()),
                    ),
                    4 => {
                        let real = [rng.pick(&vars.all_reals)];
                        (
                            Func::SetInteger,
                            fmi2SetInteger(c, real.as_ptr(), 1, [1].as_ptr()),
                        )
                    }
                    _ => {
                        let int = [rng.pick(&vars.all_integers)];
                        (
                            Func::GetReal,
                            fmi2GetReal(c, int.as_ptr(), 1, reals.as_mut_ptr()),
                        )
                    }
                };
                (f, s, Expect::Error)
            }
            // Booleans and Strings: the FMU has none.
            6 => {
                let vr = [rng.below(300) as u32];
                let text: [fmi2String; 1] = [if rng.one_in(2) {
                    c"x".as_ptr()
                } else {
                    ptr::null()
                }];
                let mut strings: [fmi2String; 1] = [ptr::null()];
                let (f, s) = match rng.below(4) {
                    0 => (
                        Func::GetBoolean,
                        fmi2GetBoolean(c, vr.as_ptr(), 1, ints.as_mut_ptr()),
                    ),
                    1 => (
                        Func::SetBoolean,
                        fmi2SetBoolean(c, vr.as_ptr(), 1, [1].as_ptr()),
                    ),
                    2 => (
                        Func::GetString,
                        fmi2GetString(c, vr.as_ptr(), 1, strings.as_mut_ptr()),
                    ),
                    _ => (
                        Func::SetString,
                        fmi2SetString(c, vr.as_ptr(), 1, text.as_ptr()),
                    ),
                };
                (f, s, Expect::Error)
            }
            // Non-finite values for Real inputs and parameters; outputs and calculated
            // parameters set; parameters set after initialization.
            7 => {
                let (vr, v) = match rng.below(4) {
                    0 => (rng.pick(&vars.real_inputs), rng.pick(&NON_FINITE)),
                    1 => (param_real(rng, vars), rng.pick(&NON_FINITE)),
                    2 => (rng.pick(&vars.real_outputs), 0.5),
                    _ => (rng.pick(&vars.calculated), 1.0),
                };
                let s = fmi2SetReal(c, [vr].as_ptr(), 1, [v].as_ptr());
                (Func::SetReal, s, Expect::Error)
            }
            8 if !matches!(cx.state, State::Instantiated | State::Init) => {
                let p = rng.pick(&vars.parameters);
                let s = if p.real {
                    fmi2SetReal(c, [p.vr].as_ptr(), 1, [p.start].as_ptr())
                } else {
                    fmi2SetInteger(c, [p.vr].as_ptr(), 1, [p.start as c_int].as_ptr())
                };
                let f = if p.real {
                    Func::SetReal
                } else {
                    Func::SetInteger
                };
                (f, s, Expect::Error)
            }
            // Experiments with a non-finite start, a stop before the start or a NaN stop.
            9 if cx.state == State::Instantiated && rng.one_in(3) => {
                let (start, defined, stop) = rng.pick(&[
                    (f64::NAN, 0, 0.0),
                    (f64::INFINITY, 0, 0.0),
                    (0.0, 1, -1.0),
                    (0.0, 1, f64::NAN),
                    (1.0, 1, 0.5),
                ]);
                let s = fmi2SetupExperiment(c, 0, 0.0, start, defined, stop);
                (Func::SetupExperiment, s, Expect::Error)
            }
            // Integers and enumerations out of their declared range (refused at the set call).
            8 | 9 => {
                let (vr, v) = match rng.below(4) {
                    0 => (vars.rod_model, rng.pick(&[0, 5, -1, i32::MAX, i32::MIN])),
                    1 => (
                        vars.rod_elements,
                        rng.pick(&[0, -1, 129, 1_000_000, i32::MAX]),
                    ),
                    2 => (vars.rod_modes, rng.pick(&[-1, i32::MIN])),
                    _ => (vars.rod_policy, rng.pick(&[0, 4, -3])),
                };
                let s = fmi2SetInteger(c, [vr].as_ptr(), 1, [v].as_ptr());
                (Func::SetInteger, s, Expect::Error)
            }
            // Bad input derivatives: order <= 0, unknown or non-input reference, non-finite.
            10 => {
                let (vr, order, v) = match rng.below(4) {
                    0 => (vars.real_inputs[1], rng.pick(&[0, -1, i32::MIN]), 10.0),
                    1 => (unknown_vr(rng, vars), 1, 10.0),
                    2 => (rng.pick(&vars.real_outputs), 1, 10.0),
                    _ => (vars.real_inputs[1], 1, rng.pick(&NON_FINITE)),
                };
                let s = fmi2SetRealInputDerivatives(
                    c,
                    [vr].as_ptr(),
                    1,
                    [order].as_ptr(),
                    [v].as_ptr(),
                );
                (Func::SetRealInputDerivatives, s, Expect::Error)
            }
            // Bad communication points and step sizes.
            11 | 12 => {
                let (t, h) = if rng.one_in(2) {
                    let wrong = rng.pick(&[1.0, -1.0, 1e-6, f64::NAN, f64::INFINITY, 1e300]);
                    (cx.time + wrong, 1e-4)
                } else {
                    let bad = [0.0, -0.0, -1e-4, f64::NAN, f64::INFINITY, f64::NEG_INFINITY];
                    (cx.time, rng.pick(&bad))
                };
                (
                    Func::DoStep,
                    fmi2DoStep(c, t, h, rng.below(2) as i32),
                    Expect::Error,
                )
            }
            // Communication steps whose internal work is beyond the bound: refused, state kept.
            13 if rng.one_in(64) => {
                let h = rng.pick(&[1e9, 1e300, f64::MAX]);
                (Func::DoStep, fmi2DoStep(c, cx.time, h, 0), Expect::Error)
            }
            // Bad FMU state handles: NULL, a random address, the twin's, freed ones.
            13..=15 => {
                let h = bad_handle(rng, cx, own);
                match rng.below(4) {
                    0 => (Func::SetFMUstate, fmi2SetFMUstate(c, h), Expect::Error),
                    1 => {
                        let mut slot = h;
                        // NULL slot content frees nothing and is fmi2OK (the handle is NULL).
                        let expect = if h.is_null() {
                            Expect::Query
                        } else {
                            Expect::Error
                        };
                        (Func::FreeFMUstate, fmi2FreeFMUstate(c, &mut slot), expect)
                    }
                    2 => {
                        let mut size = 0usize;
                        let s = fmi2SerializedFMUstateSize(c, h, &mut size);
                        (Func::SerializedFMUstateSize, s, Expect::Error)
                    }
                    _ => {
                        let mut buf = [0u8; 64];
                        let s = fmi2SerializeFMUstate(c, h, buf.as_mut_ptr().cast(), buf.len());
                        (Func::SerializeFMUstate, s, Expect::Error)
                    }
                }
            }
            // NULL outputs of the state functions and the status queries.
            16 => {
                let live = own.live.first().copied().unwrap_or(null_state());
                let vr = [vars.real_inputs[1]];
                let (f, s) = match rng.below(16) {
                    0 => (Func::GetFMUstate, fmi2GetFMUstate(c, ptr::null_mut())),
                    6 => (
                        Func::GetRealStatus,
                        fmi2GetRealStatus(c, 2, ptr::null_mut()),
                    ),
                    7 => (
                        Func::GetIntegerStatus,
                        fmi2GetIntegerStatus(c, 0, ptr::null_mut()),
                    ),
                    8 => (
                        Func::GetBooleanStatus,
                        fmi2GetBooleanStatus(c, 3, ptr::null_mut()),
                    ),
                    9 => (
                        Func::GetStringStatus,
                        fmi2GetStringStatus(c, 1, ptr::null_mut()),
                    ),
                    10 => (
                        Func::SetRealInputDerivatives,
                        fmi2SetRealInputDerivatives(
                            c,
                            ptr::null(),
                            1,
                            [1].as_ptr(),
                            [1.0].as_ptr(),
                        ),
                    ),
                    11 => (
                        Func::SetRealInputDerivatives,
                        fmi2SetRealInputDerivatives(c, vr.as_ptr(), 1, ptr::null(), [1.0].as_ptr()),
                    ),
                    12 => (
                        Func::SetRealInputDerivatives,
                        fmi2SetRealInputDerivatives(c, vr.as_ptr(), 1, [1].as_ptr(), ptr::null()),
                    ),
                    13 => (
                        Func::SerializeFMUstate,
                        fmi2SerializeFMUstate(c, live, ptr::null_mut(), 100),
                    ),
                    14 => (
                        Func::GetString,
                        fmi2GetString(c, vr.as_ptr(), 1, ptr::null_mut()),
                    ),
                    15 => (
                        Func::SetBoolean,
                        fmi2SetBoolean(c, vr.as_ptr(), 1, ptr::null()),
                    ),
                    1 => (Func::FreeFMUstate, fmi2FreeFMUstate(c, ptr::null_mut())),
                    2 => (
                        Func::SerializedFMUstateSize,
                        fmi2SerializedFMUstateSize(c, live, ptr::null_mut()),
                    ),
                    3 => (
                        Func::DeSerializeFMUstate,
                        fmi2DeSerializeFMUstate(c, ptr::null(), 16, &mut null_state()),
                    ),
                    4 => (Func::GetStatus, fmi2GetStatus(c, 0, ptr::null_mut())),
                    _ => (
                        Func::SetDebugLogging,
                        fmi2SetDebugLogging(c, 1, 2, ptr::null()),
                    ),
                };
                (f, s, Expect::Error)
            }
            // Serialized states: truncated, corrupted, random, too small a buffer.
            17 | 18 => {
                if own.bytes.is_empty() || rng.one_in(8) {
                    refresh_bytes(c, own);
                }
                let mut bytes = own.bytes.clone();
                let f = Func::DeSerializeFMUstate;
                match rng.below(4) {
                    0 if !bytes.is_empty() => {
                        bytes.truncate(rng.below(bytes.len()));
                    }
                    1 if !bytes.is_empty() => {
                        let k = rng.below(bytes.len());
                        bytes[k] ^= 1 << rng.below(8);
                    }
                    2 => {
                        let n = rng.below(600);
                        bytes = rng.bytes(n);
                    }
                    _ => {
                        let live = own.live.first().copied().unwrap_or(null_state());
                        let mut size = 0usize;
                        fmi2SerializedFMUstateSize(c, live, &mut size);
                        let mut small = vec![0u8; size.saturating_sub(1)];
                        let s =
                            fmi2SerializeFMUstate(c, live, small.as_mut_ptr().cast(), small.len());
                        return (Func::SerializeFMUstate, s, Expect::Error);
                    }
                }
                let mut slot = null_state();
                let s = fmi2DeSerializeFMUstate(c, bytes.as_ptr().cast(), bytes.len(), &mut slot);
                (f, s, Expect::Error)
            }
            // Status queries of kinds that do not exist or this FMU cannot provide.
            19 => {
                let kind = rng.pick(&[-1, 5, 7, 1000, 1]);
                let mut r = 0.0;
                let mut text: fmi2String = ptr::null();
                let (f, s) = match rng.below(5) {
                    0 => (Func::GetStatus, fmi2GetStatus(c, kind, &mut status_out)),
                    1 => (Func::GetRealStatus, fmi2GetRealStatus(c, kind, &mut r)),
                    2 => (
                        Func::GetIntegerStatus,
                        fmi2GetIntegerStatus(c, kind, &mut ints[0]),
                    ),
                    3 => (
                        Func::GetBooleanStatus,
                        fmi2GetBooleanStatus(c, kind, &mut ints[0]),
                    ),
                    _ => (
                        Func::GetStringStatus,
                        fmi2GetStringStatus(c, kind, &mut text),
                    ),
                };
                (f, s, Expect::Refused)
            }
            // Unknown log categories; functions this FMU does not provide.
            20 => {
                let names: [fmi2String; 2] = [c"logEvents".as_ptr(), c"logNothing".as_ptr()];
                match rng.below(4) {
                    0 => (
                        Func::SetDebugLogging,
                        fmi2SetDebugLogging(c, 1, 2, names.as_ptr()),
                        Expect::Error,
                    ),
                    1 => (Func::CancelStep, fmi2CancelStep(c), Expect::Error),
                    2 => {
                        let vr = [vars.real_outputs[0]];
                        let known = [vars.real_inputs[0]];
                        let s = fmi2GetDirectionalDerivative(
                            c,
                            vr.as_ptr(),
                            1,
                            known.as_ptr(),
                            1,
                            [1.0].as_ptr(),
                            reals.as_mut_ptr(),
                        );
                        (Func::GetDirectionalDerivative, s, Expect::Error)
                    }
                    _ => {
                        let vr = [vars.real_outputs[0]];
                        let s = fmi2GetRealOutputDerivatives(
                            c,
                            vr.as_ptr(),
                            1,
                            [1].as_ptr(),
                            reals.as_mut_ptr(),
                        );
                        (Func::GetRealOutputDerivatives, s, Expect::Error)
                    }
                }
            }
            // Queries: every value, status, logging switches.
            21 => {
                let n = rng.below(VALUES) + 1;
                let vr: Vec<u32> = (0..n).map(|_| rng.pick(&vars.all_reals)).collect();
                let s = fmi2GetReal(c, vr.as_ptr(), n, reals.as_mut_ptr());
                (Func::GetReal, s, Expect::Query)
            }
            // FMU states of the subject alone: get, serialize, deserialize, free.
            22 => match rng.below(4) {
                0 => {
                    let mut slot = null_state();
                    let s = fmi2GetFMUstate(c, &mut slot);
                    if s == OK {
                        own.live.push(slot);
                    }
                    (Func::GetFMUstate, s, Expect::Query)
                }
                1 => {
                    refresh_bytes(c, own);
                    let mut slot = null_state();
                    let bytes = &own.bytes;
                    let s =
                        fmi2DeSerializeFMUstate(c, bytes.as_ptr().cast(), bytes.len(), &mut slot);
                    if s == OK {
                        own.live.push(slot);
                    }
                    (Func::DeSerializeFMUstate, s, Expect::Query)
                }
                _ if !own.live.is_empty() => {
                    let k = rng.below(own.live.len());
                    let mut slot = own.live.swap_remove(k);
                    let copy = slot;
                    let s = fmi2FreeFMUstate(c, &mut slot);
                    if s == OK {
                        own.freed.push(copy);
                        // fmi2FreeFMUstate sets the handle to NULL: a second free of it is a
                        // no-op.
                        let again = fmi2FreeFMUstate(c, &mut slot);
                        if again != OK || !slot.is_null() {
                            return (Func::FreeFMUstate, ERROR, Expect::Query);
                        }
                    }
                    (Func::FreeFMUstate, s, Expect::Query)
                }
                _ => (
                    Func::SetDebugLogging,
                    fmi2SetDebugLogging(c, rng.below(2) as i32, 0, ptr::null()),
                    Expect::Query,
                ),
            },
            // The slave status where it is available.
            _ => {
                let s = fmi2GetStatus(c, 0, &mut status_out);
                (Func::GetStatus, s, Expect::Query)
            }
        }
    }
}

const NON_FINITE: [f64; 3] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY];

/// A value reference of no variable of the FMU.
fn unknown_vr(rng: &mut Rng, vars: &Vars) -> u32 {
    loop {
        let vr = match rng.below(3) {
            0 => rng.pick(&[0, 4, 9, 19, 99, 108, 117, 199, 250, 999, u32::MAX]),
            1 => rng.next() as u32,
            _ => rng.below(300) as u32,
        };
        if !vars.is_real(vr) && !vars.is_integer(vr) {
            return vr;
        }
    }
}

fn param_real(rng: &mut Rng, vars: &Vars) -> u32 {
    loop {
        let p = rng.pick(&vars.parameters);
        if p.real {
            return p.vr;
        }
    }
}

/// A handle the subject must refuse: NULL, a random address, the twin's, or a freed one.
fn bad_handle(rng: &mut Rng, cx: &Context<'_>, own: &OwnStates) -> fmi2FMUstate {
    match rng.below(4) {
        0 => null_state(),
        1 => ptr::without_provenance_mut(rng.next() as usize | 1),
        2 if !cx.twin_states.is_empty() => rng.pick(cx.twin_states),
        3 if !own.freed.is_empty() => rng.pick(&own.freed),
        _ => ptr::without_provenance_mut(0xdead_beef),
    }
}

/// Serialize a fresh state of the subject into `own.bytes` (the state is freed again).
fn refresh_bytes(c: flexrod::fmi::ffi::fmi2Component, own: &mut OwnStates) {
    // SAFETY: live instance, writable slots and buffers of the lengths passed.
    unsafe {
        let mut slot = null_state();
        if fmi2GetFMUstate(c, &mut slot) != OK {
            return;
        }
        let mut size = 0usize;
        if fmi2SerializedFMUstateSize(c, slot, &mut size) == OK {
            let mut bytes = vec![0u8; size];
            if fmi2SerializeFMUstate(c, slot, bytes.as_mut_ptr().cast(), size) == OK {
                own.bytes = bytes;
            }
        }
        fmi2FreeFMUstate(c, &mut slot);
    }
}

/// `f` with valid arguments (no values where a list is taken), for the illegal-order check.
///
/// # Safety
/// `c` is a live instance.
unsafe fn call_in_wrong_state(
    f: Func,
    c: flexrod::fmi::ffi::fmi2Component,
    time: f64,
) -> fmi2Status {
    let vr = [0u32];
    let mut x = [0.0f64];
    let mut i = [0 as c_int];
    let mut s: fmi2Status = 0;
    let mut text: *const c_char = ptr::null();
    // SAFETY: zero-length arrays and writable outputs.
    unsafe {
        match f {
            Func::SetupExperiment => fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0),
            Func::EnterInitializationMode => fmi2EnterInitializationMode(c),
            Func::ExitInitializationMode => fmi2ExitInitializationMode(c),
            Func::Terminate => fmi2Terminate(c),
            Func::GetReal => fmi2GetReal(c, vr.as_ptr(), 0, x.as_mut_ptr()),
            Func::GetInteger => fmi2GetInteger(c, vr.as_ptr(), 0, i.as_mut_ptr()),
            Func::GetBoolean => fmi2GetBoolean(c, vr.as_ptr(), 0, i.as_mut_ptr()),
            Func::GetString => fmi2GetString(c, vr.as_ptr(), 0, &mut text),
            Func::SetReal => fmi2SetReal(c, vr.as_ptr(), 0, x.as_ptr()),
            Func::SetInteger => fmi2SetInteger(c, vr.as_ptr(), 0, i.as_ptr()),
            Func::SetBoolean => fmi2SetBoolean(c, vr.as_ptr(), 0, i.as_ptr()),
            Func::SetString => fmi2SetString(c, vr.as_ptr(), 0, &text),
            Func::GetDirectionalDerivative => fmi2GetDirectionalDerivative(
                c,
                vr.as_ptr(),
                0,
                vr.as_ptr(),
                0,
                x.as_ptr(),
                x.as_mut_ptr(),
            ),
            Func::SetRealInputDerivatives => {
                fmi2SetRealInputDerivatives(c, vr.as_ptr(), 0, i.as_ptr(), x.as_ptr())
            }
            Func::GetRealOutputDerivatives => {
                fmi2GetRealOutputDerivatives(c, vr.as_ptr(), 0, i.as_ptr(), x.as_mut_ptr())
            }
            Func::DoStep => fmi2DoStep(c, time, 1e-4, 0),
            Func::CancelStep => fmi2CancelStep(c),
            Func::GetStatus => fmi2GetStatus(c, 0, &mut s),
            Func::GetRealStatus => fmi2GetRealStatus(c, 2, &mut x[0]),
            Func::GetIntegerStatus => fmi2GetIntegerStatus(c, 0, &mut i[0]),
            Func::GetBooleanStatus => fmi2GetBooleanStatus(c, 4, &mut i[0]),
            Func::GetStringStatus => fmi2GetStringStatus(c, 3, &mut text),
            other => panic!("{other:?} is allowed in every state"),
        }
    }
}

/// Whether a hostile call's status keeps the contract; the instance's error count before the
/// call tells whether an error was logged.
pub fn judge(
    f: Func,
    status: fmi2Status,
    expect: Expect,
    errors_before: u64,
    subject: &Fmu,
    violations: &mut Violations,
    seq: u64,
) {
    let refused = status != OK && status != 1;
    match expect {
        Expect::Error if status != ERROR => violations.add(format!(
            "sequence {seq}: fmi2{f:?} answered {status}, the contract says fmi2Error"
        )),
        Expect::Refused if !refused => violations.add(format!(
            "sequence {seq}: fmi2{f:?} answered {status}, the contract says it must refuse"
        )),
        _ => {}
    }
    if status == ERROR && subject.has_logger() && subject.errors_logged() <= errors_before {
        violations.add(format!(
            "sequence {seq}: fmi2{f:?} answered fmi2Error without a message to the logger"
        ));
    }
}
