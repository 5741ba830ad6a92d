//! What a guide is: the particles it reads ([`GuideParticle`]), the distribution of
//! directions it builds from them ([`GuideDistribution`]) and the extension point itself
//! ([`Guide`]).

use crate::Rgb;
use crate::guide::channel_mix::ChannelMix;
use crate::guide::table::DirectionTable;
use crate::math::Frame;
use crate::rng::Rng;
use crate::settings::GuideParams;
use glam::Vec3;

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
