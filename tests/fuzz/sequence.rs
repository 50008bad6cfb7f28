//! One fuzz sequence: a pair of instances of the default scene (subject and twin) driven in
//! lockstep by the legal stream, with hostile calls on the subject alone between the legal
//! calls. After every legal call both instances must answer the same status and hold the same
//! values bit for bit (the continuation-equivalence oracle: a refused call changes nothing),
//! the subject must show the state the oracle models, and nothing non-finite may come with
//! `fmi2OK`.

use super::fmu::{Fmu, Snapshot, Vars, OK, WARNING};
use super::hostile::{self, Context, Counts, OwnStates};
use super::legal::{self, Model, Op, SavedPair};
use super::oracle::{self, State, Violations};
use super::rng::Rng;

/// Totals over a run of sequences.
#[derive(Default, Debug)]
pub struct Totals {
    pub sequences: u64,
    pub counts: Counts,
    pub legal_calls: u64,
    pub steps_accepted: u64,
    pub steps_discarded: u64,
    pub segment_sequences: u64,
    pub hostile_calls: u64,
    pub panics: u64,
    /// Legal steps refused with fmi2Error and the instance unchanged: the crank law reached
    /// an input window (a speed of 1e4 rad/s with an acceleration), or the work bound.
    pub unchanged_refusals: u64,
    /// The generators of [`super::extended`].
    pub extended: super::extended::Extended,
}

/// Run sequence number `seq` (its own seed); violations are added to `violations`.
pub fn run(seq: u64, vars: &Vars, totals: &mut Totals, violations: &mut Violations) {
    let mut rng = Rng::new(0x14_0000_0000 ^ seq.wrapping_mul(0x9e37_79b9_7f4a_7c15));
    let subject = Fmu::new(vars, "subject");
    let twin = Fmu::new(vars, "twin");
    let mut model = Model {
        state: State::Instantiated,
        time: 0.0,
        start_time: 0.0,
        stop: None,
        saved: Vec::new(),
    };
    let mut own = OwnStates::default();
    let mut segments = false;
    let legal_calls = 10 + rng.below(50);
    // The calls so far, shown with a violation (FLEXROD_FUZZ_TRACE=1 prints every sequence's).
    let mut trace: Vec<String> = Vec::new();
    for _ in 0..legal_calls {
        // Hostile calls first (none to three), on the subject only.
        for _ in 0..rng.below(4) {
            let twin_states: Vec<_> = model.saved.iter().map(|p| p.twin).collect();
            let cx = Context {
                vars,
                subject: &subject,
                state: model.state,
                time: model.time,
                twin_states: &twin_states,
            };
            let errors_before = subject.errors_logged();
            let (f, status, expect) = hostile::call(&mut rng, &cx, &mut own);
            trace.push(format!("  hostile fmi2{f:?} -> {status}"));
            totals.hostile_calls += 1;
            count(&mut totals.counts, hostile::index(f), status);
            hostile::judge(f, status, expect, errors_before, &subject, violations, seq);
        }
        // One legal call on both.
        let op = legal::next(&mut rng, vars, &model);
        if let Op::SetInteger { vr, value: 2 | 3 } = op {
            segments |= vr == vars.rod_model;
        }
        let subject_saved: Vec<_> = model.saved.iter().map(|p| p.subject).collect();
        let twin_saved: Vec<_> = model.saved.iter().map(|p| p.twin).collect();
        let (s1, h1) = legal::apply(&op, subject.c, model.time, &subject_saved);
        let (s2, h2) = legal::apply(&op, twin.c, model.time, &twin_saved);
        totals.legal_calls += 1;
        trace.push(format!("legal {op:?} -> {s1} / {s2}"));
        count(&mut totals.counts, hostile::index(op.func()), s1);
        if s1 == -1 || s2 == -1 {
            violations.add(format!(
                "sequence {seq}: fmi2FreeFMUstate answered fmi2OK and left the handle non-NULL"
            ));
            break;
        }
        if let (Op::FreeState { k }, OK) = (&op, s1) {
            own.freed.push(subject_saved[*k]);
        }
        if s1 != s2 {
            violations.add(format!(
                "sequence {seq}: {op:?} answered {s1} on the subject and {s2} on its twin (a refused call changed the subject)"
            ));
            break;
        }
        let message = subject.log.last_error.borrow().clone();
        update(&mut model, &op, s1, h1, h2, totals);
        // The oracle's state against the subject's.
        let mut shown = oracle::probe(subject.c);
        if matches!(op, Op::DoStep { .. })
            && s1 == super::fmu::ERROR
            && shown == oracle::signature(State::StepComplete)
        {
            // Refused with the instance unchanged (docs/fmu.md, fmi2DoStep: the work bound, or
            // the crank law past an input window).
            model.state = State::StepComplete;
            totals.unchanged_refusals += 1;
            if std::env::var("FLEXROD_FUZZ_TRACE").is_ok() {
                let legal: Vec<&String> = trace.iter().filter(|l| l.starts_with("legal")).collect();
                println!("sequence {seq}, refused unchanged: {message}\n{legal:#?}");
            }
            shown = oracle::probe(subject.c);
        }
        if shown != oracle::signature(model.state) {
            violations.add(format!(
                "sequence {seq}: after {op:?} (status {s1}) the subject shows {shown:?}, the oracle expects {:?}; last error: {message}",
                model.state,
            ));
            break;
        }
        // Continuation equivalence and no garbage with fmi2OK.
        let a = subject.snapshot(vars);
        let b = twin.snapshot(vars);
        if !a.same_as(&b) {
            violations.add(format!(
                "sequence {seq}: after {op:?} the subject's values differ from its twin's:\n{a:?}\n{b:?}\n{}",
                trace.join("\n")
            ));
            break;
        }
        check_snapshot(&a, vars, violations, seq, &op);
    }
    totals.sequences += 1;
    totals.segment_sequences += segments as u64;
    totals.panics += subject.log.panics.get() + twin.log.panics.get();
    if subject.log.panics.get() + twin.log.panics.get() > 0 {
        violations.add(format!(
            "sequence {seq}: a panic was caught at the FMI boundary"
        ));
    }
}

fn count(counts: &mut Counts, index: usize, status: i32) {
    counts.calls += 1;
    counts.functions[index] += 1;
    if status != OK && status != WARNING {
        counts.refused += 1;
    }
}

/// The oracle's model after a legal call both instances answered `status`.
fn update(
    model: &mut Model,
    op: &Op,
    status: i32,
    subject_handle: flexrod::fmi::ffi::fmi2FMUstate,
    twin_handle: flexrod::fmi::ffi::fmi2FMUstate,
    totals: &mut Totals,
) {
    let ok = status == OK || status == WARNING;
    match *op {
        Op::SetupExperiment { start, stop } if ok => {
            model.start_time = start;
            model.stop = stop;
        }
        Op::Exit if ok => model.time = model.start_time,
        Op::DoStep { h } if ok => {
            model.time += h;
            totals.steps_accepted += 1;
        }
        Op::DoStep { .. } if status == super::fmu::DISCARD => totals.steps_discarded += 1,
        Op::Reset if ok => {
            model.start_time = 0.0;
            model.time = 0.0;
            model.stop = None;
        }
        Op::GetState if ok => model.saved.push(SavedPair {
            subject: subject_handle,
            twin: twin_handle,
            state: model.state,
            time: model.time,
            stop: model.stop,
        }),
        Op::SetState { k } if ok => {
            model.state = model.saved[k].state;
            model.time = model.saved[k].time;
            model.stop = model.saved[k].stop;
            return;
        }
        Op::FreeState { k } if ok => {
            model.saved.swap_remove(k);
        }
        _ => {}
    }
    model.state = oracle::after(op.func(), model.state, status);
}

/// Values read with `fmi2OK` must be finite; outputs and calculated parameters also below 1e12
/// in magnitude (parameters echo what the master set).
fn check_snapshot(a: &Snapshot, vars: &Vars, violations: &mut Violations, seq: u64, op: &Op) {
    if a.real_status != OK {
        return;
    }
    let what = format!("sequence {seq}, after {op:?}");
    for (k, &vr) in vars.all_reals.iter().enumerate() {
        let x = a.reals[k];
        let computed = vars.real_outputs.contains(&vr) || vars.calculated.contains(&vr);
        if !x.is_finite() || (computed && x.abs() >= oracle::MAX_MAGNITUDE) {
            violations.add(format!("{what}: value reference {vr} is {x} with fmi2OK"));
        }
    }
}
