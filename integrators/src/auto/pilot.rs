//! The pilot's passes: per-pixel running moments of each layer ([`Moments`]), a pilot's
//! passes of one combined image dealt to folds ([`Pilot`], [`pilot_passes`]) while its
//! time lasts ([`passes_until`]), the time of one pass of a method as it renders
//! ([`pass_seconds`]) and of the particle passes of its maps ([`particle_pass_seconds`]).
//! See the module doc of [`crate::auto`] for what they measure.

use super::params::{FOLDS, MAX_BATCHES, PROBE_SHARE};
use crate::maps::{Guidance, needed_passes};
use crate::method::Method;
use crate::moments;
use crate::passes::{CHUNK_PATHS, PassSettings, light_pass, view_pass};
use crate::render::{
    RenderOptions, RenderResult, StopRule, independent_pass, pass_settings, render_prepared,
};
use footprint::film::Image;
use footprint::guide::sampler::GuidedSampler;
use footprint::scene::Scene;
use footprint::settings::GuideParams;
use std::time::{Duration, Instant};

/// Per-pixel, per-channel running sums of a layer over pilot passes.
#[derive(Clone)]
pub(super) struct Moments {
    pub(super) sum: Vec<[f64; 3]>,
    pub(super) sum2: Vec<[f64; 3]>,
    pub(super) n: usize,
}

impl Moments {
    pub(super) fn new(npix: usize) -> Self {
        Moments {
            sum: vec![[0.0; 3]; npix],
            sum2: vec![[0.0; 3]; npix],
            n: 0,
        }
    }

    pub(super) fn add(&mut self, img: &Image) {
        self.add_pass(img.pixels.iter().map(|p| [0, 1, 2].map(|c| p[c] as f64)));
    }

    /// Adds one pass whose pixels are `values`.
    fn add_pass(&mut self, values: impl Iterator<Item = [f64; 3]>) {
        for ((s, s2), x) in self.sum.iter_mut().zip(&mut self.sum2).zip(values) {
            for c in 0..3 {
                s[c] += x[c];
                s2[c] += x[c] * x[c];
            }
        }
        self.n += 1;
    }

    /// Takes out the passes of `o` (a part of these).
    pub(super) fn remove(&mut self, o: &Moments) {
        let pairs = self.sum.iter_mut().zip(&mut self.sum2);
        for ((s, s2), (os, os2)) in pairs.zip(o.sum.iter().zip(&o.sum2)) {
            for c in 0..3 {
                s[c] -= os[c];
                s2[c] -= os2[c];
            }
        }
        self.n -= o.n;
    }

    /// Adds `a - b` pixel by pixel.
    pub(super) fn add_difference(&mut self, a: &Image, b: &Image) {
        let pix = a.pixels.iter().zip(&b.pixels);
        self.add_pass(pix.map(|(pa, pb)| [0, 1, 2].map(|c| pa[c] as f64 - pb[c] as f64)));
    }

    pub(super) fn mean(&self, i: usize, c: usize) -> f64 {
        self.sum[i][c] / self.n as f64
    }

    /// Per-pass variance (unbiased).
    pub(super) fn var(&self, i: usize, c: usize) -> f64 {
        let n = self.n as f64;
        let m = self.sum[i][c] / n;
        ((self.sum2[i][c] - n * m * m) / (n - 1.0)).max(0.0)
    }
}

/// The pilot's passes of the combined image of `guide` (`bsdf` or a guide with maps):
/// moments of the combined, pt and lt layers and of the second-moment layers (pt's and lt's
/// pass times are measured apart, [`pass_seconds`]; the combined image's by the pilot's
/// first passes, [`TIMED_PASSES`](super::TIMED_PASSES)).
pub(super) struct Pilot {
    pub(super) layers: [Moments; 3],
    /// Moments of each layer less the combined layer of the same pass: the noise of a
    /// difference of two estimates from the same paths (they are correlated).
    pub(super) diffs: [Moments; 3],
    /// The second-moment layers ([`crate::moments::LAYERS`]), their means per pass.
    pub(super) m2: [Moments; moments::LAYERS.len()],
    /// The three layers' moments per fold ([`FOLDS`]).
    pub(super) folds: [[Moments; 3]; FOLDS],
}

impl Pilot {
    pub(super) fn new(npix: usize) -> Self {
        Pilot {
            layers: std::array::from_fn(|_| Moments::new(npix)),
            diffs: std::array::from_fn(|_| Moments::new(npix)),
            m2: std::array::from_fn(|_| Moments::new(npix)),
            folds: std::array::from_fn(|_| std::array::from_fn(|_| Moments::new(npix))),
        }
    }

    /// Passes run so far.
    pub(super) fn passes(&self) -> usize {
        self.layers[0].n
    }
}

/// Runs pilot passes of `method` into `p` until `until` (at least `min_batches` in all, at
/// most [`MAX_BATCHES`]); each pass has its own seed, the count so far continuing. The
/// first `timed` passes render without the second-moment layers, as the method renders,
/// and time themselves: the fastest one's tracing time is returned (infinite when none
/// ran), so that the combined image is timed by pilot passes rather than by passes thrown
/// away (their layers count as any pass's; the second-moment layers hold the other passes).
/// A guided pilot renders no second-moment layers where their MIS estimates would read
/// other densities than its paths were drawn with ([`reads_second_moments`]); where it
/// does, for the render `ahead` describes ([`Ahead::horizon`]).
#[allow(clippy::too_many_arguments)]
pub(super) fn pilot_passes(
    scene: &Scene,
    opts: &RenderOptions,
    method: Method,
    g: &Guidance,
    until: Option<Instant>,
    min_batches: usize,
    timed: usize,
    ahead: Ahead,
    p: &mut Pilot,
) -> f64 {
    let mut seconds = f64::INFINITY;
    let first = p.passes();
    // `min_batches` counts every pass of the pilot: timed passes come first.
    debug_assert!(timed == 0 || first + timed <= min_batches);
    let second_moments = reads_second_moments(method, &opts.guide_params);
    // The last pass's wall time, for the passes still to come before `until`.
    let mut last_pass_s = f64::NAN;
    for b in passes_until(first, min_batches, until) {
        let stream = 0xa070_0000_0000_0000 ^ (b as u64 + 1);
        let plain = b < first + timed;
        let moments = (second_moments && !plain).then(|| {
            let left = until.map_or(0.0, |u| {
                u.saturating_duration_since(Instant::now()).as_secs_f64()
            });
            let to_come = if last_pass_s > 0.0 {
                left / last_pass_s
            } else {
                0.0
            };
            // The layers' passes (the timed ones carry none): those so far, this one and
            // those still to come, at least the least this call runs.
            let least = min_batches.saturating_sub(first + timed) + p.m2[0].n;
            let passes = (p.m2[0].n as f64 + 1.0 + to_come).max(least as f64);
            ahead.horizon(passes, seconds)
        });
        let pass_start = Instant::now();
        let r = independent_pass(scene, opts, method, g, stream, moments);
        last_pass_s = pass_start.elapsed().as_secs_f64();
        if plain {
            seconds = seconds.min(r.timings.tracing.as_secs_f64());
        }
        for (m, (_, img)) in p.layers.iter_mut().zip(&r.layers) {
            m.add(img);
        }
        for (m, (_, img)) in p.folds[b % FOLDS].iter_mut().zip(&r.layers) {
            m.add(img);
        }
        for (m, (_, img)) in p.m2.iter_mut().zip(r.layers.iter().skip(3)) {
            m.add(img);
        }
        let combined = &r.layers[0].1;
        for (m, (_, img)) in p.diffs.iter_mut().zip(&r.layers) {
            m.add_difference(img, combined);
        }
    }
    seconds
}

/// The render a pilot's second-moment layers predict ([`crate::moments::Horizon`]): the
/// seconds it will have (at the image's resolution), and the three estimates' pass times
/// (pt, lt, combined) at the pilot's resolution, or times in their proportion (scaled to
/// the combined pass's time where the pilot times it).
#[derive(Clone, Copy, Debug)]
pub(super) struct Ahead {
    pub(super) render_s: f64,
    pub(super) pass_s: [f64; 3],
}

impl Ahead {
    /// The horizon of a pilot of `passes` passes in all, whose combined pass was timed at
    /// `combined_s` seconds (infinite when not timed: `pass_s` as given).
    pub(super) fn horizon(&self, passes: f64, combined_s: f64) -> moments::Horizon {
        let scale = if combined_s.is_finite() && self.pass_s[2] > 0.0 {
            combined_s / self.pass_s[2]
        } else {
            1.0
        };
        moments::Horizon::new(self.render_s, passes, self.pass_s.map(|t| t * scale))
    }
}

/// Whether the pilot of `method` has second-moment layers to read. The MIS estimates need
/// the densities the guided paths were drawn with: with unguided weights (`guided_mis`
/// off) or per-event guiding (no cache: its MIS densities are the BSDF's) a guided
/// pilot's layers would read other densities, so it renders none (and what its paths see
/// of the others' missed paths counts as nothing, as a layer without passes does).
pub(super) fn reads_second_moments(method: Method, params: &GuideParams) -> bool {
    !method.guided() || (params.guided_mis && params.cache)
}

/// Pass numbers from `first` on, while fewer than `min` or `until` has not come (at most
/// [`MAX_BATCHES`]): the clock is read before each pass.
pub(super) fn passes_until(
    first: usize,
    min: usize,
    until: Option<Instant>,
) -> impl Iterator<Item = usize> {
    (first..MAX_BATCHES).take_while(move |&b| b < min || until.is_some_and(|u| Instant::now() < u))
}

/// The time of one pass of `method` (its own path loop, no MIS bookkeeping): the fastest of
/// `repeat`, since other jobs on the machine only ever slow a pass down.
pub(super) fn pass_seconds(
    scene: &Scene,
    opts: &RenderOptions,
    method: Method,
    g: &Guidance,
    repeat: usize,
) -> f64 {
    let o = RenderOptions {
        method,
        spp: 1,
        time: None,
        passes: crate::PassSelection::ALL,
        ..opts.clone()
    };
    (0..repeat)
        .map(|_| {
            let r: RenderResult =
                render_prepared(scene, &o, g, Duration::ZERO, StopRule::HalfPass, |_| {});
            r.timings.tracing.as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

/// The time the particle passes of `method`'s maps take (`scene.maps`' path counts, every
/// map round), each pass measured on [`PROBE_SHARE`] of its paths (at least four chunks of
/// paths per worker thread, so that every worker stays busy as in the full pass; all of
/// them where that is more), BSDF-sampled as a first round shoots them, and scaled up. A
/// particle path costs what the scene's paths cost there, not what a rendered pass's does
/// (those connect every vertex to the camera or a light): on the slit room the rendered
/// passes' time per path puts the maps at about four times what they take.
pub fn particle_pass_seconds(scene: &Scene, opts: &RenderOptions, method: &Method) -> f64 {
    let (need_light, need_view) = needed_passes(method, &opts.guide_params);
    let pass = pass_settings(scene, opts);
    let bsdf = GuidedSampler::bsdf();
    let least = 4 * rayon::current_num_threads() * CHUNK_PATHS;
    let probe = |n: usize| ((n as f64 * PROBE_SHARE).ceil() as usize).max(least).min(n);
    type Pass = fn(&Scene, &PassSettings, &GuidedSampler) -> crate::passes::PassOutput;
    let passes: [(bool, usize, Pass); 2] = [
        (need_light, scene.maps.photons, light_pass),
        (need_view, scene.maps.importons, view_pass),
    ];
    // Each pass on `probe(n)` of its `n` paths, its time scaled to `n`.
    let mut seconds = 0.0;
    for (_, n, run) in passes.into_iter().filter(|p| p.0) {
        let m = probe(n);
        if m == 0 {
            continue;
        }
        let s = PassSettings {
            paths: m,
            ..pass.clone()
        };
        let start = Instant::now();
        run(scene, &s, &bsdf);
        seconds += start.elapsed().as_secs_f64() * n as f64 / m as f64;
    }
    // Each round before the last shoots half the paths of the one after it.
    let rounds = 2.0 - 0.5f64.powi(scene.maps.rounds.max(1) as i32 - 1);
    seconds * rounds
}

/// An image of `w` x `h` pixels, each pixel `value(i)` in every channel (for the tests).
#[cfg(test)]
pub(super) fn test_image(w: usize, h: usize, value: impl Fn(usize) -> f32) -> Image {
    Image {
        width: w as u32,
        height: h as u32,
        pixels: (0..w * h)
            .map(|i| footprint::Rgb::splat(value(i)))
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The unguided pilot always renders its second-moment layers (its own paths' second
    /// moments are what the others' paths are compared with); a guided pilot only where its
    /// MIS densities are the ones its paths were drawn with.
    #[test]
    fn a_guided_pilot_renders_second_moments_only_with_its_own_densities() {
        let method = |i: &str, g: &str| Method::from_names(i, g).expect("registered");
        let on = GuideParams::default();
        assert!(
            on.guided_mis && on.cache,
            "the defaults guide with cached MIS densities"
        );
        let no_mis = GuideParams {
            guided_mis: false,
            ..on.clone()
        };
        let per_event = GuideParams {
            cache: false,
            ..on.clone()
        };
        for params in [&on, &no_mis, &per_event] {
            assert!(reads_second_moments(method("combined", "bsdf"), params));
        }
        assert!(reads_second_moments(method("combined", "footprint"), &on));
        assert!(!reads_second_moments(
            method("combined", "footprint"),
            &no_mis
        ));
        assert!(!reads_second_moments(
            method("combined", "grid"),
            &per_event
        ));
    }
}
