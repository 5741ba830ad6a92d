//! The walk both passes share: a visitor that stores a particle at every hit on a guiding
//! surface, and paths traced in fixed chunks in parallel, concatenated in chunk order.

use crate::walk::{Arrival, Start, Vertex, Visitor, walk};
use footprint::Rgb;
use footprint::guide::cache::Seed;
use footprint::guide::guides_at;
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

const CHUNK: usize = 2048;

#[derive(Default)]
pub(super) struct ChunkOut {
    pub(super) particles: Vec<ParticleInput>,
    pub(super) emission_points: Vec<Seed>,
    pub(super) escaped: Vec<Rgb>,
    /// Scattering events at guiding surfaces and BSDF fallbacks among them.
    pub(super) guided: (u64, u64),
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

    fn reached(&mut self, v: &Vertex, _from: &Arrival) {
        if guides_at(&v.bsdf.lobes, self.soft_glossy_max) {
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

/// Traces paths `paths` (indices into the pass's streams) in chunks of [`CHUNK`].
pub(super) fn run_chunks<'a>(
    paths: Range<usize>,
    path: impl Fn(usize, &mut ChunkOut, &mut SamplerState<'a>) + Sync,
) -> ChunkOut {
    let chunks = paths.len().div_ceil(CHUNK);
    let outs: Vec<ChunkOut> = (0..chunks)
        .into_par_iter()
        .map(|c| {
            let mut out = ChunkOut::default();
            let mut state = SamplerState::default();
            let first = paths.start + c * CHUNK;
            for i in first..(first + CHUNK).min(paths.end) {
                path(i, &mut out, &mut state);
            }
            out.guided = (state.prepared_events, state.fallbacks);
            out
        })
        .collect();
    let mut all = ChunkOut {
        particles: Vec::with_capacity(outs.iter().map(|o| o.particles.len()).sum()),
        ..Default::default()
    };
    for o in outs {
        all.guided.0 += o.guided.0;
        all.guided.1 += o.guided.1;
        all.particles.extend_from_slice(&o.particles);
        all.emission_points.extend_from_slice(&o.emission_points);
        if all.escaped.len() < o.escaped.len() {
            all.escaped.resize(o.escaped.len(), Rgb::ZERO);
        }
        for (e, x) in all.escaped.iter_mut().zip(&o.escaped) {
            *e += *x;
        }
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
