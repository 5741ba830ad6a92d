//! Pixel reconstruction filters: box (the default of footprint's own scenes), tent and
//! Gaussian (Mitsuba 3's `rfilter` types, so that imported scenes are filtered as Mitsuba
//! filters them).
//!
//! A pixel's value is the filter-weighted mean of the image function over the film:
//! `I_p = ∫ f(x - c_p) L(x) dx / ∫ f(x - c_p) dx`, both integrals over the image rectangle
//! only. That is what Mitsuba's weighted splatting converges to (its samples never leave the
//! image, so a border pixel's filter is cut off and renormalised), and it is what both of our
//! estimators compute:
//!
//! * path tracing samples the raster position of pixel `p` from `f(x - c_p)` restricted to the
//!   image (filter importance sampling, each axis by inverting its cdf), so a sample's weight
//!   is exactly 1;
//! * light tracing splats a film point `x` onto every pixel whose filter covers it, with weight
//!   `f(x - c_p) / ∫_image f(x - c_p) dx`.
//!
//! All three filters are separable, `f(x, y) = g(x) g(y)`. Each 1-D profile `g` is stored as a
//! piecewise-constant density of [`BINS`] bins over `[-radius, radius]` (as pbrt-v4's
//! `FilterSampler` tabulates its filters), which both estimators use, so that sampling and
//! splatting agree exactly.
//!
//! The profiles are Mitsuba 3's as its CPU (`scalar_*`) variants apply them: tent
//! `1 - |x|/r` (radius 1 by default) and Gaussian `exp(-x²/2σ²) - exp(-r²/2σ²)` (σ = 0.5,
//! `r = 4σ`), each read from Mitsuba's 31-step table (`ReconstructionFilter::eval_discretized`:
//! the filter at the inner end of the step `|x| ∈ [k r/31, (k+1) r/31)`). The staircase puts
//! visibly more weight in a tent's tails than the tent itself (about 10% more light bleeds
//! from a bright area light into the next pixel row), so matching Mitsuba's images needs it.
//! A step spans exactly 16 of our bins.

use glam::Vec2;

/// Steps of Mitsuba's tabulated filters over `[0, radius]` (`MI_FILTER_RESOLUTION`).
pub const MITSUBA_STEPS: usize = 31;

/// Bins per axis of the tabulated profile: 16 per Mitsuba step on each side.
pub const BINS: usize = 2 * MITSUBA_STEPS * 16;

/// The filter kinds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FilterKind {
    /// Box of width one pixel.
    Box,
    /// Tent of the given radius in pixels.
    Tent { radius: f32 },
    /// Gaussian with standard deviation `stddev` pixels, cut off at `4 stddev`.
    Gaussian { stddev: f32 },
}

/// A tabulated separable pixel filter.
#[derive(Clone, Debug)]
pub struct PixelFilter {
    pub kind: FilterKind,
    radius: f32,
    /// Normalised density per bin (integrates to 1 over `[-radius, radius]`).
    density: Vec<f32>,
    /// Cumulative distribution at the bin edges, `BINS + 1` entries from 0 to 1.
    cdf: Vec<f32>,
}

impl Default for PixelFilter {
    fn default() -> Self {
        PixelFilter::new(FilterKind::Box)
    }
}

impl PixelFilter {
    pub fn new(kind: FilterKind) -> Self {
        let (radius, smooth): (f32, Box<dyn Fn(f64) -> f64>) = match kind {
            FilterKind::Box => (0.5, Box::new(|_| 1.0)),
            FilterKind::Tent { radius } => {
                let r = radius as f64;
                (radius, Box::new(move |x: f64| (r - x.abs()).max(0.0)))
            }
            FilterKind::Gaussian { stddev } => {
                let s = stddev as f64;
                let r = 4.0 * s;
                let cut = (-(r * r) / (2.0 * s * s)).exp();
                (
                    4.0 * stddev,
                    Box::new(move |x: f64| ((-(x * x) / (2.0 * s * s)).exp() - cut).max(0.0)),
                )
            }
        };
        // Mitsuba's staircase: the profile at the inner end of each of its 31 steps.
        let r = radius as f64;
        let steps = MITSUBA_STEPS as f64;
        let profile = |x: f64| {
            let k = (x.abs() * steps / r).floor();
            if k >= steps {
                0.0
            } else {
                smooth(r * k / steps)
            }
        };
        // Bin masses by 8-point midpoint integration (exact: a step spans whole bins).
        let w = 2.0 * r / BINS as f64;
        let mass: Vec<f64> = (0..BINS)
            .map(|i| {
                let x0 = -r + i as f64 * w;
                (0..8)
                    .map(|k| profile(x0 + (k as f64 + 0.5) * w / 8.0))
                    .sum::<f64>()
                    * w
                    / 8.0
            })
            .collect();
        let total: f64 = mass.iter().sum();
        let mut cdf = Vec::with_capacity(BINS + 1);
        let mut acc = 0.0f64;
        cdf.push(0.0f32);
        for m in &mass {
            acc += m / total;
            cdf.push(acc as f32);
        }
        cdf[BINS] = 1.0;
        let density = mass.iter().map(|m| (m / total / w) as f32).collect();
        PixelFilter {
            kind,
            radius,
            density,
            cdf,
        }
    }

    /// Radius of the support in pixels.
    pub fn radius(&self) -> f32 {
        self.radius
    }

    /// Normalised 1-D profile at offset `x` (pixels from the pixel centre).
    #[inline]
    pub fn eval_1d(&self, x: f32) -> f32 {
        if !(x.abs() < self.radius) {
            return 0.0;
        }
        let b = ((x + self.radius) / (2.0 * self.radius) * BINS as f32) as usize;
        self.density[b.min(BINS - 1)]
    }

    /// Cumulative distribution of the 1-D profile at offset `x`.
    #[inline]
    pub fn cdf_1d(&self, x: f32) -> f32 {
        if x <= -self.radius {
            return 0.0;
        }
        if x >= self.radius {
            return 1.0;
        }
        let t = (x + self.radius) / (2.0 * self.radius) * BINS as f32;
        let b = (t as usize).min(BINS - 1);
        let f = t - b as f32;
        self.cdf[b] + f * (self.cdf[b + 1] - self.cdf[b])
    }

    /// Inverse of [`PixelFilter::cdf_1d`].
    #[inline]
    fn inverse_cdf(&self, u: f32) -> f32 {
        // Largest bin edge with cdf <= u.
        let b = self.cdf.partition_point(|&c| c <= u).clamp(1, BINS) - 1;
        let (c0, c1) = (self.cdf[b], self.cdf[b + 1]);
        let f = if c1 > c0 {
            ((u - c0) / (c1 - c0)).clamp(0.0, 1.0)
        } else {
            0.5
        };
        -self.radius + (b as f32 + f) * (2.0 * self.radius / BINS as f32)
    }

    /// Offset from the centre of pixel `i` of an axis of `n` pixels, sampled from the
    /// profile cut off at the image's edges, with uniform `u`.
    #[inline]
    fn sample_axis(&self, i: u32, n: u32, u: f32) -> f32 {
        let c = i as f32 + 0.5;
        let lo = self.cdf_1d(-c);
        let hi = self.cdf_1d(n as f32 - c);
        let x = self.inverse_cdf(lo + u * (hi - lo));
        // Keep the position on the film despite rounding.
        (c + x).clamp(0.0, n as f32 * (1.0 - f32::EPSILON)) - c
    }

    /// Raster position (pixels) for a camera sample of pixel `(x, y)` on a `width x height`
    /// film, from two uniform numbers.
    #[inline]
    pub fn sample_raster(&self, x: u32, y: u32, width: u32, height: u32, u: Vec2) -> Vec2 {
        if self.kind == FilterKind::Box {
            return Vec2::new(x as f32, y as f32) + u;
        }
        Vec2::new(
            x as f32 + 0.5 + self.sample_axis(x, width, u.x),
            y as f32 + 0.5 + self.sample_axis(y, height, u.y),
        )
    }

    /// Pixels of one axis covered at position `r` (pixels), with their normalised weights
    /// `g(r - c_i) / ∫_0^n g(t - c_i) dt`; calls `f(i, weight)`.
    #[inline]
    fn for_axis(&self, r: f32, n: u32, mut f: impl FnMut(u32, f32)) {
        let lo = (r - self.radius - 0.5).floor().max(0.0) as i64;
        let hi = ((r + self.radius - 0.5).ceil() as i64).min(n as i64 - 1);
        for i in lo..=hi {
            let c = i as f32 + 0.5;
            let g = self.eval_1d(r - c);
            if g > 0.0 {
                let z = self.cdf_1d(n as f32 - c) - self.cdf_1d(-c);
                if z > 0.0 {
                    f(i as u32, g / z);
                }
            }
        }
    }

    /// Calls `f(pixel_index, weight)` for every pixel of a `width x height` film whose filter
    /// covers raster position `raster`; the weights are the light tracer's splat weights.
    #[inline]
    pub fn splat_weights(
        &self,
        raster: Vec2,
        width: u32,
        height: u32,
        mut f: impl FnMut(u32, f32),
    ) {
        if self.kind == FilterKind::Box {
            let x = (raster.x as u32).min(width - 1);
            let y = (raster.y as u32).min(height - 1);
            f(y * width + x, 1.0);
            return;
        }
        let mut xs = [(0u32, 0.0f32); 16];
        let mut nx = 0;
        self.for_axis(raster.x, width, |i, w| {
            if nx < xs.len() {
                xs[nx] = (i, w);
                nx += 1;
            }
        });
        self.for_axis(raster.y, height, |j, wy| {
            for &(i, wx) in &xs[..nx] {
                f(j * width + i, wx * wy);
            }
        });
    }
}
