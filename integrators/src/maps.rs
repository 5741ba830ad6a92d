//! The particle maps and guide caches a method needs (and only those), built before
//! rendering (their pictures: [`crate::map_picture`]).
//!
//! A guided method needs the photon map when it traces camera paths and the importance map
//! when it traces light paths (the paper's symmetry). With the guide cache on, each map's
//! cache also needs the *other* pass's scattering points as region seeds, so both passes
//! run whenever a cache is built.

use crate::method::Method;
use crate::passes::{PassOutput, PassSettings, light_pass, view_pass};
use footprint::guide::cache::GuideCache;
use footprint::guide::particle_map::{MapKind, ParticleMap};
use footprint::guide::sampler::{GuideSource, GuidedSampler};
use footprint::scene::Scene;
use footprint::settings::GuideParams;
use std::time::Duration;

/// A built map with what it cost.
pub struct BuiltMap {
    pub map: ParticleMap,
    pub pass: PassOutput,
    /// Heap bytes the map keeps (tree and records), when measured.
    pub bytes: Option<usize>,
}

impl BuiltMap {
    pub fn summary(&self) -> String {
        let n = self.map.len();
        let bpp = match self.bytes {
            Some(b) if n > 0 => format!("{:.1} bytes/particle", b as f64 / n as f64),
            _ => format!("{} bytes/record", ParticleMap::RECORD_BYTES),
        };
        format!(
            "{}: {} particles from {} paths, {}, pass {:.2} s, build {:.3} s",
            self.map.kind.name(),
            n,
            self.pass.stats.paths,
            bpp,
            self.pass.stats.time.as_secs_f64(),
            self.map.build_time.as_secs_f64()
        )
    }
}

/// Builds the map of a pass's particles (those of depth `min_depth` or more); `measure` returns the heap bytes currently
/// allocated (a counting allocator), so the map's own size is the difference around the
/// build.
pub fn build_map(
    kind: MapKind,
    pass: PassOutput,
    min_depth: u16,
    measure: &dyn Fn() -> Option<usize>,
) -> BuiltMap {
    let before = measure();
    let map = ParticleMap::build_from_depth(kind, &pass.particles, min_depth);
    let after = measure();
    let bytes = match (before, after) {
        (Some(b), Some(a)) => Some(a.saturating_sub(b)),
        _ => None,
    };
    BuiltMap { map, pass, bytes }
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
}

/// What the passes of one render produced (the particles, the other pass's seeds, the
/// flux accounting), before any map is built: what `Guidance::from_passes` needs.
#[derive(Default)]
pub struct Passes {
    pub light: Option<PassOutput>,
    pub view: Option<PassOutput>,
    pub light_time: Duration,
    pub view_time: Duration,
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

/// Runs the passes `method` needs (with `scene.maps`' path counts).
pub fn run_passes(
    scene: &Scene,
    method: &Method,
    params: &GuideParams,
    pass: &PassSettings,
) -> Passes {
    let (light, view) = needed_passes(method, params);
    let bsdf = GuidedSampler::bsdf();
    let light = light.then(|| {
        let s = PassSettings {
            paths: scene.maps.photons,
            ..pass.clone()
        };
        light_pass(scene, &s, &bsdf)
    });
    let view = view.then(|| {
        let s = PassSettings {
            paths: scene.maps.importons,
            ..pass.clone()
        };
        view_pass(scene, &s, &bsdf)
    });
    Passes {
        light_time: light.as_ref().map(|p| p.stats.time).unwrap_or_default(),
        view_time: view.as_ref().map(|p| p.stats.time).unwrap_or_default(),
        light,
        view,
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
        let passes = run_passes(scene, method, params, pass);
        Self::from_passes(scene, method, params, passes, heap)
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
        let (light, view) = (passes.light, passes.view);
        let paths = method.integrator.paths();
        let (photon_map, importance_map) = (paths.camera, paths.light);
        let cache = params.cache;
        // Seeds of each cache: the other pass's scattering points.
        let photon_seeds = (cache && photon_map)
            .then(|| view.as_ref().map(|v| v.seeds()))
            .flatten();
        let importon_seeds = (cache && importance_map)
            .then(|| light.as_ref().map(|l| l.seeds()))
            .flatten();
        let max_dist = scene.map_max_dist();
        let mut make = |kind: MapKind, out: PassOutput, seeds: Option<Vec<_>>| {
            let built = build_map(kind, out, params.min_depth, heap);
            g.timings.map_builds += built.map.build_time;
            g.summaries.push(built.summary());
            let cache = seeds.map(|s| {
                let c = GuideCache::build(&built.map, method.guide, &s, params, max_dist);
                g.timings.cache_builds += c.stats.build_time;
                g.summaries
                    .push(format!("{} cache: {}", kind.name(), c.stats.summary()));
                c
            });
            (built, cache)
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
    }
}
