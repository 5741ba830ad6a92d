//! The reference a comparison measures against: given, cached beside the scene (keyed by
//! the scene files' content and the reference's settings), or rendered.

use anyhow::{Context, Result, bail};
use footprint::film::Image;
use footprint::film::image_io::{read_exr, write_exr};
use footprint::scene::Scene;
use footprint_integrators::method::Method;
use footprint_integrators::render::{RenderOptions, render};
use std::path::Path;

/// A short text that identifies what a reference was rendered from: the scene files'
/// contents, the resolution, depth and reference settings.
pub fn reference_key(scene_path: &Path, scene: &Scene, spp: u32, max_depth: u32) -> Result<String> {
    let hash = crate::scene_hash::scene_content_hash(scene_path, scene)?;
    Ok(format!(
        "scene={} res={}x{} spp={spp} max_depth={max_depth} method=combined-bsdf v{}",
        &hash[..16],
        scene.camera.width,
        scene.camera.height,
        env!("CARGO_PKG_VERSION")
    ))
}
/// Reads the key a cached reference was written with.
fn cached_key(path: &Path) -> Option<String> {
    footprint::film::image_io::read_exr_text_attribute(path, "footprint/reference_key")
}
/// The reference: `given`, or the cache in `cache_dir` (default: the scene's folder) when its
/// key matches, or a fresh render (written to the cache). Returns the image and where it
/// came from.
#[allow(clippy::too_many_arguments)]
pub fn reference(
    scene_path: &Path,
    scene: &Scene,
    given: Option<&Path>,
    spp: u32,
    max_depth: u32,
    cache_dir: Option<&Path>,
    log: &mut dyn FnMut(&str),
) -> Result<(Image, String)> {
    if let Some(p) = given {
        let img = read_exr(p)?;
        if img.width != scene.camera.width || img.height != scene.camera.height {
            bail!(
                "reference {} is {}x{}, the render is {}x{} (use --resolution)",
                p.display(),
                img.width,
                img.height,
                scene.camera.width,
                scene.camera.height
            );
        }
        return Ok((img, format!("given: {}", p.display())));
    }
    let key = reference_key(scene_path, scene, spp, max_depth)?;
    let stem = scene_path
        .file_stem()
        .map(|s| s.to_string_lossy().to_string())
        .unwrap_or("scene".into());
    let name = format!(
        ".{stem}-reference-{}x{}.exr",
        scene.camera.width, scene.camera.height
    );
    let cache = match cache_dir {
        Some(d) => d.join(name),
        None => scene_path.with_file_name(name),
    };
    if cache.exists() {
        if cached_key(&cache).as_deref() == Some(key.as_str()) {
            if let Ok(img) = read_exr(&cache) {
                return Ok((img, format!("cached: {}", cache.display())));
            }
        }
        log(&format!(
            "reference cache {} is stale (scene or settings changed): rendering it again",
            cache.display()
        ));
    }
    // The cache's folder is made before the render: a long reference is not rendered only to
    // be lost for want of a folder.
    if let Some(d) = cache.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(d)
            .with_context(|| format!("cannot create the reference cache folder {}", d.display()))?;
    }
    log(&format!(
        "rendering the reference: combined image, BSDF sampling, {spp} spp"
    ));
    let opts = RenderOptions {
        method: Method::from_names("combined", "bsdf").map_err(anyhow::Error::msg)?,
        spp,
        max_depth,
        seed: 0x5eed,
        ..Default::default()
    };
    // Progress: a line at every tenth of the passes, with the time left measured so far.
    let t0 = std::time::Instant::now();
    let mut shown = 0;
    let r = render(scene, &opts, |f| {
        let tenth = (f * 10.0).floor() as i32;
        if tenth > shown && f < 1.0 {
            shown = tenth;
            let el = t0.elapsed().as_secs_f64();
            log(&format!(
                "reference: {:.0}% of {spp} spp in {el:.0} s, about {:.0} s left",
                100.0 * f,
                el * (1.0 - f) / f
            ));
        }
    });
    // A cache that cannot be written costs the next run a render, not this one its result.
    let stored = match write_exr(
        &cache,
        &[("combined", &r.image)],
        &[("footprint/reference_key".into(), key)],
    ) {
        Ok(()) => cache.display().to_string(),
        Err(e) => {
            log(&format!(
                "warning: the reference is not cached ({e}); this run goes on with it"
            ));
            "not cached".to_string()
        }
    };
    Ok((
        r.image,
        format!("rendered: {stored} ({:.1} s)", r.elapsed.as_secs_f64()),
    ))
}
