//! Materials as the scene describes them, and their mapping from Wavefront MTL.
//!
//! | MTL | footprint |
//! |---|---|
//! | `Kd` (and `map_Kd`) | Lambertian albedo (textured when `map_Kd` is given) |
//! | `Ks` + `Ns`, `illum` 2 | normalised Blinn lobe of exponent `Ns`, layered over `Kd` |
//! | `illum` 3 or 5 | perfect mirror of reflectance `Ks` (white when `Ks` is black) |
//! | `illum` 4, 6 or 7, or `Ni` > 1 with `Tf` set | smooth dielectric, IOR `Ni`, transmittance `Tf` |
//! | `Ke` | emission: the faces become area lights of radiance `Ke` |
//!
//! Mitsuba 3 scenes (`crate::scene::mitsuba`) add the kinds Mitsuba's BSDFs need: smooth and rough
//! conductors with a complex index of refraction, smooth and rough plastic, the rough
//! dielectric, the thin dielectric sheet and the principled BSDF; the mapping is tabled in
//! `docs/mitsuba.md`.

use crate::Rgb;
use crate::bsdf::bump::BumpMap;
use crate::bsdf::microfacet::{Microfacet, MicrofacetDistribution};
use crate::bsdf::principled::PrincipledParams;
use crate::bsdf::rough_plastic::RoughPlasticTables;

/// The kind of scattering a material does.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MaterialKind {
    /// Lambertian.
    Diffuse,
    /// Lambertian plus a normalised Blinn lobe.
    Glossy,
    /// Perfect specular reflection.
    Mirror,
    /// Smooth dielectric interface with coloured transmittance.
    Glass,
    /// Smooth conductor: mirror reflection weighted by the conductor Fresnel term of the
    /// complex IOR `eta + i k`, times `ks` (Mitsuba `conductor`).
    Conductor,
    /// Microfacet conductor (Mitsuba `roughconductor`): distribution `microfacet` with
    /// roughness `alpha`, conductor Fresnel of `eta + i k`, times `ks`.
    RoughConductor,
    /// Smooth dielectric coating (IOR `ni`, reflectance `ks`) over a Lambertian base `kd`
    /// (Mitsuba `plastic`).
    Plastic,
    /// Microfacet dielectric coating (`microfacet`, `alpha`, IOR `ni`, reflectance `ks`) over
    /// a Lambertian base `kd` (Mitsuba `roughplastic`).
    RoughPlastic,
    /// Rough dielectric interface of IOR `ni` (Mitsuba `roughdielectric`): microfacet
    /// reflection (factor `ks`) and refraction (factor `sqrt(tf)` per crossing, so `tf` per
    /// passage in and out, as for `Glass`) with distribution `microfacet` of roughness `alpha`.
    RoughGlass,
    /// Thin dielectric sheet of IOR `ni` (Mitsuba `thindielectric`): reflection and straight
    /// transmission with the multiple internal reflections summed.
    ThinGlass,
    /// Mitsuba's `principled` (the Disney BSDF): base colour `kd` (and `kd_texture`), the
    /// other parameters in `principled`.
    Principled,
}

impl MaterialKind {
    pub fn parse(s: &str) -> Option<Self> {
        Some(match s {
            "diffuse" => MaterialKind::Diffuse,
            "glossy" => MaterialKind::Glossy,
            "mirror" => MaterialKind::Mirror,
            "glass" => MaterialKind::Glass,
            // The Mitsuba kinds need parameters the TOML format does not carry; Mitsuba XML
            // scenes set them directly.
            _ => return None,
        })
    }
}

/// A material: the parameters every kind may use.
#[derive(Clone, Debug)]
pub struct Material {
    pub name: String,
    pub kind: MaterialKind,
    /// Diffuse albedo (Diffuse, Glossy).
    pub kd: Rgb,
    /// Index into the scene's textures modulating `kd`.
    pub kd_texture: Option<u32>,
    /// Glossy reflectance (Glossy), mirror reflectance (Mirror), or the specular
    /// reflectance factor (Conductor, RoughConductor, Plastic, RoughPlastic, ThinGlass,
    /// RoughGlass).
    pub ks: Rgb,
    /// Index into the scene's textures modulating `ks`.
    pub ks_texture: Option<u32>,
    /// Blinn exponent (Glossy).
    pub ns: f32,
    /// Transmittance of one passage through the object (Glass, RoughGlass: two crossings of
    /// the interface), of the sheet (ThinGlass).
    pub tf: Rgb,
    /// Relative index of refraction, interior over exterior (Glass, RoughGlass, Plastic,
    /// RoughPlastic, ThinGlass).
    pub ni: f32,
    /// Real part of a conductor's relative complex IOR, per channel.
    pub eta: Rgb,
    /// Imaginary part (absorption) of a conductor's relative complex IOR, per channel.
    pub k: Rgb,
    /// Microfacet roughness α (RoughConductor, RoughPlastic, RoughGlass); of an anisotropic
    /// one, `α_u`, along the shading frame's tangent `∂p/∂u`.
    pub alpha: f32,
    /// An anisotropic roughness's `α_v`, across that tangent (RoughConductor, RoughGlass;
    /// Mitsuba's `alpha_v`); `None`: isotropic.
    pub alpha_v: Option<f32>,
    pub microfacet: Microfacet,
    /// False: the surface scatters only on the side its shading normal faces and is black
    /// seen from the back (a Mitsuba BSDF not wrapped in `twosided`). Transmissive kinds
    /// ignore it.
    pub two_sided: bool,
    /// Plastic: Mitsuba's `nonlinear` (the diffuse base's internal scattering tints it).
    pub nonlinear: bool,
    /// Emitted radiance; non-zero makes the faces area lights.
    pub ke: Rgb,
    /// RoughPlastic: the coating's precomputed tables, filled by [`Material::prepared`].
    /// Without them (or when `alpha`, `ni` or `microfacet` changed since), the BSDF fetches
    /// them from the process-wide cache at every hit, which is correct but takes a lock.
    pub rough_plastic: Option<&'static RoughPlasticTables>,
    /// A height field that tilts the shading normal (Mitsuba `bumpmap` around this material).
    pub bump: Option<BumpMap>,
    /// The surface's opacity in [0, 1] (Mitsuba `mask` around this material): where it is
    /// under 1 the surface is a cut-out that light passes straight through with probability
    /// `1 - opacity` ([`crate::scene::Scene::opacity`]). 1: opaque.
    pub opacity: f32,
    /// Index into the scene's textures whose luminance multiplies `opacity`.
    pub opacity_texture: Option<u32>,
    /// Mitsuba's `blendbsdf`: this material blended with a second one
    /// ([`crate::bsdf::blend`]); the fields above describe the first.
    pub blend: Option<Box<MaterialBlend>>,
    /// Principled: the parameters but the base colour.
    pub principled: PrincipledParams,
}

/// The second BSDF of a blend and its weight (the material holding it is the first).
#[derive(Clone, Debug)]
pub struct MaterialBlend {
    /// Share of `other`, in [0, 1] (times `weight_texture`'s luminance where given).
    pub weight: f32,
    pub weight_texture: Option<u32>,
    /// A reflecting kind without a bump map, a mask or a blend of its own.
    pub other: Material,
}

impl Default for Material {
    fn default() -> Self {
        Material {
            name: "default".into(),
            kind: MaterialKind::Diffuse,
            kd: Rgb::splat(0.5),
            kd_texture: None,
            ks: Rgb::ZERO,
            ks_texture: None,
            ns: 1.0,
            tf: Rgb::ONE,
            ni: 1.5,
            eta: Rgb::ONE,
            k: Rgb::ZERO,
            alpha: 0.1,
            alpha_v: None,
            microfacet: Microfacet::Ggx,
            two_sided: true,
            nonlinear: false,
            ke: Rgb::ZERO,
            rough_plastic: None,
            bump: None,
            opacity: 1.0,
            opacity_texture: None,
            blend: None,
            principled: PrincipledParams::default(),
        }
    }
}

impl Material {
    /// Maps an MTL material (see the module table).
    pub fn from_mtl(m: &tobj::Material, kd_texture: Option<u32>) -> Self {
        let v = |a: Option<[f32; 3]>| a.map(Rgb::from).unwrap_or(Rgb::ZERO);
        let kd = m.diffuse.map(Rgb::from).unwrap_or(Rgb::splat(0.8));
        let ks = v(m.specular);
        let ns = m.shininess.unwrap_or(1.0);
        let ni = m.optical_density.unwrap_or(1.5);
        let illum = m.illumination_model.unwrap_or(2);
        let tf = m
            .unknown_param
            .get("Tf")
            .and_then(|s| parse_rgb(s))
            .unwrap_or(Rgb::ONE);
        let ke = m
            .emissive
            .map(Rgb::from)
            .or_else(|| m.unknown_param.get("Ke").and_then(|s| parse_rgb(s)))
            .unwrap_or(Rgb::ZERO);
        let kind = match illum {
            3 | 5 => MaterialKind::Mirror,
            4 | 6 | 7 => MaterialKind::Glass,
            _ if ks.max_element() > 0.0 => MaterialKind::Glossy,
            _ => MaterialKind::Diffuse,
        };
        let ks = if kind == MaterialKind::Mirror && ks.max_element() <= 0.0 {
            Rgb::ONE
        } else {
            ks
        };
        Material {
            name: m.name.clone(),
            kind,
            kd,
            kd_texture,
            ks,
            ns,
            tf,
            ni,
            ke,
            ..Material::default()
        }
        .sanitized()
    }

    /// Clamps parameters into their physical ranges: albedos in [0, 1], `kd + ks <= 1` per
    /// channel for the layered glossy model (energy conservation), `ns >= 0`, `ni > 0`.
    pub fn sanitized(mut self) -> Self {
        let clamp01 = |c: Rgb| c.clamp(Rgb::ZERO, Rgb::ONE);
        self.kd = clamp01(self.kd);
        self.ks = clamp01(self.ks);
        self.tf = clamp01(self.tf);
        self.ke = self.ke.max(Rgb::ZERO);
        if self.kind == MaterialKind::Glossy {
            let sum = self.kd + self.ks;
            let m = sum.max_element();
            if m > 1.0 {
                self.kd /= m;
                self.ks /= m;
            }
        }
        self.ns = self.ns.clamp(0.0, 1.0e6);
        if !(self.ni > 0.0) {
            self.ni = 1.5;
        }
        self.opacity = if self.opacity.is_nan() {
            1.0
        } else {
            self.opacity.clamp(0.0, 1.0)
        };
        self
    }

    /// The material ready for rendering: a RoughPlastic gets its coating's tables (computed
    /// once per distinct `(microfacet, alpha, ni)`, a fraction of a second, then cached).
    /// `Scene::new` calls it on every material; a material built by hand for a BSDF alone
    /// (tests) calls it itself.
    pub fn prepared(mut self) -> Self {
        self.rough_plastic = match self.kind {
            MaterialKind::RoughPlastic => Some(RoughPlasticTables::get(
                self.microfacet,
                self.alpha,
                self.ni,
            )),
            _ => None,
        };
        if let Some(b) = self.blend.as_mut() {
            b.other = b.other.clone().prepared();
        }
        self
    }

    /// The material and, for a blend, its second component: the materials whose kinds a
    /// surface of this one shows.
    pub fn components(&self) -> impl Iterator<Item = &Material> {
        std::iter::once(self).chain(self.blend.as_ref().map(|b| &b.other))
    }

    /// The microfacet distribution of the rough kinds (`alpha`, `alpha_v`, `microfacet`).
    pub fn distribution(&self) -> MicrofacetDistribution {
        let alpha_v = self.alpha_v.unwrap_or(self.alpha);
        MicrofacetDistribution::anisotropic(self.microfacet, self.alpha, alpha_v)
    }

    /// The roughness is anisotropic: the BSDF's shading frame must follow `∂p/∂u`.
    pub fn is_anisotropic(&self) -> bool {
        self.alpha_v.is_some_and(|v| v != self.alpha)
    }

    /// True for the kinds that scatter through the surface: the dielectrics, and a principled
    /// BSDF that may transmit.
    pub fn transmits(&self) -> bool {
        match self.kind {
            MaterialKind::Glass | MaterialKind::ThinGlass | MaterialKind::RoughGlass => true,
            MaterialKind::Principled => self.principled.may_transmit(),
            _ => false,
        }
    }

    pub fn emits(&self) -> bool {
        self.ke.max_element() > 0.0
    }

    /// True when light may pass the surface where it is cut out (an opacity under 1, or an
    /// opacity texture).
    pub fn is_masked(&self) -> bool {
        self.opacity < 1.0 || self.opacity_texture.is_some()
    }
}

fn parse_rgb(s: &str) -> Option<Rgb> {
    let vals: Vec<f32> = s
        .split_whitespace()
        .filter_map(|t| t.parse::<f32>().ok())
        .collect();
    match vals.as_slice() {
        [v] => Some(Rgb::splat(*v)),
        [r, g, b, ..] => Some(Rgb::new(*r, *g, *b)),
        _ => None,
    }
}
