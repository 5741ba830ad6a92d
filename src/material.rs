//! Materials as the scene describes them, and their mapping from Wavefront MTL.
//!
//! | MTL | footprint |
//! |---|---|
//! | `Kd` (and `map_Kd`) | Lambertian albedo (textured when `map_Kd` is given) |
//! | `Ks` + `Ns`, `illum` 2 | normalised Blinn lobe of exponent `Ns`, layered over `Kd` |
//! | `illum` 3 or 5 | perfect mirror of reflectance `Ks` (white when `Ks` is black) |
//! | `illum` 4, 6 or 7, or `Ni` > 1 with `Tf` set | smooth dielectric, IOR `Ni`, transmittance `Tf` |
//! | `Ke` | emission: the faces become area lights of radiance `Ke` |

use crate::Rgb;

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
}

impl MaterialKind {
    pub fn parse(s: &str) -> Option<Self> {
        Some(match s {
            "diffuse" => MaterialKind::Diffuse,
            "glossy" => MaterialKind::Glossy,
            "mirror" => MaterialKind::Mirror,
            "glass" => MaterialKind::Glass,
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
    /// Glossy reflectance (Glossy) or mirror reflectance (Mirror).
    pub ks: Rgb,
    /// Blinn exponent (Glossy).
    pub ns: f32,
    /// Transmittance of one passage through the object (Glass).
    pub tf: Rgb,
    /// Index of refraction (Glass).
    pub ni: f32,
    /// Emitted radiance; non-zero makes the faces area lights.
    pub ke: Rgb,
}

impl Default for Material {
    fn default() -> Self {
        Material {
            name: "default".into(),
            kind: MaterialKind::Diffuse,
            kd: Rgb::splat(0.5),
            kd_texture: None,
            ks: Rgb::ZERO,
            ns: 1.0,
            tf: Rgb::ONE,
            ni: 1.5,
            ke: Rgb::ZERO,
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
        self
    }

    pub fn emits(&self) -> bool {
        self.ke.max_element() > 0.0
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
