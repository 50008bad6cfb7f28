//! `report.csv`: one line per setting and case, every measured number.

use std::fmt::Write as _;

use crate::rows::Row;
use crate::settings::{reference_name, Model};

const HEADER: &str = "case,model,elements,modes,reference,h,rho_inf,status,error,peak_error,force_error,exudyn_error,exudyn_peak_error,ms_per_simulated_s,real_time_factor,repeats,steps,newton_iterations,halvings,pareto,is_reference";

/// A number in the CSV (empty if not finite).
fn f(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.4e}")
    } else {
        String::new()
    }
}

pub fn csv(rows: &[Row]) -> String {
    let mut s = String::from(HEADER);
    s.push('\n');
    for r in rows {
        let st = &r.setting;
        let segments = st.model == Model::Segments;
        let (ex, exp) = r.exudyn.map(|(a, b)| (f(a), f(b))).unwrap_or_default();
        let _ = writeln!(
            s,
            "{},{},{},{},{},{:e},{},\"{}\",{},{},{},{},{},{},{},{},{},{},{},{},{}",
            r.case,
            st.model.name(),
            st.elements,
            if segments {
                String::new()
            } else {
                st.modes.to_string()
            },
            if segments {
                ""
            } else {
                reference_name(st.reference)
            },
            st.h,
            st.rho_inf,
            r.status.replace('"', "'"),
            f(r.error),
            f(r.peak_error),
            f(r.force_error),
            ex,
            exp,
            f(r.ms_per_s),
            f(r.rtf),
            r.repeats,
            r.stats.steps,
            r.stats.newton_iterations,
            r.stats.halvings,
            r.pareto,
            r.is_reference
        );
    }
    s
}
