//! Path tracing with next-event estimation and multiple importance sampling (Veach 1997,
//! §9.2), guided or not: at every scattering vertex the direction sampler (BSDF, grid or
//! footprint over the photon map) chooses the next direction; at every non-specular vertex
//! a light is chosen in proportion to power and a point on it sampled, and the MIS weight
//! between that and hitting the light uses the sampler's pdf (the guided mixture pdf,
//! evaluated at the light sample's direction). Delta lights are reached by next-event
//! estimation alone; specular vertices pass emission through unweighted.
//!
//! For the combined image the same path also carries the three-strategy weights of
//! [`crate::mis`]: its light hits and next-event connections are weighted against the light
//! tracer's camera connections.
//!
//! A uniform environment (Mitsuba's `constant`) is seen by rays that escape, weighted by MIS
//! against its next-event samples; in the combined image those paths come from the path
//! tracer alone.
//!
//! Path length: `max_depth` counts segments, the first being the camera ray. Emission seen
//! at hit `n` closes a path of `n` segments; a next-event connection at hit `n`, `n + 1`.

use crate::mis::{step_area, to_area, weight};
use footprint::Rgb;
use footprint::bsdf::{Bsdf, TransportMode};
use footprint::direction_sampler::{BsdfSampler, DirectionSampler, GuideState, ScatterPoint};
use footprint::geometry::spawn_origin;
use footprint::light::Light;
use footprint::math::power_heuristic;
use footprint::rng::Rng;
use footprint::scene::Scene;
use glam::{Vec2, Vec3};

/// Russian roulette starts after this many segments.
pub const RR_START_DEPTH: u32 = 3;

/// What one camera path contributes.
#[derive(Clone, Copy, Debug, Default)]
pub struct PathContribution {
    /// The path tracer's own estimate (NEE and hits weighted against each other).
    pub pt: Rgb,
    /// The path's share of the combined image (weighted against light tracing too).
    pub combined: Rgb,
}

/// The unguided positional density of light `li` at one of its points: choice x area pdf.
#[inline]
pub fn light_pos_pdf(scene: &Scene, li: u32) -> f64 {
    let pmf = scene.light_pmf(li) as f64;
    match &scene.lights[li as usize] {
        Light::Area { area, .. } => pmf / *area as f64,
        _ => pmf,
    }
}

/// Estimates the radiance arriving at the camera through raster position `raster`.
pub fn radiance(scene: &Scene, raster: Vec2, max_depth: u32, rng: &mut Rng) -> Rgb {
    let cam = &scene.camera;
    radiance_along(scene, cam.position, cam.ray_dir(raster), max_depth, rng)
}

/// Estimates the radiance arriving at `origin` from direction `-dir` (the ray `origin + t
/// dir`) with BSDF sampling; `origin` must already be offset off any surface it lies on.
/// Emission at the first hit counts fully.
pub fn radiance_along(
    scene: &Scene,
    origin: Vec3,
    dir: Vec3,
    max_depth: u32,
    rng: &mut Rng,
) -> Rgb {
    let mut state = GuideState::default();
    trace(
        scene,
        origin,
        dir,
        max_depth,
        rng,
        &BsdfSampler,
        &mut state,
        false,
    )
    .pt
}

/// The camera-side vertex before the current one, as the combined weights need it.
#[derive(Clone, Copy)]
struct Prev {
    p: Vec3,
    n: Option<Vec3>,
    bsdf: Option<Bsdf>,
    /// The path left this vertex by a delta lobe.
    delta: bool,
}

/// Traces one path from `origin` along `dir`. With `combined`, `origin` must be the camera
/// position (the weights assume a camera path).
#[allow(clippy::too_many_arguments)]
pub fn trace(
    scene: &Scene,
    origin: Vec3,
    dir: Vec3,
    max_depth: u32,
    rng: &mut Rng,
    sampler: &dyn DirectionSampler,
    state: &mut GuideState,
    combined: bool,
) -> PathContribution {
    let cam = &scene.camera;
    let mut out = PathContribution::default();
    let mut origin = origin;
    let mut dir = dir;
    let mut beta = Rgb::ONE;
    let mut prev_delta = true;
    let mut prev_pdf_w = 0.0f32;
    let mut prev_p = origin;
    let area_lights = scene.effects.area_lights;

    // ---- Combined-image bookkeeping (see `mis`) ----
    // d_fwd: product of camera-direction area densities up to the current vertex;
    // b_back: product of light-direction area densities of x1 .. x_{j-2};
    // before[0] = x_{j-1}, before[1] = x_{j-2} (x0 is the camera: no BSDF).
    let mut d_fwd = 1.0f64;
    let mut b_back = 1.0f64;
    let mut before: [Prev; 2] = [Prev {
        p: origin,
        n: None,
        bsdf: None,
        delta: false,
    }; 2];
    let mut x1_delta = false;

    for depth in 1..=max_depth {
        let Some(hit) = scene.intersect(origin, dir, f32::INFINITY) else {
            // ---- The environment seen by an escaping ray ----
            if let Some((ei, env)) = scene.environment() {
                let le = env.emitted(dir);
                let w = if prev_delta {
                    1.0
                } else {
                    let pdf_light = scene.light_pmf(ei) * env.pdf_li(prev_p, prev_p + dir);
                    power_heuristic(prev_pdf_w, pdf_light)
                };
                out.pt += beta * le * w;
                // The combined image takes environment paths from the path tracer alone
                // (see `light_tracer`): the same two-strategy weights.
                if combined {
                    out.combined += beta * le * w;
                }
            }
            break;
        };
        let wo = -dir;
        let bsdf = scene.bsdf(&hit);

        let mut last_fwd = 0.0f64;
        if combined {
            // Density of this vertex from the previous one (camera or surface).
            last_fwd = match before[0].bsdf {
                None => to_area(
                    cam.pdf_dir(dir.dot(cam.frame.z)) as f64,
                    cam.position,
                    hit.p,
                    Some(hit.ng),
                ),
                Some(b) => step_area(
                    &b,
                    before[0].delta,
                    before[0].p,
                    (before[1].p - before[0].p).normalize_or_zero(),
                    hit.p,
                    Some(hit.ng),
                ),
            };
            d_fwd *= last_fwd;
            // Light-direction density of x_{j-2} from x_{j-1}, now that x_j is known.
            if depth >= 3 {
                if let Some(b) = before[0].bsdf {
                    b_back *= step_area(
                        &b,
                        before[0].delta,
                        before[0].p,
                        dir,
                        before[1].p,
                        before[1].n,
                    );
                }
            }
        }

        // ---- Emission found by the sampled ray ----
        if area_lights {
            if let Some(li) = hit.light {
                let light = &scene.lights[li as usize];
                let le = light.emitted(wo);
                if le.max_element() > 0.0 {
                    if prev_delta {
                        out.pt += beta * le;
                    } else {
                        let pdf_light = scene.light_pmf(li) * light.pdf_li(prev_p, hit.p);
                        out.pt += beta * le * power_heuristic(prev_pdf_w, pdf_light);
                    }
                    if combined {
                        let p_l = light_pos_pdf(scene, li);
                        let p0 = d_fwd;
                        let p1 = match before[0].bsdf {
                            Some(_) if !before[0].delta && last_fwd > 0.0 => d_fwd / last_fwd * p_l,
                            _ => 0.0,
                        };
                        let pk = if depth == 1 {
                            p_l
                        } else if x1_delta {
                            0.0
                        } else {
                            let emit = to_area(
                                light.pdf_le_dir(wo) as f64,
                                hit.p,
                                before[0].p,
                                before[0].n,
                            );
                            p_l * b_back * emit
                        };
                        out.combined += beta * le * weight(p0, [p0, p1, pk]);
                    }
                }
            }
        }
        if depth == max_depth {
            break;
        }

        let at = ScatterPoint {
            p: hit.p,
            bsdf: &bsdf,
            wo,
            mode: TransportMode::Radiance,
            throughput: beta,
        };
        sampler.prepare(&at, state);

        // ---- Next-event estimation ----
        let u_light = rng.uniform();
        let u_pos = rng.uniform2();
        if !bsdf.is_delta() {
            let (li, pmf) = scene.light_distribution.sample(u_light);
            let light = &scene.lights[li];
            if let Some(ls) = light.sample_li(hit.p, u_pos) {
                let f = bsdf.eval(wo, ls.wi, TransportMode::Radiance);
                if f.max_element() > 0.0 && scene.visible(hit.p, hit.ng, ls.p, ls.n) {
                    let cos = ls.wi.dot(hit.ns).abs();
                    let contrib = if ls.delta {
                        beta * f * ls.li * (cos / pmf)
                    } else {
                        beta * f * ls.li * (cos / (ls.pdf_w * pmf))
                    };
                    // The path tracer's own weight: NEE against hitting the light by the sampler.
                    let w_pt = if ls.delta {
                        1.0
                    } else {
                        power_heuristic(ls.pdf_w * pmf, sampler.pdf(&at, state, ls.wi))
                    };
                    out.pt += contrib * w_pt;
                    if combined && light.is_environment() {
                        // Environment paths come from the path tracer alone (see `light_tracer`).
                        out.combined += contrib * w_pt;
                    } else if combined {
                        let p_l = light_pos_pdf(scene, li as u32);
                        let fwd_l = if ls.delta {
                            0.0
                        } else {
                            step_area(&bsdf, false, hit.p, wo, ls.p, ls.n)
                        };
                        let p0 = d_fwd * fwd_l;
                        let p1 = d_fwd * p_l;
                        let pk = if depth >= 2 && x1_delta {
                            0.0
                        } else {
                            let emit =
                                to_area(light.pdf_le_dir(-ls.wi) as f64, ls.p, hit.p, Some(hit.ng));
                            let back = if depth >= 2 {
                                step_area(&bsdf, false, hit.p, ls.wi, before[0].p, before[0].n)
                            } else {
                                1.0
                            };
                            p_l * b_back * back * emit
                        };
                        out.combined += contrib * weight(p1, [p0, p1, pk]);
                    }
                }
            }
        }

        // ---- Continue the path ----
        let Some(s) = sampler.sample(&at, state, rng) else {
            break;
        };
        beta *= s.weight;
        if !beta.is_finite() || beta.max_element() <= 0.0 {
            break;
        }
        prev_delta = s.delta;
        prev_pdf_w = s.pdf_w;
        prev_p = hit.p;
        if depth == 1 {
            // Whether x1 left by a delta lobe: light tracing cannot connect to it then.
            x1_delta = s.delta;
        }
        before[1] = before[0];
        before[0] = Prev {
            p: hit.p,
            n: Some(hit.ng),
            bsdf: Some(bsdf),
            delta: s.delta,
        };
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
    out
}
