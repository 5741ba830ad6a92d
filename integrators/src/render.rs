//! The render driver: builds the particle maps and guide caches a method needs (and only
//! those, [`Guidance`]), runs the integrator in passes over the films, in parallel with
//! rayon, until a sample count or a time budget is reached, and reports where the time
//! went. What a path computes is the integrator's business ([`crate::integrator`]).
//!
//! Reproducibility: camera path `i` of pass `k` and light path `i` of pass `k` each draw from
//! their own random stream `(seed, k, i)`; light-path splats are applied chunk by chunk in
//! chunk order. The image for a given seed and sample count is therefore the same whatever
//! the number of threads. A shard ([`RenderOptions::passes`], [`crate::shard`]) draws only
//! the passes `k` it owns, with the same streams, so shards add up to one run.

use crate::counts::GuideCounts;
use crate::integrator::Context;
use crate::maps::{Guidance, MapTimings};
use crate::method::Method;
use crate::passes::PassSettings;
use crate::shard::PassSelection;
use footprint::Rgb;
use footprint::film::filter::FilterKind;
use footprint::film::{Film, FilmMode, Image, SampleStats, SplatList};
use footprint::guide::sampler::{GuideSource, GuidedSampler, SamplerState};
use footprint::guide::selection::{SelectionLearner, SelectionRecord};
use footprint::rng::{Rng, Sequence};
use footprint::scene::Scene;
use footprint::scene::features::Specialisation;
use footprint::settings::GuideParams;
use rayon::prelude::*;
use std::time::{Duration, Instant};

/// What to render and for how long.
#[derive(Clone, Debug)]
pub struct RenderOptions {
    pub method: Method,
    /// How camera samples reach the film.
    pub film: FilmMode,
    /// The numbers camera and light paths draw (`footprint::rng`).
    pub sequence: Sequence,
    pub guide_params: GuideParams,
    /// Samples per pixel (camera paths) and light paths per pixel per pass.
    pub spp: u32,
    /// Time budget in seconds, passes that build maps included; replaces `spp` when set.
    pub time: Option<f64>,
    pub max_depth: u32,
    /// Russian roulette after scattering at vertices of this depth or deeper.
    pub rr_depth: u32,
    pub seed: u64,
    /// Which of the passes `0..spp` to draw (a shard, [`crate::shard`]); all by default. With
    /// a time budget, the selection's passes in order until the time is spent.
    pub passes: PassSelection,
    /// Run the path loop compiled for the scene's effects (the default) or the general one:
    /// the same image for a fixed seed, bit for bit (`footprint::scene::features`).
    pub specialise: bool,
    /// Add the integrator's second-moment layers after its layers
    /// ([`crate::integrator::Integrator::moment_layers`]; `auto`'s pilot asks for them), for
    /// a render of this horizon ([`crate::moments::Horizon`]).
    pub moments: Option<crate::moments::Horizon>,
}

impl Default for RenderOptions {
    /// Unguided path tracing, 16 samples per pixel, depth 8, seed 0, every pass.
    fn default() -> Self {
        RenderOptions {
            method: Method::default(),
            film: FilmMode::Splat,
            sequence: Sequence::default(),
            guide_params: GuideParams::default(),
            spp: 16,
            time: None,
            max_depth: 8,
            rr_depth: footprint::settings::DEFAULT_RR_DEPTH,
            seed: 0,
            passes: PassSelection::ALL,
            specialise: true,
            moments: None,
        }
    }
}

impl RenderOptions {
    /// The compiled path loop this render runs in: the narrowest one for the scene's
    /// effects, or the general one when `specialise` is off.
    pub fn specialisation(&self, scene: &Scene) -> Specialisation {
        if self.specialise {
            Specialisation::for_effects(&scene.effects)
        } else {
            Specialisation::General
        }
    }

    /// Options from the scene file's render and guide settings, with `method`: the scene's
    /// own names are resolved by [`Method::from_scene`] (or, with `auto` allowed, by
    /// `crate::auto::Request::from_scene`).
    pub fn from_scene(scene: &Scene, method: Method) -> Self {
        let s = &scene.settings;
        RenderOptions {
            method,
            film: FilmMode::Splat,
            sequence: Sequence::default(),
            guide_params: scene.guide.clone(),
            spp: s.spp,
            time: s.time,
            max_depth: s.max_depth,
            rr_depth: s.rr_depth,
            seed: s.seed,
            passes: PassSelection::ALL,
            specialise: true,
            moments: None,
        }
    }
}

/// Where the time went.
#[derive(Clone, Debug, Default)]
pub struct Timings {
    pub maps: MapTimings,
    pub tracing: Duration,
    /// Of the tracing, the camera paths' and the light paths' share.
    pub camera_paths: Duration,
    pub light_paths: Duration,
    pub total: Duration,
}

impl Timings {
    /// The split of the run's time: view pass, light pass, map builds, cache builds and
    /// tracing, in seconds, each with its name.
    pub fn split(&self) -> [(&'static str, f64); 5] {
        let m = &self.maps;
        [
            ("view pass", m.view_pass.as_secs_f64()),
            ("light pass", m.light_pass.as_secs_f64()),
            ("map builds", m.map_builds.as_secs_f64()),
            ("cache builds", m.cache_builds.as_secs_f64()),
            ("tracing", self.tracing.as_secs_f64()),
        ]
    }
}

/// A rendered image (or three) and what it took.
#[derive(Clone, Debug)]
pub struct RenderResult {
    /// The main image: the integrator's first layer.
    pub image: Image,
    /// Every estimate as `(layer name, image)`.
    pub layers: Vec<(&'static str, Image)>,
    /// Passes done (of the selected ones): samples per pixel (camera paths) and light paths
    /// per pixel.
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
    /// Summaries of the maps and caches built.
    pub maps: Vec<String>,
    /// Regions of the guide caches whose paths learned their own probability of sampling
    /// the BSDF (the photon map's for camera paths, the importance map's for light paths),
    /// and all their regions (`learn_p_bsdf`).
    pub learned_p_bsdf: Option<(usize, usize)>,
    /// The photon paths of the light pass when its map grew with the time budget
    /// ([`Guidance::grown`]): what, with the passes done, renders the image again without a
    /// budget (`--photons` this, `--map-grow off`, `--spp` the passes).
    pub photons_grown: Option<usize>,
    /// A line per particle pass thinned to keep the maps within the memory budget
    /// ([`crate::passes::thinning`]).
    pub maps_thinned: Vec<String>,
    /// What the scene's absent effects let the render skip, with counts ([`crate::skips`]).
    pub skipped: Vec<crate::skips::Skip>,
    /// The method rendered.
    pub method: Method,
}

/// Stream domains, so that camera and light paths never share random numbers.
const DOMAIN_CAMERA: u64 = 1;
const DOMAIN_LIGHT: u64 = 2;
/// Light paths per chunk (one splat list per layer each).
const LT_CHUNK: usize = 4096;

/// When a time budget ends the passes (whole passes only, at least one).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StopRule {
    /// Stop when another pass would end more than half a pass past the budget: the time
    /// spent is the budget to within half a pass (`render --time`).
    HalfPass,
    /// Stop when another pass would end past the budget (by the mean pass time so far):
    /// the budget is never exceeded except by a first pass longer than what is left of it
    /// (`compare`, which then reports the budget as missed).
    WithinBudget,
}

/// Renders `scene`. `on_progress(fraction)` is called after every pass.
pub fn render(scene: &Scene, opts: &RenderOptions, on_progress: impl FnMut(f64)) -> RenderResult {
    render_with(scene, opts, &|| None, on_progress)
}

/// The maps and guide caches `opts.method` needs (none for BSDF sampling); `heap` reports
/// the heap bytes in use (a counting allocator) so that the summaries state each map's size.
/// With a time budget (and `maps.grow`), sparse maps grow within a share of it
/// ([`Guidance::build_within`]).
pub fn guidance(scene: &Scene, opts: &RenderOptions, heap: &dyn Fn() -> Option<usize>) -> Guidance {
    let pass = with_target(scene, opts, pass_settings(scene, opts));
    guidance_with(scene, opts, &pass, heap)
}

/// [`guidance`] with the particle passes' settings given (`auto`'s pilot may give the view
/// pass an importance target of another resolution).
pub fn guidance_with(
    scene: &Scene,
    opts: &RenderOptions,
    pass: &PassSettings,
    heap: &dyn Fn() -> Option<usize>,
) -> Guidance {
    let budget = opts
        .time
        .filter(|_| scene.maps.grow)
        .map(Duration::from_secs_f64);
    Guidance::build_within(scene, &opts.method, &opts.guide_params, pass, budget, heap)
}

/// The particle passes' settings of a render with `opts` (no importance target: see
/// [`with_target`]).
pub fn pass_settings(scene: &Scene, opts: &RenderOptions) -> PassSettings {
    PassSettings {
        paths: 0,
        max_depth: opts.max_depth,
        rr_depth: opts.rr_depth,
        seed: opts.seed,
        soft_glossy_max: scene.maps.soft_glossy_max,
        specialise: opts.specialise,
        target: None,
        max_particles: crate::passes::thinning::max_particles(footprint::memory::budget(
            scene.maps.max_memory,
        )),
    }
}

/// Whether `opts`'s method reads the view pass's relative importance target: it guides
/// light paths by an importance map, and `relative_importance` is on.
pub fn wants_target(opts: &RenderOptions) -> bool {
    let m = &opts.method;
    opts.guide_params.relative_importance && m.guide.uses_particles() && m.integrator.paths().light
}

/// `pass` with the view pass's relative importance target ([`importance_target`]) when
/// `opts`'s method guides light paths by an importance map and `relative_importance` is on.
pub fn with_target(scene: &Scene, opts: &RenderOptions, pass: PassSettings) -> PassSettings {
    with_built_target(scene, opts, pass, &mut None)
}

/// [`with_target`], the target rendered from `target_scene` (`auto`'s pilot may read the
/// image's view from a lower resolution) once into `built` and reused from there by later
/// calls (every guide's view pass reads the same target).
pub fn with_built_target(
    target_scene: &Scene,
    opts: &RenderOptions,
    pass: PassSettings,
    built: &mut Option<Option<std::sync::Arc<crate::passes::target::ImportanceTarget>>>,
) -> PassSettings {
    if !wants_target(opts) {
        return pass;
    }
    let target =
        built.get_or_insert_with(|| importance_target(target_scene, opts).map(std::sync::Arc::new));
    PassSettings {
        target: target.clone(),
        ..pass
    }
}

/// One pass (1 sample per pixel) of `method` with `opts`' settings, its random numbers
/// seeded from `opts.seed ^ stream` (an independent pass for each `stream`); `moments`
/// asks for the second-moment layers ([`crate::moments`]) for a render of that horizon. `auto`'s pilot and the
/// relative importance target render such passes.
pub fn independent_pass(
    scene: &Scene,
    opts: &RenderOptions,
    method: Method,
    g: &Guidance,
    stream: u64,
    moments: Option<crate::moments::Horizon>,
) -> RenderResult {
    let o = RenderOptions {
        method,
        spp: 1,
        time: None,
        seed: opts.seed ^ stream,
        passes: crate::PassSelection::ALL,
        moments,
        ..opts.clone()
    };
    render_prepared(scene, &o, g, Duration::ZERO, StopRule::HalfPass, |_| {})
}

/// The relative importance target ([`crate::passes::target`]): [`crate::passes::target::TARGET_PASSES`]
/// independent passes of the unguided combined image (both directions: neither misses
/// what the other finds), its time in the target. `None` when the image is black.
pub fn importance_target(
    scene: &Scene,
    opts: &RenderOptions,
) -> Option<crate::passes::target::ImportanceTarget> {
    let start = Instant::now();
    let method = Method::from_names("combined", "bsdf").expect("registered");
    let none = Guidance::default();
    let passes: Vec<footprint::film::Image> = (0..crate::passes::target::TARGET_PASSES)
        .map(|k| independent_pass(scene, opts, method, &none, 0x7a67 << 48 | k as u64, None).image)
        .collect();
    let mut t = crate::passes::target::ImportanceTarget::from_passes(&passes)?;
    t.time = start.elapsed();
    Some(t)
}

/// [`render`], with `heap` reporting the heap bytes in use (a counting allocator) so that
/// the map summaries can state each map's real size.
pub fn render_with(
    scene: &Scene,
    opts: &RenderOptions,
    heap: &dyn Fn() -> Option<usize>,
    on_progress: impl FnMut(f64),
) -> RenderResult {
    let start = Instant::now();
    // ---- Particle maps and guide caches: only those the method uses ----
    let guidance = guidance(scene, opts, heap);
    render_guided(scene, opts, &guidance, start, on_progress)
}

/// Renders `scene` with maps and caches already built (or loaded, `footprint render
/// --maps`); `start` is when the run began, so that the budget and the reported time include
/// what was done before.
pub fn render_guided(
    scene: &Scene,
    opts: &RenderOptions,
    guidance: &Guidance,
    start: Instant,
    on_progress: impl FnMut(f64),
) -> RenderResult {
    trace(
        scene,
        opts,
        guidance,
        start,
        Duration::ZERO,
        StopRule::HalfPass,
        on_progress,
    )
}

/// Renders with maps and caches built beforehand ([`guidance`]), so that several renders
/// (`compare`'s ladder) can share them. The time budget counts from this call plus
/// `charged` (time spent before it that the budget includes, e.g. the maps' build).
pub fn render_prepared(
    scene: &Scene,
    opts: &RenderOptions,
    guidance: &Guidance,
    charged: Duration,
    rule: StopRule,
    on_progress: impl FnMut(f64),
) -> RenderResult {
    trace(
        scene,
        opts,
        guidance,
        Instant::now(),
        charged,
        rule,
        on_progress,
    )
}

fn trace(
    scene: &Scene,
    opts: &RenderOptions,
    guidance: &Guidance,
    start: Instant,
    charged: Duration,
    rule: StopRule,
    mut on_progress: impl FnMut(f64),
) -> RenderResult {
    let cam = &scene.camera;
    let npix = cam.pixel_count();
    let integrator = opts.method.integrator;
    let paths = integrator.paths();
    // The integrator's layers, and its second-moment layers after them when asked for.
    let own_layers = integrator.layers().len();
    let layers: Vec<&'static str> = integrator
        .layers()
        .iter()
        .chain(if opts.moments.is_some() {
            integrator.moment_layers()
        } else {
            &[]
        })
        .copied()
        .collect();
    let elapsed_since = |start: Instant| (charged + start.elapsed()).as_secs_f64();
    // The probability of sampling the BSDF, learned per region of each guide cache from the
    // paths of earlier passes (footprint::guide::selection): camera paths over the photon
    // map's, light paths over the importance map's.
    let learner_of = |sampler: &GuidedSampler| match &sampler.source {
        GuideSource::Cached(cache) if opts.guide_params.learn_p_bsdf => Some(
            SelectionLearner::new(cache.regions().len(), opts.guide_params.p_bsdf),
        ),
        _ => None,
    };
    let mut camera_sampler = guidance.camera_sampler(scene, &opts.method, &opts.guide_params);
    let learner = learner_of(&camera_sampler);
    camera_sampler.selection = learner.as_ref();
    let mut light_sampler = guidance.light_sampler(scene, &opts.method, &opts.guide_params);
    let light_learner = learner_of(&light_sampler);
    light_sampler.selection = light_learner.as_ref();
    let ctx = Context {
        scene,
        max_depth: opts.max_depth,
        rr_depth: opts.rr_depth,
        camera_sampler,
        light_sampler,
        guided_mis: opts.guide_params.guided_mis,
        specialisation: opts.specialisation(scene),
        moments: opts.moments.unwrap_or(crate::moments::Horizon::UNBOUNDED),
    };

    // ---- Passes ----
    let trace_start = Instant::now();
    let mut films: Vec<Film> = layers
        .iter()
        .map(|_| Film::new(cam.width, cam.height))
        .collect();
    let mut camera_guide = GuideCounts::default();
    let mut light_guide = GuideCounts::default();
    let mut passes = 0u32;
    let (mut camera_time, mut light_time) = (Duration::ZERO, Duration::ZERO);
    let budget = opts.passes.passes_of(opts.spp);
    assert!(
        opts.time.is_some() || budget > 0,
        "shard {} of {} spp has no passes",
        opts.passes,
        opts.spp
    );
    let mut last_pass_end = elapsed_since(start);
    let mut records: Vec<SelectionRecord> = Vec::new();
    let mut light_records: Vec<SelectionRecord> = Vec::new();
    let first_pass_start = last_pass_end;
    loop {
        // The stream index of this pass (a shard draws every `count`-th pass).
        let k = opts.passes.pass(passes) as u64;
        let camera_start = Instant::now();
        if paths.camera {
            // Splatting and filter importance sampling coincide for the box filter; the
            // box keeps the cheaper per-pixel accumulation.
            let splat = opts.film != FilmMode::Fis && cam.filter.kind != FilterKind::Box;
            type Row = (Vec<Rgb>, Vec<SplatList>, GuideCounts, Vec<SelectionRecord>);
            let rows: Vec<Row> = (0..cam.height)
                .into_par_iter()
                .map_init(SamplerState::default, |state, y| {
                    let before = GuideCounts::of(state);
                    let mut row = vec![Rgb::ZERO; cam.width as usize * layers.len()];
                    let mut splats =
                        vec![SplatList::default(); if splat { layers.len() } else { 0 }];
                    for (x, out) in row.chunks_exact_mut(layers.len()).enumerate() {
                        let x = x as u32;
                        let pixel = y as u64 * cam.width as u64 + x as u64;
                        let mut rng = Rng::for_pass(
                            opts.sequence,
                            opts.seed,
                            DOMAIN_CAMERA,
                            pixel,
                            npix as u64,
                            k,
                        );
                        let u = rng.uniform2();
                        let raster = if splat {
                            glam::Vec2::new(x as f32, y as f32) + u
                        } else {
                            cam.filter.sample_raster(x, y, cam.width, cam.height, u)
                        };
                        integrator.camera_path(&ctx, raster, &mut rng, state, out);
                        for (l, s) in splats.iter_mut().enumerate() {
                            let (f, w, h) = (&cam.filter, cam.width, cam.height);
                            if l >= own_layers {
                                s.splat_second_moment(f, w, h, raster, out[l]);
                            } else if opts.film == FilmMode::Weighted {
                                s.splat_weighted(f, w, h, raster, out[l]);
                            } else {
                                s.splat(f, w, h, raster, out[l]);
                            }
                        }
                    }
                    let counts = GuideCounts::of(state).minus(&before);
                    (
                        row,
                        splats,
                        counts,
                        std::mem::take(&mut state.selection_records),
                    )
                })
                .collect();
            for (l, film) in films.iter_mut().enumerate() {
                if splat {
                    // Rows in order: the sums do not depend on the thread count.
                    for r in &rows {
                        film.add_splats(&r.1[l]);
                    }
                } else {
                    // A layer that only light paths write gets zeros here.
                    film.add_per_pixel(|x, y| rows[y as usize].0[x as usize * layers.len() + l]);
                }
            }
            for r in &rows {
                camera_guide.add(&r.2);
            }
            if learner.is_some() {
                // Rows in order: the learned values do not depend on the thread count.
                records.extend(rows.iter().flat_map(|r| r.3.iter().copied()));
            }
        }
        camera_time += camera_start.elapsed();
        let light_start = Instant::now();
        if paths.light {
            let chunks = npix.div_ceil(LT_CHUNK);
            type Chunk = (Vec<SplatList>, GuideCounts, Vec<SelectionRecord>);
            let lists: Vec<Chunk> = (0..chunks)
                .into_par_iter()
                .map(|c| {
                    let mut state = SamplerState::default();
                    let mut splats = vec![SplatList::default(); layers.len()];
                    for i in c * LT_CHUNK..((c + 1) * LT_CHUNK).min(npix) {
                        let mut rng = Rng::for_pass(
                            opts.sequence,
                            opts.seed,
                            DOMAIN_LIGHT,
                            i as u64,
                            npix as u64,
                            k,
                        );
                        integrator.light_path(&ctx, &mut rng, &mut state, &mut splats);
                    }
                    let records = std::mem::take(&mut state.selection_records);
                    (splats, GuideCounts::of(&state), records)
                })
                .collect();
            for (splats, counts, records) in &lists {
                for (film, s) in films.iter_mut().zip(splats) {
                    film.add_splats(s);
                }
                light_guide.add(counts);
                // Chunks in order: the learned values do not depend on the thread count.
                light_records.extend_from_slice(records);
            }
        }
        light_time += light_start.elapsed();
        // The learned probabilities change only here, between passes: the light paths of
        // the combined image weigh the pass's camera paths with the values they drew with.
        if let Some(l) = &learner {
            l.absorb(&records);
            records.clear();
        }
        if let Some(l) = &light_learner {
            l.absorb(&light_records);
            light_records.clear();
        }
        passes += 1;
        let elapsed = elapsed_since(start);
        let pass_time = elapsed - last_pass_end;
        last_pass_end = elapsed;
        let (fraction, done) = match (opts.time, rule) {
            // Whole passes only: stop when another one would end more than half a pass past
            // the budget, so that the time spent is the budget to within half a pass.
            (Some(t), StopRule::HalfPass) => {
                ((elapsed / t).min(1.0), elapsed + 0.5 * pass_time >= t)
            }
            // Or when another pass, as long as the mean one so far, would end past it.
            (Some(t), StopRule::WithinBudget) => {
                let mean_pass = (elapsed - first_pass_start) / passes as f64;
                ((elapsed / t).min(1.0), elapsed + mean_pass > t)
            }
            (None, _) => (passes as f64 / budget as f64, passes >= budget),
        };
        on_progress(fraction);
        if done {
            break;
        }
    }
    let tracing = trace_start.elapsed();

    // Every layer averages its passes (light-path splats are already per pixel).
    let n = passes as f64;
    let mut stats = SampleStats::default();
    let layer_images: Vec<(&'static str, Image)> = layers
        .iter()
        .zip(&films)
        .map(|(name, film)| {
            stats.merge(&film.stats);
            (*name, film.to_image(1.0 / n))
        })
        .collect();
    let total_paths = passes as u64 * npix as u64 * (paths.camera as u64 + paths.light as u64);
    let mut skipped = guidance.skipped.clone();
    skipped.extend(crate::skips::counted(
        scene,
        ctx.specialisation,
        paths.camera.then_some(&camera_guide),
        total_paths,
    ));
    let elapsed = charged + start.elapsed();
    RenderResult {
        image: layer_images[0].1.clone(),
        layers: layer_images,
        passes,
        paths: total_paths,
        elapsed,
        timings: Timings {
            maps: guidance.timings.clone(),
            tracing,
            camera_paths: camera_time,
            light_paths: light_time,
            total: elapsed,
        },
        stats,
        camera_guide,
        light_guide,
        maps: {
            let mut m = guidance.summaries.clone();
            m.extend(
                learner
                    .as_ref()
                    .map(|l| format!("camera paths: {}", l.summary())),
            );
            m.extend(
                light_learner
                    .as_ref()
                    .map(|l| format!("light paths: {}", l.summary())),
            );
            m
        },
        learned_p_bsdf: {
            let regions =
                [&learner, &light_learner].map(|l| l.as_ref().map(|l| l.learned_regions()));
            regions
                .into_iter()
                .flatten()
                .reduce(|a, b| (a.0 + b.0, a.1 + b.1))
        },
        photons_grown: guidance.grown.map(|(_, after)| after),
        maps_thinned: guidance.thinned.clone(),
        skipped,
        method: opts.method,
    }
}
