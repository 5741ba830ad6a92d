//! The two particle passes (Hey & Purgathofer 2001, §2.1; METHOD.md, "Symmetry"):
//!
//! * the **light pass** emits photons from the lights in proportion to power (area lights
//!   uniformly in area and cosine-weighted in direction, spot lights in their cone in
//!   proportion to the falloff, point lights uniformly) and traces them with BSDF sampling
//!   (importance mode) and Russian roulette; each carries flux `Φ_p`;
//! * the **view pass** shoots importons from the camera through the image, uniformly in
//!   raster position, which distributes them like the camera's importance `W_e` (the first
//!   segment's weight `W_e cos θ / pdf` is exactly 1 for a pinhole), and traces them with BSDF
//!   sampling (radiance mode); each carries importance `W_p` per channel, which starts equal
//!   in all channels and is multiplied by the colours the path passes through.
//!
//! Both store a particle at every hit on a diffuse or soft glossy surface (Blinn exponent at
//! most `soft_glossy_max`), never on mirrors, glass or strongly glossy surfaces. Each path
//! starts with weight `1/N` of the whole (`N` = paths shot), so a map's weights sum to the
//! power (or importance) arriving at stored surfaces.
//!
//! Parallel with rayon; paths are traced in fixed chunks with per-path random streams and
//! concatenated in chunk order, so a map is reproducible from its seed.

use footprint::Rgb;
use footprint::bsdf::TransportMode;
// Particles are stored exactly where the guided samplers use them.
use footprint::direction_sampler::guides_at;
use footprint::geometry::{offset_ray_origin, spawn_origin};
use footprint::math::luminance;
use footprint::particle_map::ParticleInput;
use footprint::rng::Rng;
use footprint::scene::Scene;
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use std::time::{Duration, Instant};

/// Settings of one pass.
#[derive(Clone, Debug)]
pub struct PassSettings {
    /// Paths shot (photon paths or importon paths).
    pub paths: usize,
    /// Maximum path segments.
    pub max_depth: u32,
    pub seed: u64,
    /// Blinn exponents up to this count as "soft glossy" and store particles; above it a
    /// surface is "strongly glossy" and is treated like a specular one.
    pub soft_glossy_max: f32,
}

/// Flux (or importance) accounting of a pass, per bounce.
#[derive(Clone, Debug, Default)]
pub struct PassStats {
    pub paths: usize,
    /// Total emitted power (light pass) or importance (view pass: 1 per channel).
    pub emitted: Rgb,
    /// Weight leaving the scene (no hit) after bounce `k` (index 0: straight from the source).
    pub escaped: Vec<Rgb>,
    pub time: Duration,
}

pub struct PassOutput {
    pub particles: Vec<ParticleInput>,
    pub stats: PassStats,
}

const DOMAIN_LIGHT_PASS: u64 = 11;
const DOMAIN_VIEW_PASS: u64 = 12;
const CHUNK: usize = 2048;

struct ChunkOut {
    particles: Vec<ParticleInput>,
    escaped: Vec<Rgb>,
}

/// Traces one path from `origin` along `dir` with weight `beta`, storing particles.
#[allow(clippy::too_many_arguments)]
fn trace(
    scene: &Scene,
    s: &PassSettings,
    mode: TransportMode,
    mut origin: Vec3,
    mut dir: Vec3,
    mut beta: Rgb,
    rng: &mut Rng,
    out: &mut ChunkOut,
) {
    let beta_start = luminance(beta).max(f32::MIN_POSITIVE);
    let mut specular_chain = true;
    for depth in 1..=s.max_depth {
        let Some(hit) = scene.intersect(origin, dir, f32::INFINITY) else {
            let k = depth as usize - 1;
            if out.escaped.len() <= k {
                out.escaped.resize(k + 1, Rgb::ZERO);
            }
            out.escaped[k] += beta;
            return;
        };
        let wo = -dir;
        let bsdf = scene.bsdf(&hit);
        if guides_at(&bsdf.lobes, s.soft_glossy_max) {
            let n = if hit.ng.dot(wo) >= 0.0 {
                hit.ng
            } else {
                -hit.ng
            };
            out.particles.push(ParticleInput {
                position: hit.p,
                dir: wo,
                normal: n,
                weight: beta,
                depth: depth.min(u16::MAX as u32) as u16,
                specular_chain,
            });
        }
        if depth == s.max_depth {
            return;
        }
        let Some(smp) = bsdf.sample(wo, rng.uniform(), rng.uniform2(), mode) else {
            return;
        };
        beta *= smp.weight;
        if !beta.is_finite() || beta.max_element() <= 0.0 {
            return;
        }
        specular_chain &= smp.delta;
        if depth >= 2 {
            let q = (luminance(beta) / beta_start).clamp(0.05, 1.0);
            if rng.uniform() >= q {
                return;
            }
            beta /= q;
        }
        origin = spawn_origin(hit.p, hit.ng, smp.wi);
        dir = smp.wi;
    }
}

fn run_chunks(
    s: &PassSettings,
    path: impl Fn(usize, &mut ChunkOut) + Sync,
) -> (Vec<ParticleInput>, Vec<Rgb>) {
    let chunks = s.paths.div_ceil(CHUNK);
    let outs: Vec<ChunkOut> = (0..chunks)
        .into_par_iter()
        .map(|c| {
            let mut out = ChunkOut {
                particles: Vec::new(),
                escaped: Vec::new(),
            };
            for i in c * CHUNK..((c + 1) * CHUNK).min(s.paths) {
                path(i, &mut out);
            }
            out
        })
        .collect();
    let total: usize = outs.iter().map(|o| o.particles.len()).sum();
    let mut particles = Vec::with_capacity(total);
    let mut escaped: Vec<Rgb> = Vec::new();
    for o in outs {
        particles.extend_from_slice(&o.particles);
        if escaped.len() < o.escaped.len() {
            escaped.resize(o.escaped.len(), Rgb::ZERO);
        }
        for (e, x) in escaped.iter_mut().zip(&o.escaped) {
            *e += *x;
        }
    }
    (particles, escaped)
}

/// The light pass: a photon map's particles.
pub fn light_pass(scene: &Scene, s: &PassSettings) -> PassOutput {
    let start = Instant::now();
    let inv_n = 1.0 / s.paths.max(1) as f32;
    let (particles, escaped) = run_chunks(s, |i, out| {
        let mut rng = Rng::new(s.seed, DOMAIN_LIGHT_PASS, i as u64);
        let (li, pmf) = scene.light_distribution.sample(rng.uniform());
        let light = &scene.lights[li];
        let Some(em) = light.sample_le(rng.uniform2(), rng.uniform2()) else {
            return;
        };
        let beta = em.le * (em.cos_light / (em.pdf_pos * em.pdf_dir * pmf) * inv_n);
        if !beta.is_finite() || beta.max_element() <= 0.0 {
            return;
        }
        let origin = match em.n {
            Some(n) => offset_ray_origin(em.p, n),
            None => em.p,
        };
        trace(
            scene,
            s,
            TransportMode::Importance,
            origin,
            em.dir,
            beta,
            &mut rng,
            out,
        );
    });
    let emitted = scene.lights.iter().map(|l| l.power_rgb()).sum();
    PassOutput {
        particles,
        stats: PassStats {
            paths: s.paths,
            emitted,
            escaped,
            time: start.elapsed(),
        },
    }
}

/// The view pass: an importance map's particles.
pub fn view_pass(scene: &Scene, s: &PassSettings) -> PassOutput {
    let start = Instant::now();
    let cam = &scene.camera;
    let inv_n = 1.0 / s.paths.max(1) as f32;
    let size = Vec2::new(cam.width as f32, cam.height as f32);
    let (particles, escaped) = run_chunks(s, |i, out| {
        let mut rng = Rng::new(s.seed, DOMAIN_VIEW_PASS, i as u64);
        let raster = rng.uniform2() * size;
        let dir = cam.ray_dir(raster);
        trace(
            scene,
            s,
            TransportMode::Radiance,
            cam.position,
            dir,
            Rgb::splat(inv_n),
            &mut rng,
            out,
        );
    });
    PassOutput {
        particles,
        stats: PassStats {
            paths: s.paths,
            emitted: Rgb::ONE,
            escaped,
            time: start.elapsed(),
        },
    }
}
