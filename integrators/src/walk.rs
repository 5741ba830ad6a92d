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
//! **Thin dielectric sheets** (Mitsuba `thindielectric`) pass light in a straight line.
//! Sampling at a sheet chooses reflection (a mirror vertex like any other) or straight
//! transmission; a transmitted path goes on without the visitors seeing the sheet: for them
//! the path arrives from the vertex before it, with that vertex's direction density, as a
//! connection through the sheet sees it (`Scene::transmittance` multiplies by what
//! sampling at the sheet gives in expectation). The sheet still counts as a segment, in the
//! walk as in a connection, so that every strategy makes the same paths.
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
//! `rr_depth` ([`footprint::settings::DEFAULT_RR_DEPTH`] by default) or more, the path continues with probability
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
//! [`SamplerState::region_density`]; where the lobe is no narrower than
//! [`GUIDED_RR_MAX_EXPONENT`]), and continues with probability
//! `clamp(C_v / C_ref, GUIDED_RR_MIN_SURVIVAL, 1)` at every depth (not only from
//! `rr_depth`), `C_ref` the first such value of the path (adjoint-driven Russian roulette
//! without splitting; docs/method.md). β is the real throughput here: the estimate already
//! says where a guided direction leads.
//!
//! **Guided splitting** (`GuideParams::guided_split`, the other half of adjoint-driven
//! Russian roulette): where `C_v / C_ref = r > 1` the walk scatters `r` times in expectation
//! (rounded at random, at most `guided_split`), each branch with `1 / n` of the throughput
//! and its own direction, and runs each branch's rest of the path. Next-event estimation and
//! what the visitor found at the vertex count once; the visitor's running MIS quantities are
//! saved before the first branch and restored before each further one
//! ([`Visitor::branch`]); the first branch keeps the path's random stream, the others draw
//! independent ones. Unbiased for any count (each count's mean of branches is).

use footprint::Rgb;
use footprint::bsdf::{Bsdf, TransportMode};
use footprint::guide::sampler::{
    DirectionSample, GuidedSampler, SamplerState, ScatterPoint, guides_at_bsdf,
};
use footprint::math::luminance;
use footprint::rng::Rng;
use footprint::scene::features::Features;
#[allow(unused_imports)] // the doc links
use footprint::scene::features::Specialisation;
use footprint::scene::geometry::{SurfaceHit, spawn_origin};
use footprint::scene::{MAX_CUTOUT_CROSSINGS, Scene};
use glam::Vec3;

/// The rule: survival probability for throughput `beta` of a walk that started at `beta0`.
#[inline]
pub fn survival_probability(beta: Rgb, beta0_max: f32) -> f32 {
    (beta.max_element() / beta0_max).clamp(0.05, 1.0)
}

/// The least survival probability of guided Russian roulette. The rule acts at every guided
/// vertex, so it need not cut hard: at 0.05 (the throughput rule's floor) survivors carry
/// weights up to 20x and desk and door measure worse than at 0.25, 0.4 and 0.6; 0.8 costs
/// more time than it saves (docs/measurements/sweeps.md, "Guided Russian roulette and
/// splitting").
pub const GUIDED_RR_MIN_SURVIVAL: f32 = 0.6;

/// The guided rule: survival probability of a path expected to gather `c_v` from here on,
/// whose first estimated vertex expected `c_ref`. A path is kept for sure while `c_v` is at
/// least `c_ref` (other shares of `c_ref`, 0.3 to 3, measure worse on Veach Ajar:
/// docs/measurements/sweeps.md, "Guided Russian roulette and splitting").
#[inline]
pub fn guided_survival_probability(c_v: f32, c_ref: f32) -> f32 {
    (c_v / c_ref).clamp(GUIDED_RR_MIN_SURVIVAL, 1.0)
}

/// The narrowest lobe, as a Blinn exponent (`2/α² - 2` for the microfacet kinds, as
/// [`footprint::guide::sampler::guides_at`] reads them), at which guided Russian roulette and
/// splitting read a region's estimate. `lum(β · albedo · E) / π` is what a Lambertian
/// surface of that albedo reflects under the region's irradiance `E`: it tells what a path
/// gathers where the lobe averages the incident light over much of the hemisphere. A
/// narrower lobe reflects what lies around its mirror direction (the light's reflection in a
/// glossy floor, or a dark wall), which the irradiance does not tell: roughglass's floor
/// (GGX `α` 0.15, Blinn 87), steered by it, cost 1.31x BSDF sampling's error at 16 s against
/// 1.08x with the throughput rule there, while Veach Ajar's teapots (87) are even either
/// way (docs/measurements/guided-vs-bsdf.md, "Guided roulette at glossy lobes"). Such
/// vertices keep the throughput rule from `rr_depth`; their guide is unchanged.
pub const GUIDED_RR_MAX_EXPONENT: f32 = 50.0;

/// Whether guided Russian roulette and splitting read a region's estimate at a vertex of
/// `bsdf`: every lobe diffuse or at most [`GUIDED_RR_MAX_EXPONENT`] narrow.
#[inline]
fn estimates_by_irradiance(bsdf: &Bsdf) -> bool {
    guides_at_bsdf(bsdf, GUIDED_RR_MAX_EXPONENT)
}

/// A surface vertex of a walk.
pub struct Vertex {
    pub hit: SurfaceHit,
    pub bsdf: Bsdf,
    /// Unit direction back along the path.
    pub wo: Vec3,
    /// Segments from the walk's source to this vertex.
    pub depth: u32,
    /// Vertices from the walk's source to this one, this one included, not counting thin
    /// sheets passed straight through: the vertex's index in the path the MIS weights see
    /// (`depth` without sheets).
    pub index: u32,
    /// Throughput arriving at this vertex.
    pub beta: Rgb,
    /// The product of the Russian roulette survival probabilities on the way here (what
    /// `beta` was divided by); 1 before any roulette.
    pub survival: f32,
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
    /// A vertex was reached; `rng` stands at the vertex's dimensions (a camera connection
    /// draws its lens point there).
    fn reached(&mut self, _v: &Vertex, _from: &Arrival, _rng: &mut Rng) {}
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

    /// The part of the visitor's state that belongs to one path (its running MIS
    /// quantities): saved where the walk splits, and restored before each further branch.
    /// What the visitor adds up (radiance, splats) is shared by the branches.
    type Branch: Copy;
    /// Whether the walk may split here (guided splitting; off unless a visitor says so).
    fn splits(&self) -> bool {
        false
    }
    fn branch(&self) -> Self::Branch;
    fn restore(&mut self, b: Self::Branch);
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
    /// Most segments of the paths the walk's estimates count, a connection's included
    /// (`max_depth`). A guide's particles all arrived by `min_depth` segments or more, so
    /// from a vertex of depth `d` they lead only to paths of `d + min_depth` segments or
    /// more: where that is over `max_segments` (a camera path's last scattering vertex,
    /// which can only hit a light), the vertex samples its BSDF alone.
    pub max_segments: u32,
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
    let path = PathState {
        origin: start.origin,
        dir: start.dir,
        beta: start.beta,
        beta_rr: start.beta,
        from: Arrival {
            prev_p: start.origin,
            pdf_w: 0.0,
            delta: true,
        },
        expected_ref: 0.0,
        survival: 1.0,
        depth: 1,
        index: 1,
    };
    walk_from(scene, start, sampler, state, rng, visitor, path);
}

/// Where a walk (or one branch of a split walk) stands before its next segment.
#[derive(Clone, Copy)]
struct PathState {
    origin: Vec3,
    dir: Vec3,
    beta: Rgb,
    /// The throughput Russian roulette reads: BSDF sampling's weights, not the guide's.
    beta_rr: Rgb,
    from: Arrival,
    /// Guided Russian roulette: what the first estimated vertex expected the path to gather.
    expected_ref: f32,
    /// The product of the roulette's survival probabilities so far ([`Vertex::survival`]).
    survival: f32,
    /// Depth of the vertex the next segment reaches, and its index ([`Vertex::index`]).
    depth: u32,
    index: u32,
}

/// Random streams of the branches of a split after the first (which keeps the path's own).
const DOMAIN_SPLIT: u64 = 0x5b117;

/// The walk's loop from `p`; a split runs each branch's rest in a call of its own.
fn walk_from<'a, V: Visitor>(
    scene: &Scene,
    start: &Start,
    sampler: &GuidedSampler<'a>,
    state: &mut SamplerState<'a>,
    rng: &mut Rng,
    visitor: &mut V,
    mut p: PathState,
) {
    let beta0_max = start.beta0.max_element().max(f32::MIN_POSITIVE);
    let guided_rr = sampler.params.guided_rr;
    let split_max = sampler.params.guided_split.max(1);
    // The deepest vertex whose guide can lead to a path the walk counts (`Start::max_segments`).
    let guide_depth = start
        .max_segments
        .saturating_sub(u32::from(sampler.params.min_depth));
    let prepare = |at: &ScatterPoint, state: &mut SamplerState<'a>, depth: u32| {
        if depth <= guide_depth {
            sampler.prepare(at, state);
        } else {
            sampler.prepare_unguided(state);
        }
    };
    for depth in p.depth..=start.max_vertex_depth {
        let Some(hit) = next_hit::<V::F>(scene, &mut p, rng) else {
            state.escapes += 1;
            visitor.escaped(p.dir, p.beta, depth, &p.from);
            return;
        };
        state.vertices += 1;
        let v = Vertex {
            bsdf: scene.bsdf_with::<V::F>(&hit),
            hit,
            wo: -p.dir,
            depth,
            index: p.index,
            beta: p.beta,
            survival: p.survival,
        };
        // ---- A thin dielectric sheet: passed straight through, or a mirror vertex ----
        let mut drawn = None;
        if V::F::SPECULAR && scene.effects.thin_glass && v.bsdf.is_thin() {
            if depth == start.max_vertex_depth {
                return;
            }
            rng.start_vertex(depth);
            let (u_lobe, u) = v.bsdf.draw_numbers(rng);
            let s = v.bsdf.sample_with::<V::F>(v.wo, u_lobe, u, start.mode);
            let Some(s) = s else { return };
            if s.wi.dot(v.hit.ng) * v.wo.dot(v.hit.ng) < 0.0 {
                // Through: the sheet is a segment of the path, but the visitors see the path
                // go on from the vertex it arrived from, as a connection through the sheet
                // sees it (`Scene::transmittance`).
                p.beta *= s.weight;
                p.beta_rr *= s.weight;
                if !p.beta.is_finite() || p.beta.max_element() <= 0.0 {
                    return;
                }
                p.origin = scene.spawn_origin(v.hit.p, v.hit.ng, s.wi);
                continue;
            }
            drawn = Some(s.into());
        }
        // ---- The next direction, prepared before the visitor's work at the vertex ----
        // (the guide's region is looked up and its row sums fetched while the visitor
        // connects to the camera; the visitor does not read the prepared state)
        let at = ScatterPoint {
            p: v.hit.p,
            bsdf: &v.bsdf,
            wo: v.wo,
            mode: start.mode,
            throughput: p.beta,
        };
        let last = depth == start.max_vertex_depth;
        if !last {
            prepare(&at, state, depth);
        }
        // The vertex's dimensions start before the visitor's work there (which may draw a
        // camera connection's lens point), then serve next-event estimation and scattering.
        rng.start_vertex(depth);
        visitor.reached(&v, &p.from, rng);
        if last {
            return;
        }
        // What continuing from here is expected to gather, where the guide cache knows and
        // the lobe is wide enough for the estimate: `lum(β · albedo · E) / π` for the
        // region's particle density `E`.
        let expected = match state.region_density() {
            Some(e) if guided_rr && estimates_by_irradiance(&v.bsdf) => {
                let c = luminance(p.beta * v.bsdf.colour() * e) * std::f32::consts::FRAC_1_PI;
                if p.expected_ref == 0.0 && c > 0.0 && c.is_finite() {
                    p.expected_ref = c;
                }
                (p.expected_ref > 0.0 && c.is_finite()).then_some(c)
            }
            _ => None,
        };
        visitor.before_scatter(&v, &at, sampler, state, rng);

        // ---- Guided splitting ----
        let branches = match expected {
            Some(c) if split_max > 1 && c > p.expected_ref && visitor.splits() => {
                split_count(c / p.expected_ref, split_max, rng.next_u64())
            }
            _ => 1,
        };
        if branches > 1 {
            let saved = visitor.branch();
            let seed = rng.next_u64();
            let share = 1.0 / branches as f32;
            for b in 0..branches {
                let mut own;
                let r = if b == 0 {
                    &mut *rng
                } else {
                    // The earlier branches' vertices prepared the sampler for theirs.
                    prepare(&at, state, depth);
                    visitor.restore(saved);
                    own = Rng::new(seed, DOMAIN_SPLIT, b as u64);
                    &mut own
                };
                let mut q = p;
                if scatter(
                    scene.offset_scale,
                    sampler,
                    state,
                    r,
                    visitor,
                    &v,
                    &at,
                    &mut q,
                    share,
                    None,
                ) {
                    q.depth = depth + 1;
                    q.index = v.index + 1;
                    walk_from(scene, start, sampler, state, r, visitor, q);
                }
            }
            return;
        }
        if !scatter(
            scene.offset_scale,
            sampler,
            state,
            rng,
            visitor,
            &v,
            &at,
            &mut p,
            1.0,
            drawn,
        ) {
            return;
        }
        p.index += 1;

        // ---- Russian roulette ----
        let q = match expected {
            Some(c) => Some(guided_survival_probability(c, p.expected_ref)),
            None => (depth >= start.rr_depth).then(|| survival_probability(p.beta_rr, beta0_max)),
        };
        if let Some(q) = q {
            if rng.uniform() >= q {
                return;
            }
            p.beta /= q;
            p.beta_rr /= q;
            p.survival *= q;
        }
    }
}

/// The surface the path's ray meets next, passing cut-outs: where a surface's opacity
/// `α` is under 1 (Mitsuba's `mask`), the path scatters there with probability `α` and
/// passes straight through otherwise, its throughput unchanged (the cut-out lets `1 - α`
/// through, the probability it is passed with). A pass is no vertex and no segment: the
/// visitors see the path arrive from the vertex before, as a connection through the
/// cut-out sees it (`Scene::transmittance` multiplies by `1 - α`), and the surface where the
/// path does scatter scatters with its whole BSDF, the `α` of Mitsuba's `α f` being the
/// probability of getting there. The choice draws independent bits, not a dimension of the
/// sequence. `None`: the ray left the scene (or crossed `MAX_CUTOUT_CROSSINGS` cut-outs).
#[inline]
fn next_hit<F: Features>(scene: &Scene, p: &mut PathState, rng: &mut Rng) -> Option<SurfaceHit> {
    let mut hit = scene.intersect_with::<F>(p.origin, p.dir, f32::INFINITY)?;
    if !scene.effects.masks {
        return Some(hit);
    }
    for _ in 0..MAX_CUTOUT_CROSSINGS {
        let opacity = scene.opacity(&hit);
        if opacity >= 1.0 || uniform_bits(rng.next_u64()) < opacity {
            return Some(hit);
        }
        p.origin = scene.spawn_origin(hit.p, hit.ng, p.dir);
        hit = scene.intersect_with::<F>(p.origin, p.dir, f32::INFINITY)?;
    }
    None
}

/// A uniform number in [0, 1) from the top 24 of 64 random bits.
#[inline]
fn uniform_bits(bits: u64) -> f32 {
    (bits >> 40) as f32 * (1.0 / 16_777_216.0)
}

/// Samples the next direction at `v` (or takes the one `drawn` there) and moves `p` along
/// it with `share` of the throughput (one branch of `1 / share`); false when the path ends
/// there.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn scatter<'a, V: Visitor>(
    offset_scale: f32,
    sampler: &GuidedSampler<'a>,
    state: &mut SamplerState<'a>,
    rng: &mut Rng,
    visitor: &mut V,
    v: &Vertex,
    at: &ScatterPoint,
    p: &mut PathState,
    share: f32,
    drawn: Option<DirectionSample>,
) -> bool {
    let Some(s) = drawn.or_else(|| sampler.sample_with::<V::F>(at, state, rng)) else {
        return false;
    };
    p.beta *= s.weight * share;
    p.beta_rr *= s.rr_weight * share;
    if !p.beta.is_finite() || p.beta.max_element() <= 0.0 {
        return false;
    }
    visitor.scattered(v, &s);
    p.from = Arrival {
        prev_p: v.hit.p,
        pdf_w: s.pdf_w,
        delta: s.delta,
    };
    p.origin = spawn_origin(v.hit.p, v.hit.ng, s.wi, offset_scale);
    p.dir = s.wi;
    true
}

/// Branches of a guided split where a path is expected to gather `ratio` (> 1) times what
/// its first estimated vertex did: `ratio` in expectation, rounded at random with the
/// uniform bits `bits` (any count keeps the estimate unbiased: each branch carries
/// `1 / count` of the throughput), at most `max`.
#[inline]
pub fn split_count(ratio: f32, max: u32, bits: u64) -> u32 {
    let r = ratio.min(max as f32);
    let whole = r.floor();
    let u = uniform_bits(bits);
    let n = whole as u32 + u32::from(u < r - whole);
    n.clamp(1, max)
}

#[cfg(test)]
mod tests {
    use super::{GUIDED_RR_MAX_EXPONENT, estimates_by_irradiance, split_count};
    use footprint::Rgb;
    use footprint::bsdf::microfacet::{Microfacet, MicrofacetDistribution};
    use footprint::bsdf::{Bsdf, Lobes};
    use glam::Vec3;

    /// The roulette's estimate is read at diffuse surfaces and at lobes as wide as Blinn
    /// exponent 50 (GGX `α` = 0.2), not at narrower ones (roughglass's floor, `α` 0.15) nor
    /// at mirrors.
    #[test]
    fn the_estimate_is_read_where_the_lobe_is_wide() {
        let at = |lobes: Lobes| estimates_by_irradiance(&Bsdf::new(lobes, Vec3::Z, Vec3::Z));
        let conductor = |alpha: f32| Lobes::RoughConductor {
            ks: Rgb::splat(0.5),
            eta: Rgb::splat(0.2),
            k: Rgb::splat(3.0),
            distr: MicrofacetDistribution::new(Microfacet::Ggx, alpha),
        };
        assert!(at(Lobes::Diffuse {
            kd: Rgb::splat(0.5)
        }));
        assert!(at(conductor(0.3)), "Blinn 20");
        assert!(at(conductor(0.2)), "Blinn 48");
        assert!(!at(conductor(0.15)), "Blinn 87");
        assert!(!at(Lobes::Mirror { r: Rgb::ONE }));
        assert!((2.0 / (0.2f32 * 0.2) - 2.0) <= GUIDED_RR_MAX_EXPONENT);
    }

    /// Over evenly spread uniform bits the branch count averages the ratio (exactly, up to
    /// the spread's step), stays within its two neighbouring integers, and keeps the cap.
    #[test]
    fn split_counts_average_the_ratio_and_keep_the_cap() {
        let n = 4096u64;
        // The uniform number (i + 0.5) / n in the 24 bits split_count reads.
        let bits = |i: u64| (((2 * i + 1) << 24) / (2 * n)) << 40;
        for ratio in [1.0f32, 1.3, 2.0, 2.75, 3.5] {
            let counts: Vec<u32> = (0..n).map(|i| split_count(ratio, 8, bits(i))).collect();
            let mean = counts.iter().sum::<u32>() as f64 / n as f64;
            assert!(
                (mean - ratio as f64).abs() < 2.0 / n as f64,
                "{ratio}: mean {mean}"
            );
            let (lo, hi) = (ratio.floor() as u32, ratio.ceil() as u32);
            assert!(counts.iter().all(|&c| c == lo || c == hi), "{ratio}");
        }
        assert!((0..n).all(|i| split_count(40.0, 4, bits(i)) == 4));
    }
}
