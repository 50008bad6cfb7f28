//! The caps on what the command-line tool (`flexrod`), the packager (`fmu`) and the FMU read
//! and record, in one place, so that no file or flag makes them read or allocate without
//! bound. Past a cap the input is refused with a message naming the file or flag, the cap and
//! what it would take.

use std::io::Read;
use std::path::Path;

/// The most communication points one run of `flexrod simulate` or `fmu --simulate` records
/// (each holds the time, the crank input and the outputs, about 140 bytes: 10^7 points take
/// about 1.4 GB). The rows of an `--input` table are capped at the same number.
pub const MAX_POINTS: usize = 10_000_000;

/// The largest scene file read, bytes (16 MiB). The largest real scene is a few kB; 256
/// `[[rod.section]]` stations (the most allowed) with every key take about 40 kB, so the cap
/// leaves room for comments and tables four hundred times that size.
pub const SCENE_FILE_CAP: u64 = 16 << 20;

/// The largest `--input` crank table read, bytes (256 MiB): room for the [`MAX_POINTS`] rows
/// at about 26 bytes a row (three numbers of six to eight significant digits); at full double
/// precision (about 60 bytes a row) about 4.5 million rows, still 5 h of 1e-4 s steps.
pub const CSV_FILE_CAP: u64 = 256 << 20;

/// Refuse a run of `points` communication points past [`MAX_POINTS`]; `what` says which flag
/// or key asks for them (e.g. "--steps 1e-9 over the experiment 0 .. 0.0838 s").
pub fn check_points(what: &str, points: f64) -> Result<(), String> {
    if points <= MAX_POINTS as f64 {
        Ok(())
    } else {
        Err(format!(
            "{what} needs {} communication points; at most {MAX_POINTS} are allowed (a larger step or a shorter run)",
            if points < 1e16 {
                format!("{:.0}", points.ceil())
            } else if points.is_finite() {
                format!("{points:.3e}")
            } else {
                "infinitely many".to_string()
            }
        ))
    }
}

/// The text of the file `path` (`what` names it in messages: "the scene", "the --input
/// table"), read through at most `cap + 1` bytes: a longer file (or a device without end,
/// `/dev/zero`) is refused with the cap and what was read, never read to its end.
pub fn read_text(path: &Path, cap: u64, what: &str) -> Result<String, String> {
    let name = crate::text::echo(&path.display().to_string());
    let file = std::fs::File::open(path).map_err(|e| format!("cannot read {what} {name}: {e}"))?;
    let mut bytes = Vec::new();
    file.take(cap + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| format!("cannot read {what} {name}: {e}"))?;
    if bytes.len() as u64 > cap {
        return Err(format!(
            "{what} {name} is larger than {cap} bytes ({} MiB), the most read: {} bytes read before stopping",
            cap >> 20,
            bytes.len()
        ));
    }
    String::from_utf8(bytes).map_err(|e| {
        format!(
            "{what} {name} is not UTF-8 text (byte {} of {})",
            e.utf8_error().valid_up_to() + 1,
            e.as_bytes().len()
        )
    })
}

/// `[experiment]` start and stop time, the experiment of the FMI calls and every time of a
/// serialized state: within `+-EXPERIMENT_TIME_LIMIT` s.
pub const EXPERIMENT_TIME_LIMIT: f64 = 1e6;
