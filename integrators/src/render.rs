//! The render driver: runs an integrator in passes over the film, in parallel with rayon,
//! until a sample count or a time budget is reached, with progress on a terminal.
//!
//! Reproducibility: path tracing draws pixel `i` of pass `k` from stream `(seed, k, i)`;
//! light tracing draws path `i` of pass `k` from its own stream and applies splats chunk by
//! chunk in chunk order. The image for a given seed and sample count is therefore the same
//! whatever the number of threads.

use crate::{light_tracer, path_tracer};
use footprint::film::{Film, Image, SampleStats, SplatList};
use footprint::rng::Rng;
use footprint::scene::Scene;
use glam::Vec2;
use rayon::prelude::*;
use std::time::{Duration, Instant};

/// Which integrator renders the image.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Integrator {
    /// Path tracing with next-event estimation and MIS.
    Pt,
    /// Light tracing with camera connections.
    Lt,
}

impl Integrator {
    pub fn name(self) -> &'static str {
        match self {
            Integrator::Pt => "pt",
            Integrator::Lt => "lt",
        }
    }

    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "pt" => Some(Integrator::Pt),
            "lt" => Some(Integrator::Lt),
            _ => None,
        }
    }
}

/// What to render and for how long.
#[derive(Clone, Debug)]
pub struct RenderOptions {
    pub integrator: Integrator,
    /// Samples per pixel (path tracing) or light paths per pixel (light tracing).
    pub spp: u32,
    /// Time budget in seconds; replaces `spp` when set.
    pub time: Option<f64>,
    pub max_depth: u32,
    pub seed: u64,
    /// Show a progress bar (only sensible on a terminal).
    pub progress: bool,
}

impl RenderOptions {
    /// Options from the scene file's render settings.
    pub fn from_scene(scene: &Scene) -> Self {
        let s = &scene.settings;
        RenderOptions {
            integrator: Integrator::parse(&s.integrator).unwrap_or(Integrator::Pt),
            spp: s.spp,
            time: s.time,
            max_depth: s.max_depth,
            seed: s.seed,
            progress: false,
        }
    }
}

/// A rendered image and what it took.
#[derive(Clone, Debug)]
pub struct RenderResult {
    pub image: Image,
    /// Passes done: samples per pixel (pt) or light paths per pixel (lt).
    pub passes: u32,
    /// Paths traced in all.
    pub paths: u64,
    pub elapsed: Duration,
    /// Rejected samples, and the largest single-sample contribution to one pixel at one
    /// sample per pixel (luminance): the same unit for both integrators.
    pub stats: SampleStats,
}

/// Stream domains, so that the integrators never share random numbers.
const DOMAIN_PT: u64 = 1;
const DOMAIN_LT: u64 = 2;
/// Light paths per chunk (one splat list each).
const LT_CHUNK: usize = 4096;

/// One path-tracing pass: one sample in every pixel.
fn pt_pass(scene: &Scene, film: &mut Film, opts: &RenderOptions, pass: u32) {
    let w = scene.camera.width;
    let npix = scene.camera.pixel_count() as u64;
    film.add_per_pixel(|x, y| {
        let index = pass as u64 * npix + (y as u64 * w as u64 + x as u64);
        let mut rng = Rng::new(opts.seed, DOMAIN_PT, index);
        let raster = Vec2::new(x as f32, y as f32) + rng.uniform2();
        path_tracer::radiance(scene, raster, opts.max_depth, &mut rng)
    });
}

/// One light-tracing pass: as many light paths as there are pixels.
fn lt_pass(scene: &Scene, film: &mut Film, opts: &RenderOptions, pass: u32) {
    let npix = scene.camera.pixel_count();
    let chunks = npix.div_ceil(LT_CHUNK);
    let lists: Vec<SplatList> = (0..chunks)
        .into_par_iter()
        .map(|c| {
            let mut list = SplatList::default();
            let start = c * LT_CHUNK;
            let end = (start + LT_CHUNK).min(npix);
            for i in start..end {
                let index = pass as u64 * npix as u64 + i as u64;
                let mut rng = Rng::new(opts.seed, DOMAIN_LT, index);
                light_tracer::trace(scene, opts.max_depth, &mut rng, &mut list);
            }
            list
        })
        .collect();
    for l in &lists {
        film.add_splats(l);
    }
}

/// Renders `scene`. `on_progress(fraction)` is called after every pass.
pub fn render(
    scene: &Scene,
    opts: &RenderOptions,
    mut on_progress: impl FnMut(f64),
) -> RenderResult {
    let start = Instant::now();
    let cam = &scene.camera;
    let mut film = Film::new(cam.width, cam.height);
    let mut passes = 0u32;
    loop {
        match opts.integrator {
            Integrator::Pt => pt_pass(scene, &mut film, opts, passes),
            Integrator::Lt => lt_pass(scene, &mut film, opts, passes),
        }
        passes += 1;
        let elapsed = start.elapsed().as_secs_f64();
        let (fraction, done) = match opts.time {
            Some(t) => ((elapsed / t).min(1.0), elapsed >= t),
            None => (passes as f64 / opts.spp as f64, passes >= opts.spp),
        };
        on_progress(fraction);
        if done {
            break;
        }
    }
    // Path tracing averages `passes` samples per pixel; light tracing divides its splats by
    // the number of light paths, `passes` per pixel (see `light_tracer`).
    let paths_per_pass = match opts.integrator {
        Integrator::Pt => 1.0,
        Integrator::Lt => cam.pixel_count() as f64,
    };
    let image = film.to_image(1.0 / (passes as f64 * paths_per_pass));
    let mut stats = film.stats;
    stats.max_luminance /= paths_per_pass as f32;
    RenderResult {
        image,
        passes,
        paths: passes as u64 * cam.pixel_count() as u64,
        elapsed: start.elapsed(),
        stats,
    }
}
