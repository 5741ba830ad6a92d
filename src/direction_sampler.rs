//! One interface for choosing the next direction of a path, used the same way by the path
//! tracer (guided by the photon map) and the light tracer (guided by the importance map):
//! `prepare` at a scattering point, then `sample` and `pdf` as often as needed (the pdf is
//! also what next-event estimation's MIS weight needs).
//!
//! Three samplers implement it: [`BsdfSampler`] (the BSDF's own sampling),
//! [`crate::grid_sampler::GridSampler`] (Jensen 1995) and
//! [`crate::footprint_sampler::FootprintSampler`] (Hey & Purgathofer 2001). The guided ones
//! guide only at diffuse and soft glossy surfaces and only where at least `k_p` particles
//! with a positive contribution are found; elsewhere they sample the BSDF and report its pdf
//! (paper §3, METHOD.md step 1). Where they guide, the returned direction comes from the BSDF
//! with probability `p_BSDF` and from the particles otherwise, and the pdf is the mixture
//! `p_BSDF · p_bsdf(ω) + (1 - p_BSDF) · p_guide(ω)` per steradian.

use crate::Rgb;
use crate::bsdf::{Bsdf, Lobes, TransportMode};
use crate::math::{Frame, luminance};
use crate::particle_map::{Neighbor, ParticleMap};
use crate::rng::Rng;
use glam::{Vec2, Vec3};

/// A scattering point as the samplers see it.
#[derive(Clone, Copy, Debug)]
pub struct ScatterPoint<'a> {
    pub p: Vec3,
    pub bsdf: &'a Bsdf,
    /// Unit direction back along the path (toward the camera in radiance mode, toward the
    /// light in importance mode).
    pub wo: Vec3,
    pub mode: TransportMode,
    /// The path's throughput colour: reduces a particle's RGB contribution to one number, so
    /// that per-channel `W_p` steers paths by colour.
    pub throughput: Rgb,
}

impl ScatterPoint<'_> {
    /// The geometric normal on the side `wo` leaves from.
    #[inline]
    pub fn side_normal(&self) -> Vec3 {
        if self.bsdf.ng.dot(self.wo) >= 0.0 {
            self.bsdf.ng
        } else {
            -self.bsdf.ng
        }
    }

    /// `c_p = luminance(throughput · weight_p · f(wo, Ψ_p))` (paper eq. 1 and 2).
    #[inline]
    pub fn contribution(&self, dir: Vec3, weight: Rgb) -> f32 {
        let f = self.bsdf.eval(self.wo, dir, self.mode);
        luminance(self.throughput * weight * f)
    }
}

/// A sampled direction.
#[derive(Clone, Copy, Debug)]
pub struct GuideSample {
    /// World direction, unit.
    pub wi: Vec3,
    /// Density per steradian of the whole mixture (the delta lobe's probability for delta
    /// BSDF samples).
    pub pdf_w: f32,
    /// `f · |wi · n_s| / pdf_w`.
    pub weight: Rgb,
    pub delta: bool,
}

/// How the footprint radius follows the directional density (METHOD.md, "Eq. 7 is
/// dimensionally odd").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RadiusRule {
    /// The cap's solid angle is `k_r / δ` with `δ = g / (9 ω)` particles per steradian: the
    /// cap covers about `k_r` particles' share of the local density.
    SolidAngle,
    /// Eq. 7 as printed: radius `r = k_r / δ` with `δ = g / ω` (eq. 5).
    Literal,
}

impl RadiusRule {
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "solid-angle" => Some(RadiusRule::SolidAngle),
            "literal" => Some(RadiusRule::Literal),
            _ => None,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            RadiusRule::SolidAngle => "solid-angle",
            RadiusRule::Literal => "literal",
        }
    }
}

/// Parameters of the guided samplers (paper §3 defaults).
#[derive(Clone, Debug)]
pub struct GuideParams {
    /// `k_p`: particles per query.
    pub k_p: usize,
    /// Side of the footprint density grid (`k_g = side²`, paper: 32 x 32).
    pub k_g_side: usize,
    /// `k_r`: footprint radius scale.
    pub k_r: f32,
    /// Probability of sampling the BSDF where guiding.
    pub p_bsdf: f32,
    pub radius_rule: RadiusRule,
    /// Side of the classic sampler's grid per hemisphere (Jensen 1995).
    pub grid_side: usize,
    /// Particles whose `|cos θ_p|` is below this are left out, identically in sampling and
    /// evaluation (a cap confined to the hemisphere would have no room).
    pub grazing_cos_min: f32,
}

impl Default for GuideParams {
    fn default() -> Self {
        GuideParams {
            k_p: 50,
            k_g_side: 32,
            k_r: 6.0,
            p_bsdf: 0.3,
            radius_rule: RadiusRule::SolidAngle,
            grid_side: 8,
            grazing_cos_min: 1e-3,
        }
    }
}

impl GuideParams {
    /// Checks the parameters; the error names the field.
    pub fn validate(&self) -> Result<(), String> {
        if self.k_p == 0 || self.k_p > 10_000 {
            return Err(format!("k_p must be in 1..=10000, got {}", self.k_p));
        }
        if self.k_g_side < 3 || self.k_g_side > 1024 {
            return Err(format!(
                "k_g must be a side length in 3..=1024, got {}",
                self.k_g_side
            ));
        }
        if !(self.k_r.is_finite() && self.k_r > 0.0) {
            return Err(format!("k_r must be positive, got {}", self.k_r));
        }
        if !(self.p_bsdf > 0.0 && self.p_bsdf <= 1.0) {
            return Err(format!(
                "p_bsdf must be in (0, 1] (0 would leave directions the particles miss unsampled), got {}",
                self.p_bsdf
            ));
        }
        if self.grid_side == 0 || self.grid_side > 1024 {
            return Err(format!(
                "grid must be a side length in 1..=1024, got {}",
                self.grid_side
            ));
        }
        if !(self.grazing_cos_min > 0.0 && self.grazing_cos_min < 0.5) {
            return Err(format!(
                "grazing_cos_min must be in (0, 0.5), got {}",
                self.grazing_cos_min
            ));
        }
        Ok(())
    }
}

/// Per-thread state of a prepared sampler: reused from vertex to vertex, so a scattering
/// event allocates nothing once the buffers have grown.
#[derive(Debug, Default)]
pub struct GuideState {
    /// True when this vertex is guided; false: BSDF sampling only.
    pub guided: bool,
    /// Local frame around the side normal.
    pub frame: Option<Frame>,
    pub neighbors: Vec<Neighbor>,
    /// Particle directions (local) and contributions that entered the distribution.
    pub particles: Vec<(Vec3, f32)>,
    pub footprint: crate::footprint_sampler::FootprintDistribution,
    pub grid: crate::grid_sampler::GridDistribution,
    /// Counters for the run summary.
    pub prepared: u64,
    pub fallbacks: u64,
}

/// The direction-sampler interface.
pub trait DirectionSampler: Sync {
    fn name(&self) -> &'static str;
    /// Prepares `state` at a scattering point.
    fn prepare(&self, at: &ScatterPoint, state: &mut GuideState);
    /// Draws a direction; `None` when no direction could be drawn (the BSDF's own sampling
    /// failed). A direction the BSDF does not scatter into comes back with zero weight.
    fn sample(&self, at: &ScatterPoint, state: &GuideState, rng: &mut Rng) -> Option<GuideSample>;
    /// Density per steradian with which `sample` returns `wi` (0 for delta BSDFs).
    fn pdf(&self, at: &ScatterPoint, state: &GuideState, wi: Vec3) -> f32;
}

/// BSDF sampling alone.
pub struct BsdfSampler;

impl DirectionSampler for BsdfSampler {
    fn name(&self) -> &'static str {
        "bsdf"
    }

    fn prepare(&self, _at: &ScatterPoint, state: &mut GuideState) {
        state.guided = false;
    }

    fn sample(&self, at: &ScatterPoint, _state: &GuideState, rng: &mut Rng) -> Option<GuideSample> {
        let s = at
            .bsdf
            .sample(at.wo, rng.uniform(), rng.uniform2(), at.mode)?;
        Some(GuideSample {
            wi: s.wi,
            pdf_w: s.pdf_w,
            weight: s.weight,
            delta: s.delta,
        })
    }

    fn pdf(&self, at: &ScatterPoint, _state: &GuideState, wi: Vec3) -> f32 {
        at.bsdf.pdf(at.wo, wi)
    }
}

/// True when particles guide at surfaces with these lobes: diffuse, and glossy up to the
/// soft-glossy exponent (the rough conductor and rough plastic by the Blinn exponent of
/// about the same width); never mirrors, glass, smooth conductors or plastics, thin glass or
/// strongly glossy lobes.
pub fn guides_at(lobes: &Lobes, soft_glossy_max: f32) -> bool {
    match lobes {
        Lobes::Diffuse { .. } => true,
        Lobes::Glossy { exponent, .. } => *exponent <= soft_glossy_max,
        // The microfacet kinds by the Blinn exponent of about the same width, 2/α² - 2.
        Lobes::RoughConductor { distr, .. } | Lobes::RoughPlastic { distr, .. } => {
            distr.blinn_exponent() <= soft_glossy_max
        }
        // Smooth plastic has a delta coat over its diffuse base.
        Lobes::Mirror { .. }
        | Lobes::Glass { .. }
        | Lobes::Conductor { .. }
        | Lobes::Plastic { .. }
        | Lobes::ThinGlass { .. } => false,
    }
}

/// Shared part of the guided samplers' `prepare`: decides whether to guide, queries the map
/// and fills `state.particles` with the local directions and contributions of the particles
/// that count (grazing ones left out). Returns false (BSDF fallback) when fewer than `k_p`
/// remain.
pub fn gather_particles(
    map: &ParticleMap,
    params: &GuideParams,
    soft_glossy_max: f32,
    max_dist: f32,
    at: &ScatterPoint,
    state: &mut GuideState,
) -> bool {
    state.prepared += 1;
    state.guided = false;
    state.particles.clear();
    if !guides_at(&at.bsdf.lobes, soft_glossy_max) {
        return false;
    }
    let n = at.side_normal();
    // Where the map cannot hold k particles facing this way (the dark side of a wall), skip
    // the search: the query would report fewer than k.
    if !map.may_hold(at.p, n, params.k_p, max_dist) {
        state.fallbacks += 1;
        return false;
    }
    let mut neighbors = std::mem::take(&mut state.neighbors);
    let found = map.query(
        at.p,
        n,
        params.k_p,
        max_dist,
        |nb| at.contribution(nb.dir, nb.weight),
        &mut neighbors,
    );
    state.neighbors = neighbors;
    if found < params.k_p {
        state.fallbacks += 1;
        return false;
    }
    let frame = Frame::from_z(n);
    for nb in &state.neighbors {
        let d = frame.to_local(nb.dir);
        if d.z.abs() >= params.grazing_cos_min {
            state.particles.push((d, nb.contribution));
        }
    }
    if state.particles.is_empty() {
        state.fallbacks += 1;
        return false;
    }
    state.frame = Some(frame);
    state.guided = true;
    true
}

/// Shared part of the guided samplers' `sample`: the BSDF with probability `p_bsdf`, the
/// guide's own distribution otherwise (`guide_sample` returns a local direction), and the
/// mixture pdf and weight.
pub fn mixture_sample(
    sampler: &dyn DirectionSampler,
    p_bsdf: f32,
    at: &ScatterPoint,
    state: &GuideState,
    rng: &mut Rng,
    guide_sample: impl FnOnce(&mut Rng) -> Option<Vec3>,
) -> Option<GuideSample> {
    if !state.guided || at.bsdf.is_delta() {
        return BsdfSampler.sample(at, state, rng);
    }
    let wi = if rng.uniform() < p_bsdf {
        at.bsdf
            .sample(at.wo, rng.uniform(), rng.uniform2(), at.mode)?
            .wi
    } else {
        let local = guide_sample(rng)?;
        state.frame?.to_world(local).normalize()
    };
    let pdf_w = sampler.pdf(at, state, wi);
    if !(pdf_w > 0.0 && pdf_w.is_finite()) {
        return None;
    }
    // A direction the BSDF does not scatter into (a footprint across the horizon of an opaque
    // surface) is still a draw: it comes back with zero weight, so that what `sample` draws is
    // exactly the density `pdf` describes.
    let f = at.bsdf.eval(at.wo, wi, at.mode);
    let weight = f * (wi.dot(at.bsdf.frame.z).abs() / pdf_w);
    let weight = if crate::math::is_valid_rgb(weight) {
        weight
    } else {
        Rgb::ZERO
    };
    Some(GuideSample {
        wi,
        pdf_w,
        weight,
        delta: false,
    })
}

/// What differs between the particle-guided samplers: how the gathered particles (local
/// directions and contributions, grazing ones removed) become a distribution of local
/// directions, stored in the [`GuideState`].
pub trait ParticleDistribution: Sync {
    const NAME: &'static str;
    fn build(&self, particles: &[(Vec3, f32)], params: &GuideParams, state: &mut GuideState);
    fn sample(&self, state: &GuideState, u_select: f32, u: Vec2) -> Option<Vec3>;
    fn pdf(&self, state: &GuideState, local: Vec3) -> f32;
}

/// A particle-guided sampler: queries the map, builds a [`ParticleDistribution`] and mixes it
/// with the BSDF (see the module documentation). The footprint and grid samplers are this
/// type with their distributions.
pub struct ParticleGuide<'m, D> {
    pub map: &'m ParticleMap,
    pub params: GuideParams,
    pub max_dist: f32,
    pub soft_glossy_max: f32,
    pub distribution: D,
}

impl<D: ParticleDistribution> ParticleGuide<'_, D> {
    fn build(&self, state: &mut GuideState) {
        let particles = std::mem::take(&mut state.particles);
        self.distribution.build(&particles, &self.params, state);
        state.particles = particles;
    }

    /// Builds the distribution from explicit local particles (tests and benchmarks that
    /// bypass the map); the same filtering as a map query applies (positive contribution,
    /// not grazing).
    pub fn prepare_with(&self, frame: Frame, particles: &[(Vec3, f32)], state: &mut GuideState) {
        state.particles.clear();
        let min = self.params.grazing_cos_min;
        state.particles.extend(
            particles
                .iter()
                .filter(|(d, c)| *c > 0.0 && d.z.abs() >= min),
        );
        state.guided = !state.particles.is_empty();
        state.frame = Some(frame);
        if state.guided {
            self.build(state);
        }
    }
}

impl<D: ParticleDistribution> DirectionSampler for ParticleGuide<'_, D> {
    fn name(&self) -> &'static str {
        D::NAME
    }

    fn prepare(&self, at: &ScatterPoint, state: &mut GuideState) {
        if gather_particles(
            self.map,
            &self.params,
            self.soft_glossy_max,
            self.max_dist,
            at,
            state,
        ) {
            self.build(state);
        }
    }

    fn sample(&self, at: &ScatterPoint, state: &GuideState, rng: &mut Rng) -> Option<GuideSample> {
        mixture_sample(self, self.params.p_bsdf, at, state, rng, |rng| {
            self.distribution
                .sample(state, rng.uniform(), rng.uniform2())
        })
    }

    fn pdf(&self, at: &ScatterPoint, state: &GuideState, wi: Vec3) -> f32 {
        let p_bsdf = at.bsdf.pdf(at.wo, wi);
        if !state.guided || at.bsdf.is_delta() {
            return p_bsdf;
        }
        let Some(frame) = state.frame else {
            return p_bsdf;
        };
        let p = self.params.p_bsdf;
        p * p_bsdf + (1.0 - p) * self.distribution.pdf(state, frame.to_local(wi))
    }
}
