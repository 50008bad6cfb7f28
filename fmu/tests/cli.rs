//! The packager's command line: `--help` prints the usage to stdout and exits 0; unknown
//! options and bad values are refused with exit code 2 before anything is built.

use std::process::{Command, Output};

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
