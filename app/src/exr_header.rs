//! The attributes a rendered EXR carries: what was rendered and with which settings (enough
//! to render it again), what `footprint merge` checks, and where the time went.

use crate::merge;
use footprint::keyword::Keyword;
use footprint::scene::Scene;
use footprint_integrators::RenderOptions;
use footprint_integrators::auto::Choice;
use footprint_integrators::render::RenderResult;
use std::path::Path;
use std::time::Duration;

/// What a render's header is written from.
pub struct Run<'a> {
    pub scene_path: &'a Path,
    pub scene: &'a Scene,
    pub scene_hash: &'a str,
    /// The options the image was rendered with (the chosen method when `auto` chose).
    pub opts: &'a RenderOptions,
    pub result: &'a RenderResult,
    pub choice: Option<&'a Choice>,
    /// Saved maps the render read, and how long loading them took.
    pub maps_file: Option<(&'a Path, Duration)>,
}

/// The header's `(name, value)` attributes.
pub fn header(r: &Run) -> Vec<(String, String)> {
    let (opts, scene, result) = (r.opts, r.scene, r.result);
    let t = &result.timings;
    let spp_total = if opts.passes.is_all() {
        result.passes
    } else {
        opts.spp
    };
    let mut h: Vec<(&str, String)> = vec![
        ("footprint/version", env!("CARGO_PKG_VERSION").to_string()),
        ("footprint/scene", r.scene_path.display().to_string()),
        ("footprint/integrator", opts.method.integrator.name().into()),
        ("footprint/guide", opts.method.guide.name().into()),
        ("footprint/method", opts.method.name()),
        (
            "footprint/film",
            format!("{:?} {:?}", opts.film, scene.camera.filter.kind),
        ),
        ("footprint/sequence", opts.sequence.name().into()),
        ("footprint/accel", scene.bvh.name().into()),
        (
            "footprint/guide_params",
            footprint::schema::describe(&opts.guide_params, &scene.maps, |_| true),
        ),
        ("footprint/map_max_dist", scene.map_max_dist().to_string()),
        (merge::SCENE_HASH, r.scene_hash.to_string()),
        (merge::SETTINGS, merge::settings_key(opts, scene)),
        (merge::SHARD, opts.passes.to_string()),
        (merge::SPP, result.passes.to_string()),
        (merge::SPP_TOTAL, spp_total.to_string()),
        ("footprint/max_depth", opts.max_depth.to_string()),
        ("footprint/rr_depth", opts.rr_depth.to_string()),
        (merge::SEED, opts.seed.to_string()),
        (
            merge::RENDER_TIME,
            format!("{:.3}", result.elapsed.as_secs_f64()),
        ),
        (
            "footprint/time_split_s",
            t.split()
                .iter()
                .map(|(name, s)| format!("{}={s:.3}", name.replace(' ', "_")))
                .collect::<Vec<_>>()
                .join(" "),
        ),
        (
            "footprint/time_budget_s",
            opts.time.map_or("none".into(), |t| t.to_string()),
        ),
        (
            "footprint/skipped",
            result
                .skipped
                .iter()
                .map(|s| s.to_string())
                .collect::<Vec<_>>()
                .join("; "),
        ),
    ];
    if scene.stats.degenerate_skipped > 0 {
        // Left out when loaded (zero area, or too thin for a normal): said, not hidden.
        h.push((
            "footprint/degenerate_triangles_skipped",
            scene.stats.degenerate_skipped.to_string(),
        ));
    }
    if let Some(paths) = result.photons_grown {
        // The passes and these paths render the image again without the budget.
        h.push(("footprint/photons_grown", paths.to_string()));
    }
    if !result.maps_thinned.is_empty() {
        // The maps' budget (`max_memory`, else the machine's) thinned them: the image
        // depends on it.
        h.push(("footprint/maps_thinned", result.maps_thinned.join("; ")));
    }
    if let Some(c) = r.choice {
        h.push(("footprint/auto", format!("{}: {}", c.label, c.reason())));
    }
    if let Some((path, load)) = r.maps_file {
        h.push(("footprint/maps_file", path.display().to_string()));
        h.push((
            "footprint/maps_load_s",
            format!("{:.3}", load.as_secs_f64()),
        ));
    }
    h.into_iter().map(|(k, v)| (k.to_string(), v)).collect()
}
