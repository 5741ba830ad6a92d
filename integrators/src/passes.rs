//! The two particle passes (Hey & Purgathofer 2001, §2.1; docs/method.md, "Symmetry"):
//!
//! * the **light pass** emits photons from the lights in proportion to power (area lights
//!   uniformly in area and cosine-weighted in direction, or guided by an importance map,
//!   [`crate::emit`]; spot lights in their cone in proportion to the falloff, point lights
//!   uniformly) and traces them in importance mode; each carries flux `Φ_p`;
//! * the **view pass** shoots importons from the camera through the image, uniformly in
//!   raster position, which distributes them like the camera's importance `W_e` (the first
//!   segment's weight `W_e cos θ / pdf` is exactly 1 for a pinhole), and traces them in
//!   radiance mode; each carries importance `W_p` per channel, which starts equal in all
//!   channels and is multiplied by the colours the path passes through.
//!
//! Both are walks of [`crate::walk`] (the integrators' path loop and Russian roulette rule)
//! with a visitor that stores a particle at every hit on a diffuse or soft glossy surface
//! (where the guides use them, [`guides_at`]), never on mirrors, glass or strongly glossy
//! surfaces. Each path starts with weight `1/N` of the whole (`N` = paths shot), so a map's
//! weights sum to the power (or importance) arriving at stored surfaces. Directions come
//! from the pass's sampler: the BSDF's own sampling unless a map of the other pass guides
//! it.
//!
//! Besides its particles, a pass reports where its paths asked for a direction at a
//! guiding surface (its particles' places, and for the light pass the points where paths
//! left area lights): the seeds of the other map's guide cache.
//!
//! Parallel with rayon; paths are traced in fixed chunks with per-path random streams and
//! concatenated in chunk order, so a map is reproducible from its seed.

use crate::emit::{first_ray, sample_light};
use crate::walk::{Arrival, Start, Vertex, Visitor, walk};
use footprint::Rgb;
use footprint::bsdf::TransportMode;
use footprint::guide::cache::Seed;
use footprint::guide::guides_at;
use footprint::guide::particle_map::ParticleInput;
use footprint::guide::sampler::{DirectionSample, GuidedSampler, SamplerState};
use footprint::rng::Rng;
use footprint::scene::Scene;
use footprint::scene::features::{Features, Specialisation};
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use std::marker::PhantomData;
use std::ops::Range;
use std::time::{Duration, Instant};

/// Settings of one pass.
#[derive(Clone, Debug)]
pub struct PassSettings {
    /// Paths shot (photon paths or importon paths).
    pub paths: usize,
    /// Maximum path segments.
    pub max_depth: u32,
    /// Russian roulette after scattering at vertices of this depth or deeper.
    pub rr_depth: u32,
    pub seed: u64,
    /// Blinn exponents up to this count as "soft glossy" and store particles; above it a
    /// surface is "strongly glossy" and is treated like a specular one.
    pub soft_glossy_max: f32,
    /// Run the path loop compiled for the scene's effects (else the general one; the same
    /// particles either way, `footprint::scene::features`).
    pub specialise: bool,
    /// The view pass's starting weights per pixel (relative importance,
    /// [`crate::target`]); `None`: every importon path starts at `1 / N`.
    pub target: Option<std::sync::Arc<crate::target::ImportanceTarget>>,
}

impl PassSettings {
    /// The compiled loop the pass runs in.
    pub fn specialisation(&self, scene: &Scene) -> Specialisation {
        if self.specialise {
            Specialisation::for_effects(&scene.effects)
        } else {
            Specialisation::General
        }
    }
}

/// Flux (or importance) accounting of a pass, per bounce.
#[derive(Clone, Debug, Default)]
pub struct PassStats {
    pub paths: usize,
    /// Guided scattering events (at guiding surfaces) and, of those, BSDF fallbacks; zero
    /// for an unguided pass.
    pub guided_events: u64,
    pub fallbacks: u64,
    /// Total emitted power (light pass) or importance (view pass: 1 per channel).
    pub emitted: Rgb,
    /// Weight leaving the scene (no hit) after bounce `k` (index 0: straight from the source).
    pub escaped: Vec<Rgb>,
    pub time: Duration,
}

#[derive(Clone)]
pub struct PassOutput {
    pub particles: Vec<ParticleInput>,
    /// Points where paths left area lights (light pass only).
    pub emission_points: Vec<Seed>,
    pub stats: PassStats,
}

impl PassOutput {
    /// Where this pass's paths asked for a direction at guiding surfaces: the seeds of the
    /// other map's guide cache.
    pub fn seeds(&self) -> Vec<Seed> {
        self.particles
            .iter()
            .map(|p| Seed {
                position: p.position,
                normal: p.normal,
            })
            .chain(self.emission_points.iter().copied())
            .collect()
    }
}

const DOMAIN_LIGHT_PASS: u64 = 11;
const DOMAIN_VIEW_PASS: u64 = 12;
const CHUNK: usize = 2048;

#[derive(Default)]
struct ChunkOut {
    particles: Vec<ParticleInput>,
    emission_points: Vec<Seed>,
    escaped: Vec<Rgb>,
    /// Scattering events at guiding surfaces and BSDF fallbacks among them.
    guided: (u64, u64),
}

/// Stores particles along a walk.
struct Storing<'o, F> {
    soft_glossy_max: f32,
    specular_chain: bool,
    out: &'o mut ChunkOut,
    features: PhantomData<F>,
}

impl<F: Features> Visitor for Storing<'_, F> {
    type F = F;

    fn escaped(&mut self, _dir: Vec3, beta: Rgb, depth: u32, _from: &Arrival) {
        let k = depth as usize - 1;
        if self.out.escaped.len() <= k {
            self.out.escaped.resize(k + 1, Rgb::ZERO);
        }
        self.out.escaped[k] += beta;
    }

    fn reached(&mut self, v: &Vertex, _from: &Arrival) {
        if guides_at(&v.bsdf.lobes, self.soft_glossy_max) {
            let n = if v.hit.ng.dot(v.wo) >= 0.0 {
                v.hit.ng
            } else {
                -v.hit.ng
            };
            self.out.particles.push(ParticleInput {
                position: v.hit.p,
                dir: v.wo,
                normal: n,
                weight: v.beta,
                depth: v.depth.min(u16::MAX as u32) as u16,
                specular_chain: self.specular_chain,
            });
        }
    }

    fn scattered(&mut self, _v: &Vertex, s: &DirectionSample) {
        self.specular_chain &= s.delta;
    }

    // Particle paths are not split (a map's particles are independent paths).
    type Branch = ();
    fn branch(&self) {}
    fn restore(&mut self, _b: ()) {}
}

/// Traces paths `paths` (indices into the pass's streams) in chunks of [`CHUNK`].
fn run_chunks<'a>(
    paths: Range<usize>,
    path: impl Fn(usize, &mut ChunkOut, &mut SamplerState<'a>) + Sync,
) -> ChunkOut {
    let chunks = paths.len().div_ceil(CHUNK);
    let outs: Vec<ChunkOut> = (0..chunks)
        .into_par_iter()
        .map(|c| {
            let mut out = ChunkOut::default();
            let mut state = SamplerState::default();
            let first = paths.start + c * CHUNK;
            for i in first..(first + CHUNK).min(paths.end) {
                path(i, &mut out, &mut state);
            }
            out.guided = (state.prepared_events, state.fallbacks);
            out
        })
        .collect();
    let mut all = ChunkOut {
        particles: Vec::with_capacity(outs.iter().map(|o| o.particles.len()).sum()),
        ..Default::default()
    };
    for o in outs {
        all.guided.0 += o.guided.0;
        all.guided.1 += o.guided.1;
        all.particles.extend_from_slice(&o.particles);
        all.emission_points.extend_from_slice(&o.emission_points);
        if all.escaped.len() < o.escaped.len() {
            all.escaped.resize(o.escaped.len(), Rgb::ZERO);
        }
        for (e, x) in all.escaped.iter_mut().zip(&o.escaped) {
            *e += *x;
        }
    }
    all
}

/// Walks one particle path in the loop compiled for the effects `F` (the passes choose `F`
/// once, [`PassSettings::specialisation`]), storing into `out`.
#[allow(clippy::too_many_arguments)]
fn trace<'a, F: Features>(
    scene: &Scene,
    s: &PassSettings,
    start: &Start,
    sampler: &GuidedSampler<'a>,
    state: &mut SamplerState<'a>,
    rng: &mut Rng,
    out: &mut ChunkOut,
) {
    let mut v = Storing::<F> {
        soft_glossy_max: s.soft_glossy_max,
        specular_chain: true,
        out,
        features: PhantomData,
    };
    walk(scene, start, sampler, state, rng, &mut v);
}

/// The light pass: a photon map's particles. `sampler` chooses the directions (BSDF
/// sampling, or guided by an importance map).
pub fn light_pass(scene: &Scene, s: &PassSettings, sampler: &GuidedSampler) -> PassOutput {
    light_paths(scene, s, sampler, 0..s.paths)
}

/// The paths `paths` of the light pass `s` (each with weight `1 / s.paths`).
fn light_paths(
    scene: &Scene,
    s: &PassSettings,
    sampler: &GuidedSampler,
    paths: Range<usize>,
) -> PassOutput {
    let start = Instant::now();
    let inv_n = 1.0 / s.paths.max(1) as f32;
    let all = crate::specialised!(s.specialisation(scene), F => run_chunks(paths.clone(), |i, out, state| {
        let mut rng = Rng::new(s.seed, DOMAIN_LIGHT_PASS, i as u64);
        let Some(start) = sample_light(scene, &mut rng) else {
            return;
        };
        let Some((origin, dir, beta)) = first_ray::<F>(&start, sampler, state, &mut rng) else {
            return;
        };
        if let Some(n) = start.em.n {
            out.emission_points.push(Seed {
                position: start.em.p,
                normal: n,
            });
        }
        let beta = beta * inv_n;
        let start = Start {
            origin,
            dir,
            beta,
            beta0: beta,
            mode: TransportMode::Importance,
            max_vertex_depth: s.max_depth,
            rr_depth: s.rr_depth,
        };
        trace::<F>(scene, s, &start, sampler, state, &mut rng, out);
    }));
    let emitted = scene.lights.iter().map(|l| l.power_rgb()).sum();
    PassOutput {
        particles: all.particles,
        emission_points: all.emission_points,
        stats: PassStats {
            paths: paths.len(),
            guided_events: all.guided.0,
            fallbacks: all.guided.1,
            emitted,
            escaped: all.escaped,
            time: start.elapsed(),
        },
    }
}

/// The view pass: an importance map's particles. `sampler` chooses the directions (BSDF
/// sampling, or guided by a photon map).
pub fn view_pass(scene: &Scene, s: &PassSettings, sampler: &GuidedSampler) -> PassOutput {
    let start = Instant::now();
    let cam = &scene.camera;
    let inv_n = 1.0 / s.paths.max(1) as f32;
    let size = Vec2::new(cam.width as f32, cam.height as f32);
    let all = crate::specialised!(s.specialisation(scene), F => run_chunks(0..s.paths, |i, out, state| {
        let mut rng = Rng::new(s.seed, DOMAIN_VIEW_PASS, i as u64);
        let raster = rng.uniform2() * size;
        let w = inv_n * s.target.as_ref().map_or(1.0, |t| t.at_raster(raster, size));
        let start = Start {
            origin: cam.position,
            dir: cam.ray_dir(raster),
            beta: Rgb::splat(w),
            beta0: Rgb::splat(w),
            mode: TransportMode::Radiance,
            max_vertex_depth: s.max_depth,
            rr_depth: s.rr_depth,
        };
        trace::<F>(scene, s, &start, sampler, state, &mut rng, out);
    }));
    PassOutput {
        particles: all.particles,
        emission_points: all.emission_points,
        stats: PassStats {
            paths: s.paths,
            guided_events: all.guided.0,
            fallbacks: all.guided.1,
            emitted: Rgb::ONE,
            escaped: all.escaped,
            time: start.elapsed(),
        },
    }
}

/// A light pass grown to `s.paths` paths: `previous` (its first paths, traced with the same
/// settings and seed) with its weights rescaled from `1 / previous.paths` to `1 / s.paths`,
/// and the paths after it traced. The same particles as one pass of `s.paths` paths, up to
/// the rounding of the rescaled weights.
pub fn grow_light_pass(
    scene: &Scene,
    s: &PassSettings,
    sampler: &GuidedSampler,
    previous: PassOutput,
) -> PassOutput {
    let done = previous.stats.paths;
    assert!(s.paths >= done, "a pass only grows");
    let more = light_paths(scene, s, sampler, done..s.paths);
    let scale = done as f32 / s.paths as f32;
    let mut out = previous;
    for p in &mut out.particles {
        p.weight *= scale;
    }
    for e in &mut out.stats.escaped {
        *e *= scale;
    }
    out.particles.extend_from_slice(&more.particles);
    out.emission_points.extend_from_slice(&more.emission_points);
    if out.stats.escaped.len() < more.stats.escaped.len() {
        out.stats
            .escaped
            .resize(more.stats.escaped.len(), Rgb::ZERO);
    }
    for (e, x) in out.stats.escaped.iter_mut().zip(&more.stats.escaped) {
        *e += *x;
    }
    out.stats.paths = s.paths;
    out.stats.guided_events += more.stats.guided_events;
    out.stats.fallbacks += more.stats.fallbacks;
    out.stats.time += more.stats.time;
    out
}
