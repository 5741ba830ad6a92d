//! `footprint compare`: every method on one scene at equal wall-clock time (the passes that
//! build the particle maps included), against a reference, with the error measured at a
//! ladder of times; written as a table (CSV and JSON), a log-log convergence plot (SVG) and
//! a self-contained HTML page. The shape follows SmallVCM's equal-time report and pbrt-v4's
//! `--mse-reference-image`.
//!
//! Metrics against the reference `R` (per pixel and channel, image `X`):
//! * relative MSE: mean of `(X - R)² / (R² + 0.01)`, both images first divided by the
//!   reference's mean so that the `0.01` means the same in dark and bright scenes;
//! * mean absolute error: mean of `|X - R|`;
//! * spots (the paper's word, fireflies): pixels whose luminance error exceeds
//!   [`SPOT_FACTOR`] times the reference luminance plus 1% of the reference's mean.

use footprint_integrators::method::Method;
use footprint_integrators::render::{RenderOptions, StopRule, chosen_guidance, guidance, render, render_prepared};
use anyhow::{Context, Result, bail};
use footprint::film::Image;
use footprint::film::image_io::{read_exr, write_exr, write_png};
use footprint::math::luminance;
use footprint::scene::Scene;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// A run missed its budget when it took more than this fraction longer than the budget, or
/// when its map passes alone took longer than the budget (a guided method at a small rung).
pub const BUDGET_TOLERANCE: f64 = 0.1;

/// A pixel is a spot when its luminance error exceeds this multiple of the reference
/// luminance (plus 1% of the reference mean).
pub const SPOT_FACTOR: f32 = 4.0;

/// Whether a run of `seconds`, `map_seconds` of them building maps, missed budget `t`: it
/// took more than [`BUDGET_TOLERANCE`] longer, or its maps alone took longer than `t`.
pub fn missed(seconds: f64, map_seconds: f64, t: f64) -> bool {
    seconds > t * (1.0 + BUDGET_TOLERANCE) || map_seconds > t
}

/// Relative MSE (see the module doc).
pub fn rel_mse(x: &Image, r: &Image) -> f64 {
    let m = luminance(r.mean()).max(1e-20) as f64;
    let mut sum = 0.0f64;
    for (a, b) in x.pixels.iter().zip(&r.pixels) {
        for c in 0..3 {
            let (a, b) = (a[c] as f64 / m, b[c] as f64 / m);
            sum += (a - b) * (a - b) / (b * b + 0.01);
        }
    }
    sum / (3 * r.pixels.len()) as f64
}

/// Mean absolute error over pixels and channels.
pub fn mae(x: &Image, r: &Image) -> f64 {
    let sum: f64 = x
        .pixels
        .iter()
        .zip(&r.pixels)
        .map(|(a, b)| (*a - *b).abs().element_sum() as f64)
        .sum();
    sum / (3 * r.pixels.len()) as f64
}

/// Number of spots (see the module doc).
pub fn spots(x: &Image, r: &Image) -> usize {
    let floor = 0.01 * luminance(r.mean());
    x.pixels
        .iter()
        .zip(&r.pixels)
        .filter(|(a, b)| {
            let (la, lb) = (luminance(**a), luminance(**b));
            (la - lb).abs() > SPOT_FACTOR * lb + floor
        })
        .count()
}

/// One curve of the comparison: a method, possibly with changed parameters (a sweep).
#[derive(Clone, Debug)]
pub struct Variant {
    pub label: String,
    pub opts: RenderOptions,
    pub maps: footprint::settings::MapSettings,
}

/// Settings of a comparison.
#[derive(Clone, Debug)]
pub struct CompareSettings {
    pub variants: Vec<Variant>,
    /// Wall-clock budgets, ascending; the last is "equal time".
    pub ladder: Vec<f64>,
    /// Samples per pixel of the reference (combined image, BSDF sampling).
    pub reference_spp: u32,
    /// Folder of the reference cache (default: the scene's folder).
    pub reference_cache: Option<PathBuf>,
    pub out: PathBuf,
    pub seed: u64,
}

/// One measured point (a row of `metrics.csv` and `metrics.json`).
#[derive(Clone, Debug, serde::Serialize)]
pub struct Row {
    pub method: String,
    #[serde(rename = "time_budget_s")]
    pub time_budget: f64,
    pub seconds: f64,
    pub map_seconds: f64,
    pub tracing_seconds: f64,
    pub spp: u32,
    pub rel_mse: f64,
    pub mae: f64,
    pub spots: usize,
    /// The share of the image's light (luminance summed over pixels) that the largest single
    /// sample carried into one pixel: light transport at low sample counts is heavy-tailed,
    /// and a large share says that this run's error rests on a few paths (a rare, heavy
    /// path can make one seed look far better or worse than the next).
    pub largest_share: f64,
    /// The run took more than the budget (plus [`BUDGET_TOLERANCE`]): its error is not an
    /// equal-time error.
    pub budget_missed: bool,
    /// The method `auto` chose at this budget (empty for a fixed method).
    pub chosen: String,
}

/// The largest single-sample contribution's share of the image (see [`Row::largest_share`]):
/// a sample's value is averaged over the passes, so its share of the summed image is
/// `value / (passes · Σ pixels)`.
pub fn largest_share(r: &footprint_integrators::RenderResult) -> f64 {
    let total = luminance(r.image.mean()) as f64 * r.image.pixels.len() as f64;
    if !(total > 0.0) || r.passes == 0 {
        return 0.0;
    }
    r.stats.max_luminance as f64 / (r.passes as f64 * total)
}

/// A short text that identifies what a reference was rendered from: the scene files'
/// contents, the resolution, depth and reference settings.
pub fn reference_key(scene_path: &Path, scene: &Scene, spp: u32, max_depth: u32) -> Result<String> {
    let hash = crate::scene_hash::scene_content_hash(scene_path, scene)?;
    Ok(format!(
        "scene={} res={}x{} spp={spp} max_depth={max_depth} method=combined-bsdf v{}",
        &hash[..16],
        scene.camera.width,
        scene.camera.height,
        env!("CARGO_PKG_VERSION")
    ))
}

/// Reads the key a cached reference was written with.
fn cached_key(path: &Path) -> Option<String> {
    footprint::film::image_io::read_exr_text_attribute(path, "footprint/reference_key")
}

/// The reference: `given`, or the cache in `cache_dir` (default: the scene's folder) when its
/// key matches, or a fresh render (written to the cache). Returns the image and where it
/// came from.
#[allow(clippy::too_many_arguments)]
pub fn reference(
    scene_path: &Path,
    scene: &Scene,
    given: Option<&Path>,
    spp: u32,
    max_depth: u32,
    cache_dir: Option<&Path>,
    log: &mut dyn FnMut(&str),
) -> Result<(Image, String)> {
    if let Some(p) = given {
        let img = read_exr(p)?;
        if img.width != scene.camera.width || img.height != scene.camera.height {
            bail!(
                "reference {} is {}x{}, the render is {}x{} (use --resolution)",
                p.display(),
                img.width,
                img.height,
                scene.camera.width,
                scene.camera.height
            );
        }
        return Ok((img, format!("given: {}", p.display())));
    }
    let key = reference_key(scene_path, scene, spp, max_depth)?;
    let stem = scene_path
        .file_stem()
        .map(|s| s.to_string_lossy().to_string())
        .unwrap_or("scene".into());
    let name = format!(
        ".{stem}-reference-{}x{}.exr",
        scene.camera.width, scene.camera.height
    );
    let cache = match cache_dir {
        Some(d) => d.join(name),
        None => scene_path.with_file_name(name),
    };
    if cache.exists() {
        if cached_key(&cache).as_deref() == Some(key.as_str()) {
            if let Ok(img) = read_exr(&cache) {
                return Ok((img, format!("cached: {}", cache.display())));
            }
        }
        log(&format!(
            "reference cache {} is stale (scene or settings changed): rendering it again",
            cache.display()
        ));
    }
    // The cache's folder is made before the render: a long reference is not rendered only to
    // be lost for want of a folder.
    if let Some(d) = cache.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(d)
            .with_context(|| format!("cannot create the reference cache folder {}", d.display()))?;
    }
    log(&format!(
        "rendering the reference: combined image, BSDF sampling, {spp} spp"
    ));
    let opts = RenderOptions {
        method: Method::from_names("combined", "bsdf").map_err(anyhow::Error::msg)?,
        spp,
        max_depth,
        seed: 0x5eed,
        ..Default::default()
    };
    // Progress: a line at every tenth of the passes, with the time left measured so far.
    let t0 = std::time::Instant::now();
    let mut shown = 0;
    let r = render(scene, &opts, |f| {
        let tenth = (f * 10.0).floor() as i32;
        if tenth > shown && f < 1.0 {
            shown = tenth;
            let el = t0.elapsed().as_secs_f64();
            log(&format!(
                "reference: {:.0}% of {spp} spp in {el:.0} s, about {:.0} s left",
                100.0 * f,
                el * (1.0 - f) / f
            ));
        }
    });
    // A cache that cannot be written costs the next run a render, not this one its result.
    let stored = match write_exr(
        &cache,
        &[("combined", &r.image)],
        &[("footprint/reference_key".into(), key)],
    ) {
        Ok(()) => cache.display().to_string(),
        Err(e) => {
            log(&format!(
                "warning: the reference is not cached ({e}); this run goes on with it"
            ));
            "not cached".to_string()
        }
    };
    Ok((
        r.image,
        format!("rendered: {stored} ({:.1} s)", r.elapsed.as_secs_f64()),
    ))
}

/// Least-squares slope of log(error) against log(time).
pub fn log_log_slope(points: &[(f64, f64)]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|(t, e)| *t > 0.0 && *e > 0.0)
        .map(|(t, e)| (t.ln(), e.ln()))
        .collect();
    if pts.len() < 2 {
        return None;
    }
    let n = pts.len() as f64;
    let (mx, my) = (
        pts.iter().map(|p| p.0).sum::<f64>() / n,
        pts.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// A method's (seconds, relative MSE) points for the slope: one per distinct sample count
/// (rungs that rendered the same number of passes are the same image, and a slope through
/// them would be 0), the fastest of each.
pub fn slope_points(rows: &[Row], method: &str) -> Vec<(f64, f64)> {
    let mut pts: Vec<(u32, f64, f64)> = Vec::new();
    for r in rows.iter().filter(|r| r.method == method) {
        match pts.iter_mut().find(|p| p.0 == r.spp) {
            Some(p) if p.1 <= r.seconds => {}
            Some(p) => *p = (r.spp, r.seconds, r.rel_mse),
            None => pts.push((r.spp, r.seconds, r.rel_mse)),
        }
    }
    pts.sort_by(|a, b| a.1.total_cmp(&b.1));
    pts.into_iter().map(|(_, t, e)| (t, e)).collect()
}

/// Time a method needs to reach `target` error, on its log-log line through the last point
/// with the fitted slope (extrapolated when the ladder did not reach it).
pub fn time_to_reach(points: &[(f64, f64)], target: f64) -> Option<f64> {
    let slope = log_log_slope(points)?;
    if slope >= 0.0 {
        return None;
    }
    let (t, e) = *points.last()?;
    Some(t * (target / e).powf(1.0 / slope))
}

/// False-colour error image: |X - R| / (R + 1% mean) in luminance, through a blue-red ramp.
fn error_image(x: &Image, r: &Image) -> Image {
    let floor = 0.01 * luminance(r.mean()).max(1e-20);
    let mut out = Image::new(r.width, r.height);
    for ((o, a), b) in out.pixels.iter_mut().zip(&x.pixels).zip(&r.pixels) {
        let e = ((luminance(*a) - luminance(*b)).abs() / (luminance(*b) + floor)).min(1.0);
        *o = footprint::Rgb::new(e, 0.2 * (1.0 - e), 1.0 - e) * 0.8;
    }
    out
}

/// An exposure that maps the reference's mean to mid-grey in the previews.
fn preview_exposure(r: &Image) -> f32 {
    let m = luminance(r.mean()).max(1e-12);
    (0.18 / m).log2()
}

fn csv(rows: &[Row]) -> Result<String> {
    let mut w = csv::Writer::from_writer(Vec::new());
    for r in rows {
        w.serialize(r)?;
    }
    Ok(String::from_utf8(
        w.into_inner().map_err(|e| anyhow::anyhow!("{e}"))?,
    )?)
}

/// A method's line of the summary: the log-log slope of its error against time and the
/// time it needs to reach the target error.
#[derive(Clone, Debug, serde::Serialize)]
pub struct MethodSummary {
    pub method: String,
    pub slope: Option<f64>,
    pub time_to_target_s: Option<f64>,
}

fn json(
    scene: &str,
    reference: &str,
    rows: &[Row],
    summary: &[MethodSummary],
    target: f64,
) -> Result<String> {
    let report = serde_json::json!({
        "scene": scene,
        "reference": reference,
        "spot_factor": SPOT_FACTOR,
        "budget_tolerance": BUDGET_TOLERANCE,
        "budgets_missed": rows.iter().filter(|r| r.budget_missed).count(),
        "target_rel_mse": target,
        "rows": rows,
        "methods": summary,
    });
    Ok(serde_json::to_string_pretty(&report)? + "\n")
}

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

/// Runs the comparison and writes every file; returns the rows.
pub fn run(
    scene_path: &Path,
    scene: &mut Scene,
    given_ref: Option<&Path>,
    s: &CompareSettings,
    max_depth: u32,
    log: &mut dyn FnMut(&str),
) -> Result<Vec<Row>> {
    std::fs::create_dir_all(&s.out)
        .with_context(|| format!("cannot create {}", s.out.display()))?;
    let (reference, ref_source) = reference(
        scene_path,
        scene,
        given_ref,
        s.reference_spp,
        max_depth,
        s.reference_cache.as_deref(),
        log,
    )?;
    let exposure = preview_exposure(&reference);
    write_png(&s.out.join("reference.png"), &reference, exposure)?;
    let total_runs = s.variants.len() * s.ladder.len();
    let ladder_sum: f64 = s.ladder.iter().sum();
    // Wall-clock time of the runs so far and the budgets they were given: the time left is
    // the remaining budgets scaled by what the runs so far really took.
    let (mut wall, mut budgets_done) = (0.0f64, 0.0f64);
    let mut rows = Vec::new();
    let scene_maps = scene.maps.clone();
    for (mi, v) in s.variants.iter().enumerate() {
        scene.maps = v.maps.clone();
        let opts = RenderOptions {
            time: None,
            seed: s.seed,
            max_depth,
            ..v.opts.clone()
        };
        // The maps and caches once per method; their time is charged to every rung, as a
        // render of that budget would spend it.
        let left = |wall: f64, done: f64| {
            let remaining = ladder_sum * s.variants.len() as f64 - done;
            if done > 0.0 {
                format!("about {:.0} s left", remaining * wall / done)
            } else {
                format!("at least {remaining:.0} s left")
            }
        };
        let g0 = std::time::Instant::now();
        // `auto` chooses at every rung, its pilot inside the rung's budget. A sparse photon
        // map grows with the budget (`maps.grow`): then every rung builds its own maps for
        // its own budget, as a render of that budget would.
        let g = if opts.auto.is_some() {
            footprint_integrators::maps::Guidance::default()
        } else {
            guidance(scene, &opts, &|| None)
        };
        let per_rung = footprint_integrators::maps::may_grow(scene, &opts.guide_params)
            && g.photon_cache
                .as_ref()
                .is_some_and(|c| footprint_integrators::maps::sparse(&c.stats, &opts.guide_params).is_some());
        let maps = g.timings.total();
        if v.opts.method.guided() {
            log(&format!(
                "[{}/{total_runs}] {}: maps and caches built in {:.2} s, {}",
                mi * s.ladder.len() + 1,
                v.label,
                maps.as_secs_f64(),
                if per_rung {
                    "and again for every rung (its sparse photon map grows with the rung's budget)"
                } else {
                    "charged to every rung"
                }
            ));
        }
        wall += g0.elapsed().as_secs_f64();
        for (li, &t) in s.ladder.iter().enumerate() {
            let run_index = mi * s.ladder.len() + li + 1;
            log(&format!(
                "[{run_index}/{total_runs}] {} for {t} s ({})",
                v.label,
                left(wall, budgets_done)
            ));
            let opts = RenderOptions {
                time: Some(t),
                ..opts.clone()
            };
            let r0 = std::time::Instant::now();
            let (r, maps) = match &opts.auto {
                Some(spec) => {
                    let choice = footprint_integrators::auto::choose(scene, &opts, spec);
                    log(&format!(
                        "[{run_index}/{total_runs}] {} chose {} ({:.2} s pilot): {}",
                        v.label,
                        choice.method.name(),
                        choice.pilot.as_secs_f64(),
                        choice.reason
                    ));
                    let chosen = RenderOptions {
                        method: choice.method,
                        auto: None,
                        ..opts.clone()
                    };
                    let left = Some(t - r0.elapsed().as_secs_f64());
                    let g = chosen_guidance(scene, &chosen, choice.guidance, left, &|| None);
                    // The pilot and the chosen method's maps are charged to the budget.
                    let charged = r0.elapsed();
                    let mut r = render_prepared(
                        scene,
                        &chosen,
                        &g,
                        charged,
                        StopRule::WithinBudget,
                        |_| {},
                    );
                    r.auto = Some(choice.reason);
                    (r, charged)
                }
                None if per_rung => {
                    let own = guidance(scene, &opts, &|| None);
                    let maps = own.timings.total();
                    let r =
                        render_prepared(scene, &opts, &own, maps, StopRule::WithinBudget, |_| {});
                    (r, maps)
                }
                None => (
                    render_prepared(scene, &opts, &g, maps, StopRule::WithinBudget, |_| {}),
                    maps,
                ),
            };
            wall += r0.elapsed().as_secs_f64();
            budgets_done += t;
            let tm = &r.timings;
            let seconds = r.elapsed.as_secs_f64();
            let budget_missed = missed(seconds, maps.as_secs_f64(), t);
            if budget_missed {
                let why = if maps.as_secs_f64() >= t {
                    format!("its maps alone take {:.2} s", maps.as_secs_f64())
                } else {
                    format!(
                        "maps {:.2} s plus one pass {:.2} s",
                        maps.as_secs_f64(),
                        tm.tracing.as_secs_f64() / r.passes.max(1) as f64
                    )
                };
                log(&format!(
                    "warning: {} cannot keep the {t} s budget ({why}): it took {seconds:.2} s for {} spp; the row is marked budget_missed",
                    v.label, r.passes
                ));
            }
            rows.push(Row {
                method: v.label.clone(),
                time_budget: t,
                seconds,
                map_seconds: tm.maps.total().as_secs_f64(),
                tracing_seconds: tm.tracing.as_secs_f64(),
                spp: r.passes,
                rel_mse: rel_mse(&r.image, &reference),
                mae: mae(&r.image, &reference),
                spots: spots(&r.image, &reference),
                largest_share: largest_share(&r),
                budget_missed,
                chosen: if r.auto.is_some() {
                    r.method.name()
                } else {
                    String::new()
                },
            });
            if li + 1 == s.ladder.len() {
                write_png(&s.out.join(format!("{}.png", v.label)), &r.image, exposure)?;
                write_png(
                    &s.out.join(format!("{}-error.png", v.label)),
                    &error_image(&r.image, &reference),
                    0.0,
                )?;
            }
        }
    }
    scene.maps = scene_maps;
    let names: Vec<String> = s.variants.iter().map(|v| v.label.clone()).collect();
    // Slopes, and the time each method needs to reach the median of the equal-time errors
    // (of the runs that kept the budget, if any did).
    let last = *s.ladder.last().unwrap();
    let kept = rows
        .iter()
        .any(|r| r.time_budget == last && !r.budget_missed);
    let mut finals: Vec<f64> = rows
        .iter()
        .filter(|r| r.time_budget == last && (!kept || !r.budget_missed))
        .map(|r| r.rel_mse)
        .collect();
    finals.sort_by(|a, b| a.total_cmp(b));
    let target = finals.get(finals.len() / 2).copied().unwrap_or(0.0);
    let summary: Vec<MethodSummary> = names
        .iter()
        .map(|m| {
            let pts = slope_points(&rows, m);
            MethodSummary {
                method: m.clone(),
                slope: log_log_slope(&pts),
                time_to_target_s: time_to_reach(&pts, target),
            }
        })
        .collect();
    std::fs::write(s.out.join("metrics.csv"), csv(&rows)?)?;
    std::fs::write(
        s.out.join("metrics.json"),
        json(
            &scene_path.display().to_string(),
            &ref_source,
            &rows,
            &summary,
            target,
        )?,
    )?;
    std::fs::write(
        s.out.join("convergence.svg"),
        convergence_svg(&rows, &names),
    )?;
    std::fs::write(
        s.out.join("index.html"),
        html(
            scene_path,
            &ref_source,
            &rows,
            &summary,
            &names,
            s,
            target,
            scene,
        ),
    )?;
    Ok(rows)
}

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
fn html(
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
