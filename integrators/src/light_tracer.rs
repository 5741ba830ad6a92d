//! Light tracing (Veach 1997, §10.3; Dutré et al. 1993), guided or not: paths start on the
//! lights (chosen in proportion to power), every scattering direction comes from the
//! direction sampler (BSDF, grid or footprint over the importance map), and every
//! non-specular vertex, the light vertex included, is connected to the pinhole camera and
//! splatted onto the film. At area lights the emission direction is guided too: the emitted
//! cosine lobe plays the BSDF's part, and the importons that reached the light's surface
//! (paper §2.1) give the footprints.
//!
//! Normalisation. With `N` light paths, a connection from vertex `x` with throughput `β`
//! (flux per unit area and solid angle, divided by all pdfs so far) adds to pixel `j`
//!
//! `β · f(x, ω_o → ω_c) · |ω_c · n_s| · W_e(ω_c) · cos θ_c / d² · P / N`
//!
//! where `W_e · P` is the box-filter importance of one of the `P` pixels (see
//! `footprint::camera`). The driver divides by `N`; this module multiplies by `P`.
//!
//! For the combined image each connection also carries its three-strategy weight
//! ([`crate::mis`]), against the path tracer's light hits and next-event connections; its
//! splat there is divided by `P` already, so that the combined film averages per pass like
//! the camera paths' contributions.
//!
//! Path length: `max_depth` counts segments, the camera connection included: a connection
//! from the `n`-th hit closes a path of `n + 1` segments.

use crate::mis::{step_area, to_area, weight};
use crate::path_tracer::{RR_START_DEPTH, light_pos_pdf};
use footprint::Rgb;
use footprint::bsdf::{Bsdf, Lobes, TransportMode};
use footprint::direction_sampler::{DirectionSampler, GuideState, ScatterPoint};
use footprint::film::SplatList;
use footprint::geometry::{offset_ray_origin, spawn_origin};
use footprint::math::{PI, luminance};
use footprint::rng::Rng;
use footprint::scene::Scene;
use glam::Vec3;

/// Splat targets: the light tracer's own image and the combined image.
pub struct Splats<'a> {
    pub lt: &'a mut SplatList,
    pub combined: Option<&'a mut SplatList>,
}

#[derive(Clone, Copy)]
struct Vtx {
    p: Vec3,
    n: Option<Vec3>,
    bsdf: Option<Bsdf>,
    /// The path left this vertex by a delta lobe.
    delta: bool,
}

/// Traces one light path and splats its camera connections.
pub fn trace(
    scene: &Scene,
    max_depth: u32,
    rng: &mut Rng,
    sampler: &dyn DirectionSampler,
    state: &mut GuideState,
    splats: &mut Splats,
) {
    let cam = &scene.camera;
    let (w, h) = (cam.width, cam.height);
    let pixels = cam.pixel_count() as f32;
    let (li, pmf) = scene.light_distribution.sample(rng.uniform());
    let light = &scene.lights[li];
    let Some(em) = light.sample_le(rng.uniform2(), rng.uniform2()) else {
        return;
    };
    // Paths from the environment stay out of the combined image: the path tracer alone
    // makes them there (its own two-strategy weights sum to one for them), so that the
    // weights remain a partition of unity without an area density at infinity.
    let environment = light.is_environment();
    let splats = &mut Splats {
        combined: if environment {
            None
        } else {
            splats.combined.as_deref_mut()
        },
        lt: &mut *splats.lt,
    };
    let combined = splats.combined.is_some();
    let p_l = light_pos_pdf(scene, li as u32);

    // ---- The light vertex seen directly by the camera (not the environment's disk) ----
    if let Some(conn) = cam.connect(em.p).filter(|_| !environment) {
        let cos_l = em.n.map(|n| n.dot(conn.dir_to_camera)).unwrap_or(1.0);
        if cos_l > 0.0 {
            let le = light.emitted(conn.dir_to_camera);
            let visible = match em.n {
                Some(n) => scene.visible_from_camera(em.p, n),
                None => scene.visible(cam.position, cam.frame.z, em.p, None),
            };
            if le.max_element() > 0.0 && visible {
                let v = le * (cos_l * conn.we_geom * pixels / (em.pdf_pos * pmf));
                splats.lt.splat(&cam.filter, w, h, conn.raster, v);
                if let Some(c) = splats.combined.as_deref_mut() {
                    // k = 1: the camera path could hit an area light here, nothing else.
                    let p0 = if em.n.is_some() {
                        to_area(
                            cam.pdf_dir((-conn.dir_to_camera).dot(cam.frame.z)) as f64,
                            cam.position,
                            em.p,
                            em.n,
                        )
                    } else {
                        0.0
                    };
                    c.splat(
                        &cam.filter,
                        w,
                        h,
                        conn.raster,
                        v * (weight(p_l, [p0, 0.0, p_l]) / pixels),
                    );
                }
            }
        }
    }
    if max_depth < 2 {
        return;
    }

    // ---- Emission direction, guided at area lights ----
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
            let Some(s) = sampler.sample(&at, state, rng) else {
                return;
            };
            // Le cos / (pdf_pos pdf_w pmf) = Le π (f cos / pdf_w) / (pdf_pos pmf) with f = 1/π.
            (s.wi, em.le * s.weight * (PI / (em.pdf_pos * pmf)))
        }
        None => (
            em.dir,
            em.le * (em.cos_light / (em.pdf_pos * em.pdf_dir * pmf)),
        ),
    };
    let mut beta = beta;
    if !beta.is_finite() || beta.max_element() <= 0.0 {
        return;
    }
    let beta_start = luminance(beta).max(f32::MIN_POSITIVE);
    let mut origin = match em.n {
        Some(n) => offset_ray_origin(em.p, n),
        None => em.p,
    };
    let mut dir = dir;

    // ---- Combined-image bookkeeping (see `mis`) ----
    // l_fwd: light-direction area densities (light position included);
    // r_prod: camera-direction densities of y_1 .. y_{j-2} (each from its successor);
    // pf_light: camera-direction density of the light point from y_1 (0 for delta lights).
    let mut l_fwd = p_l;
    let mut r_prod = 1.0f64;
    let mut pf_light = 0.0f64;
    let mut y1_delta = false;
    let mut before: [Vtx; 2] = [Vtx {
        p: em.p,
        n: em.n,
        bsdf: None,
        delta: false,
    }; 2];

    for depth in 1..max_depth {
        let Some(hit) = scene.intersect(origin, dir, f32::INFINITY) else {
            break;
        };
        let wo = -dir;
        let bsdf = scene.bsdf(&hit);

        if combined {
            l_fwd *= match before[0].bsdf {
                None => to_area(light.pdf_le_dir(dir) as f64, em.p, hit.p, Some(hit.ng)),
                Some(b) => step_area(
                    &b,
                    before[0].delta,
                    before[0].p,
                    (before[1].p - before[0].p).normalize_or_zero(),
                    hit.p,
                    Some(hit.ng),
                ),
            };
            if depth >= 2 {
                if let Some(b) = before[0].bsdf {
                    let d = if depth == 2 && em.n.is_none() {
                        0.0 // a camera path cannot hit a delta light
                    } else {
                        step_area(
                            &b,
                            before[0].delta,
                            before[0].p,
                            dir,
                            before[1].p,
                            before[1].n,
                        )
                    };
                    if depth == 2 {
                        pf_light = d
                    } else {
                        r_prod *= d
                    }
                }
            }
        }

        // ---- Connect to the camera ----
        if !bsdf.is_delta() {
            if let Some(conn) = cam.connect(hit.p) {
                let wi = conn.dir_to_camera;
                let f = bsdf.eval(wo, wi, TransportMode::Importance);
                if f.max_element() > 0.0 && scene.visible_from_camera(hit.p, hit.ng) {
                    let v = beta * f * (wi.dot(hit.ns).abs() * conn.we_geom * pixels);
                    splats.lt.splat(&cam.filter, w, h, conn.raster, v);
                    if let Some(c) = splats.combined.as_deref_mut() {
                        let cam_area = to_area(
                            cam.pdf_dir((-wi).dot(cam.frame.z)) as f64,
                            cam.position,
                            hit.p,
                            Some(hit.ng),
                        );
                        let now = if depth == 1 && em.n.is_none() {
                            0.0
                        } else {
                            step_area(&bsdf, false, hit.p, wi, before[0].p, before[0].n)
                        };
                        let (p0, p1) = if depth == 1 {
                            (cam_area * now, cam_area * p_l)
                        } else {
                            let base = cam_area * now * r_prod;
                            (base * pf_light, if y1_delta { 0.0 } else { base * p_l })
                        };
                        c.splat(
                            &cam.filter,
                            w,
                            h,
                            conn.raster,
                            v * (weight(l_fwd, [p0, p1, l_fwd]) / pixels),
                        );
                    }
                }
            }
        }
        if depth + 1 >= max_depth {
            break;
        }

        // ---- Continue the path ----
        let at = ScatterPoint {
            p: hit.p,
            bsdf: &bsdf,
            wo,
            mode: TransportMode::Importance,
            throughput: beta,
        };
        sampler.prepare(&at, state);
        let Some(s) = sampler.sample(&at, state, rng) else {
            break;
        };
        beta *= s.weight;
        if !beta.is_finite() || beta.max_element() <= 0.0 {
            break;
        }
        if depth == 1 {
            // Whether y1 left by a delta lobe: next-event estimation cannot reach it then.
            y1_delta = s.delta;
        }
        before[1] = before[0];
        before[0] = Vtx {
            p: hit.p,
            n: Some(hit.ng),
            bsdf: Some(bsdf),
            delta: s.delta,
        };
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
