//! Every BSDF: sampling matches its pdf (chi-square), `sample` reports the pdf that `pdf`
//! gives, energy conservation (albedo at most 1), reciprocity in radiance mode, and the smooth
//! dielectric's Fresnel split, Snell's law and transport-mode scaling.
//!
//! The Mitsuba 3 kinds (conductor, rough conductor, plastic, rough plastic, thin dielectric,
//! rough dielectric), and blends of them, join the same tests, and more: their values against Mitsuba 3's own
//! (`matches_mitsuba_3`, constants printed by scripts/mitsuba_bsdf_values.py), random
//! configurations down to grazing and α = 1e-3, the white furnace, the thin sheet's
//! R + T = 1, the conductor Fresnel term, one-sidedness, and which kinds are delta and
//! guide; the rough dielectric's adjoint and generalised reciprocity across the interface,
//! and its furnace against a quadrature (`bsdf/rough_dielectric.rs`); the microfacet
//! distributions' normalisation and masking, anisotropic ones included
//! (`bsdf/microfacet.rs`).
//!
//! The parts live in `tests/bsdf/`; this root holds what they share.

mod common;

#[path = "bsdf/blend.rs"]
mod blend;
#[path = "bsdf/configs.rs"]
mod configs;
#[path = "bsdf/energy.rs"]
mod energy;
#[path = "bsdf/microfacet.rs"]
mod microfacet;
#[path = "bsdf/mitsuba.rs"]
mod mitsuba;
#[path = "bsdf/reciprocity.rs"]
mod reciprocity;
#[path = "bsdf/rough_dielectric.rs"]
mod rough_dielectric;
#[path = "bsdf/sampling.rs"]
mod sampling;
#[path = "bsdf/specular.rs"]
mod specular;

use footprint::Rgb;
use footprint::bsdf::blend::Blend;
use footprint::bsdf::material::{Material, MaterialBlend, MaterialKind};
use footprint::bsdf::{Bsdf, Lobes};
use glam::Vec3;

/// A Blinn-Phong lobe of exponent `n` over a diffuse base, chosen in proportion to `kd` and `ks`.
fn glossy(kd: f32, ks: f32, n: f32) -> Lobes {
    let (wd, wg) = (kd, ks);
    Lobes::Glossy {
        kd: Rgb::splat(kd),
        ks: Rgb::splat(ks),
        exponent: n,
        p_glossy: if wd + wg > 0.0 { wg / (wd + wg) } else { 0.5 },
    }
}

/// A direction at polar angle `theta_deg` from +z.
fn dir(theta_deg: f32, phi_deg: f32) -> Vec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

/// A one-sided material of `kind` with the test's default parameters.
fn material(kind: MaterialKind) -> Material {
    Material {
        kind,
        two_sided: false,
        ..Material::default()
    }
}

/// The BSDF of `m` on a flat surface (normal +z) with its untextured `kd` and `ks`.
/// The BSDF of `m` (untextured) under a flat shading frame, a blend's second component too.
fn flat_bsdf(m: &Material) -> Bsdf {
    let mut b = Bsdf::new(Lobes::new(m, m.kd, m.ks), Vec3::Z, Vec3::Z);
    if let Some(blend) = &m.blend {
        let other = Lobes::new(&blend.other, blend.other.kd, blend.other.ks);
        b.blend = Some(Blend {
            weight: blend.weight,
            lobes: other.lobes,
            two_sided: other.two_sided,
        });
    }
    b
}

/// A blend of `first` and `second` (weight `w` on the second), prepared.
fn blend_of(first: Material, second: Material, w: f32) -> Material {
    Material {
        blend: Some(Box::new(MaterialBlend {
            weight: w,
            weight_texture: None,
            other: second,
        })),
        ..first
    }
    .prepared()
}

// The conductor and plastic parameters scripts/mitsuba_bsdf_values.py gives Mitsuba.
const MI_ETA: Rgb = Rgb::new(0.2, 0.45, 1.4);
const MI_K: Rgb = Rgb::new(3.2, 2.5, 1.9);
const MI_KD: Rgb = Rgb::new(0.6, 0.3, 0.15);
const MI_KS: Rgb = Rgb::new(0.9, 0.8, 1.0);
