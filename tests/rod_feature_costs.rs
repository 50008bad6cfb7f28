//! The `rod-feature-costs` fragment is current.
//!
//! `examples/rod_feature_costs.rs` writes `docs/generated/rod-feature-costs.md` (`cargo run
//! --release --example rod_feature_costs -- --write`): wall times, which depend on the machine,
//! and internal step counts, which do not. This test runs every case of the example once (the
//! example's own case list and run loop, included below) and fails when the fragment's rows or
//! step counts differ from what the code computes now, so a change of the integrator or of the
//! scene that moves the step counts shows here.

mod common;

#[allow(dead_code)]
#[path = "../examples/rod_feature_costs.rs"]
mod costs;

/// (name, internal steps) of each row of the fragment's table.
fn fragment_rows(text: &str) -> Vec<(String, u64)> {
    text.lines()
        .skip(2) // header and separator
        .filter(|l| l.starts_with('|'))
        .map(|line| {
            let cells: Vec<&str> = line.trim_matches('|').split('|').map(str::trim).collect();
            assert_eq!(cells.len(), 4, "a row of four cells: {line}");
            let steps = cells[3]
                .parse()
                .unwrap_or_else(|_| panic!("steps in the last cell: {line}"));
            (cells[0].to_string(), steps)
        })
        .collect()
}

#[test]
fn fragment_rows_are_parsed() {
    let text = "| a | b | c | d |\n|---|---|---|---|\n| as shipped | 17 ms | 1.00 | 3113 |\n| x, y | 9 ms | 0.51 | 20 |\n";
    assert_eq!(
        fragment_rows(text),
        [("as shipped".to_string(), 3113), ("x, y".to_string(), 20)]
    );
}

#[test]
fn step_counts_of_the_fragment_are_current() {
    let path = common::repository().join(costs::FRAGMENT);
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    let in_fragment = fragment_rows(&text);
    let measured: Vec<(String, u64)> = costs::cases()
        .iter()
        .map(|(name, scene)| {
            let (seconds, steps) = costs::run(scene);
            println!("{name}: {steps} internal steps, {:.0} ms", seconds * 1e3);
            (name.to_string(), steps)
        })
        .collect();
    if in_fragment != measured {
        let show = |rows: &[(String, u64)]| {
            rows.iter()
                .map(|(n, s)| format!("{n}: {s}\n"))
                .collect::<String>()
        };
        panic!(
            "{} is stale (- the fragment, + measured now); rerun `cargo run --release --example \
             rod_feature_costs -- --write`, then `FLEXROD_BLESS=1 cargo test --release --test \
             generated_fragments`:\n{}",
            costs::FRAGMENT,
            common::line_diff(&show(&in_fragment), &show(&measured), 40)
        );
    }
}
