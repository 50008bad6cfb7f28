//! A hand-written SVG of error against run time: one log-log panel per case, one marker
//! style per rod model, the Pareto front as a dashed line and the front of the fixed-step
//! settings alone (without error control) as a grey line.

/// One point of a panel.
pub struct Point {
    /// Milliseconds of run time per simulated second.
    pub time: f64,
    /// Error (fraction of the reference peak).
    pub error: f64,
    /// Index into the model names (0 = FFR linear, 1 = FFR stiffened, 2 = segments, 3 = RK4,
    /// 4 to 6 the error-controlled settings).
    pub model: usize,
    pub pareto: bool,
}

/// One panel: a case title and its points.
pub struct Panel {
    pub title: String,
    pub points: Vec<Point>,
}

const MODEL_NAMES: [&str; 8] = [
    "FFR linear",
    "FFR stiffened",
    "segments",
    "FFR stiffened, RK4",
    "FFR stiffened, auto (RK4(3), minimal coordinates)",
    "segments, auto (error control)",
    "FFR stiffened, Dormand-Prince (minimal coordinates)",
    "segment chain on its modes, auto (exponential RK4(3))",
];
const COLOURS: [&str; 8] = [
    "#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#17becf", "#e377c2",
];

/// Models 0 to 3 of [`MODEL_NAMES`] step with a fixed step (no error control).
const FIXED_STEP_MODELS: usize = 4;
/// Colour of the fixed-step front.
const FIXED_STEP_FRONT: &str = "#bbbbbb";

/// The points no other point beats in both run time and error, by increasing run time.
fn non_dominated<'a>(points: &[&'a &'a Point]) -> Vec<&'a Point> {
    let mut sorted: Vec<&Point> = points.iter().map(|p| **p).collect();
    sorted.sort_by(|a, b| a.time.total_cmp(&b.time).then(a.error.total_cmp(&b.error)));
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    for p in sorted {
        if p.error < best {
            best = p.error;
            front.push(p);
        }
    }
    front
}

fn marker(model: usize, x: f64, y: f64) -> String {
    let c = COLOURS[model];
    match model {
        0 => format!(
            "<polygon points=\"{:.1},{:.1} {:.1},{:.1} {:.1},{:.1}\" fill=\"none\" stroke=\"{c}\" stroke-width=\"1.4\"/>",
            x, y - 5.0, x - 4.5, y + 3.5, x + 4.5, y + 3.5
        ),
        1 => format!("<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"3.8\" fill=\"none\" stroke=\"{c}\" stroke-width=\"1.4\"/>"),
        3 => format!(
            "<polygon points=\"{:.1},{:.1} {:.1},{:.1} {:.1},{:.1} {:.1},{:.1}\" fill=\"none\" stroke=\"{c}\" stroke-width=\"1.4\"/>",
            x, y - 5.0, x + 5.0, y, x, y + 5.0, x - 5.0, y
        ),
        _ => format!(
            "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"7\" height=\"7\" fill=\"none\" stroke=\"{c}\" stroke-width=\"1.4\"/>",
            x - 3.5,
            y - 3.5
        ),
    }
}

fn decades(lo: f64, hi: f64) -> (f64, f64) {
    let lo = lo.log10().floor();
    let mut hi = hi.log10().ceil();
    if hi <= lo {
        hi = lo + 1.0;
    }
    (lo, hi)
}

/// The whole figure, panels in a grid of two columns.
pub fn error_vs_runtime(title: &str, panels: &[Panel]) -> String {
    let (pw, ph) = (520.0, 380.0);
    let cols = 2usize;
    let rows = panels.len().div_ceil(cols).max(1);
    let (w, h) = (pw * cols as f64, ph * rows as f64 + 95.0);
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<text x=\"{}\" y=\"20\" text-anchor=\"middle\" font-size=\"15\">{title}</text>\n",
        w / 2.0
    );
    // Legend: every model's marker (three columns), then the two fronts.
    for (m, name) in MODEL_NAMES.iter().enumerate() {
        let (col, row) = (m % 3, m / 3);
        let x = 20.0 + 340.0 * col as f64;
        let y = 36.0 + 14.0 * row as f64;
        s += &marker(m, x, y);
        s += &format!("<text x=\"{}\" y=\"{}\">{name}</text>\n", x + 9.0, y + 4.0);
    }
    s += "<line x1=\"15\" x2=\"45\" y1=\"80\" y2=\"80\" stroke=\"black\" stroke-dasharray=\"4 2\"/><text x=\"50\" y=\"84\">Pareto front (all settings)</text>\n";
    s += &format!("<line x1=\"355\" x2=\"385\" y1=\"80\" y2=\"80\" stroke=\"{FIXED_STEP_FRONT}\" stroke-width=\"2\"/><text x=\"390\" y=\"84\">front of the fixed-step settings (no error control)</text>\n");
    for (i, panel) in panels.iter().enumerate() {
        let ox = pw * (i % cols) as f64;
        let oy = 95.0 + ph * (i / cols) as f64;
        let (ml, mr, mt, mb) = (70.0, 15.0, 28.0, 45.0);
        let pts: Vec<&Point> = panel
            .points
            .iter()
            .filter(|p| p.time > 0.0 && p.error > 0.0 && p.time.is_finite() && p.error.is_finite())
            .collect();
        let tmin = pts.iter().map(|p| p.time).fold(f64::INFINITY, f64::min);
        let tmax = pts.iter().map(|p| p.time).fold(0.0, f64::max);
        let emin = pts.iter().map(|p| p.error).fold(f64::INFINITY, f64::min);
        let emax = pts.iter().map(|p| p.error).fold(0.0, f64::max);
        let (x0, x1) = if pts.is_empty() {
            (0.0, 1.0)
        } else {
            decades(tmin, tmax)
        };
        let (y0, y1) = if pts.is_empty() {
            (-3.0, 0.0)
        } else {
            decades(emin, emax)
        };
        let px = |t: f64| ox + ml + (t.log10() - x0) / (x1 - x0) * (pw - ml - mr);
        let py = |e: f64| oy + mt + (y1 - e.log10()) / (y1 - y0) * (ph - mt - mb);
        s += &format!(
            "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"13\">{}</text>\n",
            ox + ml + (pw - ml - mr) / 2.0,
            oy + 16.0,
            panel.title
        );
        s += &format!(
            "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#888\"/>\n",
            ox + ml,
            oy + mt,
            pw - ml - mr,
            ph - mt - mb
        );
        for d in (x0 as i32)..=(x1 as i32) {
            let x = px(10f64.powi(d));
            s += &format!(
                "<line x1=\"{x:.1}\" x2=\"{x:.1}\" y1=\"{}\" y2=\"{}\" stroke=\"#ddd\"/><text x=\"{x:.1}\" y=\"{}\" text-anchor=\"middle\">1e{d}</text>\n",
                oy + mt,
                oy + ph - mb,
                oy + ph - mb + 14.0
            );
        }
        for d in (y0 as i32)..=(y1 as i32) {
            let y = py(10f64.powi(d));
            s += &format!(
                "<line x1=\"{}\" x2=\"{}\" y1=\"{y:.1}\" y2=\"{y:.1}\" stroke=\"#ddd\"/><text x=\"{}\" y=\"{:.1}\" text-anchor=\"end\">1e{d}</text>\n",
                ox + ml,
                ox + pw - mr,
                ox + ml - 4.0,
                y + 4.0
            );
        }
        // 0.5 % line.
        if (y0..=y1).contains(&(5e-3f64).log10()) {
            let y = py(5e-3);
            s += &format!(
                "<line x1=\"{}\" x2=\"{}\" y1=\"{y:.1}\" y2=\"{y:.1}\" stroke=\"#999\" stroke-dasharray=\"2 3\"/><text x=\"{}\" y=\"{:.1}\" fill=\"#777\">0.5 %</text>\n",
                ox + ml,
                ox + pw - mr,
                ox + pw - mr - 36.0,
                y - 3.0
            );
        }
        s += &format!(
            "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">run time, ms per simulated second</text>\n",
            ox + ml + (pw - ml - mr) / 2.0,
            oy + ph - 12.0
        );
        let cy = oy + mt + (ph - mt - mb) / 2.0;
        s += &format!(
            "<text x=\"{}\" y=\"{cy}\" text-anchor=\"middle\" transform=\"rotate(-90 {} {cy})\">max |delta v_mid/L| / peak</text>\n",
            ox + 16.0,
            ox + 16.0
        );
        let polyline = |front: &[&Point], style: &str| {
            if front.len() < 2 {
                return String::new();
            }
            let path: Vec<String> = front
                .iter()
                .map(|p| format!("{:.1},{:.1}", px(p.time), py(p.error)))
                .collect();
            format!(
                "<polyline fill=\"none\" {style} points=\"{}\"/>\n",
                path.join(" ")
            )
        };
        let mut front: Vec<&Point> = pts.iter().filter(|p| p.pareto).copied().collect();
        front.sort_by(|a, b| a.time.total_cmp(&b.time));
        s += &polyline(&front, "stroke=\"black\" stroke-dasharray=\"4 2\"");
        // The front of the fixed-step methods alone (models 0 to 3, no error control), for
        // comparison with the error-controlled ones.
        let fixed: Vec<&&Point> = pts.iter().filter(|p| p.model < FIXED_STEP_MODELS).collect();
        s += &polyline(
            &non_dominated(&fixed),
            &format!("stroke=\"{FIXED_STEP_FRONT}\" stroke-width=\"2\""),
        );
        for p in &pts {
            s += &marker(p.model, px(p.time), py(p.error));
            s += "\n";
        }
    }
    s += "</svg>\n";
    s
}
