//! What a render skips because its scene lacks an effect: the rules, each shown by a test to
//! change nothing in the image (`tests/effects.rs`), and the counters the run summary
//! reports for them. The code skips are compiled into the path loop chosen for the scene
//! (`footprint::scene::features`); the work skips are decided here.
//!
//! 1. **No area lights**: camera paths do no emission lookup (and no MIS weight) at surface
//!    hits; counted as the camera-path hits.
//! 2. **No environment**: rays that leave the scene look nothing up; counted as the
//!    camera-path rays that escaped.
//! 3. **Specialised loop**: texture lookups, shading-normal interpolation, the non-Lambertian
//!    lobes' dispatch, delta-light and environment branches compiled out where absent; counted
//!    as the paths that ran in the specialised loop.
//! 4. **No surface stores particles** (no diffuse or soft glossy surface, so no vertex can be
//!    guided and no particle stored): a guided method runs no light pass, no view pass and
//!    builds no map or cache; counted as the passes skipped.

use crate::render::GuideCounts;
use footprint::bsdf::Lobes;
use footprint::guide::guides_at;
use footprint::scene::Scene;
use footprint::scene::features::Specialisation;

/// True when some surface of the scene stores particles and can be guided (a diffuse or soft
/// glossy one, [`guides_at`]); rule 4 skips the maps otherwise.
pub fn particles_stored(scene: &Scene) -> bool {
    let mut used = vec![false; scene.materials.len()];
    for s in scene.shading.iter() {
        used[s.material as usize] = true;
    }
    scene
        .materials
        .iter()
        .zip(&used)
        .filter(|(_, u)| **u)
        .any(|(m, _)| guides_at(&Lobes::new(m, m.kd, m.ks).lobes, scene.maps.soft_glossy_max))
}

/// The line of rule 4 when it skipped `passes` passes.
pub fn maps_skipped(passes: usize) -> String {
    format!(
        "{passes} particle pass(es) and their maps and caches: no diffuse or soft glossy surface stores particles or can be guided"
    )
}

/// The run summary's lines for rules 1-3: what was skipped and how often.
pub fn counted(
    scene: &Scene,
    specialisation: Specialisation,
    camera: Option<&GuideCounts>,
    paths: u64,
) -> Vec<String> {
    let mut out = Vec::new();
    if let Some(c) = camera {
        if !scene.effects.area_lights {
            out.push(format!(
                "{} emission lookups at camera-path hits (no area lights)",
                c.vertices
            ));
        }
        if !scene.effects.environment {
            out.push(format!(
                "{} environment lookups for escaping camera rays (no environment)",
                c.escapes
            ));
        }
    }
    if specialisation != Specialisation::General {
        out.push(format!(
            "{paths} paths ran in the loop compiled for {} (the general loop's other branches compiled out)",
            specialisation.name()
        ));
    }
    out
}
