//! The film: per-pixel accumulation, the splat lists light tracing writes into, the pixel
//! filters ([`filter`]) and image files ([`image_io`]). Every value is checked where it is
//! accumulated: a NaN, infinite or negative sample never reaches a pixel; it is counted and
//! dropped.

pub mod filter;
pub mod image_io;

use crate::film::filter::PixelFilter;
use crate::math::{Rgb, is_valid_rgb, luminance};
use glam::Vec2;

/// A finished image: linear RGB, row-major, top row first.
#[derive(Clone, Debug)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<Rgb>,
}

impl Image {
    pub fn new(width: u32, height: u32) -> Self {
        Image {
            width,
            height,
            pixels: vec![Rgb::ZERO; width as usize * height as usize],
        }
    }

    #[inline]
    pub fn get(&self, x: u32, y: u32) -> Rgb {
        self.pixels[y as usize * self.width as usize + x as usize]
    }

    /// Mean over all pixels.
    pub fn mean(&self) -> Rgb {
        let mut s = [0.0f64; 3];
        for p in &self.pixels {
            s[0] += p.x as f64;
            s[1] += p.y as f64;
            s[2] += p.z as f64;
        }
        let n = self.pixels.len().max(1) as f64;
        Rgb::new((s[0] / n) as f32, (s[1] / n) as f32, (s[2] / n) as f32)
    }

    /// True when every pixel is finite and non-negative.
    pub fn all_valid(&self) -> bool {
        self.pixels.iter().all(|p| is_valid_rgb(*p))
    }
}

/// Statistics of what was accumulated.
#[derive(Clone, Copy, Debug, Default)]
pub struct SampleStats {
    /// Samples dropped because they were NaN, infinite or negative.
    pub rejected: u64,
    /// Largest luminance of one accepted sample.
    pub max_luminance: f32,
}

impl SampleStats {
    pub fn merge(&mut self, o: &SampleStats) {
        self.rejected += o.rejected;
        self.max_luminance = self.max_luminance.max(o.max_luminance);
    }

    /// Checks one sample; returns it when valid, counts and drops it otherwise.
    #[inline]
    pub fn check(&mut self, v: Rgb) -> Option<Rgb> {
        if is_valid_rgb(v) {
            self.max_luminance = self.max_luminance.max(luminance(v));
            Some(v)
        } else {
            self.rejected += 1;
            None
        }
    }
}

/// How camera samples reach the film (both converge to the filter-weighted pixel values of
/// [`filter`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FilmMode {
    /// Splat every sample into all pixels under the filter with the light tracer's weights
    /// `f(x - c_p) / ∫ f(t - c_p) dt` and divide by the sample count: each pixel averages
    /// several samples, and the estimate stays unbiased (camera samples are uniform over the
    /// image, so the normalisation is known).
    Splat,
    /// Splat every sample into all pixels under the filter and divide by the summed filter
    /// weights (Mitsuba 3, pbrt-v3): a ratio estimator, biased by O(1/samples) where the
    /// image varies inside the filter, exact for a constant image.
    Weighted,
    /// Filter importance sampling (pbrt-v4): one sample, one pixel, weight 1; pixels stay
    /// uncorrelated (what denoisers want).
    Fis,
}

impl crate::keyword::Keyword for FilmMode {
    const ALL: &'static [Self] = &[FilmMode::Splat, FilmMode::Weighted, FilmMode::Fis];

    fn name(self) -> &'static str {
        match self {
            FilmMode::Splat => "splat",
            FilmMode::Weighted => "weighted",
            FilmMode::Fis => "fis",
        }
    }

    fn about(self) -> &'static str {
        match self {
            FilmMode::Splat => {
                "Splat every sample into all pixels under the filter with the light tracer's weights `f(x - c_p) / ∫ f(t - c_p) dt` and divide by the sample count: each pixel averages several samples, and the estimate stays unbiased (camera samples are uniform over the image, so the normalisation is known)"
            }
            FilmMode::Weighted => {
                "Splat every sample into all pixels under the filter and divide by the summed filter weights (Mitsuba 3, pbrt-v3): a ratio estimator, biased by O(1/samples) where the image varies inside the filter, exact for a constant image"
            }
            FilmMode::Fis => {
                "Filter importance sampling (pbrt-v4): one sample, one pixel, weight 1; pixels stay uncorrelated (what denoisers want)"
            }
        }
    }
}

/// An accumulation buffer in f64, turned into an [`Image`]: plain sums divided by a count
/// (filter-importance-sampled camera samples, light-path splats), plus filter-weighted
/// sums divided by their summed weights (splatted camera samples).
#[derive(Clone, Debug)]
pub struct Film {
    pub width: u32,
    pub height: u32,
    sum: Vec<[f64; 3]>,
    /// Filter-weighted sums and the summed weights (empty until a weighted splat arrives).
    weighted: Vec<[f64; 4]>,
    pub stats: SampleStats,
}

impl Film {
    pub fn new(width: u32, height: u32) -> Self {
        Film {
            width,
            height,
            sum: vec![[0.0; 3]; width as usize * height as usize],
            weighted: Vec::new(),
            stats: SampleStats::default(),
        }
    }

    /// Adds an already-checked value to pixel `index`.
    #[inline]
    pub fn add_index(&mut self, index: usize, v: Rgb) {
        let s = &mut self.sum[index];
        s[0] += v.x as f64;
        s[1] += v.y as f64;
        s[2] += v.z as f64;
    }

    /// Applies a chunk's splats and merges its statistics.
    pub fn add_splats(&mut self, splats: &SplatList) {
        for &(i, v) in &splats.entries {
            self.add_index(i as usize, v);
        }
        if !splats.weighted.is_empty() && self.weighted.is_empty() {
            self.weighted = vec![[0.0; 4]; self.sum.len()];
        }
        for &(i, v, w) in &splats.weighted {
            let s = &mut self.weighted[i as usize];
            s[0] += (v.x * w) as f64;
            s[1] += (v.y * w) as f64;
            s[2] += (v.z * w) as f64;
            s[3] += w as f64;
        }
        self.stats.merge(&splats.stats);
    }

    /// Adds one value per pixel, computed in parallel by rows: `f(x, y)` returns the value
    /// (checked here) for pixel `(x, y)`.
    pub fn add_per_pixel<F>(&mut self, f: F)
    where
        F: Fn(u32, u32) -> Rgb + Sync,
    {
        use rayon::prelude::*;
        let w = self.width as usize;
        let stats: Vec<SampleStats> = self
            .sum
            .par_chunks_mut(w)
            .enumerate()
            .map(|(y, row)| {
                let mut st = SampleStats::default();
                for (x, s) in row.iter_mut().enumerate() {
                    if let Some(v) = st.check(f(x as u32, y as u32)) {
                        s[0] += v.x as f64;
                        s[1] += v.y as f64;
                        s[2] += v.z as f64;
                    }
                }
                st
            })
            .collect();
        for st in &stats {
            self.stats.merge(st);
        }
    }

    /// Plain sums scaled by `scale`, plus the weighted sums over their weights.
    pub fn to_image(&self, scale: f64) -> Image {
        let weighted = |i: usize| -> [f64; 3] {
            match self.weighted.get(i) {
                Some(w) if w[3] > 0.0 => [w[0] / w[3], w[1] / w[3], w[2] / w[3]],
                _ => [0.0; 3],
            }
        };
        Image {
            width: self.width,
            height: self.height,
            pixels: self
                .sum
                .iter()
                .enumerate()
                .map(|(i, s)| {
                    let w = weighted(i);
                    Rgb::new(
                        (s[0] * scale + w[0]) as f32,
                        (s[1] * scale + w[1]) as f32,
                        (s[2] * scale + w[2]) as f32,
                    )
                })
                .collect(),
        }
    }
}

/// The splats of one chunk of light paths, applied to the film in chunk order so that an
/// image does not depend on how chunks were spread over threads.
#[derive(Clone, Debug, Default)]
pub struct SplatList {
    entries: Vec<(u32, Rgb)>,
    /// Filter-weighted camera samples: pixel, value, filter weight.
    weighted: Vec<(u32, Rgb, f32)>,
    pub stats: SampleStats,
}

impl SplatList {
    /// Adds `v` at raster position `raster` on a `width x height` film, spread over the
    /// pixels `filter` covers there; invalid values are counted and dropped.
    #[inline]
    pub fn splat(&mut self, filter: &PixelFilter, width: u32, height: u32, raster: Vec2, v: Rgb) {
        self.push(filter, width, height, raster, v, false);
    }

    /// `v` spread over the filter's pixels with its weights, or with its weights squared.
    #[inline]
    fn push(
        &mut self,
        filter: &PixelFilter,
        width: u32,
        height: u32,
        raster: Vec2,
        v: Rgb,
        squared: bool,
    ) {
        let Some(v) = self.stats.check(v) else { return };
        if v.max_element() <= 0.0 {
            return;
        }
        let entries = &mut self.entries;
        filter.splat_weights(raster, width, height, |i, w| {
            entries.push((i, v * if squared { w * w } else { w }))
        });
    }

    /// Adds `v`, a squared value (or a second-moment term), at raster position `raster` to
    /// the pixels `filter` covers there, with the filter's weights squared: the second
    /// moment of what [`Self::splat`] adds for the value.
    #[inline]
    pub fn splat_second_moment(
        &mut self,
        filter: &PixelFilter,
        width: u32,
        height: u32,
        raster: Vec2,
        v: Rgb,
    ) {
        self.push(filter, width, height, raster, v, true);
    }

    /// Adds a camera sample `v` taken at raster position `raster` to every pixel the filter
    /// covers there, with the filter's weight, for the weighted mean `Σ w v / Σ w` (the
    /// weights are added even for a zero value; invalid values are counted and dropped).
    #[inline]
    pub fn splat_weighted(
        &mut self,
        filter: &PixelFilter,
        width: u32,
        height: u32,
        raster: Vec2,
        v: Rgb,
    ) {
        let Some(v) = self.stats.check(v) else { return };
        let weighted = &mut self.weighted;
        filter.splat_weights(raster, width, height, |i, w| weighted.push((i, v, w)));
    }

    pub fn len(&self) -> usize {
        self.entries.len() + self.weighted.len()
    }

    pub fn is_empty(&self) -> bool {
        self.entries.is_empty() && self.weighted.is_empty()
    }
}
