//! Reference runs pinned to their outputs and their step and Newton counts, so that a change
//! in results or in efficiency shows (after diffsol's snapshot tests of solver statistics).
//!
//! Each case drives the simulation at constant crank speed (or a ramp) and records every output
//! at every communication point, and the cumulative counters (steps, Newton iterations or
//! factorizations, halvings). `tests/data/golden_runs.txt` holds them, one block per case: the
//! case's name, a header that states its tolerance and names each column (output and unit),
//! one row per communication point, and the counts. Each value is written in Rust's shortest
//! round-trip form (`{:?}`: the shortest decimal that parses back to the same f64), so the file
//! reads as numbers and still pins every bit. The test compares within 1e-12 of each output's
//! peak over the case (CPU-dependent SIMD paths in the linear algebra may change the last bits
//! across machines) and the counters exactly; `FLEXROD_GOLDEN_EXACT=1` demands bit-identical
//! outputs (for refactorings on one machine), `FLEXROD_BLESS=1` (the bless variable of every generated file) rewrites the file (after
//! a change that is meant to alter results: say why in the commit), `FLEXROD_GOLDEN_REPORT=1`
//! prints the changes and the counts without failing.

use flexrod::drive::{self, communication_grid, CrankDrive};
use flexrod::scene::{DeflectionPolicy, RodModelKind, Scene, SolverMethod, StartDeflection};
use flexrod::{Outputs, Simulation};
use std::fmt::Write as _;

const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/golden_runs.txt");

struct Case {
    name: &'static str,
    scene: Scene,
    /// Crank speed at the start, rad/s, and the crank acceleration, rad/s^2.
    speed: f64,
    acceleration: f64,
    slider_force: f64,
    dt: f64,
    steps: usize,
}

fn cases() -> Vec<Case> {
    let base = Scene::benchmark;
    let mut ga = base();
    ga.solver.method = SolverMethod::GeneralizedAlpha;
    ga.solver.step = 5e-5;
    let mut seg = base();
    seg.rod.model = RodModelKind::Segments;
    seg.rod.elements = 16;
    seg.rod.damping_ratio = 0.02;
    seg.solver.step = 2e-5;
    let mut qs = base();
    qs.start.deflection = StartDeflection::QuasiStatic;
    qs.slider.mass = 0.05;
    let mut ga_slider = ga.clone();
    ga_slider.slider.mass = 0.1;
    ga_slider.rod.damping_ratio = 0.01;
    // The violent case: 600 rad/s, the chain deflects to 0.41 L in the second revolution, where
    // steps fail and are halved (the costly path; 0 halvings in every other case).
    let mut seg600 = base();
    seg600.rod.model = RodModelKind::Segments;
    seg600.rod.elements = 32;
    seg600.solver.step = 2.5e-5;
    seg600.solver.method = SolverMethod::GeneralizedAlpha;
    // Beyond the default deflection limit (0.05 L) on purpose: warn and continue.
    seg600.rod.deflection_policy = DeflectionPolicy::Warn;
    let two_revolutions = (4.0 * std::f64::consts::PI / 150.0 / 1e-4).round() as usize;
    vec![
        Case {
            name: "default scene, 150 rad/s, dt 1e-4, two revolutions",
            scene: base(),
            speed: 150.0,
            acceleration: 0.0,
            slider_force: 0.0,
            dt: 1e-4,
            steps: two_revolutions,
        },
        Case {
            name: "generalized-alpha h 5e-5, 150 rad/s, dt 1e-4",
            scene: ga,
            speed: 150.0,
            acceleration: 0.0,
            slider_force: 0.0,
            dt: 1e-4,
            steps: 420,
        },
        Case {
            name: "segments N 16, damping 0.02, h 2e-5, 150 rad/s, dt 2e-4",
            scene: seg,
            speed: 150.0,
            acceleration: 0.0,
            slider_force: 0.0,
            dt: 2e-4,
            steps: 210,
        },
        Case {
            name: "quasi-static start, slider 0.05 kg, 150 rad/s, dt 1e-4",
            scene: qs,
            speed: 150.0,
            acceleration: 0.0,
            slider_force: 0.0,
            dt: 1e-4,
            steps: 420,
        },
        Case {
            name: "generalized-alpha, slider 0.1 kg, force -200 N, ramp 50 rad/s + 2000 rad/s^2",
            scene: ga_slider,
            speed: 50.0,
            acceleration: 2000.0,
            slider_force: -200.0,
            dt: 2.5e-4,
            steps: 200,
        },
        Case {
            name: "segments N 32, h 2.5e-5, 600 rad/s, dt 1e-4, two revolutions (step halvings)",
            scene: seg600,
            speed: 600.0,
            acceleration: 0.0,
            slider_force: 0.0,
            dt: 1e-4,
            steps: 209,
        },
    ]
}

fn output_values(o: &Outputs) -> [f64; 9] {
    o.named().map(|(_, x)| x)
}

/// The unit of each output of [`Outputs::named`], in its order.
const UNITS: [&str; 9] = ["m", "1", "N", "N", "N", "N", "N m", "m", "m/s"];

/// Largest change of an output, as a fraction of its peak over the case.
const TOLERANCE: f64 = 1e-12;

/// Width of a column of the data file.
const WIDTH: usize = 24;

/// The lines of the data file before the first case.
const PREAMBLE: &str = "\
# Reference runs of tests/golden_runs.rs, one block per case: its name, its tolerance, the
# outputs (one column each, named with its unit) at every communication point as the shortest
# decimal that parses back to the same f64, and the cumulative step, iteration and halving
# counts at the end.
";

/// A case's header lines: its tolerance and the columns.
fn case_header() -> String {
    let mut text = format!(
        "# tolerance: each output within {TOLERANCE:e} of its peak over the case \
         (bit-identical with FLEXROD_GOLDEN_EXACT=1); counts exact\n#"
    );
    for ((name, _), unit) in Outputs::default().named().iter().zip(UNITS) {
        write!(text, " {:>WIDTH$}", format!("{name} [{unit}]")).unwrap();
    }
    text.push('\n');
    text
}

/// One row of outputs: each in Rust's shortest round-trip form (`{:?}`), so that parsing it
/// gives the same bits.
fn format_row(values: &[f64]) -> String {
    let mut text = String::new();
    for x in values {
        write!(text, " {x:>WIDTH$?}").unwrap();
    }
    text.push('\n');
    text
}

/// Run a case: returns the text block of the data file.
fn run(case: &Case) -> String {
    let drive = CrankDrive::UniformAcceleration {
        speed: case.speed,
        acceleration: case.acceleration,
    };
    let mut sim = Simulation::new(&case.scene).unwrap();
    let grid = communication_grid(0.0, case.dt, case.steps);
    let record = drive::run(&mut sim, &drive, case.slider_force, &grid).unwrap();
    let mut text = format!("case {}\n", case.name);
    text.push_str(&case_header());
    for o in &record.outputs {
        text.push_str(&format_row(&output_values(o)));
    }
    let s = record.stats;
    writeln!(
        text,
        "counts steps {} iterations {} halvings {}",
        s.steps, s.newton_iterations, s.halvings
    )
    .unwrap();
    text
}

/// One case of the data file.
struct Block<'a> {
    name: &'a str,
    /// The `#` lines after the name.
    header: Vec<&'a str>,
    rows: Vec<Vec<f64>>,
    counts: &'a str,
}

/// The cases of a data file's text (the lines before the first case left out).
fn parse(text: &str) -> Vec<Block<'_>> {
    let mut blocks: Vec<Block> = Vec::new();
    for line in text.lines() {
        if let Some(name) = line.strip_prefix("case ") {
            blocks.push(Block {
                name,
                header: Vec::new(),
                rows: Vec::new(),
                counts: "",
            });
            continue;
        }
        let Some(block) = blocks.last_mut() else {
            continue;
        };
        if line.starts_with('#') {
            block.header.push(line);
        } else if line.starts_with("counts ") {
            block.counts = line;
        } else {
            let row = line.split_whitespace().map(|x| x.parse().unwrap());
            block.rows.push(row.collect());
        }
    }
    blocks
}

#[test]
fn reference_runs_are_unchanged() {
    let blocks: Vec<String> = cases().iter().map(run).collect();
    if std::env::var_os("FLEXROD_BLESS").is_some_and(|v| v == "1") {
        std::fs::write(DATA, PREAMBLE.to_string() + &blocks.concat()).unwrap();
        return;
    }
    let exact = std::env::var_os("FLEXROD_GOLDEN_EXACT").is_some();
    let stored = std::fs::read_to_string(DATA).expect("tests/data/golden_runs.txt");
    let stored_blocks = parse(&stored);
    assert_eq!(stored_blocks.len(), blocks.len(), "number of cases");
    let report_only = std::env::var_os("FLEXROD_GOLDEN_REPORT").is_some();
    for (new, old) in blocks.iter().zip(stored_blocks) {
        let new = parse(new).pop().unwrap();
        let name = new.name;
        assert_eq!(name, old.name, "case order");
        assert_eq!(
            new.header, old.header,
            "{name}: header (columns, tolerance)"
        );
        let (a, b) = (&new.rows, &old.rows);
        assert_eq!(a.len(), b.len(), "{name}: number of communication points");
        let mut worst: f64 = 0.0;
        let mut worst_output = 0;
        for j in 0..9 {
            let peak = b.iter().map(|r| r[j].abs()).fold(0.0, f64::max).max(1e-300);
            for (ra, rb) in a.iter().zip(b) {
                let change = (ra[j] - rb[j]).abs() / peak;
                if change > worst {
                    worst = change;
                    worst_output = j;
                }
                if exact {
                    assert_eq!(
                        ra[j].to_bits(),
                        rb[j].to_bits(),
                        "{name}: output {j} not bit-identical"
                    );
                }
            }
        }
        println!(
            "{name}: largest change {worst:.2e} of peak (output {}); {}",
            Outputs::default().named()[worst_output].0,
            new.counts
        );
        if report_only {
            println!("  before: {}", old.counts);
            continue;
        }
        assert!(
            worst <= TOLERANCE,
            "{name}: outputs changed by {worst:e} of their peak"
        );
        assert_eq!(new.counts, old.counts, "{name}: step and iteration counts");
    }
}

/// Every stored value is the shortest decimal of its f64: formatting the parsed rows again
/// gives the file's rows, character for character.
#[test]
fn stored_values_are_in_shortest_round_trip_form() {
    let stored = std::fs::read_to_string(DATA).expect("tests/data/golden_runs.txt");
    let rows = stored
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("case ") && !l.starts_with("counts "));
    let mut n = 0;
    for line in rows {
        let values: Vec<f64> = line
            .split_whitespace()
            .map(|x| x.parse().unwrap())
            .collect();
        assert_eq!(values.len(), 9, "{line}");
        assert_eq!(format_row(&values), format!("{line}\n"));
        n += 1;
    }
    assert!(n > 2000, "{n} rows");
}
