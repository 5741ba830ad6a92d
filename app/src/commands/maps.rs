//! `footprint maps`: both particle passes, their maps and guide caches, pictures of the maps
//! seen from the camera, and saved passes for `render --maps`.

use crate::args::{ImportArgs, SettingArgs, heap_bytes, load_scene, parse_resolution, set_threads};
use crate::map_picture::{PICTURE_K, density_picture};
use crate::maps_file;
use crate::scene_hash::scene_content_hash;
use anyhow::{Context, Result};
use clap::Args;
use footprint::film::image_io::write_png;
use footprint::scene::Scene;
use footprint_integrators::maps::{Guidance, run_passes};
use footprint_integrators::passes::PassOutput;
use footprint_integrators::render::{pass_settings, with_target};
use footprint_integrators::{Method, RenderOptions};
use std::path::{Path, PathBuf};

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
#[derive(Args, Debug)]
pub struct MapsArgs {
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
    settings: SettingArgs,
    #[command(flatten)]
    import: ImportArgs,
}

pub fn run(a: MapsArgs) -> Result<()> {
    set_threads(a.threads)?;
    let scene = load_scene(&a.scene, &a.import, &a.settings, a.resolution)?;
    let save = a
        .save
        .map(|p| anyhow::Ok((p, scene_content_hash(&a.scene, &scene)?)))
        .transpose()?;
    maps(&scene, a.out.as_deref(), save, a.max_depth, a.seed)
}

fn maps(
    scene: &Scene,
    out: Option<&Path>,
    save: Option<(PathBuf, String)>,
    max_depth: Option<u32>,
    seed: Option<u64>,
) -> Result<()> {
    if let Some(out) = out {
        std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    }
    // Both maps, and their guide caches when the cache is on: what `combined-footprint` uses.
    let method = Method::from_names("combined", "footprint").map_err(anyhow::Error::msg)?;
    // The passes as `render` runs them for that method, relative importance target included
    // (`render --maps FILE` must find the particles a render without the file would make).
    let mut opts = RenderOptions::from_scene(scene, method);
    if let Some(d) = max_depth {
        opts.max_depth = d;
    }
    if let Some(s) = seed {
        opts.seed = s;
    }
    let params = &opts.guide_params;
    let pass = with_target(scene, &opts, pass_settings(scene, &opts));
    println!(
        "maximum query distance {:.4} (scene units)",
        scene.map_max_dist()
    );
    let heap_start = footprint::heap::heap_bytes();
    footprint::heap::reset_peak();
    let passes = run_passes(scene, &method, params, &pass);
    if let Some((path, hash)) = save {
        let key = maps_file::maps_key(&hash, scene, pass.max_depth, pass.seed);
        maps_file::save(&path, &key, &passes)?;
        let count = |p: &Option<PassOutput>| p.as_ref().map_or(0, |o| o.particles.len());
        let bytes = std::fs::metadata(&path).map_or(0, |m| m.len());
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
    // What the memory budget is reckoned in (integrators/src/passes/thinning.rs).
    let peak = footprint::heap::heap_peak().saturating_sub(heap_start);
    let kept: usize = [&g.photons, &g.importons]
        .into_iter()
        .flatten()
        .map(|b| b.pass.particles.len())
        .sum();
    println!(
        "heap at its peak over the scene: {:.1} MB, {:.0} bytes per particle of both passes (max_memory {} allows {} per particle)",
        peak as f64 / 1e6,
        peak as f64 / kept.max(1) as f64,
        footprint::memory::format_size(footprint::memory::budget(scene.maps.max_memory)),
        footprint_integrators::passes::thinning::PEAK_BYTES_PER_PARTICLE
    );
    let Some(out) = out else { return Ok(()) };
    for (built, file) in [(&g.photons, "photons.png"), (&g.importons, "importons.png")] {
        let Some(b) = built else { continue };
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
    Ok(())
}
