//! Saved FMU states (`fmi2GetFMUstate`) and their byte form (`fmi2SerializeFMUstate`).
//!
//! A saved state holds everything the instance needs to continue bit for bit: the state
//! machine's state, the experiment, the last step's status, and the model's own saved state
//! ([`SavedModel`]: its parameters, its inputs and their law, and the simulation). The byte
//! form, little endian:
//!
//! ```text
//! magic "FLXRFMI2", format version u32, GUID (u32 length + UTF-8),
//! machine state u8, last step status u8, started u8,
//! start time f64, stop time defined u8, stop time f64,
//! inputs: angle, speed, slider force, acceleration, jerk f64,
//!         acceleration source u8 (0 none, 1 crank.speed, 2 crank.angle, 3 the FMI 3.0 input
//!         crank.acceleration), jerk source u8 (0 none, 1 crank.speed, 2 crank.angle, 3 the
//!         FMI 3.0 input crank.jerk), force changed u8 (the model's `Inputs::to_bytes`),
//! scene (u32 length + TOML), simulation present u8 (+ u64 length + core bytes),
//! checksum u64: FNV-1a 64 of all bytes before it
//! ```
//!
//! The law in force (theta_k, omega_k, alpha_k, j_k, t_k) is part of the core's bytes, which carry
//! their own magic, version and model fingerprint. The checksum makes any corruption of the
//! bytes (a flipped bit in a stored double, too) a rejection rather than a silently different
//! state.
//!
//! The checksum is unkeyed, so every field is checked against its range when the bytes are
//! read; a state holds nothing a set call or an accepted step would refuse:
//!
//! | field | range | checked by |
//! |---|---|---|
//! | magic, format version | `FLXRFMI2`, [`VERSION`] | [`deserialize`] |
//! | GUID / `instantiationToken` | the instance's own | [`deserialize`] |
//! | machine state | a known code | [`deserialize`] |
//! | last step status | OK, or Discard; Discard in StepFailed | [`deserialize`] |
//! | started, stop time defined, simulation present | 0 or 1; a simulation after initialization | [`deserialize`] |
//! | start time, stop time | the experiment's range, `Experiment::check_times`: start in [-1e6, 1e6] s, stop after it and at most 1e6 s (the same check as `[experiment]` and the FMI calls) | [`deserialize`] |
//! | inputs: `crank.angle`, `crank.speed`, `slider.force`, crank acceleration, jerk | the windows of their set calls | `Inputs::from_bytes` |
//! | acceleration and jerk sources, force changed | known codes, 0 or 1 | `Inputs::from_bytes` |
//! | scene text | the scene keys' ranges (`Scene::validate_settings`) | `SavedModel::from_parts` |
//! | scene text | the instance's own scene with only declared parameters changed, Real finite, Integer within the declared range | `model::binding::check_same_model` |
//! | scene's physical parameters | the ranges of the model's build | `Simulation::new` (states with a simulation; otherwise at initialization, as set values) |
//! | core: magic, version, model fingerprint, length | `FLEXROD\0`, the core's version, this scene's model, this model's dimensions | `Simulation::restore_from_bytes`, `MechanismState::read_bytes` |
//! | core: time, input time, previous input time | finite, within +-1e6 s, input time <= time; the time in [start, stop or 1e6] s after initialization | `MechanismState::validate`, [`check_time`] |
//! | core: law in force and the one before (angle, speed, acceleration, jerk), slider force | the windows of the set calls | `Simulation::restore_from_bytes` |
//! | core: cached outputs (the nine scalars, section loads) | finite, \|value\| < `MAX_OUTPUT_MAGNITUDE` = 1e12, the range of an accepted step (`Outputs::out_of_range`, the same check); stress NaN where not computed | `MechanismState::validate` |
//! | core: coordinates, velocities, accelerations, multipliers | finite (the range of an accepted step) | `MechanismState::validate` |
//! | core: integrator time | equal to the time | `MechanismState::validate` |
//! | core: step proposal | finite, >= 0 | `MechanismState::validate` |
//! | core: deflection amplitude, the start's vibration amplitude | finite, >= 0, < 1e12 | `MechanismState::validate`, `read_bytes` |
//! | core: held internal step | finite, length in (0, 0.0125] s, contains the time | `MechanismState::validate` |
//! | core: counters (steps, Newton iterations, halvings) | any u64 (counts only) | none needed |
//! | core: deflection warned, held-step flag | 0 or 1 (held only with dense output) | `MechanismState::read_bytes` |
//!
//! Outputs are also checked when they are read (`Model::get_real`): a computed value outside the
//! range of an accepted step is never handed out with OK.

use super::experiment::Experiment;
use super::instance::TIME_TOLERANCE;
use super::standard::Standard;
use super::state_machine::MachineState;
use super::status::Status;
use crate::hash::fnv1a_64;
use crate::model::EXPERIMENT_TIME_LIMIT;
use crate::model::{Inputs, SavedModel};

const MAGIC: &[u8; 8] = b"FLXRFMI2";
const VERSION: u32 = 3;

/// A saved state of an instance.
#[derive(Clone, Debug)]
pub(crate) struct FmuState {
    pub machine: MachineState,
    pub experiment: Experiment,
    pub last_step: Status,
    pub model: SavedModel,
}

/// A parsed byte form: the state without its simulation, and the core's bytes of it.
pub(crate) struct Parsed<'a> {
    pub state: FmuState,
    pub simulation_bytes: Option<&'a [u8]>,
}

fn put_f64(out: &mut Vec<u8>, x: f64) {
    out.extend_from_slice(&x.to_le_bytes());
}

fn put_bytes_u32(out: &mut Vec<u8>, bytes: &[u8]) {
    out.extend_from_slice(&(bytes.len() as u32).to_le_bytes());
    out.extend_from_slice(bytes);
}

/// Write `state`; `simulation_bytes` are the core's bytes of `state.simulation`.
pub(crate) fn serialize(guid: &str, state: &FmuState, simulation_bytes: Option<&[u8]>) -> Vec<u8> {
    let mut out = Vec::new();
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&VERSION.to_le_bytes());
    put_bytes_u32(&mut out, guid.as_bytes());
    out.push(state.machine.code());
    out.push(state.last_step.code() as u8);
    out.push(u8::from(state.model.started()));
    put_f64(&mut out, state.experiment.start_time);
    out.push(u8::from(state.experiment.stop_time.is_some()));
    put_f64(&mut out, state.experiment.stop_time.unwrap_or(0.0));
    out.extend_from_slice(&state.model.inputs_bytes());
    put_bytes_u32(&mut out, state.model.parameters_text().as_bytes());
    match simulation_bytes {
        None => out.push(0),
        Some(b) => {
            out.push(1);
            out.extend_from_slice(&(b.len() as u64).to_le_bytes());
            out.extend_from_slice(b);
        }
    }
    let checksum = fnv1a_64(&out);
    out.extend_from_slice(&checksum.to_le_bytes());
    out
}

struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8], String> {
        let left = self.bytes.len() - self.at;
        if n > left {
            return Err(format!(
                "truncated: {what} needs {n} bytes at offset {}, only {left} left",
                self.at
            ));
        }
        let b = &self.bytes[self.at..self.at + n];
        self.at += n;
        Ok(b)
    }

    fn u8(&mut self, what: &str) -> Result<u8, String> {
        Ok(self.take(1, what)?[0])
    }

    fn flag(&mut self, what: &str) -> Result<bool, String> {
        match self.u8(what)? {
            0 => Ok(false),
            1 => Ok(true),
            b => Err(format!("{what} is {b}, allowed 0 or 1")),
        }
    }

    fn u32(&mut self, what: &str) -> Result<u32, String> {
        let b = self.take(4, what)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    fn u64(&mut self, what: &str) -> Result<u64, String> {
        let b = self.take(8, what)?;
        let mut a = [0u8; 8];
        a.copy_from_slice(b);
        Ok(u64::from_le_bytes(a))
    }

    fn f64(&mut self, what: &str) -> Result<f64, String> {
        Ok(f64::from_bits(self.u64(what)?))
    }

    fn str_u32(&mut self, what: &str) -> Result<&'a str, String> {
        let n = self.u32(what)? as usize;
        let b = self.take(n, what)?;
        std::str::from_utf8(b).map_err(|_| format!("{what} is not UTF-8"))
    }
}

/// Read bytes written by [`serialize`] for the FMU with this GUID (FMI 2.0) or
/// `instantiationToken` (FMI 3.0); messages name both as the `standard` does.
pub(crate) fn deserialize<'a>(
    guid: &str,
    standard: Standard,
    bytes: &'a [u8],
) -> Result<Parsed<'a>, String> {
    let mut r = Reader { bytes, at: 0 };
    if r.take(8, "the header").ok() != Some(&MAGIC[..]) {
        return Err(format!(
            "the {} bytes do not start with this FMU's header \"FLXRFMI2\" (foreign or truncated bytes)",
            bytes.len()
        ));
    }
    let version = r.u32("the format version")?;
    if version != VERSION {
        return Err(format!(
            "format version {version}, this FMU reads version {VERSION}"
        ));
    }
    if bytes.len() < MAGIC.len() + 4 + 8 {
        return Err(format!(
            "truncated: {} bytes cannot hold a state and its checksum",
            bytes.len()
        ));
    }
    let (content, stored) = bytes.split_at(bytes.len() - 8);
    let mut checksum = [0u8; 8];
    checksum.copy_from_slice(stored);
    if u64::from_le_bytes(checksum) != fnv1a_64(content) {
        return Err(format!(
            "the checksum of the {} bytes does not match their content (corrupted, truncated or extended bytes)",
            bytes.len()
        ));
    }
    let mut r = Reader {
        bytes: content,
        at: r.at,
    };
    let token = standard.token_name();
    let written_by = r.str_u32(&format!("the {token}"))?;
    if written_by != guid {
        return Err(format!(
            "it was written by the FMU with {token} {written_by}, this FMU has {token} {guid}"
        ));
    }
    let machine_code = r.u8("the machine state")?;
    let machine = MachineState::from_code(machine_code)
        .ok_or_else(|| format!("machine state code {machine_code} is unknown"))?;
    let status_code = r.u8("the last step status")?;
    let last_step = Status::from_code(i32::from(status_code))
        .ok_or_else(|| format!("status code {status_code} is unknown"))?;
    let started = r.flag("the started flag")?;
    let start_time = r.f64("the start time")?;
    let stop_defined = r.flag("the stop time flag")?;
    let stop = r.f64("the stop time")?;
    let mut inputs = [0u8; Inputs::BYTES];
    inputs.copy_from_slice(r.take(Inputs::BYTES, "the inputs")?);
    let parameters = r.str_u32("the scene")?;
    let model = SavedModel::from_parts(started, &inputs, parameters)?;
    let simulation_bytes = if r.flag("the simulation flag")? {
        let n = r.u64("the simulation length")?;
        let n = usize::try_from(n).map_err(|_| format!("simulation length {n} is too large"))?;
        Some(r.take(n, "the simulation")?)
    } else {
        None
    };
    if r.at != content.len() {
        return Err(format!(
            "{} unexpected bytes after the end of the state at offset {}",
            content.len() - r.at,
            r.at
        ));
    }
    Experiment::check_times(
        start_time,
        stop_defined.then_some(stop),
        ["the start time", "the stop time"],
    )?;
    if !matches!(last_step, Status::Ok | Status::Discard)
        || (machine == MachineState::StepFailed && last_step != Status::Discard)
    {
        return Err(format!(
            "the last step status {} does not fit the machine state {} (allowed {p}OK, or {p}Discard in StepFailed)",
            last_step.code(),
            machine.name(),
            p = standard.prefix()
        ));
    }
    if machine.is_stepping() && simulation_bytes.is_none() {
        return Err(format!(
            "machine state {} without a simulation (a state after initialization always holds one, with its model fingerprint)",
            machine.name()
        ));
    }
    Ok(Parsed {
        state: FmuState {
            machine,
            experiment: Experiment {
                start_time,
                stop_time: stop_defined.then_some(stop),
            },
            last_step,
            model,
        },
        simulation_bytes,
    })
}

/// The time of a state after initialization within its experiment: from the start time to
/// the stop time (or the end of the experiment's range without one), within the tolerance of a
/// communication point.
pub(crate) fn check_time(time: f64, experiment: &Experiment) -> Result<(), String> {
    let start = experiment.start_time;
    let end = experiment.stop_time.unwrap_or(EXPERIMENT_TIME_LIMIT);
    let tolerance = |t: f64| TIME_TOLERANCE * t.abs().max(1.0);
    if time >= start - tolerance(start) && time <= end + tolerance(end) {
        Ok(())
    } else {
        Err(format!(
            "the time {time} s is outside the experiment [{start}, {end}] s (allowed from the start time to the stop time, or to {EXPERIMENT_TIME_LIMIT:e} s without one)"
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::model::{AccelerationSource, Scene};

    fn inputs() -> Inputs {
        Inputs {
            angle: 1.25,
            speed: 150.0,
            slider_force: -3.5,
            acceleration: 10.0,
            source: AccelerationSource::Angle,
            jerk: -4.0e5,
            jerk_source: AccelerationSource::Speed,
            force_changed: true,
        }
    }

    fn sample() -> FmuState {
        let model =
            SavedModel::from_parts(true, &inputs().to_bytes(), &Scene::benchmark().to_toml())
                .unwrap();
        FmuState {
            machine: MachineState::StepComplete,
            experiment: Experiment {
                start_time: 0.0,
                stop_time: Some(0.5),
            },
            last_step: Status::Ok,
            model,
        }
    }

    /// `bytes` with the checksum recomputed (bytes crafted with a valid checksum).
    fn resealed(mut bytes: Vec<u8>) -> Vec<u8> {
        let n = bytes.len() - 8;
        let checksum = fnv1a_64(&bytes[..n]);
        bytes[n..].copy_from_slice(&checksum.to_le_bytes());
        bytes
    }

    #[test]
    fn round_trip_without_simulation() {
        let s = sample();
        let bytes = serialize("{g}", &s, Some(&[1, 2, 3]));
        let p = deserialize("{g}", Standard::Fmi2, &bytes).unwrap();
        assert_eq!(p.state.model.inputs_bytes(), s.model.inputs_bytes());
        assert_eq!(p.state.model.parameters_text(), s.model.parameters_text());
        assert!(p.state.model.started());
        assert_eq!(p.state.experiment, s.experiment);
        assert_eq!(p.state.machine, s.machine);
        assert_eq!(p.simulation_bytes, Some(&[1u8, 2, 3][..]));
    }

    #[test]
    fn foreign_truncated_and_other_fmu_rejected() {
        let bytes = serialize("{g}", &sample(), None);
        assert!(deserialize("{g}", Standard::Fmi2, b"hello world")
            .err()
            .unwrap()
            .contains("foreign"));
        for cut in [3, 20, bytes.len() - 1] {
            let e = deserialize("{g}", Standard::Fmi2, &bytes[..cut])
                .err()
                .expect("truncated");
            assert!(
                e.contains("truncated") || e.contains("foreign") || e.contains("checksum"),
                "{e}"
            );
        }
        assert!(deserialize("{h}", Standard::Fmi2, &bytes)
            .err()
            .unwrap()
            .contains("GUID"));
        let e = deserialize("{h}", Standard::Fmi3, &bytes).err().unwrap();
        assert!(
            e.contains("instantiationToken") && !e.contains("GUID"),
            "{e}"
        );
        let mut longer = bytes.clone();
        longer.push(0);
        assert!(deserialize("{g}", Standard::Fmi2, &longer)
            .err()
            .unwrap()
            .contains("checksum"));
    }

    #[test]
    fn every_flipped_byte_is_rejected() {
        let bytes = serialize("{g}", &sample(), Some(&[9; 40]));
        for at in 0..bytes.len() {
            let mut corrupted = bytes.clone();
            corrupted[at] ^= 0x10;
            assert!(
                deserialize("{g}", Standard::Fmi2, &corrupted).is_err(),
                "byte {at} flipped"
            );
        }
    }

    /// The checksum is unkeyed, so bytes with a valid checksum but values out of
    /// range are crafted easily; every field is validated after reading.
    #[test]
    fn crafted_values_with_a_valid_checksum_are_rejected() {
        type Case = (&'static str, fn(&mut FmuState), &'static str);
        // A NaN crank.speed, its bytes after the magic, version, GUID "{g}", three flags,
        // start time, stop flag, stop time and crank.angle.
        let mut bytes = serialize("{g}", &sample(), Some(&[1, 2, 3]));
        let at = 8 + 4 + 4 + 3 + 3 + 8 + 1 + 8 + 8;
        bytes[at..at + 8].copy_from_slice(&f64::NAN.to_le_bytes());
        let e = deserialize("{g}", Standard::Fmi2, &resealed(bytes))
            .err()
            .expect("a NaN crank.speed is rejected");
        assert!(e.contains("crank.speed is NaN"), "{e}");
        let cases: [Case; 5] = [
            (
                "infinite start",
                |s| s.experiment.start_time = f64::INFINITY,
                "start time",
            ),
            (
                "stop before start",
                |s| s.experiment.stop_time = Some(-1.0),
                "stop time",
            ),
            (
                "error status",
                |s| s.last_step = Status::Error,
                "last step status",
            ),
            (
                "StepFailed with fmi2OK",
                |s| s.machine = MachineState::StepFailed,
                "last step status",
            ),
            ("no simulation", |_| {}, "without a simulation"),
        ];
        for (label, change, expected) in cases {
            let mut state = sample();
            change(&mut state);
            let sim: Option<&[u8]> = if label == "no simulation" {
                None
            } else {
                Some(&[1, 2, 3])
            };
            let e = deserialize("{g}", Standard::Fmi2, &serialize("{g}", &state, sim))
                .err()
                .unwrap_or_else(|| panic!("{label} accepted"));
            assert!(e.contains(expected), "{label}: {e}");
        }
    }
}
