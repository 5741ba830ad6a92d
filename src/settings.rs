//! What a scene file's `[render]`, `[maps]` and `[guide]` tables hold (the command line
//! overrides them): plain data with the paper's defaults, read by serde and checked by
//! `validate`, whose errors name the setting. The scene stores these values; only the
//! renderer reads them, so the scene does not depend on the guiding code.

use serde::{Deserialize, Serialize};

/// A setting with a bad value: which one, and why. A scene file reports it as
/// `guide.k_p: ...`, the command line as `--k-p ...` ([`SettingError::flag`]).
#[derive(Debug, Clone, thiserror::Error)]
#[error("{table}.{key} {message}")]
pub struct SettingError {
    /// The scene file's table: `render`, `maps` or `guide`.
    pub table: &'static str,
    /// The key in that table (the command-line flag is the same name with dashes).
    pub key: &'static str,
    pub message: String,
}

impl SettingError {
    fn new(table: &'static str, key: &'static str, message: String) -> Self {
        SettingError {
            table,
            key,
            message,
        }
    }

    /// The command-line flag of the setting (underscores become dashes).
    pub fn flag(&self) -> String {
        format!("--{}", self.key.replace('_', "-"))
    }

    /// The message as the command line shows it: `--k-p must be ...`.
    pub fn as_flag_error(&self) -> String {
        format!("{} {}", self.flag(), self.message)
    }
}

/// A name given in a scene file with where it was given, so that an unknown name can be
/// reported at its place (`door.toml:12:14`) by the code that knows the valid names.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Named {
    pub name: String,
    /// `file:line:column`, or the file alone.
    pub at: String,
}

/// The `[render]` table.
#[derive(Clone, Debug)]
pub struct RenderSettings {
    /// The integrator's name (`pt`, `lt`, `combined`; resolved by the integrators crate).
    pub integrator: Option<Named>,
    /// The direction sampler's name (`bsdf`, `grid`, `footprint`).
    pub guide: Option<Named>,
    /// Samples per pixel (path tracing) or light paths per pixel (light tracing).
    pub spp: u32,
    /// Time budget in seconds; when set it replaces `spp`.
    pub time: Option<f64>,
    /// Maximum number of path segments.
    pub max_depth: u32,
    /// Russian roulette applies after scattering at vertices of this depth or deeper
    /// (Mitsuba's `rr_depth`; [`DEFAULT_RR_DEPTH`] by default).
    pub rr_depth: u32,
    pub seed: u64,
    /// Exposure of the PNG preview in stops (`--exposure` overrides it): a dim scene such as
    /// door sets it so that its first picture is not black.
    pub exposure: f32,
}

/// Russian roulette's default start depth ([`RenderSettings::rr_depth`]): 8, where Mitsuba's
/// `path` starts at 5. The throughput rule cuts the long paths that carry light into rooms
/// lit indirectly, and starting later measured better at equal time on four of five scenes
/// (Veach Ajar `pt-bsdf` 0.76x the error, door `lt-footprint` 0.75x, desk `lt-bsdf` 0.89x,
/// Bitterli's box 0.96x; cornell, whose paths end at 8 segments, 1.05x; the table:
/// `docs/measurements/sweeps.md`, "Russian roulette depth").
pub const DEFAULT_RR_DEPTH: u32 = 8;

impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings {
            integrator: None,
            guide: None,
            spp: 16,
            time: None,
            max_depth: 8,
            rr_depth: DEFAULT_RR_DEPTH,
            seed: 0,
            exposure: 0.0,
        }
    }
}

impl RenderSettings {
    pub fn validate(&self) -> Result<(), SettingError> {
        let e = |key, m: String| Err(SettingError::new("render", key, m));
        if self.spp == 0 {
            return e("spp", "must be at least 1".into());
        }
        if let Some(t) = self.time {
            if !(t.is_finite() && t > 0.0) {
                return e(
                    "time",
                    format!("must be a positive number of seconds, got {t}"),
                );
            }
        }
        if self.rr_depth == 0 || self.rr_depth > 1024 {
            return e(
                "rr_depth",
                format!("must be in 1..=1024, got {}", self.rr_depth),
            );
        }
        if !self.exposure.is_finite() {
            return e(
                "exposure",
                format!("must be a finite number of stops, got {}", self.exposure),
            );
        }
        if self.max_depth == 0 || self.max_depth > 1024 {
            return e(
                "max_depth",
                format!("must be in 1..=1024, got {}", self.max_depth),
            );
        }
        Ok(())
    }
}

/// Largest particle path count accepted (each path may store several particles).
pub const MAX_MAP_PATHS: usize = 50_000_000;

/// The `[maps]` table: the two particle passes.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(default, deny_unknown_fields)]
pub struct MapSettings {
    /// Photon paths shot by the light pass.
    pub photons: usize,
    /// Importon paths shot by the view pass (the first quarter of them seed the photon map's
    /// cache, and path tracing shoots only those: `footprint_integrators::passes::seed_paths`).
    pub importons: usize,
    /// Maximum distance of a particle from a query point; `None`: 5% of the scene's
    /// bounding-box diagonal.
    pub max_dist: Option<f32>,
    /// Blinn exponents up to this are "soft glossy" (particles stored, footprints used);
    /// above it "strongly glossy" (treated like specular).
    pub soft_glossy_max: f32,
    /// Rounds of passes that refine each other: round `r + 1`'s light pass is guided by
    /// round `r`'s importance map (photons go where the camera looks) and its view pass by
    /// round `r`'s photon map (importons go where light comes from). Each round shoots twice
    /// the paths of the one before; the last shoots `photons` and `importons`, and only its
    /// particles make the maps. 1: one unguided round.
    pub rounds: u32,
    /// With a time budget, a photon map whose guide cache is sparse (few regions guide, or
    /// few particles per region) grows: the light pass shoots 2 to 16 times the paths, as
    /// many as fit 15% of the budget (`Guidance::build_within` in the integrators crate).
    pub grow: bool,
    /// Bytes the particle maps and guide caches may take (`None`: half the machine's
    /// memory, [`crate::memory::budget`]); past it each pass keeps a share of its particles
    /// (`integrators/src/passes/thinning.rs`).
    #[serde(
        with = "crate::memory::serde_size",
        skip_serializing_if = "Option::is_none"
    )]
    pub max_memory: Option<u64>,
}

impl Default for MapSettings {
    fn default() -> Self {
        MapSettings {
            photons: 200_000,
            importons: 200_000,
            max_dist: None,
            soft_glossy_max: 100.0,
            rounds: 1,
            grow: true,
            max_memory: None,
        }
    }
}

impl MapSettings {
    /// Checks the settings; the error names the offending key.
    pub fn validate(&self) -> Result<(), SettingError> {
        let e = |key, m: String| Err(SettingError::new("maps", key, m));
        for (key, n) in [("photons", self.photons), ("importons", self.importons)] {
            if n == 0 {
                return e(key, "must be at least 1".into());
            }
            if n > MAX_MAP_PATHS {
                return e(
                    key,
                    format!("= {n} is absurd: at most {MAX_MAP_PATHS} paths"),
                );
            }
        }
        if let Some(d) = self.max_dist {
            if !(d.is_finite() && d > 0.0) {
                return e("max_dist", format!("must be a positive distance, got {d}"));
            }
        }
        if self.rounds == 0 || self.rounds > 8 {
            return e("rounds", format!("must be in 1..=8, got {}", self.rounds));
        }
        if !(self.soft_glossy_max.is_finite() && self.soft_glossy_max >= 0.0) {
            return e(
                "soft_glossy_max",
                format!("must be finite and >= 0, got {}", self.soft_glossy_max),
            );
        }
        Ok(())
    }
}

/// How the footprint radius follows the directional density (docs/method.md, "Eq. 7").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RadiusRule {
    /// The cap's solid angle is k_r over the directional density (particles per steradian)
    SolidAngle,
    /// Eq. 7 as printed: radius k_r over the density g/ω
    Literal,
}

impl RadiusRule {
    pub fn name(self) -> &'static str {
        match self {
            RadiusRule::SolidAngle => "solid-angle",
            RadiusRule::Literal => "literal",
        }
    }
}

/// The `[guide]` table: parameters of the guided samplers (paper §3 defaults) and of the
/// guide cache.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(default, deny_unknown_fields)]
pub struct GuideParams {
    /// `k_p`: particles per per-event query, and the fewest a cached region guides with.
    pub k_p: usize,
    /// Side of the footprint density grid (`k_g = side²`, paper: 32 x 32).
    #[serde(rename = "k_g")]
    pub k_g_side: usize,
    /// `k_r`: footprint radius scale.
    pub k_r: f32,
    /// Probability of sampling the BSDF where guiding (with `learn_p_bsdf`: until the guide
    /// cache has pooled enough records to choose for the regions that have not learned
    /// their own).
    pub p_bsdf: f32,
    /// Camera paths (path tracing, the combined image) and light paths (light tracing, the
    /// combined image) learn the probability of sampling the BSDF per region of their guide
    /// cache from earlier passes, 1 (not guided) where guiding does not pay for its time
    /// (`src/guide/selection.rs`). On by default.
    pub learn_p_bsdf: bool,
    /// Russian roulette reads the guide cache's estimate of what a path would still gather
    /// (its region's particle density times the path's throughput and the surface's
    /// albedo) against that estimate at the path's first vertex, instead of the throughput
    /// alone (`integrators/src/walk.rs`, "Guided Russian roulette").
    pub guided_rr: bool,
    /// Guided splitting (with `guided_rr`; path tracing and light tracing, not the combined
    /// image): a path expected to gather `r > 1` times what its first estimated vertex did
    /// is split into `r` branches in expectation, at most this many, each with its share of
    /// the throughput (`integrators/src/walk.rs`); 1 never splits.
    pub guided_split: u32,
    /// The view pass weighs each importon path by `m / (L + 0.1 m)`, `L` its pixel's
    /// luminance in a short unguided pre-render and `m` the mean: the importance map then
    /// guides light paths where the relative error is (`integrators/src/target.rs`).
    pub relative_importance: bool,
    pub radius_rule: RadiusRule,
    /// Side of the classic sampler's grid per hemisphere (Jensen 1995).
    #[serde(rename = "grid")]
    pub grid_side: usize,
    /// Prepare the guide distributions once per region of space and normal direction
    /// (the guide cache) instead of at every scattering event (the paper's method).
    pub cache: bool,
    /// Most particles one cached region's distribution is built from.
    pub region_particles: usize,
    /// Most scattering points of the other pass per region of the cache.
    pub region_seeds: usize,
    /// Particles that reached their surface in fewer segments are left out of the maps that
    /// guide. Depth-1 photons carry direct light, which next-event estimation samples already;
    /// depth-1 importons point at the camera, which a light path cannot hit (its camera
    /// connection covers that light). 1 keeps every particle.
    pub min_depth: u16,
    /// The combined image's MIS weights use the densities the guided samplers really draw
    /// with (with the guide cache: a region lookup per vertex) instead of the unguided ones.
    pub guided_mis: bool,
    /// Side of the per-hemisphere grid on which each cached region's guide density is
    /// tabulated for those weights (`src/guide/table.rs`); 0 reads the exact density. Only
    /// footprints sampled from their caps (`raster = 0`) have a table: a rasterised
    /// distribution's density is a lookup already.
    pub mis_table: usize,
    /// Side of the equal-area grid per hemisphere on which a cached region's footprint
    /// mixture is rasterised for sampling (`FootprintDistribution::rasterise`); 0 samples
    /// the caps themselves (the paper's method).
    pub raster: usize,
    /// Particles whose `|cos θ_p|` is below this are left out, identically in sampling and
    /// evaluation (a cap confined to the hemisphere would have no room).
    #[serde(skip)]
    pub grazing_cos_min: f32,
}

impl Default for GuideParams {
    fn default() -> Self {
        GuideParams {
            k_p: 50,
            k_g_side: 32,
            k_r: 6.0,
            p_bsdf: 0.5,
            learn_p_bsdf: true,
            guided_rr: true,
            guided_split: 4,
            relative_importance: true,
            radius_rule: RadiusRule::SolidAngle,
            grid_side: 8,
            cache: true,
            region_particles: 400,
            region_seeds: 4096,
            min_depth: 2,
            guided_mis: true,
            mis_table: 16,
            raster: 16,
            grazing_cos_min: 1e-3,
        }
    }
}

impl GuideParams {
    /// Checks the parameters; the error names the key.
    pub fn validate(&self) -> Result<(), SettingError> {
        let e = |key, m: String| Err(SettingError::new("guide", key, m));
        if self.k_p == 0 || self.k_p > 10_000 {
            return e("k_p", format!("must be in 1..=10000, got {}", self.k_p));
        }
        if self.k_g_side < 3 || self.k_g_side > 1024 {
            return e(
                "k_g",
                format!("must be a side length in 3..=1024, got {}", self.k_g_side),
            );
        }
        if !(self.k_r.is_finite() && self.k_r > 0.0) {
            return e("k_r", format!("must be positive, got {}", self.k_r));
        }
        if !(self.p_bsdf > 0.0 && self.p_bsdf <= 1.0) {
            return e(
                "p_bsdf",
                format!(
                    "must be in (0, 1] (0 would leave directions the particles miss unsampled), got {}",
                    self.p_bsdf
                ),
            );
        }
        if self.grid_side == 0 || self.grid_side > 1024 {
            return e(
                "grid",
                format!("must be a side length in 1..=1024, got {}", self.grid_side),
            );
        }
        if self.region_particles < self.k_p || self.region_particles > 65_535 {
            return e(
                "region_particles",
                format!(
                    "must be in k_p..=65535 (k_p = {}), got {}",
                    self.k_p, self.region_particles
                ),
            );
        }
        if self.region_seeds < 8 || self.region_seeds > 1_000_000 {
            return e(
                "region_seeds",
                format!("must be in 8..=1000000, got {}", self.region_seeds),
            );
        }
        if self.mis_table == 1 || self.mis_table > 256 {
            return e(
                "mis_table",
                format!(
                    "must be 0 (the exact density) or a side length in 2..=256, got {}",
                    self.mis_table
                ),
            );
        }
        if self.raster > 1024 {
            return e(
                "raster",
                format!(
                    "must be 0 (sample the caps) or a side length in 1..=1024, got {}",
                    self.raster
                ),
            );
        }
        if self.min_depth == 0 || self.min_depth > 1024 {
            return e(
                "min_depth",
                format!("must be in 1..=1024, got {}", self.min_depth),
            );
        }
        if !(self.grazing_cos_min > 0.0 && self.grazing_cos_min < 0.5) {
            return e(
                "grazing_cos_min",
                format!("must be in (0, 0.5), got {}", self.grazing_cos_min),
            );
        }
        Ok(())
    }
}
