//! What a particle pass is given ([`PassSettings`]) and gives ([`PassOutput`], with its
//! flux or importance accounting, [`PassStats`]).

use footprint::Rgb;
use footprint::guide::cache::Seed;
use footprint::guide::particle_map::ParticleInput;
use footprint::scene::Scene;
use footprint::scene::features::Specialisation;
use std::time::Duration;

/// Settings of one pass.
#[derive(Clone, Debug)]
pub struct PassSettings {
    /// Paths shot (photon paths or importon paths).
    pub paths: usize,
    /// Maximum path segments.
    pub max_depth: u32,
    /// Russian roulette after scattering at vertices of this depth or deeper.
    pub rr_depth: u32,
    pub seed: u64,
    /// Blinn exponents up to this count as "soft glossy" and store particles; above it a
    /// surface is "strongly glossy" and is treated like a specular one.
    pub soft_glossy_max: f32,
    /// Run the path loop compiled for the scene's effects (else the general one; the same
    /// particles either way, `footprint::scene::features`).
    pub specialise: bool,
    /// The view pass's starting weights per pixel (relative importance,
    /// [`crate::passes::target`]); `None`: every importon path starts at `1 / N`.
    pub target: Option<std::sync::Arc<crate::passes::target::ImportanceTarget>>,
    /// The most particles the pass keeps (its share of the memory budget,
    /// [`crate::passes::thinning`]); past it the pass thins.
    pub max_particles: usize,
}

impl PassSettings {
    /// The compiled loop the pass runs in.
    pub fn specialisation(&self, scene: &Scene) -> Specialisation {
        if self.specialise {
            Specialisation::for_effects(&scene.effects)
        } else {
            Specialisation::General
        }
    }
}

/// Flux (or importance) accounting of a pass, per bounce.
#[derive(Clone, Debug, Default)]
pub struct PassStats {
    pub paths: usize,
    /// Guided scattering events (at guiding surfaces) and, of those, BSDF fallbacks; zero
    /// for an unguided pass.
    pub guided_events: u64,
    pub fallbacks: u64,
    /// Total emitted power (light pass) or importance (view pass: 1 per channel).
    pub emitted: Rgb,
    /// Weight leaving the scene (no hit) after bounce `k` (index 0: straight from the source).
    pub escaped: Vec<Rgb>,
    pub time: Duration,
    /// Particles the paths stored before thinning.
    pub particles_drawn: usize,
    /// The thinning level: the pass kept a share `2^-thinning` of its particles
    /// ([`crate::passes::thinning`]); 0 kept all.
    pub thinning: u32,
    /// View pass: how many of its first particles the first [`crate::passes::seed_paths`]
    /// paths stored, the photon map's cache seeds (`None`: all of them; a thinned pass's).
    pub seed_particles: Option<usize>,
}

#[derive(Clone)]
pub struct PassOutput {
    pub particles: Vec<ParticleInput>,
    /// Points where paths left area lights (light pass only).
    pub emission_points: Vec<Seed>,
    pub stats: PassStats,
}

impl PassOutput {
    /// Where this pass's paths asked for a direction at guiding surfaces: the seeds of the
    /// other map's guide cache.
    pub fn seeds(&self) -> Vec<Seed> {
        self.seeds_of(self.particles.len())
    }

    /// The seeds of the photon map's cache from a view pass: the points of its first
    /// [`crate::passes::seed_paths`] paths ([`PassStats::seed_particles`]), the same whether
    /// the pass shot only those (path tracing) or more (the combined image, `auto`'s pilot).
    /// A pass thinned to its share of the memory budget no longer knows them and gives all
    /// its particles: path tracing reading a thinned combined image's or `auto` pilot's maps
    /// then builds another cache than from its own, smaller pass (the same image only where
    /// the maps fit their budget).
    pub fn photon_cache_seeds(&self) -> Vec<Seed> {
        self.seeds_of(self.stats.seed_particles.unwrap_or(self.particles.len()))
    }

    /// The points of the first `n` particles, and the emission points.
    fn seeds_of(&self, n: usize) -> Vec<Seed> {
        self.particles[..n.min(self.particles.len())]
            .iter()
            .map(|p| Seed {
                position: p.position,
                normal: p.normal,
            })
            .chain(self.emission_points.iter().copied())
            .collect()
    }
}
