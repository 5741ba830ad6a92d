//! `convergence.svg`: error against time on log-log axes, one polyline per method.

use super::rows::Row;
use std::fmt::Write as _;

/// A log-log plot of error against time, one polyline per method.
pub fn convergence_svg(rows: &[Row], methods: &[String]) -> String {
    let (w, h, l, b, t, rgt) = (640.0, 420.0, 70.0, 50.0, 20.0, 170.0);
    let pts: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.rel_mse > 0.0)
        .map(|r| (r.seconds.max(1e-3).log10(), r.rel_mse.log10()))
        .collect();
    if pts.is_empty() {
        return format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\"></svg>\n"
        );
    }
    let (x0, x1) = (
        pts.iter().map(|p| p.0).fold(f64::MAX, f64::min).floor(),
        pts.iter()
            .map(|p| p.0)
            .fold(f64::MIN, f64::max)
            .ceil()
            .max(0.0),
    );
    let (y0, y1) = (
        pts.iter().map(|p| p.1).fold(f64::MAX, f64::min).floor(),
        pts.iter().map(|p| p.1).fold(f64::MIN, f64::max).ceil(),
    );
    let (x1, y1) = (
        if x1 <= x0 { x0 + 1.0 } else { x1 },
        if y1 <= y0 { y0 + 1.0 } else { y1 },
    );
    let px = |x: f64| l + (x - x0) / (x1 - x0) * (w - l - rgt);
    let py = |y: f64| t + (y1 - y) / (y1 - y0) * (h - t - b);
    let colours = [
        "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
        "#bcbd22", "#17becf",
    ];
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    );
    // Axes and decade grid.
    let mut d = x0;
    while d <= x1 + 1e-9 {
        let _ = writeln!(
            s,
            "<line x1=\"{0:.1}\" y1=\"{1:.1}\" x2=\"{0:.1}\" y2=\"{2:.1}\" stroke=\"#ddd\"/><text x=\"{0:.1}\" y=\"{3:.1}\" text-anchor=\"middle\">{4}</text>",
            px(d),
            py(y1),
            py(y0),
            h - b + 16.0,
            fmt_decade(d)
        );
        d += 1.0;
    }
    let mut d = y0;
    while d <= y1 + 1e-9 {
        let _ = writeln!(
            s,
            "<line x1=\"{0:.1}\" y1=\"{1:.1}\" x2=\"{2:.1}\" y2=\"{1:.1}\" stroke=\"#ddd\"/><text x=\"{3:.1}\" y=\"{4:.1}\" text-anchor=\"end\">{5}</text>",
            px(x0),
            py(d),
            px(x1),
            l - 6.0,
            py(d) + 4.0,
            fmt_decade(d)
        );
        d += 1.0;
    }
    let _ = writeln!(
        s,
        "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">wall-clock time (s, maps included)</text>",
        (l + w - rgt) / 2.0,
        h - 8.0
    );
    let _ = writeln!(
        s,
        "<text x=\"16\" y=\"{:.1}\" transform=\"rotate(-90 16 {:.1})\" text-anchor=\"middle\">relative MSE</text>",
        (t + h - b) / 2.0,
        (t + h - b) / 2.0
    );
    for (i, m) in methods.iter().enumerate() {
        let c = colours[i % colours.len()];
        let pts: Vec<(f64, f64, bool)> = rows
            .iter()
            .filter(|r| &r.method == m && r.rel_mse > 0.0)
            .map(|r| {
                (
                    px(r.seconds.max(1e-3).log10()),
                    py(r.rel_mse.log10()),
                    r.budget_missed,
                )
            })
            .collect();
        let line: Vec<String> = pts
            .iter()
            .map(|p| format!("{:.1},{:.1}", p.0, p.1))
            .collect();
        let _ = writeln!(
            s,
            "<polyline class=\"method\" fill=\"none\" stroke=\"{c}\" stroke-width=\"2\" points=\"{}\"/>",
            line.join(" ")
        );
        // A run that missed its budget is a hollow point.
        for &(x, y, missed) in &pts {
            let fill = if missed { "white" } else { c };
            let _ = writeln!(
                s,
                "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"3.5\" fill=\"{fill}\" stroke=\"{c}\" stroke-width=\"1.5\"/>"
            );
        }
        let _ = writeln!(
            s,
            "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"14\" height=\"4\" fill=\"{c}\"/><text x=\"{:.1}\" y=\"{:.1}\">{m}</text>",
            w - rgt + 15.0,
            t + 10.0 + 18.0 * i as f64,
            w - rgt + 34.0,
            t + 15.0 + 18.0 * i as f64
        );
    }
    if rows.iter().any(|r| r.budget_missed) {
        let y = t + 15.0 + 18.0 * methods.len() as f64 + 8.0;
        let _ = writeln!(
            s,
            "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"3.5\" fill=\"white\" stroke=\"#444\" stroke-width=\"1.5\"/><text x=\"{:.1}\" y=\"{:.1}\">budget missed</text>",
            w - rgt + 22.0,
            y - 4.0,
            w - rgt + 34.0,
            y
        );
    }
    s += "</svg>\n";
    s
}
fn fmt_decade(d: f64) -> String {
    format!("1e{}", d.round() as i64)
}
