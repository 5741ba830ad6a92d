//! The compiled path loops and the choice among them: a scene's effects
//! ([`crate::scene::effects::Effects`]) pick the narrowest instantiation of the
//! [`crate::features`] types that handles them. The types are re-exported here.

pub use crate::features::{Features, General, LambertArea, Untextured};
use crate::scene::effects::Effects;

/// The compiled loops, chosen once per render from the scene's effects.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Specialisation {
    LambertArea,
    Untextured,
    General,
}

impl Specialisation {
    /// The narrowest compiled loop that handles every effect of `e`.
    pub fn for_effects(e: &Effects) -> Self {
        let plain = !e.textures && !e.shading_normals && !e.environment;
        let lambert = !e.non_lambertian && !e.glossy && !e.specular_reflection && !e.refraction;
        let delta_lights = e.spot_lights || e.point_lights || e.directional_lights;
        if plain && lambert && !delta_lights {
            Specialisation::LambertArea
        } else if plain {
            Specialisation::Untextured
        } else {
            Specialisation::General
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Specialisation::LambertArea => "lambertian surfaces, area lights",
            Specialisation::Untextured => "no textures, no shading normals, no environment",
            Specialisation::General => "general",
        }
    }
}
