//! The effects a path loop is compiled for. The integrators' one path loop
//! (`integrators/src/walk.rs`) and what it calls at a vertex (the hit, the BSDF, the direction
//! sampler) take a [`Features`] type whose `const` flags say which effects can occur; code for
//! an absent effect is compiled out of that instantiation. A render picks the instantiation for
//! its scene's effect set once ([`crate::scene::features::Specialisation::for_effects`]);
//! `General` has every flag and is what the plain (unsuffixed) functions run.
//!
//! **Same image.** A specialised loop only leaves out branches that cannot be taken in a scene
//! of its effect set and computes everything else with the same floating-point operations in
//! the same order (for example the Lambertian BSDF computes only the cosines it needs, each
//! the very dot product the general frame transform makes): for a fixed seed it draws the same
//! random numbers and gives the same image, bit for bit (`tests/effects.rs`).
//!
//! Where a flag only enables a fast path whose guard is also checked at run time (the
//! Lambertian lobes), a wrong analysis costs speed, never correctness; the flags that remove
//! work outright (textures, shading normals, lights, the environment) come from
//! [`crate::scene::effects::Effects::analyse`], which reads every triangle and light.

/// Which effects a compiled loop handles. Every flag false means the effect cannot occur in
/// the scenes this instantiation is used for.
pub trait Features: Send + Sync + 'static {
    /// Materials with a texture.
    const TEXTURES: bool;
    /// Triangles with vertex normals (shading normals differ from geometric ones).
    const SHADING_NORMALS: bool;
    /// Lobes other than a plain Lambertian one that are not delta (Blinn, microfacet, the
    /// plastics' bases).
    const GLOSSY: bool;
    /// Delta lobes (mirrors, glass, conductors, the coat of smooth plastic).
    const SPECULAR: bool;
    const AREA_LIGHTS: bool;
    /// Point, spot and directional lights.
    const DELTA_LIGHTS: bool;
    /// An environment (uniform or from an image).
    const ENVIRONMENT: bool;
    /// Every surface is Lambertian: the BSDF's fast path.
    const LAMBERTIAN: bool = !Self::GLOSSY && !Self::SPECULAR;
}

/// Every effect: the general loop.
pub struct General;
/// Lambertian surfaces lit by area lights, no textures, no shading normals, no environment
/// (cornell, door, the furnace, both Cornell boxes of `scenes-ext`).
pub struct LambertArea;
/// Any lobes and lights but no textures, shading normals or environment (desk, glass and
/// metal scenes built from flat meshes).
pub struct Untextured;

impl Features for General {
    const TEXTURES: bool = true;
    const SHADING_NORMALS: bool = true;
    const GLOSSY: bool = true;
    const SPECULAR: bool = true;
    const AREA_LIGHTS: bool = true;
    const DELTA_LIGHTS: bool = true;
    const ENVIRONMENT: bool = true;
}

impl Features for LambertArea {
    const TEXTURES: bool = false;
    const SHADING_NORMALS: bool = false;
    const GLOSSY: bool = false;
    const SPECULAR: bool = false;
    const AREA_LIGHTS: bool = true;
    const DELTA_LIGHTS: bool = false;
    const ENVIRONMENT: bool = false;
}

impl Features for Untextured {
    const TEXTURES: bool = false;
    const SHADING_NORMALS: bool = false;
    const GLOSSY: bool = true;
    const SPECULAR: bool = true;
    const AREA_LIGHTS: bool = true;
    const DELTA_LIGHTS: bool = true;
    const ENVIRONMENT: bool = false;
}
