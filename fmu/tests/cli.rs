//! The packager's command line: `--help` prints the usage to stdout and exits 0; unknown
//! options and bad values are refused with exit code 2 before anything is built; the
//! `--simulate` summary of every shipped scene speaks the scene's words.

use std::process::{Command, Output};

#[path = "../../tests/common/summary.rs"]
mod summary;

fn fmu(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_fmu"))
        .args(args)
        .output()
        .expect("the fmu binary runs")
}

#[test]
fn help_goes_to_stdout_with_exit_code_0() {
    for flag in ["--help", "-h"] {
        let out = fmu(&[flag]);
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert_eq!(out.status.code(), Some(0), "{flag}");
        assert!(out.stderr.is_empty(), "{flag}");
        assert!(stdout.contains("usage: fmu [SCENE.toml]"), "{stdout}");
        for option in [
            "--out DIR",
            "--fmi 2|3",
            "--simulate",
            "--csv FILE",
            "--no-package",
        ] {
            assert!(stdout.contains(option), "{option}: {stdout}");
        }
    }
}

#[test]
fn bad_command_lines_are_refused() {
    for (args, message) in [
        (&["--bogus"][..], "unknown option --bogus"),
        (&["--no-pakage"][..], "unknown option --no-pakage"),
        (
            &["--fmi", "4"][..],
            "--fmi: \"4\" is not a standard: allowed 2 or 3",
        ),
        (&["--out"][..], "--out needs a value"),
        (
            &["--accel", "x"][..],
            "--accel: \"x\" is not a finite number",
        ),
        (&["--steps", "1e-4,-1"][..], "must be positive steps"),
    ] {
        let out = fmu(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(message), "{args:?}: {stderr}");
        assert!(out.stdout.is_empty(), "{args:?}");
    }
}

/// `--simulate` past the point cap that `flexrod simulate` shares
/// (`flexrod::limits::MAX_POINTS`) is refused before anything is allocated or built, naming
/// the flag, the points it would need and the cap; a child past 60 s fails the test.
#[test]
fn simulate_past_the_shared_point_cap_is_refused() {
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/benchmark.toml");
    for steps in ["1e-9", "1e-4,1e-3"] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_fmu"))
            .args([scene, "--no-package", "--simulate", "--steps", steps])
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .expect("the fmu binary runs");
        let t0 = std::time::Instant::now();
        while child.try_wait().expect("the child's status").is_none() {
            if t0.elapsed() > std::time::Duration::from_secs(60) {
                let _ = child.kill();
                let _ = child.wait();
                panic!("--steps {steps}: the packager ran past 60 s");
            }
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
        let out = child.wait_with_output().expect("the child's output");
        let stderr = String::from_utf8_lossy(&out.stderr);
        if steps == "1e-9" {
            assert_eq!(out.status.code(), Some(2), "{stderr}");
            for part in [
                "--steps 1e-9",
                "83800001 communication points",
                &format!("at most {}", flexrod::limits::MAX_POINTS),
            ] {
                assert!(stderr.contains(part), "'{part}' not in {stderr}");
            }
            assert!(out.stdout.is_empty());
        } else {
            // 155 points: within the cap, the run completes.
            assert_eq!(out.status.code(), Some(0), "{stderr}");
        }
    }
}

/// `--simulate` of every shipped scene: its summary names the rod model built and how it was
/// chosen, as the scene spells them, and no Rust name (`tests/common/summary.rs`).
#[test]
fn simulate_summaries_of_the_shipped_scenes_use_the_scenes_words() {
    let repository = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."));
    for path in summary::shipped_scenes(repository) {
        let scene = flexrod::Scene::from_file(&path).expect("a shipped scene reads");
        let built = flexrod::Simulation::new(&scene)
            .expect("a shipped scene builds")
            .mechanism()
            .spec
            .rod
            .clone();
        let file = path.display().to_string();
        let out = fmu(&[&file, "--no-package", "--simulate"]);
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert_eq!(out.status.code(), Some(0), "{file}: {stdout}");
        let names = summary::rust_names(&stdout, &scene);
        assert!(
            names.is_empty(),
            "{file}: Rust names {names:?} in\n{stdout}"
        );
        let set = match scene.rod.model {
            flexrod::rod::RodModelKind::Auto => "(auto: ".to_string(),
            model => format!("(set {})", model.name()),
        };
        for word in [
            format!("{}: t = ", scene.name),
            format!("rod model {} {set}", built.model.name()),
        ] {
            assert!(stdout.contains(&word), "{file}: '{word}' not in\n{stdout}");
        }
    }
}

/// The automotive rod's summary says what it retains and what its band is: three modes up to
/// rod.mode_band_hz = 6000 Hz (the highest retained bending mode is 5162 Hz), and the axial
/// dynamics chosen against the band's limit, named as such.
#[test]
fn automotive_summary_names_the_retained_modes_and_the_band() {
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/automotive_rod.toml");
    let out = fmu(&[scene, "--no-package", "--simulate"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{stdout}");
    for part in [
        "  rod: rod.model = ffr, rod.elements = 8, rod.reference = simply_supported",
        "3 modes retained (2 bending, 1 axial), every mode up to rod.mode_band_hz = 6000 Hz",
        "modes kept: 2012 Hz bending, 3269 Hz axial, 5162 Hz bending",
        "against 1.5 x the mode band's limit rod.mode_band_hz = 6000 Hz",
    ] {
        assert!(stdout.contains(part), "'{part}' not in\n{stdout}");
    }
    assert!(!stdout.contains("4 modes"), "{stdout}");
    assert!(!stdout.contains("retained bending mode 6000"), "{stdout}");
}
