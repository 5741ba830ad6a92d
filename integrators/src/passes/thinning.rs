//! A pass within its memory budget (`[maps] max_memory`, `--max-memory`): past its share of
//! particles a pass keeps an even sample of them, each kept particle's weight raised by
//! the inverse of the share kept, so that a map's weights still sum, in expectation, to
//! the power (or importance) arriving at its surfaces, and a guide drawn from it is the
//! same distribution in expectation. Guided estimators stay unbiased whatever a map holds
//! (the guides only choose directions, with their true densities), so thinning costs
//! noise, not correctness.
//!
//! **The rule.** At level `k` a particle is kept when the low `k` bits of a hash of its
//! position and direction are zero (a share `2^-k`), its weight multiplied by `2^k`. The
//! levels are nested (what level `k + 1` keeps, level `k` kept), so a pass thins as it
//! goes: after each batch of paths, while its particles are more than its share, the
//! level rises by one. The particles a pass ends with are those of the lowest level at
//! which all its paths' particles fit, whatever the batches were, so they do not depend on
//! the thread count. The points where photon paths leave area lights (the importance
//! cache's seeds) are thinned by the same rule.
//!
//! **The share.** Particles cost [`PEAK_BYTES_PER_PARTICLE`] at the peak of a guided render
//! (both passes' particles as drawn, their maps' trees and records, the spatial sort's copy
//! and the caches' seeds and regions; measured in `docs/measurements/memory.md`), so a
//! budget of `B` bytes allows each of the two passes `B / (2 · PEAK_BYTES_PER_PARTICLE)`.

use super::pass::PassOutput;
use footprint::guide::cache::Seed;
use footprint::guide::particle_map::ParticleInput;
use glam::Vec3;

/// Heap bytes per particle (of both passes together) at the peak of building the maps and
/// caches of `combined --guide footprint` (the most a render holds): 173 measured on door
/// (`docs/measurements/memory.md`), with a tenth more for what a pass holds past its
/// budget until its next check.
pub const PEAK_BYTES_PER_PARTICLE: u64 = 192;

/// The most particles each pass may keep within a budget of `bytes` (the two passes share
/// it evenly).
pub fn max_particles(bytes: u64) -> usize {
    (bytes / (2 * PEAK_BYTES_PER_PARTICLE)).max(1) as usize
}

/// The hash that decides a particle's fate (a SplitMix64 finaliser over its bits).
fn hash(a: Vec3, b: Vec3) -> u64 {
    let mut h = 0x9e37_79b9_7f4a_7c15u64;
    for x in a.to_array().into_iter().chain(b.to_array()) {
        h ^= x.to_bits() as u64;
        h = (h ^ (h >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        h = (h ^ (h >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        h ^= h >> 31;
    }
    h
}

/// Whether a particle at `(a, b)` is kept at `level`.
fn kept(a: Vec3, b: Vec3, level: u32) -> bool {
    level == 0 || hash(a, b).trailing_zeros() >= level
}

/// Brings particles and seeds kept at level `from` to level `to >= from`.
pub(super) fn thin(particles: &mut Vec<ParticleInput>, seeds: &mut Vec<Seed>, from: u32, to: u32) {
    if to <= from {
        return;
    }
    let scale = (1u64 << (to - from).min(63)) as f32;
    particles.retain_mut(|p| {
        let keep = kept(p.position, p.dir, to);
        p.weight *= scale;
        keep
    });
    seeds.retain(|s| kept(s.position, s.normal, to));
}

/// What a pass has kept so far, at its thinning level: the batches of a pass are appended
/// in order (`ChunkOut::append`, each thinned to the level) and the level raised after each
/// while the particles are more than the pass's share ([`Kept::within`]). The particles kept
/// in the end do not depend on the batches.
pub(super) struct Kept<'a> {
    pub(super) particles: &'a mut Vec<ParticleInput>,
    pub(super) seeds: &'a mut Vec<Seed>,
    pub(super) level: &'a mut u32,
}

impl Kept<'_> {
    /// Raises the level while the particles are more than `max`.
    pub(super) fn within(self, max: usize) {
        while self.particles.len() > max && *self.level < 63 {
            let from = *self.level;
            *self.level += 1;
            thin(self.particles, self.seeds, from, *self.level);
        }
    }
}

impl PassOutput {
    /// Thins this pass (kept at `self.stats.thinning`) to `level`.
    pub fn thin_to(&mut self, level: u32) {
        let from = self.stats.thinning;
        thin(&mut self.particles, &mut self.emission_points, from, level);
        self.stats.thinning = self.stats.thinning.max(level);
        self.forget_seed_count(from);
    }

    /// A view pass thinned past `from` no longer knows which of its particles its seeding
    /// paths stored (`PassStats::seed_particles`): its cache then reads them all.
    fn forget_seed_count(&mut self, from: u32) {
        if self.stats.thinning > from {
            self.stats.seed_particles = None;
        }
    }

    /// Thins this pass until it holds at most `max` particles.
    pub fn within(&mut self, max: usize) {
        let from = self.stats.thinning;
        let kept = Kept {
            particles: &mut self.particles,
            seeds: &mut self.emission_points,
            level: &mut self.stats.thinning,
        };
        kept.within(max);
        self.forget_seed_count(from);
    }

    /// The share of the drawn particles this pass kept: `2^-thinning`.
    pub fn kept_share(&self) -> f64 {
        0.5f64.powi(self.stats.thinning as i32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use footprint::Rgb;

    fn particles(n: usize) -> Vec<ParticleInput> {
        (0..n)
            .map(|i| ParticleInput {
                position: Vec3::new(i as f32 * 0.37, (i % 17) as f32, 1.0),
                dir: Vec3::Z,
                normal: Vec3::Z,
                weight: Rgb::splat(1.0),
                depth: 1,
                specular_chain: false,
            })
            .collect()
    }

    /// The levels nest, each keeps about half of the one before (a binomial count within
    /// 5 standard deviations), and the kept weights sum to the drawn ones within the same
    /// bound.
    #[test]
    fn each_level_keeps_half_of_the_one_before_and_the_weights_sum_stays() {
        let n = 100_000;
        let all = particles(n);
        let mut last = all.clone();
        for level in 1..=6 {
            let mut p = all.clone();
            thin(&mut p, &mut Vec::new(), 0, level);
            let expect = n as f64 / (1u64 << level) as f64;
            let sd = (expect * (1.0 - 0.5f64.powi(level as i32))).sqrt();
            assert!(
                (p.len() as f64 - expect).abs() < 5.0 * sd,
                "level {level}: {} of {n}",
                p.len()
            );
            let sum: f64 = p.iter().map(|q| q.weight.x as f64).sum();
            assert!((sum - n as f64).abs() < 5.0 * sd * (1u64 << level) as f64);
            // Thinning the level before (a superset) gives the same particles and weights.
            thin(&mut last, &mut Vec::new(), level - 1, level);
            assert_eq!(last.len(), p.len());
            let same = |a: &ParticleInput, b: &ParticleInput| {
                a.position == b.position && a.weight == b.weight
            };
            assert!(last.iter().zip(&p).all(|(a, b)| same(a, b)));
            last = p;
        }
    }

    /// The particles a pass keeps do not depend on its batches (so neither on its thread
    /// count): the same 100,000 particles appended in batches of 1,000, 7,000 and all at
    /// once, each followed by the budget check, end at the same level with the same
    /// particles and weights, bit for bit, and within the budget.
    #[test]
    fn the_particles_kept_do_not_depend_on_the_batches() {
        let all = particles(100_000);
        let max = 9_000;
        let run = |batch: usize| {
            let (mut kept, mut seeds, mut level) = (Vec::new(), Vec::new(), 0u32);
            for chunk in all.chunks(batch) {
                // A batch drawn at level 0, thinned to the level kept so far, appended.
                let mut drawn = chunk.to_vec();
                thin(&mut drawn, &mut Vec::new(), 0, level);
                kept.append(&mut drawn);
                let k = Kept {
                    particles: &mut kept,
                    seeds: &mut seeds,
                    level: &mut level,
                };
                k.within(max);
            }
            (kept, level)
        };
        let bits = |p: &[ParticleInput]| -> Vec<[u32; 4]> {
            p.iter()
                .map(|q| {
                    let (a, w) = (q.position.to_array(), q.weight.x);
                    [a[0], a[1], a[2], w].map(f32::to_bits)
                })
                .collect()
        };
        let (once, level) = run(all.len());
        assert!(
            level >= 4 && once.len() <= max,
            "level {level}, {} kept",
            once.len()
        );
        for batch in [1_000, 7_000] {
            let (kept, l) = run(batch);
            assert_eq!(l, level, "batches of {batch}");
            assert_eq!(bits(&kept), bits(&once), "batches of {batch}");
        }
    }
}
