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
//!   times the ratio of the two under the same weights ([`split::split_ratio`]), its time
//!   its own passes'. On door this is the difference: light tracing gains 1.7x from splitting, path
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

mod metric;
mod params;
mod pilot;
mod predict;
mod split;

pub use params::*;
pub use predict::Candidate;

use crate::maps::{Guidance, run_passes};
use crate::method::Method;
use crate::render::{RenderOptions, guidance_with, pass_settings, with_built_target};
use crate::skips::particles_stored;
use footprint::scene::Scene;
use footprint::settings::GuideParams;
use metric::{Metric, Pooled, fold_metrics};
use pilot::{Pilot, pass_seconds, pilot_passes};
use predict::{GuidedPilot, can_miss_light, measure, predict_all};
use split::SplitPilot;
use std::time::{Duration, Instant};

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

/// Orders `all` by prediction, best first, but a guided candidate that fails to beat its
/// rival by its margin ([`rival`]) steps aside for the first that does not (all stay in
/// order of prediction behind it). Returns the note that says so when the best predicted
/// stepped aside.
fn rank(all: &mut Vec<Candidate>) -> Option<String> {
    all.sort_by(|a, b| a.predicted.total_cmp(&b.predicted));
    let stepped: Vec<usize> = (0..all.len())
        .filter(|&i| rival(all, &all[i]).is_some())
        .collect();
    let note = (stepped.first() == Some(&0)).then(|| {
        let c = &all[0];
        let (u, margin, what) = rival(all, c).expect("stepped aside");
        format!(
            "{} stepped aside: predicted only {:.2}x better than {what} (it must be {margin}x)",
            c.method,
            u / c.predicted
        )
    });
    if let Some(pos) = (0..all.len()).find(|i| !stepped.contains(i)) {
        let c = all.remove(pos);
        all.insert(0, c);
    }
    note
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
    let reference = &pilot.layers[0];
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
    // pilots' combined images ([`predict_all`]).
    let mut pilots: Vec<GuidedPilot> = Vec::new();
    // Guided maps are piloted even when they do not fit when nothing else is wanted.
    let only_guided = spec.candidates.iter().all(|m| m.guide.uses_particles());
    // The unguided candidates measured on the unguided pilot alone (its own image as `R`):
    // what they are when no guide is piloted, and how hard the scene is per sample (the
    // relative variance of one pass of the one predicted best).
    let unguided_alone = {
        let scale = Metric::mean_luminance(&[reference]);
        let metric = Metric::with_scale(scene.camera.width, &Pooled::new(&[reference]), scale);
        let folds = fold_metrics(scene.camera.width, &[], &pilot, scale);
        measure(
            scene, &pilot, reference, &metric, &folds, true, secs, "bsdf",
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
    let share = scene.maps.rounds <= 1 && (!opts.specialise || particles_stored(scene));
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
                    let pass =
                        with_built_target(target_scene, &o, pass_settings(scene, &o), &mut target);
                    let p = run_passes(scene, &both, &o.guide_params, &pass);
                    passes_s = t.elapsed().as_secs_f64();
                    p
                }
            };
            Guidance::from_passes(scene, &both, &o.guide_params, passes, &|| None)
        } else {
            let pass = with_built_target(target_scene, &o, pass_settings(scene, &o), &mut target);
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
        pilots.push(GuidedPilot {
            guide: gname,
            pilot: p,
            secs,
            split,
        });
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
        for (g, (_, gd)) in pilots.iter_mut().zip(&built) {
            let until = Instant::now() + Duration::from_secs_f64(each);
            let combined = find("combined", g.guide);
            pilot_passes(scene, opts, combined, gd, Some(until), 0, 0, &mut g.pilot);
        }
        guided_passes_s += extra_start.elapsed().as_secs_f64();
    }
    let mut all = predict_all(
        scene,
        &opts.guide_params,
        reference,
        &pilot,
        unguided_alone,
        secs,
        &pilots,
    );
    // Every candidate predicted at the same time left: what remains after the whole pilot.
    let time_left = horizon(start.elapsed().as_secs_f64());
    for c in &mut all {
        c.predict_at(time_left);
    }
    all.retain(|c| wanted(&c.method));
    if let Some(note) = rank(&mut all) {
        notes.push(note);
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
        if c.missing > 0.1 * c.predicted
            && c.missing > 0.0
            && let Some(why) = can_miss_light(scene, c.method.split('-').next().unwrap_or(""))
        {
            reason += &format!("; {} misses light ({why})", c.method);
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

    /// Ranking: by prediction, but the best predicted steps aside for the first candidate
    /// that clears its margins, and so does every other that fails them (door's seed-2
    /// predictions: the combined image steps aside for the light tracer, and so does
    /// guided path tracing, only 1.23x ahead of `pt-bsdf`); the others keep their
    /// order, and the note names the combined image's rival; no note where the best
    /// predicted clears its margins.
    #[test]
    fn the_best_predicted_steps_aside_for_the_first_that_clears_its_margins() {
        let mut all = vec![
            candidate("pt-bsdf", 0.9),
            candidate("lt-footprint", 0.736),
            candidate("pt-footprint", 0.733),
            candidate("combined-footprint", 0.730),
            candidate("lt-bsdf", 2.39),
        ];
        let note = rank(&mut all).expect("the combined image steps aside");
        let order: Vec<&str> = all.iter().map(|c| c.method.as_str()).collect();
        assert_eq!(
            order,
            [
                "lt-footprint",
                "combined-footprint",
                "pt-footprint",
                "pt-bsdf",
                "lt-bsdf"
            ]
        );
        assert!(
            note.starts_with("combined-footprint stepped aside") && note.contains("pt or lt"),
            "{note}"
        );
        let mut clear = vec![
            candidate("pt-bsdf", 1.0),
            candidate("lt-footprint", 0.5),
            candidate("lt-bsdf", 2.39),
        ];
        assert!(rank(&mut clear).is_none());
        assert_eq!(clear[0].method, "lt-footprint");
    }
}
