//! The walk both passes share: a visitor that stores a particle at every hit on a guiding
//! surface, and paths traced in fixed chunks in parallel, concatenated in chunk order and
//! kept within the pass's particle budget.

use crate::walk::{Arrival, Start, Vertex, Visitor, walk};
use footprint::Rgb;
use footprint::guide::cache::Seed;
use footprint::guide::guides_at_bsdf;
use footprint::guide::particle_map::ParticleInput;
use footprint::guide::sampler::{DirectionSample, GuidedSampler, SamplerState};
use footprint::rng::Rng;
use footprint::scene::Scene;
use footprint::scene::features::Features;
use glam::Vec3;
use rayon::prelude::*;
use std::marker::PhantomData;
use std::ops::Range;

use super::pass::PassSettings;
use super::thinning::Kept;

/// Paths a worker traces as one task of a pass.
pub const CHUNK_PATHS: usize = 2048;

#[derive(Default)]
pub(super) struct ChunkOut {
    pub(super) particles: Vec<ParticleInput>,
    pub(super) emission_points: Vec<Seed>,
    pub(super) escaped: Vec<Rgb>,
    /// Scattering events at guiding surfaces and BSDF fallbacks among them.
    pub(super) guided: (u64, u64),
    /// Particles stored before thinning, and the thinning level ([`super::thinning`]).
    pub(super) drawn: usize,
    pub(super) thinning: u32,
}

/// Stores particles along a walk.
struct Storing<'o, F> {
    soft_glossy_max: f32,
    specular_chain: bool,
    out: &'o mut ChunkOut,
    features: PhantomData<F>,
}

impl<F: Features> Visitor for Storing<'_, F> {
    type F = F;

    fn escaped(&mut self, _dir: Vec3, beta: Rgb, depth: u32, _from: &Arrival) {
        let k = depth as usize - 1;
        if self.out.escaped.len() <= k {
            self.out.escaped.resize(k + 1, Rgb::ZERO);
        }
        self.out.escaped[k] += beta;
    }

    fn reached(&mut self, v: &Vertex, _from: &Arrival, _rng: &mut Rng) {
        if guides_at_bsdf(&v.bsdf, self.soft_glossy_max) {
            let n = if v.hit.ng.dot(v.wo) >= 0.0 {
                v.hit.ng
            } else {
                -v.hit.ng
            };
            self.out.particles.push(ParticleInput {
                position: v.hit.p,
                dir: v.wo,
                normal: n,
                weight: v.beta,
                depth: v.depth.min(u16::MAX as u32) as u16,
                specular_chain: self.specular_chain,
            });
        }
    }

    fn scattered(&mut self, _v: &Vertex, s: &DirectionSample) {
        self.specular_chain &= s.delta;
    }

    // Particle paths are not split (a map's particles are independent paths).
    type Branch = ();
    fn branch(&self) {}
    fn restore(&mut self, _b: ()) {}
}

/// Particles a path stores, for the batch size: about 8 on door, fewer on open scenes.
const PARTICLES_PER_PATH: usize = 8;

impl ChunkOut {
    /// Appends `later` (later paths of the pass: a chunk of a batch, or a part traced apart)
    /// as one run of both would have kept them: both parts at one thinning level (then
    /// [`ChunkOut::within`] the budget: the same particles for any split, as for any batch
    /// size, [`super::thinning`]).
    pub(super) fn append(&mut self, later: &mut ChunkOut) {
        self.drawn += later.drawn;
        self.guided.0 += later.guided.0;
        self.guided.1 += later.guided.1;
        if self.escaped.len() < later.escaped.len() {
            self.escaped.resize(later.escaped.len(), Rgb::ZERO);
        }
        for (e, x) in self.escaped.iter_mut().zip(&later.escaped) {
            *e += *x;
        }
        let level = self.thinning.max(later.thinning);
        for part in [&mut *self, &mut *later] {
            let from = part.thinning;
            super::thinning::thin(&mut part.particles, &mut part.emission_points, from, level);
            part.thinning = level;
        }
        self.particles.append(&mut later.particles);
        self.emission_points.append(&mut later.emission_points);
    }

    /// Raises the thinning level while the particles are more than `max_particles`.
    pub(super) fn within(&mut self, max_particles: usize) {
        let kept = Kept {
            particles: &mut self.particles,
            seeds: &mut self.emission_points,
            level: &mut self.thinning,
        };
        kept.within(max_particles);
    }
}

/// Traces paths `paths` (indices into the pass's streams) in chunks of [`CHUNK_PATHS`], in
/// batches; after each batch the particles are thinned while they are more than
/// `max_particles` ([`super::thinning`]: the result is the same for any batch size, so for
/// any thread count). `all.thinning` is the level reached, `all.drawn` the particles
/// stored before thinning.
pub(super) fn run_chunks<'a>(
    paths: Range<usize>,
    max_particles: usize,
    path: impl Fn(usize, &mut ChunkOut, &mut SamplerState<'a>) + Sync,
) -> ChunkOut {
    let chunks = paths.len().div_ceil(CHUNK_PATHS);
    // Chunks traced between two checks of the budget: as many as hold a quarter of the
    // budget's particles at [`PARTICLES_PER_PATH`] (the whole pass at once under the
    // default budget), and one per worker at least, so that what a pass holds past its
    // budget is at most one batch and every worker has a chunk.
    let batch =
        (max_particles / (4 * CHUNK_PATHS * PARTICLES_PER_PATH)).max(rayon::current_num_threads());
    let mut all = ChunkOut::default();
    for first_chunk in (0..chunks).step_by(batch) {
        let outs: Vec<ChunkOut> = (first_chunk..(first_chunk + batch).min(chunks))
            .into_par_iter()
            .map(|c| {
                let mut out = ChunkOut::default();
                let mut state = SamplerState::default();
                let first = paths.start + c * CHUNK_PATHS;
                for i in first..(first + CHUNK_PATHS).min(paths.end) {
                    path(i, &mut out, &mut state);
                }
                out.guided = (state.prepared_events, state.fallbacks);
                out.drawn = out.particles.len();
                out
            })
            .collect();
        all.particles
            .reserve(outs.iter().map(|o| o.particles.len()).sum());
        // The budget is checked after the batch, not after each chunk of it.
        for mut o in outs {
            all.append(&mut o);
        }
        all.within(max_particles);
    }
    if all.thinning > 0 {
        all.particles.shrink_to_fit();
        all.emission_points.shrink_to_fit();
    }
    all
}

/// Walks one particle path in the loop compiled for the effects `F` (the passes choose `F`
/// once, [`PassSettings::specialisation`]), storing into `out`.
#[allow(clippy::too_many_arguments)]
pub(super) fn trace<'a, F: Features>(
    scene: &Scene,
    s: &PassSettings,
    start: &Start,
    sampler: &GuidedSampler<'a>,
    state: &mut SamplerState<'a>,
    rng: &mut Rng,
    out: &mut ChunkOut,
) {
    let mut v = Storing::<F> {
        soft_glossy_max: s.soft_glossy_max,
        specular_chain: true,
        out,
        features: PhantomData,
    };
    walk(scene, start, sampler, state, rng, &mut v);
}
