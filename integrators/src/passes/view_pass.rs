//! The view pass (paper §2.1): importons shot from the camera through the image and
//! traced in radiance mode; each carries importance `W_p` per channel. It makes the
//! importance map that guides light paths.

use super::pass::{PassOutput, PassSettings, PassStats};
use super::storing::{run_chunks, trace};
use crate::walk::Start;
use footprint::Rgb;
use footprint::bsdf::TransportMode;
use footprint::guide::sampler::GuidedSampler;
use footprint::rng::Rng;
use footprint::scene::Scene;
use glam::Vec2;
use std::time::Instant;

const DOMAIN_VIEW_PASS: u64 = 12;

/// The share of a view pass's paths whose particles seed the photon map's cache, and the
/// share path tracing's view pass shoots (its importons serve only as those seeds). Seeds
/// only say where regions are: a region is at most the query distance wide and holds at
/// most `region_seeds`, so a quarter of the seeds gives nearly as many regions (Bitterli's
/// Cornell box, 64x64: 2711 regions against 3012) and the same error per sample, for a
/// quarter of the pass's time (docs/measurements/guided-vs-bsdf.md, "Seed passes"). Every
/// method's photon cache reads the same first paths' particles
/// ([`PassOutput::photon_cache_seeds`]), so path tracing builds the cache the combined image
/// and `auto`'s pilot build. Light tracing's light pass, the importance map's seeds, keeps
/// its paths: photons are sparse where light arrives through a narrow way, and door
/// measures worse with a quarter of them.
pub const SEED_PASS_SHARE: f64 = 0.25;

/// The first paths of a view pass of `paths` paths whose particles seed the photon map's
/// cache ([`SEED_PASS_SHARE`]).
pub fn seed_paths(paths: usize) -> usize {
    ((paths as f64 * SEED_PASS_SHARE) as usize).clamp(1, paths.max(1))
}

/// The view pass: an importance map's particles. `sampler` chooses the directions (BSDF
/// sampling, or guided by a photon map). The particles of its first
/// [`seed_paths`]`(s.paths)` paths are the photon map's cache seeds
/// ([`view_pass_seeding`]).
pub fn view_pass(scene: &Scene, s: &PassSettings, sampler: &GuidedSampler) -> PassOutput {
    view_pass_seeding(scene, s, sampler, seed_paths(s.paths))
}

/// The view pass, its first `seed_paths` paths traced first and their particles counted
/// ([`PassStats::seed_particles`]): the photon map's cache reads only those, so that path
/// tracing, whose view pass shoots only them, builds the same cache as the combined image
/// or `auto`'s pilot, which shoot them and more. A path's particles do not depend on how
/// many paths the pass shoots: each path draws from its own stream, and starts at its
/// pixel's relative importance with the pass's `1 / N` applied to the particles at the end
/// (Russian roulette reads the throughput relative to the start, which `1 / N` would
/// round differently for different `N`).
pub fn view_pass_seeding(
    scene: &Scene,
    s: &PassSettings,
    sampler: &GuidedSampler,
    seed_paths: usize,
) -> PassOutput {
    let start = Instant::now();
    let cam = &scene.camera;
    let inv_n = 1.0 / s.paths.max(1) as f32;
    let size = Vec2::new(cam.width as f32, cam.height as f32);
    let run = |paths: std::ops::Range<usize>| {
        crate::specialised!(s.specialisation(scene), F => run_chunks(paths, s.max_particles, |i, out, state| {
            let mut rng = Rng::new(s.seed, DOMAIN_VIEW_PASS, i as u64);
            let raster = rng.uniform2() * size;
            let w = s.target.as_ref().map_or(1.0, |t| t.at_raster(raster, size));
            // From a point of the lens, as the camera paths start (the pinhole draws none).
            let (origin, dir) = cam.ray(raster, cam.draw_lens_sample(&mut rng));
            let start = Start {
                origin,
                dir,
                beta: Rgb::splat(w),
                beta0: Rgb::splat(w),
                mode: TransportMode::Radiance,
                max_vertex_depth: s.max_depth,
                max_segments: s.max_depth,
                rr_depth: s.rr_depth,
            };
            trace::<F>(scene, s, &start, sampler, state, &mut rng, out);
        }))
    };
    let k = seed_paths.min(s.paths);
    let mut all = run(0..k);
    let seeding = all.particles.len();
    if k < s.paths {
        let mut rest = run(k..s.paths);
        all.append(&mut rest);
        all.within(s.max_particles);
    }
    for p in &mut all.particles {
        p.weight *= inv_n;
    }
    for e in &mut all.escaped {
        *e *= inv_n;
    }
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
            particles_drawn: all.drawn,
            thinning: all.thinning,
            // A thinned pass kept a share of each part's particles: their count in the
            // first part is not the seeding paths' own.
            seed_particles: (all.thinning == 0).then_some(seeding),
        },
    }
}
