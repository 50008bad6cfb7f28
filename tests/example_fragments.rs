//! The fragments written by examples are current.
//!
//! `examples/exponential_choice.rs` and `examples/speed.rs` print the table they write to
//! `docs/generated/<id>.md` (with `FLEXROD_BLESS=1`). Each test here runs the example
//! (`cargo run --release --example NAME`) and compares what it prints with the committed
//! fragment: `exponential-choice` byte for byte (steps, right-hand sides and errors do not
//! depend on the machine), `speed-minimal` with its times masked (its step and right-hand-side
//! counts and the peak do not depend on the machine; its times do). With `FLEXROD_BLESS=1` the
//! examples rewrite their fragments instead. (`rod-feature-costs`: `tests/rod_feature_costs.rs`.)
//! `examples/long_run.rs` (`long-run`, byte for byte) runs for minutes: its test is ignored
//! (`cargo test --release --test example_fragments long_run -- --ignored`).

mod common;

/// What `cargo run --release --example NAME` prints, and the committed fragment named `id`; `None`
/// when blessing (the example has then rewritten the fragment).
fn run_example(name: &str, id: &str) -> Option<(String, String)> {
    let out = std::process::Command::new(env!("CARGO"))
        .args(["run", "--release", "-q", "--example", name])
        .current_dir(common::repository())
        .output()
        .unwrap_or_else(|e| panic!("cannot run cargo: {e}"));
    assert!(
        out.status.success(),
        "cargo run --release --example {name} failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    if common::blessing() {
        return None;
    }
    let path = common::fragment_path(id);
    let committed = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    Some((
        committed,
        String::from_utf8(out.stdout).expect("UTF-8 output"),
    ))
}

/// `text` with every number that is a time (followed by `ms`, `ns`, `us` or `x real time`)
/// replaced by `#`.
fn mask_times(text: &str) -> String {
    text.lines()
        .map(|line| {
            let words: Vec<&str> = line.split(' ').collect();
            let masked: Vec<String> = words
                .iter()
                .enumerate()
                .map(|(k, w)| {
                    let next = words.get(k + 1).copied().unwrap_or("");
                    let after = words.get(k + 2).copied().unwrap_or("");
                    let unit = ["ms", "ms;", "ns", "us"].contains(&next)
                        || (next == "x" && after == "real");
                    let number = w.trim_start_matches('(');
                    if unit && number.parse::<f64>().is_ok() {
                        format!("{}#", &w[..w.len() - number.len()])
                    } else {
                        w.to_string()
                    }
                })
                .collect();
            masked.join(" ")
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn times_are_masked() {
    assert_eq!(
        mask_times(
            "| 0.282 ms (297 x real time); 98 steps | 210 ns / 266 ns | 0.61 us a call | 1.5e-2 |"
        ),
        "| # ms (# x real time); 98 steps | # ns / # ns | # us a call | 1.5e-2 |"
    );
}

#[test]
fn exponential_choice_is_current() {
    let Some((committed, printed)) = run_example("exponential_choice", "exponential-choice") else {
        return;
    };
    assert!(
        committed == printed,
        "docs/generated/exponential-choice.md is stale (- the file, + what the example computes \
         now); `FLEXROD_BLESS=1 cargo run --release --example exponential_choice` rewrites it:\n{}",
        common::line_diff(&committed, &printed, 40)
    );
}

#[test]
fn speed_minimal_counts_are_current() {
    let Some((committed, printed)) = run_example("speed", "speed-minimal") else {
        return;
    };
    let (committed, printed) = (mask_times(&committed), mask_times(&printed));
    assert!(
        committed == printed,
        "docs/generated/speed-minimal.md is stale beyond its times (- the file, + what the \
         example computes now); `FLEXROD_BLESS=1 cargo run --release --example speed` rewrites \
         it:\n{}",
        common::line_diff(&committed, &printed, 40)
    );
}

#[test]
#[ignore = "three runs of 100,000 revolutions (minutes)"]
fn long_run_is_current() {
    let Some((committed, printed)) = run_example("long_run", "long-run") else {
        return;
    };
    assert!(
        committed == printed,
        "docs/generated/long-run.md is stale (- the file, + what the example computes now); \
         `FLEXROD_BLESS=1 cargo run --release --example long_run` rewrites it:\n{}",
        common::line_diff(&committed, &printed, 40)
    );
}
