//! The README-facing extracts of the report, written as generated fragments
//! `docs/generated/<id>.md` (the convention is in `tests/generated_fragments.rs`: README.md and
//! docs/*.md embed each between `<!-- generated: <id> -->` and `<!-- end generated: <id> -->`,
//! and that test checks the embedded copies against these files).
//!
//! - `report-fastest`: per case, the fastest setting reaching 0.5 % (pointwise and peak), and
//!   the fastest FFR stiffened (generalized-alpha) and FFR linear ones;
//! - `report-front`: the front of each case sampled at pointwise errors from 2 % to 0.1 %: the
//!   fastest setting reaching each;
//! - `report-speed`: the default scene's setting (`scenes/benchmark.toml`) in every case:
//!   accuracy, run time, real-time factor.

use std::fmt::Write as _;

use crate::cases::Case;
use crate::markdown::{pct, pct_signed};
use crate::pareto::{fastest_model_within, fastest_within, front_at};
use crate::rows::Row;
use crate::settings::{Model, Setting};

/// A generated fragment: `docs/generated/<id>.md`.
pub struct Fragment {
    pub id: &'static str,
    pub text: String,
}

/// The first line of every fragment (invisible when rendered).
pub const SOURCE: &str = "<!-- written by `cargo run --release --bin report` (src/bin/report/fragments.rs): rerun it, do not edit -->\n";

/// The accuracy target of the fastest-setting table.
const TARGET: f64 = 5e-3;

/// The pointwise errors at which the front is sampled.
const FRONT_LEVELS: [f64; 5] = [2e-2, 1e-2, 5e-3, 2.5e-3, 1e-3];

/// The fragments of a full report. `default_setting`: the default scene's setting, or why it
/// could not be built.
pub fn fragments(
    rows: &[Row],
    cases: &[Case],
    default_setting: Result<Setting, String>,
) -> Vec<Fragment> {
    vec![
        Fragment {
            id: "report-fastest",
            text: format!("{SOURCE}{}", fastest_table(rows, cases)),
        },
        Fragment {
            id: "report-front",
            text: format!("{SOURCE}{}", front_table(rows, cases)),
        },
        Fragment {
            id: "report-speed",
            text: format!("{SOURCE}{}", speed_table(rows, cases, default_setting)),
        },
    ]
}

/// Per case: the fastest setting reaching 0.5 % in both pointwise and peak error, and the
/// fastest FFR stiffened and FFR linear ones (generalized-alpha).
pub fn fastest_table(rows: &[Row], cases: &[Case]) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "| case | fastest overall | error | peak | ms/s | RTF | fastest FFR stiffened (error) | fastest FFR linear |");
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|");
    let desc = |r: &Option<Row>| {
        r.as_ref()
            .map(|r| {
                format!(
                    "{} ({}, {:.0} ms/s)",
                    r.setting.label(),
                    pct(r.error),
                    r.ms_per_s
                )
            })
            .unwrap_or_else(|| "none in the matrix".into())
    };
    for c in cases {
        let ffr = desc(&fastest_model_within(
            rows,
            c.key,
            TARGET,
            Model::FfrStiffened,
        ));
        let lin = desc(&fastest_model_within(rows, c.key, TARGET, Model::FfrLinear));
        let _ = match fastest_within(rows, c.key, TARGET) {
            Some(r) => writeln!(
                s,
                "| {} | {} | {} | {} | {:.1} | {:.1} | {ffr} | {lin} |",
                c.title,
                r.setting.label(),
                pct(r.error),
                pct_signed(r.peak_error),
                r.ms_per_s,
                r.rtf,
            ),
            None => writeln!(s, "| {} | none | | | | | {ffr} | {lin} |", c.title),
        };
    }
    s
}

/// The front sampled at [`FRONT_LEVELS`]: per level and case, the fastest setting whose
/// pointwise error is at most the level.
fn front_table(rows: &[Row], cases: &[Case]) -> String {
    let mut s = String::from("| pointwise error at most |");
    for c in cases {
        let _ = write!(s, " ({}) |", c.key);
    }
    s.push_str("\n|---|");
    s.push_str(&"---|".repeat(cases.len()));
    s.push('\n');
    for level in FRONT_LEVELS {
        let _ = write!(s, "| {} |", pct(level));
        for c in cases {
            let _ = match front_at(rows, c.key, level) {
                Some(r) => write!(
                    s,
                    " {}: {}, {:.1} ms/s |",
                    r.setting.label(),
                    pct(r.error),
                    r.ms_per_s
                ),
                None => write!(s, " none in the matrix |"),
            };
        }
        s.push('\n');
    }
    s
}

/// The default scene's setting in every case.
fn speed_table(rows: &[Row], cases: &[Case], default_setting: Result<Setting, String>) -> String {
    let setting = match default_setting {
        Ok(s) => s,
        Err(e) => return format!("The default scene's setting could not be built: {e}\n"),
    };
    let mut s = String::new();
    let _ = writeln!(
        s,
        "| case | setting | error | peak | force error | ms/s | RTF | steps |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|");
    for c in cases {
        let row = rows
            .iter()
            .find(|r| r.case == c.key && r.setting.same_run(&setting));
        let _ = match row {
            Some(r) if r.ok() => writeln!(
                s,
                "| {} | {} | {} | {} | {} | {:.1} | {:.1} | {} |",
                c.title,
                r.setting.label(),
                pct(r.error),
                pct_signed(r.peak_error),
                pct(r.force_error),
                r.ms_per_s,
                r.rtf,
                r.stats.steps
            ),
            Some(r) => writeln!(
                s,
                "| {} | {} | {} | | | | | |",
                c.title,
                r.setting.label(),
                r.status
            ),
            None => writeln!(
                s,
                "| {} | {} not in the matrix | | | | | | |",
                c.title,
                setting.label()
            ),
        };
    }
    s
}
