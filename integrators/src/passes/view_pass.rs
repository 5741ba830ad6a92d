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

/// The view pass: an importance map's particles. `sampler` chooses the directions (BSDF
/// sampling, or guided by a photon map).
pub fn view_pass(scene: &Scene, s: &PassSettings, sampler: &GuidedSampler) -> PassOutput {
    let start = Instant::now();
    let cam = &scene.camera;
    let inv_n = 1.0 / s.paths.max(1) as f32;
    let size = Vec2::new(cam.width as f32, cam.height as f32);
    let all = crate::specialised!(s.specialisation(scene), F => run_chunks(0..s.paths, s.max_particles, |i, out, state| {
        let mut rng = Rng::new(s.seed, DOMAIN_VIEW_PASS, i as u64);
        let raster = rng.uniform2() * size;
        let w = inv_n * s.target.as_ref().map_or(1.0, |t| t.at_raster(raster, size));
        // From a point of the lens, as the camera paths start (the pinhole draws none).
        let (origin, dir) = cam.ray(raster, cam.draw_lens_sample(&mut rng));
        let start = Start {
            origin,
            dir,
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
            particles_drawn: all.drawn,
            thinning: all.thinning,
        },
    }
}
