//! Random number streams. Every pixel (path tracing) and every light path (light tracing)
//! gets its own stream derived from the seed and its index, so an image is reproducible from
//! its seed whatever the number of threads.
//!
//! A camera or light path of the render draws either independent numbers or, by default, the
//! coordinates of one point of an **Owen-scrambled Sobol sequence** ([`Sequence`]; Burley
//! 2020, "Practical Hash-based Owen Scrambling", through the `sobol_burley` crate): pass `k`
//! of pixel `p` is point `k` of pixel `p`'s own scrambled sequence, so the samples a pixel
//! gathers over the passes are stratified in every 2D and 4D projection the path uses, while
//! every single point stays uniformly distributed (each estimate is unbiased as it is with
//! independent numbers). Dimensions are **padded** as pbrt-v4's `PaddedSobolSampler` and
//! Burley's paper pad them: each group of four dimensions is the first four dimensions of
//! Sobol with its own scramble and shuffle, so groups are only randomly associated and the
//! sequence has no dimension limit. A pair of numbers ([`Rng::uniform2`]) never straddles two
//! groups, and [`Rng::start_vertex`] gives every scattering vertex its own groups so that the
//! same decision (light choice, light point, direction, roulette) reads the same dimensions in
//! every sample of a pixel, whatever the path did before. Choices spend no dimension of
//! their own where they can help it: the light choice reuses the light point's first number
//! (`Scene::choose_light`), and a BSDF of one lobe draws no lobe number
//! (`Bsdf::draw_numbers`), so that at a Lambertian vertex the light point's pair and the
//! direction's pair share one group of four: the vertex costs one scrambled group, not
//! two, and the two pairs are stratified together. The scrambled sequence holds 2^16
//! points; passes beyond that draw independent numbers.

use glam::Vec2;
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::{Rng as _, SeedableRng};

/// Which numbers the paths of a render draw (pbrt's and Mitsuba's `sampler`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Sequence {
    /// Owen-scrambled Sobol points, one per pass, padded in groups of four dimensions.
    #[default]
    Sobol,
    /// Independent uniform numbers (Mitsuba's `independent`).
    Independent,
}

impl crate::keyword::Keyword for Sequence {
    const ALL: &'static [Self] = &[Sequence::Sobol, Sequence::Independent];

    fn name(self) -> &'static str {
        match self {
            Sequence::Sobol => "sobol",
            Sequence::Independent => "independent",
        }
    }

    fn about(self) -> &'static str {
        match self {
            Sequence::Sobol => {
                "Owen-scrambled Sobol points, one per pass, padded in groups of four dimensions"
            }
            Sequence::Independent => "Independent uniform numbers (Mitsuba's `independent`)",
        }
    }
}

/// Dimensions a path's start uses before its first scattering vertex: the pixel position
/// (camera) or the light, point and direction (light paths).
const START_DIMENSIONS: u32 = 8;
/// Dimensions reserved for each scattering vertex (next-event estimation, the direction,
/// Russian roulette). A vertex that draws more goes on into the next vertex's dimensions,
/// which then starts after them: a dimension is never read twice in one path.
const VERTEX_DIMENSIONS: u32 = 16;
/// Dimensions drawn from the scrambled sequence: the path's start and its first
/// [`SOBOL_VERTICES`] scattering vertices; later vertices draw independent numbers.
const SOBOL_DIMENSIONS: u32 = START_DIMENSIONS + SOBOL_VERTICES * VERTEX_DIMENSIONS;
const SOBOL_VERTICES: u32 = 1;
/// Points of the scrambled sequence (`sobol_burley`'s limit).
const SOBOL_POINTS: u64 = 1 << 16;

/// A random number generator for one sample stream.
pub struct Rng {
    random: Xoshiro256PlusPlus,
    sobol: Option<SobolPoint>,
}

/// One point of a padded, Owen-scrambled Sobol sequence, read dimension by dimension.
struct SobolPoint {
    /// The point's index in its sequence (the pass).
    index: u32,
    /// The stream's scramble: every group of four dimensions hashes it with its number.
    stream: u64,
    /// The next dimension to read.
    dim: u32,
    /// The group whose four values `values` holds (`u32::MAX`: none yet).
    group: u32,
    values: [f32; 4],
}

impl SobolPoint {
    /// The next dimension's value, or `None` past [`SOBOL_DIMENSIONS`].
    #[inline]
    fn next(&mut self) -> Option<f32> {
        if self.dim >= SOBOL_DIMENSIONS {
            return None;
        }
        let group = self.dim >> 2;
        if group != self.group {
            let seed = mix64(self.stream ^ (group as u64).wrapping_mul(0x9e3779b97f4a7c15));
            self.values = sobol_burley::sample_4d(self.index, 0, (seed >> 32) as u32);
            self.group = group;
        }
        let v = self.values[(self.dim & 3) as usize];
        self.dim += 1;
        Some(v)
    }
}

/// SplitMix64 finaliser: decorrelates nearby stream indices.
#[inline]
fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58476d1ce4e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d049bb133111eb);
    z ^ (z >> 31)
}

#[inline]
fn stream_seed(seed: u64, domain: u64, index: u64) -> u64 {
    mix64(
        seed ^ mix64(domain.wrapping_add(0x9e3779b97f4a7c15))
            ^ mix64(index.wrapping_mul(0xd1b54a32d192ed03)),
    )
}

impl Rng {
    /// The independent stream for (`seed`, `domain`, `index`). `domain` separates uses (e.g.
    /// the camera pass from the light pass) so that they never share numbers.
    pub fn new(seed: u64, domain: u64, index: u64) -> Self {
        Rng {
            random: Xoshiro256PlusPlus::seed_from_u64(stream_seed(seed, domain, index)),
            sobol: None,
        }
    }

    /// The numbers of pass `pass` of stream `stream` (a pixel, or a light path's slot in a
    /// pass) in `domain`. With [`Sequence::Independent`] this is `Rng::new(seed, domain,
    /// pass * streams + stream)`; with
    /// [`Sequence::Sobol`], point `pass` of the stream's own scrambled sequence (independent
    /// numbers, from that same stream, past its 2^16 points).
    pub fn for_pass(
        sequence: Sequence,
        seed: u64,
        domain: u64,
        stream: u64,
        streams: u64,
        pass: u64,
    ) -> Self {
        let mut rng = Rng::new(seed, domain, pass * streams + stream);
        if sequence == Sequence::Sobol && pass < SOBOL_POINTS {
            rng.sobol = Some(SobolPoint {
                index: pass as u32,
                stream: stream_seed(seed, domain ^ 0x50b01, stream),
                dim: 0,
                group: u32::MAX,
                values: [0.0; 4],
            });
        }
        rng
    }

    /// Uniform in [0, 1).
    #[inline]
    pub fn uniform(&mut self) -> f32 {
        if let Some(v) = self.sobol.as_mut().and_then(SobolPoint::next) {
            return v;
        }
        // 24 high bits give every representable multiple of 2^-24 in [0, 1).
        (self.random.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
    }

    /// Two uniform numbers in [0, 1)², stratified together in a Sobol stream (the pair
    /// starts at an even dimension, so it lies within one group of four).
    #[inline]
    pub fn uniform2(&mut self) -> Vec2 {
        if let Some(s) = self.sobol.as_mut() {
            s.dim = (s.dim + 1) & !1;
        }
        Vec2::new(self.uniform(), self.uniform())
    }

    /// The path reached its scattering vertex `depth` (1 = the first hit): a Sobol stream
    /// moves on to that vertex's dimensions, unless earlier draws went past them already
    /// (never back, so no number is used twice). Independent streams ignore it.
    #[inline]
    pub fn start_vertex(&mut self, depth: u32) {
        if let Some(s) = self.sobol.as_mut() {
            let first = START_DIMENSIONS + VERTEX_DIMENSIONS * depth.saturating_sub(1);
            s.dim = s.dim.max(first);
        }
    }

    /// 64 random bits (from the independent generator, in either mode: for hashing and
    /// choices that are not integration dimensions).
    #[inline]
    pub fn next_u64(&mut self) -> u64 {
        self.random.next_u64()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The first 2^m points of a pixel's Sobol stream put exactly one point in each of the
    /// 2^m cells of every elementary 2D grid (2^a x 2^(m-a)) of its first pair: the
    /// stratification the sequence is chosen for, and which independent numbers lack.
    #[test]
    fn sobol_pairs_are_stratified_and_independent_ones_are_not() {
        let m = 8u32;
        let n = 1u64 << m;
        let points = |sequence| -> Vec<Vec2> {
            (0..n)
                .map(|k| Rng::for_pass(sequence, 7, 1, 42, 1000, k).uniform2())
                .collect()
        };
        let full = |pts: &[Vec2], a: u32| {
            let (nx, ny) = (1u32 << a, 1u32 << (m - a));
            let mut seen = vec![0u32; (nx * ny) as usize];
            for p in pts {
                let (x, y) = ((p.x * nx as f32) as u32, (p.y * ny as f32) as u32);
                seen[(y * nx + x) as usize] += 1;
            }
            seen.iter().all(|&c| c == 1)
        };
        let sobol = points(Sequence::Sobol);
        for a in 0..=m {
            assert!(
                full(&sobol, a),
                "Sobol pair not stratified on 2^{a} x 2^{}",
                m - a
            );
        }
        // 256 independent points fill all 256 cells of a 16x16 grid with probability
        // 256!/256^256 (about 1e-110): this fails only if the stream were not independent.
        assert!(!full(&points(Sequence::Independent), 4));
    }

    /// Every draw lies in [0, 1); a vertex never re-reads a dimension an earlier draw used;
    /// a pair never straddles two groups of four.
    #[test]
    fn dimensions_are_never_reused() {
        let mut rng = Rng::for_pass(Sequence::Sobol, 1, 2, 3, 10, 5);
        let dim = |r: &Rng| r.sobol.as_ref().unwrap().dim;
        rng.uniform();
        assert_eq!(dim(&rng), 1);
        rng.uniform2();
        assert_eq!(dim(&rng), 4, "a pair starts at an even dimension");
        rng.start_vertex(1);
        assert_eq!(dim(&rng), START_DIMENSIONS);
        for _ in 0..5 {
            rng.uniform();
        }
        // Asked again for a vertex it has passed, the stream does not go back.
        rng.start_vertex(1);
        assert_eq!(
            dim(&rng),
            START_DIMENSIONS + 5,
            "a vertex never re-reads dimensions"
        );
        for _ in 0..40 {
            let u = rng.uniform();
            assert!((0.0..1.0).contains(&u));
        }
        // Past the Sobol dimensions the draws are independent and the counter stops there.
        assert_eq!(dim(&rng), SOBOL_DIMENSIONS);
        rng.start_vertex(5);
        assert_eq!(dim(&rng), START_DIMENSIONS + 4 * VERTEX_DIMENSIONS);
        // Past the sequence's points the stream is the independent one of that pass.
        let mut late = Rng::for_pass(Sequence::Sobol, 1, 2, 3, 10, SOBOL_POINTS);
        let mut ind = Rng::for_pass(Sequence::Independent, 1, 2, 3, 10, SOBOL_POINTS);
        assert!(late.sobol.is_none());
        assert_eq!(late.uniform(), ind.uniform());
    }
}
