//! Random number streams. Every pixel (path tracing) and every light path (light tracing)
//! gets its own stream derived from the seed and its index, so an image is reproducible from
//! its seed whatever the number of threads.

use glam::Vec2;
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::{Rng as _, SeedableRng};

/// A random number generator for one sample stream.
pub struct Rng(Xoshiro256PlusPlus);

/// SplitMix64 finaliser: decorrelates nearby stream indices.
#[inline]
fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58476d1ce4e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d049bb133111eb);
    z ^ (z >> 31)
}

impl Rng {
    /// The stream for (`seed`, `domain`, `index`). `domain` separates uses (e.g. the camera
    /// pass from the light pass) so that they never share numbers.
    pub fn new(seed: u64, domain: u64, index: u64) -> Self {
        let s = mix64(
            seed ^ mix64(domain.wrapping_add(0x9e3779b97f4a7c15))
                ^ mix64(index.wrapping_mul(0xd1b54a32d192ed03)),
        );
        Rng(Xoshiro256PlusPlus::seed_from_u64(s))
    }

    /// Uniform in [0, 1).
    #[inline]
    pub fn uniform(&mut self) -> f32 {
        // 24 high bits give every representable multiple of 2^-24 in [0, 1).
        (self.0.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
    }

    #[inline]
    pub fn uniform2(&mut self) -> Vec2 {
        Vec2::new(self.uniform(), self.uniform())
    }

    #[inline]
    pub fn next_u64(&mut self) -> u64 {
        self.0.next_u64()
    }
}
