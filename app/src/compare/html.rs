//! `index.html`: the comparison as one self-contained page (table, plot, images).

use super::metrics::{BUDGET_TOLERANCE, SPOT_FACTOR};
use super::rows::{CompareSettings, MethodSummary, Row};
use footprint::scene::Scene;
use std::fmt::Write as _;
use std::path::Path;

fn missed_class(r: &Row) -> &'static str {
    if r.budget_missed {
        " class=\"missed\""
    } else {
        ""
    }
}
fn budget_cell(r: &Row) -> String {
    if r.budget_missed {
        format!(
            "<span class=\"warn\">missed ({:.2} s for {} s)</span>",
            r.seconds, r.time_budget
        )
    } else {
        "kept".into()
    }
}
#[allow(clippy::too_many_arguments)]
pub fn html(
    scene_path: &Path,
    ref_source: &str,
    rows: &[Row],
    summary: &[MethodSummary],
    names: &[String],
    s: &CompareSettings,
    target: f64,
    scene: &Scene,
) -> String {
    let t_eq = *s.ladder.last().unwrap();
    let (w, h) = (scene.camera.width, scene.camera.height);
    // A crop of a quarter of the image around its centre, shown magnified for every image.
    let (cw, ch) = ((w / 4).max(1), (h / 4).max(1));
    let (cx, cy) = (w / 2 - cw / 2, h / 2 - ch / 2);
    let zoom = 4;
    let crop = |img: &str| {
        format!(
            "<div class=\"crop\" style=\"width:{}px;height:{}px\"><img src=\"{img}\" style=\"width:{}px;height:{}px;left:-{}px;top:-{}px\"></div>",
            cw * zoom,
            ch * zoom,
            w * zoom,
            h * zoom,
            cx * zoom,
            cy * zoom
        )
    };
    let mut out = String::new();
    let _ = write!(
        out,
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>footprint compare: {scene}</title>\n<style>\nbody {{ font-family: sans-serif; margin: 20px; }}\n.grid {{ display: flex; flex-wrap: wrap; gap: 16px; }}\n.cell {{ text-align: center; }}\n.crop {{ position: relative; overflow: hidden; border: 1px solid #888; }}\n.crop img {{ position: absolute; image-rendering: pixelated; }}\nimg.full {{ width: {w2}px; image-rendering: pixelated; }}\ntable {{ border-collapse: collapse; }} td, th {{ border: 1px solid #ccc; padding: 3px 8px; text-align: right; white-space: nowrap; }}\ntr.missed td {{ background: #fde0dc; }}\n.warn {{ color: #b00; font-weight: bold; }}\n</style></head><body>\n<h1>{scene}</h1>\n<p>Every method for {t_eq} s of wall-clock time, passes that build the particle maps included (built once per method and charged to every rung); reference: {refsrc}. Relative MSE = mean of (X - R)² / (R² + 0.01) after dividing by the reference mean; spots = pixels whose luminance error exceeds {SPOT_FACTOR} x the reference (+1% of its mean). Crops: the centre quarter, {zoom}x.</p>\n",
        scene = scene_path.display(),
        w2 = w.max(256),
        refsrc = ref_source
    );
    let missed = rows.iter().filter(|r| r.budget_missed).count();
    if missed > 0 {
        let _ = writeln!(
            out,
            "<p class=\"warn\">{missed} of {} runs missed their budget (took more than {:.0}% longer, or their maps alone took longer; marked in red below and as budget_missed in metrics.csv and metrics.json): their errors are not equal-time errors.</p>",
            rows.len(),
            100.0 * BUDGET_TOLERANCE
        );
    }
    out += "<h2>Equal time</h2>\n<table><tr><th>method</th><th>spp</th><th>seconds</th><th>maps (s)</th><th>relative MSE</th><th>MAE</th><th>spots</th><th>largest sample</th><th>slope</th><th>time to reach target (s)</th><th>budget</th></tr>\n";
    for MethodSummary {
        method: m,
        slope,
        time_to_target_s: tt,
    } in summary
    {
        let (slope, tt) = (*slope, *tt);
        if let Some(r) = rows
            .iter()
            .find(|r| &r.method == m && r.time_budget == t_eq)
        {
            let f = |v: Option<f64>| {
                v.filter(|x| x.is_finite())
                    .map(|x| format!("{x:.3}"))
                    .unwrap_or("-".into())
            };
            let _ = writeln!(
                out,
                "<tr{}><td style=\"text-align:left\">{m}</td><td>{}</td><td>{:.2}</td><td>{:.2}</td><td>{:.4e}</td><td>{:.4e}</td><td>{}</td><td>{:.2}%</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                missed_class(r),
                r.spp,
                r.seconds,
                r.map_seconds,
                r.rel_mse,
                r.mae,
                r.spots,
                100.0 * r.largest_share,
                f(slope),
                f(tt),
                budget_cell(r)
            );
        }
    }
    let _ = writeln!(
        out,
        "</table>\n<p>Target error for the last column: {target:.4e} (the median equal-time relative MSE). Slope: of log error against log time over the rungs with different sample counts (- when fewer than two). Largest sample: the share of the image's light that the largest single sample carried into one pixel; when it is large the error rests on a few rare paths, and a single run's relative MSE can be far from the typical one (compare several seeds).</p>"
    );
    out += "<h2>Every rung</h2>\n<table><tr><th>method</th><th>budget (s)</th><th>seconds</th><th>maps (s)</th><th>tracing (s)</th><th>spp</th><th>relative MSE</th><th>MAE</th><th>spots</th><th>budget</th></tr>\n";
    for r in rows {
        let _ = writeln!(
            out,
            "<tr{}><td style=\"text-align:left\">{}</td><td>{}</td><td>{:.2}</td><td>{:.2}</td><td>{:.2}</td><td>{}</td><td>{:.4e}</td><td>{:.4e}</td><td>{}</td><td>{}</td></tr>",
            missed_class(r),
            r.method,
            r.time_budget,
            r.seconds,
            r.map_seconds,
            r.tracing_seconds,
            r.spp,
            r.rel_mse,
            r.mae,
            r.spots,
            budget_cell(r)
        );
    }
    out += "</table>\n";
    out += "<h2>Error against time</h2>\n<img src=\"convergence.svg\" alt=\"convergence plot\">\n<h2>Images</h2>\n<div class=\"grid\">\n";
    let _ = writeln!(
        out,
        "<div class=\"cell\"><img class=\"full\" src=\"reference.png\"><br>reference<br>{}</div>",
        crop("reference.png")
    );
    for m in names {
        let _ = writeln!(
            out,
            "<div class=\"cell\"><img class=\"full\" src=\"{m}.png\"><br>{m}<br>{}<br><img class=\"full\" src=\"{m}-error.png\"><br>error (blue 0, red ≥ 1 relative)</div>",
            crop(&format!("{m}.png"))
        );
    }
    out += "</div>\n<script>\nwindow.addEventListener('load', () => {\n  const imgs = [...document.images];\n  document.body.dataset.loaded = imgs.filter(i => i.complete && i.naturalWidth > 0).length + '/' + imgs.length;\n});\n</script>\n</body></html>\n";
    out
}
