//! A minimal SVG line plot for the command-line tool (no plotting dependency needed for
//! two-axis line charts).

/// One curve: label, colour, points (x, y).
pub struct Curve<'a> {
    pub label: &'a str,
    pub colour: &'a str,
    pub points: Vec<(f64, f64)>,
}

/// An SVG document with the curves on common axes.
pub fn line_plot(title: &str, x_label: &str, y_label: &str, curves: &[Curve]) -> String {
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
    if x1.partial_cmp(&x0) != Some(std::cmp::Ordering::Greater) {
        x1 = x0 + 1.0;
    }
    if y1.partial_cmp(&y0) != Some(std::cmp::Ordering::Greater) {
        y1 = y0 + 1.0;
    }
    let pad = 0.05 * (y1 - y0);
    let (y0, y1) = (y0 - pad, y1 + pad);
    let px = |x: f64| ml + (x - x0) / (x1 - x0) * (w - ml - mr);
    let py = |y: f64| mt + (y1 - y) / (y1 - y0) * (h - mt - mb);
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<text x=\"{}\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">{title}</text>\n",
        w / 2.0
    );
    for k in 0..=5 {
        let yv = y0 + (y1 - y0) * k as f64 / 5.0;
        let xv = x0 + (x1 - x0) * k as f64 / 5.0;
        s += &format!(
            "<line x1=\"{ml}\" x2=\"{}\" y1=\"{y}\" y2=\"{y}\" stroke=\"#ddd\"/><text x=\"{}\" y=\"{}\" text-anchor=\"end\">{yv:.3e}</text>\n",
            w - mr,
            ml - 4.0,
            py(yv) + 4.0,
            y = py(yv)
        );
        s += &format!(
            "<line y1=\"{mt}\" y2=\"{}\" x1=\"{x}\" x2=\"{x}\" stroke=\"#ddd\"/><text x=\"{x}\" y=\"{}\" text-anchor=\"middle\">{xv:.3}</text>\n",
            h - mb,
            h - mb + 16.0,
            x = px(xv)
        );
    }
    s += &format!(
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{x_label}</text>\n",
        w / 2.0,
        h - 8.0
    );
    s += &format!("<text x=\"16\" y=\"{}\" text-anchor=\"middle\" transform=\"rotate(-90 16 {})\">{y_label}</text>\n", h / 2.0, h / 2.0);
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
            c.label
        );
    }
    s + "</svg>\n"
}
