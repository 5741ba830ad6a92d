//! Guided splitting in the pilot: a splitting direction piloted with passes of its own
//! ([`SplitPilot`]), and what splitting does to its noise ([`split_ratio`]).

use super::metric::Metric;
use super::params::FOLDS;
use super::pilot::{Moments, passes_until};
use crate::maps::Guidance;
use crate::method::Method;
use crate::render::{RenderOptions, independent_pass};
use footprint::scene::Scene;
use std::time::Instant;

/// A guided path or light tracer piloted with passes of its own, split where its guide
/// expects more light as it renders (guided splitting): the combined image does not split,
/// so its pt and lt layers measure these directions unsplit, and on door light tracing
/// gains 1.7x from splitting that the layers cannot show (docs/measurements/sweeps.md,
/// "Guided Russian roulette and splitting"): unsplit, they predict `lt-footprint` and
/// `pt-footprint` near a tie, about 3.3x apart rendered (docs/measurements/door-desk.md).
pub(super) struct SplitPilot {
    pub(super) image: Moments,
    /// The fastest pass's tracing time (other jobs on the machine only slow a pass down).
    pub(super) seconds: f64,
}

impl SplitPilot {
    /// Runs passes of `method` until `until` (at least `min_passes`, at most
    /// [`MAX_BATCHES`](super::MAX_BATCHES)), each with its own seed from `stream`.
    pub(super) fn run(
        scene: &Scene,
        opts: &RenderOptions,
        method: Method,
        g: &Guidance,
        until: Option<Instant>,
        min_passes: usize,
        stream: u64,
    ) -> Self {
        let mut image = Moments::new(scene.camera.pixel_count());
        let mut seconds = f64::INFINITY;
        for b in passes_until(0, min_passes, until) {
            let r = independent_pass(scene, opts, method, g, stream ^ (b as u64 + 1), None);
            image.add(&r.image);
            seconds = seconds.min(r.timings.tracing.as_secs_f64());
        }
        SplitPilot { image, seconds }
    }

    /// The relative variance of one pass, each pixel weighed with the mean of `folds`'
    /// weights (those the unsplit layer's folds are weighed with: the two are compared
    /// under the same weights, see [`predict_all`](super::predict::predict_all)); `None`
    /// with fewer than two passes.
    pub(super) fn pass_variance(&self, folds: &[Metric; FOLDS]) -> Option<f64> {
        let m = &self.image;
        if m.n < 2 {
            return None;
        }
        let mut var = 0.0f64;
        for i in 0..m.sum.len() {
            for c in 0..3 {
                let w = folds.iter().map(|f| f.weight[i][c]).sum::<f64>() / FOLDS as f64;
                var += m.var(i, c) * w;
            }
        }
        let (scale, n) = (folds[0].scale, (3 * m.sum.len()).max(1) as f64);
        Some(var / (scale * scale) / n)
    }
}

/// What guided splitting of at most `branches` branches does to a direction's per-pass
/// noise: `split / unsplit`, the split pilot's relative variance over the unsplit layer's
/// under the same weights (a ratio, so that what the weights' own noise adds to both
/// cancels: measured alone, with `R` from the combined pilots, door's split `pt-footprint`
/// passes read several times the unsplit layer's noise where splitting changes nothing),
/// clamped to `[1 / branches, 1]` against the noise of a few passes: a pass of more
/// branches is never noisier, and one split into n branches divides a pass's variance by at
/// most n (all of it arising after the split). Nested splits at later vertices could divide
/// it by more; the bound then only makes the prediction cautious. 1 when the layer measured
/// no variance.
pub(super) fn split_ratio(unsplit: f64, split: f64, branches: u32) -> f64 {
    if unsplit > 0.0 && split.is_finite() {
        (split / unsplit).clamp(1.0 / branches.max(1) as f64, 1.0)
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::auto::pilot::test_image as image;
    use rand_xoshiro::Xoshiro256PlusPlus;
    use rand_xoshiro::rand_core::{Rng, SeedableRng};

    /// The splitting ratio is the measured one where it is possible (between `1 / n` and
    /// 1), and clamped where noise put it outside: never below `1 / n`, never above 1.
    #[test]
    fn split_ratio_is_measured_within_what_n_branches_can_do() {
        assert_eq!(split_ratio(100.0, 40.0, 4), 0.4);
        assert_eq!(split_ratio(100.0, 10.0, 4), 0.25);
        assert_eq!(split_ratio(100.0, 300.0, 4), 1.0);
        assert_eq!(split_ratio(100.0, 40.0, 1), 1.0);
        assert_eq!(split_ratio(0.0, 40.0, 4), 1.0);
        assert_eq!(split_ratio(100.0, f64::NAN, 4), 1.0);
    }

    /// A split pilot's pass variance is the per-pixel variance weighed with the mean of the
    /// folds' weights, over the scale squared: 400 passes of uniform noise of variance 4
    /// (fixed seed) on 64 pixels, the folds' weights 1, 2, 3 and 6 (mean 3), scale 2, give
    /// 4 * 3 / 4 = 3. The sample variance of 400 passes has a relative standard error of
    /// `sqrt((kurtosis - 1) / n)` = `sqrt(0.8 / 400)` = 4.5% per pixel (uniform noise:
    /// kurtosis 1.8), 0.56% over 64 independent pixels (the channels are equal); the bound is
    /// 5 of those, 2.8% (one fold's weights alone would give 1 or 2: off by a third or more).
    #[test]
    fn split_pilot_weighs_its_noise_with_the_folds_mean_weights() {
        let (w, h) = (8usize, 8usize);
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(11);
        let mut sp = SplitPilot {
            image: Moments::new(w * h),
            seconds: 0.1,
        };
        for _ in 0..400 {
            let noise: Vec<f32> = (0..w * h)
                .map(|_| {
                    let u = (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
                    (5.0 + 2.0 * 3f64.sqrt() * (2.0 * u - 1.0)) as f32
                })
                .collect();
            sp.image.add(&image(w, h, |i| noise[i]));
        }
        let folds: [Metric; FOLDS] = std::array::from_fn(|k| Metric {
            scale: 2.0,
            weight: vec![[[1.0, 2.0, 3.0, 6.0][k]; 3]; w * h],
        });
        let v = sp.pass_variance(&folds).expect("two passes or more");
        assert!((v / 3.0 - 1.0).abs() < 0.028, "{v}");
        let one = SplitPilot {
            image: Moments::new(w * h),
            seconds: 0.1,
        };
        assert!(one.pass_variance(&folds).is_none());
    }
}
