//! Guiding: choosing the next direction of a path from particles that the *other* kind of
//! path left behind (Hey & Purgathofer 2001; `docs/method.md`).
//!
//! The design is symmetric. A light pass fills a **photon map** (flux `Φ_p`) that guides
//! view paths (path tracing); a view pass fills an **importance map** (importance `W_p`,
//! per channel) that guides light paths (light tracing). Both maps are one data structure
//! ([`particle_map`]), and one sampler ([`sampler::GuidedSampler`]) serves both directions:
//! only the map it reads differs.
//!
//! * [`particle_map`]: the particles, a kd-tree and the k-nearest query (§2.1).
//! * [`Guide`] (this file): the extension point. A guide turns the particles gathered
//!   around a point into a distribution of directions ([`GuideDistribution`]). Three are
//!   registered in [`GUIDES`]: BSDF sampling alone, the classic grid of Jensen 1995
//!   ([`grid`]) and the paper's footprints ([`footprint`]).
//! * [`cache`]: the guide cache. Distributions are prepared once per region of space and
//!   normal direction, where the other pass's paths scatter, and shared by every
//!   scattering event in the region; the paper's per-event preparation stays available.
//! * [`sampler`]: what the integrators call at a scattering point: `prepare`, `sample`,
//!   `pdf`, mixing the guide with BSDF sampling (`p_BSDF`) and falling back to the BSDF
//!   where particles cannot guide.
//! * [`selection`]: the probability `p_BSDF` of sampling the BSDF, learned per cached
//!   region from the render's own paths.
//! * [`table`]: a cached region's density tabulated for the combined image's MIS weights.
//!
//! Adding a guide: write `src/guide/NAME.rs` with a unit struct implementing [`Guide`] and
//! a type implementing [`GuideDistribution`], declare the module below and add the struct
//! to [`GUIDES`]. The command line, scene files, `compare` and the EXR header take its name
//! from there.

pub mod cache;
pub mod footprint;
pub mod grid;
pub mod particle_map;
pub mod sampler;
pub mod selection;
pub mod table;

use crate::Rgb;
use crate::bsdf::Lobes;
use crate::math::Frame;
use crate::rng::Rng;
use crate::settings::GuideParams;
use glam::Vec3;
use table::DirectionTable;

/// A particle as a guide sees it: its incoming direction `Ψ_p` (world, unit, pointing away
/// from the surface toward where it came from) and its weight per channel (`Φ_p` or `W_p`,
/// or the per-event contribution `c_p` in channel 0).
#[derive(Clone, Copy, Debug)]
pub struct GuideParticle {
    pub dir: Vec3,
    pub weight: Rgb,
}

impl GuideParticle {
    /// True when the particle may enter a guide built around side normal `n`: a positive,
    /// finite weight in some channel, and not grazing (`|Ψ_p · N| >= grazing_cos_min`, the
    /// same rule in sampling and evaluation, docs/method.md "Grazing particles").
    #[inline]
    pub fn admissible(&self, n: Vec3, params: &GuideParams) -> bool {
        self.weight.is_finite()
            && self.weight.min_element() >= 0.0
            && self.weight.max_element() > 0.0
            && self.dir.dot(n).abs() >= params.grazing_cos_min
    }
}

/// Probabilities of the three colour channels in a per-channel mixture (they sum to 1).
///
/// A particle's selection weight at a Lambertian vertex is `c_p = Σ_c a_c W_p,c` with
/// `a_c = (luminance coefficient · throughput · albedo)_c` (paper eq. 1-2 with the
/// throughput colour). So choosing channel `c` with probability `a_c S_c / Σ a S` (`S_c` the
/// channel's total weight) and then a particle with probability `W_p,c / S_c` picks `p`
/// with exactly `c_p / Σ c`: per-channel distributions prepared once reproduce per-event
/// colour steering.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChannelMix(pub [f32; 3]);

impl ChannelMix {
    /// The mixture for a path colour `a` (luminance coefficients, throughput and albedo
    /// multiplied) over channel totals `totals`; `None` when nothing would be chosen.
    pub fn new(a: Rgb, totals: Rgb) -> Option<Self> {
        let w = a.max(Rgb::ZERO) * totals.max(Rgb::ZERO);
        let sum = w.x + w.y + w.z;
        if !(sum > 0.0 && sum.is_finite()) {
            return None;
        }
        Some(ChannelMix([w.x / sum, w.y / sum, w.z / sum]))
    }

    /// A channel drawn with these probabilities from `u` in [0, 1).
    #[inline]
    pub fn pick(&self, u: f32) -> usize {
        let [a, b, _] = self.0;
        if u < a && a > 0.0 {
            0
        } else if u < a + b && b > 0.0 {
            1
        } else if self.0[2] > 0.0 {
            2
        } else if b > 0.0 {
            1
        } else {
            0
        }
    }
}

/// A distribution of directions prepared from particles: the density a guided sampler
/// draws from with probability `1 - p_BSDF`. `sample` must draw exactly the density `pdf`
/// describes, for every channel mixture.
pub trait GuideDistribution: Send + Sync {
    /// Per-channel sums of the weights the distribution was built from.
    fn channel_totals(&self) -> Rgb;
    /// A world direction (unit) drawn from the mixture `mix` of the channel distributions.
    fn sample(&self, mix: &ChannelMix, rng: &mut Rng) -> Option<Vec3>;
    /// Density per steradian of `sample` at the world direction `wi` (unit).
    fn pdf(&self, mix: &ChannelMix, wi: Vec3) -> f32;
    /// The distribution tabulated on `side x side` cells per hemisphere of `frame` (the
    /// frame it was built in) for the combined image's MIS weights ([`DirectionTable`]).
    /// `None`: the weights read [`GuideDistribution::pdf`] (a distribution whose `pdf` is a
    /// lookup already, as the grid's).
    fn tabulate(&self, _frame: &Frame, _side: usize) -> Option<DirectionTable> {
        None
    }
    /// Heap bytes held (the guide cache reports its memory).
    fn heap_bytes(&self) -> usize;
    /// The concrete type, for tests and tools that inspect a prepared distribution.
    fn as_any(&self) -> &dyn std::any::Any;
}

/// The extension point of direction sampling: how particles become a distribution.
pub trait Guide: Send + Sync {
    /// The name used by `--guide`, scene files, `compare` and EXR headers.
    fn name(&self) -> &'static str;
    /// One line for `--help`.
    fn about(&self) -> &'static str;
    /// False for BSDF sampling alone: no particle map is built and nothing is guided.
    fn uses_particles(&self) -> bool {
        true
    }
    /// The distribution of the particles around a point whose side normal is `frame.z`
    /// (particles with zero weight or grazing `|Ψ_p · N| < grazing_cos_min` already left
    /// out; at least one). `None` when these particles cannot guide.
    fn build(
        &self,
        frame: &Frame,
        particles: &[GuideParticle],
        params: &GuideParams,
    ) -> Option<Box<dyn GuideDistribution>>;
}

/// BSDF sampling alone: the guide that guides nowhere.
pub struct BsdfOnly;

impl Guide for BsdfOnly {
    fn name(&self) -> &'static str {
        "bsdf"
    }
    fn about(&self) -> &'static str {
        "The BSDF's own sampling (no particle map)"
    }
    fn uses_particles(&self) -> bool {
        false
    }
    fn build(
        &self,
        _frame: &Frame,
        _particles: &[GuideParticle],
        _params: &GuideParams,
    ) -> Option<Box<dyn GuideDistribution>> {
        None
    }
}

/// Every guide, by name: the one registration list.
pub static GUIDES: &[&dyn Guide] = &[&BsdfOnly, &grid::GridGuide, &footprint::FootprintGuide];

/// The guide named `name`.
pub fn find_guide(name: &str) -> Option<&'static dyn Guide> {
    GUIDES.iter().copied().find(|g| g.name() == name)
}

/// The registered guides' names, comma-separated (for error messages).
pub fn guide_names() -> String {
    GUIDES
        .iter()
        .map(|g| g.name())
        .collect::<Vec<_>>()
        .join(", ")
}

/// True when particles are stored and guide at surfaces with these lobes: diffuse, and
/// glossy up to the soft-glossy exponent (the rough conductor and rough plastic by the
/// Blinn exponent of about the same width); never mirrors, glass, smooth conductors or
/// plastics, thin glass or strongly glossy lobes (paper §3).
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
