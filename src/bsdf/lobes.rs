//! The scattering lobes a material resolves to at a point (textures looked up), and their
//! non-delta `f` and density in the local shading frame (the kinds and their formulas:
//! [`crate::bsdf`]).

use crate::bsdf::blinn::{blinn_eval, blinn_pdf, blinn_sample};
use crate::bsdf::fresnel::{fresnel_conductor, fresnel_dielectric, fresnel_diffuse_reflectance};
use crate::bsdf::material::{Material, MaterialKind};
use crate::bsdf::microfacet::MicrofacetDistribution;
use crate::bsdf::principled::Principled;
use crate::bsdf::rough_glass::RoughGlass;
use crate::bsdf::rough_plastic::RoughPlasticTables;
use crate::bsdf::surface::TransportMode;
use crate::math::{INV_PI, Rgb, luminance};
use crate::sampling::{cosine_hemisphere_pdf, sample_cosine_hemisphere};
use glam::{Vec2, Vec3};

/// The scattering lobes with their parameters resolved at a point (textures looked up).
#[derive(Clone, Copy, Debug)]
pub enum Lobes {
    Diffuse {
        kd: Rgb,
    },
    Glossy {
        kd: Rgb,
        ks: Rgb,
        exponent: f32,
        p_glossy: f32,
    },
    Mirror {
        r: Rgb,
    },
    Glass {
        eta: f32,
        tf_sqrt: Rgb,
    },
    /// Smooth conductor of relative complex IOR `eta + i k`.
    Conductor {
        ks: Rgb,
        eta: Rgb,
        k: Rgb,
    },
    /// Microfacet conductor.
    RoughConductor {
        ks: Rgb,
        eta: Rgb,
        k: Rgb,
        distr: MicrofacetDistribution,
    },
    /// Smooth plastic of IOR `eta`; `diffuse` is `k_d' / η²` (see [`crate::bsdf`]) and
    /// `spec_weight` is `w_s`.
    Plastic {
        diffuse: Rgb,
        ks: Rgb,
        eta: f32,
        spec_weight: f32,
    },
    /// Rough plastic; `diffuse` as for `Plastic` with the tabled internal reflectance.
    RoughPlastic {
        diffuse: Rgb,
        ks: Rgb,
        eta: f32,
        spec_weight: f32,
        distr: MicrofacetDistribution,
        tables: &'static RoughPlasticTables,
    },
    /// Rough dielectric interface (microfacet reflection and refraction, both sides).
    RoughGlass(RoughGlass),
    /// Thin dielectric sheet of IOR `eta`: reflectance factor `ks`, transmittance `tf`.
    ThinGlass {
        eta: f32,
        ks: Rgb,
        tf: Rgb,
    },
    /// Mitsuba's `principled` ([`crate::bsdf::principled`]): reflection only, from the
    /// front, where it does not transmit; on both sides where it does.
    Principled(Principled),
}

/// A direction sampled from the lobes in their local frame, `wo` above the surface.
#[derive(Clone, Copy, Debug)]
pub(super) enum LocalSample {
    /// From a non-delta lobe: `f` and the density are evaluated for it.
    Smooth(Vec3),
    /// From a delta lobe: the direction, its weight `f · cos / prob` and the lobe's discrete
    /// probability `prob`.
    Delta { li: Vec3, weight: Rgb, prob: f32 },
}

/// Lobes and the sidedness of the surface: what a material resolves to at a point. A bare
/// [`Lobes`] converts into a two-sided one.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceLobes {
    pub lobes: Lobes,
    /// False: reflection only above the shading normal (see [`crate::bsdf`]).
    pub two_sided: bool,
}

impl From<Lobes> for SurfaceLobes {
    fn from(lobes: Lobes) -> Self {
        SurfaceLobes {
            lobes,
            two_sided: true,
        }
    }
}

#[inline]
fn mean(c: Rgb) -> f32 {
    (c.x + c.y + c.z) / 3.0
}

/// Mitsuba's `specular_sampling_weight`, `mean(ks) / (mean(kd) + mean(ks))`.
#[inline]
fn specular_weight(kd: Rgb, ks: Rgb) -> f32 {
    let (d, s) = (mean(kd), mean(ks));
    if d + s > 0.0 { s / (d + s) } else { 0.5 }
}

/// The plastic base `k_d'/η²`: `kd` divided by `1 - fdr` (or `1 - kd·fdr` when `nonlinear`),
/// `fdr` the coating's internal diffuse reflectance.
#[inline]
fn plastic_base(kd: Rgb, fdr: f32, nonlinear: bool, eta: f32) -> Rgb {
    let den = if nonlinear {
        Rgb::ONE - kd * fdr
    } else {
        Rgb::splat(1.0 - fdr)
    };
    kd / den / (eta * eta)
}

/// Probability of choosing the specular lobe when it scatters the fraction `fs` of the
/// light and the base `1 - fs` (Mitsuba's plastics).
#[inline]
pub(super) fn specular_probability(fs: f32, spec_weight: f32) -> f32 {
    let ps = fs * spec_weight;
    let pd = (1.0 - fs) * (1.0 - spec_weight);
    if ps + pd > 0.0 { ps / (ps + pd) } else { 0.0 }
}

impl Lobes {
    /// Lobes of `material` with diffuse albedo `kd` and specular reflectance `ks` (both
    /// already textured), with the material's sidedness; textured scalar parameters take
    /// their untextured values ([`Lobes::new_at`]).
    #[allow(clippy::new_ret_no_self)]
    pub fn new(material: &Material, kd: Rgb, ks: Rgb) -> SurfaceLobes {
        Self::new_at(material, kd, ks, |_| None)
    }

    /// [`Lobes::new`] with the textured scalar parameters (the principled material's) from
    /// `scalar`, a texture index to the texture's value at the point (`None`: the
    /// parameter's untextured value).
    pub fn new_at(
        material: &Material,
        kd: Rgb,
        ks: Rgb,
        scalar: impl Fn(u32) -> Option<f32>,
    ) -> SurfaceLobes {
        let lobes = match material.kind {
            MaterialKind::Diffuse => Lobes::Diffuse { kd },
            MaterialKind::Glossy => {
                let wd = luminance(kd);
                let wg = luminance(ks);
                let p_glossy = if wd + wg > 0.0 { wg / (wd + wg) } else { 0.5 };
                Lobes::Glossy {
                    kd,
                    ks,
                    exponent: material.ns,
                    p_glossy,
                }
            }
            MaterialKind::Mirror => Lobes::Mirror { r: ks },
            MaterialKind::Glass => Lobes::Glass {
                eta: material.ni,
                tf_sqrt: Rgb::new(
                    material.tf.x.sqrt(),
                    material.tf.y.sqrt(),
                    material.tf.z.sqrt(),
                ),
            },
            MaterialKind::Conductor => Lobes::Conductor {
                ks,
                eta: material.eta,
                k: material.k,
            },
            MaterialKind::RoughConductor => Lobes::RoughConductor {
                ks,
                eta: material.eta,
                k: material.k,
                distr: material.distribution(),
            },
            MaterialKind::Plastic => {
                let eta = material.ni;
                let fdr = fresnel_diffuse_reflectance(1.0 / eta);
                Lobes::Plastic {
                    diffuse: plastic_base(kd, fdr, material.nonlinear, eta),
                    ks,
                    eta,
                    spec_weight: specular_weight(kd, ks),
                }
            }
            MaterialKind::RoughPlastic => {
                let (kind, alpha, eta) = (material.microfacet, material.alpha, material.ni);
                let tables = match material.rough_plastic {
                    Some(t) if t.matches(kind, alpha, eta) => t,
                    _ => RoughPlasticTables::get(kind, alpha, eta),
                };
                Lobes::RoughPlastic {
                    diffuse: plastic_base(kd, tables.internal_reflectance, material.nonlinear, eta),
                    ks,
                    eta,
                    spec_weight: specular_weight(kd, ks),
                    distr: MicrofacetDistribution::new(kind, alpha),
                    tables,
                }
            }
            MaterialKind::ThinGlass => Lobes::ThinGlass {
                eta: material.ni,
                ks,
                tf: material.tf,
            },
            MaterialKind::RoughGlass => Lobes::RoughGlass(RoughGlass {
                eta: material.ni,
                ks,
                // `tf` is per passage in and out, two crossings.
                kt: material.tf.map(f32::sqrt),
                distr: material.distribution(),
            }),
            MaterialKind::Principled => Lobes::Principled(material.principled.at(kd, scalar)),
        };
        SurfaceLobes {
            lobes,
            two_sided: material.two_sided,
        }
    }

    /// True when every lobe is a delta distribution (smooth plastic is not: its base is
    /// diffuse; [`crate::bsdf::BsdfSample::delta`] tells which lobe a sample came from).
    pub fn is_delta(&self) -> bool {
        matches!(
            self,
            Lobes::Mirror { .. }
                | Lobes::Glass { .. }
                | Lobes::Conductor { .. }
                | Lobes::ThinGlass { .. }
        )
    }

    /// The lobes' reflectance colour, per channel (kd + ks for the layered kinds): the factor
    /// by which a guide weighs particles of each colour channel at this surface (an
    /// approximation only steers variance; guided estimates stay unbiased whatever it is).
    pub fn colour(&self) -> Rgb {
        match *self {
            Lobes::Diffuse { kd } => kd,
            Lobes::Glossy { kd, ks, .. } => kd + ks,
            Lobes::Mirror { r } => r,
            Lobes::Glass { tf_sqrt, .. } => tf_sqrt * tf_sqrt,
            Lobes::Conductor { ks, .. } | Lobes::RoughConductor { ks, .. } => ks,
            Lobes::Plastic { diffuse, ks, .. } | Lobes::RoughPlastic { diffuse, ks, .. } => {
                diffuse + ks
            }
            Lobes::ThinGlass { tf, .. } => tf,
            Lobes::RoughGlass(g) => g.kt,
            Lobes::Principled(p) => p.base_color,
        }
    }

    /// True for the kinds whose sampling reads a number to choose a lobe (or reflection
    /// against refraction); the others (one lobe: Lambertian, a mirror, a conductor) read
    /// none, and their vertices spend no dimension of the sequence on it.
    pub(super) fn chooses_a_lobe(&self) -> bool {
        matches!(
            self,
            Lobes::Glossy { .. }
                | Lobes::Plastic { .. }
                | Lobes::RoughPlastic { .. }
                | Lobes::ThinGlass { .. }
                | Lobes::Glass { .. }
                | Lobes::RoughGlass(_)
                | Lobes::Principled(_)
        )
    }

    /// True for the kinds that scatter through the surface (they ignore sidedness).
    pub(super) fn transmits(&self) -> bool {
        match self {
            Lobes::Glass { .. } | Lobes::ThinGlass { .. } | Lobes::RoughGlass(_) => true,
            Lobes::Principled(p) => p.transmits(),
            _ => false,
        }
    }

    /// True where the lobes are anisotropic about the normal: their frame's tangent must be
    /// the surface's `∂p/∂u`, as Mitsuba's shading frame.
    pub fn is_anisotropic(&self) -> bool {
        match self {
            Lobes::RoughConductor { distr, .. } => !distr.is_isotropic(),
            Lobes::RoughGlass(g) => !g.distr.is_isotropic(),
            Lobes::Principled(p) => p.is_anisotropic(),
            _ => false,
        }
    }

    /// True for the non-delta lobes that scatter to both sides and read `wo`'s side in the
    /// shading frame themselves (the rough dielectric, a transmitting principled): they are
    /// evaluated and sampled by [`Lobes::eval_both_sides`], [`Lobes::pdf_both_sides`] and
    /// [`Lobes::sample_both_sides`], whatever the surface's sidedness flag.
    #[inline]
    pub(super) fn scatters_both_sides(&self) -> bool {
        match self {
            Lobes::RoughGlass(_) => true,
            Lobes::Principled(p) => p.transmits(),
            _ => false,
        }
    }

    /// `f(lo, li)` of the lobes that scatter to both sides, `lo` and `li` on either side.
    #[inline]
    pub(super) fn eval_both_sides(&self, lo: Vec3, li: Vec3, mode: TransportMode) -> Rgb {
        match self {
            Lobes::RoughGlass(g) => g.eval(lo, li, mode),
            Lobes::Principled(p) => p.eval(lo, li, mode),
            _ => Rgb::ZERO,
        }
    }

    /// The density of [`Lobes::sample_both_sides`].
    #[inline]
    pub(super) fn pdf_both_sides(&self, lo: Vec3, li: Vec3) -> f32 {
        match self {
            Lobes::RoughGlass(g) => g.pdf(lo, li),
            Lobes::Principled(p) => p.pdf(lo, li),
            _ => 0.0,
        }
    }

    /// Samples the lobes that scatter to both sides from `lo` on either side.
    #[inline]
    pub(super) fn sample_both_sides(&self, lo: Vec3, u_lobe: f32, u: Vec2) -> Option<Vec3> {
        match self {
            Lobes::RoughGlass(g) => g.sample(lo, u_lobe, u),
            Lobes::Principled(p) => p.sample(lo, u_lobe, u),
            _ => None,
        }
    }

    /// Samples a reflection in the local frame from `lo` (above the surface) with the lobe
    /// number `u_lobe` and the pair `u`; `None` for the transmitting kinds.
    #[inline]
    pub(super) fn sample_reflection_local(
        &self,
        lo: Vec3,
        u_lobe: f32,
        u: Vec2,
    ) -> Option<LocalSample> {
        let mirror = Vec3::new(-lo.x, -lo.y, lo.z);
        let delta = |weight: Rgb, prob: f32| {
            Some(LocalSample::Delta {
                li: mirror,
                weight,
                prob,
            })
        };
        let li = match *self {
            Lobes::Diffuse { .. } => sample_cosine_hemisphere(u),
            Lobes::Glossy {
                exponent, p_glossy, ..
            } => {
                if u_lobe < p_glossy {
                    blinn_sample(exponent, lo, u)?
                } else {
                    sample_cosine_hemisphere(u)
                }
            }
            Lobes::RoughConductor { distr, .. } => reflect(lo, distr.sample_visible(lo, u)),
            Lobes::Principled(p) => p.sample(lo, u_lobe, u)?,
            Lobes::Plastic {
                ks,
                eta,
                spec_weight,
                ..
            } => {
                let fi = fresnel_dielectric(lo.z, eta);
                let ps = specular_probability(fi, spec_weight);
                if u_lobe < ps {
                    return delta(ks * (fi / ps), ps);
                }
                sample_cosine_hemisphere(u)
            }
            Lobes::RoughPlastic {
                spec_weight,
                distr,
                tables,
                ..
            } => {
                let ps = specular_probability(1.0 - tables.transmittance(lo.z), spec_weight);
                if u_lobe < ps {
                    reflect(lo, distr.sample_visible(lo, u))
                } else {
                    sample_cosine_hemisphere(u)
                }
            }
            Lobes::Mirror { r } => return delta(r, 1.0),
            Lobes::Conductor { ks, eta, k } => {
                return delta(ks * fresnel_conductor(lo.z, eta, k), 1.0);
            }
            Lobes::Glass { .. } | Lobes::ThinGlass { .. } | Lobes::RoughGlass(_) => return None,
        };
        Some(LocalSample::Smooth(li))
    }

    /// Non-delta part of `f` in the local frame, both directions above the surface (the
    /// rough dielectric, which scatters to both sides, is evaluated by the surface itself).
    pub(super) fn eval_local(&self, lo: Vec3, li: Vec3) -> Rgb {
        match *self {
            Lobes::Diffuse { kd } => kd * INV_PI,
            Lobes::Glossy {
                kd, ks, exponent, ..
            } => kd * INV_PI + blinn_eval(ks, exponent, lo, li),
            Lobes::RoughConductor { ks, eta, k, distr } => {
                let (h, c) = half_vector(lo, li);
                let d = distr.d(h);
                if d == 0.0 {
                    return Rgb::ZERO;
                }
                let g = distr.g1_front(lo) * distr.g1_front(li);
                ks * fresnel_conductor(c, eta, k) * (d * g / (4.0 * lo.z * li.z))
            }
            Lobes::Plastic { diffuse, eta, .. } => {
                let t =
                    (1.0 - fresnel_dielectric(lo.z, eta)) * (1.0 - fresnel_dielectric(li.z, eta));
                diffuse * (t * INV_PI)
            }
            Lobes::RoughPlastic {
                diffuse,
                ks,
                eta,
                distr,
                tables,
                ..
            } => {
                let (h, c) = half_vector(lo, li);
                let g = distr.g1_front(lo) * distr.g1_front(li);
                let spec = fresnel_dielectric(c, eta) * distr.d(h) * g / (4.0 * lo.z * li.z);
                let t = tables.transmittance(lo.z) * tables.transmittance(li.z);
                ks * spec + diffuse * (t * INV_PI)
            }
            // Both above: a reflection, the same in either mode.
            Lobes::Principled(p) => p.eval(lo, li, TransportMode::Radiance),
            Lobes::Mirror { .. }
            | Lobes::Glass { .. }
            | Lobes::Conductor { .. }
            | Lobes::ThinGlass { .. }
            | Lobes::RoughGlass(_) => Rgb::ZERO,
        }
    }

    /// Density of the non-delta samples in the local frame, both directions above the
    /// surface (the delta lobes' probability left out, so it does not integrate to 1 then).
    pub(super) fn pdf_local(&self, lo: Vec3, li: Vec3) -> f32 {
        match *self {
            Lobes::Diffuse { .. } => cosine_hemisphere_pdf(li.z),
            Lobes::Glossy {
                exponent, p_glossy, ..
            } => {
                (1.0 - p_glossy) * cosine_hemisphere_pdf(li.z)
                    + p_glossy * blinn_pdf(exponent, lo, li)
            }
            Lobes::RoughConductor { distr, .. } => {
                let (h, _) = half_vector(lo, li);
                distr.d(h) * distr.g1_sampled_front(lo) / (4.0 * lo.z)
            }
            Lobes::Plastic {
                eta, spec_weight, ..
            } => {
                let ps = specular_probability(fresnel_dielectric(lo.z, eta), spec_weight);
                (1.0 - ps) * cosine_hemisphere_pdf(li.z)
            }
            Lobes::RoughPlastic {
                spec_weight,
                distr,
                tables,
                ..
            } => {
                let ps = specular_probability(1.0 - tables.transmittance(lo.z), spec_weight);
                let (h, _) = half_vector(lo, li);
                let spec = distr.d(h) * distr.g1_sampled_front(lo) / (4.0 * lo.z);
                ps * spec + (1.0 - ps) * cosine_hemisphere_pdf(li.z)
            }
            Lobes::Principled(p) => p.pdf(lo, li),
            Lobes::Mirror { .. }
            | Lobes::Glass { .. }
            | Lobes::Conductor { .. }
            | Lobes::ThinGlass { .. }
            | Lobes::RoughGlass(_) => 0.0,
        }
    }
}

/// The half vector of two local directions above the surface and its cosine with either,
/// `|lo + li| / 2`: the same for both (exactly, so that `f` stays exactly reciprocal) and
/// positive, so the microfacet terms need no orientation test (`(v·h)(v·n) > 0` holds).
#[inline]
pub(super) fn half_vector(lo: Vec3, li: Vec3) -> (Vec3, f32) {
    let sum = lo + li;
    let len = sum.length();
    (sum / len, 0.5 * len)
}

/// Mirror of local `v` about `m`.
#[inline]
pub(super) fn reflect(v: Vec3, m: Vec3) -> Vec3 {
    2.0 * v.dot(m) * m - v
}
