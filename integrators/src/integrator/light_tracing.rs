//! Light tracing (Veach 1997, §10.3; Dutré et al. 1993), guided or not: paths start on the
//! lights (chosen in proportion to power), every scattering direction comes from the
//! direction sampler (BSDF, grid or footprint over the importance map), and every
//! non-specular vertex, the light vertex included, is connected to the camera (a point sampled
//! on its lens, with one more pair of numbers per connection, where it has one) and splatted
//! onto the film. At area lights the emission direction is guided too
//! ([`crate::emit`]).
//!
//! Normalisation. With `N = n P` light paths (`n` passes of one path per each of the `P`
//! pixels), a connection from vertex `x` with throughput `β` (flux per unit area and solid
//! angle, divided by all pdfs so far) adds to pixel `j`
//!
//! `β · f(x, ω_o → ω_c) · |ω_c · n_s| · W_e(ω_c) · cos θ_c / d² · P / N`
//!
//! where `W_e · P` is the box-filter importance of one of the `P` pixels (see
//! `footprint::scene::camera`). The splat is that value times `n`, so that every layer is
//! averaged over passes like the camera paths' values.
//!
//! A light path can also feed a second estimate with other weights ([`LightShare`]): the
//! combined image's share, weighted against path tracing by [`crate::mis::LightMis`].
//! Paths from the environment stay out of it: the path tracer alone makes them there (its
//! own two-strategy weights sum to one for them), so that the weights remain a partition
//! of unity without an area density at infinity. Paths from the directional light are in it,
//! weighted against next-event estimation (the only other strategy that makes them).
//!
//! The first vertex of a path from a light at infinity lies on the scene's bounding disk,
//! which no camera sees: it is not connected.
//!
//! Path length: `max_depth` counts segments, the camera connection included: a connection
//! from the `n`-th hit closes a path of `n + 1` segments.

use super::{Context, Integrator, Paths};
use crate::emit::{first_ray, sample_light};
use crate::learning::Learning;
use crate::mis::{LightMis, PilotMis, Strategies};
use crate::walk::{Arrival, Start, Vertex, Visitor, walk};
use footprint::Rgb;
use footprint::bsdf::TransportMode;
use footprint::film::SplatList;
use footprint::guide::sampler::{DirectionSample, SamplerState};
use footprint::rng::Rng;
use footprint::scene::camera::{Camera, CameraConnection};
use footprint::scene::features::Features;
use footprint::scene::light::Light;
use footprint::scene::{Scene, Toward};
use glam::{Vec2, Vec3};
use std::marker::PhantomData;

/// Light tracing, registered as `lt`.
pub struct LightTracing;

impl Integrator for LightTracing {
    fn name(&self) -> &'static str {
        "lt"
    }
    fn about(&self) -> &'static str {
        "Light tracing: paths from the lights connected to the camera, guided by the importance map"
    }
    fn layers(&self) -> &'static [&'static str] {
        &["lt"]
    }
    fn paths(&self) -> Paths {
        Paths {
            camera: false,
            light: true,
        }
    }
    fn light_path<'a>(
        &self,
        ctx: &Context<'a>,
        rng: &mut Rng,
        state: &mut SamplerState<'a>,
        splats: &mut [SplatList],
    ) {
        light_path(ctx, rng, state, &mut splats[0], None, |_, _, _| ());
    }
}

/// One light path in the render's compiled loop (arguments as [`trace`]).
pub fn light_path<'a, W: LightShare>(
    ctx: &Context<'a>,
    rng: &mut Rng,
    state: &mut SamplerState<'a>,
    lt: &mut SplatList,
    share: Option<Shared<'_>>,
    weights: impl FnOnce(u32, Vec3, Option<Vec3>) -> W,
) {
    crate::specialised!(ctx.specialisation, F => trace::<F, _>(
        ctx, rng, state, lt, share, weights,
    ));
}

/// A second estimate a light path feeds, with its own weights for the same connections.
pub trait LightShare: Copy {
    /// The strategies (and so the weight) of the light point itself seen by the camera
    /// through the connection `c`.
    fn light_seen(&self, scene: &Scene, c: &CameraConnection) -> Strategies;
    fn arrive(&mut self, light: &Light, v: &Vertex);
    /// The strategies of the camera connection `c` from `v`.
    fn connection(&self, scene: &Scene, v: &Vertex, c: &CameraConnection) -> Strategies;
    fn scattered(&mut self, v: &Vertex, s: &DirectionSample);
}

impl LightShare for () {
    fn light_seen(&self, _scene: &Scene, _c: &CameraConnection) -> Strategies {
        Strategies::NONE
    }
    fn arrive(&mut self, _light: &Light, _v: &Vertex) {}
    fn connection(&self, _scene: &Scene, _v: &Vertex, _c: &CameraConnection) -> Strategies {
        Strategies::NONE
    }
    fn scattered(&mut self, _v: &Vertex, _s: &DirectionSample) {}
}

impl LightShare for LightMis<'_> {
    fn light_seen(&self, scene: &Scene, c: &CameraConnection) -> Strategies {
        LightMis::light_seen(self, scene, c.lens, c.dir_to_camera)
    }
    fn arrive(&mut self, light: &Light, v: &Vertex) {
        LightMis::arrive(self, light, v.index, -v.wo, v.hit.p, v.hit.ng);
    }
    fn connection(&self, scene: &Scene, v: &Vertex, c: &CameraConnection) -> Strategies {
        let (p, ng) = (v.hit.p, v.hit.ng);
        self.camera_connection(scene, v.index, &v.bsdf, p, ng, c.lens, c.dir_to_camera)
    }
    fn scattered(&mut self, v: &Vertex, s: &DirectionSample) {
        LightMis::scattered(self, v.index, v.hit.p, v.hit.ng, &v.bsdf, s.delta);
    }
}

/// `auto`'s pilot: the samplers' weights, and the unguided densities beside them.
impl LightShare for PilotMis<LightMis<'_>> {
    fn light_seen(&self, scene: &Scene, c: &CameraConnection) -> Strategies {
        Strategies {
            unguided: LightShare::light_seen(&self.unguided, scene, c).p,
            ..LightShare::light_seen(&self.main, scene, c)
        }
    }
    fn arrive(&mut self, light: &Light, v: &Vertex) {
        LightShare::arrive(&mut self.main, light, v);
        LightShare::arrive(&mut self.unguided, light, v);
    }
    fn connection(&self, scene: &Scene, v: &Vertex, c: &CameraConnection) -> Strategies {
        Strategies {
            unguided: LightShare::connection(&self.unguided, scene, v, c).p,
            ..LightShare::connection(&self.main, scene, v, c)
        }
    }
    fn scattered(&mut self, v: &Vertex, s: &DirectionSample) {
        LightShare::scattered(&mut self.main, v, s);
        LightShare::scattered(&mut self.unguided, v, s);
    }
}

/// The combined image's splats a light path adds to: its share, weighted, and the
/// second-moment layers ([`crate::moments`]) when they are asked for.
pub struct Shared<'f> {
    pub combined: &'f mut SplatList,
    pub moments: Option<&'f mut [SplatList]>,
    /// The horizon of the second-moment layers (`crate::moments::Horizon`).
    pub horizon: crate::moments::Horizon,
}

impl Shared<'_> {
    /// Splats a connection of unweighted value `v` at `raster`, made by `st` on a light path
    /// of roulette survival `survival`.
    #[inline]
    fn splat(&mut self, cam: &Camera, raster: Vec2, v: Rgb, st: &Strategies, survival: f32) {
        let (f, w, h) = (&cam.filter, cam.width, cam.height);
        self.combined.splat(f, w, h, raster, v * st.weight());
        if let Some(m) = self.moments.as_deref_mut() {
            let t = crate::moments::terms(v, st, v, false, survival, &self.horizon);
            for (list, t) in m.iter_mut().zip(t) {
                list.splat_second_moment(f, w, h, raster, t);
            }
        }
    }
}

/// Traces one light path, in the loop compiled for the effects `F`, and splats its camera
/// connections into `lt`, and into `share` weighted by the running weights `weights(light,
/// point, normal)` makes at the light point.
pub fn trace<'a, F: Features, W: LightShare>(
    ctx: &Context<'a>,
    rng: &mut Rng,
    state: &mut SamplerState<'a>,
    lt: &mut SplatList,
    share: Option<Shared<'_>>,
    weights: impl FnOnce(u32, Vec3, Option<Vec3>) -> W,
) {
    let scene = ctx.scene;
    let cam = &scene.camera;
    let (w, h) = (cam.width, cam.height);
    let Some(start) = sample_light(scene, rng) else {
        return;
    };
    let (li, pmf, light) = (start.index, start.pmf, start.light);
    let em = &start.em;
    // The combined image's light paths never split, environment paths included (they feed
    // only the `lt` layer there).
    let combined = share.is_some();
    let mut share = share.filter(|_| !light.is_environment());
    let weights = weights(li as u32, em.p, em.n);

    // ---- The light vertex seen directly by the camera (not a bounding disk of a light at
    // infinity), through a lens point drawn after the light's numbers ----
    let u_lens = if light.is_infinite() {
        Vec2::ZERO
    } else {
        cam.draw_lens_sample(rng)
    };
    if let Some(conn) = cam.connect(em.p, u_lens).filter(|_| !light.is_infinite()) {
        let cos_l = em.n.map(|n| n.dot(conn.dir_to_camera)).unwrap_or(1.0);
        if cos_l > 0.0 {
            let le = light.emitted(conn.dir_to_camera);
            // One segment, and one more per thin sheet passed through.
            let sheets = ctx.max_depth.saturating_sub(1);
            let (t, _) = match em.n {
                Some(n) => scene.transmittance(Toward::Camera, em.p, n, conn.lens, None, sheets),
                None => {
                    scene.transmittance(Toward::Camera, conn.lens, cam.frame.z, em.p, None, sheets)
                }
            };
            if le.max_element() > 0.0 && t.max_element() > 0.0 {
                let v = le * t * (cos_l * conn.we_geom / (em.pdf_pos * pmf));
                lt.splat(&cam.filter, w, h, conn.raster, v);
                if let Some(s) = share.as_mut() {
                    let st = weights.light_seen(scene, &conn);
                    s.splat(cam, conn.raster, v, &st, 1.0);
                }
            }
        }
    }
    if ctx.max_depth < 2 {
        return;
    }

    // ---- Emission direction, guided at area lights ----
    let Some((origin, dir, beta)) = first_ray::<F>(&start, &ctx.light_sampler, state, rng) else {
        return;
    };
    let start = Start {
        origin,
        dir,
        beta,
        beta0: beta,
        mode: TransportMode::Importance,
        // A connection from the n-th hit closes n + 1 segments.
        max_vertex_depth: ctx.max_depth - 1,
        max_segments: ctx.max_depth,
        rr_depth: ctx.rr_depth,
    };
    let mut v = LightVisitor::<W, F> {
        scene,
        max_depth: ctx.max_depth,
        light,
        lt,
        share,
        combined,
        weights,
        learning: Learning::new(ctx.light_sampler.selection.is_some()),
        features: PhantomData,
    };
    walk(scene, &start, &ctx.light_sampler, state, rng, &mut v);
    v.learning.finish(&mut state.selection_records);
}

struct LightVisitor<'s, 'f, W, F> {
    scene: &'s Scene,
    /// Most segments of a path (a connection through thin sheets counts each).
    max_depth: u32,
    light: &'s Light,
    lt: &'f mut SplatList,
    /// The second estimate's splats and weights.
    share: Option<Shared<'f>>,
    /// The path belongs to the combined image (it does not split).
    combined: bool,
    weights: W,
    /// The guided vertices followed for the learned `p_BSDF` ([`crate::learning`]).
    learning: Learning,
    features: PhantomData<F>,
}

impl<W: LightShare, F: Features> Visitor for LightVisitor<'_, '_, W, F> {
    type F = F;

    // ---- Connect to the camera ----
    fn reached(&mut self, v: &Vertex, _from: &Arrival, rng: &mut Rng) {
        let scene = self.scene;
        if self.share.is_some() {
            self.weights.arrive(self.light, v);
        }
        if v.bsdf.is_delta_with::<F>() {
            return;
        }
        let cam = &scene.camera;
        let Some(conn) = cam.connect(v.hit.p, cam.draw_lens_sample(rng)) else {
            return;
        };
        let wi = conn.dir_to_camera;
        let f = v.bsdf.eval_with::<F>(v.wo, wi, TransportMode::Importance);
        if f.max_element() <= 0.0 {
            return;
        }
        // The connection closes depth + 1 segments, and one more per thin sheet.
        let sheets = self.max_depth.saturating_sub(v.depth + 1);
        let (t, _) =
            scene.transmittance(Toward::Camera, v.hit.p, v.hit.ng, conn.lens, None, sheets);
        if t.max_element() <= 0.0 {
            return;
        }
        let value = v.beta * f * t * (wi.dot(v.hit.ns).abs() * conn.we_geom);
        let (w, h) = (cam.width, cam.height);
        self.lt.splat(&cam.filter, w, h, conn.raster, value);
        match self.share.as_mut() {
            Some(s) => {
                let st = self.weights.connection(scene, v, &conn);
                s.splat(cam, conn.raster, value, &st, v.survival);
                // The combined image is the estimate its light paths serve.
                self.learning.credit(value * st.weight());
            }
            None => self.learning.credit(value),
        }
    }

    fn scattered(&mut self, v: &Vertex, s: &DirectionSample) {
        if self.share.is_some() {
            self.weights.scattered(v, s);
        }
        self.learning.scattered(s);
    }

    // ---- Guided splitting: each branch starts from the same running weights ----
    type Branch = (W, usize);
    /// Not in the combined image (as camera paths, `path_tracing`).
    fn splits(&self) -> bool {
        !self.combined
    }
    fn branch(&self) -> (W, usize) {
        (self.weights, self.learning.branch())
    }
    fn restore(&mut self, (weights, mark): (W, usize)) {
        self.weights = weights;
        self.learning.restore(mark);
    }
}
