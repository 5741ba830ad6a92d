//! What a comparison is made of: its curves ([`Variant`]), its settings, and what it
//! measured ([`Row`], one per method and budget; [`MethodSummary`], one per method).

use footprint_integrators::RenderOptions;
use footprint_integrators::auto::Request;
use std::path::PathBuf;

/// One curve of the comparison: a method, possibly with changed parameters (a sweep).
#[derive(Clone, Debug)]
pub struct Variant {
    pub label: String,
    /// The method, or `auto`'s choice at every rung.
    pub request: Request,
    /// The render settings (the method is the request's).
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
/// A method's line of the summary: the log-log slope of its error against time and the
/// time it needs to reach the target error.
#[derive(Clone, Debug, serde::Serialize)]
pub struct MethodSummary {
    pub method: String,
    pub slope: Option<f64>,
    pub time_to_target_s: Option<f64>,
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
