//! The one path loop: a random walk through the scene, shared by path tracing, light
//! tracing and both particle passes (as pbrt-v4's BDPT `RandomWalk` serves both subpaths).
//! The walk intersects, builds the BSDF, lets its [`Visitor`] act at the vertex (emission,
//! next-event estimation, a camera connection, storing a particle), asks the direction
//! sampler for the next direction, applies the Russian roulette rule and spawns the next
//! ray. What differs between the integrators lives in their visitors.
//!
//! **Depth.** A vertex's depth is the number of segments from the walk's source (camera or
//! light) to it: the first hit has depth 1. The walk visits vertices up to
//! `max_vertex_depth` and scatters only from vertices below it.
//!
//! **Specialised once per render.** The loop and its visitors are generic over a
//! [`Features`] type (the visitor's [`Visitor::F`]): the effects the scene can show. A render
//! picks the narrowest compiled loop for its scene's effect set
//! ([`Specialisation::for_effects`]) and [`specialised!`] turns that choice into the type,
//! in one match; for a fixed seed every instantiation gives the same image, bit for bit
//! (`footprint::scene::features`).
//!
//! **Russian roulette, one rule** for every walk (read with the guide's estimate at guided
//! vertices, below): after scattering at a vertex of depth
//! `rr_depth` ([`RR_START_DEPTH`] by default) or more, the path continues with probability
//! `q = clamp(max_c β_c / max_c β_0, 0.05, 1)` (β the throughput after scattering, β_0 the
//! throughput the walk started with) and its throughput is divided by `q`. β here is the
//! throughput BSDF sampling would have given the same directions ([`DirectionSample::rr_weight`]):
//! a guide lowers the weight of the directions it favours, and would otherwise get exactly
//! those paths cut more often. Any `q > 0` keeps the estimate unbiased. Camera paths
//! start at β_0 = 1; light paths and particles at their emitted weight, so the rule reads
//! the same relative to what the path carried at its start.
//!
//! **Guided Russian roulette** (`GuideParams::guided_rr`) replaces that probability where
//! the sampler guides from a cached region: the path is expected to gather
//! `C_v = lum(β · albedo · E) / π` from the vertex on (`E` the region's particle density,
//! [`SamplerState::region_density`]), and continues with probability
//! `clamp(C_v / C_ref, GUIDED_RR_MIN_SURVIVAL, 1)` at every depth (not only from
//! `rr_depth`), `C_ref` the first such value of the path (adjoint-driven Russian roulette
//! without splitting; docs/method.md). β is the real throughput here: the estimate already
//! says where a guided direction leads.

use footprint::Rgb;
use footprint::bsdf::{Bsdf, TransportMode};
use footprint::guide::sampler::{DirectionSample, GuidedSampler, SamplerState, ScatterPoint};
use footprint::math::luminance;
use footprint::rng::Rng;
use footprint::scene::Scene;
use footprint::scene::features::Features;
#[allow(unused_imports)] // the doc links
use footprint::scene::features::Specialisation;
use footprint::scene::geometry::{SurfaceHit, spawn_origin};
use glam::Vec3;

/// Russian roulette applies after scattering at vertices of this depth or deeper, unless a
/// walk says otherwise (`Start::rr_depth`, the render's `rr_depth`); guided vertices use
/// guided Russian roulette at every depth when it is on.
pub const RR_START_DEPTH: u32 = 5;

/// The rule: survival probability for throughput `beta` of a walk that started at `beta0`.
#[inline]
pub fn survival_probability(beta: Rgb, beta0_max: f32) -> f32 {
    (beta.max_element() / beta0_max).clamp(0.05, 1.0)
}

/// The least survival probability of guided Russian roulette. The rule acts at every guided
/// vertex, so it need not cut hard: 0.05 (the throughput rule's floor) left survivors with
/// weights up to 20x and was worse on desk and door than 0.25, 0.4 and 0.6; 0.8 costs more
/// time than it saves (docs/method.md).
pub const GUIDED_RR_MIN_SURVIVAL: f32 = 0.6;

/// The guided rule: survival probability of a path expected to gather `c_v` from here on,
/// whose first estimated vertex expected `c_ref`. A path is kept for sure while `c_v` is at
/// least `c_ref` (other shares of `c_ref`, 0.3 to 3, were worse on Veach Ajar:
/// docs/method.md).
#[inline]
pub fn guided_survival_probability(c_v: f32, c_ref: f32) -> f32 {
    (c_v / c_ref).clamp(GUIDED_RR_MIN_SURVIVAL, 1.0)
}

/// A surface vertex of a walk.
pub struct Vertex {
    pub hit: SurfaceHit,
    pub bsdf: Bsdf,
    /// Unit direction back along the path.
    pub wo: Vec3,
    /// Segments from the walk's source to this vertex.
    pub depth: u32,
    /// Throughput arriving at this vertex.
    pub beta: Rgb,
}

/// How the walk arrived at the current vertex (or left the scene): the previous vertex and
/// the density of the direction sampled there.
#[derive(Clone, Copy, Debug)]
pub struct Arrival {
    pub prev_p: Vec3,
    /// Density per steradian of the direction that led here (0 for the walk's first ray).
    pub pdf_w: f32,
    /// The direction came from a delta lobe, or is the walk's first ray.
    pub delta: bool,
}

/// Runs `$body` with the type `$F` bound to the [`Features`] of the compiled loop
/// `$which` (a [`Specialisation`]): the one place where a render's choice of loop becomes
/// a type.
#[macro_export]
macro_rules! specialised {
    ($which:expr, $F:ident => $body:expr) => {
        match $which {
            ::footprint::scene::features::Specialisation::LambertArea => {
                type $F = ::footprint::scene::features::LambertArea;
                $body
            }
            ::footprint::scene::features::Specialisation::Untextured => {
                type $F = ::footprint::scene::features::Untextured;
                $body
            }
            ::footprint::scene::features::Specialisation::General => {
                type $F = ::footprint::scene::features::General;
                $body
            }
        }
    };
}

/// What a walk's owner does along it. Every method has a default that does nothing.
pub trait Visitor {
    /// The effects the walk is compiled for.
    type F: Features;
    /// The ray along `dir` from `from.prev_p` left the scene; `beta` is its throughput and
    /// `depth` the segment count it would have closed.
    fn escaped(&mut self, _dir: Vec3, _beta: Rgb, _depth: u32, _from: &Arrival) {}
    /// A vertex was reached.
    fn reached(&mut self, _v: &Vertex, _from: &Arrival) {}
    /// The sampler is prepared at `v` (only at vertices the walk scatters from): next-event
    /// estimation happens here.
    fn before_scatter(
        &mut self,
        _v: &Vertex,
        _at: &ScatterPoint,
        _sampler: &GuidedSampler,
        _state: &SamplerState,
        _rng: &mut Rng,
    ) {
    }
    /// A direction was sampled at `v`.
    fn scattered(&mut self, _v: &Vertex, _s: &DirectionSample) {}
}

/// Where a walk starts and how far it goes.
#[derive(Clone, Copy, Debug)]
pub struct Start {
    /// Ray origin, already offset off any surface it lies on.
    pub origin: Vec3,
    pub dir: Vec3,
    /// Throughput of the first segment.
    pub beta: Rgb,
    /// Throughput the Russian roulette rule is relative to (see the module doc).
    pub beta0: Rgb,
    pub mode: TransportMode,
    pub max_vertex_depth: u32,
    /// Russian roulette after scattering at vertices of this depth or deeper.
    pub rr_depth: u32,
}

/// Walks from `start` until the path leaves the scene, reaches `max_vertex_depth`, fails
/// to sample a direction or is terminated by Russian roulette.
pub fn walk<'a, V: Visitor>(
    scene: &Scene,
    start: &Start,
    sampler: &GuidedSampler<'a>,
    state: &mut SamplerState<'a>,
    rng: &mut Rng,
    visitor: &mut V,
) {
    let beta0_max = start.beta0.max_element().max(f32::MIN_POSITIVE);
    let mut origin = start.origin;
    let mut dir = start.dir;
    let mut beta = start.beta;
    // The throughput Russian roulette reads: BSDF sampling's weights, not the guide's.
    let mut beta_rr = start.beta;
    let mut from = Arrival {
        prev_p: start.origin,
        pdf_w: 0.0,
        delta: true,
    };
    // Guided Russian roulette: what the first estimated vertex expected the path to gather.
    let guided_rr = sampler.params.guided_rr;
    let mut expected_ref = 0.0f32;
    for depth in 1..=start.max_vertex_depth {
        let Some(hit) = scene.intersect_with::<V::F>(origin, dir, f32::INFINITY) else {
            state.escapes += 1;
            visitor.escaped(dir, beta, depth, &from);
            return;
        };
        state.vertices += 1;
        let v = Vertex {
            bsdf: scene.bsdf_with::<V::F>(&hit),
            hit,
            wo: -dir,
            depth,
            beta,
        };
        visitor.reached(&v, &from);
        if depth == start.max_vertex_depth {
            return;
        }

        // ---- The next direction ----
        let at = ScatterPoint {
            p: v.hit.p,
            bsdf: &v.bsdf,
            wo: v.wo,
            mode: start.mode,
            throughput: beta,
        };
        sampler.prepare(&at, state);
        // What continuing from here is expected to gather, where the guide cache knows:
        // `lum(β · albedo · E) / π` for the region's particle density `E`.
        let expected = match state.region_density() {
            Some(e) if guided_rr => {
                let c = luminance(beta * v.bsdf.lobes.colour() * e) * std::f32::consts::FRAC_1_PI;
                if expected_ref == 0.0 && c > 0.0 && c.is_finite() {
                    expected_ref = c;
                }
                (expected_ref > 0.0 && c.is_finite()).then_some(c)
            }
            _ => None,
        };
        rng.start_vertex(depth);
        visitor.before_scatter(&v, &at, sampler, state, rng);
        let Some(s) = sampler.sample_with::<V::F>(&at, state, rng) else {
            return;
        };
        beta *= s.weight;
        beta_rr *= s.rr_weight;
        if !beta.is_finite() || beta.max_element() <= 0.0 {
            return;
        }
        visitor.scattered(&v, &s);
        from = Arrival {
            prev_p: v.hit.p,
            pdf_w: s.pdf_w,
            delta: s.delta,
        };

        // ---- Russian roulette ----
        let q = match expected {
            Some(c) => Some(guided_survival_probability(c, expected_ref)),
            None => (depth >= start.rr_depth).then(|| survival_probability(beta_rr, beta0_max)),
        };
        if let Some(q) = q {
            if rng.uniform() >= q {
                return;
            }
            beta /= q;
            beta_rr /= q;
        }
        origin = spawn_origin(v.hit.p, v.hit.ng, s.wi);
        dir = s.wi;
    }
}
