//! `report`: error against run time of the rod models and solver settings.
//!
//! ```sh
//! cargo run --release --bin report            # full matrix: docs/report/, docs/generated/
//! cargo run --release --bin report -- --quick # reduced matrix (also run by `cargo test --bin report`)
//! cargo run --release --bin report -- --out DIR [--fragments DIR]
//! ```
//!
//! For each benchmark case ([`cases`]: constant 150 rad/s from an undeformed start; a smooth
//! start to 150 rad/s; constant 300 rad/s; 150 rad/s with a 0.03 kg slider) and each setting
//! ([`settings`]: rod model, elements, modes, reference conditions, solver step h, rho_inf) it
//! runs the case through `flexrod::drive::run` for two revolutions of the final speed after
//! its start, with the communication step equal to the solver step ([`timing`]), and measures
//! against the case's reference (finite segments, N = 64, h = 1e-5 s; [`metrics`]):
//! - deflection error: max |v_mid/L - v_ref/L| over the setting's communication points (a
//!   subset of the reference's grid) / max |v_ref/L|; and the peak error max|v|/max|v_ref| - 1;
//! - pin B force error: max |F_B - F_B,ref| (vector norm) / max |F_B,ref|; on the smooth start
//!   directly, on the abrupt starts after a zero-phase 4th-order Butterworth low-pass at 2 kHz
//!   ([`filter`]) applied to both signals on the reference's grid (the setting's forces
//!   interpolated linearly onto it), ignoring 1 ms at both ends;
//! - run time: median of at least 5 in-process repeats on one thread (each a whole
//!   `drive::run`: `Simulation::start` and the loop of `set_input` + `advance` + reading the
//!   outputs; `Simulation::new` excluded), as ms per simulated second and real-time factor
//!   (simulated time / wall time);
//! - internal steps, Newton iterations, step halvings.
//!
//! The engine section ([`engine`]): the automotive rod (`scenes/automotive_rod.toml`) in its
//! engine run with a gas pulse against the geometrically exact shear beam, both rod models,
//! errors against run time.
//!
//! Outputs: `report.csv` ([`csv`]), `report.md` ([`markdown`]), `error_vs_runtime.svg`
//! ([`svg`]) in the output folder; the full matrix into the default folder also writes the
//! README-facing fragments `docs/generated/report-*.md` ([`fragments`]; [`pareto`] picks the
//! front and the fastest settings).

// Index loops are the natural notation for the filter and plot formulas.
#![allow(clippy::needless_range_loop)]

mod cases;
mod csv;
mod engine;
mod filter;
mod fragments;
mod markdown;
mod metrics;
mod pareto;
mod progress;
mod rows;
mod settings;
mod svg;
mod timing;

use std::path::{Path, PathBuf};
use std::time::Instant;

use cases::{cases, Case};
use markdown::pct;
use rows::Row;
use settings::{matrix, reference_setting, Setting};

const USAGE: &str = "usage: report [--quick] [--out DIR] [--fragments DIR]  (default DIR: docs/report; fragments: docs/generated for the full matrix into docs/report, else only with --fragments)";

struct Options {
    quick: bool,
    out: PathBuf,
    /// Where the README-facing fragments go (None: not written).
    fragments: Option<PathBuf>,
}

fn repository_path(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(relative)
}

fn parse_args() -> Result<Options, String> {
    let mut quick = false;
    let mut out = None;
    let mut fragments = None;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--quick" => quick = true,
            "--out" => out = Some(PathBuf::from(args.next().ok_or("--out needs a folder")?)),
            "--fragments" => {
                fragments = Some(PathBuf::from(
                    args.next().ok_or("--fragments needs a folder")?,
                ))
            }
            "-h" | "--help" => return Err(USAGE.into()),
            other => return Err(format!("unknown argument {other}; {USAGE}")),
        }
    }
    // The checked-in fragments come only from the full matrix written to the checked-in report.
    let fragments =
        fragments.or_else(|| (!quick && out.is_none()).then(|| repository_path("docs/generated")));
    let out = out.unwrap_or_else(|| repository_path("docs/report"));
    Ok(Options {
        quick,
        out,
        fragments,
    })
}

/// Run every setting of the matrix on `case`; the reference first (every other setting is
/// compared with its record). Returns the case's rows (front marked) and the reference peak.
fn run_case(
    case: &Case,
    settings: &[Setting],
    reference: &Setting,
    min_repeats: usize,
    exudyn_data: &[(f64, f64)],
    progress: &mut progress::Progress,
) -> Result<(Vec<Row>, f64), String> {
    let ref_run = timing::timed_runs(reference, case, min_repeats)
        .map_err(|e| format!("case {}: the reference run failed: {e}", case.key))?;
    let mut rows = Vec::new();
    for s in settings {
        let is_reference = s.same_run(reference);
        progress.tick(&format!("case {}: {}", case.key, s.label()));
        let row = if is_reference {
            Row::measured(case, s, true, &ref_run, &ref_run, exudyn_data)
        } else {
            match timing::timed_runs(s, case, min_repeats) {
                Ok(t) => Row::measured(case, s, false, &t, &ref_run, exudyn_data),
                Err(e) => Row::failed(case, s, false, &e),
            }
        };
        rows.push(row);
    }
    pareto::mark_pareto(&mut rows);
    Ok((rows, metrics::peak(&ref_run.series.v)))
}

fn write_file(folder: &Path, name: &str, text: &str) -> Result<(), String> {
    std::fs::create_dir_all(folder)
        .map_err(|e| format!("cannot create {}: {e}", folder.display()))?;
    let path = folder.join(name);
    std::fs::write(&path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))
}

/// Run the matrix and write the report files (and the fragments, if asked). Returns the rows.
fn run_report(options: &Options) -> Result<Vec<Row>, String> {
    let clock = Instant::now();
    let quick = options.quick;
    let all_cases = cases();
    let settings = matrix(quick);
    let reference = reference_setting(quick);
    let min_repeats = if quick { 3 } else { 5 };
    let exudyn_data = metrics::exudyn();
    let mut progress = progress::Progress::new(all_cases.len() * settings.len());
    let mut rows: Vec<Row> = Vec::new();
    let mut peaks = Vec::new();
    for case in &all_cases {
        let (case_rows, peak) = run_case(
            case,
            &settings,
            &reference,
            min_repeats,
            &exudyn_data,
            &mut progress,
        )?;
        rows.extend(case_rows);
        peaks.push((case.key, peak));
    }
    progress.finish();
    println!("the automotive rod's engine run ...");
    let engine_rows = engine::measure(quick)?;
    let engine_table = engine::table(&engine_rows);
    let out = &options.out;
    write_file(out, "report.csv", &csv::csv(&rows))?;
    let summary = markdown::Summary {
        reference: &reference,
        peaks: &peaks,
        quick,
        seconds: clock.elapsed().as_secs_f64(),
    };
    let engine_section = format!(
        "\n## The automotive rod in its engine run\n\n`scenes/automotive_rod.toml` undamped, ramp to 6000 rpm over 40 ms, two revolutions, a 38 kN gas pulse at firing (`flexrod::drive::engine`), against the geometrically exact shear beam `tests/data/exudyn_automotive_rod.csv`: largest pointwise differences relative to the reference's peaks (firing: 60 degrees before to 120 after the gas peak), and the median wall time of {} run(s).\n\n{engine_table}",
        if quick { 1 } else { 3 }
    );
    write_file(
        out,
        "report.md",
        &(markdown::markdown(&rows, &all_cases, &summary) + &engine_section),
    )?;
    write_file(out, "error_vs_runtime.svg", &figure(&rows, &all_cases))?;
    if let Some(folder) = &options.fragments {
        let default_setting = Setting::default_scene().map_err(|e| e.to_string());
        for f in fragments::fragments(&rows, &all_cases, default_setting) {
            write_file(folder, &format!("{}.md", f.id), &f.text)?;
        }
        write_file(
            folder,
            "report-engine.md",
            &format!("{}{engine_table}", fragments::SOURCE),
        )?;
    }
    Ok(rows)
}

/// Error against run time, one panel per case.
fn figure(rows: &[Row], cases: &[Case]) -> String {
    let panels: Vec<svg::Panel> = cases
        .iter()
        .map(|c| svg::Panel {
            title: c.title.to_string(),
            points: rows
                .iter()
                .filter(|r| r.case == c.key && r.ok() && !r.is_reference)
                .map(|r| svg::Point {
                    time: r.ms_per_s,
                    error: r.error,
                    model: r.setting.model.index(),
                    pareto: r.pareto,
                })
                .collect(),
        })
        .collect();
    svg::error_vs_runtime(
        "Deflection error against run time (reference: segments N = 64, h = 1e-5 s)",
        &panels,
    )
}

fn main() {
    let options = match parse_args() {
        Ok(o) => o,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(2);
        }
    };
    let rows = match run_report(&options) {
        Ok(rows) => rows,
        Err(e) => {
            eprintln!("report failed: {e}");
            std::process::exit(1);
        }
    };
    for c in &cases() {
        match pareto::fastest_within(&rows, c.key, 5e-3) {
            Some(r) => println!(
                "case {}: fastest within 0.5 %: {} ({}, {:.1} ms/s, RTF {:.1})",
                c.key,
                r.setting.label(),
                pct(r.error),
                r.ms_per_s,
                r.rtf
            ),
            None => println!("case {}: no setting within 0.5 %", c.key),
        }
    }
    println!(
        "wrote {}/report.csv, report.md, error_vs_runtime.svg",
        options.out.display()
    );
    if let Some(folder) = &options.fragments {
        println!(
            "wrote the fragments {}/report-*.md; `FLEXROD_BLESS=1 cargo test --release --test generated_fragments` copies them into the docs that embed them",
            folder.display()
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use flexrod::drive::CrankDrive;

    #[test]
    fn cases_are_the_documented_drives() {
        let c = cases();
        assert_eq!(c[0].drive, CrankDrive::Constant { speed: 150.0 });
        assert_eq!(
            c[1].drive,
            CrankDrive::Ramp {
                speed: 150.0,
                time: 0.02
            }
        );
        assert!((c[1].drive.at(0.02).speed - 150.0).abs() < 1e-12);
        assert!(c[0].abrupt() && !c[1].abrupt());
        let two_revolutions = 4.0 * std::f64::consts::PI / 150.0;
        assert!((c[1].duration() - (0.02 + two_revolutions)).abs() < 1e-15);
    }

    /// The default scene's setting is in both matrices (the speed fragment reports it).
    #[test]
    fn default_scene_setting_is_in_the_matrix() {
        let d = Setting::default_scene().unwrap();
        for quick in [true, false] {
            assert!(matrix(quick).iter().any(|s| s.same_run(&d)), "{d:?}");
        }
    }

    /// The quick matrix end to end (exercises the whole report in CI, well under 60 s).
    #[test]
    fn quick_report_runs() {
        let out = std::env::temp_dir().join(format!("flexrod-report-quick-{}", std::process::id()));
        let options = Options {
            quick: true,
            out: out.clone(),
            fragments: Some(out.join("generated")),
        };
        let rows = run_report(&options).unwrap();
        assert!(
            rows.iter().all(|r| r.ok()),
            "{:?}",
            rows.iter()
                .filter(|r| !r.ok())
                .map(|r| &r.status)
                .collect::<Vec<_>>()
        );
        for name in ["report.csv", "report.md", "error_vs_runtime.svg"] {
            let text = std::fs::read_to_string(out.join(name)).unwrap();
            assert!(text.len() > 200, "{name}");
        }
        for id in [
            "report-fastest",
            "report-front",
            "report-speed",
            "report-engine",
        ] {
            let text =
                std::fs::read_to_string(out.join("generated").join(format!("{id}.md"))).unwrap();
            assert!(text.starts_with("<!--") && text.contains("\n|---|"), "{id}");
        }
        // The reference has zero error; some setting is on each case's front.
        for c in cases() {
            assert!(rows
                .iter()
                .any(|r| r.case == c.key && r.is_reference && r.error == 0.0));
            assert!(rows.iter().any(|r| r.case == c.key && r.pareto));
        }
        let _ = std::fs::remove_dir_all(&out);
    }
}
