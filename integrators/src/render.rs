//! The render driver: builds the particle maps an integrator needs (and only those), runs
//! the integrator in passes over the film, in parallel with rayon, until a sample count or a
//! time budget is reached, and reports where the time went.
//!
//! * `pt`: path tracing; guided by the photon map (`--guide grid|footprint`).
//! * `lt`: light tracing; guided by the importance map.
//! * `combined`: both in every pass, each image kept as a layer, and one combined image in
//!   which every path is weighted against the other strategies ([`crate::mis`]).
//!
//! Reproducibility: camera path `i` of pass `k` and light path `i` of pass `k` each draw from
//! their own random stream `(seed, k, i)`; light-path splats are applied chunk by chunk in
//! chunk order. The image for a given seed and sample count is therefore the same whatever
//! the number of threads.

use crate::light_tracer::{self, Splats};
use crate::maps::{BuiltMap, build_map};
use crate::passes::PassSettings;
use crate::path_tracer;
use footprint::direction_sampler::{BsdfSampler, DirectionSampler, GuideParams, GuideState};
use footprint::film::{Film, Image, SampleStats, SplatList};
use footprint::footprint_sampler::FootprintSampler;
use footprint::grid_sampler::GridSampler;
use footprint::particle_map::{MapKind, ParticleMap};
use footprint::rng::Rng;
use footprint::scene::Scene;
use rayon::prelude::*;
use std::time::{Duration, Instant};

/// Which integrator renders the image.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Integrator {
    /// Path tracing with next-event estimation and MIS.
    Pt,
    /// Light tracing with camera connections.
    Lt,
    /// Both, and their MIS combination.
    Combined,
}

impl Integrator {
    pub fn name(self) -> &'static str {
        match self {
            Integrator::Pt => "pt",
            Integrator::Lt => "lt",
            Integrator::Combined => "combined",
        }
    }

    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "pt" => Some(Integrator::Pt),
            "lt" => Some(Integrator::Lt),
            "combined" => Some(Integrator::Combined),
            _ => None,
        }
    }

    fn traces_camera_paths(self) -> bool {
        self != Integrator::Lt
    }

    fn traces_light_paths(self) -> bool {
        self != Integrator::Pt
    }
}

/// Which direction sampler guides the paths.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Guide {
    Bsdf,
    Grid,
    Footprint,
}

impl Guide {
    pub fn name(self) -> &'static str {
        match self {
            Guide::Bsdf => "bsdf",
            Guide::Grid => "grid",
            Guide::Footprint => "footprint",
        }
    }

    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "bsdf" => Some(Guide::Bsdf),
            "grid" => Some(Guide::Grid),
            "footprint" => Some(Guide::Footprint),
            _ => None,
        }
    }
}

/// What to render and for how long.
#[derive(Clone, Debug)]
pub struct RenderOptions {
    pub integrator: Integrator,
    pub guide: Guide,
    pub guide_params: GuideParams,
    /// Samples per pixel (camera paths) and light paths per pixel per pass.
    pub spp: u32,
    /// Time budget in seconds, passes that build maps included; replaces `spp` when set.
    pub time: Option<f64>,
    pub max_depth: u32,
    pub seed: u64,
    /// Show a progress bar (only sensible on a terminal).
    pub progress: bool,
}

impl Default for RenderOptions {
    /// Unguided path tracing, 16 samples per pixel, depth 8, seed 0.
    fn default() -> Self {
        RenderOptions {
            integrator: Integrator::Pt,
            guide: Guide::Bsdf,
            guide_params: GuideParams::default(),
            spp: 16,
            time: None,
            max_depth: 8,
            seed: 0,
            progress: false,
        }
    }
}

impl RenderOptions {
    /// Options from the scene file's render and guide settings.
    pub fn from_scene(scene: &Scene) -> Self {
        let s = &scene.settings;
        RenderOptions {
            integrator: Integrator::parse(&s.integrator).unwrap_or(Integrator::Pt),
            guide: Guide::parse(&s.guide).unwrap_or(Guide::Bsdf),
            guide_params: scene.guide.clone(),
            spp: s.spp,
            time: s.time,
            max_depth: s.max_depth,
            seed: s.seed,
            progress: false,
        }
    }
}

/// Where the time went.
#[derive(Clone, Debug, Default)]
pub struct Timings {
    pub view_pass: Duration,
    pub light_pass: Duration,
    pub map_builds: Duration,
    pub tracing: Duration,
    pub total: Duration,
}

/// Counts of guided scattering events and of fallbacks to BSDF sampling.
#[derive(Clone, Copy, Debug, Default)]
pub struct GuideCounts {
    pub prepared: u64,
    pub fallbacks: u64,
}

impl GuideCounts {
    fn add(&mut self, s: &GuideState) {
        self.prepared += s.prepared;
        self.fallbacks += s.fallbacks;
    }
}

/// A rendered image (or three) and what it took.
#[derive(Clone, Debug)]
pub struct RenderResult {
    /// The main image: `pt`, `lt` or `combined`.
    pub image: Image,
    /// Every estimate as `(layer name, image)`: one for pt and lt, three for combined.
    pub layers: Vec<(&'static str, Image)>,
    /// Passes done: samples per pixel (camera paths) and light paths per pixel.
    pub passes: u32,
    /// Paths traced in all (camera and light).
    pub paths: u64,
    pub elapsed: Duration,
    pub timings: Timings,
    /// Rejected samples, and the largest single-sample contribution to one pixel at one
    /// sample per pixel (luminance), over every layer.
    pub stats: SampleStats,
    /// Guided scattering events and BSDF fallbacks: camera paths, light paths.
    pub camera_guide: GuideCounts,
    pub light_guide: GuideCounts,
    /// Summaries of the maps built.
    pub maps: Vec<String>,
}

/// Stream domains, so that the integrators never share random numbers.
const DOMAIN_PT: u64 = 1;
const DOMAIN_LT: u64 = 2;
/// Light paths per chunk (one splat list each).
const LT_CHUNK: usize = 4096;

fn make_sampler<'m>(
    guide: Guide,
    map: Option<&'m ParticleMap>,
    params: &GuideParams,
    max_dist: f32,
    soft: f32,
) -> Box<dyn DirectionSampler + 'm> {
    match (guide, map) {
        (Guide::Grid, Some(m)) => Box::new(GridSampler::new(m, params.clone(), max_dist, soft)),
        (Guide::Footprint, Some(m)) => {
            Box::new(FootprintSampler::new(m, params.clone(), max_dist, soft))
        }
        _ => Box::new(BsdfSampler),
    }
}

/// Renders `scene`. `on_progress(fraction)` is called after every pass.
pub fn render(scene: &Scene, opts: &RenderOptions, on_progress: impl FnMut(f64)) -> RenderResult {
    render_with(scene, opts, &|| None, on_progress)
}

/// [`render`], with `heap` reporting the heap bytes in use (a counting allocator) so that
/// the map summaries can state each map's real size.
pub fn render_with(
    scene: &Scene,
    opts: &RenderOptions,
    heap: &dyn Fn() -> Option<usize>,
    mut on_progress: impl FnMut(f64),
) -> RenderResult {
    let start = Instant::now();
    let cam = &scene.camera;
    let npix = cam.pixel_count();
    let mut timings = Timings::default();
    let mut map_summaries = Vec::new();

    // ---- Particle maps: only those the integrator and guide use ----
    let guided = opts.guide != Guide::Bsdf;
    let pass = |paths: usize| PassSettings {
        paths,
        max_depth: opts.max_depth,
        seed: opts.seed,
        soft_glossy_max: scene.maps.soft_glossy_max,
    };
    let mut build = |kind: MapKind, paths: usize| -> BuiltMap {
        let b = build_map(scene, kind, &pass(paths), heap);
        match kind {
            MapKind::Photons => timings.light_pass += b.pass.stats.time,
            MapKind::Importons => timings.view_pass += b.pass.stats.time,
        }
        timings.map_builds += b.map.build_time;
        map_summaries.push(b.summary());
        b
    };
    let photons = (guided && opts.integrator.traces_camera_paths())
        .then(|| build(MapKind::Photons, scene.maps.photons));
    let importons = (guided && opts.integrator.traces_light_paths())
        .then(|| build(MapKind::Importons, scene.maps.importons));
    let max_dist = scene.map_max_dist();
    let soft = scene.maps.soft_glossy_max;
    let camera_sampler = make_sampler(
        opts.guide,
        photons.as_ref().map(|b| &b.map),
        &opts.guide_params,
        max_dist,
        soft,
    );
    let light_sampler = make_sampler(
        opts.guide,
        importons.as_ref().map(|b| &b.map),
        &opts.guide_params,
        max_dist,
        soft,
    );

    // ---- Passes ----
    let trace_start = Instant::now();
    let want_combined = opts.integrator == Integrator::Combined;
    let mut pt_film = Film::new(cam.width, cam.height);
    let mut lt_film = Film::new(cam.width, cam.height);
    let mut combined_film = Film::new(cam.width, cam.height);
    let mut camera_guide = GuideCounts::default();
    let mut light_guide = GuideCounts::default();
    let mut passes = 0u32;
    let mut last_pass_end = start.elapsed().as_secs_f64();
    loop {
        if opts.integrator.traces_camera_paths() {
            let rows: Vec<(Vec<footprint::Rgb>, Vec<footprint::Rgb>, GuideCounts)> = (0..cam
                .height)
                .into_par_iter()
                .map_init(GuideState::default, |state, y| {
                    let before = (state.prepared, state.fallbacks);
                    let mut pt = Vec::with_capacity(cam.width as usize);
                    let mut comb =
                        Vec::with_capacity(if want_combined { cam.width as usize } else { 0 });
                    for x in 0..cam.width {
                        let index =
                            passes as u64 * npix as u64 + (y as u64 * cam.width as u64 + x as u64);
                        let mut rng = Rng::new(opts.seed, DOMAIN_PT, index);
                        let raster =
                            cam.filter
                                .sample_raster(x, y, cam.width, cam.height, rng.uniform2());
                        let c = path_tracer::trace(
                            scene,
                            cam.position,
                            cam.ray_dir(raster),
                            opts.max_depth,
                            &mut rng,
                            camera_sampler.as_ref(),
                            state,
                            want_combined,
                        );
                        pt.push(c.pt);
                        if want_combined {
                            comb.push(c.combined);
                        }
                    }
                    let counts = GuideCounts {
                        prepared: state.prepared - before.0,
                        fallbacks: state.fallbacks - before.1,
                    };
                    (pt, comb, counts)
                })
                .collect();
            pt_film.add_per_pixel(|x, y| rows[y as usize].0[x as usize]);
            if want_combined {
                combined_film.add_per_pixel(|x, y| rows[y as usize].1[x as usize]);
            }
            for r in &rows {
                camera_guide.prepared += r.2.prepared;
                camera_guide.fallbacks += r.2.fallbacks;
            }
        }
        if opts.integrator.traces_light_paths() {
            let chunks = npix.div_ceil(LT_CHUNK);
            let lists: Vec<(SplatList, SplatList, GuideCounts)> = (0..chunks)
                .into_par_iter()
                .map(|c| {
                    let mut state = GuideState::default();
                    let mut lt = SplatList::default();
                    let mut comb = SplatList::default();
                    for i in c * LT_CHUNK..((c + 1) * LT_CHUNK).min(npix) {
                        let index = passes as u64 * npix as u64 + i as u64;
                        let mut rng = Rng::new(opts.seed, DOMAIN_LT, index);
                        let mut splats = Splats {
                            lt: &mut lt,
                            combined: want_combined.then_some(&mut comb),
                        };
                        light_tracer::trace(
                            scene,
                            opts.max_depth,
                            &mut rng,
                            light_sampler.as_ref(),
                            &mut state,
                            &mut splats,
                        );
                    }
                    let mut counts = GuideCounts::default();
                    counts.add(&state);
                    (lt, comb, counts)
                })
                .collect();
            for (lt, comb, counts) in &lists {
                lt_film.add_splats(lt);
                if want_combined {
                    combined_film.add_splats(comb);
                }
                light_guide.prepared += counts.prepared;
                light_guide.fallbacks += counts.fallbacks;
            }
        }
        passes += 1;
        let elapsed = start.elapsed().as_secs_f64();
        let pass_time = elapsed - last_pass_end;
        last_pass_end = elapsed;
        let (fraction, done) = match opts.time {
            // Whole passes only: stop when another one would end more than half a pass past
            // the budget, so that the time spent is the budget to within half a pass.
            Some(t) => ((elapsed / t).min(1.0), elapsed + 0.5 * pass_time >= t),
            None => (passes as f64 / opts.spp as f64, passes >= opts.spp),
        };
        on_progress(fraction);
        if done {
            break;
        }
    }
    timings.tracing = trace_start.elapsed();

    // Camera paths average `passes` samples per pixel; light paths divide their splats by
    // the number of light paths, `passes` per pixel (see `light_tracer`).
    let n = passes as f64;
    let pt_img = pt_film.to_image(1.0 / n);
    let lt_img = lt_film.to_image(1.0 / (n * npix as f64));
    let mut stats = SampleStats::default();
    let mut pt_stats = pt_film.stats;
    let mut lt_stats = lt_film.stats;
    lt_stats.max_luminance /= npix as f32;
    pt_stats.merge(&lt_stats);
    stats.merge(&pt_stats);
    let mut layers: Vec<(&'static str, Image)> = Vec::new();
    let image = match opts.integrator {
        Integrator::Pt => {
            layers.push(("pt", pt_img.clone()));
            pt_img
        }
        Integrator::Lt => {
            layers.push(("lt", lt_img.clone()));
            lt_img
        }
        Integrator::Combined => {
            // Camera-path contributions and light-path splats (pre-divided by P in
            // `light_tracer`) are both averaged per pass.
            let combined = combined_film.to_image(1.0 / n);
            stats.merge(&combined_film.stats);
            layers.push(("combined", combined.clone()));
            layers.push(("pt", pt_img));
            layers.push(("lt", lt_img));
            combined
        }
    };
    let paths = passes as u64
        * npix as u64
        * (opts.integrator.traces_camera_paths() as u64
            + opts.integrator.traces_light_paths() as u64);
    timings.total = start.elapsed();
    RenderResult {
        image,
        layers,
        passes,
        paths,
        elapsed: start.elapsed(),
        timings,
        stats,
        camera_guide,
        light_guide,
        maps: map_summaries,
    }
}
