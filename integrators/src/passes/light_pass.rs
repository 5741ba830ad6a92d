//! The light pass (paper §2.1): photons emitted from the lights in proportion to power
//! and traced in importance mode; each carries flux `Φ_p`. It makes the photon map that
//! guides camera paths.

use super::pass::{PassOutput, PassSettings, PassStats};
use super::storing::{run_chunks, trace};
use crate::emit::{first_ray, sample_light};
use crate::walk::Start;
use footprint::Rgb;
use footprint::bsdf::TransportMode;
use footprint::guide::cache::Seed;
use footprint::guide::sampler::GuidedSampler;
use footprint::rng::Rng;
use footprint::scene::Scene;
use std::ops::Range;
use std::time::Instant;

const DOMAIN_LIGHT_PASS: u64 = 11;

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
    let all = crate::specialised!(s.specialisation(scene), F => run_chunks(paths.clone(), s.max_particles, |i, out, state| {
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
            // A photon of depth `max_depth` would close a path of `max_depth + 1` segments
            // or more with any camera vertex it guides: it is not traced.
            max_vertex_depth: s.max_depth.saturating_sub(1).max(1),
            max_segments: s.max_depth,
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
            particles_drawn: all.drawn,
            thinning: all.thinning,
            seed_particles: None,
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
    let mut more = light_paths(scene, s, sampler, done..s.paths);
    let scale = done as f32 / s.paths as f32;
    let mut out = previous;
    // Both parts at one thinning level, then within the budget together.
    let level = out.stats.thinning.max(more.stats.thinning);
    out.thin_to(level);
    more.thin_to(level);
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
    out.stats.particles_drawn += more.stats.particles_drawn;
    out.within(s.max_particles);
    out.stats.guided_events += more.stats.guided_events;
    out.stats.fallbacks += more.stats.fallbacks;
    out.stats.time += more.stats.time;
    out
}
