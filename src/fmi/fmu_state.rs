//! Saved FMU states (`fmi2GetFMUstate`) and their byte form (`fmi2SerializeFMUstate`).
//!
//! A saved state holds everything the instance needs to continue bit for bit: the state
//! machine's state, the experiment, the last step's status, and the model's own saved state
//! (opaque here: [`crate::cosimulation::SavedState`]). The byte form is this header around the
//! model's bytes (little endian; the model's layout: `docs/fmu.md`, "Saved states"):
//!
//! ```text
//! magic "FLXRFMI2", format version u32, GUID (u32 length + UTF-8),
//! machine state u8, last step status u8,
//! start time f64, stop time defined u8, stop time f64,
//! model (u64 length + the model's bytes),
//! checksum u64: FNV-1a 64 of all bytes before it
//! ```
//!
//! The checksum makes any corruption of the bytes (a flipped bit in a stored double, too) a
//! rejection rather than a silently different state. It is unkeyed, so every field is checked
//! against its range when the bytes are read, here for the header and by the model for its
//! bytes:
//!
//! | field | range | checked by |
//! |---|---|---|
//! | magic, format version | `FLXRFMI2`, [`VERSION`] | [`deserialize`] |
//! | GUID / `instantiationToken` | the instance's own | [`deserialize`] |
//! | machine state | a known code | [`deserialize`] |
//! | last step status | OK, or Discard; Discard in StepFailed | [`deserialize`] |
//! | stop time defined | 0 or 1 | [`deserialize`] |
//! | start time, stop time | the experiment's range, `Experiment::check_times`: start in [-1e6, 1e6] s, stop after it and at most 1e6 s (the same check as the FMI calls) | [`deserialize`] |
//! | model bytes | the model's own checks | `CoSimulationModel::read_saved` |
//! | the model's time | a built model after initialization, its time in [start, stop or 1e6] s | `Instance::deserialize_fmu_state`, [`check_time`] |

use super::experiment::Experiment;
use super::experiment::TIME_TOLERANCE;
use super::standard::Standard;
use super::state_machine::MachineState;
use super::status::Status;
use crate::bytes::{ByteReader, ByteWriter};
use crate::cosimulation::SavedState;
use crate::hash::fnv1a_64;
use crate::limits::EXPERIMENT_TIME_LIMIT;

const MAGIC: &[u8; 8] = b"FLXRFMI2";
const VERSION: u32 = 5;

/// What the shell saves of an instance besides the model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Header {
    pub machine: MachineState,
    pub experiment: Experiment,
    pub last_step: Status,
}

/// A saved state of an instance.
pub(crate) struct FmuState {
    pub header: Header,
    pub model: SavedState,
}

/// Write the header around the model's bytes, with the checksum.
pub(crate) fn serialize(guid: &str, header: &Header, model_bytes: &[u8]) -> Vec<u8> {
    let mut w = ByteWriter::default();
    w.raw(MAGIC);
    w.u32(VERSION);
    w.bytes_u32(guid.as_bytes());
    w.u8(header.machine.code());
    w.u8(header.last_step.code() as u8);
    w.f64(header.experiment.start_time);
    w.flag(header.experiment.stop_time.is_some());
    w.f64(header.experiment.stop_time.unwrap_or(0.0));
    w.bytes_u64(model_bytes);
    let checksum = fnv1a_64(&w.bytes);
    w.u64(checksum);
    w.bytes
}

/// Read bytes written by [`serialize`] for the FMU with this GUID (FMI 2.0) or
/// `instantiationToken` (FMI 3.0); messages name both as the `standard` does.
pub(crate) fn deserialize<'a>(
    guid: &str,
    standard: Standard,
    bytes: &'a [u8],
) -> Result<(Header, &'a [u8]), String> {
    let mut r = ByteReader::new(bytes);
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
    let mut r = ByteReader::new(content);
    r.take(MAGIC.len() + 4, "the header")?;
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
    let start_time = r.f64("the start time")?;
    let stop_defined = r.flag("the stop time flag")?;
    let stop = r.f64("the stop time")?;
    let model_bytes = r.bytes_u64("the model's state")?;
    r.finish("the state")?;
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
    let header = Header {
        machine,
        experiment: Experiment {
            start_time,
            stop_time: stop_defined.then_some(stop),
        },
        last_step,
    };
    Ok((header, model_bytes))
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

    fn sample() -> Header {
        Header {
            machine: MachineState::StepComplete,
            experiment: Experiment {
                start_time: 0.0,
                stop_time: Some(0.5),
            },
            last_step: Status::Ok,
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
    fn round_trip() {
        let bytes = serialize("{g}", &sample(), &[1, 2, 3]);
        let (header, model) = deserialize("{g}", Standard::Fmi2, &bytes).unwrap();
        assert_eq!(header, sample());
        assert_eq!(model, &[1u8, 2, 3][..]);
    }

    #[test]
    fn foreign_truncated_and_other_fmu_rejected() {
        let bytes = serialize("{g}", &sample(), &[]);
        assert!(deserialize("{g}", Standard::Fmi2, b"hello world")
            .err()
            .unwrap()
            .contains("foreign"));
        for cut in [3, 20, bytes.len() - 1] {
            let e = deserialize("{g}", Standard::Fmi2, &bytes[..cut]).expect_err("truncated");
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
        // A model length past the end, with a valid checksum.
        let mut long_model = bytes.clone();
        let at = long_model.len() - 16;
        long_model[at..at + 8].copy_from_slice(&5u64.to_le_bytes());
        let e = deserialize("{g}", Standard::Fmi2, &resealed(long_model))
            .err()
            .unwrap();
        assert!(e.contains("truncated: the model's state"), "{e}");
    }

    #[test]
    fn every_flipped_byte_is_rejected() {
        let bytes = serialize("{g}", &sample(), &[9; 40]);
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
        type Case = (&'static str, fn(&mut Header), &'static str);
        let cases: [Case; 4] = [
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
        ];
        for (label, change, expected) in cases {
            let mut header = sample();
            change(&mut header);
            let e = deserialize("{g}", Standard::Fmi2, &serialize("{g}", &header, &[1]))
                .err()
                .unwrap_or_else(|| panic!("{label} accepted"));
            assert!(e.contains(expected), "{label}: {e}");
        }
        // An unknown machine state code with a valid checksum.
        let mut bytes = serialize("{g}", &sample(), &[1]);
        bytes[8 + 4 + 4 + 3] = 99;
        let e = deserialize("{g}", Standard::Fmi2, &resealed(bytes))
            .err()
            .unwrap();
        assert!(e.contains("machine state code 99"), "{e}");
    }
}
