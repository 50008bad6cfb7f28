//! The `flexrod` command line as a user meets it: `--help` everywhere, bad command lines refused
//! with exit code 2 and a message that names the value and what is allowed (never a panic,
//! never a run of unbounded length), the stress columns of the CSV when the scene asks for
//! stress outputs, the warning when an `--input` table ends before the stop time, plots
//! against the crank angle in degrees with plain tick labels, summaries in the scene's words
//! (never a Rust name), and README.md's command lines run as written.

use std::path::PathBuf;
use std::process::{Command, Output};

mod common;

use common::summary::{rust_names, shipped_scenes};

fn flexrod(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flexrod"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the flexrod binary runs")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// A fresh directory for one test's files.
fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("cli_{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn help_everywhere() {
    for (args, usage) in [
        (&["--help"][..], "Usage: flexrod <COMMAND>"),
        (&["help"][..], "Usage: flexrod <COMMAND>"),
        (
            &["simulate", "--help"][..],
            "Usage: flexrod simulate [OPTIONS] [SCENE]",
        ),
        (
            &["modes", "--help"][..],
            "Usage: flexrod modes [OPTIONS] [SCENE]",
        ),
        (
            &["help", "simulate"][..],
            "Usage: flexrod simulate [OPTIONS] [SCENE]",
        ),
    ] {
        let out = flexrod(args);
        let stdout = text(&out.stdout);
        assert_eq!(
            out.status.code(),
            Some(0),
            "{args:?}: {}",
            text(&out.stderr)
        );
        assert!(stdout.contains(usage), "{args:?}:\n{stdout}");
    }
    let simulate = text(&flexrod(&["simulate", "--help"]).stdout);
    for option in [
        "--speed",
        "--revolutions",
        "--ramp",
        "--step",
        "--input",
        "--out",
        "--plot",
        "10^7",
    ] {
        assert!(simulate.contains(option), "{option}:\n{simulate}");
    }
    assert!(text(&flexrod(&["modes", "--help"]).stdout).contains("--csv"));
}

/// Each bad command line: exit code 2, the message parts on stderr, no panic, nothing on
/// stdout (no run started).
#[test]
fn bad_command_lines_are_refused() {
    let cases: &[(&[&str], &[&str])] = &[
        (&[], &["Usage: flexrod <COMMAND>"]),
        (
            &["simulat"],
            &["unrecognized subcommand 'simulat'", "simulate"],
        ),
        (
            &["simulate", "--revolutoins", "2"],
            &["unexpected argument '--revolutoins'", "'--revolutions'"],
        ),
        (
            &["modes", "--cvs", "x.csv"],
            &["unexpected argument '--cvs'"],
        ),
        (&["simulate", "-x"], &["unexpected argument '-x'"]),
        (
            &["simulate", "--revolutions", "-3"],
            &[
                "invalid value '-3' for '--revolutions <N>'",
                "allowed a finite number > 0",
            ],
        ),
        (
            &["simulate", "--revolutions", "0"],
            &["invalid value '0' for '--revolutions <N>'", "> 0"],
        ),
        (
            &["simulate", "--ramp", "-1"],
            &[
                "invalid value '-1' for '--ramp <SECONDS>'",
                "allowed a finite number > 0",
            ],
        ),
        (
            &["simulate", "--step", "0"],
            &[
                "invalid value '0' for '--step <SECONDS>'",
                "allowed a finite number > 0",
            ],
        ),
        (
            &["simulate", "--step", "NaN"],
            &["invalid value 'NaN' for '--step <SECONDS>'", "> 0"],
        ),
        (
            &["simulate", "--speed", "inf"],
            &["invalid value 'inf' for '--speed <RAD_PER_S>'", "finite"],
        ),
        (
            &["simulate", "--speed", "fast"],
            &[
                "invalid value 'fast' for '--speed <RAD_PER_S>'",
                "not a number",
            ],
        ),
        (
            &["simulate", "--speed"],
            &["'--speed <RAD_PER_S>'", "value"],
        ),
        (
            &["simulate", "--speed", "0", "--revolutions", "1"],
            &[
                "--revolutions 1 at crank speed 0 rad/s never ends",
                "W != 0",
            ],
        ),
        (
            &["simulate", "--revolutions", "1e300"],
            &[
                "--revolutions 1e300 at 150 rad/s",
                "4.189e302 communication points",
                "at most 10000000",
            ],
        ),
        (
            &["simulate", "--revolutions", "2", "--step", "1e-9"],
            &[
                "--step 1e-9 s",
                "83775805 communication points",
                "at most 10000000",
            ],
        ),
        (
            &["simulate", "--ramp", "0.1", "--input", "table.csv"],
            &["'--ramp <SECONDS>' cannot be used with '--input <CSV>'"],
        ),
    ];
    for (args, parts) in cases {
        let out = flexrod(args);
        let stderr = text(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
        assert!(out.stdout.is_empty(), "{args:?}: {}", text(&out.stdout));
        for part in *parts {
            assert!(stderr.contains(part), "{args:?}: '{part}' not in\n{stderr}");
        }
    }
}

#[test]
fn a_failing_run_exits_1() {
    let out = flexrod(&["simulate", "no_such_scene.toml"]);
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("no_such_scene.toml"), "{stderr}");
    let dir = scratch("bad_table");
    let table = dir.join("one_row.csv");
    std::fs::write(&table, "t,angle,speed\n0,0,150\n").unwrap();
    let out = flexrod(&["simulate", "--input", table.to_str().unwrap()]);
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("--input table") && stderr.contains("needs at least two rows"),
        "{stderr}"
    );
}

/// Header and rows of a CSV written by `flexrod simulate --out`.
fn read_csv(path: &std::path::Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let content = std::fs::read_to_string(path).unwrap();
    let mut lines = content.lines();
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

#[test]
fn stress_columns_when_the_scene_has_stress_outputs() {
    let dir = scratch("stress");
    let csv = dir.join("automotive.csv");
    let out = flexrod(&[
        "simulate",
        "scenes/automotive_rod.toml",
        "--revolutions",
        "0.5",
        "--out",
        csv.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let (header, rows) = read_csv(&csv);
    let stress = [
        "axial_force_mid",
        "bending_moment_mid",
        "stress_max",
        "stress_max_position",
    ];
    assert_eq!(header.len(), 16, "{header:?}");
    assert_eq!(header[12..], stress, "{header:?}");
    assert!(rows.len() > 100 && rows.iter().all(|r| r.len() == 16));
    // The section forces and stress are those of a loaded rod: the axial force at L/2 of the
    // order of the pin forces, the stress positive and located on the rod.
    let peak = |k: usize| rows.iter().map(|r| r[k].abs()).fold(0.0, f64::max);
    assert!(peak(12) > 1e3 && peak(12) < 1e5, "N_mid {}", peak(12));
    assert!(peak(13) > 0.0, "M_mid");
    assert!(rows.iter().all(|r| r[14] > 0.0 && r[14].is_finite()));
    assert!(rows.iter().all(|r| (0.0..=0.1507).contains(&r[15])));

    // Without [outputs] stress the CSV has the twelve columns only.
    let plain = dir.join("benchmark.csv");
    let out = flexrod(&["simulate", "--out", plain.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let (header, _) = read_csv(&plain);
    assert_eq!(header.len(), 12, "{header:?}");
    assert!(!header.iter().any(|h| stress.contains(&h.as_str())));
}

#[test]
fn warning_when_the_input_table_ends_before_the_stop_time() {
    let dir = scratch("table");
    let short = dir.join("short.csv");
    // The crank at rest up to t = 0.01 s; the default run goes on to 0.0838 s.
    std::fs::write(&short, "t,angle,speed\n0,0,0\n0.01,0,0\n").unwrap();
    let out = flexrod(&["simulate", "--input", short.to_str().unwrap()]);
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert!(
        stderr.contains("ends at t = 0.01 s, before the run's stop time 0.0838 s")
            && stderr.contains("past it the crank turns on at the last row's speed (angle 0 rad, speed 0 rad/s at the last row)"),
        "{stderr}"
    );
    // A table that covers the run: no warning.
    let long = dir.join("long.csv");
    std::fs::write(&long, "t,angle,speed\n0,0,150\n0.1,15,150\n").unwrap();
    let out = flexrod(&["simulate", "--input", long.to_str().unwrap()]);
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert!(!stderr.contains("ends at t ="), "{stderr}");
}

/// The text of every `<text>` element of an SVG document.
fn svg_texts(svg: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .map(|s| {
            let body = &s[s.find('>').unwrap() + 1..];
            body[..body.find("</text>").unwrap()].to_string()
        })
        .collect()
}

#[test]
fn plots_against_crank_angle_in_degrees_with_plain_ticks() {
    let dir = scratch("plot");
    for (scene, y_labels) in [
        ("scenes/benchmark.toml", ["v_mid / L", "force (N)"]),
        (
            "scenes/automotive_rod.toml",
            ["v_mid / L (×10⁻⁶)", "force (kN)"],
        ),
    ] {
        let prefix = dir.join("p");
        let out = flexrod(&[
            "simulate",
            scene,
            "--revolutions",
            "2",
            "--plot",
            prefix.to_str().unwrap(),
        ]);
        assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
        for (name, y_label) in ["deflection", "forces"].into_iter().zip(y_labels) {
            let svg = std::fs::read_to_string(dir.join(format!("p_{name}.svg"))).unwrap();
            let texts = svg_texts(&svg);
            assert!(texts.iter().any(|t| t == "crank angle (deg)"), "{texts:?}");
            assert!(texts.iter().any(|t| t == y_label), "{scene} {texts:?}");
            // Two revolutions: 0 to 720 degrees in steps of 90.
            for tick in ["0", "90", "360", "630"] {
                assert!(texts.iter().any(|t| t == tick), "{tick}: {texts:?}");
            }
            let numbers: Vec<&String> = texts.iter().filter(|t| t.parse::<f64>().is_ok()).collect();
            assert!(numbers.len() >= 12, "{texts:?}");
            for t in numbers {
                assert!(
                    !t.contains(['e', 'E']) && t.len() <= 6,
                    "tick label {t} in {texts:?}"
                );
            }
        }
    }
}

/// `flexrod modes` lists the modes the simulation uses: for the automotive rod the mass-loaded
/// modes up to its band (the piston-rod axial mode at 3268.5 Hz among them) retained, and the
/// bending modes above the band as static corrections; for the default scene the free modes by
/// count.
#[test]
fn modes_lists_what_the_simulation_uses() {
    let out = flexrod(&["modes", "scenes/automotive_rod.toml"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    assert!(stdout.contains("mass-loaded modes"), "{stdout}");
    assert!(stdout.contains("3 modes retained"), "{stdout}");
    let row = |mode: usize| {
        stdout
            .lines()
            .find(|l| l.split_whitespace().next() == Some(&mode.to_string()))
            .unwrap_or_else(|| panic!("mode {mode} listed:\n{stdout}"))
            .to_string()
    };
    assert!(row(2).contains("3268.52") && row(2).contains("axial") && row(2).ends_with("retained"));
    assert!(
        row(4).contains("bending") && row(4).ends_with("static correction"),
        "{}",
        row(4)
    );
    assert!(
        row(6).contains("axial") && row(6).ends_with("no"),
        "{}",
        row(6)
    );
    let default = text(&flexrod(&["modes"]).stdout);
    assert!(
        default.contains("free modes") && default.contains("rod.modes = 3"),
        "{default}"
    );
    // The bending modes left out are static corrections with a count of modes too.
    assert!(
        default.contains("37 bending modes left out as static corrections"),
        "{default}"
    );
}

/// The `cargo run --release --bin flexrod -- ...` lines of README.md's command-line quick start
/// run as written (the files they write go to a scratch folder) and print their summaries.
#[test]
fn readme_command_lines_run() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md"))
        .expect("read README.md");
    let prefix = "cargo run --release --bin flexrod -- ";
    let lines: Vec<&str> = readme
        .lines()
        .filter_map(|l| l.trim().strip_prefix(prefix))
        .collect();
    let commands: Vec<&str> = lines
        .iter()
        .filter_map(|l| l.split_whitespace().next())
        .collect();
    assert!(
        commands.contains(&"simulate") && commands.contains(&"modes"),
        "README.md shows no `{prefix}simulate` and `modes` line: {lines:?}"
    );
    let dir = scratch("readme");
    for line in lines {
        let mut args: Vec<String> = Vec::new();
        let mut written = Vec::new();
        let mut words = line.split_whitespace().peekable();
        while let Some(word) = words.next() {
            args.push(word.to_string());
            if matches!(word, "--out" | "--plot") {
                let value = words.next().expect("a value after --out or --plot");
                let path = dir.join(value);
                args.push(path.display().to_string());
                written.push((word, path));
            }
        }
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = flexrod(&args);
        assert_eq!(
            out.status.code(),
            Some(0),
            "README.md: {line}\n{}",
            text(&out.stderr)
        );
        let stdout = text(&out.stdout);
        assert!(stdout.contains("scene "), "{line}:\n{stdout}");
        for (flag, path) in written {
            let files = match flag {
                "--plot" => vec![
                    PathBuf::from(format!("{}_deflection.svg", path.display())),
                    PathBuf::from(format!("{}_forces.svg", path.display())),
                ],
                _ => vec![path],
            };
            for file in files {
                assert!(file.is_file(), "{line}: {} not written", file.display());
            }
        }
    }
}

#[test]
fn rust_names_are_found() {
    let scene = flexrod::Scene::benchmark();
    let text = format!(
        "scene {}: Ffr rod, 8 elements, SimplySupported; Consistent mass, ffr, simply_supported, \
         rod.mode_band_hz, RK4(3), ETDRK4, FFR rod, Runge-Kutta",
        scene.name
    );
    assert_eq!(
        rust_names(&text, &scene),
        ["Ffr", "SimplySupported", "Consistent"]
    );
}

/// The summaries of `flexrod simulate` and `flexrod modes` of every shipped scene speak the
/// scene's words: the rod model built and the one set (`rod.model = ...`), the reference
/// conditions and the element mass of the FFR rod as the scene spells them, and no Rust name.
#[test]
fn summaries_of_the_shipped_scenes_use_the_scenes_words() {
    for path in shipped_scenes(common::repository()) {
        let scene = flexrod::Scene::from_file(&path).expect("a shipped scene reads");
        let built = flexrod::Simulation::new(&scene)
            .expect("a shipped scene builds")
            .mechanism()
            .spec
            .rod
            .clone();
        let file = path.display().to_string();
        let ffr = built.model == flexrod::rod::RodModelKind::Ffr;
        for command in ["simulate", "modes"] {
            let out = flexrod(&[command, &file]);
            assert_eq!(out.status.code(), Some(0), "{command} {file}");
            let stdout = text(&out.stdout);
            let summary = stdout
                .lines()
                .take_while(|l| !l.starts_with("mode  frequency_hz"))
                .collect::<Vec<_>>()
                .join("\n");
            let names = rust_names(&summary, &scene);
            assert!(
                names.is_empty(),
                "{command} {file}: Rust names {names:?} in\n{summary}"
            );
            let mut words = vec![format!("scene {}", scene.name)];
            if command == "simulate" {
                words.push(format!("rod.model = {}", built.model.name()));
                if scene.rod.model != built.model {
                    words.push(format!("rod.model = {}", scene.rod.model.name()));
                }
            }
            if ffr {
                words.push(format!("rod.reference = {}", scene.rod.reference.name()));
            }
            if ffr && command == "modes" {
                words.push(format!("rod.mass = {}", scene.rod.mass.name()));
            }
            for word in words {
                assert!(
                    summary.contains(&word),
                    "{command} {file}: '{word}' not in\n{summary}"
                );
            }
        }
    }
}

/// The number in "N modes retained" of a summary.
fn retained(text: &str) -> Option<usize> {
    let at = text.find(" modes retained")?;
    text[..at].rsplit(' ').next()?.parse().ok()
}

/// `flexrod simulate` and `flexrod modes` of every shipped scene agree on how many modes the
/// FFR rod retains (the table of `modes` marks them); the automotive rod's band: its three
/// modes up to rod.mode_band_hz = 6000 Hz (2012 Hz bending, 3269 Hz axial, 5162 Hz bending),
/// with the band's limit named as such where the axial dynamics are chosen against it.
#[test]
fn simulate_and_modes_agree_on_the_retained_modes() {
    for path in shipped_scenes(common::repository()) {
        let file = path.display().to_string();
        let simulate = text(&flexrod(&["simulate", &file]).stdout);
        let modes = text(&flexrod(&["modes", &file]).stdout);
        let rows = modes.lines().filter(|l| l.ends_with(" retained")).count();
        let (in_simulate, in_modes) = (retained(&simulate), retained(&modes));
        assert!(in_simulate.is_some(), "{file}: simulate says\n{simulate}");
        assert_eq!(in_simulate, in_modes, "{file}:\n{simulate}\n{modes}");
        assert_eq!(in_modes, Some(rows), "{file}:\n{modes}");
    }
    let automotive = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/automotive_rod.toml");
    let simulate = text(&flexrod(&["simulate", automotive]).stdout);
    for part in [
        "3 modes retained (2 bending, 1 axial), every mode up to rod.mode_band_hz = 6000 Hz",
        "modes kept: 2012 Hz bending, 3269 Hz axial, 5162 Hz bending",
    ] {
        assert!(simulate.contains(part), "'{part}' not in\n{simulate}");
    }
    let modes = text(&flexrod(&["modes", automotive]).stdout);
    let class = modes.lines().next().unwrap_or_default();
    assert!(
        class.contains("against 1.5 x the mode band's limit rod.mode_band_hz = 6000 Hz"),
        "{class}"
    );
    assert!(!class.contains("retained bending mode"), "{class}");
}
