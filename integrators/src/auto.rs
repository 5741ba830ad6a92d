//! `auto`: the renderer chooses the method. A short **pilot** renders a few independent
//! passes of the combined image, which carries the path tracer's, the light tracer's and the
//! combined estimate of the same paths as three layers, and measures per pixel what each
//! direction contributes: its mean and its variance per pass. With the time one pass of each
//! method costs, that predicts each candidate's relative MSE (`compare`'s metric) at the time
//! left, and the rest of the budget goes to the candidate predicted best.
//!
//! * **Prediction.** For candidate `m` with per-pass variance `σ²_m` per pixel and channel, a
//!   pass time `t_m` and the time left `T`: `E_m = mean[(σ²_m t_m / T + b²_m) / (R² + 0.01)]`,
//!   everything divided by `R`'s mean luminance as `compare` does. `R` is a combined mean
//!   over a window around the pixel, the smallest whose standard error is at most 20% of it
//!   ([`crate::window`]): a pixel's own pilot mean is heavy-tailed and usually
//!   low where rare bright paths carry the light, and `1 / (R² + 0.01)` of a low `R`
//!   overweights exactly the pixels guiding helps (door with a 3x3 window: `lt-footprint`
//!   predicted 4x its error). `R` pools every pilot's combined image, each pilot weighed by
//!   the inverse of its variance ([`Pooled`]), but a pilot's passes are dealt to [`FOLDS`]
//!   folds and each fold's squared deviations are weighed with `R` without that fold's
//!   passes (cross-fitting: a bright sample must not raise the `R` that weighs it), read
//!   over a window sized by the noise of every pass (a fold must not be weighed with the
//!   near-zero `R` of passes that missed its rare light, [`fold_metrics`]). Measured with
//!   the truth's `R` (door's 900-s reference), the predictions matched 16-s renders within
//!   1.1x (`lt-footprint` 151 per pass against 140-160).
//! * **Paths the pilot missed.** A few passes miss a method's rare, bright paths (door's
//!   unguided path tracing: 14 passes predicted 0.063 where 16 s measure 0.81). The pilot's
//!   combined image also estimates each estimate's second moment by MIS from every path,
//!   and a guided pilot the unguided estimates' from its guided paths ([`crate::moments`]);
//!   what exceeds the estimate's own paths' second moment is added to `σ²_m` (the reason
//!   line says where it is most of it). On door this brings `pt-bsdf`'s prediction to
//!   0.57-0.73.
//! * **Missing light.** A method that cannot make some paths is biased there: path tracing
//!   misses caustics of point and spot lights (`L S+ D ... E`: a delta light behind a specular
//!   surface), light tracing misses what the pinhole sees through a specular surface and the
//!   environment seen directly. Where the scene's effects allow that, the candidate's squared
//!   difference to the combined mean (less what its noise explains) is added as `b²_m`,
//!   measured on blocks of pixels that hold [`BIAS_BLOCK_SAMPLES`] pilot samples: a
//!   point-light caustic seen only by the light tracer rules path tracing out.
//! * **Guided candidates** (`--guide auto`) are piloted only where one pass of the best
//!   unguided candidate has at least [`GUIDED_MIN_PASS_VARIANCE`] relative variance (a scene
//!   hard per sample), and when their maps are predicted to take at most
//!   [`FIRST_GUIDE_MAPS_SHARE`] of the budget for the first guide, [`GUIDED_MAPS_SHARE`]
//!   for all together after it (the passes' paths at the pilot's time per path); the guides
//!   share one pilot's time ([`PILOT_SHARE`] / the number of guides
//!   each); their maps are then built once, piloted with the same passes, and reused by
//!   the render if one of them wins. With one map round the particle passes do not depend on
//!   the guide: they run once and every guide builds its maps and caches from them. A
//!   guide not piloted (its maps would not fit) leaves its pilot time to those piloted.
//!   When a method that reads the photon map wins, its sparse photon map grows with the time
//!   left, as a fixed method's grows with its budget
//!   ([`crate::render::chosen_guidance`]).
//! * **Guided splitting.** A guided path or light tracer splits where its guide expects
//!   more light; the combined image does not, so its layers measure both directions
//!   unsplit. Each splitting direction is also piloted with a few passes of its own, as it
//!   renders ([`SplitPilot`], [`SPLIT_PILOT_SHARE`]): its predicted noise is the layer's
//!   times the ratio of the two under the same weights ([`split_ratio`]), its time its own
//!   passes'. On door this is the difference: light tracing gains 1.7x from splitting, path
//!   tracing nothing, and the unsplit layers predicted a near tie (3.5x apart rendered).
//! * **Margins.** A guided candidate must be predicted [`GUIDED_MARGIN`] times better than
//!   BSDF sampling of its own integrator: the pilot's passes are independent samples, and
//!   what the render's Sobol sequence gains over thousands of passes it cannot measure (it
//!   gains BSDF sampling more; see the constant). A guided combined image must be predicted
//!   [`SPLIT_MARGIN`] times better than its guide's path and light tracers (measured: its
//!   prediction runs low against theirs).
//! * **Budget.** With `--time T` the pilot takes about [`PILOT_SHARE`] of `T` (at least
//!   [`MIN_BATCHES`] + [`TIMED_PASSES`] passes) and counts in the budget: the render stops
//!   at `T`, pilot included. With `--spp N` the pilot's passes (the unguided pilot's
//!   [`MIN_BATCHES`] + [`TIMED_PASSES`], and the guided pilots') are extra, the candidates
//!   are compared at the time `N` passes of path tracing take, and the chosen method renders
//!   `N` passes.

use crate::maps::{Guidance, run_passes};
use crate::method::Method;
use crate::moments;
use crate::render::{
    RenderOptions, RenderResult, StopRule, guidance_with, importance_target, independent_pass,
    pass_settings, render_prepared, wants_target,
};
use crate::skips::particles_stored;
use footprint::Rgb;
use footprint::film::Image;
use footprint::math::luminance;
use footprint::scene::Scene;
use footprint::settings::GuideParams;
use std::time::{Duration, Instant};

/// Share of a time budget the unguided pilot takes.
pub const PILOT_SHARE: f64 = 0.04;
/// Guided candidates are piloted only when the scene is hard enough
/// ([`GUIDED_MIN_PASS_VARIANCE`]) and their maps are predicted to take at most this share of
/// the budget, all guides piloted so far included...
pub const GUIDED_MAPS_SHARE: f64 = 0.15;
/// ...or, for the first guide piloted (the paper's footprints), this share: where a scene is
/// hard, guiding won by 3-10x, and door's footprint maps and pilot (3.4 s of 16 s on a slow
/// day of the 2-core VM) no longer fitted 15%, which left `auto` with unguided light tracing
/// there (4-4.6x behind `lt-footprint`). 0.25 until Russian roulette started at depth 8
/// (thirteenth session): door's light paths grew longer (maps 1.6 → 2.6 s), its estimate
/// came to 4.06 s of 16, and `auto` chose `pt-bsdf` at 4x `lt-footprint`'s error.
pub const FIRST_GUIDE_MAPS_SHARE: f64 = 0.3;
/// Guided candidates are piloted only where one pass of the unguided candidate the pilot
/// predicts best has at least this relative variance (the metric's, averaged over pixels
/// and channels: about the squared relative noise of one sample per pixel). Below it the
/// image converges without guiding, and a guided pilot (maps, caches and passes: 24-29% of
/// a 16-s budget on cornell) costs more than guiding wins. Measured (one pass of the best
/// unguided method): furnace 0.02, Bitterli's Cornell box 0.4, cornell 0.8, features 1.5,
/// desk 2.8 (guided methods lose or tie at equal time on all five) against Veach Ajar 48
/// and door 2650 (guided methods 3-10x ahead); README "auto: the renderer chooses".
pub const GUIDED_MIN_PASS_VARIANCE: f64 = 10.0;
/// A guided candidate is chosen only when predicted better than BSDF sampling of its own
/// integrator by this factor (else the next candidate is). The pilot's passes are
/// independent samples, but the render's are a Sobol sequence, whose stratification gains
/// BSDF sampling more over thousands of passes than guided sampling (cornell, 16 s: Sobol
/// against independent numbers 2.0x less error for `pt-bsdf`, 1.5x for `pt-footprint`),
/// and which a short pilot cannot measure (4-6 passes per randomisation showed 1.2x for
/// both); where guiding helps it wins by far more (Veach Ajar, door: 3-10x). Against the
/// other direction the margin does not apply: on door `lt-footprint` wins over `pt-bsdf`
/// by far more than its prediction says, and a margin against the best unguided method of
/// either direction chose `pt-bsdf` there (6x behind).
pub const GUIDED_MARGIN: f64 = 1.3;
/// A guided combined image is chosen only when predicted better than the better of its own
/// guide's path and light tracer by this factor (else the next candidate is). Set when the
/// pilot measured all three unsplit, from the combined image's layers (door 16 s, seed 2:
/// `combined-footprint` predicted 0.730 and `lt-footprint` 0.736, rendered 0.67-1.31
/// against 0.30-0.35); kept now that the splitting directions are piloted as they render
/// ([`SplitPilot`]): on Veach Ajar (30 s) the combined image is still predicted about as
/// good as `pt-footprint` (seeds 1-3 of the thirteenth session: 0.97x, 1.04x and 1.29x
/// its prediction) where 30-s renders of the two measure 1.05-1.4x apart in
/// `pt-footprint`'s favour on most seeds; a `compare` run of seed 2 chose the combined
/// image even so, at 1.24x `pt-footprint`'s error.
pub const SPLIT_MARGIN: f64 = 1.3;
/// A guided path or light tracer that splits is piloted with passes of its own
/// ([`SplitPilot`]) for this share of its guide's combined pilot's time each, and at least
/// [`MIN_SPLIT_PASSES`] of them.
pub const SPLIT_PILOT_SHARE: f64 = 0.5;
pub const MIN_SPLIT_PASSES: usize = 3;
/// Fewest and most pilot passes per set of candidates (the unguided pilot's fewest with
/// the second-moment layers; [`TIMED_PASSES`] more run before them).
pub const MIN_BATCHES: usize = 4;
/// The first passes of each combined pilot render without the second-moment layers, as the
/// combined image renders, and time it (the fastest of them, [`pilot_passes`]): two passes
/// that timed it apart were thrown away (door, 16 s: 0.5 s of a 6.5-s pilot). Their layers
/// count as every pass's; at least [`MIN_BATCHES`] (unguided) or two (guided) passes with
/// the second-moment layers follow, and what a candidate's own paths missed is measured on
/// those (both second-moment layers from the same passes). Two, as other jobs on the
/// machine only slow a pass down. Veach Ajar at 30 s, seeds 2 and 3, predicted
/// `pt-footprint` 1.08e-2 and 7.7e-3 so, 1.12e-2 and 7.1e-3 with one timed pass, 1.21e-2
/// and 8.9e-3 with the timing passes apart (every pass in the second-moment layers): within
/// what one seed's pilot varies from run to run (1.1-1.8e-2 on seed 2).
pub const TIMED_PASSES: usize = 2;
pub const MAX_BATCHES: usize = 48;
/// A time budget shorter than this many passes of pt and lt together leaves no room for a
/// pilot (its least cost is about 7 such pairs): the first unguided candidate renders.
pub const MIN_BUDGET_PAIRS: f64 = 40.0;
/// The pilot's passes are dealt to this many folds (pass `b` to fold `b % FOLDS`): the
/// squared deviations of a fold's passes are weighed with `R` from every other pass
/// ([`measure`]).
pub const FOLDS: usize = 4;
/// Pilot samples per block of pixels on which missing light is measured (see [`measure`]).
pub const BIAS_BLOCK_SAMPLES: f64 = 64.0;
/// An image of more pixels than this is piloted at a lower resolution
/// ([`pilot_resolution`]), the same view through fewer, larger pixels. The pilot's least
/// passes (six unguided, four guided combined and three split per direction) and the view
/// pass's importance target render every pixel, so their cost grows with the image while
/// the budget does not: door at its own 256x256 and 16 s piloted for 11-13 s (its pixels
/// four times those of the 128x128 at which `auto` was tuned), and `auto`'s error was
/// 2.7-5.4x `lt-footprint`'s (README "`auto` against the fixed methods"). One pass of a
/// method has about the same relative variance per pixel at either resolution (one path per
/// pixel, the same paths; a light pass traces one path per pixel, and each of its splats
/// carries the pixel count's share), while its time scales with the pixel count: the
/// pilot's pass times are scaled by the ratio of the pixel counts, which leaves the ranking
/// as measured and predicts each candidate's error at the image's resolution. The maps are
/// not tied to the resolution (the view pass draws raster positions uniformly over the
/// image; its importance target is the image's where the time allows,
/// [`FULL_TARGET_SHARE`]), so a guided winner still reuses them. 64x64
/// was tried: door's passes of 4096 pixels took longer per path (a pass's fixed costs), the
/// footprints' maps were estimated at 5.1 s, over their 30% of 16 s, and `auto` chose
/// `pt-bsdf` at 3.5x `lt-footprint`'s error.
pub const PILOT_MAX_PIXELS: usize = 128 * 128;
/// A pilot at a lower resolution ([`PILOT_MAX_PIXELS`]) builds the view pass's importance
/// target ([`crate::target`]) at the image's resolution when the extra passes that takes
/// are predicted at most this share of the rendering time left, and the first guide's maps
/// still fit [`FIRST_GUIDE_MAPS_SHARE`] with them (never at the footprints' cost; unless
/// every candidate is guided, when the maps are piloted whatever they cost). The target at
/// the pilot's resolution is coarser than the image whose relative error it weighs, and
/// maps built with it guide the light tracer worse per pass: door 256x256, 120 light
/// passes, seeds 11-13, `lt-footprint` with the pilot's maps 0.379, 0.375, 0.439 against
/// its own maps' 0.364, 0.383, 0.348 (1.09x on average, so about 8% of the passes are
/// lost); with the target at the image's resolution, door at 32 s had 0.98-1.03x the fixed
/// method's error per pass. Its four passes at 256x256 cost door 0.6-1.0 s more than at
/// 128x128. Door 256x256 against `lt-footprint` (nineteenth session, README "Nineteenth
/// session"): at 16 s (0.63 s estimated against 0.83 s) seeds 1-12 read 0.76-1.39x, median
/// 1.29 (seeds 1-6: 1.21-1.35x where the coarse target read 1.24-1.50x and misranked seed
/// 1, 4.8x; a later run of seed 1 with the target misranked it too); at 32 s, seeds 1-4,
/// 1.07-1.22x against 1.23-1.30x; at 64 s, seeds 1-2, 1.17 and 1.03x.
pub const FULL_TARGET_SHARE: f64 = 0.08;

/// The pilot's resolution for a `width` x `height` image: the image's own up to
/// [`PILOT_MAX_PIXELS`] pixels, else both sides divided (rounded up) by the least integer
/// that brings it under.
pub fn pilot_resolution(width: u32, height: u32) -> (u32, u32) {
    let pixels = |f: u32| width.div_ceil(f) as usize * height.div_ceil(f) as usize;
    let f = (1..)
        .find(|&f| pixels(f) <= PILOT_MAX_PIXELS)
        .expect("1x1 fits");
    (width.div_ceil(f), height.div_ceil(f))
}

/// The pilot's particle passes' settings for `o`: with the importance target rendered from
/// `target_scene` (the pilot's view or the image's, [`FULL_TARGET_SHARE`]) where `o`'s
/// method reads one ([`wants_target`]), built at the first call and reused by the next.
fn pass_with_target(
    scene: &Scene,
    target_scene: &Scene,
    o: &RenderOptions,
    target: &mut Option<Option<std::sync::Arc<crate::target::ImportanceTarget>>>,
) -> crate::passes::PassSettings {
    let pass = pass_settings(scene, o);
    if !wants_target(o) {
        return pass;
    }
    let built =
        target.get_or_insert_with(|| importance_target(target_scene, o).map(std::sync::Arc::new));
    crate::passes::PassSettings {
        target: built.clone(),
        ..pass
    }
}

/// What `auto` chooses among.
#[derive(Clone, Debug, PartialEq)]
pub struct AutoSpec {
    pub candidates: Vec<Method>,
    /// `auto`, `auto-bsdf` (integrator chosen), `pt-auto` (guide chosen).
    pub label: String,
}

impl AutoSpec {
    /// `integrator` and `guide` fixed when given, chosen when `None`; the integrators are
    /// path tracing, light tracing and the combined image.
    pub fn new(integrator: Option<Method>, guide: Option<Method>) -> Self {
        let integrators: Vec<&'static dyn crate::integrator::Integrator> = match integrator {
            Some(m) => vec![m.integrator],
            None => ["pt", "lt", "combined"]
                .iter()
                .filter_map(|n| crate::integrator::find_integrator(n))
                .collect(),
        };
        let guides: Vec<&'static dyn footprint::guide::Guide> = match guide {
            Some(m) => vec![m.guide],
            None => footprint::guide::GUIDES.to_vec(),
        };
        let mut candidates = Vec::new();
        for g in &guides {
            for i in &integrators {
                candidates.push(Method {
                    integrator: *i,
                    guide: *g,
                });
            }
        }
        let label = format!(
            "{}-{}",
            integrator.map(|m| m.integrator.name()).unwrap_or("auto"),
            guide.map(|m| m.guide.name()).unwrap_or("auto")
        );
        AutoSpec {
            candidates,
            label: if label == "auto-auto" {
                "auto".into()
            } else {
                label
            },
        }
    }

    /// Every registered method.
    pub fn all() -> Self {
        Self::new(None, None)
    }
}

/// One candidate as the pilot measured it.
#[derive(Clone, Debug)]
pub struct Candidate {
    pub method: String,
    /// Predicted relative MSE at the time left.
    pub predicted: f64,
    /// Seconds per pass at the image's resolution (a lower-resolution pilot's scaled by the
    /// pixel counts' ratio, [`PILOT_MAX_PIXELS`]).
    pub pass_seconds: f64,
    /// The relative variance of one pass (`predicted` divides it by the passes left).
    pub pass_variance: f64,
    /// Part of `pass_variance` from paths the pilot's own passes of the direction missed
    /// (estimated by MIS from the other direction's paths, [`crate::moments`]).
    pub unseen: f64,
    /// Part of `predicted` from light the method cannot find.
    pub missing: f64,
}

impl Candidate {
    /// Sets `predicted` for `time_left` seconds of rendering (infinite for a candidate that
    /// was not timed).
    fn predict_at(&mut self, time_left: f64) {
        if !self.pass_seconds.is_finite() {
            self.predicted = f64::INFINITY;
            return;
        }
        let passes = (time_left / self.pass_seconds).max(1.0);
        self.predicted = self.pass_variance / passes + self.missing;
    }
}

/// What `auto` chose and why.
pub struct Choice {
    pub method: Method,
    /// One line: the choice, its predicted error against the others', and why.
    pub reason: String,
    pub candidates: Vec<Candidate>,
    /// Time the pilot took (maps of guided candidates included).
    pub pilot: Duration,
    /// Maps built by the pilot for the chosen method (guided winners reuse them).
    pub guidance: Option<Guidance>,
}

/// Per-pixel, per-channel running sums of a layer over pilot passes.
#[derive(Clone)]
struct Moments {
    sum: Vec<[f64; 3]>,
    sum2: Vec<[f64; 3]>,
    n: usize,
}

impl Moments {
    fn new(npix: usize) -> Self {
        Moments {
            sum: vec![[0.0; 3]; npix],
            sum2: vec![[0.0; 3]; npix],
            n: 0,
        }
    }

    fn add(&mut self, img: &Image) {
        for ((s, s2), p) in self.sum.iter_mut().zip(&mut self.sum2).zip(&img.pixels) {
            for c in 0..3 {
                let x = p[c] as f64;
                s[c] += x;
                s2[c] += x * x;
            }
        }
        self.n += 1;
    }

    /// Adds the passes of `o` (another pilot's estimate of the same image).
    fn pool(&mut self, o: &Moments) {
        let pairs = self.sum.iter_mut().zip(&mut self.sum2);
        for ((s, s2), (os, os2)) in pairs.zip(o.sum.iter().zip(&o.sum2)) {
            for c in 0..3 {
                s[c] += os[c];
                s2[c] += os2[c];
            }
        }
        self.n += o.n;
    }

    /// Takes out the passes of `o` (a part of these).
    fn remove(&mut self, o: &Moments) {
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
    fn add_difference(&mut self, a: &Image, b: &Image) {
        let pix = a.pixels.iter().zip(&b.pixels);
        for ((s, s2), (pa, pb)) in self.sum.iter_mut().zip(&mut self.sum2).zip(pix) {
            for c in 0..3 {
                let x = pa[c] as f64 - pb[c] as f64;
                s[c] += x;
                s2[c] += x * x;
            }
        }
        self.n += 1;
    }

    fn mean(&self, i: usize, c: usize) -> f64 {
        self.sum[i][c] / self.n as f64
    }

    /// Per-pass variance (unbiased).
    fn var(&self, i: usize, c: usize) -> f64 {
        let n = self.n as f64;
        let m = self.sum[i][c] / n;
        ((self.sum2[i][c] - n * m * m) / (n - 1.0)).max(0.0)
    }
}

/// The image as several pilots estimate it together, for the metric's `R`: each pilot's
/// mean weighed by its passes over its per-pass variance (inverse-variance pooling, one
/// weight per pilot, image-wide). Pooling passes alike let the noisiest pilot set `R`: on
/// door 20-odd unguided passes of relative variance 2650 each outweighed a guided pilot's
/// 5 of 160, and the window `R` is read over widened until it blurred the light the guided
/// passes carry (`lt-footprint` predicted at 2-3x its error). Weights per pilot, not per
/// pixel: a pixel's own variance rises with its bright samples, and weighing by it would
/// pull `R` down where rare paths carry the light.
struct Pooled {
    mean: Vec<[f64; 3]>,
    /// The variance of `mean`.
    var_of_mean: Vec<[f64; 3]>,
}

impl Pooled {
    /// From `parts` (each pilot's passes; those without passes are left out).
    fn new(parts: &[&Moments]) -> Self {
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

/// Whether `integrator` can miss light in `scene` (see the module doc).
fn can_miss_light(scene: &Scene, integrator: &str) -> Option<&'static str> {
    let e = &scene.effects;
    let specular = e.specular_reflection || e.refraction;
    match integrator {
        "pt" if specular && (e.spot_lights || e.point_lights) => {
            Some("path tracing cannot find caustics of point and spot lights")
        }
        "lt" if specular => Some("light tracing cannot see through specular surfaces"),
        "lt" if e.environment => Some("light tracing does not see the environment directly"),
        _ => None,
    }
}

/// The pilot's passes of the combined image of `guide` (`bsdf` or a guide with maps):
/// moments of the combined, pt and lt layers and of the second-moment layers (pt's and lt's
/// pass times are measured apart, [`pass_seconds`]; the combined image's by the pilot's
/// first passes, [`TIMED_PASSES`]).
struct Pilot {
    layers: [Moments; 3],
    /// Moments of each layer less the combined layer of the same pass: the noise of a
    /// difference of two estimates from the same paths (they are correlated).
    diffs: [Moments; 3],
    /// The second-moment layers ([`crate::moments::LAYERS`]), their means per pass.
    m2: [Moments; moments::LAYERS.len()],
    /// The three layers' moments per fold ([`FOLDS`]).
    folds: [[Moments; 3]; FOLDS],
}

impl Pilot {
    fn new(npix: usize) -> Self {
        Pilot {
            layers: std::array::from_fn(|_| Moments::new(npix)),
            diffs: std::array::from_fn(|_| Moments::new(npix)),
            m2: std::array::from_fn(|_| Moments::new(npix)),
            folds: std::array::from_fn(|_| std::array::from_fn(|_| Moments::new(npix))),
        }
    }

    /// Passes run so far.
    fn passes(&self) -> usize {
        self.layers[0].n
    }
}

/// Runs pilot passes of `method` into `p` until `until` (at least `min_batches` in all, at
/// most [`MAX_BATCHES`]); each pass has its own seed, the count so far continuing. The
/// first `timed` passes render without the second-moment layers, as the method renders,
/// and time themselves: the fastest one's tracing time is returned (infinite when none
/// ran), so that the combined image is timed by pilot passes rather than by passes thrown
/// away (their layers count as any pass's; the second-moment layers hold the other passes).
#[allow(clippy::too_many_arguments)]
fn pilot_passes(
    scene: &Scene,
    opts: &RenderOptions,
    method: Method,
    g: &Guidance,
    until: Option<Instant>,
    min_batches: usize,
    timed: usize,
    p: &mut Pilot,
) -> f64 {
    let mut seconds = f64::INFINITY;
    let first = p.passes();
    // `min_batches` counts every pass of the pilot: timed passes come first.
    debug_assert!(timed == 0 || first + timed <= min_batches);
    for b in passes_until(first, min_batches, until) {
        let stream = 0xa070_0000_0000_0000 ^ (b as u64 + 1);
        let plain = b < first + timed;
        let r = independent_pass(scene, opts, method, g, stream, !plain);
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

/// Pass numbers from `first` on, while fewer than `min` or `until` has not come (at most
/// [`MAX_BATCHES`]): the clock is read before each pass.
fn passes_until(first: usize, min: usize, until: Option<Instant>) -> impl Iterator<Item = usize> {
    (first..MAX_BATCHES).take_while(move |&b| b < min || until.is_some_and(|u| Instant::now() < u))
}

/// The time of one pass of `method` (its own path loop, no MIS bookkeeping): the fastest of
/// `repeat`, since other jobs on the machine only ever slow a pass down.
fn pass_seconds(
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
        auto: None,
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

/// A guided path or light tracer piloted with passes of its own, split where its guide
/// expects more light as it renders (guided splitting): the combined image does not split,
/// so its pt and lt layers measure these directions unsplit, and on door light tracing
/// gains 1.7x from splitting that the layers cannot show (the eleventh and twelfth
/// sessions' near ties of `lt-footprint` and `pt-footprint`, 3.5x apart when rendered).
struct SplitPilot {
    image: Moments,
    /// The fastest pass's tracing time (other jobs on the machine only slow a pass down).
    seconds: f64,
}

impl SplitPilot {
    /// Runs passes of `method` until `until` (at least `min_passes`, at most
    /// [`MAX_BATCHES`]), each with its own seed from `stream`.
    fn run(
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
            let r = independent_pass(scene, opts, method, g, stream ^ (b as u64 + 1), false);
            image.add(&r.image);
            seconds = seconds.min(r.timings.tracing.as_secs_f64());
        }
        SplitPilot { image, seconds }
    }

    /// The relative variance of one pass, each pixel weighed with the mean of `folds`'
    /// weights (those the unsplit layer's folds are weighed with: the two are compared
    /// under the same weights, see [`choose`]); `None` with fewer than two passes.
    fn pass_variance(&self, folds: &[Metric; FOLDS]) -> Option<f64> {
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

/// What one pilot measured of the candidates of `guide` (the combined image, pt and lt: its
/// three layers): the relative variance per pass and the missing light. `predicted` is set
/// later, for every candidate at the same time left ([`Candidate::predict_at`]).
/// `same_paths`: `reference` is this pilot's own combined layer (so the layers' differences
/// to it are measured per pass), not an independent pilot's.
#[allow(clippy::too_many_arguments)]
fn measure(
    scene: &Scene,
    pilot: &Pilot,
    reference: &Moments,
    metric: &Metric,
    folds: &[Metric; FOLDS],
    same_paths: bool,
    seconds: [f64; 3],
    guide: &str,
) -> Vec<Candidate> {
    let npix = reference.sum.len();
    let scale = metric.scale;
    let k = pilot.layers[0].n as f64;
    let k_ref = reference.n as f64;
    let width = (scene.camera.width as usize).max(1);
    let height = npix / width;
    // Missing light is measured on square blocks of pixels holding at least
    // BIAS_BLOCK_SAMPLES pilot samples: with a handful of passes a pixel's reference mean is
    // mostly noise, and the metric's weight 1 / (R^2 + 0.01) of a noisy R undercounts the
    // light a method misses (a point-light caustic measured pixel by pixel from 4 passes read
    // 0.12 where the block estimate reads the whole caustic).
    let side = ((BIAS_BLOCK_SAMPLES / k_ref).sqrt().ceil() as usize).max(1);
    ["combined", "pt", "lt"]
        .iter()
        .enumerate()
        .map(|(l, name)| {
            let layer = &pilot.layers[l];
            // The per-pass variance, each fold's squared deviations from the mean weighed
            // with its own weights (from `R` without the fold's passes).
            let mut var = 0.0f64;
            for (fold, w) in pilot.folds.iter().zip(folds) {
                let f = &fold[l];
                if f.n == 0 {
                    continue;
                }
                for i in 0..npix {
                    for c in 0..3 {
                        let m = layer.mean(i, c);
                        let dev2 = f.sum2[i][c] - 2.0 * m * f.sum[i][c] + f.n as f64 * m * m;
                        var += dev2.max(0.0) * w.weight[i][c];
                    }
                }
            }
            var /= (k - 1.0).max(1.0) * scale * scale;
            // What the estimate's own pilot paths missed of its second moment: the MIS
            // estimate from every path less its own (crate::moments).
            let e = estimate_index(l);
            let unseen = metric.excess(&pilot.m2[moments::MIS + e], &pilot.m2[moments::OWN + e]);
            let mut bias = 0.0f64;
            if can_miss_light(scene, name).is_some() {
                for y0 in (0..height).step_by(side) {
                    for x0 in (0..width).step_by(side) {
                        let (mut m, mut sl, mut sr, mut noise) =
                            (0.0, [0.0; 3], [0.0; 3], [0.0; 3]);
                        for y in y0..(y0 + side).min(height) {
                            for x in x0..(x0 + side).min(width) {
                                let i = y * width + x;
                                m += 1.0;
                                for c in 0..3 {
                                    sl[c] += layer.mean(i, c);
                                    sr[c] += reference.mean(i, c);
                                    noise[c] += if same_paths {
                                        pilot.diffs[l].var(i, c) / k
                                    } else {
                                        layer.var(i, c) / k + reference.var(i, c) / k_ref
                                    };
                                }
                            }
                        }
                        for c in 0..3 {
                            // The squared difference of the block means, less what their
                            // noise explains in expectation; summed signed over the image
                            // and clamped once, so that noise alone adds no bias.
                            let r = sr[c] / m / scale;
                            let diff = (sl[c] - sr[c]) / m / scale;
                            let noise = noise[c] / (m * m) / (scale * scale);
                            bias += m * (diff * diff - noise) / (r * r + 0.01);
                        }
                    }
                }
            }
            let n = (3 * npix) as f64;
            let (var, bias) = (var / n, (bias / n).max(0.0));
            Candidate {
                method: format!("{name}-{guide}"),
                predicted: f64::INFINITY,
                pass_seconds: seconds[l],
                pass_variance: var + unseen,
                unseen,
                missing: bias,
            }
        })
        .collect()
}

/// The metric's weights: `compare`'s relative MSE, `1 / (R² + 0.01)` per pixel and channel
/// after dividing by `scale`, the reference's mean luminance.
struct Metric {
    scale: f64,
    weight: Vec<[f64; 3]>,
}

impl Metric {
    /// The image's mean luminance, what the metric divides by.
    fn mean_luminance(reference: &Moments) -> f64 {
        let npix = reference.sum.len();
        let mut m = Rgb::ZERO;
        for i in 0..npix {
            m += Rgb::new(
                reference.mean(i, 0) as f32,
                reference.mean(i, 1) as f32,
                reference.mean(i, 2) as f32,
            );
        }
        (luminance(m / npix as f32) as f64).max(1e-20)
    }

    /// The weights from `reference`, the image divided by `scale`: `R` read over a window
    /// widened where the pilots' mean is noisy ([`crate::window`]).
    fn with_scale(width: u32, reference: &Pooled, scale: f64) -> Self {
        Self::with_noise(width, &reference.mean, &reference.var_of_mean, scale)
    }

    /// As [`Metric::with_scale`], the window sized by `var_of_mean` (another estimate's
    /// noise than `mean`'s, [`fold_metrics`]).
    fn with_noise(width: u32, mean: &[[f64; 3]], var_of_mean: &[[f64; 3]], scale: f64) -> Self {
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
    fn excess(&self, a: &Moments, b: &Moments) -> f64 {
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
/// without one see a dim, smooth image and a small window, so the fold holding it was
/// weighed with `1 / (R² + 0.01)` of a near-zero `R` (door: `lt-footprint` predicted at
/// 377-575 per pass against a true 218, measured over 404 independent passes, and ranked
/// behind `pt-footprint`; sized by every pass: 166 and 258, `pt-footprint` 306-337 against
/// 340).
fn fold_metrics(width: u32, base: &[&Moments], pilot: &Pilot, scale: f64) -> [Metric; FOLDS] {
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

/// What guided splitting of at most `branches` branches does to a direction's per-pass
/// noise: `split / unsplit`, the split pilot's relative variance over the unsplit layer's
/// under the same weights (a ratio, so that what the weights' own noise adds to both
/// cancels: measured alone, with `R` from the combined pilots, door's split `pt-footprint`
/// passes read 600-800 against 200-270 unsplit where splitting changes nothing), clamped
/// to `[1 / branches, 1]` against the noise of a few passes: a pass of more branches is
/// never noisier, and one split into n branches divides a pass's variance by at most n
/// (all of it arising after the split). Nested splits at later vertices could divide it
/// by more; the bound then only makes the prediction cautious. 1 when the layer measured
/// no variance.
fn split_ratio(unsplit: f64, split: f64, branches: u32) -> f64 {
    if unsplit > 0.0 && split.is_finite() {
        (split / unsplit).clamp(1.0 / branches.max(1) as f64, 1.0)
    } else {
        1.0
    }
}

/// The second-moment layers' estimate for the image layer `l` (combined, pt, lt).
fn estimate_index(l: usize) -> usize {
    [moments::COMBINED, moments::PT, moments::LT][l]
}

/// The prediction among `all` that candidate `c` fails to beat by its margin, with the
/// margin and what it is, if any: a guided candidate must beat BSDF sampling of its own
/// integrator by [`GUIDED_MARGIN`], and a guided combined image the better of its own
/// guide's pt and lt by [`SPLIT_MARGIN`].
fn rival(all: &[Candidate], c: &Candidate) -> Option<(f64, f64, &'static str)> {
    let m = Method::parse(&c.method).ok().filter(|m| m.guided())?;
    let predicted = |name: String| all.iter().find(|o| o.method == name).map(|o| o.predicted);
    let bsdf = predicted(format!("{}-bsdf", m.integrator.name()))
        .map(|u| (u, GUIDED_MARGIN, "BSDF sampling of its integrator"));
    let split = (m.integrator.name() == "combined")
        .then(|| {
            ["pt", "lt"]
                .iter()
                .filter_map(|i| predicted(format!("{i}-{}", m.guide.name())))
                .min_by(f64::total_cmp)
        })
        .flatten()
        .map(|u| (u, SPLIT_MARGIN, "its guide's pt or lt, which split"));
    [bsdf, split]
        .into_iter()
        .flatten()
        .find(|(u, margin, _)| *u < margin * c.predicted)
}

/// Runs the pilot for `opts` (whose `auto` names the candidates; its `time` is the budget)
/// and chooses.
pub fn choose(scene: &Scene, opts: &RenderOptions, spec: &AutoSpec) -> Choice {
    let start = Instant::now();
    let find = |i: &str, g: &str| Method::from_names(i, g).expect("registered");
    let wanted = |name: &str| spec.candidates.iter().any(|m| m.name() == name);
    if spec.candidates.len() == 1 {
        return Choice {
            method: spec.candidates[0],
            reason: "the only candidate".into(),
            candidates: Vec::new(),
            pilot: Duration::ZERO,
            guidance: None,
        };
    }
    let budget = opts.time;
    let unguided = Guidance::default();
    // ---- A large image is piloted at a lower resolution (PILOT_MAX_PIXELS) ----
    let (image_w, image_h) = (scene.camera.width, scene.camera.height);
    let (pilot_w, pilot_h) = pilot_resolution(image_w, image_h);
    let image_scene = scene;
    let lower;
    let scene = if (pilot_w, pilot_h) == (image_w, image_h) {
        scene
    } else {
        lower = scene
            .with_resolution(pilot_w, pilot_h)
            .expect("a smaller resolution of a valid camera");
        &lower
    };
    // Seconds of a pass at the image's resolution per second of a pilot pass.
    let pixel_ratio = (image_w as f64 * image_h as f64) / scene.camera.pixel_count() as f64;
    let mut notes = Vec::new();
    if pixel_ratio > 1.0 {
        notes.push(format!(
            "piloted at {pilot_w}x{pilot_h} (the {image_w}x{image_h} image has more than {PILOT_MAX_PIXELS} pixels; pass times scaled by {pixel_ratio:.2})"
        ));
    }
    // ---- pt's and lt's own pass times; a budget too short for a pilot ----
    // The pilot's own passes, unscaled: what the budget must hold is the pilot's least cost.
    let t_pt1 = pass_seconds(scene, opts, find("pt", "bsdf"), &unguided, 1);
    let t_lt1 = pass_seconds(scene, opts, find("lt", "bsdf"), &unguided, 1);
    if let Some(t) = budget.filter(|t| *t < MIN_BUDGET_PAIRS * (t_pt1 + t_lt1)) {
        let method = *spec
            .candidates
            .iter()
            .find(|m| !m.guide.uses_particles())
            .unwrap_or(&spec.candidates[0]);
        return Choice {
            method,
            reason: format!(
                "{}: no pilot, the budget of {t:.2} s is under {MIN_BUDGET_PAIRS} passes of pt and lt ({:.3} s a pair)",
                method.name(),
                t_pt1 + t_lt1
            ),
            candidates: Vec::new(),
            pilot: start.elapsed(),
            guidance: None,
        };
    }
    // ---- Unguided pilot: the combined image's three layers ----
    let until = budget.map(|t| start + Duration::from_secs_f64(PILOT_SHARE * t));
    // Its first passes time the combined image as it renders (the fastest of them).
    let mut pilot = Pilot::new(scene.camera.pixel_count());
    let t_c = pilot_passes(
        scene,
        opts,
        find("combined", "bsdf"),
        &unguided,
        until,
        MIN_BATCHES + TIMED_PASSES,
        TIMED_PASSES,
        &mut pilot,
    );
    let pilot = pilot;
    let t_pt = t_pt1.min(pass_seconds(scene, opts, find("pt", "bsdf"), &unguided, 2));
    let t_lt = t_lt1.min(pass_seconds(scene, opts, find("lt", "bsdf"), &unguided, 2));
    let reference = pilot.layers[0].clone();
    if reference.sum.iter().all(|p| p.iter().all(|x| *x <= 0.0)) {
        return Choice {
            method: spec.candidates[0],
            reason: "the pilot found no light: the first candidate".into(),
            candidates: Vec::new(),
            pilot: start.elapsed(),
            guidance: None,
        };
    }
    // Pass times at the image's resolution (the pilot's scaled, PILOT_MAX_PIXELS).
    let secs = [t_c, t_pt, t_lt].map(|t| t * pixel_ratio);
    // The time the candidates are compared at (without a budget: the samples asked for, at
    // path tracing's pass time).
    let horizon = |spent: f64| match budget {
        Some(t) => (t - spent).max(1e-3),
        None => opts.spp as f64 * secs[1],
    };
    // Every pilot is measured at the end, with the metric's weights read from the other
    // pilots' combined images (see below).
    let mut pilots: Vec<(&str, Pilot, [f64; 3], [Option<SplitPilot>; 2])> = Vec::new();
    // Guided maps are piloted even when they do not fit when nothing else is wanted.
    let only_guided = spec.candidates.iter().all(|m| m.guide.uses_particles());
    // The unguided candidates measured on the unguided pilot alone (its own image as `R`):
    // what they are when no guide is piloted, and how hard the scene is per sample (the
    // relative variance of one pass of the one predicted best).
    let unguided_alone = {
        let scale = Metric::mean_luminance(&reference);
        let metric = Metric::with_scale(scene.camera.width, &Pooled::new(&[&reference]), scale);
        let folds = fold_metrics(scene.camera.width, &[], &pilot, scale);
        measure(
            scene, &pilot, &reference, &metric, &folds, true, secs, "bsdf",
        )
    };
    // The wanted unguided candidate predicted best with `time_left` seconds left.
    let best_unguided = |time_left: f64| {
        unguided_alone
            .iter()
            .filter(|c| wanted(&c.method))
            .map(|c| {
                let mut c = c.clone();
                c.predict_at(time_left);
                c
            })
            .min_by(|a, b| a.predicted.total_cmp(&b.predicted))
    };
    let easy_scene = best_unguided(horizon(start.elapsed().as_secs_f64()))
        .filter(|c| c.pass_variance < GUIDED_MIN_PASS_VARIANCE);
    // A direction whose unguided layer misses more light (`b²`, which no time removes) than
    // the best unguided candidate's whole predicted error cannot win guided either: a guide
    // does not make the paths it cannot make (a light tracer still cannot see through glass),
    // so its split pilot is not run (Veach Ajar's light tracer: 0.3 s of 30). The best
    // unguided error is taken at the least time the guided pilots can leave (they are
    // piloted within FIRST_GUIDE_MAPS_SHARE of the budget), where it is largest.
    let least_left = horizon(start.elapsed().as_secs_f64() + FIRST_GUIDE_MAPS_SHARE * horizon(0.0));
    let best_at_least = best_unguided(least_left).map_or(f64::INFINITY, |c| c.predicted);
    let misses_light = |direction: &str| {
        let name = format!("{direction}-bsdf");
        let layer = unguided_alone.iter().find(|c| c.method == name);
        layer.is_some_and(|c| c.missing > best_at_least)
    };
    // ---- Guided pilots, when their maps fit ----
    // The view pass's importance target at the image's resolution when its extra passes
    // (TARGET_PASSES unguided combined passes, the pilot's scaled) fit FULL_TARGET_SHARE of
    // the least rendering time left, and the first guide's maps still fit their share with
    // them (decided there); else at the pilot's.
    let target_extra = crate::target::TARGET_PASSES as f64 * (secs[0] - t_c);
    let full_target = pixel_ratio > 1.0
        && opts.guide_params.relative_importance
        && target_extra <= FULL_TARGET_SHARE * least_left;
    let mut target_scene = scene;
    // The target does not depend on the guide: built once, every guide's view pass reads it
    // (without shared passes each guide runs its own).
    let mut target: Option<Option<std::sync::Arc<crate::target::ImportanceTarget>>> = None;
    let mut built: Vec<(String, Guidance)> = Vec::new();
    let guided_start = Instant::now();
    // Where the pilot's time goes (printed with the choice): the unguided pilot, the guided
    // pilots' particle passes with their maps and caches, the guided pilots' passes.
    let unguided_s = start.elapsed().as_secs_f64();
    let (mut maps_s, mut guided_passes_s) = (0.0f64, 0.0f64);
    // What one guide's maps and pilot took (the estimate for the next guide).
    let mut last_guided: Option<f64> = None;
    // With one map round the particle passes do not depend on the guide: they run once and
    // every guide builds its maps and caches from them (`passes_s`: what they took).
    let share = scene.maps.rounds <= 1 && !(opts.specialise && !particles_stored(scene));
    let mut passes_s = 0.0f64;
    // The paper's footprints are piloted first (they measured ahead of the grid in every
    // equal-time cell of door and desk, README): when the budget leaves room for one guide
    // only, it is theirs.
    let guided: Vec<&str> = footprint::guide::GUIDES
        .iter()
        .filter(|g| g.uses_particles())
        .map(|g| g.name())
        .rev()
        .filter(|gname| {
            ["pt", "lt", "combined"]
                .iter()
                .any(|i| wanted(&format!("{i}-{gname}")))
        })
        .collect();
    // The guided pilots share one pilot's time: each guide's passes get PILOT_SHARE / n of
    // the budget, so that every guide fits where one did.
    let guided_count = guided.len();
    let guided_pilot = PILOT_SHARE / guided_count.max(1) as f64;
    for gname in guided {
        // A particle path costs about a pass's path; the map and cache builds about as much
        // again, and the guided pilot passes as much as both (measured on cornell, door and
        // desk: 3-5x the passes' paths alone).
        let npix = scene.camera.pixel_count() as f64;
        let maps_est = match last_guided {
            // The next guide reuses the passes.
            Some(t) => (t - passes_s).max(0.0),
            None => {
                4.0 * (scene.maps.photons as f64 * t_lt / npix
                    + scene.maps.importons as f64 * t_pt / npix)
                    + budget.map_or(0.0, |t| guided_pilot * t)
            }
        };
        if let (Some(c), false) = (&easy_scene, only_guided) {
            notes.push(format!(
                "{gname} not piloted: one pass of {} has relative variance {:.2}, under {GUIDED_MIN_PASS_VARIANCE} (guiding does not repay its maps where unguided passes are this good)",
                c.method, c.pass_variance
            ));
            continue;
        }
        let spent = guided_start.elapsed().as_secs_f64();
        let maps_share = if pilots.is_empty() {
            FIRST_GUIDE_MAPS_SHARE
        } else {
            GUIDED_MAPS_SHARE
        };
        if spent + maps_est > maps_share * horizon(0.0) && !only_guided {
            notes.push(format!(
                "{gname} not piloted: its maps and pilot would take about {maps_est:.2} s, more than {:.0}% of {:.2} s",
                100.0 * maps_share,
                horizon(0.0)
            ));
            continue;
        }
        if full_target && last_guided.is_none() {
            if only_guided || spent + maps_est + target_extra <= maps_share * horizon(0.0) {
                target_scene = image_scene;
            } else {
                notes.push(format!(
                    "importance target at {pilot_w}x{pilot_h}: at {image_w}x{image_h} ({target_extra:.2} s more) the maps would not fit {:.0}% of {:.2} s",
                    100.0 * maps_share,
                    horizon(0.0)
                ));
            }
        }
        let g0 = Instant::now();
        let both = find("combined", gname);
        let o = RenderOptions {
            method: both,
            auto: None,
            ..opts.clone()
        };
        // The view pass's relative importance target renders passes of its own, independent
        // of the pilot's: made from the unguided pilot's image, the importance map followed
        // the noise of the `R` that weighs the light tracer's pilot, and door's
        // `lt-footprint` was predicted at 2-3x its error (seeds 1, 4, 5: 1.12, 0.92, 0.80
        // against 0.40, 0.41, 0.40 with its own passes; rendered 0.30-0.47 either way).
        let gd = if share {
            // The first guide's maps take the passes' particles; a later one copies them
            // from those maps. Copying them for the first as well cost door (128x128) 0.1 s
            // and slowed the map builds after it by 0.35 s (the pilot's particle passes,
            // maps and caches 2.5-2.8 s without the copy, 3.0-3.4 s with, in one hour).
            let passes = match built.first() {
                Some((_, first)) => first.passes(),
                None => {
                    let t = Instant::now();
                    let pass = pass_with_target(scene, target_scene, &o, &mut target);
                    let p = run_passes(scene, &both, &o.guide_params, &pass);
                    passes_s = t.elapsed().as_secs_f64();
                    p
                }
            };
            Guidance::from_passes(scene, &both, &o.guide_params, passes, &|| None)
        } else {
            let pass = pass_with_target(scene, target_scene, &o, &mut target);
            guidance_with(scene, &o, &pass, &|| None)
        };
        let guide_maps_s = g0.elapsed().as_secs_f64();
        maps_s += guide_maps_s;
        // Its first passes time the guided combined image as it renders (its halves also
        // carry their MIS densities; it never splits).
        let until = budget.map(|t| Instant::now() + Duration::from_secs_f64(guided_pilot * t));
        let mut p = Pilot::new(scene.camera.pixel_count());
        let min = TIMED_PASSES + 2;
        let t_c_g = pilot_passes(scene, opts, both, &gd, until, min, TIMED_PASSES, &mut p);
        // The guided pt and lt split as they render (guided splitting), which the combined
        // image's layers cannot show: each is piloted with passes of its own, their noise
        // and time as rendered ([`SplitPilot`]).
        let directions = ["pt", "lt"];
        let splits = opts.guide_params.guided_split > 1;
        // Per direction: its guided method is wanted, and its split pilot skipped.
        let skip: [(bool, bool); 2] = std::array::from_fn(|d| {
            let m = find(directions[d], gname);
            let wanted = wanted(&m.name());
            let skipped = splits && wanted && misses_light(directions[d]);
            if skipped {
                notes.push(format!(
                    "{} not piloted split: {}-bsdf misses more light than the best unguided candidate's predicted error",
                    m.name(),
                    directions[d]
                ));
            }
            (wanted, skipped)
        });
        let split: [Option<SplitPilot>; 2] = std::array::from_fn(|d| {
            let ((wanted, skipped), m) = (skip[d], find(directions[d], gname));
            (splits && wanted && !skipped).then(|| {
                let share = SPLIT_PILOT_SHARE * guided_pilot;
                let until = budget.map(|t| Instant::now() + Duration::from_secs_f64(share * t));
                let stream = 0xa071_0000_0000_0000 ^ ((d as u64) << 40);
                SplitPilot::run(scene, opts, m, &gd, until, MIN_SPLIT_PASSES, stream)
            })
        });
        // Without splitting (`guided_split` 1), or for a direction that misses light, the
        // guided pt and lt passes time themselves (two each, the faster), as the unguided ones
        // do: unsplit, as the combined image's layers measure their noise. A direction not
        // wanted is not timed (its candidate is dropped before any comparison).
        let unsplit = RenderOptions {
            guide_params: GuideParams {
                guided_split: 1,
                ..opts.guide_params.clone()
            },
            ..opts.clone()
        };
        let time = |d: usize| {
            let m = find(directions[d], gname);
            match &split[d] {
                Some(sp) => sp.seconds,
                None if skip[d].0 => pass_seconds(scene, &unsplit, m, &gd, 2),
                None => f64::INFINITY,
            }
        };
        let (t_pt_g, t_lt_g) = (time(0), time(1));
        let guide_s = g0.elapsed().as_secs_f64();
        last_guided = Some(guide_s);
        guided_passes_s += guide_s - guide_maps_s;
        let secs = [t_c_g, t_pt_g, t_lt_g].map(|t| t * pixel_ratio);
        pilots.push((gname, p, secs, split));
        built.push((gname.to_string(), gd));
    }
    // Said where the view pass read a target of the image's size (not only where it was
    // decided: a method without light paths builds none).
    if let Some(Some(t)) = &target
        && pixel_ratio > 1.0
        && (t.width, t.height) == (image_w, image_h)
    {
        notes.push(format!(
            "importance target at {image_w}x{image_h}: about {target_extra:.2} s more than at {pilot_w}x{pilot_h}, within {:.0}% of the {least_left:.2} s left",
            100.0 * FULL_TARGET_SHARE
        ));
    }
    // The pilot time of guides not piloted goes to those piloted: more passes, less noise
    // in their predictions (on Veach Ajar the footprints alone had 8-9 passes, whose
    // estimates of the guided candidates' error ranged over 2.5x from seed to seed).
    let unpiloted = guided_count - pilots.len();
    if let (Some(t), true) = (budget, unpiloted > 0 && !pilots.is_empty()) {
        let each = guided_pilot * t * unpiloted as f64 / pilots.len() as f64;
        let extra_start = Instant::now();
        for ((gname, p, _, _), (_, gd)) in pilots.iter_mut().zip(&built) {
            let until = Instant::now() + Duration::from_secs_f64(each);
            let combined = find("combined", gname);
            pilot_passes(scene, opts, combined, gd, Some(until), 0, 0, p);
        }
        guided_passes_s += extra_start.elapsed().as_secs_f64();
    }
    // The MIS estimates need the densities the guided paths were drawn with: with
    // unguided weights (--guided-mis off) or per-event guiding (no cache: its MIS
    // densities are the BSDF's) the layers read other densities.
    if !(opts.guide_params.guided_mis && opts.guide_params.cache) {
        for (_, p, _, _) in &mut pilots {
            p.m2 = std::array::from_fn(|_| Moments::new(0));
        }
    }
    // The metric's weights `1 / (R² + 0.01)` for each pilot's candidates read `R` from the
    // other pilots' combined images pooled with the pilot's own passes but those of the
    // fold being weighed ([`fold_metrics`]); what exceeds a candidate's own second moment
    // and its missing light are weighed with the other pilots' images alone. A pilot's own
    // image is correlated with its candidates' noise (a bright sample raises both `R` and
    // the variance at its pixel, and the noisiest pixels get the least weight): with a
    // guided pilot's own `R` its candidates came out 3-9x too low. With the other pilots'
    // `R` alone the guided candidates, weighed with the noisy unguided image, came out
    // 1.5-4x too high (door `lt-footprint`, Veach Ajar `pt-footprint`).
    // The pilots are pooled by inverse variance ([`Pooled`]).
    let others = |skip: Option<usize>| -> Vec<&Moments> {
        let unguided = skip.map(|_| &reference);
        let guided = pilots.iter().enumerate().filter(|(j, _)| Some(*j) != skip);
        unguided
            .into_iter()
            .chain(guided.map(|(_, (_, p, _, _))| &p.layers[0]))
            .collect()
    };
    // One scale for every candidate: the image's mean luminance from every pilot pooled
    // (an image-wide mean, barely correlated with any pilot's per-pixel noise); only the
    // per-pixel weights leave a pilot's own image out.
    let mut all_pooled = reference.clone();
    for (_, p, _, _) in &pilots {
        all_pooled.pool(&p.layers[0]);
    }
    let scale = Metric::mean_luminance(&all_pooled);
    // Without guided pilots the weights are the unguided pilot's own, as measured above.
    let mut all = if pilots.is_empty() {
        unguided_alone
    } else {
        let base = others(None);
        let metric = Metric::with_scale(scene.camera.width, &Pooled::new(&base), scale);
        let folds = fold_metrics(scene.camera.width, &base, &pilot, scale);
        measure(
            scene, &pilot, &reference, &metric, &folds, true, secs, "bsdf",
        )
    };
    for (j, (gname, p, secs, split)) in pilots.iter().enumerate() {
        let rest = others(Some(j));
        let own = Metric::with_scale(scene.camera.width, &Pooled::new(&rest), scale);
        let folds = fold_metrics(scene.camera.width, &rest, p, scale);
        all.extend(measure(
            scene, p, &reference, &own, &folds, false, *secs, gname,
        ));
        // What the unguided candidates' own pilot paths missed, seen from the guided paths
        // (crate::moments): the guided pilot's MIS estimate of each unguided estimate's
        // second moment less the unguided pilot's own, weighed without that guided pilot's
        // image (its rare bright paths raise both).
        for (l, c) in all.iter_mut().take(3).enumerate() {
            let e = estimate_index(l);
            let seen = own.excess(&p.m2[moments::UNGUIDED + e], &pilot.m2[moments::OWN + e]);
            if seen > c.unseen {
                c.pass_variance += seen - c.unseen;
                c.unseen = seen;
            }
        }
        // A split direction's per-pass noise: its unsplit layer's as measured (cross-fitted,
        // with what its paths missed), times the ratio of its own passes' noise to the
        // layer's under the same weights ([`split_ratio`]); its time is theirs.
        for (d, sp) in split.iter().enumerate() {
            let name = format!("{}-{gname}", ["pt", "lt"][d]);
            let Some(v) = sp.as_ref().and_then(|sp| sp.pass_variance(&folds)) else {
                continue;
            };
            if let Some(c) = all.iter_mut().find(|c| c.method == name) {
                let ratio = split_ratio(
                    c.pass_variance - c.unseen,
                    v,
                    opts.guide_params.guided_split,
                );
                c.unseen *= ratio;
                c.pass_variance *= ratio;
            }
        }
    }
    // Every candidate predicted at the same time left: what remains after the whole pilot.
    let time_left = horizon(start.elapsed().as_secs_f64());
    for c in &mut all {
        c.predict_at(time_left);
    }
    all.retain(|c| wanted(&c.method));
    all.sort_by(|a, b| a.predicted.total_cmp(&b.predicted));
    // A guided candidate must beat its rivals by their margins, else it steps aside for
    // the next candidate.
    let stepped: Vec<usize> = (0..all.len())
        .filter(|&i| rival(&all, &all[i]).is_some())
        .collect();
    if stepped.first() == Some(&0) {
        let c = &all[0];
        let (u, margin, what) = rival(&all, c).expect("stepped aside");
        notes.push(format!(
            "{} stepped aside: predicted only {:.2}x better than {what} (it must be {margin}x)",
            c.method,
            u / c.predicted
        ));
    }
    if let Some(pos) = (0..all.len()).find(|i| !stepped.contains(i)) {
        let c = all.remove(pos);
        all.insert(0, c);
    }
    let Some(best) = all.first().cloned() else {
        return Choice {
            method: spec.candidates[0],
            reason: format!(
                "{}: no candidate could be piloted ({})",
                spec.candidates[0].name(),
                notes.join("; ")
            ),
            candidates: all,
            pilot: start.elapsed(),
            guidance: None,
        };
    };
    let method = Method::parse(&best.method).expect("a candidate");
    let others: Vec<String> = all[1..]
        .iter()
        .map(|c| format!("{} {:.3e}", c.method, c.predicted))
        .collect();
    let pilot_s = start.elapsed().as_secs_f64();
    let mut reason = format!(
        "{} predicted relative MSE {:.3e} at {:.1} s ({}); pilot {} passes; pilot {pilot_s:.2} s: unguided passes {unguided_s:.2} s, particle passes, maps and caches {maps_s:.2} s, guided passes {guided_passes_s:.2} s, predictions {:.2} s",
        best.method,
        best.predicted,
        time_left,
        others.join(", "),
        pilot.layers[0].n,
        (pilot_s - unguided_s - maps_s - guided_passes_s).max(0.0)
    );
    for c in &all {
        if c.missing > 0.1 * c.predicted && c.missing > 0.0 {
            if let Some(why) = can_miss_light(scene, c.method.split('-').next().unwrap_or("")) {
                reason += &format!("; {} misses light ({why})", c.method);
            }
        }
    }
    for n in notes {
        reason += &format!("; {n}");
    }
    for c in &all {
        if c.unseen > 0.25 * c.pass_variance {
            reason += &format!(
                "; {}: {:.0}% of its predicted noise from paths its own pilot passes missed (seen by MIS from the others)",
                c.method,
                100.0 * c.unseen / c.pass_variance
            );
        }
    }
    let guidance = built
        .into_iter()
        .find(|(g, _)| *g == method.guide.name())
        .map(|(_, g)| g);
    Choice {
        method,
        reason,
        candidates: all,
        pilot: start.elapsed(),
        guidance,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_xoshiro::Xoshiro256PlusPlus;
    use rand_xoshiro::rand_core::{Rng, SeedableRng};

    fn image(w: usize, h: usize, value: impl Fn(usize) -> f32) -> Image {
        Image {
            width: w as u32,
            height: h as u32,
            pixels: (0..w * h).map(|i| Rgb::splat(value(i))).collect(),
        }
    }

    /// Images over PILOT_MAX_PIXELS are piloted with both sides divided alike.
    #[test]
    fn pilot_resolution_divides_both_sides_until_the_pixels_fit() {
        // At or under the limit: the image's own.
        assert_eq!(pilot_resolution(128, 128), (128, 128));
        assert_eq!(pilot_resolution(128, 72), (128, 72));
        assert_eq!(pilot_resolution(16384, 1), (16384, 1));
        // Over it: the least divisor that fits, sides rounded up.
        assert_eq!(pilot_resolution(256, 256), (128, 128));
        assert_eq!(pilot_resolution(129, 128), (65, 64));
        assert_eq!(pilot_resolution(1920, 1080), (160, 90));
        assert_eq!(pilot_resolution(16385, 1), (8193, 1));
        for (w, h) in [(256u32, 256u32), (1000, 3), (4096, 2160), (300, 200)] {
            let (pw, ph) = pilot_resolution(w, h);
            assert!(pw as usize * ph as usize <= PILOT_MAX_PIXELS, "{w}x{h}");
        }
    }

    /// A candidate that was not timed (its direction not wanted) is predicted infinite, not
    /// at one pass's error, and so never ranks ahead of a timed one.
    #[test]
    fn a_candidate_not_timed_is_predicted_infinite() {
        let mut timed = Candidate {
            method: "pt-bsdf".into(),
            predicted: 0.0,
            pass_seconds: 0.01,
            pass_variance: 100.0,
            unseen: 0.0,
            missing: 0.0,
        };
        let mut untimed = Candidate {
            method: "lt-footprint".into(),
            pass_seconds: f64::INFINITY,
            pass_variance: 1e-6,
            ..timed.clone()
        };
        timed.predict_at(10.0);
        untimed.predict_at(10.0);
        assert!((timed.predicted - 0.1).abs() < 1e-12, "{}", timed.predicted);
        assert!(untimed.predicted.is_infinite(), "{}", untimed.predicted);
    }

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

    /// Two pilots of the same image (every pixel 1): 20 passes with per-pass noise of
    /// standard deviation 3, and 5 passes with 0.3. Pooled by inverse variance, the mean's
    /// standard error is `1 / sqrt(20 / 9 + 5 / 0.09)` = 0.132 per pixel; pooled pass by pass
    /// (as before), `sqrt(20 * 9 + 5 * 0.09) / 25` = 0.537. Over 256 pixels of independent
    /// noise (fixed seed) the root-mean-square error has a relative standard deviation of
    /// about `1 / sqrt(2 * 256)` = 4.4%, so 1.2x 0.132 (4.5 of those) bounds the first and
    /// lies far below the second.
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

    fn candidate(method: &str, predicted: f64) -> Candidate {
        Candidate {
            method: method.into(),
            predicted,
            pass_seconds: 0.01,
            pass_variance: 1.0,
            unseen: 0.0,
            missing: 0.0,
        }
    }

    /// The margins: door's seed-2 predictions (`combined-footprint` 0.730 against
    /// `lt-footprint` 0.736) make the combined image step aside for the light tracer, which
    /// splits; far ahead of both tracers it stays; a guided tracer must beat its own
    /// integrator's BSDF sampling by 1.3x, and unguided candidates have no rival.
    #[test]
    fn guided_candidates_beat_their_rivals_by_the_margins() {
        let all = [
            candidate("combined-footprint", 0.730),
            candidate("lt-footprint", 0.736),
            candidate("pt-footprint", 0.877),
            candidate("combined-bsdf", 3.06),
            candidate("pt-bsdf", 1.0),
            candidate("lt-bsdf", 2.39),
        ];
        let (u, margin, _) = rival(&all, &all[0]).expect("steps aside");
        assert_eq!((u, margin), (0.736, SPLIT_MARGIN));
        assert!(
            rival(&all, &all[1]).is_none(),
            "lt-footprint 3.2x ahead of lt-bsdf"
        );
        let (u, margin, _) = rival(&all, &all[2]).expect("only 1.14x ahead of pt-bsdf");
        assert_eq!((u, margin), (1.0, GUIDED_MARGIN));
        assert!(all[3..].iter().all(|c| rival(&all, c).is_none()));
        // Far ahead of its guide's tracers the combined image is chosen.
        let ahead = [
            candidate("combined-footprint", 0.5),
            all[1].clone(),
            all[3].clone(),
        ];
        assert!(rival(&ahead, &ahead[0]).is_none());
        // The margin is against its own guide's tracers, not another guide's.
        let grid = [
            candidate("combined-footprint", 0.5),
            candidate("lt-grid", 0.4),
        ];
        assert!(rival(&grid, &grid[0]).is_none());
    }

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
        // The other folds hold the sample in their `R`, as before.
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
}
