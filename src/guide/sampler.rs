//! The direction sampler the integrators call at every scattering vertex, the same way for
//! camera paths (guided by the photon map) and light paths (guided by the importance map):
//! `prepare` at the point, then `sample` and `pdf` as often as needed (the pdf is also what
//! next-event estimation's MIS weight needs).
//!
//! Guiding happens only at diffuse and soft glossy surfaces ([`guides_at`]) and only where a
//! distribution exists; elsewhere the sampler is the BSDF's own sampling and reports its pdf
//! (paper §3, docs/method.md step 1), counting the fallback. Where it guides, the direction
//! comes from the BSDF with probability `p_BSDF` and from the guide's distribution
//! otherwise, and the pdf is the one-sample mixture
//! `p_BSDF · p_bsdf(ω) + (1 - p_BSDF) · p_guide(ω)` per steradian.
//!
//! The distribution comes from one of two [`GuideSource`]s:
//! * **cached**: the region of the [`GuideCache`] holding the point (a tree descent, no
//!   search), with per-channel particle weights mixed by the path's colour;
//! * **per event** (the paper's method): the `k_p` nearest particles with a positive
//!   contribution `c_p = luminance(throughput · weight_p · f(wo, Ψ_p))` (eq. 1-2), gathered
//!   and turned into a distribution at this very point.

use crate::Rgb;
use crate::bsdf::{Bsdf, BsdfSample, Lobes, TransportMode};
use crate::features::{Features, General};
use crate::guide::cache::{GuideCache, Region, RegionDistribution};
use crate::guide::channel_mix::ChannelMix;
use crate::guide::distribution::{Guide, GuideDistribution, GuideParticle};
use crate::guide::grid::GridDistribution;
use crate::guide::particle_map::{Neighbor, ParticleMap};
use crate::guide::selection::SelectionLearner;
use crate::math::{Frame, is_valid_rgb, luminance};
use crate::rng::Rng;
use crate::settings::GuideParams;
use glam::Vec3;

/// Luminance coefficients (Rec. 709), the weights of [`luminance`].
pub const LUMINANCE: Rgb = Rgb::new(0.2126, 0.7152, 0.0722);

/// True when particles are stored and guide at surfaces with these lobes: diffuse, and
/// glossy up to the soft-glossy exponent (the rough conductor, rough plastic, rough
/// dielectric and principled by the Blinn exponent of about the same width); never mirrors, glass, smooth conductors or
/// plastics, thin glass or strongly glossy lobes (paper §3).
pub fn guides_at(lobes: &Lobes, soft_glossy_max: f32) -> bool {
    match lobes {
        Lobes::Diffuse { .. } => true,
        Lobes::Glossy { exponent, .. } => *exponent <= soft_glossy_max,
        // The microfacet kinds by the Blinn exponent of about the same width, 2/α² - 2.
        Lobes::RoughConductor { distr, .. } | Lobes::RoughPlastic { distr, .. } => {
            distr.blinn_exponent() <= soft_glossy_max
        }
        Lobes::RoughGlass(g) => g.distr.blinn_exponent() <= soft_glossy_max,
        // By the main lobe (reflection, metal and refraction alike; `α² = α_u α_v` when
        // anisotropic, as for the other microfacet kinds). The clearcoat's sharp GTR1 lobe (α <= 0.1) is
        // weak, `0.25 clearcoat` times a Fresnel term of 4% at normal incidence, and stays
        // reachable by BSDF sampling in the guide's mixture.
        Lobes::Principled(p) => p.distribution().blinn_exponent() <= soft_glossy_max,
        // Smooth plastic has a delta coat over its diffuse base.
        Lobes::Mirror { .. }
        | Lobes::Glass { .. }
        | Lobes::Conductor { .. }
        | Lobes::Plastic { .. }
        | Lobes::ThinGlass { .. } => false,
    }
}

/// [`guides_at`] for a BSDF at a point: both components of a blend must be guided kinds.
pub fn guides_at_bsdf(bsdf: &Bsdf, soft_glossy_max: f32) -> bool {
    guides_at(&bsdf.lobes, soft_glossy_max)
        && bsdf
            .blend
            .is_none_or(|b| guides_at(&b.lobes, soft_glossy_max))
}

/// A scattering point as the sampler sees it.
#[derive(Clone, Copy, Debug)]
pub struct ScatterPoint<'a> {
    pub p: Vec3,
    pub bsdf: &'a Bsdf,
    /// Unit direction back along the path (toward the camera in radiance mode, toward the
    /// light in importance mode).
    pub wo: Vec3,
    pub mode: TransportMode,
    /// The path's throughput colour: reduces a particle's RGB weight to one number, so that
    /// per-channel `W_p` steers paths by colour.
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

    /// The per-channel factor `a` of the cached distributions' channel mixture: luminance
    /// coefficients, throughput and the lobes' colour ([`ChannelMix`]).
    #[inline]
    pub fn channel_factor(&self) -> Rgb {
        LUMINANCE * self.throughput * self.bsdf.colour()
    }
}

/// A sampled direction.
#[derive(Clone, Copy, Debug)]
pub struct DirectionSample {
    /// World direction, unit.
    pub wi: Vec3,
    /// Density per steradian of the whole mixture (the delta lobe's probability for delta
    /// BSDF samples).
    pub pdf_w: f32,
    /// `f · |wi · n_s| / pdf_w`.
    pub weight: Rgb,
    /// The weight BSDF sampling alone would have given this direction, `f · |wi · n_s| /
    /// p_bsdf(wi)`: what Russian roulette reads, so that a guide that sends paths where they
    /// matter (and so lowers their weight there) does not get them cut more often.
    pub rr_weight: Rgb,
    pub delta: bool,
    /// Drawn from a cached region's mixture: what the learned selection probability needs.
    pub guided: Option<GuidedDraw>,
}

impl From<BsdfSample> for DirectionSample {
    /// A direction drawn by BSDF sampling alone.
    fn from(s: BsdfSample) -> Self {
        DirectionSample {
            wi: s.wi,
            pdf_w: s.pdf_w,
            weight: s.weight,
            rr_weight: s.weight,
            delta: s.delta,
            guided: None,
        }
    }
}

/// How a guided direction was drawn (for [`SelectionLearner`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct GuidedDraw {
    /// The guide cache's region.
    pub region: u32,
    /// Densities per steradian of the direction under the BSDF and under the guide.
    pub pdf_bsdf_w: f32,
    pub pdf_guide_w: f32,
}

/// Where the guided distributions come from.
pub enum GuideSource<'a> {
    /// BSDF sampling alone.
    Bsdf,
    /// The paper's method: the `k_p` nearest particles of `map`, turned into a
    /// distribution by `guide` at every scattering event.
    PerEvent {
        map: &'a ParticleMap,
        guide: &'static dyn Guide,
        max_dist: f32,
    },
    /// Distributions prepared once per region.
    Cached(&'a GuideCache),
    /// One distribution everywhere (tests and benchmarks that bypass the maps).
    Fixed(&'a dyn GuideDistribution),
}

/// The distribution prepared at the current vertex.
#[derive(Default)]
enum Prepared<'a> {
    #[default]
    Bsdf,
    /// [`GuideSource::Fixed`]'s distribution.
    Fixed(&'a dyn GuideDistribution),
    Region(&'a RegionDistribution),
    Owned(Box<dyn GuideDistribution>),
}

/// The prepared distribution as `sample` and `pdf` call it: a raster by a static call (the
/// guide cache's common case), anything else through the trait.
#[derive(Clone, Copy)]
enum DistRef<'b> {
    Raster(&'b GridDistribution),
    Dyn(&'b dyn GuideDistribution),
}

impl DistRef<'_> {
    /// A draw and its density (a raster reads it from the drawn cell).
    #[inline]
    fn sample_with_pdf(self, mix: &ChannelMix, rng: &mut Rng) -> Option<(Vec3, f32)> {
        match self {
            DistRef::Raster(g) => g.sample_with_pdf(mix, rng),
            DistRef::Dyn(d) => d.sample(mix, rng).map(|w| (w, d.pdf(mix, w))),
        }
    }

    #[inline]
    fn pdf(self, mix: &ChannelMix, wi: Vec3) -> f32 {
        match self {
            DistRef::Raster(g) => g.pdf(mix, wi),
            DistRef::Dyn(d) => d.pdf(mix, wi),
        }
    }
}

/// Per-thread state of the sampler, reused from vertex to vertex.
#[derive(Default)]
pub struct SamplerState<'a> {
    prepared: Prepared<'a>,
    mix: Option<ChannelMix>,
    /// The cached region of the current vertex, and the probability of sampling the BSDF
    /// there (both set by `prepare`).
    region: Option<u32>,
    p_bsdf: f32,
    /// The region's [`Region::density`] (set by `prepare` where a cached region guides).
    density: Option<Rgb>,
    neighbors: Vec<Neighbor>,
    particles: Vec<GuideParticle>,
    /// Scattering events prepared at guiding surfaces.
    pub prepared_events: u64,
    /// Of those, the events that fell back to BSDF sampling (no region, too few particles).
    pub fallbacks: u64,
    /// Surface hits and rays that left the scene, counted by the path loop that owns this
    /// state (what the run summary's skip counters are made of).
    pub vertices: u64,
    pub escapes: u64,
    /// What finished camera or light paths teach the learned selection probabilities, in
    /// the order the paths were traced (the path loop's owner hands them to the learner).
    pub selection_records: Vec<crate::guide::selection::SelectionRecord>,
}

impl SamplerState<'_> {
    /// What the other pass's map says arrives per unit area at the current vertex (its
    /// cached region's [`Region::density`]), where a cached region guides it.
    pub fn region_density(&self) -> Option<Rgb> {
        self.density
    }

    /// True when the current vertex is guided.
    pub fn guided(&self) -> bool {
        !matches!(self.prepared, Prepared::Bsdf)
    }

    fn distribution(&self) -> Option<DistRef<'_>> {
        match &self.prepared {
            Prepared::Bsdf => None,
            Prepared::Fixed(d) => Some(DistRef::Dyn(*d)),
            Prepared::Region(RegionDistribution::Raster(g)) => Some(DistRef::Raster(g)),
            Prepared::Region(RegionDistribution::Boxed(d)) => Some(DistRef::Dyn(d.as_ref())),
            Prepared::Owned(d) => Some(DistRef::Dyn(d.as_ref())),
        }
    }
}

/// The sampler: a guide source, the mixture probability and the rule of where to guide.
pub struct GuidedSampler<'a> {
    pub source: GuideSource<'a>,
    pub params: GuideParams,
    pub soft_glossy_max: f32,
    /// `p_BSDF` learned per cached region (else `params.p_bsdf` everywhere).
    pub selection: Option<&'a SelectionLearner>,
}

impl<'a> GuidedSampler<'a> {
    /// BSDF sampling alone.
    pub fn bsdf() -> Self {
        GuidedSampler {
            source: GuideSource::Bsdf,
            params: GuideParams::default(),
            soft_glossy_max: 0.0,
            selection: None,
        }
    }

    /// The probability of sampling the BSDF in cached region `region`.
    #[inline]
    fn p_bsdf_in(&self, region: u32) -> f32 {
        match self.selection {
            Some(l) => l.p_bsdf(region),
            None => self.params.p_bsdf,
        }
    }

    /// Prepares `state` for BSDF sampling alone at a vertex where guiding cannot pay (no
    /// region is looked up, nothing is counted).
    #[inline]
    pub fn prepare_unguided(&self, state: &mut SamplerState<'a>) {
        state.prepared = Prepared::Bsdf;
        state.mix = None;
        state.region = None;
        state.density = None;
        state.p_bsdf = self.params.p_bsdf;
    }

    /// Prepares `state` at a scattering point.
    pub fn prepare(&self, at: &ScatterPoint, state: &mut SamplerState<'a>) {
        self.prepare_unguided(state);
        if matches!(self.source, GuideSource::Bsdf)
            || !guides_at_bsdf(at.bsdf, self.soft_glossy_max)
        {
            return;
        }
        state.prepared_events += 1;
        match &self.source {
            GuideSource::Bsdf => {}
            GuideSource::Cached(cache) => {
                // The region's summary first: a region without a distribution, or one that
                // learned BSDF sampling alone, is decided without touching its `Region`.
                if let Some((i, summary)) = cache
                    .lookup_index(at.p, at.side_normal())
                    .map(|i| (i, cache.summary(i)))
                    .filter(|(_, s)| s.guides)
                {
                    let p_bsdf = self.p_bsdf_in(i);
                    if p_bsdf >= 1.0 {
                        // A region that learned BSDF sampling alone (`selection`, "Guiding
                        // where it pays for its time"): its estimate still steers Russian
                        // roulette, but its distribution is not read. Not a fallback.
                        state.density = summary.density;
                        state.p_bsdf = p_bsdf;
                        return;
                    }
                    if let Some(dist) = cache.regions()[i as usize].distribution.as_ref() {
                        state.mix =
                            ChannelMix::new(at.channel_factor(), dist.get().channel_totals());
                        if state.mix.is_some() {
                            if let RegionDistribution::Raster(g) = dist {
                                g.prefetch();
                            }
                            state.prepared = Prepared::Region(dist);
                            state.region = Some(i);
                            state.density = summary.density;
                            state.p_bsdf = p_bsdf;
                        }
                    }
                }
            }
            GuideSource::Fixed(dist) => {
                state.mix = ChannelMix::new(at.channel_factor(), dist.channel_totals());
                if state.mix.is_some() {
                    state.prepared = Prepared::Fixed(*dist);
                }
            }
            GuideSource::PerEvent {
                map,
                guide,
                max_dist,
            } => {
                if let Some(dist) = self.prepare_per_event(map, *guide, *max_dist, at, state) {
                    state.mix = ChannelMix::new(Rgb::ONE, dist.channel_totals());
                    if state.mix.is_some() {
                        state.prepared = Prepared::Owned(dist);
                    }
                }
            }
        }
        if !state.guided() {
            state.fallbacks += 1;
        }
    }

    /// The paper's per-event preparation: query, filter, build.
    fn prepare_per_event(
        &self,
        map: &ParticleMap,
        guide: &dyn Guide,
        max_dist: f32,
        at: &ScatterPoint,
        state: &mut SamplerState,
    ) -> Option<Box<dyn GuideDistribution>> {
        let n = at.side_normal();
        let k = self.params.k_p;
        // Where the map cannot hold k particles facing this way (the dark side of a wall),
        // skip the search: the query would report fewer than k.
        if !map.may_hold(at.p, n, k, max_dist) {
            return None;
        }
        let found = map.query(
            at.p,
            n,
            k,
            max_dist,
            |nb| at.contribution(nb.dir, nb.weight),
            &mut state.neighbors,
        );
        if found < k {
            return None;
        }
        state.particles.clear();
        state.particles.extend(
            state
                .neighbors
                .iter()
                .map(|nb| GuideParticle {
                    dir: nb.dir,
                    weight: Rgb::new(nb.contribution, 0.0, 0.0),
                })
                .filter(|p| p.admissible(n, &self.params)),
        );
        if state.particles.is_empty() {
            return None;
        }
        // The paper's method samples the caps themselves: rasterising (`raster`) pays off
        // only when a distribution serves a whole region.
        let params = GuideParams {
            raster: 0,
            ..self.params.clone()
        };
        guide.build(&Frame::from_z(n), &state.particles, &params)
    }

    /// Draws a direction; `None` when no direction could be drawn (the BSDF's own sampling
    /// failed). A direction the BSDF does not scatter into comes back with zero weight.
    pub fn sample(
        &self,
        at: &ScatterPoint,
        state: &SamplerState,
        rng: &mut Rng,
    ) -> Option<DirectionSample> {
        self.sample_with::<General>(at, state, rng)
    }

    /// [`GuidedSampler::sample`] compiled for the effects `F`.
    #[inline]
    pub fn sample_with<F: Features>(
        &self,
        at: &ScatterPoint,
        state: &SamplerState,
        rng: &mut Rng,
    ) -> Option<DirectionSample> {
        let guide = match (state.distribution(), state.mix) {
            (Some(d), Some(mix)) if !at.bsdf.is_delta_with::<F>() => Some((d, mix)),
            _ => None,
        };
        let Some((dist, mix)) = guide else {
            let (u_lobe, u) = at.bsdf.draw_numbers(rng);
            return at
                .bsdf
                .sample_with::<F>(at.wo, u_lobe, u, at.mode)
                .map(Into::into);
        };
        let p = state.p_bsdf;
        let (wi, guide_pdf) = if rng.uniform() < p {
            let (u_lobe, u) = at.bsdf.draw_numbers(rng);
            let wi = at.bsdf.sample_with::<F>(at.wo, u_lobe, u, at.mode)?.wi;
            (wi, dist.pdf(&mix, wi))
        } else {
            dist.sample_with_pdf(&mix, rng)?
        };
        let bsdf_pdf = at.bsdf.pdf_with::<F>(at.wo, wi);
        let pdf_w = p * bsdf_pdf + (1.0 - p) * guide_pdf;
        if !(pdf_w > 0.0 && pdf_w.is_finite()) {
            return None;
        }
        // A direction the BSDF does not scatter into (a footprint across the horizon of an
        // opaque surface) is still a draw: it comes back with zero weight, so that what
        // `sample` draws is exactly the density `pdf` describes.
        let fc = at.bsdf.eval_with::<F>(at.wo, wi, at.mode) * wi.dot(at.bsdf.frame.z).abs();
        let valid = |w: Rgb| if is_valid_rgb(w) { w } else { Rgb::ZERO };
        let weight = valid(fc / pdf_w);
        Some(DirectionSample {
            wi,
            pdf_w,
            weight,
            rr_weight: if bsdf_pdf > 0.0 {
                valid(fc / bsdf_pdf)
            } else {
                weight
            },
            delta: false,
            guided: state.region.map(|region| GuidedDraw {
                region,
                pdf_bsdf_w: bsdf_pdf,
                pdf_guide_w: guide_pdf,
            }),
        })
    }

    /// The one-sample mixture's density of `wi` whose BSDF density is `bsdf_pdf`.
    #[inline]
    fn mixture_pdf(
        &self,
        state: &SamplerState,
        dist: DistRef,
        mix: &ChannelMix,
        wi: Vec3,
        bsdf_pdf: f32,
    ) -> f32 {
        let p = state.p_bsdf;
        p * bsdf_pdf + (1.0 - p) * dist.pdf(mix, wi)
    }

    /// The density with which this sampler draws `wi` at `at` for a path of white colour (the
    /// channel mixture without the throughput), without preparing a state: what the combined
    /// image's guided MIS weights use. Both subpaths must compute the same value for the same
    /// path, and neither knows the colour the other would have carried there. Per-event
    /// sources give the BSDF's pdf (their distribution would need a query).
    pub fn mis_pdf(&self, at: &ScatterPoint, wi: Vec3) -> f32 {
        let bsdf_pdf = at.bsdf.pdf(at.wo, wi);
        if at.bsdf.is_delta() || !guides_at_bsdf(at.bsdf, self.soft_glossy_max) {
            return bsdf_pdf;
        }
        let white = LUMINANCE * at.bsdf.colour();
        let mut p = self.params.p_bsdf;
        let guide_pdf = match &self.source {
            GuideSource::Cached(cache) => {
                match cache.lookup_index(at.p, at.side_normal()).map(|i| {
                    p = self.p_bsdf_in(i);
                    &cache.regions()[i as usize]
                }) {
                    // A region that learned BSDF sampling alone.
                    Some(_) if p >= 1.0 => None,
                    // The region's table when it has one (src/guide/table.rs), else its density.
                    Some(Region {
                        table: Some(t),
                        distribution: Some(_),
                        ..
                    }) => ChannelMix::new(white, t.channel_totals()).map(|mix| t.pdf(&mix, wi)),
                    Some(Region {
                        distribution: Some(d),
                        ..
                    }) => ChannelMix::new(white, d.get().channel_totals())
                        .map(|mix| d.get().pdf(&mix, wi)),
                    _ => None,
                }
            }
            GuideSource::Fixed(d) => {
                ChannelMix::new(white, d.channel_totals()).map(|mix| d.pdf(&mix, wi))
            }
            GuideSource::Bsdf | GuideSource::PerEvent { .. } => None,
        };
        match guide_pdf {
            Some(g) => p * bsdf_pdf + (1.0 - p) * g,
            None => bsdf_pdf,
        }
    }

    /// Density per steradian with which `sample` returns `wi` (0 for delta BSDFs).
    pub fn pdf(&self, at: &ScatterPoint, state: &SamplerState, wi: Vec3) -> f32 {
        self.pdf_with::<General>(at, state, wi)
    }

    /// [`GuidedSampler::pdf`] compiled for the effects `F`.
    #[inline]
    pub fn pdf_with<F: Features>(&self, at: &ScatterPoint, state: &SamplerState, wi: Vec3) -> f32 {
        self.pdf_given_bsdf_with::<F>(at, state, wi, at.bsdf.pdf_with::<F>(at.wo, wi))
    }

    /// [`GuidedSampler::pdf_with`] of a direction whose BSDF density `bsdf_pdf` is known
    /// already (from [`Bsdf::eval_and_lambert_pdf_with`]).
    #[inline]
    pub fn pdf_given_bsdf_with<F: Features>(
        &self,
        at: &ScatterPoint,
        state: &SamplerState,
        wi: Vec3,
        bsdf_pdf: f32,
    ) -> f32 {
        match (state.distribution(), &state.mix) {
            (Some(d), Some(mix)) if !at.bsdf.is_delta_with::<F>() => {
                self.mixture_pdf(state, d, mix, wi, bsdf_pdf)
            }
            _ => bsdf_pdf,
        }
    }
}
