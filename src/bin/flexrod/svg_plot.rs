//! A minimal SVG line plot for the command-line tool (no plotting dependency needed for
//! two-axis line charts). Tick labels are plain numbers at steps of 1, 2 or 5 times a power of
//! ten (angles: 15, 30, 45, 90, 180, 360 degrees and multiples); where the values are below
//! 0.01 or reach 10^4 the ticks are scaled by an engineering power 10^(3k), and the axis label
//! says so (`force (kN)`, `v_mid / L (×10⁻³)`).

/// One curve: label, colour, points (x, y).
pub struct Curve<'a> {
    pub label: &'a str,
    pub colour: &'a str,
    pub points: Vec<(f64, f64)>,
}

/// An axis: what it shows, its unit ("" for none) and whether it is an angle in degrees
/// (ticks at multiples of 15, 45, 90 ... degrees, never scaled).
pub struct Axis<'a> {
    pub label: &'a str,
    pub unit: &'a str,
    pub degrees: bool,
}

/// Tick positions over `[lo, hi]` (four to nine) and their step.
fn ticks(lo: f64, hi: f64, degrees: bool) -> (Vec<f64>, f64) {
    // Eight intervals, or up to 5 % more of a rounder step.
    let raw = (hi - lo) / 8.0 / 1.05;
    let nice = |raw: f64| {
        let e = raw.log10().floor();
        let p = 10f64.powf(e);
        let m = [1.0, 2.0, 5.0, 10.0]
            .into_iter()
            .find(|&m| m * p >= raw)
            .unwrap_or(10.0);
        m * p
    };
    let step = if degrees {
        const STEPS: [f64; 11] = [
            1.0, 2.0, 5.0, 10.0, 15.0, 30.0, 45.0, 90.0, 180.0, 360.0, 720.0,
        ];
        match STEPS.into_iter().find(|&s| s >= raw) {
            Some(s) if raw >= 1.0 => s,
            _ if raw < 1.0 => nice(raw),
            _ => 360.0 * nice(raw / 360.0),
        }
    } else {
        nice(raw)
    };
    let first = (lo / step - 1e-9).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    ((first..=last).map(|k| k as f64 * step).collect(), step)
}

/// The engineering exponent (a multiple of 3) for values up to `magnitude`: 0 from 0.01 to
/// below 10^4.
fn engineering_exponent(magnitude: f64) -> i32 {
    if magnitude == 0.0 || !magnitude.is_finite() || (1e-2..1e4).contains(&magnitude) {
        return 0;
    }
    3 * (magnitude.log10().floor() as i32).div_euclid(3)
}

fn superscript(n: i32) -> String {
    n.to_string()
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            d => ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'][d as usize - '0' as usize],
        })
        .collect()
}

/// The axis label with its unit and scale: `force (kN)`, `v_mid / L (×10⁻³)`, `angle (deg)`.
fn axis_label(axis: &Axis, exponent: i32) -> String {
    let prefix = match (axis.unit.is_empty(), exponent) {
        (_, 0) => Some(""),
        (false, -12) => Some("p"),
        (false, -9) => Some("n"),
        (false, -6) => Some("µ"),
        (false, -3) => Some("m"),
        (false, 3) => Some("k"),
        (false, 6) => Some("M"),
        (false, 9) => Some("G"),
        (false, 12) => Some("T"),
        _ => None,
    };
    let unit = match prefix {
        Some(_) if axis.unit.is_empty() => String::new(),
        Some(p) => format!("{p}{}", axis.unit),
        None if axis.unit.is_empty() => format!("×10{}", superscript(exponent)),
        None => format!("×10{} {}", superscript(exponent), axis.unit),
    };
    if unit.is_empty() {
        axis.label.to_string()
    } else {
        format!("{} ({unit})", axis.label)
    }
}

/// A tick value as plain text with as many decimals as the step needs (no "-0").
fn tick_text(value: f64, step: f64) -> String {
    let decimals = (-(step.log10() + 1e-9).floor()).max(0.0) as usize;
    let text = format!("{value:.decimals$}");
    if text
        .trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        text.trim_start_matches('-').to_string()
    } else {
        text
    }
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// An SVG document with the curves on common axes.
pub fn line_plot(title: &str, x_axis: &Axis, y_axis: &Axis, curves: &[Curve]) -> String {
    let (w, h, ml, mr, mt, mb) = (800.0, 420.0, 80.0, 20.0, 40.0, 50.0);
    let all = curves.iter().flat_map(|c| c.points.iter());
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for &(x, y) in all {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if !x0.is_finite() || !x1.is_finite() {
        (x0, x1) = (0.0, 1.0);
    }
    if !y0.is_finite() || !y1.is_finite() {
        (y0, y1) = (0.0, 1.0);
    }
    if x1.partial_cmp(&x0) != Some(std::cmp::Ordering::Greater) {
        x1 = x0 + 1.0;
    }
    if y1.partial_cmp(&y0) != Some(std::cmp::Ordering::Greater) {
        let half = if y0 == 0.0 { 1.0 } else { 0.5 * y0.abs() };
        (y0, y1) = (y0 - half, y1 + half);
    }
    let pad = 0.05 * (y1 - y0);
    let (y0, y1) = (y0 - pad, y1 + pad);
    let px = |x: f64| ml + (x - x0) / (x1 - x0) * (w - ml - mr);
    let py = |y: f64| mt + (y1 - y) / (y1 - y0) * (h - mt - mb);
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<text x=\"{}\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">{}</text>\n",
        w / 2.0,
        escape(title)
    );
    let ey = if y_axis.degrees {
        0
    } else {
        engineering_exponent(y0.abs().max(y1.abs()))
    };
    let ex = if x_axis.degrees {
        0
    } else {
        engineering_exponent(x0.abs().max(x1.abs()))
    };
    let (y_ticks, y_step) = ticks(y0, y1, y_axis.degrees);
    for yv in y_ticks {
        let scale = 10f64.powi(ey);
        s += &format!(
            "<line x1=\"{ml}\" x2=\"{}\" y1=\"{y:.2}\" y2=\"{y:.2}\" stroke=\"#ddd\"/><text x=\"{}\" y=\"{:.2}\" text-anchor=\"end\">{}</text>\n",
            w - mr,
            ml - 4.0,
            py(yv) + 4.0,
            tick_text(yv / scale, y_step / scale),
            y = py(yv)
        );
    }
    let (x_ticks, x_step) = ticks(x0, x1, x_axis.degrees);
    for xv in x_ticks {
        let scale = 10f64.powi(ex);
        s += &format!(
            "<line y1=\"{mt}\" y2=\"{}\" x1=\"{x:.2}\" x2=\"{x:.2}\" stroke=\"#ddd\"/><text x=\"{x:.2}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n",
            h - mb,
            h - mb + 16.0,
            tick_text(xv / scale, x_step / scale),
            x = px(xv)
        );
    }
    s += &format!(
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n",
        w / 2.0,
        h - 8.0,
        escape(&axis_label(x_axis, ex))
    );
    s += &format!(
        "<text x=\"16\" y=\"{}\" text-anchor=\"middle\" transform=\"rotate(-90 16 {})\">{}</text>\n",
        h / 2.0,
        h / 2.0,
        escape(&axis_label(y_axis, ey))
    );
    for (i, c) in curves.iter().enumerate() {
        let path: Vec<String> = c
            .points
            .iter()
            .map(|&(x, y)| format!("{:.2},{:.2}", px(x), py(y)))
            .collect();
        s += &format!(
            "<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"1.3\" points=\"{}\"/>\n",
            c.colour,
            path.join(" ")
        );
        s += &format!(
            "<text x=\"{}\" y=\"{}\" fill=\"{}\">{}</text>\n",
            ml + 10.0 + 150.0 * i as f64,
            mt + 14.0,
            c.colour,
            escape(c.label)
        );
    }
    s + "</svg>\n"
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round_numbers() {
        assert_eq!(
            ticks(0.0, 720.0, true).0,
            [0.0, 90.0, 180.0, 270.0, 360.0, 450.0, 540.0, 630.0, 720.0]
        );
        assert_eq!(ticks(0.0, 40.0, true).1, 5.0);
        assert_eq!(ticks(0.0, 7200.0, true).1, 1800.0);
        assert_eq!(
            ticks(-1.2, 1.3, false),
            (vec![-1.0, -0.5, 0.0, 0.5, 1.0], 0.5)
        );
        assert_eq!(tick_text(-0.0, 0.5), "0.0");
        assert_eq!(tick_text(1500.0, 500.0), "1500");
        assert_eq!(tick_text(-2.0e-3 / 1e-3, 5e-4 / 1e-3), "-2.0");
    }

    #[test]
    fn scale_only_where_needed() {
        let plain = Axis {
            label: "v_mid / L",
            unit: "",
            degrees: false,
        };
        let force = Axis {
            label: "force",
            unit: "N",
            degrees: false,
        };
        assert_eq!(engineering_exponent(3e-3), -3);
        assert_eq!(engineering_exponent(4500.0), 0);
        assert_eq!(engineering_exponent(38e3), 3);
        assert_eq!(axis_label(&plain, -3), "v_mid / L (×10⁻³)");
        assert_eq!(axis_label(&plain, 0), "v_mid / L");
        assert_eq!(axis_label(&force, 3), "force (kN)");
        assert_eq!(axis_label(&force, 0), "force (N)");
        assert_eq!(axis_label(&force, 15), "force (×10¹⁵ N)");
    }
}
