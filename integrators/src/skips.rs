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

use crate::counts::GuideCounts;
use footprint::bsdf::Lobes;
use footprint::guide::guides_at;
use footprint::scene::Scene;
use footprint::scene::features::Specialisation;
use std::fmt;

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
        .any(|(m, _)| {
            m.components()
                .all(|c| guides_at(&Lobes::new(c, c.kd, c.ks).lobes, scene.maps.soft_glossy_max))
        })
}

/// What a render skipped by one rule, and how often: the run summary prints it, the tests
/// read its fields.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Skip {
    /// Rule 1: emission lookups at camera-path hits (no area lights).
    EmissionLookups(u64),
    /// Rule 2: environment lookups for escaping camera rays (no environment).
    EnvironmentLookups(u64),
    /// Rule 3: paths that ran in the loop compiled for the scene's effects.
    SpecialisedLoop {
        paths: u64,
        specialisation: Specialisation,
    },
    /// Rule 4: particle passes (and their maps and caches) not run.
    ParticlePasses(usize),
}

impl Skip {
    /// How often the rule skipped its work.
    pub fn count(&self) -> u64 {
        match *self {
            Skip::EmissionLookups(n) | Skip::EnvironmentLookups(n) => n,
            Skip::SpecialisedLoop { paths, .. } => paths,
            Skip::ParticlePasses(n) => n as u64,
        }
    }
}

impl fmt::Display for Skip {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Skip::EmissionLookups(n) => {
                write!(
                    f,
                    "{n} emission lookups at camera-path hits (no area lights)"
                )
            }
            Skip::EnvironmentLookups(n) => write!(
                f,
                "{n} environment lookups for escaping camera rays (no environment)"
            ),
            Skip::SpecialisedLoop {
                paths,
                specialisation,
            } => write!(
                f,
                "{paths} paths ran in the loop compiled for {} (the general loop's other branches compiled out)",
                specialisation.name()
            ),
            Skip::ParticlePasses(n) => write!(
                f,
                "{n} particle pass(es) and their maps and caches: no diffuse or soft glossy surface stores particles or can be guided"
            ),
        }
    }
}

/// What rules 1-3 skipped in a render, and how often.
pub fn counted(
    scene: &Scene,
    specialisation: Specialisation,
    camera: Option<&GuideCounts>,
    paths: u64,
) -> Vec<Skip> {
    let mut out = Vec::new();
    if let Some(c) = camera {
        if !scene.effects.area_lights {
            out.push(Skip::EmissionLookups(c.vertices));
        }
        if !scene.effects.environment {
            out.push(Skip::EnvironmentLookups(c.escapes));
        }
    }
    if specialisation != Specialisation::General {
        out.push(Skip::SpecialisedLoop {
            paths,
            specialisation,
        });
    }
    out
}
