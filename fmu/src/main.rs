//! `fmu`: export a scene as FMI 2.0 and FMI 3.0 Co-Simulation FMUs, and run its default
//! experiment.
//!
//! ```text
//! cargo run --release -p fmu [-- [SCENE.toml] [--out DIR] [--fmi 2|3] [--simulate]
//!                                [--csv FILE] [--accel A] [--steps H1,H2,...] [--no-package]]
//! ```
//!
//! - Packaging (default): builds the release library (`cargo build --release --lib -p flexrod`)
//!   and writes `<target>/fmu/<modelIdentifier>.fmu` (FMI 2.0) and
//!   `<target>/fmu/<modelIdentifier>-fmi3.fmu` (FMI 3.0), or into `DIR`; `--fmi 2` or
//!   `--fmi 3` writes only that one. Both archives hold the same library.
//! - `--simulate`: runs the scene's default experiment in-process with `flexrod::Simulation`,
//!   driving the crank exactly as an FMU importer would (inputs set at every communication
//!   point), and prints a summary. `--csv FILE` writes the outputs at the communication
//!   points; `--accel A` drives the crank with a constant acceleration A (rad/s^2) supplied as
//!   the input derivative; `--steps` cycles through the given communication steps instead of
//!   the scene's fixed step. These are the reference results of the Python tests.

mod docs;
mod package;
mod simulate;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use flexrod::fmi::registry::ModelKind;
use flexrod::fmi::{ModelDescription, Standard};
use flexrod::model::variables::VariableTable;
use flexrod::Scene;

/// Command-line arguments.
struct Args {
    scene: PathBuf,
    out: Option<PathBuf>,
    package: bool,
    simulate: bool,
    csv: Option<PathBuf>,
    accel: f64,
    steps: Option<Vec<f64>>,
    /// Which standards to package.
    standards: Vec<Standard>,
}

const USAGE: &str = "usage: fmu [SCENE.toml] [--out DIR] [--fmi 2|3] [--simulate] [--csv FILE] [--accel A] [--steps H1,H2,...] [--no-package]";

/// `--help`: the usage with what each option does.
const HELP: &str = "\
Export a flexrod scene as FMI 2.0 and FMI 3.0 Co-Simulation FMUs, and run its default experiment.

usage: fmu [SCENE.toml] [--out DIR] [--fmi 2|3] [--simulate] [--csv FILE] [--accel A] [--steps H1,H2,...] [--no-package]
       (cargo run --release -p fmu -- ...)

  SCENE.toml     the scene (default: scenes/benchmark.toml)
  --out DIR      write the FMUs into DIR (default: <target>/fmu)
  --fmi 2|3      write only the FMI 2.0 or only the FMI 3.0 FMU (default: both)
  --no-package   do not build and write FMUs
  --simulate     run the scene's default experiment in-process and print a summary
  --csv FILE     with --simulate (implied): write the outputs at the communication points
  --accel A      with --simulate: a constant crank acceleration A, rad/s^2 (finite)
  --steps H1,... with --simulate: cycle through these communication steps, s (each > 0)

A run records at most 10^7 communication points; the scene file is read up to 16 MiB.
  -h, --help     print this help

Exit codes: 0 done, 1 packaging or the run failed, 2 a bad command line.";

/// Why the packager stops: a bad command line (exit code 2) or a failure (exit code 1).
enum Failure {
    Usage(String),
    Run(String),
}

impl From<String> for Failure {
    fn from(message: String) -> Self {
        Failure::Run(message)
    }
}

/// The arguments, or `None` for `--help`.
fn parse_args() -> Result<Option<Args>, String> {
    let workspace = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut args = Args {
        scene: workspace.join("scenes/benchmark.toml"),
        out: None,
        package: true,
        simulate: false,
        csv: None,
        accel: 0.0,
        steps: None,
        standards: vec![Standard::Fmi2, Standard::Fmi3],
    };
    let mut it = std::env::args().skip(1);
    let value = |it: &mut dyn Iterator<Item = String>, flag: &str| {
        it.next()
            .ok_or_else(|| format!("{flag} needs a value\n{USAGE}"))
    };
    let number = |text: &str, flag: &str| {
        text.trim()
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| {
                format!(
                    "{flag}: \"{}\" is not a finite number",
                    flexrod::text::echo(text)
                )
            })
    };
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "--out" => args.out = Some(PathBuf::from(value(&mut it, "--out")?)),
            "--simulate" => args.simulate = true,
            "--fmi" => {
                args.standards = match value(&mut it, "--fmi")?.as_str() {
                    "2" => vec![Standard::Fmi2],
                    "3" => vec![Standard::Fmi3],
                    other => {
                        return Err(format!(
                    "--fmi: \"{}\" is not a standard: allowed 2 or 3 (default: both)\n{USAGE}",
                    flexrod::text::echo(other)
                ))
                    }
                }
            }
            "--no-package" => args.package = false,
            "--csv" => {
                args.csv = Some(PathBuf::from(value(&mut it, "--csv")?));
                args.simulate = true;
            }
            "--accel" => args.accel = number(&value(&mut it, "--accel")?, "--accel")?,
            "--steps" => {
                let list = value(&mut it, "--steps")?;
                let steps = list
                    .split(',')
                    .map(|h| number(h, "--steps"))
                    .collect::<Result<Vec<_>, _>>()?;
                if steps.is_empty() || steps.iter().any(|&h| h <= 0.0) {
                    return Err(format!(
                        "--steps: \"{}\" must be positive steps",
                        flexrod::text::echo(&list)
                    ));
                }
                args.steps = Some(steps);
            }
            "-h" | "--help" => return Ok(None),
            flag if flag.starts_with('-') => {
                return Err(format!(
                    "unknown option {}\n{USAGE}",
                    flexrod::text::echo(flag)
                ))
            }
            path => args.scene = PathBuf::from(path),
        }
    }
    Ok(Some(args))
}

fn run() -> Result<(), Failure> {
    let Some(args) = parse_args().map_err(Failure::Usage)? else {
        println!("{HELP}");
        return Ok(());
    };

    let scene_text = flexrod::limits::read_text(
        &args.scene,
        flexrod::limits::SCENE_FILE_CAP,
        "the scene file",
    )?;
    let origin = args.scene.display().to_string();
    // The rod's scene, or `None` for another model ([`ModelKind`]).
    let scene = match ModelKind::of_scene_text(&scene_text) {
        ModelKind::Rod => {
            Some(Scene::from_toml_str(&scene_text, &origin).map_err(|e| e.to_string())?)
        }
        ModelKind::Crankshaft => None,
    };
    let describe = |standard: Standard| {
        ModelDescription::for_scene_text(&scene_text, &origin, standard).map_err(|e| {
            format!(
                "the scene {origin} does not give a valid {}model: {e}",
                match standard {
                    Standard::Fmi2 => "",
                    Standard::Fmi3 => "FMI 3.0 ",
                }
            )
        })
    };
    let description = describe(Standard::Fmi2)?;

    if args.simulate {
        let Some(scene) = &scene else {
            return Err(Failure::Usage(format!(
                "--simulate runs the rod's scenes; {origin} describes the crankshaft, whose FMU runs in an importer (e.g. FMPy)"
            )));
        };
        let e = &scene.experiment;
        simulate::check_length(
            e.start_time,
            e.stop_time,
            e.step_size,
            args.steps.as_deref(),
        )
        .map_err(Failure::Usage)?;
    }

    let mut fmu_path = None;
    if args.package {
        package::check_identifier(&description.info.name)?;
        package::check_experiment(&description.info.default_experiment, &origin)?;
        package::platform()?;
        let target_dir = package::target_dir()?;
        let library = package::build_library(&target_dir)?;
        let out_dir = args.out.clone().unwrap_or_else(|| target_dir.join("fmu"));
        for &standard in &args.standards {
            let description = match standard {
                Standard::Fmi2 => description.clone(),
                Standard::Fmi3 => describe(Standard::Fmi3)?,
            };
            let documentation = match &scene {
                Some(scene) => docs::index_html(scene, &description),
                None => docs::model_page(&description),
            };
            let fmu = package::write_fmu(
                &out_dir,
                &scene_text,
                &description,
                &documentation,
                &library,
            )?;
            println!(
                "wrote {} (FMI {}, {} {}, {} variables)",
                fmu.display(),
                standard.version(),
                standard.token_name(),
                description.guid,
                description.table.variables().len()
            );
            fmu_path.get_or_insert(fmu);
        }
    }

    if let (true, Some(scene)) = (args.simulate, &scene) {
        let options = simulate::Options {
            accel: args.accel,
            steps: args.steps.clone(),
        };
        let run = simulate::run(scene, &options)?;
        if let Some(csv) = &args.csv {
            let table = VariableTable::for_scene(scene, Standard::Fmi2.interface())
                .map_err(|e| e.to_string())?;
            simulate::write_csv(csv, &table, &run)?;
            println!("wrote {}", csv.display());
        }
        simulate::print_summary(scene, &run, fmu_path.as_deref());
    }
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Usage(message)) => {
            eprintln!("fmu: error: {message}");
            ExitCode::from(2)
        }
        Err(Failure::Run(message)) => {
            eprintln!("fmu: error: {message}");
            ExitCode::FAILURE
        }
    }
}
