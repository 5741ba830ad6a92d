//! Light tracing (Veach 1997, §10.3; Dutré et al. 1993): paths start on the lights (chosen
//! in proportion to power) and every non-specular vertex, the light vertex included, is
//! connected to the pinhole camera and splatted onto the film.
//!
//! Normalisation. With `N` light paths, a connection from vertex `x` with throughput `β`
//! (flux per unit area and solid angle, divided by all pdfs so far) adds to pixel `j`
//!
//! `β · f(x, ω_o → ω_c) · |ω_c · n_s| · W_e(ω_c) · cos θ_c / d² · P / N`
//!
//! where `W_e · P` is the box-filter importance of one of the `P` pixels (see
//! `footprint::camera`). The driver divides by `N`; this module multiplies by `P`.
//!
//! Path length: `max_depth` counts segments, the camera connection included: a connection
//! from the `n`-th hit closes a path of `n + 1` segments.

use crate::path_tracer::RR_START_DEPTH;
use footprint::bsdf::TransportMode;
use footprint::film::SplatList;
use footprint::geometry::{offset_ray_origin, spawn_origin};
use footprint::math::luminance;
use footprint::rng::Rng;
use footprint::scene::Scene;

/// Traces one light path and splats its camera connections into `splats`.
pub fn trace(scene: &Scene, max_depth: u32, rng: &mut Rng, splats: &mut SplatList) {
    let cam = &scene.camera;
    let (w, h) = (cam.width, cam.height);
    let pixels = cam.pixel_count() as f32;
    let (li, pmf) = scene.light_distribution.sample(rng.uniform());
    let light = &scene.lights[li];
    let Some(em) = light.sample_le(rng.uniform2(), rng.uniform2()) else {
        return;
    };

    // ---- The light vertex seen directly by the camera ----
    if let Some(conn) = cam.connect(em.p) {
        let cos_l = em.n.map(|n| n.dot(conn.dir_to_camera)).unwrap_or(1.0);
        if cos_l > 0.0 {
            let le = light.emitted(conn.dir_to_camera);
            let visible = match em.n {
                Some(n) => scene.visible_from_camera(em.p, n),
                None => scene.visible(cam.position, cam.frame.z, em.p, None),
            };
            if le.max_element() > 0.0 && visible {
                let v = le * (cos_l * conn.we_geom * pixels / (em.pdf_pos * pmf));
                splats.splat(w, h, conn.raster, v);
            }
        }
    }
    if max_depth < 2 {
        return;
    }

    let mut beta = em.le * (em.cos_light / (em.pdf_pos * em.pdf_dir * pmf));
    if !beta.is_finite() || beta.max_element() <= 0.0 {
        return;
    }
    let beta_start = luminance(beta).max(f32::MIN_POSITIVE);
    let mut origin = match em.n {
        Some(n) => offset_ray_origin(em.p, n),
        None => em.p,
    };
    let mut dir = em.dir;

    for depth in 1..max_depth {
        let Some(hit) = scene.intersect(origin, dir, f32::INFINITY) else {
            break;
        };
        let wo = -dir;
        let bsdf = scene.bsdf(&hit);

        // ---- Connect to the camera ----
        if !bsdf.is_delta() {
            if let Some(conn) = cam.connect(hit.p) {
                let wi = conn.dir_to_camera;
                let f = bsdf.eval(wo, wi, TransportMode::Importance);
                if f.max_element() > 0.0 && scene.visible_from_camera(hit.p, hit.ng) {
                    let v = beta * f * (wi.dot(hit.ns).abs() * conn.we_geom * pixels);
                    splats.splat(w, h, conn.raster, v);
                }
            }
        }
        if depth + 1 >= max_depth {
            break;
        }

        // ---- Continue the path ----
        let Some(s) = bsdf.sample(wo, rng.uniform(), rng.uniform2(), TransportMode::Importance)
        else {
            break;
        };
        beta *= s.weight;
        if !beta.is_finite() || beta.max_element() <= 0.0 {
            break;
        }
        if depth + 1 >= RR_START_DEPTH {
            let q = (luminance(beta) / beta_start).min(1.0).max(0.05);
            if rng.uniform() >= q {
                break;
            }
            beta /= q;
        }
        origin = spawn_origin(hit.p, hit.ng, s.wi);
        dir = s.wi;
    }
}
