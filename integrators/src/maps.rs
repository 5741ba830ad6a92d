//! The particle maps and guide caches a method needs (and only those), built before
//! rendering (their pictures: `footprint maps`, `app/src/map_picture.rs`).
//!
//! A guided method needs the photon map when it traces camera paths and the importance map
//! when it traces light paths (the paper's symmetry). With the guide cache on, each map's
//! cache also needs the *other* pass's scattering points as region seeds, so both passes
//! run whenever a cache is built.

use crate::method::Method;
use crate::passes::thinning::{Cells, PARTICLES_PER_REGION, thinned_by_cell};
use crate::passes::{
    PassOutput, PassSettings, grow_light_pass, light_pass, seed_paths, view_pass_seeding,
};
use crate::skips::Skip;
use footprint::guide::cache::{CacheStats, GuideCache, Partition, Seed};
use footprint::guide::particle_map::{MapKind, ParticleInput, ParticleMap};
use footprint::guide::sampler::{GuideSource, GuidedSampler};
use footprint::scene::{Scene, Toward};
use footprint::settings::GuideParams;
use footprint::settings::MAX_MAP_PATHS;
use glam::Vec2;
use rayon::prelude::*;
use std::time::{Duration, Instant};

/// A built map with what it cost.
pub struct BuiltMap {
    pub map: ParticleMap,
    pub pass: PassOutput,
    /// Heap bytes the map keeps (tree and records), when measured.
    pub bytes: Option<usize>,
    /// When the map holds the pass's particles thinned by region (`passes::thinning`): how
    /// many were kept of how many, and the thinning's time.
    pub thinned: Option<(usize, usize, Duration)>,
}

impl BuiltMap {
    pub fn summary(&self) -> String {
        let n = self.map.len();
        let bpp = match self.bytes {
            Some(b) if n > 0 => format!("{:.1} bytes/particle", b as f64 / n as f64),
            _ => format!("{} bytes/record", ParticleMap::RECORD_BYTES),
        };
        let thinned = match self.thinned {
            Some((kept, all, t)) => format!(
                " (thinned by region: {kept} of {all} kept, {:.2} s)",
                t.as_secs_f64()
            ),
            None => String::new(),
        };
        format!(
            "{}: {} particles from {} paths{thinned}, {}, pass {:.2} s, build {:.3} s",
            self.map.kind.name(),
            n,
            self.pass.stats.paths,
            bpp,
            self.pass.stats.time.as_secs_f64(),
            self.map.build_time.as_secs_f64()
        )
    }
}

/// Builds the map of a pass's particles (those of depth `min_depth` or more), or of
/// `thinned`, the pass's particles thinned by region (`passes::thinning`) and the
/// thinning's time, when given;
/// `measure` returns the heap bytes currently allocated (a counting allocator), so the
/// map's own size is the difference around the build.
pub fn build_map(
    kind: MapKind,
    pass: PassOutput,
    thinned: Option<(Vec<ParticleInput>, Duration)>,
    min_depth: u16,
    measure: &dyn Fn() -> Option<usize>,
) -> BuiltMap {
    let before = measure();
    let particles = thinned.as_ref().map_or(&pass.particles[..], |t| &t.0[..]);
    let map = ParticleMap::build_from_depth(kind, particles, min_depth);
    let after = measure();
    let summary = thinned.map(|(t, time)| (t.len(), pass.particles.len(), time));
    let bytes = match (before, after) {
        (Some(b), Some(a)) => Some(a.saturating_sub(b)),
        _ => None,
    };
    BuiltMap {
        map,
        pass,
        bytes,
        thinned: summary,
    }
}

/// Where the time before rendering went.
#[derive(Clone, Debug, Default)]
pub struct MapTimings {
    pub view_pass: Duration,
    pub light_pass: Duration,
    pub map_builds: Duration,
    pub cache_builds: Duration,
}

impl MapTimings {
    pub fn total(&self) -> Duration {
        self.view_pass + self.light_pass + self.map_builds + self.cache_builds
    }
}

/// The maps and caches of one render.
#[derive(Default)]
pub struct Guidance {
    /// The photon map (guides camera paths) and the importance map (guides light paths).
    pub photons: Option<BuiltMap>,
    pub importons: Option<BuiltMap>,
    pub photon_cache: Option<GuideCache>,
    pub importon_cache: Option<GuideCache>,
    pub timings: MapTimings,
    /// One line per map and cache built.
    pub summaries: Vec<String>,
    /// The passes the scene's effects made useless ([`crate::skips`], rule 4).
    pub skipped: Vec<Skip>,
    /// The photon paths before and after a sparse photon map grew with the budget.
    pub grown: Option<(usize, usize)>,
    /// A line per pass thinned to keep the maps within the memory budget ([`thinned`]).
    pub thinned: Vec<String>,
}

/// What the passes of one render produced (the particles, the other pass's seeds, the
/// flux accounting), before any map is built: what `Guidance::from_passes` needs.
#[derive(Clone, Default)]
pub struct Passes {
    pub light: Option<PassOutput>,
    pub view: Option<PassOutput>,
    /// Time of the light passes (and, with several rounds, of the intermediate rounds' map
    /// and cache builds) and of the view passes.
    pub light_time: Duration,
    pub view_time: Duration,
    /// One line per round when there are several.
    pub rounds: Vec<String>,
}

/// Which passes a guided `method` needs: the light pass for the photon map (camera paths) and
/// the view pass for the importance map (light paths); with the guide cache, each map's
/// cache also needs the other pass as its seeds.
pub fn needed_passes(method: &Method, params: &GuideParams) -> (bool, bool) {
    if !method.guided() {
        return (false, false);
    }
    let paths = method.integrator.paths();
    let cache = params.cache;
    (
        paths.camera || (cache && paths.light),
        paths.light || (cache && paths.camera),
    )
}

/// Whether `method`'s view pass only seeds the photon map's cache (it reads the photon map
/// and not the importance map): it then shoots [`seed_paths`] of its paths.
pub fn view_pass_seeds_only(method: &Method) -> bool {
    let paths = method.integrator.paths();
    paths.camera && !paths.light
}

/// Runs the passes `method` needs (with `scene.maps`' path counts; a view pass that only
/// seeds the photon map's cache with [`seed_paths`] of them), in `scene.maps.rounds` rounds
/// that refine each other (see `MapSettings::rounds`; docs/method.md, "Maps that refine each
/// other"; the rounds before the last build both maps and shoot every pass's full count).
pub fn run_passes(
    scene: &Scene,
    method: &Method,
    params: &GuideParams,
    pass: &PassSettings,
) -> Passes {
    let (need_light, need_view) = needed_passes(method, params);
    let seeds_only_view = view_pass_seeds_only(method);
    let rounds = if need_light || need_view {
        scene.maps.rounds.max(1)
    } else {
        1
    };
    let mut out = Passes::default();
    // The relative importance target's pre-render counts as the view pass's time.
    if need_view {
        out.view_time += pass.target.as_ref().map_or(Duration::ZERO, |t| t.time);
    }
    // The guidance of the previous round (both maps and caches; none in the first round).
    let mut previous: Option<Guidance> = None;
    let both = Method {
        integrator: crate::integrator::find_integrator("combined").expect("registered"),
        guide: method.guide,
    };
    let round_params = GuideParams {
        cache: true,
        ..params.clone()
    };
    for r in 0..rounds {
        let last = r + 1 == rounds;
        // Twice the paths of the round before; the last round shoots the full count.
        let share = 0.5f64.powi((rounds - 1 - r) as i32);
        let count = |n: usize| ((n as f64 * share) as usize).max(1);
        let seed = if last {
            pass.seed
        } else {
            pass.seed ^ (0x9e37_79b9_7f4a_7c15u64.wrapping_mul(r as u64 + 1))
        };
        let bsdf = GuidedSampler::bsdf();
        let (light_sampler, view_sampler) = match &previous {
            Some(g) => (
                g.light_sampler(scene, &both, &round_params),
                g.camera_sampler(scene, &both, &round_params),
            ),
            None => (GuidedSampler::bsdf(), GuidedSampler::bsdf()),
        };
        let light = (need_light || !last).then(|| {
            let s = PassSettings {
                paths: count(scene.maps.photons),
                seed,
                ..pass.clone()
            };
            light_pass(scene, &s, if r == 0 { &bsdf } else { &light_sampler })
        });
        let view = (need_view || !last).then(|| {
            let all = count(scene.maps.importons);
            let seeding = seed_paths(all);
            let s = PassSettings {
                paths: if last && seeds_only_view {
                    seeding
                } else {
                    all
                },
                seed,
                ..pass.clone()
            };
            let sampler = if r == 0 { &bsdf } else { &view_sampler };
            view_pass_seeding(scene, &s, sampler, seeding)
        });
        let round = Passes {
            light_time: light.as_ref().map(|p| p.stats.time).unwrap_or_default(),
            view_time: view.as_ref().map(|p| p.stats.time).unwrap_or_default(),
            light,
            view,
            rounds: Vec::new(),
        };
        out.light_time += round.light_time;
        out.view_time += round.view_time;
        if rounds > 1 {
            out.rounds.push(round.summary(scene, r));
        }
        if last {
            out.light = round.light;
            out.view = round.view;
        } else {
            drop((light_sampler, view_sampler));
            let g = Guidance::from_passes(scene, &both, &round_params, round, &|| None);
            out.light_time += g.timings.map_builds + g.timings.cache_builds;
            previous = Some(g);
        }
    }
    out
}

impl Passes {
    /// One line on a round: paths, particles, the share of particles on surfaces the
    /// camera sees, and how often the guided passes fell back to BSDF sampling.
    fn summary(&self, scene: &Scene, round: u32) -> String {
        let side = |name: &str, p: &Option<PassOutput>| match p {
            Some(p) => format!(
                "{name}: {} paths, {} particles, {:.1}% seen by the camera, {}",
                p.stats.paths,
                p.particles.len(),
                100.0 * seen_fraction(scene, &p.particles),
                if p.stats.guided_events > 0 {
                    format!(
                        "guided, {:.1}% fallbacks",
                        100.0 * p.stats.fallbacks as f64 / p.stats.guided_events as f64
                    )
                } else {
                    "unguided".to_string()
                }
            ),
            None => format!("{name}: none"),
        };
        format!(
            "map round {}: {}; {}",
            round + 1,
            side("light pass", &self.light),
            side("view pass", &self.view)
        )
    }
}

/// The fraction of `particles` on surfaces the camera sees directly (inside the image,
/// unoccluded from the lens centre; through thin dielectric sheets as the camera connections see, at most
/// [`SEEN_THROUGH_SHEETS`]), from up to 20,000 of them spread evenly over the list.
pub fn seen_fraction(scene: &Scene, particles: &[ParticleInput]) -> f64 {
    if particles.is_empty() {
        return 0.0;
    }
    let step = particles.len().div_ceil(20_000);
    let sample: Vec<&ParticleInput> = particles.iter().step_by(step).collect();
    let seen = sample
        .par_iter()
        .filter(|p| {
            // Seen from the lens centre (the pinhole's position).
            let Some(c) = scene.camera.connect(p.position, Vec2::splat(0.5)) else {
                return false;
            };
            scene
                .transmittance(
                    Toward::Camera,
                    p.position,
                    p.normal,
                    c.lens,
                    None,
                    SEEN_THROUGH_SHEETS,
                )
                .0
                .max_element()
                > 0.0
        })
        .count();
    seen as f64 / sample.len() as f64
}

/// Most thin dielectric sheets between a particle and the camera for [`seen_fraction`].
pub const SEEN_THROUGH_SHEETS: u32 = 8;

/// With a time budget, a sparse photon map grows: the light pass shoots more paths, by the
/// largest power of two whose passes and builds take at most this share of the budget.
pub const GROWTH_SHARE: f64 = 0.15;
/// A guide cache is sparse when fewer than this share of its regions can guide...
pub const SPARSE_GUIDING: f64 = 0.8;
/// ...or its guiding regions hold on average less than this share of `region_particles`.
pub const SPARSE_FILL: f64 = 0.6;
/// The least share of indirect light ([`indirect_share`]) in a sparse photon cache's regions
/// for its map to grow, where at least [`MAX_GUIDING_TO_WEIGH_LIGHT`] of them guide. Where
/// light reaches the regions mostly directly (a scene open to a sky or an environment map),
/// a denser guide of indirect light pays for less than its passes: at 8 s the material
/// preview (7% indirect) renders at 1.08x `pt-bsdf`'s error ungrown and 1.23x grown, the
/// living room (22%) as well either way.
/// Veach Ajar, door and the slit room, where guiding pays and growth with it, read 60-72%
/// (docs/measurements/public-scenes.md, "Photon map growth and indirect light").
pub const MIN_INDIRECT_SHARE: f64 = 0.5;
/// The share of a sparse cache's regions that guide below which its map grows whatever the
/// light ([`growth`]): the dining room's (no region guides) renders with less error grown.
pub const MAX_GUIDING_TO_WEIGH_LIGHT: f64 = 0.5;
/// Most doublings of a pass (16 times its paths).
pub const MAX_GROWTHS: u32 = 4;

/// True when `scene`'s photon map may grow with a time budget (`maps.grow`, one map round,
/// the guide cache on): the one condition [`Guidance::build_within`] and `compare` share.
pub fn may_grow(scene: &Scene, params: &GuideParams) -> bool {
    scene.maps.grow && scene.maps.rounds <= 1 && params.cache
}

/// Why a cache with statistics `st` is sparse ([`SPARSE_GUIDING`], [`SPARSE_FILL`]), or
/// `None`.
pub fn sparse(st: &CacheStats, params: &GuideParams) -> Option<String> {
    if st.regions == 0 {
        return None;
    }
    let guiding = st.guiding as f64 / st.regions as f64;
    let fill = st.particles as f64 / st.guiding.max(1) as f64 / params.region_particles as f64;
    (guiding < SPARSE_GUIDING || fill < SPARSE_FILL).then(|| {
        format!(
            "{:.0}% of regions guide, {:.0}% full",
            100.0 * guiding,
            100.0 * fill
        )
    })
}

/// The share of the light arriving in `cache`'s regions that came by at least `min_depth`
/// segments: what a guide of `min_depth` particles can lead to, against the direct light
/// (depth 1) that next-event estimation samples. `particles` are the light pass's, every
/// depth; each counts in the region its position and normal fall in (luminance of its flux).
/// `None` when no particle falls in a region.
pub fn indirect_share(
    cache: &GuideCache,
    particles: &[ParticleInput],
    min_depth: u16,
) -> Option<f64> {
    // Chunks summed in order: the same share on any thread count.
    let sums: Vec<(f64, f64)> = particles
        .par_chunks(1 << 14)
        .map(|chunk| {
            let (mut all, mut indirect) = (0.0f64, 0.0f64);
            for p in chunk {
                if cache.lookup_index(p.position, p.normal).is_some() {
                    let l = footprint::math::luminance(p.weight) as f64;
                    all += l;
                    if p.depth >= min_depth {
                        indirect += l;
                    }
                }
            }
            (all, indirect)
        })
        .collect();
    let (all, indirect) = sums
        .iter()
        .fold((0.0, 0.0), |(a, i), &(x, y)| (a + x, i + y));
    (all > 0.0).then(|| indirect / all)
}

/// Whether a photon map grows with a time budget ([`Guidance::grow_within`]).
pub enum Growth {
    /// The cache is not [`sparse`]: the map keeps its count.
    Dense,
    /// The cache is sparse, but most of its regions guide and under [`MIN_INDIRECT_SHARE`]
    /// of the light arriving in them is indirect: the map keeps its count; the run
    /// summary's line says why.
    MostlyDirect(String),
    /// The map grows, for this reason.
    Grows(String),
}

/// Whether the photon map whose light pass stored `particles` grows, its cache `cache`.
pub fn growth(cache: &GuideCache, particles: &[ParticleInput], params: &GuideParams) -> Growth {
    let Some(why) = sparse(&cache.stats, params) else {
        return Growth::Dense;
    };
    // A cache where most regions cannot guide at all grows whatever the light: its vertices
    // are neither guided nor steered by guided Russian roulette, and growth makes them so.
    let guiding = cache.stats.guiding as f64 / cache.stats.regions.max(1) as f64;
    if guiding < MAX_GUIDING_TO_WEIGH_LIGHT {
        return Growth::Grows(why);
    }
    // A guide leads only to light of `min_depth` segments or more: where most of what
    // arrives in the regions is direct light, which next-event estimation samples, a
    // denser guide has little to gain.
    match indirect_share(cache, particles, params.min_depth) {
        Some(share) if share >= MIN_INDIRECT_SHARE => Growth::Grows(format!(
            "{why}, {:.0}% of the light arriving in them indirect",
            100.0 * share
        )),
        share => Growth::MostlyDirect(format!(
            "maps not grown: {why}, but {:.0}% of the light arriving in the regions is \
             indirect (at least {:.0}% grows)",
            100.0 * share.unwrap_or(0.0),
            100.0 * MIN_INDIRECT_SHARE
        )),
    }
}

impl Guidance {
    /// Runs the passes and builds the maps and caches `method` needs.
    pub fn build(
        scene: &Scene,
        method: &Method,
        params: &GuideParams,
        pass: &PassSettings,
        heap: &dyn Fn() -> Option<usize>,
    ) -> Self {
        Self::build_within(scene, method, params, pass, None, heap)
    }

    /// [`Guidance::build`]; with `budget` (a render's time budget) and one map round, a
    /// photon map whose guide cache is [`sparse`] grows: the light pass shoots `2^k` times
    /// its paths (the first ones kept, their weights rescaled, [`grow_light_pass`]), `k` the
    /// largest (at most [`MAX_GROWTHS`]) whose passes and builds take at most
    /// [`GROWTH_SHARE`] of the budget, and the maps and caches are built again (the first
    /// build's time counts). A dense map costs nothing more. The run summary says what grew
    /// and why. The importance map does not grow: on door, light tracing guided by a grown
    /// one loses a third of its passes and has more error (docs/measurements/sweeps.md,
    /// `map_grow`).
    pub fn build_within(
        scene: &Scene,
        method: &Method,
        params: &GuideParams,
        pass: &PassSettings,
        budget: Option<Duration>,
        heap: &dyn Fn() -> Option<usize>,
    ) -> Self {
        let (light, view) = needed_passes(method, params);
        if pass.specialise && (light || view) && !crate::skips::particles_stored(scene) {
            return Guidance {
                skipped: vec![Skip::ParticlePasses(light as usize + view as usize)],
                ..Default::default()
            };
        }
        let passes = run_passes(scene, method, params, pass);
        let Some(budget) = budget.filter(|_| may_grow(scene, params)) else {
            return Self::from_passes(scene, method, params, passes, heap);
        };
        // The view pass's points are kept (timed and charged) as the seeds of a grown photon
        // map's cache; the light pass comes back out of the photon map.
        let times = (passes.light_time, passes.view_time);
        let copy_start = Instant::now();
        let seeds = method
            .integrator
            .paths()
            .camera
            .then(|| passes.view.as_ref().map(|v| v.photon_cache_seeds()))
            .flatten();
        let copying = copy_start.elapsed();
        let mut first = Self::from_passes(scene, method, params, passes, heap);
        first.timings.map_builds += copying;
        first.grow_within(scene, method, params, pass, seeds, times, budget, heap)
    }

    /// Grows a sparse photon map of maps already built ([`Guidance::build_within`]; `auto`
    /// grows its pilot's maps when a method that reads the photon map wins): `seeds` are the
    /// view pass's points (the photon cache's seeds; `None`: read from the importance map
    /// held, only when the map grows), `times` the light and view passes'
    /// times, `budget` the time the growth is a share of. Unchanged when the photon cache
    /// is not sparse or no doubling fits; else the photon map and its cache are built again
    /// from the grown light pass (the first builds' time counts), the importance map and
    /// its cache kept.
    #[allow(clippy::too_many_arguments)]
    pub fn grow_within(
        mut self,
        scene: &Scene,
        method: &Method,
        params: &GuideParams,
        pass: &PassSettings,
        seeds: Option<Vec<Seed>>,
        (light_time, view_time): (Duration, Duration),
        budget: Duration,
        heap: &dyn Fn() -> Option<usize>,
    ) -> Self {
        // Only a method that reads the photon map grows it (auto's pilot builds both maps
        // for the combined image, also when a light tracer wins).
        if !may_grow(scene, params) || !method.integrator.paths().camera {
            return self;
        }
        let (Some(photons), Some(cache)) = (&self.photons, &self.photon_cache) else {
            return self;
        };
        // The decision reads the light pass's particles in the cache: its time counts with
        // the cache's.
        let deciding = Instant::now();
        let decided = growth(cache, &photons.pass.particles, params);
        self.timings.cache_builds += deciding.elapsed();
        let why = match decided {
            Growth::Grows(why) => why,
            Growth::Dense => return self,
            Growth::MostlyDirect(line) => {
                self.summaries.push(line);
                return self;
            }
        };
        // The largest doubling whose passes and builds (the first, and the grown one, taken
        // to grow with the particles) fit the share.
        let built = photons.map.build_time + cache.stats.build_time;
        let cost = |factor: u32| light_time * factor + view_time + built * (1 + factor);
        let paths = photons.pass.stats.paths;
        let mut factor = 1u32;
        while factor < 1 << MAX_GROWTHS
            && 2 * factor as usize * paths <= MAX_MAP_PATHS
            && cost(2 * factor).as_secs_f64() <= GROWTH_SHARE * budget.as_secs_f64()
        {
            factor *= 2;
        }
        if factor == 1 {
            return self;
        }
        // Without `seeds`, the view pass's points come from the importance map held.
        let seeds = seeds.or_else(|| self.importons.as_ref().map(|m| m.pass.photon_cache_seeds()));
        let light = self.photons.take().expect("checked above").pass;
        self.photon_cache = None;
        let s = PassSettings {
            paths: factor as usize * light.stats.paths,
            ..pass.clone()
        };
        self.grown = Some((light.stats.paths, s.paths));
        let grown = format!("photons {} -> {} paths ({why})", light.stats.paths, s.paths);
        let before = light.stats.time;
        let light = grow_light_pass(scene, &s, &GuidedSampler::bsdf(), light);
        if let Some(line) = thinned(scene, "grown light pass", &light) {
            self.thinned.retain(|l| !l.starts_with("light pass"));
            self.summaries.push(line.clone());
            self.thinned.push(line);
        }
        self.timings.light_pass += light.stats.time - before;
        // The first photon map's and cache's lines give way to the grown ones'.
        let name = MapKind::Photons.name();
        self.summaries.retain(|l| !l.starts_with(name));
        let (map, cache) = build_with_cache(
            scene,
            method,
            params,
            MapKind::Photons,
            light,
            seeds,
            &mut self.timings,
            &mut self.summaries,
            heap,
        );
        self.photons = Some(map);
        self.photon_cache = cache;
        self.summaries.push(format!(
            "maps grown with the {:.0}-s budget: {grown} (the first build, {:.2} s, discarded)",
            budget.as_secs_f64(),
            built.as_secs_f64()
        ));
        self
    }

    /// Builds the maps and caches `method` needs from the passes' output.
    pub fn from_passes(
        scene: &Scene,
        method: &Method,
        params: &GuideParams,
        passes: Passes,
        heap: &dyn Fn() -> Option<usize>,
    ) -> Self {
        let mut g = Guidance::default();
        if !method.guided() {
            return g;
        }
        g.timings.light_pass = passes.light_time;
        g.timings.view_pass = passes.view_time;
        g.summaries.extend(passes.rounds);
        let (light, view) = (passes.light, passes.view);
        for (name, pass) in [("light pass", &light), ("view pass", &view)] {
            if let Some(line) = pass.as_ref().and_then(|p| thinned(scene, name, p)) {
                g.summaries.push(line.clone());
                g.thinned.push(line);
            }
        }
        let paths = method.integrator.paths();
        let (photon_map, importance_map) = (paths.camera, paths.light);
        let cache = params.cache;
        // Seeds of each cache: the other pass's scattering points.
        let photon_seeds = (cache && photon_map)
            .then(|| view.as_ref().map(|v| v.photon_cache_seeds()))
            .flatten();
        let importon_seeds = (cache && importance_map)
            .then(|| light.as_ref().map(|l| l.seeds()))
            .flatten();
        let mut make = |kind: MapKind, out: PassOutput, seeds: Option<Vec<_>>| {
            let (t, s) = (&mut g.timings, &mut g.summaries);
            build_with_cache(scene, method, params, kind, out, seeds, t, s, heap)
        };
        if let (true, Some(out)) = (photon_map, light) {
            let (b, c) = make(MapKind::Photons, out, photon_seeds);
            g.photons = Some(b);
            g.photon_cache = c;
        }
        if let (true, Some(out)) = (importance_map, view) {
            let (b, c) = make(MapKind::Importons, out, importon_seeds);
            g.importons = Some(b);
            g.importon_cache = c;
        }
        g
    }

    /// The passes these maps were built from (a copy; no rounds), for another guide to
    /// build its maps from the same particles. Complete only for a method that builds both
    /// maps (the combined image, as `auto`'s pilot): a pass kept only as the other cache's
    /// seeds is not held and comes back `None`; a grown photon map gives the grown pass.
    pub fn passes(&self) -> Passes {
        Passes {
            light: self.photons.as_ref().map(|b| b.pass.clone()),
            view: self.importons.as_ref().map(|b| b.pass.clone()),
            light_time: self.timings.light_pass,
            view_time: self.timings.view_pass,
            rounds: Vec::new(),
        }
    }

    /// The sampler of camera paths (over the photon map).
    pub fn camera_sampler(
        &self,
        scene: &Scene,
        method: &Method,
        params: &GuideParams,
    ) -> GuidedSampler<'_> {
        let (map, cache) = (self.photons.as_ref(), self.photon_cache.as_ref());
        sampler(scene, method, params, map, cache)
    }

    /// The sampler of light paths (over the importance map).
    pub fn light_sampler(
        &self,
        scene: &Scene,
        method: &Method,
        params: &GuideParams,
    ) -> GuidedSampler<'_> {
        let (map, cache) = (self.importons.as_ref(), self.importon_cache.as_ref());
        sampler(scene, method, params, map, cache)
    }
}

/// The line that says a pass was thinned to keep the maps within the memory budget
/// ([`crate::passes::thinning`]); `None` when it kept every particle.
pub fn thinned(scene: &Scene, name: &str, pass: &PassOutput) -> Option<String> {
    let level = pass.stats.thinning;
    (level > 0).then(|| {
        format!(
            "{name} thinned to keep the maps within max_memory {}: kept 1/{} of its {} particles ({}), each weighing {}x",
            footprint::memory::format_size(footprint::memory::budget(scene.maps.max_memory)),
            1u64 << level,
            pass.stats.particles_drawn,
            pass.particles.len(),
            1u64 << level,
        )
    })
}

/// Builds the map of `kind` from a pass's output and, with `seeds`, its guide cache; their
/// times and summaries are added to `timings` and `summaries`.
#[allow(clippy::too_many_arguments)]
fn build_with_cache(
    scene: &Scene,
    method: &Method,
    params: &GuideParams,
    kind: MapKind,
    out: PassOutput,
    seeds: Option<Vec<Seed>>,
    timings: &mut MapTimings,
    summaries: &mut Vec<String>,
    heap: &dyn Fn() -> Option<usize>,
) -> (BuiltMap, Option<GuideCache>) {
    let max_dist = scene.map_max_dist();
    // The cache's regions first, so that the map holds only what they can read
    // (`passes::thinning`, "Thinning by region").
    let partition = seeds.map(|s| Partition::new(&s, params, max_dist));
    let start = Instant::now();
    let thinned = partition.as_ref().and_then(|p| {
        let cells = Cells {
            count: p.cells(),
            of: |q: &ParticleInput| p.cell(q.position, q.normal),
            centre: |c| p.centre(c),
        };
        let per_cell = PARTICLES_PER_REGION * params.region_particles;
        let (level, min_depth) = (out.stats.thinning, params.min_depth);
        thinned_by_cell(&out.particles, level, min_depth, cells, per_cell)
    });
    let thinned = thinned.map(|t| (t, start.elapsed()));
    let built = build_map(kind, out, thinned, params.min_depth, heap);
    timings.map_builds += built.map.build_time + built.thinned.map_or(Duration::ZERO, |t| t.2);
    summaries.push(built.summary());
    let cache = partition.map(|partition| {
        let c = GuideCache::from_partition(&built.map, method.guide, partition, params, max_dist);
        timings.cache_builds += c.stats.build_time;
        summaries.push(format!("{} cache: {}", kind.name(), c.stats.summary()));
        c
    });
    (built, cache)
}

fn sampler<'a>(
    scene: &Scene,
    method: &Method,
    params: &GuideParams,
    map: Option<&'a BuiltMap>,
    cache: Option<&'a GuideCache>,
) -> GuidedSampler<'a> {
    let source = match (cache, map) {
        (Some(c), _) => GuideSource::Cached(c),
        (None, Some(m)) => GuideSource::PerEvent {
            map: &m.map,
            guide: method.guide,
            max_dist: scene.map_max_dist(),
        },
        (None, None) => GuideSource::Bsdf,
    };
    GuidedSampler {
        source,
        params: params.clone(),
        soft_glossy_max: scene.maps.soft_glossy_max,
        selection: None,
    }
}
