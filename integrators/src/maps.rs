//! `footprint maps`: builds the photon map and the importance map of a scene and writes
//! pictures of them seen from the camera (particles splatted as points coloured by their
//! power or importance, as in the paper's figure 10), with counts, memory and times.

use crate::passes::{PassOutput, PassSettings, light_pass, view_pass};
use footprint::Rgb;
use footprint::film::Image;
use footprint::particle_map::{MapKind, ParticleInput, ParticleMap};
use footprint::scene::Scene;
use rayon::prelude::*;

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

/// Runs a pass and builds its map; `measure` returns the heap bytes currently allocated
/// (a counting allocator), so the map's own footprint is the difference around the build.
pub fn build_map(
    scene: &Scene,
    kind: MapKind,
    s: &PassSettings,
    measure: &dyn Fn() -> Option<usize>,
) -> BuiltMap {
    let pass = match kind {
        MapKind::Photons => light_pass(scene, s),
        MapKind::Importons => view_pass(scene, s),
    };
    let before = measure();
    let map = ParticleMap::build(kind, &pass.particles);
    let after = measure();
    let bytes = match (before, after) {
        (Some(b), Some(a)) => Some(a.saturating_sub(b)),
        _ => None,
    };
    BuiltMap { map, pass, bytes }
}

/// A picture of `particles` seen from the camera: every particle visible from the camera is
/// a point of its weight's colour, normalised so that the 99th-percentile particle is white.
pub fn picture(scene: &Scene, particles: &[ParticleInput]) -> Image {
    let cam = &scene.camera;
    let mut peak: Vec<f32> = particles
        .iter()
        .map(|p| p.weight.max_element())
        .filter(|v| *v > 0.0)
        .collect();
    let norm = if peak.is_empty() {
        1.0
    } else {
        let i = ((peak.len() as f64 * 0.99) as usize).min(peak.len() - 1);
        *peak.select_nth_unstable_by(i, |a, b| a.total_cmp(b)).1
    };
    let splats: Vec<(usize, Rgb)> = particles
        .par_iter()
        .filter_map(|p| {
            let conn = cam.connect(p.position)?;
            if !scene.visible_from_camera(p.position, p.normal) {
                return None;
            }
            let x = (conn.raster.x as usize).min(cam.width as usize - 1);
            let y = (conn.raster.y as usize).min(cam.height as usize - 1);
            Some((y * cam.width as usize + x, (p.weight / norm).min(Rgb::ONE)))
        })
        .collect();
    let mut img = Image::new(cam.width, cam.height);
    let mut count = vec![0u32; img.pixels.len()];
    for (i, c) in splats {
        img.pixels[i] += c;
        count[i] += 1;
    }
    for (p, c) in img.pixels.iter_mut().zip(count) {
        if c > 0 {
            *p /= c as f32;
        }
    }
    img
}
