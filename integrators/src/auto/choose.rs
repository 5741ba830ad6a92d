//! The choice: the unguided pilot, the guided pilots where their maps fit, every
//! candidate predicted at the time left, and the ranking (module doc of [`crate::auto`]).

use super::choice::{Choice, Decision, Note, PilotTimes};
use super::metric::{Metric, Pooled, fold_metrics};
use super::params::*;
use super::pilot::{Ahead, Pilot, particle_pass_seconds, pass_seconds, pilot_passes};
use super::predict::{Candidate, GuidedPilot, can_miss_light, measure, predict_all};
use super::rank::rank;
use super::spec::AutoSpec;
use super::split::SplitPilot;
use crate::maps::{Guidance, run_passes};
use crate::method::Method;
use crate::passes::target::{ImportanceTarget, TARGET_PASSES};
use crate::render::{RenderOptions, guidance_with, pass_settings, wants_target, with_built_target};
use crate::skips::particles_stored;
use footprint::scene::Scene;
use footprint::settings::GuideParams;
use std::sync::Arc;
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

fn find(i: &str, g: &str) -> Method {
    Method::from_names(i, g).expect("registered")
}

/// What the guided pilots are given: the unguided pilot's findings and the budget.
struct Plan<'a> {
    /// The scene at the pilot's resolution, and at the image's.
    scene: &'a Scene,
    image_scene: &'a Scene,
    opts: &'a RenderOptions,
    spec: &'a AutoSpec,
    /// When the pilot started.
    started: Instant,
    /// The unguided path and light tracers' pass times at the pilot's resolution.
    t_pt: f64,
    t_lt: f64,
    /// Every candidate guided: their maps are piloted even where they do not fit.
    only_guided: bool,
    /// The best unguided candidate where one pass of it is good enough that guiding does
    /// not repay its maps.
    easy_scene: Option<Candidate>,
    /// The directions whose unguided layer misses more light than the best unguided
    /// candidate's whole predicted error.
    misses_light: [bool; 2],
    /// The importance target may be built at the image's resolution, for `target_extra`
    /// seconds more.
    full_target: bool,
    target_extra: f64,
}

impl Plan<'_> {
    fn wanted(&self, name: &str) -> bool {
        wanted(self.spec, name)
    }

    fn horizon(&self, spent: f64, t_pt_image: f64) -> f64 {
        horizon(self.opts, spent, t_pt_image)
    }

    /// The render a guided pilot's second-moment layers predict, when `more` seconds of
    /// pilot are still to come after now: the unguided pass times in proportion (the
    /// guided pilot times its own combined pass).
    fn ahead(&self, more: f64, t_pt_image: f64) -> Ahead {
        let spent = self.started.elapsed().as_secs_f64() + more;
        Ahead {
            render_s: self.horizon(spent, t_pt_image),
            pass_s: [self.t_pt, self.t_lt, self.t_pt + self.t_lt],
        }
    }
}

fn wanted(spec: &AutoSpec, name: &str) -> bool {
    spec.candidates.iter().any(|m| m.name() == name)
}

/// The time the candidates are compared at after `spent` seconds of pilot (without a
/// budget: the samples asked for, at path tracing's pass time `t_pt_image`).
fn horizon(opts: &RenderOptions, spent: f64, t_pt_image: f64) -> f64 {
    match opts.time {
        Some(t) => (t - spent).max(1e-3),
        None => opts.spp as f64 * t_pt_image,
    }
}

/// What the guided pilots made: each guide's pilot and maps, and their times.
#[derive(Default)]
struct Guided {
    pilots: Vec<GuidedPilot>,
    built: Vec<(String, Guidance)>,
    /// Guides wanted (piloted or not).
    count: usize,
    maps_s: f64,
    passes_s: f64,
    /// The importance target the view passes read (built once for every guide).
    target: Option<Option<Arc<ImportanceTarget>>>,
}

/// Runs the pilot for `opts` (its `time` is the budget) and chooses among `spec`'s
/// candidates.
pub fn choose(scene: &Scene, opts: &RenderOptions, spec: &AutoSpec) -> Choice {
    let start = Instant::now();
    if spec.candidates.len() == 1 {
        return Choice::unpiloted(&spec.label, spec.candidates[0], Decision::OnlyCandidate);
    }
    let budget = opts.time;
    let unguided = Guidance::default();
    let mut notes = Vec::new();
    // ---- A large image is piloted at a lower resolution (PILOT_MAX_PIXELS) ----
    let image = (scene.camera.width, scene.camera.height);
    let pilot_res = pilot_resolution(image.0, image.1);
    let image_scene = scene;
    let lower;
    let scene = if pilot_res == image {
        scene
    } else {
        lower = scene
            .with_resolution(pilot_res.0, pilot_res.1)
            .expect("a smaller resolution of a valid camera");
        &lower
    };
    // Seconds of a pass at the image's resolution per second of a pilot pass.
    let pixel_ratio = (image.0 as f64 * image.1 as f64) / scene.camera.pixel_count() as f64;
    if pixel_ratio > 1.0 {
        notes.push(Note::PilotResolution {
            pilot: pilot_res,
            image,
            pass_scale: pixel_ratio,
        });
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
        let decision = Decision::NoRoomForPilot {
            budget_s: t,
            pairs: MIN_BUDGET_PAIRS,
            pair_s: t_pt1 + t_lt1,
        };
        let mut c = Choice::unpiloted(&spec.label, method, decision);
        c.pilot.total = start.elapsed();
        return c;
    }
    // ---- Unguided pilot: the combined image's three layers ----
    let until = budget.map(|t| start + Duration::from_secs_f64(PILOT_SHARE * t));
    // Its first passes time the combined image as it renders (the fastest of them).
    let mut pilot = Pilot::new(scene.camera.pixel_count());
    // Its second-moment layers predict the render after about the pilot's share (a combined
    // pass takes about a pt and an lt pass).
    let ahead = Ahead {
        render_s: horizon(
            opts,
            PILOT_SHARE * budget.unwrap_or(0.0),
            t_pt1 * pixel_ratio,
        ),
        pass_s: [t_pt1, t_lt1, t_pt1 + t_lt1],
    };
    let t_c = pilot_passes(
        scene,
        opts,
        find("combined", "bsdf"),
        &unguided,
        until,
        MIN_BATCHES + TIMED_PASSES,
        TIMED_PASSES,
        ahead,
        &mut pilot,
    );
    let pilot = pilot;
    let t_pt = t_pt1.min(pass_seconds(scene, opts, find("pt", "bsdf"), &unguided, 2));
    let t_lt = t_lt1.min(pass_seconds(scene, opts, find("lt", "bsdf"), &unguided, 2));
    let reference = &pilot.layers[0];
    if reference.sum.iter().all(|p| p.iter().all(|x| *x <= 0.0)) {
        let mut c = Choice::unpiloted(&spec.label, spec.candidates[0], Decision::NoLight);
        c.pilot.total = start.elapsed();
        return c;
    }
    // Pass times at the image's resolution (the pilot's scaled, PILOT_MAX_PIXELS).
    let secs = [t_c, t_pt, t_lt].map(|t| t * pixel_ratio);
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
            .filter(|c| wanted(spec, &c.method))
            .map(|c| {
                let mut c = c.clone();
                c.predict_at(time_left);
                c
            })
            .min_by(|a, b| a.predicted.total_cmp(&b.predicted))
    };
    let horizon = |spent: f64| horizon(opts, spent, secs[1]);
    let easy_scene = best_unguided(horizon(start.elapsed().as_secs_f64()))
        .filter(|c| c.pass_variance < GUIDED_MIN_PASS_VARIANCE);
    // Path tracing this hard per sample bets on guided path tracing where no guide can be
    // piloted (HARD_PASS_VARIANCE): read on `pt-bsdf`'s own passes (the combined image's
    // are less noisy per pass and slower, and on Veach Ajar read under the threshold where
    // `pt-bsdf`'s read 22-29), unless light tracing is the best unguided candidate (a
    // scene whose light the light tracer finds, Veach Bidir's) or path tracing misses light
    // (checked below, with `misses_light`).
    let best_is_lt = best_unguided(horizon(start.elapsed().as_secs_f64()))
        .is_some_and(|c| c.method.starts_with("lt-"));
    let hard_scene = unguided_alone
        .iter()
        .find(|c| c.method == "pt-bsdf")
        .map(|c| c.pass_variance)
        .filter(|&v| v >= HARD_PASS_VARIANCE && !best_is_lt);
    // A direction whose unguided layer misses more light (`b²`, which no time removes) than
    // the best unguided candidate's whole predicted error cannot win guided either: a guide
    // does not make the paths it cannot make (a light tracer still cannot see through glass),
    // so its split pilot is not run. The best unguided error is taken at the least time the
    // guided pilots can leave (they are piloted within FIRST_GUIDE_MAPS_SHARE of the
    // budget), where it is largest.
    let least_left = horizon(start.elapsed().as_secs_f64() + FIRST_GUIDE_MAPS_SHARE * horizon(0.0));
    let best_at_least = best_unguided(least_left).map_or(f64::INFINITY, |c| c.predicted);
    let misses_light = ["pt", "lt"].map(|direction| {
        let name = format!("{direction}-bsdf");
        let layer = unguided_alone.iter().find(|c| c.method == name);
        layer.is_some_and(|c| c.missing > best_at_least)
    });
    // The view pass's importance target at the image's resolution when its extra passes
    // (TARGET_PASSES unguided combined passes, the pilot's scaled) fit FULL_TARGET_SHARE of
    // the least rendering time left, and the first guide's maps still fit their share with
    // them (decided there); else at the pilot's.
    let target_extra = TARGET_PASSES as f64 * (secs[0] - t_c);
    let full_target = pixel_ratio > 1.0
        && opts.guide_params.relative_importance
        && target_extra <= FULL_TARGET_SHARE * least_left;
    let plan = Plan {
        scene,
        image_scene,
        opts,
        spec,
        started: start,
        t_pt,
        t_lt,
        only_guided: spec.candidates.iter().all(|m| m.guide.uses_particles()),
        easy_scene,
        misses_light,
        full_target,
        target_extra,
    };
    let unguided_s = start.elapsed().as_secs_f64();
    // ---- Guided pilots, when their maps fit ----
    let guided = pilot_guides(&plan, secs[1], pixel_ratio, &mut notes);
    // Where the pilot's time went (`total` set where the choice is made).
    let times = PilotTimes {
        total: Duration::ZERO,
        unguided_s,
        maps_s: guided.maps_s,
        guided_passes_s: guided.passes_s,
        passes: pilot.layers[0].n,
    };
    // No guide piloted because none fit the budget, on a scene hard per sample: guided path
    // tracing with the guide piloted first (the paper's footprints), its maps built with the
    // time left, rather than an unguided method.
    let first_guide = footprint::guide::GUIDES
        .iter()
        .rev()
        .find(|g| g.uses_particles() && wanted(spec, &format!("pt-{}", g.name())));
    let none_fit = guided.pilots.is_empty()
        && !plan.misses_light[0]
        && notes
            .iter()
            .any(|n| matches!(n, Note::MapsTooCostly { .. }));
    if let (Some(pass_variance), Some(g), true) = (hard_scene, first_guide, none_fit) {
        let decision = Decision::HardSceneUnpiloted { pass_variance };
        let mut c = Choice::unpiloted(&spec.label, find("pt", g.name()), decision);
        c.notes = notes;
        c.pilot = PilotTimes {
            total: start.elapsed(),
            ..times
        };
        return c;
    }
    // Said where the view pass read a target of the image's size (not only where it was
    // decided: a method without light paths builds none).
    if let Some(Some(t)) = &guided.target
        && pixel_ratio > 1.0
        && (t.width, t.height) == image
    {
        notes.push(Note::TargetAtImageResolution {
            pilot: pilot_res,
            image,
            extra_s: target_extra,
            share: FULL_TARGET_SHARE,
            left_s: least_left,
        });
    }
    // ---- Every candidate predicted at the time left, and ranked ----
    let mut all = predict_all(
        scene,
        &opts.guide_params,
        reference,
        &pilot,
        unguided_alone,
        secs,
        &guided.pilots,
    );
    // Every candidate predicted at the same time left: what remains after the whole pilot.
    let time_left = horizon(start.elapsed().as_secs_f64());
    for c in &mut all {
        c.predict_at(time_left);
    }
    all.retain(|c| wanted(spec, &c.method));
    notes.extend(rank(&mut all));
    let Some(best) = all.first() else {
        let mut c = Choice::unpiloted(&spec.label, spec.candidates[0], Decision::NothingPiloted);
        c.notes = notes;
        c.pilot = PilotTimes {
            total: start.elapsed(),
            ..times
        };
        return c;
    };
    let method = Method::parse(&best.method).expect("a candidate");
    // What the reason line says beyond the pilot's own notes: who misses light, and whose
    // noise comes mostly from paths its own passes missed.
    let mut said: Vec<Note> = all
        .iter()
        .filter(|c| c.missing > 0.1 * c.predicted && c.missing > 0.0)
        .filter_map(|c| {
            let why = can_miss_light(scene, c.method.split('-').next().unwrap_or(""))?;
            Some(Note::MissesLight {
                method: c.method.clone(),
                why,
            })
        })
        .collect();
    said.extend(notes);
    said.extend(
        all.iter()
            .filter(|c| c.unseen > 0.25 * c.pass_variance)
            .map(|c| Note::Unseen {
                method: c.method.clone(),
                share: c.unseen / c.pass_variance,
            }),
    );
    let guidance = guided
        .built
        .into_iter()
        .find(|(g, _)| *g == method.guide.name())
        .map(|(_, g)| g);
    Choice {
        label: spec.label.clone(),
        method,
        decision: Decision::Predicted {
            time_left_s: time_left,
        },
        candidates: all,
        notes: said,
        pilot: PilotTimes {
            total: start.elapsed(),
            ..times
        },
        guidance,
    }
}

/// The guided pilots: for every wanted guide whose maps fit their share of the budget, its
/// particle passes, maps and caches, passes of its combined image, and its splitting
/// directions' own passes; the pilot time of guides not piloted then goes to those piloted.
fn pilot_guides(plan: &Plan, t_pt_image: f64, pixel_ratio: f64, notes: &mut Vec<Note>) -> Guided {
    let (scene, opts) = (plan.scene, plan.opts);
    let budget = opts.time;
    let horizon = |spent: f64| plan.horizon(spent, t_pt_image);
    let pilot_res = (scene.camera.width, scene.camera.height);
    let image = (
        plan.image_scene.camera.width,
        plan.image_scene.camera.height,
    );
    let mut out = Guided::default();
    let mut target_scene = scene;
    let guided_start = Instant::now();
    // What one guide's maps and pilot took (the estimate for the next guide).
    let mut last_guided: Option<f64> = None;
    // With one map round the particle passes do not depend on the guide: they run once and
    // every guide builds its maps and caches from them (`passes_s`: what they took).
    let share = scene.maps.rounds <= 1 && (!opts.specialise || particles_stored(scene));
    let mut passes_s = 0.0f64;
    // The paper's footprints are piloted first (they measure ahead of the grid on door
    // and desk, docs/measurements/door-desk.md): when the budget leaves room for one guide
    // only, it is theirs.
    let guides: Vec<&'static str> = footprint::guide::GUIDES
        .iter()
        .filter(|g| g.uses_particles())
        .map(|g| g.name())
        .rev()
        .filter(|gname| {
            ["pt", "lt", "combined"]
                .iter()
                .any(|i| plan.wanted(&format!("{i}-{gname}")))
        })
        .collect();
    // The guided pilots share one pilot's time: each guide's passes get PILOT_SHARE / n of
    // the budget, so that every guide fits where one did.
    out.count = guides.len();
    let guided_pilot = PILOT_SHARE / out.count.max(1) as f64;
    // The particle passes' time, once measured (`particle_pass_seconds`).
    let mut probed: Option<f64> = None;
    for gname in guides {
        if let (Some(c), false) = (&plan.easy_scene, plan.only_guided) {
            notes.push(Note::EasyScene {
                guide: gname,
                method: c.method.clone(),
                pass_variance: c.pass_variance,
            });
            continue;
        }
        // The first guide's maps: its particle passes as measured on a part of their paths
        // (the same for every guide, measured once), the map and cache builds up to
        // MAPS_BUILD_FACTOR times as long again, and its pilot passes (the combined image's
        // and each splitting direction's, about twice its pilot share); a later guide takes
        // what the first one's maps and pilot took, less the passes it reuses.
        let maps_est = match last_guided {
            // Every candidate guided: the maps are piloted whatever they cost.
            _ if plan.only_guided => 0.0,
            Some(t) => (t - passes_s).max(0.0),
            None => {
                let both = find("combined", gname);
                // The probe's time counts as the maps' (the pilot's times say so).
                let particles_s = *probed.get_or_insert_with(|| {
                    let t = Instant::now();
                    // Passes skipped where no surface of the scene stores particles.
                    let s = if !opts.specialise || particles_stored(scene) {
                        particle_pass_seconds(scene, opts, &both)
                    } else {
                        0.0
                    };
                    out.maps_s += t.elapsed().as_secs_f64();
                    s
                });
                let target_s = if wants_target(&RenderOptions {
                    method: both,
                    ..opts.clone()
                }) {
                    TARGET_PASSES as f64 * (plan.t_pt + plan.t_lt)
                } else {
                    0.0
                };
                (1.0 + MAPS_BUILD_FACTOR) * particles_s
                    + target_s
                    + budget.map_or(0.0, |t| 2.0 * guided_pilot * t)
            }
        };
        let spent = guided_start.elapsed().as_secs_f64();
        let maps_share = if out.pilots.is_empty() {
            FIRST_GUIDE_MAPS_SHARE
        } else {
            GUIDED_MAPS_SHARE
        };
        if spent + maps_est > maps_share * horizon(0.0) && !plan.only_guided {
            notes.push(Note::MapsTooCostly {
                guide: gname,
                estimate_s: maps_est,
                share: maps_share,
                horizon_s: horizon(0.0),
            });
            continue;
        }
        if plan.full_target && last_guided.is_none() {
            let fits = spent + maps_est + plan.target_extra <= maps_share * horizon(0.0);
            if plan.only_guided || fits {
                target_scene = plan.image_scene;
            } else {
                notes.push(Note::TargetAtPilotResolution {
                    pilot: pilot_res,
                    image,
                    extra_s: plan.target_extra,
                    share: maps_share,
                    horizon_s: horizon(0.0),
                });
            }
        }
        let g0 = Instant::now();
        let both = find("combined", gname);
        let o = RenderOptions {
            method: both,
            ..opts.clone()
        };
        // The view pass's relative importance target renders passes of its own, independent
        // of the pilot's: made from the unguided pilot's image, the importance map would
        // follow the noise of the `R` that weighs the light tracer's pilot.
        let gd = if share {
            // The first guide's maps take the passes' particles; a later one copies them
            // from those maps.
            let passes = match out.built.first() {
                Some((_, first)) => first.passes(),
                None => {
                    let t = Instant::now();
                    let pass = pass_settings(scene, &o);
                    let pass = with_built_target(target_scene, &o, pass, &mut out.target);
                    let p = run_passes(scene, &both, &o.guide_params, &pass);
                    passes_s = t.elapsed().as_secs_f64();
                    p
                }
            };
            Guidance::from_passes(scene, &both, &o.guide_params, passes, &|| None)
        } else {
            let pass = pass_settings(scene, &o);
            let pass = with_built_target(target_scene, &o, pass, &mut out.target);
            guidance_with(scene, &o, &pass, &|| None)
        };
        let guide_maps_s = g0.elapsed().as_secs_f64();
        out.maps_s += guide_maps_s;
        // The guide's pilot passes, its split pilots and the next guides' maps still to come.
        let more = budget.map_or(0.0, |t| 3.0 * guided_pilot * t);
        let ahead = plan.ahead(more, t_pt_image);
        let (p, secs) = pilot_guide(plan, gname, &gd, guided_pilot, ahead, notes);
        let guide_s = g0.elapsed().as_secs_f64();
        last_guided = Some(guide_s);
        out.passes_s += guide_s - guide_maps_s;
        out.pilots.push(GuidedPilot {
            guide: gname,
            pilot: p.0,
            secs: secs.map(|t| t * pixel_ratio),
            split: p.1,
        });
        out.built.push((gname.to_string(), gd));
    }
    // The pilot time of guides not piloted goes to those piloted: more passes, less noise
    // in their predictions.
    let unpiloted = out.count - out.pilots.len();
    if let (Some(t), true) = (budget, unpiloted > 0 && !out.pilots.is_empty()) {
        let each = guided_pilot * t * unpiloted as f64 / out.pilots.len() as f64;
        let extra_start = Instant::now();
        let all_extra = each * out.pilots.len() as f64;
        for (g, (_, gd)) in out.pilots.iter_mut().zip(&out.built) {
            let until = Instant::now() + Duration::from_secs_f64(each);
            let combined = find("combined", g.guide);
            // The guide's own pass times (at the pilot's resolution).
            let [t_c, t_pt, t_lt] = g.secs.map(|t| t / pixel_ratio);
            let ahead = Ahead {
                pass_s: [t_pt, t_lt, t_c],
                ..plan.ahead(all_extra, t_pt_image)
            };
            pilot_passes(
                scene,
                opts,
                combined,
                gd,
                Some(until),
                0,
                0,
                ahead,
                &mut g.pilot,
            );
        }
        out.passes_s += extra_start.elapsed().as_secs_f64();
    }
    out
}

/// One guide's pilot with its maps `gd`: passes of its combined image, and of its guided
/// pt and lt as they render (split) where wanted; returns the pilot, the split pilots and
/// the three pass times (combined, pt, lt) at the pilot's resolution.
fn pilot_guide(
    plan: &Plan,
    gname: &'static str,
    gd: &Guidance,
    guided_pilot: f64,
    ahead: Ahead,
    notes: &mut Vec<Note>,
) -> ((Pilot, [Option<SplitPilot>; 2]), [f64; 3]) {
    let (scene, opts) = (plan.scene, plan.opts);
    let budget = opts.time;
    let both = find("combined", gname);
    // Its first passes time the guided combined image as it renders (its halves also
    // carry their MIS densities; it never splits).
    let until = budget.map(|t| Instant::now() + Duration::from_secs_f64(guided_pilot * t));
    let mut p = Pilot::new(scene.camera.pixel_count());
    let min = TIMED_PASSES + 2;
    let t_c_g = pilot_passes(
        scene,
        opts,
        both,
        gd,
        until,
        min,
        TIMED_PASSES,
        ahead,
        &mut p,
    );
    // The guided pt and lt split as they render (guided splitting), which the combined
    // image's layers cannot show: each is piloted with passes of its own, their noise and
    // time as rendered ([`SplitPilot`]).
    let directions = ["pt", "lt"];
    let splits = opts.guide_params.guided_split > 1;
    // Per direction: its guided method is wanted, and its split pilot skipped.
    let skip: [(bool, bool); 2] = std::array::from_fn(|d| {
        let m = find(directions[d], gname);
        let wanted = plan.wanted(&m.name());
        let skipped = splits && wanted && plan.misses_light[d];
        if skipped {
            notes.push(Note::SplitNotPiloted { method: m.name() });
        }
        (wanted, skipped)
    });
    let split: [Option<SplitPilot>; 2] = std::array::from_fn(|d| {
        let ((wanted, skipped), m) = (skip[d], find(directions[d], gname));
        (splits && wanted && !skipped).then(|| {
            let share = SPLIT_PILOT_SHARE * guided_pilot;
            let until = budget.map(|t| Instant::now() + Duration::from_secs_f64(share * t));
            let stream = 0xa071_0000_0000_0000 ^ ((d as u64) << 40);
            SplitPilot::run(scene, opts, m, gd, until, MIN_SPLIT_PASSES, stream)
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
            None if skip[d].0 => pass_seconds(scene, &unsplit, m, gd, 2),
            None => f64::INFINITY,
        }
    };
    let (t_pt_g, t_lt_g) = (time(0), time(1));
    ((p, split), [t_c_g, t_pt_g, t_lt_g])
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
}
