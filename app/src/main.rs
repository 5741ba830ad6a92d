//! The `footprint` command line.

use anyhow::{Context, Result, bail};
use clap::builder::{PossibleValue, PossibleValuesParser};
use clap::{Parser, Subcommand};
use footprint::film::image_io::{write_exr, write_png};
use footprint::guide::GUIDES;
use footprint::scene::Scene;
use footprint::settings::RadiusRule;
use footprint_integrators::integrator::INTEGRATORS;
use footprint_app::scene_hash::scene_content_hash;
use footprint_integrators::{Method, RenderOptions};
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;

mod bench;

/// Counts the heap bytes in use, so that `maps` and `render` can report what a particle map
/// really occupies (kd-tree included).
#[global_allocator]
static GLOBAL: footprint::heap::CountingAlloc = footprint::heap::CountingAlloc;

fn heap_bytes() -> Option<usize> {
    Some(footprint::heap::heap_bytes())
}

#[derive(Parser, Debug)]
#[command(
    name = "footprint",
    version,
    about = "A physically based CPU renderer that guides light and view paths with particle maps",
    long_about = "footprint renders scenes described in TOML (see README.md, \"Scene format\") or \
                  Mitsuba 3 XML (docs/mitsuba.md) with path tracing, light tracing or both, guided \
                  by particle maps.\n\nExamples:\n  footprint render scenes/desk/desk.toml\n  \
                  footprint render scene.xml -D resx=128 -D resy=72"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Acceleration structure: Embree 3 where the system has it (`libembree3`, loaded at
    /// run time; Debian: libembree3-3), else footprint's own CWBVH [default:
    /// FOOTPRINT_ACCEL, else auto]
    #[arg(long, global = true, value_enum)]
    accel: Option<footprint::scene::accel::Backend>,
}

/// `--integrator`'s values: the registered integrators, with their help lines.
fn integrator_values() -> PossibleValuesParser {
    PossibleValuesParser::new(
        INTEGRATORS
            .iter()
            .map(|i| PossibleValue::new(i.name()).help(i.about()))
            .chain([PossibleValue::new("auto")
                .help("Chosen by a short pilot: the method predicted to give the lowest error")]),
    )
}

/// `--guide`'s values: the registered guides, with their help lines.
fn guide_values() -> PossibleValuesParser {
    PossibleValuesParser::new(
        GUIDES
            .iter()
            .map(|g| PossibleValue::new(g.name()).help(g.about()))
            .chain([PossibleValue::new("auto").help(
                "Chosen by a short pilot (guided candidates where the scene is hard per sample and their maps fit the budget)",
            )]),
    )
}

/// Direction-sampler parameters (paper defaults) and the guide cache.
#[derive(clap::Args, Debug, Clone)]
struct GuideParamArgs {
    /// Particles per query, k_p [default: the scene's guide.k_p, else 50]
    #[arg(long)]
    k_p: Option<usize>,
    /// Side of the footprint density grid (k_g = side²) [default: guide.k_g, else 32]
    #[arg(long)]
    k_g: Option<usize>,
    /// Footprint radius scale k_r [default: guide.k_r, else 6]
    #[arg(long, allow_negative_numbers = true)]
    k_r: Option<f32>,
    /// Probability of sampling the BSDF where guiding [default: guide.p_bsdf, else 0.5]
    #[arg(long, allow_negative_numbers = true)]
    p_bsdf: Option<f32>,
    /// Footprint radius rule [default: guide.radius_rule, else solid-angle]
    #[arg(long, value_enum)]
    radius_rule: Option<RadiusRule>,
    /// Side of the classic sampler's grid per hemisphere [default: guide.grid, else 8]
    #[arg(long)]
    grid: Option<usize>,
    /// Prepare guide distributions once per region (on) or at every scattering event as
    /// the paper does (off) [default: guide.cache, else on]
    #[arg(long, value_parser = ["on", "off"])]
    guide_cache: Option<String>,
    /// Most particles per cached region [default: guide.region_particles, else 400]
    #[arg(long)]
    region_particles: Option<usize>,
    /// Most scattering points of the other pass per cached region [default:
    /// guide.region_seeds, else 4096]
    #[arg(long)]
    region_seeds: Option<usize>,
    /// Leave particles that arrived in fewer segments out of the guiding maps (2: no direct
    /// light in the photon map, no camera directions in the importance map; 1: keep all)
    /// [default: guide.min_depth, else 2]
    #[arg(long)]
    min_depth: Option<u16>,
    /// The combined image's MIS weights from the guided samplers' densities (on) or the
    /// unguided ones (off) [default: guide.guided_mis, else on]
    #[arg(long, value_parser = ["on", "off"])]
    guided_mis: Option<String>,
    /// Camera paths (pt, combined) learn the probability of sampling the BSDF per region of
    /// the guide cache from earlier passes (on) or keep --p-bsdf everywhere (off)
    /// [default: guide.learn_p_bsdf, else off]
    #[arg(long, value_parser = ["on", "off"])]
    learn_p_bsdf: Option<String>,
    /// Russian roulette reads the guide cache's estimate of what a path would still gather
    /// against that estimate at its first vertex (on), or its throughput alone (off); guided
    /// paths only [default: guide.guided_rr, else on]
    #[arg(long, value_parser = ["on", "off"])]
    guided_rr: Option<String>,
    /// Guided splitting (pt, lt; not the combined image): a guided path expected to gather
    /// r > 1 times what its first estimated vertex did is split into r branches (in
    /// expectation), at most this many; 1 never splits; needs --guided-rr on [default:
    /// guide.guided_split, else 4]
    #[arg(long)]
    guided_split: Option<u32>,
    /// The view pass weighs each importon path by m / (L + 0.1 m), L its pixel's luminance
    /// in a short unguided pre-render (4 passes of the combined image) and m the image's
    /// mean: light paths are guided where the relative error is (on), or by the camera's
    /// importance alone (off); methods whose light paths are guided only [default:
    /// guide.relative_importance, else on]
    #[arg(long, value_parser = ["on", "off"])]
    relative_importance: Option<String>,
    /// Side of the per-hemisphere table of each cached region's density that those guided
    /// MIS weights read when footprints are sampled from their caps (--raster 0); 0 reads
    /// the exact density (slower, the same image in expectation)
    /// [default: guide.mis_table, else 16]
    #[arg(long)]
    mis_table: Option<usize>,
    /// Side of the equal-area grid per hemisphere on which each cached region's footprint
    /// mixture is rasterised for sampling (a cell search and a lookup instead of a walk over
    /// the caps); 0 samples the caps, as the paper does [default: guide.raster, else 16]
    #[arg(long)]
    raster: Option<usize>,
}

impl GuideParamArgs {
    fn apply(&self, p: &mut footprint::settings::GuideParams) -> Result<()> {
        if let Some(v) = self.k_p {
            p.k_p = v;
        }
        if let Some(v) = self.k_g {
            p.k_g_side = v;
        }
        if let Some(v) = self.k_r {
            p.k_r = v;
        }
        if let Some(v) = self.p_bsdf {
            p.p_bsdf = v;
        }
        if let Some(v) = self.radius_rule {
            p.radius_rule = v;
        }
        if let Some(v) = self.grid {
            p.grid_side = v;
        }
        if let Some(v) = &self.guide_cache {
            p.cache = v == "on";
        }
        if let Some(v) = self.region_particles {
            p.region_particles = v;
        }
        if let Some(v) = self.region_seeds {
            p.region_seeds = v;
        }
        if let Some(v) = self.min_depth {
            p.min_depth = v;
        }
        if let Some(v) = &self.guided_mis {
            p.guided_mis = v == "on";
        }
        if let Some(v) = &self.learn_p_bsdf {
            p.learn_p_bsdf = v == "on";
        }
        if let Some(v) = &self.guided_rr {
            p.guided_rr = v == "on";
        }
        if let Some(v) = self.guided_split {
            p.guided_split = v;
        }
        if let Some(v) = &self.relative_importance {
            p.relative_importance = v == "on";
        }
        if let Some(v) = self.mis_table {
            p.mis_table = v;
        }
        if let Some(v) = self.raster {
            p.raster = v;
        }
        p.validate().map_err(|e| anyhow::anyhow!(e.as_flag_error()))
    }
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Render a scene to an EXR (linear float RGB) and a PNG preview
    Render {
        /// Scene file: footprint TOML (.toml) or Mitsuba 3 XML (.xml)
        scene: PathBuf,
        /// Integrator [default: the scene's render.integrator; when neither the integrator
        /// nor the guide is given here or in the scene, auto; else pt]
        #[arg(long, value_parser = integrator_values())]
        integrator: Option<String>,
        /// Direction sampler [default: the scene's render.guide; auto when neither is given;
        /// else bsdf]
        #[arg(long, value_parser = guide_values())]
        guide: Option<String>,
        /// Samples per pixel (pt) or light paths per pixel (lt) [default: the scene's render.spp, else 16]
        #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
        spp: Option<u32>,
        /// Render for this many seconds instead of a sample count
        #[arg(long, conflicts_with = "spp", allow_negative_numbers = true)]
        time: Option<f64>,
        /// Maximum path length in segments [default: the scene's render.max_depth, else 8]
        #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
        max_depth: Option<u32>,
        /// Russian roulette after scattering at vertices of this depth or deeper (Mitsuba's
        /// rr_depth; guided vertices with --guided-rr on use their estimate at every depth)
        /// [default: the scene's render.rr_depth, else 8]
        #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
        rr_depth: Option<u32>,
        /// Random seed; equal seeds give equal images whatever the thread count [default: the scene's render.seed, else 0]
        #[arg(long)]
        seed: Option<u64>,
        /// Output EXR path; the PNG preview is written beside it with the extension .png
        /// [default: <scene name>.exr in the current directory]
        #[arg(long, short)]
        out: Option<PathBuf>,
        /// Exposure of the PNG preview in stops (the preview is 2^exposure * linear, clamped,
        /// sRGB-encoded) [default: the scene's render.exposure, else 0]
        #[arg(long, allow_negative_numbers = true)]
        exposure: Option<f32>,
        /// Image size WIDTHxHEIGHT, replacing the scene's camera.resolution (same vertical field of view)
        #[arg(long, value_parser = parse_resolution)]
        resolution: Option<(u32, u32)>,
        /// Worker threads [default: all cores]
        #[arg(long)]
        threads: Option<usize>,
        /// How camera samples reach the film: splat into every pixel under the filter
        /// (Mitsuba, pbrt-v3) or filter importance sampling (pbrt-v4; uncorrelated pixels)
        #[arg(long, value_enum, default_value_t = footprint::film::FilmMode::Splat)]
        film: footprint::film::FilmMode,
        /// The numbers camera and light paths draw (pbrt's and Mitsuba's sampler): one point
        /// of a pixel's own Owen-scrambled Sobol sequence per pass (pbrt-v4's default kind),
        /// or independent numbers (Mitsuba's `independent`). Both converge to the same image
        #[arg(long, value_enum, default_value_t = footprint::rng::Sequence::Sobol)]
        sequence: footprint::rng::Sequence,
        /// Render only shard i of N (zero-based): the passes k < spp with k mod N = i, so that
        /// N shards with the same --spp (the total) and seed, put together by `footprint
        /// merge`, are the image of one run. Needs --spp, not --time
        #[arg(long, value_name = "i/N", value_parser = footprint_integrators::PassSelection::parse)]
        shard: Option<footprint_integrators::PassSelection>,
        /// Load the particle maps' passes from this file (written by `footprint maps --save`)
        /// instead of running them; refused if made for another scene or other settings
        #[arg(long = "maps", value_name = "MAPS.fpm")]
        maps_file: Option<PathBuf>,
        /// Run the general path loop instead of the one compiled for the scene's effects
        /// (the same image, bit for bit; for measuring what the specialisation gains)
        #[arg(long)]
        general_loop: bool,
        #[command(flatten)]
        params: GuideParamArgs,
        #[command(flatten)]
        maps: MapArgs,
        #[command(flatten)]
        import: ImportArgs,
    },
    /// Put the shards of one render (`render --shard i/N`) together: every layer, weighted
    /// by its sample count; refuses shards of other scenes, settings or seeds, a shard given
    /// twice, and missing ones
    Merge {
        /// Output EXR (the PNG preview is written beside it)
        out: PathBuf,
        /// The shards' EXR files, all N of them, in any order
        #[arg(required = true)]
        shards: Vec<PathBuf>,
        /// Exposure of the PNG preview in stops
        #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
        exposure: f32,
    },
    /// Build the photon map and the importance map and write pictures of them seen from the camera
    ///
    /// Runs the light pass (photons) and the view pass (importons), builds both maps and
    /// their guide caches (what `render --integrator combined --guide footprint` uses) and
    /// prints for each its particles, bytes per particle, pass and build times, and the
    /// caches' regions, memory and build time. Writes DIR/photons.png (irradiance, W/m²) and
    /// DIR/importons.png (importance per m²): for every pixel a density estimate from the 32
    /// nearest particles at the surface the pixel sees, on a log scale with a legend below the
    /// image; surfaces without particles are grey.
    ///
    /// Example: footprint maps scenes/door/door.toml --out maps-door
    Maps {
        /// Scene file: footprint TOML (.toml) or Mitsuba 3 XML (.xml)
        scene: PathBuf,
        /// Folder for photons.png and importons.png (created if missing; existing pictures
        /// are replaced)
        #[arg(long, short, required_unless_present = "save")]
        out: Option<PathBuf>,
        /// Save both passes' particles (what the maps and guide caches are built from) to this
        /// file, for `render --maps`; it records the scene's content hash and the map settings
        #[arg(long, value_name = "MAPS.fpm")]
        save: Option<PathBuf>,
        /// Image size WIDTHxHEIGHT, replacing the scene's (the view pass depends on it: use
        /// the render's)
        #[arg(long, value_parser = parse_resolution)]
        resolution: Option<(u32, u32)>,
        #[command(flatten)]
        maps: MapArgs,
        #[command(flatten)]
        import: ImportArgs,
        /// Maximum path length in segments [default: the scene's render.max_depth]
        #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
        max_depth: Option<u32>,
        /// Random seed [default: the scene's render.seed]
        #[arg(long)]
        seed: Option<u64>,
        /// Worker threads [default: all cores]
        #[arg(long)]
        threads: Option<usize>,
        #[command(flatten)]
        params: GuideParamArgs,
    },
    /// Compare methods at equal time (map passes included) against a reference: table, error
    /// against time, parameter sweeps, and an HTML page
    Compare {
        /// Scene file: footprint TOML (.toml) or Mitsuba 3 XML (.xml)
        scene: PathBuf,
        /// Equal-time budget in seconds per method (the top of the ladder)
        #[arg(long, default_value_t = 8.0)]
        time: f64,
        /// Budgets at which the error is measured, comma-separated [default: time/8,time/4,time/2,time]
        #[arg(long, value_delimiter = ',')]
        ladder: Option<Vec<f64>>,
        /// Reference image (EXR, same resolution); default: rendered once with the combined
        /// image and BSDF sampling at --reference-spp and cached next to the scene
        #[arg(long)]
        reference: Option<PathBuf>,
        /// Samples per pixel of a rendered reference
        #[arg(long, default_value_t = 256, value_parser = clap::value_parser!(u32).range(1..))]
        reference_spp: u32,
        /// Folder for the cached reference [default: the scene's folder]
        #[arg(long)]
        reference_cache: Option<PathBuf>,
        /// Methods, comma-separated, each INTEGRATOR-GUIDE (pt|lt|combined - bsdf|grid|footprint)
        /// [default: pt and lt with each guide, and combined-footprint]
        #[arg(long, value_delimiter = ',')]
        methods: Option<Vec<String>>,
        /// Parameter sweep NAME=V1,V2,... over k_p, k_r, p_bsdf, learn_p_bsdf (0, 1), guided_rr (0, 1), guided_split, relative_importance (0, 1), k_g, grid, region_particles,
        /// region_seeds, min_depth, mis_table, raster, photons, importons, map_rounds,
        /// map_grow (0, 1) or sequence (sobol, independent): every method is run once per value [default methods for a sweep: pt-footprint,lt-footprint]
        #[arg(long)]
        sweep: Option<String>,
        /// Output folder [default: compare-<scene name>]
        #[arg(long, short)]
        out: Option<PathBuf>,
        /// Image size WIDTHxHEIGHT [default: the scene's]
        #[arg(long, value_parser = parse_resolution)]
        resolution: Option<(u32, u32)>,
        /// Maximum path length in segments [default: the scene's render.max_depth]
        #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
        max_depth: Option<u32>,
        /// Random seed of the method renders
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Worker threads [default: all cores]
        #[arg(long)]
        threads: Option<usize>,
        #[command(flatten)]
        params: GuideParamArgs,
        #[command(flatten)]
        maps: MapArgs,
        #[command(flatten)]
        import: ImportArgs,
    },
    /// Print the error metrics of `footprint compare` (relative MSE, mean absolute error,
    /// spots) of an image against a reference, e.g. for another renderer's image
    Metrics {
        /// Image (EXR)
        image: PathBuf,
        /// Reference (EXR, same size)
        #[arg(long)]
        reference: PathBuf,
    },
    /// Write a scene as Mitsuba 3 XML (scene.xml + one OBJ per material in meshes/), for
    /// rendering it with Mitsuba; the XML takes -D resx, resy, spp, max_depth, rfilter
    Export {
        /// Scene file: footprint TOML (.toml) or Mitsuba 3 XML (.xml)
        scene: PathBuf,
        /// Output folder (created if missing)
        #[arg(long, short)]
        out: PathBuf,
        #[command(flatten)]
        import: ImportArgs,
    },
    /// Measure speed: closest-hit rays per second on door, path samples per second on cornell
    Bench {
        /// Folder holding the bundled scenes
        #[arg(long, default_value = "scenes")]
        scenes: PathBuf,
        /// Seconds to spend on each measurement
        #[arg(long, default_value_t = 3.0)]
        seconds: f64,
        /// Worker threads [default: all cores]
        #[arg(long)]
        threads: Option<usize>,
        /// A further scene (TOML or Mitsuba XML, e.g. Veach Ajar with -D resx=128 -D
        /// resy=72) whose guided path throughput is measured next to door's
        #[arg(long)]
        scene: Option<PathBuf>,
        #[command(flatten)]
        import: ImportArgs,
    },
}

/// Scene-import flags (Mitsuba 3 XML scenes).
#[derive(clap::Args, Debug, Clone)]
struct ImportArgs {
    /// Set a Mitsuba XML parameter, overriding its <default> (repeatable), as Mitsuba's own
    /// -D: `-D resx=128 -D resy=72`
    #[arg(short = 'D', value_name = "NAME=VALUE", value_parser = footprint::scene::mitsuba::parse_define)]
    define: Vec<(String, String)>,
    /// Replace unsupported Mitsuba elements with documented stand-ins (listed on stderr)
    /// instead of stopping with an error
    #[arg(long)]
    lenient: bool,
}

impl ImportArgs {
    /// Loads the scene file with these flags; prints what a lenient import replaced.
    fn load(&self, path: &Path) -> Result<Scene> {
        let opts = footprint::scene::mitsuba::ImportOptions {
            defines: self.define.clone(),
            lenient: self.lenient,
        };
        let sc = footprint::scene::load::load_scene_with(path, &opts)?;
        for n in &sc.import_notes {
            eprintln!("note: {n}");
        }
        Ok(sc)
    }
}

/// Particle-map flags, shared by the commands that build maps.
#[derive(clap::Args, Debug, Clone)]
struct MapArgs {
    /// Photon paths shot by the light pass (with --time, more when the map grows: --map-grow)
    /// [default: the scene's maps.photons, else 200000]
    #[arg(long)]
    photons: Option<usize>,
    /// Importon paths shot by the view pass [default: the scene's maps.importons, else 200000]
    #[arg(long)]
    importons: Option<usize>,
    /// Maximum distance of a particle from a query point [default: the scene's maps.max_dist,
    /// else 5% of the scene's bounding-box diagonal]
    #[arg(long, allow_negative_numbers = true)]
    max_dist: Option<f32>,
    /// Largest Blinn exponent counted as soft glossy (particles stored) [default: the scene's
    /// maps.soft_glossy_max, else 100]
    #[arg(long, allow_negative_numbers = true)]
    soft_glossy_max: Option<f32>,
    /// Rounds of passes that refine each other: each round's light pass is guided by the
    /// round before's importance map, its view pass by the photon map; each round shoots
    /// twice the paths of the one before, the last the full counts [default: the scene's
    /// maps.rounds, else 1]
    #[arg(long)]
    map_rounds: Option<u32>,
    /// With --time: when the photon map's guide cache is sparse (under 80% of its regions
    /// guide, or their particles fill under 60% of region_particles), the light pass shoots
    /// 2, 4, 8 or 16 times its paths, as many as fit 15% of the budget (on), or keeps its
    /// count (off); not with several map rounds or --guide-cache off [default: the scene's
    /// maps.grow, else on]
    #[arg(long, value_parser = ["on", "off"])]
    map_grow: Option<String>,
}

impl MapArgs {
    /// Applies the flags to the scene's map settings and validates them.
    fn apply(&self, scene: &mut Scene) -> Result<()> {
        let m = &mut scene.maps;
        if let Some(v) = self.photons {
            m.photons = v;
        }
        if let Some(v) = self.importons {
            m.importons = v;
        }
        if self.max_dist.is_some() {
            m.max_dist = self.max_dist;
        }
        if let Some(v) = self.soft_glossy_max {
            m.soft_glossy_max = v;
        }
        if let Some(v) = self.map_rounds {
            m.rounds = v;
        }
        if let Some(v) = &self.map_grow {
            m.grow = v == "on";
        }
        m.validate().map_err(|e| anyhow::anyhow!(e.as_flag_error()))
    }
}

/// Loads a scene and applies the map flags and a resolution override.
fn load_scene_with(
    path: &Path,
    import: &ImportArgs,
    maps: &MapArgs,
    resolution: Option<(u32, u32)>,
) -> Result<Scene> {
    let mut sc = import.load(path)?;
    maps.apply(&mut sc)?;
    if let Some((w, h)) = resolution {
        sc.camera = sc
            .camera
            .with_resolution(w, h)
            .map_err(|e| anyhow::anyhow!("--resolution: {e}"))?;
    }
    Ok(sc)
}

fn parse_resolution(s: &str) -> std::result::Result<(u32, u32), String> {
    let (w, h) = s
        .split_once('x')
        .ok_or_else(|| format!("expected WIDTHxHEIGHT, got '{s}'"))?;
    let w: u32 = w
        .trim()
        .parse()
        .map_err(|_| format!("bad width in '{s}'"))?;
    let h: u32 = h
        .trim()
        .parse()
        .map_err(|_| format!("bad height in '{s}'"))?;
    if w == 0 || h == 0 || w > 32768 || h > 32768 {
        return Err(format!(
            "resolution must be between 1x1 and 32768x32768, got {w}x{h}"
        ));
    }
    Ok((w, h))
}

fn main() {
    // Bad input exits with 1 whether the argument parser or the renderer finds it (clap's
    // own exit code for a usage error is 2); `--help` and `--version` exit with 0.
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let _ = e.print();
            std::process::exit(if e.use_stderr() { 1 } else { 0 });
        }
    };
    if let Some(backend) = cli.accel {
        footprint::scene::accel::set_backend(backend);
    }
    if let Err(e) = run(cli) {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}

fn set_threads(threads: Option<usize>) -> Result<()> {
    if let Some(n) = threads {
        if n == 0 {
            bail!("--threads must be at least 1");
        }
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()
            .context("cannot set up the thread pool")?;
    }
    Ok(())
}

fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Render {
            scene,
            integrator,
            spp,
            time,
            max_depth,
            rr_depth,
            seed,
            out,
            exposure,
            resolution,
            threads,
            shard,
            maps_file,
            general_loop,
            guide,
            film,
            sequence,
            params,
            maps,
            import,
        } => {
            set_threads(threads)?;
            if let Some(t) = time {
                if !(t.is_finite() && t > 0.0) {
                    bail!("--time must be a positive number of seconds, got {t}");
                }
            }
            if shard.is_some() && time.is_some() {
                bail!(
                    "--shard needs --spp, not --time: with a time budget every machine renders as many passes as its speed allows, so the shards would not add up to the samples of one run; give every shard the same --spp (the total)"
                );
            }
            if exposure.is_some_and(|x| !x.is_finite()) {
                bail!("--exposure must be finite");
            }
            let t0 = Instant::now();
            let sc = load_scene_with(&scene, &import, &maps, resolution)?;
            let load_time = t0.elapsed();
            let mut opts = RenderOptions::from_scene(&sc).map_err(anyhow::Error::msg)?;
            let neither = integrator.is_none()
                && guide.is_none()
                && sc.settings.integrator.is_none()
                && sc.settings.guide.is_none();
            opts.apply_names(integrator.as_deref(), guide.as_deref())
                .map_err(anyhow::Error::msg)?;
            // A shard keeps the fixed default (pt, bsdf): every shard must render one method.
            if neither && shard.is_none() {
                opts.auto = Some(footprint_integrators::auto::AutoSpec::all());
            }
            params.apply(&mut opts.guide_params)?;
            opts.film = film;
            opts.sequence = sequence;
            opts.specialise = !general_loop;
            if let Some(s) = spp {
                opts.spp = s;
                opts.time = None;
            }
            if time.is_some() {
                opts.time = time;
            }
            if let Some(d) = max_depth {
                opts.max_depth = d;
            }
            if let Some(d) = rr_depth {
                opts.rr_depth = d;
            }
            if let Some(s) = seed {
                opts.seed = s;
            }
            if let Some(sh) = shard {
                if opts.time.is_some() {
                    bail!(
                        "--shard needs a sample count, but the scene file sets render.time: give --spp (the total over all shards)"
                    );
                }
                if sh.passes_of(opts.spp) == 0 {
                    bail!(
                        "--shard {sh}: {} spp cannot be split into {} shards (each needs a pass)",
                        opts.spp,
                        sh.count
                    );
                }
                opts.passes = sh;
            }
            let out = out.unwrap_or_else(|| {
                let stem = scene
                    .file_stem()
                    .map(|s| s.to_string_lossy().to_string())
                    .unwrap_or("render".into());
                PathBuf::from(format!("{stem}.exr"))
            });
            let exposure = exposure.unwrap_or(sc.settings.exposure);
            render_command(
                &scene,
                &sc,
                opts,
                &out,
                maps_file.as_deref(),
                exposure,
                load_time.as_secs_f64(),
            )
        }
        Command::Maps {
            scene,
            out,
            save,
            resolution,
            maps,
            max_depth,
            seed,
            threads,
            params,
            import,
        } => {
            set_threads(threads)?;
            let sc = load_scene_with(&scene, &import, &maps, resolution)?;
            let mut guide = sc.guide.clone();
            params.apply(&mut guide)?;
            let save = save
                .map(|p| {
                    let hash = scene_content_hash(&scene, &sc)?;
                    anyhow::Ok((p, hash))
                })
                .transpose()?;
            maps_command(&sc, out.as_deref(), save, &guide, max_depth, seed)
        }
        Command::Merge {
            out,
            shards,
            exposure,
        } => {
            if out.extension().and_then(|e| e.to_str()) != Some("exr") {
                bail!(
                    "the merged image must be an .exr file, got {}",
                    out.display()
                );
            }
            if !exposure.is_finite() {
                bail!("--exposure must be finite");
            }
            let m = footprint_app::merge::merge(&out, &shards)?;
            let png = out.with_extension("png");
            write_png(&png, &m.image, exposure)?;
            println!(
                "merged {} shards ({} spp in all; layers {}) -> {}, {}",
                m.shards,
                m.spp,
                m.layers.join(", "),
                out.display(),
                png.display()
            );
            Ok(())
        }
        Command::Compare {
            scene,
            time,
            ladder,
            reference,
            reference_spp,
            reference_cache,
            methods,
            sweep,
            out,
            resolution,
            max_depth,
            seed,
            threads,
            params,
            maps,
            import,
        } => {
            set_threads(threads)?;
            let mut sc = load_scene_with(&scene, &import, &maps, resolution)?;
            if !(time.is_finite() && time > 0.0) {
                bail!("--time must be a positive number of seconds, got {time}");
            }
            let ladder = ladder.unwrap_or_else(|| vec![time / 8.0, time / 4.0, time / 2.0, time]);
            if ladder.is_empty()
                || ladder.iter().any(|t| !(t.is_finite() && *t > 0.0))
                || ladder.windows(2).any(|w| w[0] >= w[1])
            {
                bail!("--ladder must be positive, increasing times, got {ladder:?}");
            }
            let mut base = RenderOptions::from_scene(&sc).map_err(anyhow::Error::msg)?;
            params.apply(&mut base.guide_params)?;
            let max_depth = max_depth.unwrap_or(base.max_depth);
            let default_methods = if sweep.is_some() {
                vec!["pt-footprint".to_string(), "lt-footprint".to_string()]
            } else {
                Method::all().iter().map(|m| m.name()).collect()
            };
            let methods = methods.unwrap_or(default_methods);
            let parsed = methods
                .iter()
                .map(|m| Method::parse_request(m).map_err(|e| anyhow::anyhow!("--methods: {e}")))
                .collect::<Result<Vec<_>>>()?;
            let variants = compare_variants(&parsed, &base, &sc, sweep.as_deref())?;
            let stem = scene
                .file_stem()
                .map(|s| s.to_string_lossy().to_string())
                .unwrap_or("scene".into());
            let out = out.unwrap_or_else(|| PathBuf::from(format!("compare-{stem}")));
            let settings = footprint_app::compare::CompareSettings {
                variants,
                ladder,
                reference_spp,
                reference_cache: reference_cache.clone(),
                out: out.clone(),
                seed,
            };
            let start = Instant::now();
            let rows = footprint_app::compare::run(
                &scene,
                &mut sc,
                reference.as_deref(),
                &settings,
                max_depth,
                &mut |m| eprintln!("{m}"),
            )?;
            let last = *settings.ladder.last().unwrap();
            println!(
                "{:<28} {:>6} {:>9} {:>12} {:>12} {:>7} {:>9}  budget",
                "method", "spp", "seconds", "rel. MSE", "MAE", "spots", "largest"
            );
            for r in rows.iter().filter(|r| r.time_budget == last) {
                println!(
                    "{:<28} {:>6} {:>9.2} {:>12.4e} {:>12.4e} {:>7} {:>8.2}%  {}",
                    r.method,
                    r.spp,
                    r.seconds,
                    r.rel_mse,
                    r.mae,
                    r.spots,
                    100.0 * r.largest_share,
                    if r.budget_missed { "MISSED" } else { "kept" }
                );
            }
            let missed: Vec<String> = rows
                .iter()
                .filter(|r| r.budget_missed)
                .map(|r| format!("{} at {} s ({:.2} s)", r.method, r.time_budget, r.seconds))
                .collect();
            if !missed.is_empty() {
                eprintln!(
                    "warning: {} of {} runs missed their budget (took more than {:.0}% longer, or their maps alone took longer; budget_missed in metrics.csv and metrics.json, red in index.html): {}",
                    missed.len(),
                    rows.len(),
                    100.0 * footprint_app::compare::BUDGET_TOLERANCE,
                    missed.join(", ")
                );
            }
            println!(
                "wrote {} (index.html, metrics.csv, metrics.json, convergence.svg) in {:.0} s",
                out.display(),
                start.elapsed().as_secs_f64()
            );
            Ok(())
        }
        Command::Metrics { image, reference } => {
            use footprint_app::compare::{mae, rel_mse, spots};
            let x = footprint::film::image_io::read_exr(&image)?;
            let r = footprint::film::image_io::read_exr(&reference)?;
            if (x.width, x.height) != (r.width, r.height) {
                bail!(
                    "{} is {}x{}, the reference {}x{}",
                    image.display(),
                    x.width,
                    x.height,
                    r.width,
                    r.height
                );
            }
            println!(
                "rel_mse={:.6e} mae={:.6e} spots={}",
                rel_mse(&x, &r),
                mae(&x, &r),
                spots(&x, &r)
            );
            Ok(())
        }
        Command::Export { scene, out, import } => {
            let sc = import.load(&scene)?;
            let notes = footprint::scene::mitsuba::export::export(&sc, &scene, &out)?;
            for n in &notes {
                eprintln!("note: {n}");
            }
            println!("{} -> {}", scene.display(), out.join("scene.xml").display());
            Ok(())
        }
        Command::Bench {
            scenes,
            seconds,
            threads,
            scene,
            import,
        } => {
            set_threads(threads)?;
            if !(seconds.is_finite() && seconds > 0.0) {
                bail!("--seconds must be positive");
            }
            let extra = scene
                .map(|p| import.load(&p).map(|sc| (p, sc)))
                .transpose()?;
            bench::run(
                &scenes,
                seconds,
                extra.as_ref().map(|(p, s)| (p.as_path(), s)),
            )
        }
    }
}

/// The curves of a comparison: each method once, or once per value of a swept parameter.
fn compare_variants(
    methods: &[(Method, Option<footprint_integrators::auto::AutoSpec>)],
    base: &RenderOptions,
    scene: &Scene,
    sweep: Option<&str>,
) -> Result<Vec<footprint_app::compare::Variant>> {
    use footprint_app::compare::Variant;
    let make = |(m, auto): &(Method, Option<footprint_integrators::auto::AutoSpec>),
                label: String,
                opts: RenderOptions,
                maps: footprint::settings::MapSettings|
     -> Result<Variant> {
        opts.guide_params
            .validate()
            .map_err(|e| anyhow::anyhow!("--sweep: {e}"))?;
        maps.validate()
            .map_err(|e| anyhow::anyhow!("--sweep: {e}"))?;
        Ok(Variant {
            label,
            opts: RenderOptions {
                method: *m,
                auto: auto.clone(),
                ..opts
            },
            maps,
        })
    };
    let Some(sweep) = sweep else {
        return methods
            .iter()
            .map(|m| {
                let label = m.1.as_ref().map(|a| a.label.clone()).unwrap_or(m.0.name());
                make(m, label, base.clone(), scene.maps.clone())
            })
            .collect();
    };
    let (name, values) = sweep
        .split_once('=')
        .ok_or_else(|| anyhow::anyhow!("--sweep: expected NAME=V1,V2,..., got '{sweep}'"))?;
    let mut out = Vec::new();
    for v in values.split(',') {
        let v = v.trim();
        let num: f64 = if name.trim() == "sequence" {
            0.0
        } else {
            v.parse()
                .map_err(|_| anyhow::anyhow!("--sweep: '{v}' is not a number"))?
        };
        for m in methods {
            let mut opts = base.clone();
            let mut maps = scene.maps.clone();
            match name.trim() {
                "sequence" => {
                    opts.sequence = <footprint::rng::Sequence as clap::ValueEnum>::from_str(v, true)
                        .map_err(|_| {
                            anyhow::anyhow!(
                                "--sweep: sequence '{v}' (expected sobol or independent)"
                            )
                        })?
                }
                "k_p" => opts.guide_params.k_p = num as usize,
                "k_r" => opts.guide_params.k_r = num as f32,
                "p_bsdf" => opts.guide_params.p_bsdf = num as f32,
                "learn_p_bsdf" => opts.guide_params.learn_p_bsdf = num != 0.0,
                "guided_rr" => opts.guide_params.guided_rr = num != 0.0,
                "guided_split" => opts.guide_params.guided_split = num as u32,
                "relative_importance" => opts.guide_params.relative_importance = num != 0.0,
                "k_g" => opts.guide_params.k_g_side = num as usize,
                "grid" => opts.guide_params.grid_side = num as usize,
                "photons" => maps.photons = num as usize,
                "region_particles" => opts.guide_params.region_particles = num as usize,
                "region_seeds" => opts.guide_params.region_seeds = num as usize,
                "min_depth" => opts.guide_params.min_depth = num as u16,
                "mis_table" => opts.guide_params.mis_table = num as usize,
                "raster" => opts.guide_params.raster = num as usize,
                "importons" => maps.importons = num as usize,
                "map_rounds" => maps.rounds = num as u32,
                "map_grow" => maps.grow = num != 0.0,
                other => bail!(
                    "--sweep: unknown parameter '{other}' (expected k_p, k_r, p_bsdf, learn_p_bsdf (0 or 1), guided_rr (0 or 1), guided_split, relative_importance (0 or 1), k_g, grid, region_particles, region_seeds, min_depth, mis_table, raster, photons, importons, map_rounds, map_grow (0 or 1) or sequence)"
                ),
            }
            out.push(make(
                m,
                format!(
                    "{}@{}={v}",
                    m.1.as_ref().map(|a| a.label.clone()).unwrap_or(m.0.name()),
                    name.trim()
                ),
                opts,
                maps,
            )?);
        }
    }
    Ok(out)
}

fn maps_command(
    scene: &Scene,
    out: Option<&Path>,
    save: Option<(PathBuf, String)>,
    params: &footprint::settings::GuideParams,
    max_depth: Option<u32>,
    seed: Option<u64>,
) -> Result<()> {
    use footprint_app::map_picture::{PICTURE_K, density_picture};
    use footprint_integrators::maps::{Guidance, run_passes};
    use footprint_integrators::render::{pass_settings, with_target};
    if let Some(out) = out {
        std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    }
    // Both maps, and their guide caches when the cache is on: what `combined-footprint` uses.
    let method = Method::from_names("combined", "footprint").map_err(anyhow::Error::msg)?;
    // The passes as `render` runs them for that method, relative importance target included
    // (`render --maps FILE` must find the particles a render without the file would make).
    let mut opts = RenderOptions::from_scene(scene).map_err(anyhow::Error::msg)?;
    opts.method = method;
    opts.auto = None;
    opts.guide_params = params.clone();
    if let Some(d) = max_depth {
        opts.max_depth = d;
    }
    if let Some(s) = seed {
        opts.seed = s;
    }
    let pass = with_target(scene, &opts, pass_settings(scene, &opts));
    println!(
        "maximum query distance {:.4} (scene units)",
        scene.map_max_dist()
    );
    let passes = run_passes(scene, &method, params, &pass);
    if let Some((path, hash)) = save {
        use footprint_app::maps_file;
        let key = maps_file::maps_key(
            &hash,
            scene,
            pass.max_depth,
            pass.seed,
            params.relative_importance,
        );
        maps_file::save(&path, &key, &passes)?;
        let count = |p: &Option<footprint_integrators::passes::PassOutput>| {
            p.as_ref().map(|o| o.particles.len()).unwrap_or(0)
        };
        let bytes = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
        println!(
            "saved the passes ({} photons, {} importons; {:.1} MB) -> {}",
            count(&passes.light),
            count(&passes.view),
            bytes as f64 / 1e6,
            path.display()
        );
    }
    let g = Guidance::from_passes(scene, &method, params, passes, &heap_bytes);
    for line in &g.summaries {
        println!("{line}");
    }
    let Some(out) = out else { return Ok(()) };
    for (built, file) in [(&g.photons, "photons.png"), (&g.importons, "importons.png")] {
        if let Some(b) = built {
            let path = out.join(file);
            let pic = density_picture(scene, &b.map, PICTURE_K);
            write_png(&path, &pic.image, 0.0)?;
            match pic.range {
                Some((lo, hi)) => println!(
                    "  -> {}: {} from the {PICTURE_K} nearest particles per pixel, log scale {lo:.3e} to {hi:.3e}; particles on {:.0}% of the visible surface",
                    path.display(),
                    pic.quantity,
                    100.0 * pic.covered
                ),
                None => println!(
                    "  -> {}: no particle on any visible surface",
                    path.display()
                ),
            }
        }
    }
    Ok(())
}

fn render_command(
    scene_path: &Path,
    scene: &Scene,
    mut opts: RenderOptions,
    out: &Path,
    maps_file: Option<&Path>,
    exposure: f32,
    load_s: f64,
) -> Result<()> {
    use footprint_integrators::maps::{Guidance, needed_passes};
    use footprint_app::merge;
    if out.extension().and_then(|e| e.to_str()) != Some("exr") {
        bail!("--out must name an .exr file, got {}", out.display());
    }
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        if !dir.is_dir() {
            bail!("output folder {} does not exist", dir.display());
        }
    }
    let terminal = std::io::stderr().is_terminal();
    let cam = &scene.camera;
    let effects: Vec<&str> = scene
        .effects
        .list()
        .iter()
        .filter(|(_, on)| *on)
        .map(|(n, _)| *n)
        .collect();
    if terminal {
        eprintln!(
            "{}: {} triangles, {} lights, {}x{}, loaded in {:.2} s",
            scene_path.display(),
            scene.triangles.len(),
            scene.lights.len(),
            cam.width,
            cam.height,
            load_s
        );
        eprintln!("effects: {}", effects.join(", "));
        eprintln!("path loop: {}", opts.specialisation(scene).name());
        for s in scene.effects.skipped() {
            eprintln!("skips: {s}");
        }
        if !footprint_integrators::skips::particles_stored(scene) {
            eprintln!("skips: particle passes and maps (no surface stores particles)");
        }
    }
    if scene.stats.degenerate_skipped > 0 {
        eprintln!(
            "warning: skipped {} degenerate triangles",
            scene.stats.degenerate_skipped
        );
    }
    let bar = if terminal {
        let b = ProgressBar::new(1000);
        b.set_style(
            ProgressStyle::with_template(
                "{spinner} {msg} [{bar:40}] {percent}% elapsed {elapsed} eta {eta}",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        b.set_message(opts.method.name());
        Some(b)
    } else {
        None
    };
    let scene_hash = scene_content_hash(scene_path, scene)?;
    let start = Instant::now();
    // ---- auto: the pilot chooses the method; its time counts in the budget ----
    let mut auto_reason = None;
    let mut piloted = None;
    if let Some(spec) = opts.auto.take() {
        if !opts.passes.is_all() {
            bail!(
                "--shard needs a fixed method: every shard must render the same one (give --integrator and --guide)"
            );
        }
        let choice = footprint_integrators::auto::choose(scene, &opts, &spec);
        eprintln!(
            "auto ({}): {} ({:.2} s pilot): {}",
            spec.label,
            choice.method.name(),
            choice.pilot.as_secs_f64(),
            choice.reason
        );
        opts.method = choice.method;
        auto_reason = Some(format!("{}: {}", spec.label, choice.reason));
        piloted = choice.guidance;
        if let Some(b) = &bar {
            b.set_message(format!("auto: {}", opts.method.name()));
        }
    }
    let guidance = match maps_file.filter(|_| opts.method.guided() && piloted.is_none()) {
        Some(path) => {
            let key = footprint_app::maps_file::maps_key(
                &scene_hash,
                scene,
                opts.max_depth,
                opts.seed,
                opts.guide_params.relative_importance,
            );
            let passes = footprint_app::maps_file::load(path, &key)?;
            let (light, view) = needed_passes(&opts.method, &opts.guide_params);
            if (light && passes.light.is_none()) || (view && passes.view.is_none()) {
                bail!(
                    "{} lacks a pass that {} needs (write it with `footprint maps --save`)",
                    path.display(),
                    opts.method.name()
                );
            }
            Guidance::from_passes(scene, &opts.method, &opts.guide_params, passes, &heap_bytes)
        }
        None if piloted.is_some() => {
            let left = opts.time.map(|t| t - start.elapsed().as_secs_f64());
            footprint_integrators::render::chosen_guidance(
                scene,
                &opts,
                piloted.take(),
                left,
                &heap_bytes,
            )
        }
        None => {
            if maps_file.is_some() {
                eprintln!(
                    "note: {} uses no particle map: --maps is ignored",
                    opts.method.name()
                );
            }
            footprint_integrators::render::guidance(scene, &opts, &heap_bytes)
        }
    };
    let maps_load = start.elapsed();
    let result = footprint_integrators::render_guided(scene, &opts, &guidance, start, |f| {
        if let Some(b) = &bar {
            b.set_position((f * 1000.0) as u64);
        }
    });
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let secs = result.elapsed.as_secs_f64();
    let t = &result.timings;
    let p = &opts.guide_params;
    let header = vec![
        (
            "footprint/version".to_string(),
            env!("CARGO_PKG_VERSION").to_string(),
        ),
        (
            "footprint/scene".to_string(),
            scene_path.display().to_string(),
        ),
        (
            "footprint/integrator".to_string(),
            opts.method.integrator.name().to_string(),
        ),
        (
            "footprint/guide".to_string(),
            opts.method.guide.name().to_string(),
        ),
        ("footprint/method".to_string(), opts.method.name()),
        (
            "footprint/film".to_string(),
            format!("{:?} {:?}", opts.film, scene.camera.filter.kind),
        ),
        (
            "footprint/sequence".to_string(),
            opts.sequence.name().to_string(),
        ),
        ("footprint/accel".to_string(), scene.bvh.name().to_string()),
        (
            "footprint/guide_params".to_string(),
            format!(
                "k_p={} k_g={}x{} k_r={} p_bsdf={} learn_p_bsdf={} guided_rr={} guided_split={} relative_importance={} radius_rule={} grid={}x{} cache={} region_particles={} region_seeds={} min_depth={} guided_mis={} mis_table={} raster={} photons={} importons={} max_dist={}",
                p.k_p,
                p.k_g_side,
                p.k_g_side,
                p.k_r,
                p.p_bsdf,
                if p.learn_p_bsdf { "on" } else { "off" },
                if p.guided_rr { "on" } else { "off" },
                p.guided_split,
                if p.relative_importance { "on" } else { "off" },
                p.radius_rule.name(),
                p.grid_side,
                p.grid_side,
                if p.cache { "on" } else { "off" },
                p.region_particles,
                p.region_seeds,
                p.min_depth,
                if p.guided_mis { "on" } else { "off" },
                p.mis_table,
                p.raster,
                scene.maps.photons,
                scene.maps.importons,
                scene.map_max_dist()
            ),
        ),
        (merge::SCENE_HASH.to_string(), scene_hash),
        (
            merge::SETTINGS.to_string(),
            merge::settings_key(&opts, scene),
        ),
        (merge::SHARD.to_string(), opts.passes.to_string()),
        (merge::SPP.to_string(), result.passes.to_string()),
        (
            merge::SPP_TOTAL.to_string(),
            if opts.passes.is_all() {
                result.passes
            } else {
                opts.spp
            }
            .to_string(),
        ),
        (
            "footprint/max_depth".to_string(),
            opts.max_depth.to_string(),
        ),
        (merge::SEED.to_string(), opts.seed.to_string()),
        (merge::RENDER_TIME.to_string(), format!("{secs:.3}")),
        (
            "footprint/time_split_s".to_string(),
            format!(
                "view_pass={:.3} light_pass={:.3} map_builds={:.3} cache_builds={:.3} tracing={:.3}",
                t.maps.view_pass.as_secs_f64(),
                t.maps.light_pass.as_secs_f64(),
                t.maps.map_builds.as_secs_f64(),
                t.maps.cache_builds.as_secs_f64(),
                t.tracing.as_secs_f64()
            ),
        ),
        (
            "footprint/time_budget_s".to_string(),
            opts.time.map(|t| t.to_string()).unwrap_or("none".into()),
        ),
    ];
    let mut header = header;
    header.push(("footprint/skipped".into(), result.skipped.join("; ")));
    if let Some(a) = &auto_reason {
        header.push(("footprint/auto".into(), a.clone()));
    }
    if let Some(path) = maps_file.filter(|_| opts.method.guided()) {
        header.push(("footprint/maps_file".into(), path.display().to_string()));
        header.push((
            "footprint/maps_load_s".into(),
            format!("{:.3}", maps_load.as_secs_f64()),
        ));
    }
    let layers: Vec<(&str, &footprint::film::Image)> =
        result.layers.iter().map(|(n, i)| (*n, i)).collect();
    write_exr(out, &layers, &header)?;
    let png = out.with_extension("png");
    write_png(&png, &result.image, exposure)?;
    if terminal {
        for m in &result.maps {
            eprintln!("{m}");
        }
        if !opts.method.guided() {
            eprintln!("maps: none built (BSDF sampling needs no particle map)");
        }
        let g = |name: &str, c: &footprint_integrators::render::GuideCounts| {
            if c.prepared > 0 {
                eprintln!(
                    "{name}: {} scattering events, {} fell back to BSDF sampling ({:.1}%)",
                    c.prepared,
                    c.fallbacks,
                    100.0 * c.fallbacks as f64 / c.prepared as f64
                );
            }
        };
        g("camera paths", &result.camera_guide);
        g("light paths", &result.light_guide);
        for s in &result.skipped {
            eprintln!("skipped: {s}");
        }
        eprintln!(
            "time: view pass {:.2} s, light pass {:.2} s, map builds {:.2} s, cache builds {:.2} s, tracing {:.2} s",
            t.maps.view_pass.as_secs_f64(),
            t.maps.light_pass.as_secs_f64(),
            t.maps.map_builds.as_secs_f64(),
            t.maps.cache_builds.as_secs_f64(),
            t.tracing.as_secs_f64()
        );
    }
    let fallbacks = result.camera_guide.fallbacks + result.light_guide.fallbacks;
    let prepared = result.camera_guide.prepared + result.light_guide.prepared;
    println!(
        "{}: {} ({}) {} {}x{} in {:.2} s (maps {:.2} s, {:.2} M paths/s), BSDF fallbacks {}/{}, max sample {:.4}, rejected {} -> {}, {}",
        scene_path.display(),
        opts.method.integrator.name(),
        opts.method.guide.name(),
        if opts.passes.is_all() {
            format!("{} spp", result.passes)
        } else {
            format!(
                "{} spp (shard {} of {} spp)",
                result.passes, opts.passes, opts.spp
            )
        },
        cam.width,
        cam.height,
        secs,
        t.maps.total().as_secs_f64(),
        result.paths as f64 / t.tracing.as_secs_f64().max(1e-9) / 1e6,
        fallbacks,
        prepared,
        result.stats.max_luminance,
        result.stats.rejected,
        out.display(),
        png.display()
    );
    Ok(())
}
