//! The legal stream: calls a correct master may make in the state the instance is in, made on
//! both instances of a pair (subject and twin) with the same arguments. Parameters may be
//! absurd (negative lengths, a crank longer than the rod, `rod.modes` 10 000): the FMU must
//! refuse them cleanly, and both instances must refuse them alike.

use std::ffi::c_int;

use flexrod::fmi::ffi::lifecycle::*;
use flexrod::fmi::ffi::states::*;
use flexrod::fmi::ffi::stepping::*;
use flexrod::fmi::ffi::values::*;
use flexrod::fmi::ffi::{fmi2Component, fmi2FMUstate, fmi2Status};

use super::fmu::{null_state, Vars, OK};
use super::oracle::{Func, State};
use super::rng::Rng;

/// A state saved on both instances at the same point, with what the oracle knows of it.
#[derive(Clone, Copy)]
pub struct SavedPair {
    pub subject: fmi2FMUstate,
    pub twin: fmi2FMUstate,
    pub state: State,
    pub time: f64,
    /// The stop time of the experiment the state holds.
    pub stop: Option<f64>,
}

/// The oracle's view of a pair of instances.
pub struct Model {
    pub state: State,
    pub time: f64,
    pub start_time: f64,
    pub stop: Option<f64>,
    pub saved: Vec<SavedPair>,
}

/// One legal call, with its arguments drawn once and applied to an instance.
#[derive(Clone, Debug)]
pub enum Op {
    SetupExperiment { start: f64, stop: Option<f64> },
    Enter,
    Exit,
    SetReal { vr: u32, value: f64 },
    SetInteger { vr: u32, value: c_int },
    InputDerivative { vr: u32, order: c_int, value: f64 },
    DoStep { h: f64 },
    GetState,
    SetState { k: usize },
    FreeState { k: usize },
    Terminate,
    Reset,
    Logging { on: bool },
}

impl Op {
    pub fn func(&self) -> Func {
        match self {
            Op::SetupExperiment { .. } => Func::SetupExperiment,
            Op::Enter => Func::EnterInitializationMode,
            Op::Exit => Func::ExitInitializationMode,
            Op::SetReal { .. } => Func::SetReal,
            Op::SetInteger { .. } => Func::SetInteger,
            Op::InputDerivative { .. } => Func::SetRealInputDerivatives,
            Op::DoStep { .. } => Func::DoStep,
            Op::GetState => Func::GetFMUstate,
            Op::SetState { .. } => Func::SetFMUstate,
            Op::FreeState { .. } => Func::FreeFMUstate,
            Op::Terminate => Func::Terminate,
            Op::Reset => Func::Reset,
            Op::Logging { .. } => Func::SetDebugLogging,
        }
    }
}

/// The next legal call for the state `m` is in.
pub fn next(rng: &mut Rng, vars: &Vars, m: &Model) -> Op {
    let any_saved = !m.saved.is_empty();
    if rng.one_in(60) {
        return Op::Reset;
    }
    if rng.one_in(80) {
        return Op::Logging { on: rng.one_in(2) };
    }
    match m.state {
        State::Instantiated => match rng.below(10) {
            0..=3 => parameter(rng, vars),
            4 => Op::SetupExperiment {
                start: rng.pick(&[0.0, 0.0, 0.5, -1.0]),
                stop: rng.one_in(3).then(|| rng.pick(&[0.002, 0.01, 1.0])),
            },
            5 => input(rng, vars),
            6 if any_saved => Op::SetState {
                k: rng.below(m.saved.len()),
            },
            _ => Op::Enter,
        },
        State::Init => match rng.below(6) {
            0 | 1 => input(rng, vars),
            2 => derivative(rng, vars),
            3 if rng.one_in(4) => parameter(rng, vars),
            _ => Op::Exit,
        },
        State::StepComplete => match rng.below(20) {
            0..=2 => input(rng, vars),
            3 => derivative(rng, vars),
            4 => Op::GetState,
            5 if any_saved => Op::SetState {
                k: rng.below(m.saved.len()),
            },
            6 if any_saved && rng.one_in(3) => Op::FreeState {
                k: rng.below(m.saved.len()),
            },
            7 if rng.one_in(6) => Op::Terminate,
            _ => {
                let h = if rng.one_in(40) {
                    rng.pick(&[5e-324, 1e-12, 3e-3])
                } else {
                    rng.pick(&[1e-5, 1e-5, 1e-4, 1e-4, 3e-4, 1e-3])
                };
                match m.stop {
                    // Up to the stop time, not past it.
                    Some(stop) if m.time + h > stop => {
                        if stop - m.time > 1e-9 && !rng.one_in(4) {
                            Op::DoStep { h: stop - m.time }
                        } else {
                            Op::Terminate
                        }
                    }
                    _ => Op::DoStep { h },
                }
            }
        },
        State::StepFailed | State::Terminated | State::Error => {
            if any_saved && !rng.one_in(4) {
                Op::SetState {
                    k: rng.below(m.saved.len()),
                }
            } else if m.state == State::StepFailed && rng.one_in(3) {
                Op::Terminate
            } else {
                Op::Reset
            }
        }
    }
}

/// A parameter: mostly near its start value, sometimes absurd.
fn parameter(rng: &mut Rng, vars: &Vars) -> Op {
    let p = rng.pick(&vars.parameters);
    if !p.real {
        let value = if p.vr == vars.rod_model {
            rng.pick(&[1, 2, 2, 4])
        } else if p.vr == vars.rod_elements {
            // Cheap meshes mostly; the declared limit now and then.
            if rng.one_in(200) {
                128
            } else {
                rng.pick(&[1, 2, 3, 4, 6, 8, 10, 12])
            }
        } else if p.vr == vars.rod_modes {
            if rng.one_in(20) {
                rng.pick(&[10_000, 1_000_000, i32::MAX])
            } else {
                rng.below(7) as c_int
            }
        } else {
            // Enumerations, their Integer twins and the policy: 1..=4 (past some ranges).
            1 + rng.below(4) as c_int
        };
        return Op::SetInteger { vr: p.vr, value };
    }
    let value = match rng.below(12) {
        0 => rng.pick(&[0.0, -p.start, 1e300, 5e-324, -1e-9, 1e12]),
        // A crank longer than the rod, a shorter rod.
        1 => p.start * rng.pick(&[3.0, 10.0, 0.1]),
        _ => p.start * rng.uniform(0.7, 1.4),
    };
    Op::SetReal { vr: p.vr, value }
}

/// A crank input: angle and speed in the contract's ranges, now and then beyond them.
fn input(rng: &mut Rng, vars: &Vars) -> Op {
    let k = rng.below(vars.real_inputs.len());
    let vr = vars.real_inputs[k];
    let value = match k {
        // Huge and denormal inputs now and then: refused (or taken) alike by both instances.
        _ if rng.one_in(50) => rng.pick(&[1e300, -1e300, 5e-324, f64::MAX, 1e12]),
        0 => rng.uniform(-7.0, 7.0),
        1 if rng.one_in(10) => rng.pick(&[-1163.7, 600.0, 0.0, 1e4]),
        1 => rng.uniform(-300.0, 300.0),
        _ => rng.uniform(-5e3, 5e3),
    };
    Op::SetReal { vr, value }
}

fn derivative(rng: &mut Rng, vars: &Vars) -> Op {
    let (vr, order) = if rng.one_in(2) {
        (vars.real_inputs[1], 1)
    } else {
        (vars.real_inputs[0], rng.pick(&[1, 2, 3]))
    };
    Op::InputDerivative {
        vr,
        order,
        value: rng.uniform(-2e3, 2e3),
    }
}

/// Apply `op` to instance `c`; `saved` are that instance's handles of the model's saved pairs
/// (in the model's order). Returns the status and, for `GetState`, the new handle.
pub fn apply(
    op: &Op,
    c: fmi2Component,
    time: f64,
    saved: &[fmi2FMUstate],
) -> (fmi2Status, fmi2FMUstate) {
    let mut handle = null_state();
    // SAFETY: live instance; arrays of length one; handles of this instance.
    let status = unsafe {
        match *op {
            Op::SetupExperiment { start, stop } => {
                fmi2SetupExperiment(c, 0, 0.0, start, stop.is_some() as i32, stop.unwrap_or(0.0))
            }
            Op::Enter => fmi2EnterInitializationMode(c),
            Op::Exit => fmi2ExitInitializationMode(c),
            Op::SetReal { vr, value } => fmi2SetReal(c, &vr, 1, &value),
            Op::SetInteger { vr, value } => fmi2SetInteger(c, &vr, 1, &value),
            Op::InputDerivative { vr, order, value } => {
                fmi2SetRealInputDerivatives(c, &vr, 1, &order, &value)
            }
            Op::DoStep { h } => fmi2DoStep(c, time, h, 0),
            Op::GetState => fmi2GetFMUstate(c, &mut handle),
            Op::SetState { k } => fmi2SetFMUstate(c, saved[k]),
            Op::FreeState { k } => {
                let mut slot = saved[k];
                let s = fmi2FreeFMUstate(c, &mut slot);
                if s == OK && !slot.is_null() {
                    return (-1, slot);
                }
                s
            }
            Op::Terminate => fmi2Terminate(c),
            Op::Reset => fmi2Reset(c),
            Op::Logging { on } => fmi2SetDebugLogging(c, on as i32, 0, std::ptr::null()),
        }
    };
    (status, handle)
}
