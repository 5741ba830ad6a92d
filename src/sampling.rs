//! Warps from the unit square and discrete distributions. Each warp is a pair (or triple):
//! `sample_*` maps uniform numbers to the domain, `*_pdf` gives the density of that mapping
//! in the measure named by the function (per steradian for directions).

use crate::math::{INV_4PI, INV_PI, PI, safe_sqrt, sin_cos_quarter, sin_cos_turns};
use glam::{Vec2, Vec3};

/// Concentric mapping of the unit square to the unit disc (Shirley & Chiu 1997).
#[inline]
pub fn sample_concentric_disk(u: Vec2) -> Vec2 {
    let o = 2.0 * u - Vec2::ONE;
    if o.x == 0.0 && o.y == 0.0 {
        return Vec2::ZERO;
    }
    // θ = (π/4)(y/x), or π/2 - (π/4)(x/y) whose cosine and sine are the sine and cosine of
    // (π/4)(x/y): either way one angle of at most π/4.
    if o.x.abs() > o.y.abs() {
        let (sin, cos) = sin_cos_quarter((PI / 4.0) * (o.y / o.x));
        o.x * Vec2::new(cos, sin)
    } else {
        let (sin, cos) = sin_cos_quarter((PI / 4.0) * (o.x / o.y));
        o.y * Vec2::new(sin, cos)
    }
}

/// Cosine-weighted direction on the hemisphere around +z.
#[inline]
pub fn sample_cosine_hemisphere(u: Vec2) -> Vec3 {
    let d = sample_concentric_disk(u);
    let z = safe_sqrt(1.0 - d.x * d.x - d.y * d.y);
    Vec3::new(d.x, d.y, z)
}

/// Density per steradian of [`sample_cosine_hemisphere`] at a direction with cosine `cos_theta`.
#[inline]
pub fn cosine_hemisphere_pdf(cos_theta: f32) -> f32 {
    cos_theta.max(0.0) * INV_PI
}

/// Uniform direction on the unit sphere.
#[inline]
pub fn sample_uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = safe_sqrt(1.0 - z * z);
    let (sin_phi, cos_phi) = sin_cos_turns(u.y);
    Vec3::new(r * cos_phi, r * sin_phi, z)
}

/// Density per steradian of [`sample_uniform_sphere`].
#[inline]
pub fn uniform_sphere_pdf() -> f32 {
    INV_4PI
}

/// Uniform direction in the cone around +z with half-angle cosine `cos_max`.
#[inline]
pub fn sample_uniform_cone(u: Vec2, cos_max: f32) -> Vec3 {
    let cos_t = 1.0 - u.x * (1.0 - cos_max);
    let sin_t = safe_sqrt(1.0 - cos_t * cos_t);
    let (sin_phi, cos_phi) = sin_cos_turns(u.y);
    Vec3::new(sin_t * cos_phi, sin_t * sin_phi, cos_t)
}

/// Density per steradian of [`sample_uniform_cone`].
#[inline]
pub fn uniform_cone_pdf(cos_max: f32) -> f32 {
    1.0 / (2.0 * PI * (1.0 - cos_max))
}

/// Uniform barycentric coordinates `(b1, b2)` on a triangle (Heitz 2019, low distortion).
#[inline]
pub fn sample_uniform_triangle(u: Vec2) -> (f32, f32) {
    let (b0, b1);
    if u.x < u.y {
        b0 = u.x / 2.0;
        b1 = u.y - b0;
    } else {
        b1 = u.y / 2.0;
        b0 = u.x - b1;
    }
    (b1, 1.0 - b0 - b1)
}

/// A discrete distribution over `n` items proportional to non-negative weights.
#[derive(Clone, Debug, Default)]
pub struct Distribution1D {
    /// Cumulative distribution, `cdf[0] = 0`, `cdf[n] = 1`.
    cdf: Vec<f32>,
    pmf: Vec<f32>,
    total: f64,
    /// A guide table over `cdf` (the cutpoint method, Chen & Asau 1974): with `m =
    /// guide.len() - 1` cells, a power of two, `guide[k]` is the last index `i` with
    /// `cdf[i] <= k / m`. A number `u` of cell `k = floor(u m)` then has its item between
    /// `guide[k]` and `guide[k + 1]`, and the search is over that short stretch of `cdf`
    /// instead of all of it: one or two cache lines where the binary search over a large
    /// distribution (a scene's tens of thousands of emitting triangles) misses the cache at
    /// every level. Empty for small distributions, which search all of `cdf`.
    guide: Vec<u32>,
}

/// Distributions of at least this many items get a guide table ([`Distribution1D::guide`]).
const GUIDE_MIN_ITEMS: usize = 64;

/// The guide table of `cdf` (non-decreasing, `cdf[0] = 0`) with about one cell per two
/// items: `k / m` is exact in `f32` for a power of two `m` up to `2^24`.
fn guide_table(cdf: &[f32]) -> Vec<u32> {
    let n = cdf.len() - 1;
    if n < GUIDE_MIN_ITEMS {
        return Vec::new();
    }
    let m = (n.next_power_of_two() / 2).min(1 << 24);
    let mut guide = Vec::with_capacity(m + 1);
    let mut i = 0usize;
    for k in 0..=m {
        let t = k as f32 / m as f32;
        while i + 1 < cdf.len() && cdf[i + 1] <= t {
            i += 1;
        }
        guide.push(i as u32);
    }
    guide
}

impl Distribution1D {
    /// Builds the distribution; negative or non-finite weights count as zero. Returns `None`
    /// when every weight is zero.
    pub fn new(weights: &[f32]) -> Option<Self> {
        let clean: Vec<f64> = weights
            .iter()
            .map(|&w| {
                if w.is_finite() && w > 0.0 {
                    w as f64
                } else {
                    0.0
                }
            })
            .collect();
        let total: f64 = clean.iter().sum();
        if total <= 0.0 || weights.is_empty() {
            return None;
        }
        let mut cdf = Vec::with_capacity(clean.len() + 1);
        cdf.push(0.0f32);
        let mut acc = 0.0f64;
        for &w in &clean {
            acc += w;
            cdf.push((acc / total) as f32);
        }
        *cdf.last_mut().unwrap() = 1.0;
        let pmf = clean.iter().map(|&w| (w / total) as f32).collect();
        let guide = guide_table(&cdf);
        Some(Distribution1D {
            cdf,
            pmf,
            total,
            guide,
        })
    }

    pub fn len(&self) -> usize {
        self.pmf.len()
    }

    pub fn is_empty(&self) -> bool {
        self.pmf.is_empty()
    }

    /// Sum of the (cleaned) weights.
    pub fn total(&self) -> f64 {
        self.total
    }

    /// Chooses an item; returns it with its probability. Items of zero probability are never
    /// returned.
    #[inline]
    pub fn sample(&self, u: f32) -> (usize, f32) {
        // The last index with cdf[i] <= u (cdf[i] <= u < cdf[i+1]).
        let n = self.pmf.len();
        let mut i = self.last_at_or_below(u).min(n - 1);
        // Skip zero-probability items that rounding could select.
        while self.pmf[i] == 0.0 && i + 1 < n {
            i += 1;
        }
        while self.pmf[i] == 0.0 && i > 0 {
            i -= 1;
        }
        (i, self.pmf[i])
    }

    /// The last index `i` with `cdf[i] <= u` (0 when there is none: a negative or NaN `u`),
    /// by the guide table where there is one: the same index as the search over all of
    /// `cdf` (`tests::the_guide_table_finds_what_the_whole_search_finds`).
    #[inline]
    fn last_at_or_below(&self, u: f32) -> usize {
        let whole = |cdf: &[f32]| cdf.partition_point(|&c| c <= u).saturating_sub(1);
        if self.guide.is_empty() || !(u >= 0.0) {
            return whole(&self.cdf);
        }
        let m = self.guide.len() - 1;
        // `u m` is exact (m a power of two), so `k / m <= u < (k + 1) / m` for `u` in
        // [0, 1); the clamp takes `u >= 1` to the last cell, whose bounds still hold.
        let k = ((u * m as f32) as usize).min(m - 1);
        let (lo, hi) = (self.guide[k] as usize, self.guide[k + 1] as usize);
        // cdf[lo] <= k / m: the answer is lo or one of the indices after it up to hi.
        lo + self.cdf[lo + 1..=hi.max(lo)].partition_point(|&c| c <= u)
    }

    /// [`Distribution1D::sample`], and `u` stretched back to `[0, 1)` within the chosen
    /// item's interval, `(u - cdf_i) / pmf_i`: a uniform number independent of the choice,
    /// for reuse (pbrt's "sample remapping"). It keeps about `24 + log2(pmf_i)` of `u`'s 24
    /// bits.
    #[inline]
    pub fn sample_remapped(&self, u: f32) -> (usize, f32, f32) {
        let (i, pmf) = self.sample(u);
        let rest = ((u - self.cdf[i]) / pmf).clamp(0.0, 1.0 - f32::EPSILON / 2.0);
        (i, pmf, rest)
    }

    /// The least probability of an item that can be chosen (items of weight zero aside).
    pub fn min_pmf(&self) -> f32 {
        self.pmf
            .iter()
            .copied()
            .filter(|&p| p > 0.0)
            .fold(1.0, f32::min)
    }

    #[inline]
    pub fn pmf(&self, i: usize) -> f32 {
        self.pmf[i]
    }
}

#[cfg(test)]
mod tests {
    use super::Distribution1D;
    use crate::rng::Rng;

    /// The guide table's search returns the index the search over the whole cdf returns,
    /// for every kind of `u` (uniform, on and beside every cdf value and cell boundary, 0,
    /// 1, beyond, negative, NaN) over distributions with runs of empty items, one dominant
    /// item and weights spanning twelve decades.
    #[test]
    fn the_guide_table_finds_what_the_whole_search_finds() {
        let mut rng = Rng::new(3, 1, 4);
        for (case, n) in [64usize, 65, 100, 1000, 4097].into_iter().enumerate() {
            let weights: Vec<f32> = (0..n)
                .map(|i| match case {
                    0 => 1.0,
                    1 if i == 7 => 1e6,
                    1 => 1.0,
                    _ if i % 5 < 2 => 0.0,
                    _ => 10f32.powf(12.0 * rng.uniform() - 6.0),
                })
                .collect();
            let d = Distribution1D::new(&weights).unwrap();
            assert!(!d.guide.is_empty(), "{n} items have a guide table");
            let whole = |u: f32| d.cdf.partition_point(|&c| c <= u).saturating_sub(1);
            let m = (d.guide.len() - 1) as f32;
            let mut us = vec![
                0.0,
                1.0,
                1.5,
                f32::INFINITY,
                -0.25,
                f32::NAN,
                f32::MIN_POSITIVE,
            ];
            us.extend((0..20_000).map(|_| rng.uniform()));
            for &c in &d.cdf {
                us.extend([c, c.next_down(), c.next_up()]);
            }
            for k in 0..=d.guide.len() {
                let b = k as f32 / m;
                us.extend([b, b.next_down(), b.next_up()]);
            }
            for u in us {
                assert_eq!(d.last_at_or_below(u), whole(u), "{n} items, u = {u:e}");
            }
        }
        let small = Distribution1D::new(&[1.0; 63]).unwrap();
        assert!(small.guide.is_empty());
    }

    /// The stretched number is uniform within each choice and independent of it: `n` evenly
    /// spaced `u` put `n pmf_i` numbers in item `i`, and those fall evenly into ten bins of
    /// `[0, 1)` (each bin within one of its share, the rounding at the interval's ends).
    #[test]
    fn remapped_numbers_are_uniform_within_each_choice() {
        let d = Distribution1D::new(&[1.0, 3.0, 0.0, 4.0]).unwrap();
        let n = 80_000usize;
        let mut bins = [[0usize; 10]; 4];
        for k in 0..n {
            let u = (k as f32 + 0.5) / n as f32;
            let (i, pmf, rest) = d.sample_remapped(u);
            assert_eq!(pmf, d.pmf(i));
            assert!((0.0..1.0).contains(&rest), "{rest}");
            bins[i][(rest * 10.0) as usize] += 1;
        }
        assert_eq!(bins[2], [0; 10], "an item of weight zero is never chosen");
        for (i, b) in bins.iter().enumerate() {
            let expected = n as f32 * d.pmf(i) / 10.0;
            for &c in b {
                assert!((c as f32 - expected).abs() <= 1.0, "item {i}: {b:?}");
            }
        }
        assert_eq!(d.min_pmf(), 0.125);
    }
}
