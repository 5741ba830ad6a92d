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
//! The principled BSDF (`bsdf/principled.rs`) joins the chi-square and sample-pdf harnesses,
//! and is checked against Mitsuba 3's values and sampled albedos, for reciprocity and the
//! adjoint, energy where its model conserves it, and sidedness; the anisotropic microfacet
//! distributions' sampling has a chi-square of its own (`bsdf/anisotropic.rs`).
//!
//! The parts live in `tests/bsdf/`; this root holds what they share.

mod common;

#[path = "bsdf/anisotropic.rs"]
mod anisotropic;
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
#[path = "bsdf/principled.rs"]
mod principled;
#[path = "bsdf/principled_values.rs"]
mod principled_values;
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
use footprint::bsdf::{Bsdf, Lobes, TransportMode};
use glam::Vec3;

/// A row of Mitsuba's values (scripts/mitsuba_bsdf_values.py): material, importance mode,
/// `wo` and `wi` as (θ, φ) in degrees, `f = eval / |cos θ_i|`, pdf.
type MitsubaRow = (&'static str, bool, [f32; 2], [f32; 2], [f32; 3], f32);

/// `|a - b| / |b|`, 0 where the two are equal (zeros included).
fn relative_difference(a: f32, b: f32) -> f32 {
    if a == b {
        0.0
    } else {
        (a - b).abs() / b.abs().max(1e-30)
    }
}

/// `b`'s `eval` and `pdf` against Mitsuba's `row`: asserts `f` within 1e-3 and the pdf
/// within `pdf_tol` (relative), and returns the two relative differences.
fn check_mitsuba_row(b: &Bsdf, row: &MitsubaRow, pdf_tol: f32) -> (f32, f32) {
    let &(name, importance, wo, wi, f_ref, pdf_ref) = row;
    let mode = if importance {
        TransportMode::Importance
    } else {
        TransportMode::Radiance
    };
    let (wo, wi) = (dir(wo[0], wo[1]), dir(wi[0], wi[1]));
    let f = b.eval(wo, wi, mode);
    let pdf = b.pdf(wo, wi);
    let f_ref = Rgb::from(f_ref);
    let f_err = (0..3)
        .map(|c| relative_difference(f[c], f_ref[c]))
        .fold(0.0, f32::max);
    let pdf_err = relative_difference(pdf, pdf_ref);
    assert!(
        f_err <= 1e-3,
        "{name} {mode:?} {wo} {wi}: f {f} vs Mitsuba {f_ref}"
    );
    assert!(
        pdf_err <= pdf_tol,
        "{name} {wo} {wi}: pdf {pdf} vs Mitsuba {pdf_ref}"
    );
    (f_err, pdf_err)
}

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
