//! Scene analysis: which light-transport effects a scene contains, so that the passes and
//! code paths for absent effects are skipped rather than run idle.

use crate::bsdf::material::{Material, MaterialKind};
use crate::bsdf::principled::Scalar;
use crate::scene::geometry::TriangleShading;
use crate::scene::light::Light;

/// The effects a scene calls for.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Effects {
    pub diffuse: bool,
    pub glossy: bool,
    pub specular_reflection: bool,
    /// Delta refraction (smooth and thin glass); the rough dielectric's is glossy.
    pub refraction: bool,
    /// Thin dielectric sheets (Mitsuba `thindielectric`): connections pass through them
    /// with their transmittance ([`crate::scene::Scene::transmittance`]).
    pub thin_glass: bool,
    /// Cut-out surfaces (Mitsuba `mask`): light passes them straight through where their
    /// opacity is under 1 ([`crate::scene::Scene::opacity`]).
    pub masks: bool,
    /// Transmission that changes colour (glass with a non-grey `Tf`).
    pub coloured_filtering: bool,
    pub textures: bool,
    /// Some triangle has vertex normals (shading normals).
    pub shading_normals: bool,
    /// Some material is other than a plain Lambertian one (glossy, plastic, conductor,
    /// glass, ...), whatever its reflectances.
    pub non_lambertian: bool,
    pub area_lights: bool,
    pub spot_lights: bool,
    pub point_lights: bool,
    /// A directional light (Mitsuba's `directional`): a delta light at infinity.
    pub directional_lights: bool,
    /// An environment (Mitsuba's `constant` or `envmap` emitter): escaped paths see it.
    pub environment: bool,
    /// A light path can reach a diffuse or glossy surface after a specular bounce
    /// (L S+ D): needs a specular surface and a non-specular one.
    pub caustics_possible: bool,
}

impl Effects {
    /// Analyses the materials actually used by triangles, and the lights.
    pub fn analyse(materials: &[Material], shading: &[TriangleShading], lights: &[Light]) -> Self {
        let mut used = vec![false; materials.len()];
        for s in shading {
            used[s.material as usize] = true;
        }
        let mut e = Effects::default();
        e.shading_normals = shading.iter().any(|s| s.normals.is_some());
        let components = materials
            .iter()
            .zip(&used)
            .filter(|(_, u)| **u)
            .flat_map(|(m, _)| m.components());
        for m in components {
            // A blend is no plain Lambertian surface, whatever its components.
            e.non_lambertian |= m.kind != MaterialKind::Diffuse || m.blend.is_some();
            match m.kind {
                MaterialKind::Diffuse => e.diffuse |= m.kd.max_element() > 0.0,
                MaterialKind::Glossy => {
                    e.diffuse |= m.kd.max_element() > 0.0;
                    e.glossy |= m.ks.max_element() > 0.0;
                }
                MaterialKind::Mirror => e.specular_reflection |= m.ks.max_element() > 0.0,
                MaterialKind::Glass => {
                    e.refraction = true;
                    e.specular_reflection = true;
                    let t = m.tf;
                    e.coloured_filtering |= t.max_element() - t.min_element() > 1e-4;
                }
                MaterialKind::Conductor => e.specular_reflection |= m.ks.max_element() > 0.0,
                MaterialKind::RoughConductor => e.glossy |= m.ks.max_element() > 0.0,
                MaterialKind::Plastic => {
                    e.diffuse |= m.kd.max_element() > 0.0;
                    e.specular_reflection |= m.ks.max_element() > 0.0;
                }
                MaterialKind::RoughPlastic => {
                    e.diffuse |= m.kd.max_element() > 0.0;
                    e.glossy |= m.ks.max_element() > 0.0;
                }
                // Glossy reflection and glossy refraction: no delta lobe.
                MaterialKind::RoughGlass => {
                    e.glossy |= m.ks.max_element() > 0.0 || m.tf.max_element() > 0.0;
                    let t = m.tf;
                    e.coloured_filtering |= t.max_element() - t.min_element() > 1e-4;
                }
                MaterialKind::ThinGlass => {
                    e.specular_reflection = true;
                    e.refraction = true;
                    e.thin_glass = true;
                    let t = m.tf;
                    e.coloured_filtering |= t.max_element() - t.min_element() > 1e-4;
                }
                // The main lobe is glossy (reflection, and refraction where it transmits,
                // tinted by the base colour's square root); the diffuse lobe is there unless
                // the material is all metal or all transmission.
                MaterialKind::Principled => {
                    let p = &m.principled;
                    let varies = |s: Scalar| s.texture.is_some();
                    let base = m.kd_texture.is_some() || m.kd.max_element() > 0.0;
                    e.glossy = true;
                    e.diffuse |= base
                        && (varies(p.metallic) || p.metallic.value < 1.0)
                        && (varies(p.spec_trans) || p.spec_trans.value < 1.0);
                    let transmits = varies(p.spec_trans) || p.spec_trans.value > 0.0;
                    let c = m.kd;
                    e.coloured_filtering |= transmits
                        && (m.kd_texture.is_some() || c.max_element() - c.min_element() > 1e-4);
                    e.textures |= p.textured();
                }
            }
            e.masks |= m.is_masked();
            // A bump map's height field and an opacity map are textures too.
            e.textures |= m.kd_texture.is_some()
                || m.ks_texture.is_some()
                || m.bump.is_some()
                || m.opacity_texture.is_some()
                || m.blend.as_ref().is_some_and(|b| b.weight_texture.is_some());
        }
        for l in lights {
            match l {
                Light::Area { .. } => e.area_lights = true,
                Light::Spot { .. } => e.spot_lights = true,
                Light::Point { .. } => e.point_lights = true,
                Light::Directional { .. } => e.directional_lights = true,
                Light::Environment { .. } => e.environment = true,
            }
        }
        e.caustics_possible = (e.specular_reflection || e.refraction) && (e.diffuse || e.glossy);
        e
    }

    /// True when a connection may pass a surface: thin dielectric sheets or cut-outs
    /// ([`crate::scene::Scene::transmittance`]).
    #[inline]
    pub fn passes_light(&self) -> bool {
        self.thin_glass || self.masks
    }

    /// `(name, present)` for every effect, in a fixed order.
    pub fn list(&self) -> [(&'static str, bool); 14] {
        [
            ("diffuse", self.diffuse),
            ("glossy", self.glossy),
            ("specular reflection", self.specular_reflection),
            ("refraction", self.refraction),
            ("coloured filtering", self.coloured_filtering),
            ("cut-outs", self.masks),
            ("textures", self.textures),
            ("shading normals", self.shading_normals),
            ("area lights", self.area_lights),
            ("spot lights", self.spot_lights),
            ("point lights", self.point_lights),
            ("directional lights", self.directional_lights),
            ("environment", self.environment),
            ("caustic paths", self.caustics_possible),
        ]
    }

    /// What the renderer skips because of absent effects (one line each): only code paths
    /// and passes that are actually guarded by the analysis are listed (the rules:
    /// `integrators/src/skips.rs`; the compiled loops: [`crate::scene::features`]).
    pub fn skipped(&self) -> Vec<&'static str> {
        let mut s = Vec::new();
        if !self.area_lights {
            s.push("emission lookups and MIS weights at surface hits (no area lights)");
        }
        if !self.environment {
            s.push("environment lookups for escaping rays (no environment)");
        }
        if !self.textures {
            s.push("texture lookups (no textures)");
        }
        if !self.shading_normals {
            s.push("shading-normal interpolation (no vertex normals)");
        }
        s
    }
}
