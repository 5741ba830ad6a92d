//! Path tracing with next-event estimation and multiple importance sampling (Veach 1997,
//! §9.2), guided or not: at every scattering vertex the direction sampler (BSDF, grid or
//! footprint over the photon map) chooses the next direction; at every non-specular vertex
//! a light is chosen in proportion to power and a point on it sampled, and the MIS weight
//! between that and hitting the light uses the sampler's pdf (the guided mixture pdf,
//! evaluated at the light sample's direction). Delta lights are reached by next-event
//! estimation alone; specular vertices pass emission through unweighted.
//!
//! An environment (Mitsuba's `constant` or `envmap`) is seen by rays that escape, weighted by
//! MIS against its next-event samples. The directional light, a delta, is reached by
//! next-event estimation alone, as point lights.
//!
//! A camera path can also feed a second estimate with other weights ([`CameraShare`]): the
//! combined image's share, weighted against light tracing by [`crate::mis::CameraMis`].
//!
//! Path length: `max_depth` counts segments, the first being the camera ray. Emission seen
//! at hit `n` closes a path of `n` segments; a next-event connection at hit `n`, `n + 1`.

use super::{Context, Integrator, Paths};
use crate::learning::Learning;
use crate::mis::{CameraMis, PilotMis, Strategies};
use crate::walk::{Arrival, Start, Vertex, Visitor, walk};
use footprint::Rgb;
use footprint::bsdf::TransportMode;
use footprint::guide::sampler::{DirectionSample, GuidedSampler, SamplerState, ScatterPoint};
use footprint::math::power_heuristic;
use footprint::rng::Rng;
use footprint::scene::features::{Features, General};
use footprint::scene::light::LightSample;
use footprint::scene::{Scene, Toward};
use glam::{Vec2, Vec3};
use std::marker::PhantomData;

/// Path tracing, registered as `pt`.
pub struct PathTracing;

impl Integrator for PathTracing {
    fn name(&self) -> &'static str {
        "pt"
    }
    fn about(&self) -> &'static str {
        "Path tracing with next-event estimation and MIS, guided by the photon map"
    }
    fn layers(&self) -> &'static [&'static str] {
        &["pt"]
    }
    fn paths(&self) -> Paths {
        Paths {
            camera: true,
            light: false,
        }
    }
    fn camera_path<'a>(
        &self,
        ctx: &Context<'a>,
        raster: Vec2,
        rng: &mut Rng,
        state: &mut SamplerState<'a>,
        out: &mut [Rgb],
    ) {
        out[0] += camera_path(ctx, raster, rng, state, |_| ()).pt;
    }
}

/// One camera path through `raster` in the render's compiled loop, feeding the share
/// `share(lens point)` makes at the camera vertex (a point sampled on the lens: the numbers
/// after the raster position's, drawn only where the camera has a lens).
pub fn camera_path<'a, S: CameraShare>(
    ctx: &Context<'a>,
    raster: Vec2,
    rng: &mut Rng,
    state: &mut SamplerState<'a>,
    share: impl FnOnce(Vec3) -> S,
) -> CameraContribution {
    let cam = &ctx.scene.camera;
    let (origin, dir) = cam.ray(raster, cam.draw_lens_sample(rng));
    let share = share(origin);
    crate::specialised!(ctx.specialisation, F => trace::<F, _>(
        ctx.scene,
        origin,
        dir,
        (ctx.max_depth, ctx.rr_depth),
        &ctx.camera_sampler,
        state,
        rng,
        share,
    ))
}

/// A second estimate a camera path feeds, with its own weights for the same
/// contributions. `()` feeds none.
pub trait CameraShare: Copy {
    /// False for `()`: nothing to compute.
    const ACTIVE: bool;
    fn arrive(&mut self, _scene: &Scene, _v: &Vertex) {}
    /// The strategies (and so the weight) of emission from light `li` found at `v`.
    fn light_hit(&self, _scene: &Scene, _li: u32, _v: &Vertex) -> Strategies {
        Strategies::NONE
    }
    /// The strategies of a next-event connection from `v` to `ls` on light `li`.
    fn nee(&self, _scene: &Scene, _li: u32, _v: &Vertex, _ls: &LightSample) -> Strategies {
        Strategies::NONE
    }
    fn scattered(&mut self, _v: &Vertex, _s: &DirectionSample) {}
    /// The path also feeds the second-moment layers (`crate::moments`), for a render of
    /// this horizon.
    fn moments(&self) -> Option<&crate::moments::Horizon> {
        None
    }
}

impl CameraShare for () {
    const ACTIVE: bool = false;
}

impl CameraShare for CameraMis<'_> {
    const ACTIVE: bool = true;
    fn arrive(&mut self, scene: &Scene, v: &Vertex) {
        CameraMis::arrive(self, scene, v.index, -v.wo, v.hit.p, v.hit.ng);
    }
    fn light_hit(&self, scene: &Scene, li: u32, v: &Vertex) -> Strategies {
        CameraMis::light_hit(self, scene, li, v.index, v.wo, v.hit.p)
    }
    fn nee(&self, scene: &Scene, li: u32, v: &Vertex, ls: &LightSample) -> Strategies {
        CameraMis::nee(
            self, scene, li, v.index, &v.bsdf, v.hit.p, v.hit.ng, v.wo, ls,
        )
    }
    fn scattered(&mut self, v: &Vertex, s: &DirectionSample) {
        CameraMis::scattered(self, v.index, v.hit.p, v.hit.ng, &v.bsdf, s.delta);
    }
}

/// `auto`'s pilot: the samplers' weights, and the unguided densities beside them.
impl CameraShare for PilotMis<CameraMis<'_>> {
    const ACTIVE: bool = true;
    fn arrive(&mut self, scene: &Scene, v: &Vertex) {
        CameraShare::arrive(&mut self.main, scene, v);
        CameraShare::arrive(&mut self.unguided, scene, v);
    }
    fn light_hit(&self, scene: &Scene, li: u32, v: &Vertex) -> Strategies {
        Strategies {
            unguided: CameraShare::light_hit(&self.unguided, scene, li, v).p,
            ..CameraShare::light_hit(&self.main, scene, li, v)
        }
    }
    fn nee(&self, scene: &Scene, li: u32, v: &Vertex, ls: &LightSample) -> Strategies {
        Strategies {
            unguided: CameraShare::nee(&self.unguided, scene, li, v, ls).p,
            ..CameraShare::nee(&self.main, scene, li, v, ls)
        }
    }
    fn scattered(&mut self, v: &Vertex, s: &DirectionSample) {
        CameraShare::scattered(&mut self.main, v, s);
        CameraShare::scattered(&mut self.unguided, v, s);
    }
    fn moments(&self) -> Option<&crate::moments::Horizon> {
        Some(&self.horizon)
    }
}

/// What one camera path contributes: the path tracer's own estimate (NEE and light hits
/// weighted against each other), its share of a second estimate, and what it adds to the
/// second-moment layers ([`crate::moments`], when the share asks for them).
#[derive(Clone, Copy, Debug, Default)]
pub struct CameraContribution {
    pub pt: Rgb,
    pub share: Rgb,
    pub m2: [Rgb; crate::moments::LAYERS.len()],
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
    let sampler = GuidedSampler::bsdf();
    let mut state = SamplerState::default();
    let depths = (max_depth, footprint::settings::DEFAULT_RR_DEPTH);
    trace::<General, _>(scene, origin, dir, depths, &sampler, &mut state, rng, ()).pt
}

/// Traces one camera path from `origin` along `dir` with `(max_depth, rr_depth)`, in the
/// loop compiled for the effects `F`; `share` receives the second estimate's weights (its
/// `origin` must be the camera vertex: the lens point the ray starts from).
#[allow(clippy::too_many_arguments)]
pub fn trace<'a, F: Features, S: CameraShare>(
    scene: &Scene,
    origin: Vec3,
    dir: Vec3,
    (max_depth, rr_depth): (u32, u32),
    sampler: &GuidedSampler<'a>,
    state: &mut SamplerState<'a>,
    rng: &mut Rng,
    share: S,
) -> CameraContribution {
    let mut v = CameraVisitor::<S, F> {
        scene,
        max_depth,
        out: CameraContribution::default(),
        share,
        learning: Learning::new(sampler.selection.is_some()),
        features: PhantomData,
    };
    let start = Start {
        origin,
        dir,
        beta: Rgb::ONE,
        beta0: Rgb::ONE,
        mode: TransportMode::Radiance,
        max_vertex_depth: max_depth,
        max_segments: max_depth,
        rr_depth,
    };
    walk(scene, &start, sampler, state, rng, &mut v);
    v.learning.finish(&mut state.selection_records);
    v.out
}

struct CameraVisitor<'s, S, F> {
    scene: &'s Scene,
    /// Most segments of a path (a connection through thin sheets counts each).
    max_depth: u32,
    out: CameraContribution,
    share: S,
    learning: Learning,
    features: PhantomData<F>,
}

impl<S: CameraShare, F: Features> CameraVisitor<'_, S, F> {
    /// A contribution of unweighted value `value`, made by `st` on a path of roulette
    /// survival `survival`, of which the path tracer kept `own`, adds to the second-moment
    /// layers when they are asked for.
    #[inline]
    fn moments(&mut self, value: Rgb, st: &Strategies, own: Rgb, survival: f32) {
        if let Some(horizon) = self.share.moments() {
            let t = crate::moments::terms(value, st, own, true, survival, horizon);
            for (m, t) in self.out.m2.iter_mut().zip(t) {
                *m += t;
            }
        }
    }
}

impl<S: CameraShare, F: Features> Visitor for CameraVisitor<'_, S, F> {
    type F = F;

    // ---- The environment seen by an escaping ray ----
    fn escaped(&mut self, dir: Vec3, beta: Rgb, _depth: u32, from: &Arrival) {
        if !F::ENVIRONMENT {
            return;
        }
        let Some((ei, env)) = self.scene.environment() else {
            return;
        };
        // The environment's light along `dir` arrives from `-dir`'s far end: it leaves the
        // environment toward `-dir`.
        let le = env.emitted(-dir);
        let w = if from.delta {
            1.0
        } else {
            let pdf_light = self.scene.light_pmf(ei) * env.pdf_environment(dir);
            power_heuristic(from.pdf_w, pdf_light)
        };
        self.out.pt += beta * le * w;
        self.learning.credit(beta * le * w);
        // The second estimate takes environment paths from the path tracer alone (see
        // `light_tracing`): the same two-strategy weights. They add nothing to the
        // second-moment layers (`crate::moments`).
        if S::ACTIVE {
            self.out.share += beta * le * w;
        }
    }

    // ---- Emission found by the sampled ray ----
    fn reached(&mut self, v: &Vertex, from: &Arrival, _rng: &mut Rng) {
        if S::ACTIVE {
            self.share.arrive(self.scene, v);
        }
        if !F::AREA_LIGHTS || !self.scene.effects.area_lights {
            return;
        }
        let Some(li) = v.hit.light else { return };
        let light = &self.scene.lights[li as usize];
        let le = light.emitted(v.wo);
        if le.max_element() <= 0.0 {
            return;
        }
        let c = if from.delta {
            v.beta * le
        } else {
            let pdf_light = self.scene.light_pmf(li) * light.pdf_li(from.prev_p, v.hit.p);
            v.beta * le * power_heuristic(from.pdf_w, pdf_light)
        };
        self.out.pt += c;
        self.learning.credit(c);
        if S::ACTIVE {
            let st = self.share.light_hit(self.scene, li, v);
            self.out.share += v.beta * le * st.weight();
            self.moments(v.beta * le, &st, c, v.survival);
        }
    }

    // ---- Next-event estimation ----
    fn before_scatter(
        &mut self,
        v: &Vertex,
        at: &ScatterPoint,
        sampler: &GuidedSampler,
        state: &SamplerState,
        rng: &mut Rng,
    ) {
        let scene = self.scene;
        let (li, pmf, u_pos) = scene.choose_light(rng);
        if v.bsdf.is_delta_with::<F>() {
            return;
        }
        let light = &scene.lights[li];
        let Some(ls) = light.sample_li(v.hit.p, u_pos) else {
            return;
        };
        // The Lambertian fast path gives the BSDF's density of `ls.wi` with `f`, for the
        // weight below.
        let (f, bsdf_pdf) =
            v.bsdf
                .eval_and_lambert_pdf_with::<F>(v.wo, ls.wi, TransportMode::Radiance);
        // Point, spot and directional lights are the delta lights.
        let delta = F::DELTA_LIGHTS && ls.delta;
        if f.max_element() <= 0.0 {
            return;
        }
        // The connection closes a path of depth + 1 segments, and one more per thin sheet it
        // passes through.
        let sheets = self.max_depth.saturating_sub(v.depth + 1);
        let (t, _) = scene.transmittance(Toward::Light, v.hit.p, v.hit.ng, ls.p, ls.n, sheets);
        if t.max_element() <= 0.0 {
            return;
        }
        let cos = ls.wi.dot(v.hit.ns).abs();
        let contrib = if delta {
            v.beta * f * t * ls.li * (cos / pmf)
        } else {
            v.beta * f * t * ls.li * (cos / (ls.pdf_w * pmf))
        };
        // The path tracer's own weight: NEE against hitting the light by the sampler.
        let w_pt = if delta {
            1.0
        } else {
            let pdf = match bsdf_pdf {
                Some(p) => sampler.pdf_given_bsdf_with::<F>(at, state, ls.wi, p),
                None => sampler.pdf_with::<F>(at, state, ls.wi),
            };
            power_heuristic(ls.pdf_w * pmf, pdf)
        };
        self.out.pt += contrib * w_pt;
        self.learning.credit(contrib * w_pt);
        if S::ACTIVE {
            // Environment paths come from the path tracer alone (see `light_tracing`).
            if F::ENVIRONMENT && light.is_environment() {
                self.out.share += contrib * w_pt;
            } else {
                let st = self.share.nee(scene, li as u32, v, &ls);
                self.out.share += contrib * st.weight();
                self.moments(contrib, &st, contrib * w_pt, v.survival);
            }
        }
    }

    fn scattered(&mut self, v: &Vertex, s: &DirectionSample) {
        self.learning.scattered(s);
        if S::ACTIVE {
            self.share.scattered(v, s);
        }
    }

    // ---- Guided splitting: each branch starts from the same running weights ----
    type Branch = (S, usize);
    /// Not in the combined image (its weights do not count branches; it measures worse
    /// with them on door and desk, docs/measurements/sweeps.md, "Guided Russian roulette
    /// and splitting").
    fn splits(&self) -> bool {
        !S::ACTIVE
    }
    fn branch(&self) -> (S, usize) {
        (self.share, self.learning.branch())
    }
    fn restore(&mut self, (share, mark): (S, usize)) {
        self.share = share;
        self.learning.restore(mark);
    }
}
