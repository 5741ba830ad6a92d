//! `footprint render`: a scene to an EXR (every layer, with a header that records how) and
//! a PNG preview, with a fixed method or `auto`'s choice, from maps it builds or saved ones.

use crate::args::{
    ImportArgs, SettingArgs, heap_bytes, keyword, load_scene, parse_resolution, set_threads,
};
use crate::exr_header;
use crate::maps_file;
use crate::scene_hash::scene_content_hash;
use anyhow::{Result, bail};
use clap::Args;
use clap::builder::{PossibleValue, PossibleValuesParser};
use footprint::film::FilmMode;
use footprint::film::image_io::{write_exr, write_png};
use footprint::guide::GUIDES;
use footprint::rng::Sequence;
use footprint::scene::Scene;
use footprint_integrators::auto::{Choice, Request, Run, SavedMaps, render_request};
use footprint_integrators::counts::GuideCounts;
use footprint_integrators::integrator::INTEGRATORS;
use footprint_integrators::maps::{Guidance, needed_passes};
use footprint_integrators::{Method, PassSelection, RenderOptions};
use indicatif::{ProgressBar, ProgressStyle};
use std::cell::Cell;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// `--integrator`'s values: the registered integrators, with their help lines.
pub fn integrator_values() -> PossibleValuesParser {
    PossibleValuesParser::new(
        INTEGRATORS
            .iter()
            .map(|i| PossibleValue::new(i.name()).help(i.about()))
            .chain([PossibleValue::new("auto")
                .help("Chosen by a short pilot: the method predicted to give the lowest error")]),
    )
}

/// `--guide`'s values: the registered guides, with their help lines.
pub fn guide_values() -> PossibleValuesParser {
    PossibleValuesParser::new(
        GUIDES
            .iter()
            .map(|g| PossibleValue::new(g.name()).help(g.about()))
            .chain([PossibleValue::new("auto").help(
                "Chosen by a short pilot (guided candidates where the scene is hard per sample and their maps fit the budget)",
            )]),
    )
}

/// Render a scene to an EXR (linear float RGB) and a PNG preview
#[derive(Args, Debug)]
pub struct RenderArgs {
    /// Scene file: footprint TOML (.toml) or Mitsuba 3 XML (.xml)
    scene: PathBuf,
    /// Integrator [default: the scene's render.integrator; auto when the guide is auto or
    /// neither is given here or in the scene; else pt]
    #[arg(long, value_parser = integrator_values())]
    integrator: Option<String>,
    /// Direction sampler [default: the scene's render.guide; auto when the integrator is
    /// auto or neither is given here or in the scene; else bsdf]
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
    #[arg(long, value_parser = keyword::<FilmMode>(), default_value = "splat")]
    film: FilmMode,
    /// The numbers camera and light paths draw (pbrt's and Mitsuba's sampler): one point
    /// of a pixel's own Owen-scrambled Sobol sequence per pass (pbrt-v4's default kind),
    /// or independent numbers (Mitsuba's `independent`). Both converge to the same image
    #[arg(long, value_parser = keyword::<Sequence>(), default_value = "sobol")]
    sequence: Sequence,
    /// Render only shard i of N (zero-based): the passes k < spp with k mod N = i, so that
    /// N shards with the same --spp (the total) and seed, put together by `footprint
    /// merge`, are the image of one run. Needs --spp, not --time
    #[arg(long, value_name = "i/N", value_parser = PassSelection::parse)]
    shard: Option<PassSelection>,
    /// Load the particle maps' passes from this file (written by `footprint maps --save`)
    /// instead of running them; refused if made for another scene or other settings
    #[arg(long = "maps", value_name = "MAPS.fpm")]
    maps_file: Option<PathBuf>,
    /// Run the general path loop instead of the one compiled for the scene's effects
    /// (the same image, bit for bit; for measuring what the specialisation gains)
    #[arg(long)]
    general_loop: bool,
    #[command(flatten)]
    settings: SettingArgs,
    #[command(flatten)]
    import: ImportArgs,
}

/// Checks the flags, loads the scene, resolves the request and renders.
pub fn run(a: RenderArgs) -> Result<()> {
    set_threads(a.threads)?;
    if let Some(t) = a.time
        && !(t.is_finite() && t > 0.0)
    {
        bail!("--time must be a positive number of seconds, got {t}");
    }
    if a.shard.is_some() && a.time.is_some() {
        bail!(
            "--shard needs --spp, not --time: with a time budget every machine renders as many passes as its speed allows, so the shards would not add up to the samples of one run; give every shard the same --spp (the total)"
        );
    }
    if a.exposure.is_some_and(|x| !x.is_finite()) {
        bail!("--exposure must be finite");
    }
    let t0 = Instant::now();
    let sc = load_scene(&a.scene, &a.import, &a.settings, a.resolution)?;
    let load_time = t0.elapsed();
    // What is named, here or in the scene. A part named nowhere is chosen by auto when the
    // other part is (`--integrator auto` alone chooses the guide too), and both are when
    // neither is named; a shard keeps the fixed default (pt, bsdf) for a part named nowhere:
    // every shard must render one method.
    let scene_name = |n: &Option<footprint::settings::Named>| n.as_ref().map(|n| n.name.clone());
    let integrator = a
        .integrator
        .clone()
        .or_else(|| scene_name(&sc.settings.integrator));
    let guide = a.guide.clone().or_else(|| scene_name(&sc.settings.guide));
    let chooses = |n: &Option<String>| n.as_deref() == Some("auto");
    let auto_part = a.shard.is_none() && (chooses(&integrator) || chooses(&guide));
    let unnamed = |n: &Option<String>| {
        let rest_auto = auto_part || (integrator.is_none() && guide.is_none() && a.shard.is_none());
        (n.is_none() && rest_auto).then_some("auto")
    };
    let request = Request::from_scene(&sc)
        .and_then(|r| {
            r.with_names(
                a.integrator.as_deref().or(unnamed(&integrator)),
                a.guide.as_deref().or(unnamed(&guide)),
            )
        })
        .map_err(anyhow::Error::msg)?;
    let mut opts = RenderOptions::from_scene(&sc, request.fixed().unwrap_or_default());
    opts.film = a.film;
    opts.sequence = a.sequence;
    opts.specialise = !a.general_loop;
    if let Some(s) = a.spp {
        opts.spp = s;
        opts.time = None;
    }
    if a.time.is_some() {
        opts.time = a.time;
    }
    if let Some(d) = a.max_depth {
        opts.max_depth = d;
    }
    if let Some(d) = a.rr_depth {
        opts.rr_depth = d;
    }
    if let Some(s) = a.seed {
        opts.seed = s;
    }
    if let Some(sh) = a.shard {
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
        if request.fixed().is_none() {
            bail!(
                "--shard needs a fixed method: every shard must render the same one (give --integrator and --guide)"
            );
        }
        opts.passes = sh;
    }
    let out = a.out.unwrap_or_else(|| {
        let stem = a
            .scene
            .file_stem()
            .map(|s| s.to_string_lossy().to_string())
            .unwrap_or("render".into());
        PathBuf::from(format!("{stem}.exr"))
    });
    let exposure = a.exposure.unwrap_or(sc.settings.exposure);
    let target = Target {
        scene_path: &a.scene,
        out: &out,
        maps_file: a.maps_file.as_deref(),
        exposure,
        load_s: load_time.as_secs_f64(),
    };
    render(&sc, &request, opts, &target)
}

/// Where a render goes and what it may read.
struct Target<'a> {
    scene_path: &'a Path,
    out: &'a Path,
    maps_file: Option<&'a Path>,
    exposure: f32,
    load_s: f64,
}

/// What the scene is and how it will run (on a terminal).
fn print_scene(t: &Target, scene: &Scene, opts: &RenderOptions) {
    let cam = &scene.camera;
    let effects: Vec<&str> = scene
        .effects
        .list()
        .iter()
        .filter(|(_, on)| *on)
        .map(|(n, _)| *n)
        .collect();
    eprintln!(
        "{}: {} triangles, {} lights, {}x{}, loaded in {:.2} s",
        t.scene_path.display(),
        scene.triangles.len(),
        scene.lights.len(),
        cam.width,
        cam.height,
        t.load_s
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

fn progress_bar(message: String) -> ProgressBar {
    let b = ProgressBar::new(1000);
    b.set_style(
        ProgressStyle::with_template(
            "{spinner} {msg} [{bar:40}] {percent}% elapsed {elapsed} eta {eta}",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    b.set_message(message);
    b
}

fn render(scene: &Scene, request: &Request, opts: RenderOptions, t: &Target) -> Result<()> {
    if t.out.extension().and_then(|e| e.to_str()) != Some("exr") {
        bail!("--out must name an .exr file, got {}", t.out.display());
    }
    if let Some(dir) = t.out.parent().filter(|d| !d.as_os_str().is_empty())
        && !dir.is_dir()
    {
        bail!("output folder {} does not exist", dir.display());
    }
    let terminal = std::io::stderr().is_terminal();
    if terminal {
        print_scene(t, scene, &opts);
    }
    if scene.stats.degenerate_skipped > 0 {
        eprintln!(
            "warning: skipped {} degenerate triangles",
            scene.stats.degenerate_skipped
        );
    }
    let bar = terminal.then(|| progress_bar(request.label()));
    let scene_hash = scene_content_hash(t.scene_path, scene)?;
    // ---- Saved maps: loaded for a guided method that needs them ----
    let load_time = Cell::new(None);
    let load = |o: &RenderOptions| -> Result<Guidance, String> {
        let path = t.maps_file.expect("only with a file");
        let t0 = Instant::now();
        let g = saved_guidance(path, &scene_hash, scene, o).map_err(|e| format!("{e:#}"))?;
        load_time.set(Some(t0.elapsed()));
        Ok(g)
    };
    let run = Run {
        heap: &heap_bytes,
        saved: t.maps_file.map(|_| &load as SavedMaps),
        ..Run::default()
    };
    // ---- auto tells its choice before the chosen method renders ----
    let mut told = |c: &Choice| {
        eprintln!(
            "auto ({}): {} ({:.2} s pilot): {}",
            c.label,
            c.method.name(),
            c.pilot.total.as_secs_f64(),
            c.reason()
        );
        if let Some(b) = &bar {
            b.set_message(format!("auto: {}", c.method.name()));
        }
    };
    let rendered = render_request(scene, &opts, request, &run, &mut told, |f| {
        if let Some(b) = &bar {
            b.set_position((f * 1000.0) as u64);
        }
    })
    .map_err(anyhow::Error::msg)?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let result = &rendered.result;
    let opts = RenderOptions {
        method: result.method,
        ..opts
    };
    if t.maps_file.is_some() && load_time.get().is_none() {
        eprintln!(
            "note: {} reads no saved particle map: --maps is ignored",
            opts.method.name()
        );
    }
    let header = exr_header::header(&exr_header::Run {
        scene_path: t.scene_path,
        scene,
        scene_hash: &scene_hash,
        opts: &opts,
        result,
        choice: rendered.choice.as_ref(),
        maps_file: t.maps_file.zip(load_time.get()),
    });
    let layers: Vec<(&str, &footprint::film::Image)> =
        result.layers.iter().map(|(n, i)| (*n, i)).collect();
    write_exr(t.out, &layers, &header)?;
    let png = t.out.with_extension("png");
    write_png(&png, &result.image, t.exposure)?;
    if terminal {
        print_details(&opts, result);
    } else {
        for line in &result.maps_thinned {
            eprintln!("warning: {line}");
        }
    }
    print_summary(t, scene, &opts, result, &png);
    Ok(())
}

/// The maps of `o`'s method from a saved file, refused when the file was made for another
/// scene or other settings, or lacks a pass the method needs.
fn saved_guidance(path: &Path, hash: &str, scene: &Scene, o: &RenderOptions) -> Result<Guidance> {
    let key = maps_file::maps_key(hash, scene, o.max_depth, o.seed);
    let mut passes = maps_file::load(path, &key)?;
    // Saved on a machine with more memory, or with a larger budget: thinned to this one's.
    let max = footprint_integrators::passes::thinning::max_particles(footprint::memory::budget(
        scene.maps.max_memory,
    ));
    for pass in [&mut passes.light, &mut passes.view].into_iter().flatten() {
        pass.within(max);
    }
    let (light, view) = needed_passes(&o.method, &o.guide_params);
    if (light && passes.light.is_none()) || (view && passes.view.is_none()) {
        bail!(
            "{} lacks a pass that {} needs (write it with `footprint maps --save`)",
            path.display(),
            o.method.name()
        );
    }
    Ok(Guidance::from_passes(
        scene,
        &o.method,
        &o.guide_params,
        passes,
        &heap_bytes,
    ))
}

/// The maps, the guided events, the skips and the time split (on a terminal).
fn print_details(opts: &RenderOptions, result: &footprint_integrators::RenderResult) {
    for m in &result.maps {
        eprintln!("{m}");
    }
    if !opts.method.guided() {
        eprintln!("maps: none built (BSDF sampling needs no particle map)");
    }
    let g = |name: &str, c: &GuideCounts| {
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
    let split: Vec<String> = result
        .timings
        .split()
        .iter()
        .map(|(name, s)| format!("{name} {s:.2} s"))
        .collect();
    eprintln!("time: {}", split.join(", "));
}

/// The run's one line on standard output.
fn print_summary(
    t: &Target,
    scene: &Scene,
    opts: &RenderOptions,
    result: &footprint_integrators::RenderResult,
    png: &Path,
) {
    let tm = &result.timings;
    let fallbacks = result.camera_guide.fallbacks + result.light_guide.fallbacks;
    let prepared = result.camera_guide.prepared + result.light_guide.prepared;
    let method: Method = opts.method;
    println!(
        "{}: {} ({}) {} {}x{} in {:.2} s (maps {:.2} s, {:.2} M paths/s), BSDF fallbacks {}/{}, max sample {:.4}, rejected {} -> {}, {}",
        t.scene_path.display(),
        method.integrator.name(),
        method.guide.name(),
        if opts.passes.is_all() {
            format!("{} spp", result.passes)
        } else {
            format!(
                "{} spp (shard {} of {} spp)",
                result.passes, opts.passes, opts.spp
            )
        },
        scene.camera.width,
        scene.camera.height,
        result.elapsed.as_secs_f64(),
        tm.maps.total().as_secs_f64(),
        result.paths as f64 / tm.tracing.as_secs_f64().max(1e-9) / 1e6,
        fallbacks,
        prepared,
        result.stats.max_luminance,
        result.stats.rejected,
        t.out.display(),
        png.display()
    );
}
