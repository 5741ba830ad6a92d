//! BSDFs at a surface point, evaluated in the local shading frame.
//!
//! Conventions (as pbrt-v4): `wo` points from the surface toward where the path came from
//! (the camera side in radiance mode, the light side in importance mode), `wi` is the other
//! direction, the one being sampled. `eval` returns `f(wo, wi)` without any cosine; the
//! estimator multiplies by `|wi · n_s|`. Every call takes a [`TransportMode`]:
//!
//! * refraction scales radiance by `1/η²` but not importance (Veach 1997, §5.2);
//! * shading normals make the BSDF non-symmetric; in importance mode the adjoint BSDF carries
//!   the correction `|wo·n_s| |wi·n_g| / (|wo·n_g| |wi·n_s|)` (Veach 1997, eq. 5.19).
//!
//! Lobes: Lambertian; a normalised Blinn lobe layered over it; a perfect mirror; a smooth
//! dielectric with coloured transmittance. The Blinn lobe is
//! `f = k_s (n+1)/(8π) · cos^n θ_h / ((h·wi) · max(cos θ_i, cos θ_o))`
//! (Ashikhmin & Shirley 2000 without the Fresnel factor): reciprocal, its albedo is at most
//! `k_s` for every exponent, and sampling the half vector with density
//! `(n+1)/(2π) cos^n θ_h` gives a sample weight of at most `k_s`.
//!
//! The Mitsuba 3 kinds evaluate to what Mitsuba's plugins of the same names evaluate to
//! (`eval` there includes the cosine, here it does not):
//!
//! * `conductor`: a mirror of weight `k_s F_c(cos θ)`, `F_c` the conductor Fresnel term of
//!   `η + i k` ([`crate::bsdf::fresnel`]);
//! * `roughconductor`: `k_s F_c(wo·h) D(h) G(wo, wi) / (4 cos θ_o cos θ_i)` with the
//!   distributions of [`crate::bsdf::microfacet`], sampled by visible normals;
//! * `plastic`: a mirror of weight `k_s F(cos θ_o)` over a Lambertian base seen through the
//!   interface, `f = k_d' (1 - F(cos θ_o)) (1 - F(cos θ_i)) / (π η²)` with
//!   `k_d' = k_d / (1 - F_dr)` (`k_d / (1 - k_d F_dr)` when `nonlinear`), `F_dr` the diffuse
//!   reflectance of the interface seen from inside; the lobe is chosen with probability
//!   ∝ `F w_s` for the mirror and `(1 - F)(1 - w_s)` for the base, `w_s` = mean(k_s) /
//!   (mean(k_d) + mean(k_s));
//! * `roughplastic`: the microfacet reflection of a dielectric, `k_s F(wo·h) D G / (4 cos
//!   cos)`, plus the base `k_d' t(cos θ_o) t(cos θ_i) / (π η²)`, `t` the coating's tabled
//!   transmittance and `k_d'` divided by its tabled internal reflectance
//!   ([`crate::bsdf::rough_plastic`]); lobe probabilities as plastic with `1 - t` for `F`;
//! * `thindielectric`: reflection `R' = 2R/(1 + R)` (the sheet's inner reflections summed),
//!   straight transmission `1 - R'` (`wi = -wo`), with `k_s` and `T_f` as factors and no
//!   `1/η²` (the ray leaves into the medium it came from).
//!
//! Sidedness: two-sided surfaces reflect on whichever side `wo` is (the frame is flipped to
//! it); a one-sided surface (Mitsuba's BSDFs unless wrapped in `twosided`) is black unless
//! both directions are above the shading normal, as Mitsuba evaluates it. Glass and thin
//! glass scatter on both sides regardless.

pub mod fresnel;
pub mod material;
pub mod microfacet;
pub mod rough_plastic;

use crate::bsdf::fresnel::fresnel_diffuse_reflectance;
use crate::bsdf::material::{Material, MaterialKind};
use crate::bsdf::microfacet::MicrofacetDistribution;
use crate::bsdf::rough_plastic::RoughPlasticTables;
use crate::math::{Frame, INV_PI, PI, Rgb, luminance, safe_sqrt};
use crate::rng::Rng;
use crate::sampling::{cosine_hemisphere_pdf, sample_cosine_hemisphere};
use crate::scene::features::{Features, General};
use glam::{Vec2, Vec3};

pub use crate::bsdf::fresnel::{fresnel_conductor, fresnel_dielectric};

/// Which quantity a path carries: radiance (paths from the camera) or importance (paths
/// from the lights).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TransportMode {
    Radiance,
    Importance,
}

/// A sampled direction.
#[derive(Clone, Copy, Debug)]
pub struct BsdfSample {
    /// Sampled direction, world space, unit.
    pub wi: Vec3,
    /// `f(wo, wi)` (for a delta lobe, the delta's coefficient).
    pub f: Rgb,
    /// Density per steradian of `wi` (for a delta lobe, the discrete probability of the lobe).
    pub pdf_w: f32,
    /// `f · |wi·n_s| / pdf_w`, including the importance-mode shading-normal correction.
    pub weight: Rgb,
    /// True when `wi` came from a delta lobe (mirror, smooth glass, the coat of smooth
    /// plastic): a BSDF may mix delta and non-delta lobes, so this is per sample.
    pub delta: bool,
}

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
    /// Smooth plastic of IOR `eta`; `diffuse` is `k_d' / η²` (see the module doc) and
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
    /// Thin dielectric sheet of IOR `eta`: reflectance factor `ks`, transmittance `tf`.
    ThinGlass {
        eta: f32,
        ks: Rgb,
        tf: Rgb,
    },
}

/// Lobes and the sidedness of the surface: what a material resolves to at a point. A bare
/// [`Lobes`] converts into a two-sided one.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceLobes {
    pub lobes: Lobes,
    /// False: reflection only above the shading normal (see the module doc).
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

/// A BSDF at one surface point: lobes, shading frame and geometric normal.
#[derive(Clone, Copy, Debug)]
pub struct Bsdf {
    pub lobes: Lobes,
    /// Shading frame; `z` is the shading normal on the side of `ng`.
    pub frame: Frame,
    /// Geometric normal, unit.
    pub ng: Vec3,
    /// False: the reflecting kinds are black seen from below the shading normal.
    pub two_sided: bool,
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
fn specular_probability(fs: f32, spec_weight: f32) -> f32 {
    let ps = fs * spec_weight;
    let pd = (1.0 - fs) * (1.0 - spec_weight);
    if ps + pd > 0.0 { ps / (ps + pd) } else { 0.0 }
}

impl Lobes {
    /// Lobes of `material` with diffuse albedo `kd` and specular reflectance `ks` (both
    /// already textured), with the material's sidedness.
    #[allow(clippy::new_ret_no_self)]
    pub fn new(material: &Material, kd: Rgb, ks: Rgb) -> SurfaceLobes {
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
                distr: MicrofacetDistribution::new(material.microfacet, material.alpha),
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
        };
        SurfaceLobes {
            lobes,
            two_sided: material.two_sided,
        }
    }

    /// True when every lobe is a delta distribution (smooth plastic is not: its base is
    /// diffuse; [`BsdfSample::delta`] tells which lobe a sample came from).
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
        }
    }

    /// True for the kinds whose sampling reads a number to choose a lobe (or reflection
    /// against refraction); the others (one lobe: Lambertian, a mirror, a conductor) read
    /// none, and their vertices spend no dimension of the sequence on it.
    fn chooses_a_lobe(&self) -> bool {
        matches!(
            self,
            Lobes::Glossy { .. }
                | Lobes::Plastic { .. }
                | Lobes::RoughPlastic { .. }
                | Lobes::ThinGlass { .. }
                | Lobes::Glass { .. }
        )
    }

    /// True for the kinds that scatter through the surface (they ignore sidedness).
    fn transmits(&self) -> bool {
        matches!(self, Lobes::Glass { .. } | Lobes::ThinGlass { .. })
    }

    /// Non-delta part of `f` in the local frame, both directions above the surface.
    fn eval_local(&self, lo: Vec3, li: Vec3) -> Rgb {
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
            Lobes::Mirror { .. }
            | Lobes::Glass { .. }
            | Lobes::Conductor { .. }
            | Lobes::ThinGlass { .. } => Rgb::ZERO,
        }
    }

    /// Density of the non-delta samples in the local frame, both directions above the
    /// surface (the delta lobes' probability left out, so it does not integrate to 1 then).
    fn pdf_local(&self, lo: Vec3, li: Vec3) -> f32 {
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
            Lobes::Mirror { .. }
            | Lobes::Glass { .. }
            | Lobes::Conductor { .. }
            | Lobes::ThinGlass { .. } => 0.0,
        }
    }
}

// ---- Blinn lobe, local frame, both directions in the upper hemisphere ----

/// `cos^n θ_h` of the unit half vector `h`, accurate for large `n`: computed as
/// `exp(n · ln(1 - (1 - cos θ_h)))` with `1 - cos θ_h = sin²θ_h / (1 + cos θ_h)`, which
/// does not cancel near the normal (an exponent of 10⁴ needs it).
#[inline]
fn blinn_cos_pow(h: Vec3, n: f32) -> f32 {
    let sin2 = h.x * h.x + h.y * h.y;
    let one_minus_cos = sin2 / (1.0 + h.z);
    (n * (-one_minus_cos).ln_1p()).exp()
}

#[inline]
fn blinn_eval(ks: Rgb, n: f32, wo: Vec3, wi: Vec3) -> Rgb {
    let h = (wo + wi).normalize_or_zero();
    let h_wi = h.dot(wi);
    if h.z <= 0.0 || h_wi <= 0.0 {
        return Rgb::ZERO;
    }
    let d = (n + 1.0) * blinn_cos_pow(h, n);
    ks * (d / (8.0 * PI * h_wi * wo.z.max(wi.z)))
}

#[inline]
fn blinn_pdf(n: f32, wo: Vec3, wi: Vec3) -> f32 {
    let h = (wo + wi).normalize_or_zero();
    let h_wo = h.dot(wo);
    if h.z <= 0.0 || h_wo <= 0.0 {
        return 0.0;
    }
    (n + 1.0) * blinn_cos_pow(h, n) / (2.0 * PI * 4.0 * h_wo)
}

#[inline]
fn blinn_sample(n: f32, wo: Vec3, u: Vec2) -> Option<Vec3> {
    // cos θ_h = u^(1/(n+1)); 1 - cos θ_h by expm1 so that small angles keep their precision.
    let one_minus_cos = -(u.x.max(f32::MIN_POSITIVE).ln() / (n + 1.0)).exp_m1();
    let cos_h = 1.0 - one_minus_cos;
    let sin_h = safe_sqrt(one_minus_cos * (2.0 - one_minus_cos));
    let (sin_phi, cos_phi) = crate::math::sin_cos_turns(u.y);
    let h = Vec3::new(sin_h * cos_phi, sin_h * sin_phi, cos_h);
    let wi = 2.0 * wo.dot(h) * h - wo;
    if wi.z <= 0.0 || wo.dot(h) <= 0.0 {
        return None;
    }
    Some(wi.normalize())
}

/// The half vector of two local directions above the surface and its cosine with either,
/// `|lo + li| / 2`: the same for both (exactly, so that `f` stays exactly reciprocal) and
/// positive, so the microfacet terms need no orientation test (`(v·h)(v·n) > 0` holds).
#[inline]
fn half_vector(lo: Vec3, li: Vec3) -> (Vec3, f32) {
    let sum = lo + li;
    let len = sum.length();
    (sum / len, 0.5 * len)
}

/// Mirror of local `v` about `m`.
#[inline]
fn reflect(v: Vec3, m: Vec3) -> Vec3 {
    2.0 * v.dot(m) * m - v
}

impl Bsdf {
    /// A BSDF with shading normal `ns` and geometric normal `ng` (both unit, same side);
    /// `lobes` is a [`SurfaceLobes`] or a bare (two-sided) [`Lobes`].
    pub fn new(lobes: impl Into<SurfaceLobes>, ns: Vec3, ng: Vec3) -> Self {
        let SurfaceLobes { lobes, two_sided } = lobes.into();
        Bsdf {
            lobes,
            frame: Frame::from_z(ns),
            ng,
            two_sided,
        }
    }

    pub fn is_delta(&self) -> bool {
        self.lobes.is_delta()
    }

    /// `|wo·n_s| |wi·n_g| / (|wo·n_g| |wi·n_s|)` in importance mode, 1 in radiance mode.
    #[inline]
    fn adjoint_correction(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> f32 {
        if mode == TransportMode::Radiance {
            return 1.0;
        }
        let ns = self.frame.z;
        let num = wo.dot(ns).abs() * wi.dot(self.ng).abs();
        let den = wo.dot(self.ng).abs() * wi.dot(ns).abs();
        if den <= 0.0 || !num.is_finite() {
            return 0.0;
        }
        num / den
    }

    /// [`Bsdf::adjoint_correction`] compiled for the effects `F`. Without shading normals the
    /// frame's normal is the geometric one (bit for bit: `surface_hit_with` and the emission
    /// lobe pass `ng` as `ns`), so the general form's numerator and denominator are the same
    /// product `|wo·n_g| |wi·n_g|`, and its quotient is exactly 1 wherever it divides: the
    /// same value, without two of the four dot products and the division.
    #[inline]
    fn adjoint_correction_with<F: Features>(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> f32 {
        if F::SHADING_NORMALS {
            return self.adjoint_correction(wo, wi, mode);
        }
        if mode == TransportMode::Radiance {
            return 1.0;
        }
        debug_assert!(
            self.frame.z.to_array().map(f32::to_bits) == self.ng.to_array().map(f32::to_bits),
            "a shading normal in a loop compiled without them"
        );
        let den = wo.dot(self.ng).abs() * wi.dot(self.ng).abs();
        if den > 0.0 && den.is_finite() {
            1.0
        } else {
            0.0
        }
    }

    /// The side the reflecting kinds work on for `wo`: -1 when a two-sided surface is seen
    /// from below its geometric normal (the local frame is flipped), else 1.
    #[inline]
    fn reflection_side(&self, wo: Vec3) -> f32 {
        if self.two_sided && wo.dot(self.ng) < 0.0 {
            -1.0
        } else {
            1.0
        }
    }

    /// Local directions of a reflection, flipped to the upper side on two-sided surfaces.
    /// Returns `None` when `wo` and `wi` are not both on the same geometric side (no
    /// reflection through a surface) or not both above the (flipped) shading horizon.
    #[inline]
    fn reflection_local(&self, wo: Vec3, wi: Vec3) -> Option<(Vec3, Vec3)> {
        if wo.dot(self.ng) * wi.dot(self.ng) <= 0.0 {
            return None;
        }
        let side = self.reflection_side(wo);
        let mut lo = self.frame.to_local(wo);
        let mut li = self.frame.to_local(wi);
        lo.z *= side;
        li.z *= side;
        if lo.z <= 0.0 || li.z <= 0.0 {
            return None;
        }
        Some((lo, li))
    }

    /// The numbers [`Bsdf::sample`] reads, drawn from `rng` in a fixed order: the direction's
    /// pair first, then the lobe's number only where the BSDF has a choice of lobes (0
    /// otherwise, unread). A Lambertian vertex thus draws two numbers, and its direction keeps
    /// the same dimensions of the sequence whatever the other vertices' materials.
    #[inline]
    pub fn draw_numbers(&self, rng: &mut Rng) -> (f32, Vec2) {
        let u = rng.uniform2();
        let u_lobe = if self.lobes.chooses_a_lobe() {
            rng.uniform()
        } else {
            0.0
        };
        (u_lobe, u)
    }

    /// True when every lobe is a delta distribution, compiled for the effects `F` (false
    /// without specular surfaces).
    #[inline]
    pub fn is_delta_with<F: Features>(&self) -> bool {
        F::SPECULAR && self.lobes.is_delta()
    }

    /// The Lambertian fast path's cosines: `(lo.z, li.z)` of [`Bsdf::reflection_local`],
    /// each the same dot product the frame transform makes, without the tangential parts
    /// the Lambertian lobe does not read.
    #[inline]
    fn lambert_cosines(&self, wo: Vec3, wi: Vec3) -> Option<(f32, f32)> {
        if wo.dot(self.ng) * wi.dot(self.ng) <= 0.0 {
            return None;
        }
        let side = self.reflection_side(wo);
        let (lo, li) = (wo.dot(self.frame.z) * side, wi.dot(self.frame.z) * side);
        if lo <= 0.0 || li <= 0.0 {
            return None;
        }
        Some((lo, li))
    }

    /// `f(wo, wi)`; zero for delta lobes.
    pub fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> Rgb {
        self.eval_with::<General>(wo, wi, mode)
    }

    /// [`Bsdf::eval`] compiled for the effects `F`.
    #[inline]
    pub fn eval_with<F: Features>(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> Rgb {
        if F::LAMBERTIAN {
            if let Lobes::Diffuse { kd } = self.lobes {
                return match self.lambert_cosines(wo, wi) {
                    Some(_) => kd * INV_PI * self.adjoint_correction_with::<F>(wo, wi, mode),
                    None => Rgb::ZERO,
                };
            }
        }
        if self.is_delta_with::<F>() {
            return Rgb::ZERO;
        }
        let f = match self.reflection_local(wo, wi) {
            Some((lo, li)) => self.lobes.eval_local(lo, li),
            None => return Rgb::ZERO,
        };
        f * self.adjoint_correction_with::<F>(wo, wi, mode)
    }

    /// `f(wo, wi)` ([`Bsdf::eval_with`]) and, where it comes at no extra cost, the density
    /// [`Bsdf::pdf_with`] of `wi`: the Lambertian fast path reads both from one set of
    /// cosines (the very values the two calls compute); elsewhere the density is left to be
    /// computed where it is needed (`None`). Always inlined: without the fast path it is
    /// [`Bsdf::eval_with`] itself.
    #[inline(always)]
    pub fn eval_and_lambert_pdf_with<F: Features>(
        &self,
        wo: Vec3,
        wi: Vec3,
        mode: TransportMode,
    ) -> (Rgb, Option<f32>) {
        if F::LAMBERTIAN {
            if let Lobes::Diffuse { kd } = self.lobes {
                return match self.lambert_cosines(wo, wi) {
                    Some((_, li)) => (
                        kd * INV_PI * self.adjoint_correction_with::<F>(wo, wi, mode),
                        Some(cosine_hemisphere_pdf(li)),
                    ),
                    None => (Rgb::ZERO, Some(0.0)),
                };
            }
        }
        (self.eval_with::<F>(wo, wi, mode), None)
    }

    /// Density per steradian with which [`Bsdf::sample`] returns `wi` from its non-delta
    /// lobes (times their probability); zero for delta lobes.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.pdf_with::<General>(wo, wi)
    }

    /// [`Bsdf::pdf`] compiled for the effects `F`.
    #[inline]
    pub fn pdf_with<F: Features>(&self, wo: Vec3, wi: Vec3) -> f32 {
        if F::LAMBERTIAN {
            if let Lobes::Diffuse { .. } = self.lobes {
                return match self.lambert_cosines(wo, wi) {
                    Some((_, li)) => cosine_hemisphere_pdf(li),
                    None => 0.0,
                };
            }
        }
        if self.is_delta_with::<F>() {
            return 0.0;
        }
        match self.reflection_local(wo, wi) {
            Some((lo, li)) => self.lobes.pdf_local(lo, li),
            None => 0.0,
        }
    }

    /// A delta sample in local direction `li` (already flipped by `side`) of coefficient
    /// `weight` (`f · cos / prob`) and discrete probability `prob`.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    fn delta_sample(
        &self,
        wo: Vec3,
        li: Vec3,
        side: f32,
        weight: Rgb,
        prob: f32,
        mode: TransportMode,
        transmitted: bool,
    ) -> Option<BsdfSample> {
        let wi = self.frame.to_world(Vec3::new(li.x, li.y, li.z * side));
        let crosses = wi.dot(self.ng) * wo.dot(self.ng);
        if (transmitted && crosses >= 0.0) || (!transmitted && crosses <= 0.0) {
            return None;
        }
        let corr = self.adjoint_correction(wo, wi, mode);
        Some(BsdfSample {
            wi,
            f: weight * (prob * corr / li.z.abs()),
            pdf_w: prob,
            weight: weight * corr,
            delta: true,
        })
    }

    /// Samples `wi` given `wo`, with one number to choose a lobe and two for the direction.
    pub fn sample(
        &self,
        wo: Vec3,
        u_lobe: f32,
        u: Vec2,
        mode: TransportMode,
    ) -> Option<BsdfSample> {
        self.sample_with::<General>(wo, u_lobe, u, mode)
    }

    /// [`Bsdf::sample`] compiled for the effects `F`: the Lambertian fast path evaluates
    /// `f` and the pdf from one set of cosines (the same operations as the general path).
    #[inline]
    pub fn sample_with<F: Features>(
        &self,
        wo: Vec3,
        u_lobe: f32,
        u: Vec2,
        mode: TransportMode,
    ) -> Option<BsdfSample> {
        if F::LAMBERTIAN {
            if let Lobes::Diffuse { kd } = self.lobes {
                let side = self.reflection_side(wo);
                if wo.dot(self.frame.z) * side <= 0.0 {
                    return None;
                }
                let li = sample_cosine_hemisphere(u);
                if li.z <= 0.0 {
                    return None;
                }
                let wi = self.frame.to_world(Vec3::new(li.x, li.y, li.z * side));
                let (_, cos_i) = self.lambert_cosines(wo, wi)?;
                let pdf_w = cosine_hemisphere_pdf(cos_i);
                let f = kd * INV_PI * self.adjoint_correction_with::<F>(wo, wi, mode);
                if pdf_w <= 0.0 || !pdf_w.is_finite() || f.max_element() <= 0.0 {
                    return None;
                }
                let weight = f * (wi.dot(self.frame.z).abs() / pdf_w);
                return Some(BsdfSample {
                    wi,
                    f,
                    pdf_w,
                    weight,
                    delta: false,
                });
            }
        }
        self.sample_general(wo, u_lobe, u, mode)
    }

    fn sample_general(
        &self,
        wo: Vec3,
        u_lobe: f32,
        u: Vec2,
        mode: TransportMode,
    ) -> Option<BsdfSample> {
        // The frame is flipped to wo's side for the transmitting kinds and for two-sided
        // reflection; a one-sided surface seen from below scatters nothing.
        let side = if self.lobes.transmits() {
            if wo.dot(self.ng) >= 0.0 { 1.0 } else { -1.0 }
        } else {
            self.reflection_side(wo)
        };
        let mut lo = self.frame.to_local(wo);
        lo.z *= side;
        if lo.z <= 0.0 {
            return None;
        }
        let mirror = Vec3::new(-lo.x, -lo.y, lo.z);
        let li = match self.lobes {
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
            Lobes::Plastic {
                ks,
                eta,
                spec_weight,
                ..
            } => {
                let fi = fresnel_dielectric(lo.z, eta);
                let ps = specular_probability(fi, spec_weight);
                if u_lobe < ps {
                    return self.delta_sample(wo, mirror, side, ks * (fi / ps), ps, mode, false);
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
            Lobes::Mirror { r } => return self.delta_sample(wo, mirror, side, r, 1.0, mode, false),
            Lobes::Conductor { ks, eta, k } => {
                let w = ks * fresnel_conductor(lo.z, eta, k);
                return self.delta_sample(wo, mirror, side, w, 1.0, mode, false);
            }
            Lobes::ThinGlass { eta, ks, tf } => {
                // Reflectance with the sheet's inner reflections summed: R + T²R/(1 - R²).
                let r = fresnel_dielectric(lo.z, eta);
                let r = if r < 1.0 { 2.0 * r / (1.0 + r) } else { 1.0 };
                return if u_lobe < r {
                    self.delta_sample(wo, mirror, side, ks, r, mode, false)
                } else {
                    self.delta_sample(wo, -lo, side, tf, 1.0 - r, mode, true)
                };
            }
            Lobes::Glass { eta, tf_sqrt } => {
                return self.sample_glass(wo, lo, side, eta, tf_sqrt, u_lobe, mode);
            }
        };
        if li.z <= 0.0 {
            return None;
        }
        let wi = self.frame.to_world(Vec3::new(li.x, li.y, li.z * side));
        let pdf_w = self.pdf(wo, wi);
        let f = self.eval(wo, wi, mode);
        if pdf_w <= 0.0 || !pdf_w.is_finite() || f.max_element() <= 0.0 {
            return None;
        }
        let weight = f * (wi.dot(self.frame.z).abs() / pdf_w);
        Some(BsdfSample {
            wi,
            f,
            pdf_w,
            weight,
            delta: false,
        })
    }

    /// The smooth dielectric: Fresnel reflection or refraction, `lo` on the incident side.
    #[allow(clippy::too_many_arguments)]
    fn sample_glass(
        &self,
        wo: Vec3,
        lo: Vec3,
        side: f32,
        eta: f32,
        tf_sqrt: Rgb,
        u_lobe: f32,
        mode: TransportMode,
    ) -> Option<BsdfSample> {
        // Entering when wo is on the side the geometric normal points to.
        let entering = side > 0.0;
        let eta_rel = if entering { eta } else { 1.0 / eta };
        let fr = fresnel_dielectric(lo.z, eta_rel);
        if u_lobe < fr {
            let li = Vec3::new(-lo.x, -lo.y, lo.z);
            return self.delta_sample(wo, li, side, Rgb::ONE, fr, mode, false);
        }
        // Refraction about the local normal (+z), incident direction -lo.
        let cos_i = lo.z;
        let sin2_t = (1.0 - cos_i * cos_i) / (eta_rel * eta_rel);
        if sin2_t >= 1.0 {
            return None; // fr = 1 here; unreachable in exact arithmetic
        }
        let cos_t = safe_sqrt(1.0 - sin2_t);
        let li = (-lo / eta_rel + Vec3::new(0.0, 0.0, cos_i / eta_rel - cos_t)).normalize();
        let radiance_scale = if mode == TransportMode::Radiance {
            1.0 / (eta_rel * eta_rel)
        } else {
            1.0
        };
        self.delta_sample(wo, li, side, tf_sqrt * radiance_scale, 1.0 - fr, mode, true)
    }
}
