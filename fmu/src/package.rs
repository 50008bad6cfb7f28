//! Build the library and write the `.fmu` archive.

use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;

use flexrod::cosimulation::DefaultExperiment;
use flexrod::fmi::resource::SCENE_FILE;
use flexrod::fmi::{ModelDescription, Standard};
use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, DateTime, ZipWriter};

/// The modelIdentifier names the binary and must be a C identifier (FMI 2.0, 2.2.1).
pub fn check_identifier(identifier: &str) -> Result<(), String> {
    let mut chars = identifier.chars();
    let first_ok = chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_');
    if first_ok && chars.all(|c| c.is_ascii_alphanumeric() || c == '_') {
        Ok(())
    } else {
        Err(format!(
            "the scene's name \"{identifier}\" is the FMU's modelIdentifier and must be a C identifier ([A-Za-z_][A-Za-z0-9_]*)"
        ))
    }
}

/// Relative tolerance of [`check_experiment`].
const GRID_TOLERANCE: f64 = 1e-9;

/// The default experiment must be a whole number of steps: `stop_time - start_time = n
/// step_size`, n >= 1, within 1e-9 relative. Otherwise a fixed-step importer that passes the
/// stop time to `fmi2SetupExperiment` would have to step past it on its last step (the FMU
/// refuses: it never integrates past stopTime), and fmusim refuses to start.
pub fn check_experiment(e: &DefaultExperiment, origin: &str) -> Result<(), String> {
    let (start, stop, step) = (e.start_time, e.stop_time, e.step_size);
    let duration = stop - start;
    let valid = start.is_finite() && stop.is_finite() && step.is_finite();
    if !(valid && step > 0.0 && duration > 0.0) {
        return Err(format!(
            "{origin}: [experiment] start_time = {start} s, stop_time = {stop} s, step_size = {step} s: allowed finite values with step_size > 0 and stop_time > start_time"
        ));
    }
    let steps = (duration / step).round();
    if steps < 1.0 || (duration - steps * step).abs() > GRID_TOLERANCE * duration {
        let lower = (duration / step).floor().max(1.0);
        return Err(format!(
            "{origin}: [experiment] stop_time - start_time = {duration} s is not a whole number of step_size = {step} s ({} steps): a fixed-step importer that passes stopTime to fmi2SetupExperiment could not end on stop_time (the FMU never steps past it) and fmusim refuses such an experiment. Allowed: stop_time = start_time + n step_size within {GRID_TOLERANCE:e} relative, e.g. stop_time = {} or {} (n = {lower} or {}), or step_size = {} (n = {})",
            duration / step,
            start + lower * step,
            start + (lower + 1.0) * step,
            lower + 1.0,
            duration / steps.max(1.0),
            steps.max(1.0),
        ));
    }
    Ok(())
}

/// The FMI 2.0 platform folder under `binaries/` and the file name of the shared library
/// cargo builds, for the platform this packager runs on (the library is built natively).
/// Only `linux64` is supported: the resource loading, the tests and the contract are Linux's.
pub fn platform() -> Result<(&'static str, &'static str), String> {
    platform_of(std::env::consts::OS, std::env::consts::ARCH)
}

fn platform_of(os: &str, arch: &str) -> Result<(&'static str, &'static str), String> {
    match (os, arch) {
        ("linux", "x86_64") => Ok(("linux64", "libflexrod.so")),
        _ => Err(format!(
            "cannot package for {os}/{arch}: this packager builds FMUs only on x86_64 Linux (binaries/linux64); build and package on such a machine"
        )),
    }
}

/// The cargo target directory this binary was built in (`<target>/<profile>/fmu`), so
/// `CARGO_TARGET_DIR` and `build.target-dir` are honoured.
pub fn target_dir() -> Result<PathBuf, String> {
    let exe = std::env::current_exe()
        .map_err(|e| format!("cannot locate the running executable: {e}"))?;
    exe.parent()
        .and_then(Path::parent)
        .map(Path::to_path_buf)
        .ok_or_else(|| format!("cannot derive the target directory from {}", exe.display()))
}

/// `cargo build --release --lib -p flexrod`; returns the path of the shared library.
pub fn build_library(target_dir: &Path) -> Result<PathBuf, String> {
    let (_, library_name) = platform()?;
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_string());
    let workspace = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    println!("building the FMU binary: {cargo} build --release --lib -p flexrod");
    let status = Command::new(&cargo)
        .args([
            "build",
            "--release",
            "--lib",
            "-p",
            "flexrod",
            "--target-dir",
        ])
        .arg(target_dir)
        .current_dir(&workspace)
        .status()
        .map_err(|e| format!("cannot run {cargo}: {e}"))?;
    if !status.success() {
        return Err(format!("cargo build of the FMU library failed ({status})"));
    }
    let library = target_dir.join("release").join(library_name);
    if !library.is_file() {
        return Err(format!(
            "the build succeeded but {} does not exist",
            library.display()
        ));
    }
    Ok(library)
}

/// The FMI 3.0 platform tuple under `binaries/` (FMI 3.0, 2.5.1.1), for the one platform
/// packaged.
pub const FMI3_PLATFORM: &str = "x86_64-linux";

/// Write `<out_dir>/<modelIdentifier>.fmu` (FMI 2.0) or `<out_dir>/<modelIdentifier>-fmi3.fmu`
/// (FMI 3.0), from the same library (it exports the `fmi2*` and the `fmi3*` functions).
pub fn write_fmu(
    out_dir: &Path,
    scene_text: &str,
    description: &ModelDescription,
    documentation: &str,
    library: &Path,
) -> Result<PathBuf, String> {
    let identifier = description.info.name.as_str();
    let (platform, suffix) = match description.standard() {
        Standard::Fmi2 => (platform()?.0, ""),
        Standard::Fmi3 => {
            platform()?;
            (FMI3_PLATFORM, "-fmi3")
        }
    };
    let binary = std::fs::read(library)
        .map_err(|e| format!("cannot read the library {}: {e}", library.display()))?;
    std::fs::create_dir_all(out_dir)
        .map_err(|e| format!("cannot create {}: {e}", out_dir.display()))?;
    let path = out_dir.join(format!("{identifier}{suffix}.fmu"));
    let file = File::create(&path).map_err(|e| format!("cannot create {}: {e}", path.display()))?;

    let entries: [(String, &[u8], u32); 4] = [
        (
            "modelDescription.xml".into(),
            description.xml.as_bytes(),
            0o644,
        ),
        (
            format!("binaries/{platform}/{identifier}.so"),
            &binary,
            0o755,
        ),
        (
            format!("resources/{SCENE_FILE}"),
            scene_text.as_bytes(),
            0o644,
        ),
        (
            "documentation/index.html".into(),
            documentation.as_bytes(),
            0o644,
        ),
    ];

    let mut zip = ZipWriter::new(file);
    for (name, bytes, mode) in entries {
        // Fixed timestamps: the same inputs give the same archive.
        let options = SimpleFileOptions::default()
            .compression_method(CompressionMethod::Deflated)
            .last_modified_time(DateTime::default())
            .unix_permissions(mode);
        zip.start_file(name.as_str(), options)
            .map_err(|e| format!("cannot add {name} to {}: {e}", path.display()))?;
        zip.write_all(bytes)
            .map_err(|e| format!("cannot write {name} into {}: {e}", path.display()))?;
    }
    zip.finish()
        .map_err(|e| format!("cannot finish {}: {e}", path.display()))?;
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn experiment_of(start: f64, stop: f64, step: f64) -> DefaultExperiment {
        DefaultExperiment {
            start_time: start,
            stop_time: stop,
            step_size: step,
        }
    }

    #[test]
    fn experiments_must_be_whole_numbers_of_steps() {
        assert!(check_experiment(&experiment_of(0.0, 0.0838, 1e-4), "s").is_ok());
        assert!(check_experiment(&experiment_of(0.1, 0.3, 0.1), "s").is_ok());
        assert!(check_experiment(&experiment_of(0.0, 1.0, 1.0), "s").is_ok());
        let two_revolutions = 4.0 * std::f64::consts::PI / 150.0;
        let e =
            check_experiment(&experiment_of(0.0, two_revolutions, 1e-4), "the scene").unwrap_err();
        assert!(e.starts_with("the scene: [experiment]"), "{e}");
        assert!(
            e.contains("not a whole number of step_size = 0.0001 s"),
            "{e}"
        );
        assert!(e.contains("or 0.0838 (n = 837 or 838)"), "{e}");
        for (start, stop, step) in [
            (0.0, 0.0, 1e-4),
            (0.0, 1.0, 0.0),
            (0.0, 1.0, 2.0),
            (0.0, f64::NAN, 1e-4),
        ] {
            assert!(check_experiment(&experiment_of(start, stop, step), "s").is_err());
        }
    }

    #[test]
    fn every_shipped_scene_is_a_whole_number_of_steps() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
        let mut n = 0;
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().and_then(|e| e.to_str()) != Some("toml") {
                continue;
            }
            let text = std::fs::read_to_string(&path).unwrap();
            let origin = path.display().to_string();
            let d = ModelDescription::for_scene_text(&text, &origin, Standard::Fmi2).unwrap();
            check_experiment(&d.info.default_experiment, &origin).unwrap();
            n += 1;
        }
        assert!(n >= 6, "{n} scenes in {}", dir.display());
    }

    /// `[experiment]` is optional (docs/fmu.md, "Keys"): a scene without it passes the
    /// packager's checks with the default experiment, whose DefaultExperiment the model
    /// description declares (tests/doc_facts.rs compares the documented defaults).
    #[test]
    fn a_scene_without_experiment_is_packaged_with_the_defaults() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/benchmark.toml");
        let text = std::fs::read_to_string(path).unwrap();
        let without = &text[..text.find("[experiment]").unwrap()];
        let scene = flexrod::Scene::from_toml_str(without, "the scene").unwrap();
        assert_eq!(scene.experiment, flexrod::scene::ExperimentSpec::default());
        let description = ModelDescription::for_scene(&scene).unwrap();
        check_identifier(&description.info.name).unwrap();
        check_experiment(&description.info.default_experiment, "the scene").unwrap();
        assert!(
            description.xml.contains(
                r#"<DefaultExperiment startTime="0.0" stopTime="0.0838" stepSize="0.0001"/>"#
            ),
            "{}",
            description.xml
        );
    }

    #[test]
    fn platform_folder_from_os_and_arch() {
        assert_eq!(
            platform_of("linux", "x86_64").unwrap(),
            ("linux64", "libflexrod.so")
        );
        for (os, arch) in [
            ("linux", "aarch64"),
            ("windows", "x86_64"),
            ("macos", "aarch64"),
        ] {
            let e = platform_of(os, arch).unwrap_err();
            assert!(e.contains(&format!("{os}/{arch}")), "{e}");
        }
    }
}
