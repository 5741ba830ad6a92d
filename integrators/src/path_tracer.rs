//! Path tracing with next-event estimation and multiple importance sampling (Veach 1997,
//! §9.2): at every non-specular vertex a light is chosen in proportion to power and a point
//! on it sampled; a BSDF-sampled ray that hits an area light is weighted against that
//! strategy with the power heuristic. Delta lights are reached by next-event estimation
//! alone; specular vertices pass emission through unweighted.
//!
//! Path length: `max_depth` counts segments, the first being the camera ray. Emission seen
//! at hit `n` closes a path of `n` segments; a next-event connection at hit `n`, `n + 1`.

use footprint::Rgb;
use footprint::bsdf::TransportMode;
use footprint::geometry::spawn_origin;
use footprint::math::power_heuristic;
use footprint::rng::Rng;
use footprint::scene::Scene;
use glam::{Vec2, Vec3};

/// Russian roulette starts after this many segments.
pub const RR_START_DEPTH: u32 = 3;

/// Estimates the radiance arriving at the camera through raster position `raster`.
pub fn radiance(scene: &Scene, raster: Vec2, max_depth: u32, rng: &mut Rng) -> Rgb {
    let cam = &scene.camera;
    radiance_along(scene, cam.position, cam.ray_dir(raster), max_depth, rng)
}

/// Estimates the radiance arriving at `origin` from direction `-dir` (the ray `origin + t
/// dir`); `origin` must already be offset off any surface it lies on. Emission at the first
/// hit counts fully.
pub fn radiance_along(
    scene: &Scene,
    origin: Vec3,
    dir: Vec3,
    max_depth: u32,
    rng: &mut Rng,
) -> Rgb {
    let mut origin = origin;
    let mut dir = dir;
    let mut beta = Rgb::ONE;
    let mut l = Rgb::ZERO;
    let mut prev_delta = true;
    let mut prev_pdf_w = 0.0f32;
    let mut prev_p = origin;
    let area_lights = scene.effects.area_lights;

    for depth in 1..=max_depth {
        let Some(hit) = scene.intersect(origin, dir, f32::INFINITY) else {
            break;
        };
        let wo = -dir;

        // ---- Emission found by the sampled ray ----
        if area_lights {
            if let Some(li) = hit.light {
                let light = &scene.lights[li as usize];
                let le = light.emitted(wo);
                if le.max_element() > 0.0 {
                    if prev_delta {
                        l += beta * le;
                    } else {
                        let pdf_light = scene.light_pmf(li) * light.pdf_li(prev_p, hit.p);
                        l += beta * le * power_heuristic(prev_pdf_w, pdf_light);
                    }
                }
            }
        }
        if depth == max_depth {
            break;
        }

        let bsdf = scene.bsdf(&hit);

        // ---- Next-event estimation ----
        if !bsdf.is_delta() {
            let (li, pmf) = scene.light_distribution.sample(rng.uniform());
            let light = &scene.lights[li];
            if let Some(ls) = light.sample_li(hit.p, rng.uniform2()) {
                let f = bsdf.eval(wo, ls.wi, TransportMode::Radiance);
                if f.max_element() > 0.0 && scene.visible(hit.p, hit.ng, ls.p, ls.n) {
                    let cos = ls.wi.dot(hit.ns).abs();
                    if ls.delta {
                        l += beta * f * ls.li * (cos / pmf);
                    } else {
                        let pdf_light = ls.pdf_w * pmf;
                        let w = power_heuristic(pdf_light, bsdf.pdf(wo, ls.wi));
                        l += beta * f * ls.li * (cos * w / pdf_light);
                    }
                }
            }
        } else {
            // Keep the random number sequence aligned whatever the material.
            rng.uniform();
            rng.uniform2();
        }

        // ---- Continue the path ----
        let Some(s) = bsdf.sample(wo, rng.uniform(), rng.uniform2(), TransportMode::Radiance)
        else {
            break;
        };
        beta *= s.weight;
        if !beta.is_finite() || beta.max_element() <= 0.0 {
            break;
        }
        prev_delta = s.delta;
        prev_pdf_w = s.pdf_w;
        prev_p = hit.p;
        if depth >= RR_START_DEPTH {
            let q = beta.max_element().min(1.0).max(0.05);
            if rng.uniform() >= q {
                break;
            }
            beta /= q;
        }
        origin = spawn_origin(hit.p, hit.ng, s.wi);
        dir = s.wi;
    }
    l
}
