//! Where light paths start, for the light tracer and the light pass alike: a light chosen
//! in proportion to power, a point and a direction sampled on it, and the emission
//! direction guided at area lights: the emitted cosine lobe plays the part of a white
//! Lambertian BSDF about the light's normal, and the importons that reached the light's
//! surface (paper §2.1) give the distribution.

use footprint::Rgb;
use footprint::bsdf::{Bsdf, Lobes, TransportMode};
use footprint::guide::sampler::{GuidedSampler, SamplerState, ScatterPoint};
use footprint::math::PI;
use footprint::rng::Rng;
use footprint::scene::Scene;
use footprint::scene::features::Features;
use footprint::scene::geometry::offset_ray_origin;
use footprint::scene::light::{Light, LightEmission};
use glam::Vec3;

/// A light chosen and a point on it sampled (with the light's own direction sample).
pub struct LightStart<'s> {
    pub index: usize,
    pub light: &'s Light,
    /// Probability of choosing the light.
    pub pmf: f32,
    pub em: LightEmission,
    /// The scene's [`Scene::offset_scale`], for the first ray's origin.
    pub offset_scale: f32,
}

/// Chooses a light in proportion to power and samples a point and a direction on it.
pub fn sample_light<'s>(scene: &'s Scene, rng: &mut Rng) -> Option<LightStart<'s>> {
    let (index, pmf, u_pos) = scene.choose_light(rng);
    let light = &scene.lights[index];
    let em = light.sample_le(u_pos, rng.uniform2())?;
    Some(LightStart {
        index,
        light,
        pmf,
        em,
        offset_scale: scene.offset_scale,
    })
}

/// The first ray of a light path: origin (off the light's surface), direction and
/// throughput `Le cos / (pdf_pos pdf_dir pmf)`; the direction guided by `sampler` at area
/// lights, sampled in the loop compiled for the effects `F` (the emitted lobe is Lambertian:
/// where `F` has the Lambertian fast path, it samples the lobe as the surfaces' vertices do).
/// `None` when no direction could be drawn or the throughput is zero.
pub fn first_ray<'a, F: Features>(
    start: &LightStart,
    sampler: &GuidedSampler<'a>,
    state: &mut SamplerState<'a>,
    rng: &mut Rng,
) -> Option<(Vec3, Vec3, Rgb)> {
    let em = &start.em;
    let (dir, beta) = match em.n {
        Some(n) => {
            // The emitted cosine lobe as a Lambertian "BSDF" of albedo 1 about the normal.
            let lobe = Bsdf::new(Lobes::Diffuse { kd: Rgb::ONE }, n, n);
            let at = ScatterPoint {
                p: em.p,
                bsdf: &lobe,
                wo: n,
                mode: TransportMode::Importance,
                throughput: em.le,
            };
            sampler.prepare(&at, state);
            let s = sampler.sample_with::<F>(&at, state, rng)?;
            // Le cos / (pdf_pos pdf_w pmf) = Le π (f cos / pdf_w) / (pdf_pos pmf) with f = 1/π.
            (s.wi, em.le * s.weight * (PI / (em.pdf_pos * start.pmf)))
        }
        None => (
            em.dir,
            em.le * (em.cos_light / (em.pdf_pos * em.pdf_dir * start.pmf)),
        ),
    };
    if !beta.is_finite() || beta.max_element() <= 0.0 {
        return None;
    }
    let origin = match em.n {
        Some(n) => offset_ray_origin(em.p, n, start.offset_scale),
        None => em.p,
    };
    Some((origin, dir, beta))
}
