//! The metric's weights `1 / (R² + 0.01)` (`compare`'s relative MSE) as the pilot reads
//! them: `R` pooled over the pilots by their noise ([`Pooled`]), read over a window widened
//! where it is noisy ([`Metric`], [`crate::window`]), and cross-fitted per fold
//! ([`fold_metrics`]).

use super::params::FOLDS;
use super::pilot::{Moments, Pilot};
use footprint::Rgb;
use footprint::math::luminance;

/// The image as several pilots estimate it together, for the metric's `R`: each pilot's
/// mean weighed by its passes over its per-pass variance (inverse-variance pooling, one
/// weight per pilot, image-wide). Pooling passes alike would let the noisiest pilot set
/// `R`: on door the unguided pilot's passes, each far noisier than a guided pilot's, would
/// outweigh them, and the window `R` is read over would widen until it blurred the light
/// the guided passes carry (`lt-footprint` predicted above its error). Weights per pilot,
/// not per pixel: a pixel's own variance rises with its bright samples, and weighing by it
/// would pull `R` down where rare paths carry the light.
pub(super) struct Pooled {
    pub(super) mean: Vec<[f64; 3]>,
    /// The variance of `mean`.
    pub(super) var_of_mean: Vec<[f64; 3]>,
}

impl Pooled {
    /// From `parts` (each pilot's passes; those without passes are left out).
    pub(super) fn new(parts: &[&Moments]) -> Self {
        let npix = parts.first().map_or(0, |m| m.sum.len());
        let parts: Vec<&Moments> = parts.iter().copied().filter(|m| m.n > 0).collect();
        // Each pilot's per-pass variance, averaged over pixels and channels; a single pass
        // (or a variance that is not a finite positive number) has none to measure, and the
        // pilot counts as the noisiest of the others, at every pixel.
        let per_pass: Vec<Option<f64>> = parts
            .iter()
            .map(|m| {
                let v: f64 = (0..npix)
                    .map(|i| (0..3).map(|c| m.var(i, c)).sum::<f64>())
                    .sum();
                let v = v / (3 * npix.max(1)) as f64;
                (m.n > 1 && v.is_finite() && v > 0.0).then_some(v)
            })
            .collect();
        let noisiest = per_pass.iter().flatten().fold(0.0f64, |a, &b| a.max(b));
        // Weights relative to the noisiest pilot's (so a pilot that measured almost no
        // variance weighs at most 1e9 of it and none overflows); all alike when none
        // measured any.
        let weight: Vec<f64> = parts
            .iter()
            .zip(&per_pass)
            .map(|(m, v)| match (v, noisiest > 0.0) {
                (Some(v), true) => m.n as f64 * noisiest / v.max(1e-9 * noisiest),
                _ => m.n as f64,
            })
            .collect();
        let total: f64 = weight.iter().sum();
        let mut mean = vec![[0.0; 3]; npix];
        let mut var_of_mean = vec![[0.0; 3]; npix];
        for ((m, a), v) in parts.iter().zip(&weight).zip(&per_pass) {
            let (a, n) = (a / total, m.n as f64);
            for i in 0..npix {
                for c in 0..3 {
                    let var = match v {
                        Some(_) => m.var(i, c),
                        None => noisiest,
                    };
                    mean[i][c] += a * m.mean(i, c);
                    var_of_mean[i][c] += a * a * var / n;
                }
            }
        }
        Pooled { mean, var_of_mean }
    }
}

/// The metric's weights: `compare`'s relative MSE, `1 / (R² + 0.01)` per pixel and channel
/// after dividing by `scale`, the reference's mean luminance.
pub(super) struct Metric {
    pub(super) scale: f64,
    pub(super) weight: Vec<[f64; 3]>,
}

impl Metric {
    /// The image's mean luminance, what the metric divides by, from the passes of `parts`
    /// (pilots of the same image) pooled alike.
    pub(super) fn mean_luminance(parts: &[&Moments]) -> f64 {
        let npix = parts.first().map_or(0, |m| m.sum.len());
        let n: usize = parts.iter().map(|m| m.n).sum();
        let mut m = Rgb::ZERO;
        for i in 0..npix {
            let [r, g, b] = [0, 1, 2].map(|c| {
                let sum = parts.iter().fold(0.0f64, |s, p| s + p.sum[i][c]);
                (sum / n as f64) as f32
            });
            m += Rgb::new(r, g, b);
        }
        (luminance(m / npix as f32) as f64).max(1e-20)
    }

    /// The weights from `reference`, the image divided by `scale`: `R` read over a window
    /// widened where the pilots' mean is noisy ([`crate::window`]).
    pub(super) fn with_scale(width: u32, reference: &Pooled, scale: f64) -> Self {
        Self::with_noise(width, &reference.mean, &reference.var_of_mean, scale)
    }

    /// As [`Metric::with_scale`], the window sized by `var_of_mean` (another estimate's
    /// noise than `mean`'s, [`fold_metrics`]).
    pub(super) fn with_noise(
        width: u32,
        mean: &[[f64; 3]],
        var_of_mean: &[[f64; 3]],
        scale: f64,
    ) -> Self {
        let means = crate::window::window_means(
            width as usize,
            mean.len(),
            &|i, c| mean[i][c],
            &|i, c| var_of_mean[i][c],
            0.1 * scale,
        );
        let weight = means
            .iter()
            .map(|acc| {
                acc.map(|a| {
                    let r = a / scale;
                    1.0 / (r * r + 0.01)
                })
            })
            .collect();
        Metric { scale, weight }
    }

    /// `a - b` (per-pass means of two second-moment layers) in the metric's units, per pixel
    /// and channel: summed signed over the image and clamped once (noise alone adds
    /// nothing); 0 without layers.
    pub(super) fn excess(&self, a: &Moments, b: &Moments) -> f64 {
        if a.n == 0 || b.n == 0 {
            return 0.0;
        }
        let mut sum = 0.0f64;
        for (i, w) in self.weight.iter().enumerate() {
            for (c, w) in w.iter().enumerate() {
                sum += (a.mean(i, c) - b.mean(i, c)) * w;
            }
        }
        (sum / (self.scale * self.scale) / (3 * self.weight.len()) as f64).max(0.0)
    }
}

/// The weights of each fold of `pilot` ([`FOLDS`]): `R` from `base` (the other pilots'
/// combined images) and the pilot's own passes but the fold's, so that no pass is weighed
/// with an `R` its own noise raised; but the window `R` is read over is sized by the noise
/// of every pass, the fold's included. Where light arrives by rare bright paths, the folds
/// without one see a dim, smooth image and a small window, which alone would weigh the fold
/// holding it with `1 / (R² + 0.01)` of a near-zero `R` (on door, `lt-footprint` would be
/// predicted well above its error and ranked behind `pt-footprint`).
pub(super) fn fold_metrics(
    width: u32,
    base: &[&Moments],
    pilot: &Pilot,
    scale: f64,
) -> [Metric; FOLDS] {
    let mut every = base.to_vec();
    every.push(&pilot.layers[0]);
    let noise = Pooled::new(&every).var_of_mean;
    std::array::from_fn(|k| {
        let mut own = pilot.layers[0].clone();
        let fold = &pilot.folds[k][0];
        if fold.n < own.n {
            own.remove(fold);
        }
        let mut parts = base.to_vec();
        parts.push(&own);
        Metric::with_noise(width, &Pooled::new(&parts).mean, &noise, scale)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::auto::pilot::test_image as image;
    use footprint::film::Image;
    use rand_xoshiro::Xoshiro256PlusPlus;
    use rand_xoshiro::rand_core::{Rng, SeedableRng};

    /// A fold is not weighed with the `R` of passes that missed its rare light. A 64x64
    /// image: the left half a constant 1 in every pass, the right half dark but for one
    /// bright sample (50) at one pixel in pass 0, which lies in fold 0. The other passes see
    /// zeros there, so a window sized by their noise alone stays 3x3 and reads `R` = 0: the
    /// fold's bright sample weighed 100 (`1 / 0.01`). Sized by every pass, the window grows
    /// until its standard error is small and reaches the lit half: a weight of at most 20
    /// (`R` about 0.24, its radius-16 window a quarter lit).
    #[test]
    fn a_fold_is_weighed_with_a_window_sized_by_every_pass() {
        let (w, h, n) = (64usize, 64usize, 8usize);
        let bright = 32 * w + 40;
        let mut pilot = Pilot::new(w * h);
        for pass in 0..n {
            let img = image(w, h, |i| {
                if i % w < w / 2 {
                    1.0
                } else if i == bright && pass == 0 {
                    50.0
                } else {
                    0.0
                }
            });
            pilot.layers[0].add(&img);
            pilot.folds[pass % FOLDS][0].add(&img);
        }
        let folds = fold_metrics(w as u32, &[], &pilot, 1.0);
        let weight = folds[0].weight[bright][0];
        assert!(weight < 20.0, "the bright sample's weight {weight}");
        // The other folds hold the sample in their `R`: a small weight too.
        assert!(folds[1].weight[bright][0] < 20.0);
    }

    /// The metric's `R` widens its window where the pilot's mean is noisy and keeps 3x3
    /// where it is not. A 64x64 image: the left half a constant 1 from passes that agree,
    /// the right half 0.5 on average from passes alternating 0 and 1, with one pixel whose
    /// first pass read 160 (a firefly: a mean of 20). A 3x3 window would read R = 2.7
    /// beside the firefly (a weight 25x too small); the widened window reads close to 0.5.
    /// Left of the edge the weight is the constant's.
    #[test]
    fn r_widens_its_window_where_the_pilot_is_noisy() {
        let (w, h, n) = (64usize, 64usize, 8usize);
        let mut m = Moments::new(w * h);
        let spike = 40 * w + 48;
        for pass in 0..n {
            let pixels = (0..w * h)
                .map(|i| {
                    let v = if i % w < w / 2 {
                        1.0
                    } else if i == spike {
                        if pass == 0 { 20.0 * n as f32 } else { 0.0 }
                    } else {
                        ((pass + i) % 2) as f32
                    };
                    Rgb::splat(v)
                })
                .collect();
            m.add(&Image {
                width: w as u32,
                height: h as u32,
                pixels,
            });
        }
        let metric = Metric::with_scale(w as u32, &Pooled::new(&[&m]), 1.0);
        let r_of = |i: usize| (1.0 / metric.weight[i][0] - 0.01).max(0.0).sqrt();
        // Beside the firefly.
        let r = r_of(spike + 1);
        assert!((r - 0.5).abs() < 0.15, "R beside the firefly {r}");
        // In the constant half, away from the edge: the constant.
        let r = r_of(20 * w + 10);
        assert!((r - 1.0).abs() < 1e-9, "R of the constant {r}");
    }

    /// Two pilots of the same image (every pixel 1): 20 passes with per-pass noise of
    /// standard deviation 3, and 5 passes with 0.3. Pooled by inverse variance, the mean's
    /// standard error is `1 / sqrt(20 / 9 + 5 / 0.09)` = 0.132 per pixel; pooled pass by
    /// pass (the alternative), `sqrt(20 * 9 + 5 * 0.09) / 25` = 0.537. Over 256 pixels of
    /// independent noise (fixed seed) the root-mean-square error has a relative standard
    /// deviation of about `1 / sqrt(2 * 256)` = 4.4%, so 1.2x 0.132 (4.5 of those) bounds
    /// the first and lies far below the second.
    #[test]
    fn pooled_weighs_each_pilot_by_its_noise() {
        let (w, h) = (16usize, 16usize);
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(7);
        // `passes` passes of every pixel 1 plus uniform noise of standard deviation `sd`
        // (half-width sd * sqrt(3)).
        let mut pilot = |passes: usize, sd: f64| {
            let mut m = Moments::new(w * h);
            for _ in 0..passes {
                let pixels = (0..w * h)
                    .map(|_| {
                        let u = (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
                        Rgb::splat((1.0 + sd * 3f64.sqrt() * (2.0 * u - 1.0)) as f32)
                    })
                    .collect();
                m.add(&Image {
                    width: w as u32,
                    height: h as u32,
                    pixels,
                });
            }
            m
        };
        let (a, b) = (pilot(20, 3.0), pilot(5, 0.3));
        let pooled = Pooled::new(&[&a, &b]);
        let rms = |mean: &dyn Fn(usize) -> f64| {
            ((0..w * h).map(|i| (mean(i) - 1.0).powi(2)).sum::<f64>() / (w * h) as f64).sqrt()
        };
        let by_noise = rms(&|i| pooled.mean[i][0]);
        let by_pass = rms(&|i| (a.sum[i][0] + b.sum[i][0]) / 25.0);
        assert!(
            by_noise < 1.2 * 0.132,
            "pooled by noise: rms error {by_noise}"
        );
        assert!(
            by_pass > 2.0 * by_noise,
            "pooled by pass {by_pass}, by noise {by_noise}"
        );
        // The variance it reports is the pooled mean's, 0.132² on average (per-pixel sample
        // variances of 5 uniform passes: a relative standard deviation of about 0.5 each,
        // 0.03 over 256 pixels; 0.15 is 5 of those).
        let reported = (0..w * h).map(|i| pooled.var_of_mean[i][0]).sum::<f64>() / (w * h) as f64;
        assert!(
            (reported / (0.132 * 0.132) - 1.0).abs() < 0.15,
            "reported {reported}"
        );
    }
}
