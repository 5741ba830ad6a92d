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

use crate::material::{Material, MaterialKind};
use crate::math::{Frame, INV_PI, PI, Rgb, luminance, safe_sqrt};
use crate::sampling::{cosine_hemisphere_pdf, sample_cosine_hemisphere};
use glam::{Vec2, Vec3};

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
    /// True when `wi` came from a delta lobe (mirror, smooth glass).
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
}

/// A BSDF at one surface point: lobes, shading frame and geometric normal.
#[derive(Clone, Copy, Debug)]
pub struct Bsdf {
    pub lobes: Lobes,
    /// Shading frame; `z` is the shading normal on the side of `ng`.
    pub frame: Frame,
    /// Geometric normal, unit.
    pub ng: Vec3,
}

impl Lobes {
    /// Lobes of `material` with diffuse albedo `kd` (already textured).
    pub fn new(material: &Material, kd: Rgb) -> Self {
        match material.kind {
            MaterialKind::Diffuse => Lobes::Diffuse { kd },
            MaterialKind::Glossy => {
                let wd = luminance(kd);
                let wg = luminance(material.ks);
                let p_glossy = if wd + wg > 0.0 { wg / (wd + wg) } else { 0.5 };
                Lobes::Glossy {
                    kd,
                    ks: material.ks,
                    exponent: material.ns,
                    p_glossy,
                }
            }
            MaterialKind::Mirror => Lobes::Mirror { r: material.ks },
            MaterialKind::Glass => Lobes::Glass {
                eta: material.ni,
                tf_sqrt: Rgb::new(
                    material.tf.x.sqrt(),
                    material.tf.y.sqrt(),
                    material.tf.z.sqrt(),
                ),
            },
        }
    }

    /// True when every lobe is a delta distribution.
    pub fn is_delta(&self) -> bool {
        matches!(self, Lobes::Mirror { .. } | Lobes::Glass { .. })
    }
}

/// Fresnel reflectance of a smooth dielectric for unpolarised light; `cos_i` on the incident
/// side (positive), `eta` = η_t/η_i.
pub fn fresnel_dielectric(cos_i: f32, eta: f32) -> f32 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = safe_sqrt(1.0 - sin2_t);
    let r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    0.5 * (r_parl * r_parl + r_perp * r_perp)
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
    let phi = 2.0 * PI * u.y;
    let h = Vec3::new(sin_h * phi.cos(), sin_h * phi.sin(), cos_h);
    let wi = 2.0 * wo.dot(h) * h - wo;
    if wi.z <= 0.0 || wo.dot(h) <= 0.0 {
        return None;
    }
    Some(wi.normalize())
}

impl Bsdf {
    /// A BSDF with shading normal `ns` and geometric normal `ng` (both unit, same side).
    pub fn new(lobes: Lobes, ns: Vec3, ng: Vec3) -> Self {
        Bsdf {
            lobes,
            frame: Frame::from_z(ns),
            ng,
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

    /// Local directions with `wo` flipped to the upper side (surfaces are two-sided for
    /// reflection). Returns `None` when `wo` and `wi` are not both on the same geometric
    /// side (no reflection through a surface) or lie in the shading horizon.
    #[inline]
    fn reflection_local(&self, wo: Vec3, wi: Vec3) -> Option<(Vec3, Vec3)> {
        if wo.dot(self.ng) * wi.dot(self.ng) <= 0.0 {
            return None;
        }
        let mut lo = self.frame.to_local(wo);
        let mut li = self.frame.to_local(wi);
        if wo.dot(self.ng) < 0.0 {
            lo.z = -lo.z;
            li.z = -li.z;
        }
        if lo.z <= 0.0 || li.z <= 0.0 {
            return None;
        }
        Some((lo, li))
    }

    /// `f(wo, wi)`; zero for delta lobes.
    pub fn eval(&self, wo: Vec3, wi: Vec3, mode: TransportMode) -> Rgb {
        let f = match self.lobes {
            Lobes::Diffuse { kd } => match self.reflection_local(wo, wi) {
                Some(_) => kd * INV_PI,
                None => Rgb::ZERO,
            },
            Lobes::Glossy {
                kd, ks, exponent, ..
            } => match self.reflection_local(wo, wi) {
                Some((lo, li)) => kd * INV_PI + blinn_eval(ks, exponent, lo, li),
                None => Rgb::ZERO,
            },
            Lobes::Mirror { .. } | Lobes::Glass { .. } => Rgb::ZERO,
        };
        f * self.adjoint_correction(wo, wi, mode)
    }

    /// Density per steradian with which [`Bsdf::sample`] returns `wi`; zero for delta lobes.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        match self.lobes {
            Lobes::Diffuse { .. } => match self.reflection_local(wo, wi) {
                Some((_, li)) => cosine_hemisphere_pdf(li.z),
                None => 0.0,
            },
            Lobes::Glossy {
                exponent, p_glossy, ..
            } => match self.reflection_local(wo, wi) {
                Some((lo, li)) => {
                    (1.0 - p_glossy) * cosine_hemisphere_pdf(li.z)
                        + p_glossy * blinn_pdf(exponent, lo, li)
                }
                None => 0.0,
            },
            Lobes::Mirror { .. } | Lobes::Glass { .. } => 0.0,
        }
    }

    /// Samples `wi` given `wo`, with one number to choose a lobe and two for the direction.
    pub fn sample(
        &self,
        wo: Vec3,
        u_lobe: f32,
        u: Vec2,
        mode: TransportMode,
    ) -> Option<BsdfSample> {
        let ng_side = if wo.dot(self.ng) >= 0.0 { 1.0 } else { -1.0 };
        let mut lo = self.frame.to_local(wo);
        lo.z *= ng_side;
        if lo.z <= 0.0 {
            return None;
        }
        let to_world = |l: Vec3| self.frame.to_world(Vec3::new(l.x, l.y, l.z * ng_side));
        match self.lobes {
            Lobes::Diffuse { .. } | Lobes::Glossy { .. } => {
                let li = match self.lobes {
                    Lobes::Glossy {
                        exponent, p_glossy, ..
                    } if u_lobe < p_glossy => blinn_sample(exponent, lo, u)?,
                    _ => sample_cosine_hemisphere(u),
                };
                if li.z <= 0.0 {
                    return None;
                }
                let wi = to_world(li);
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
            Lobes::Mirror { r } => {
                let li = Vec3::new(-lo.x, -lo.y, lo.z);
                let wi = to_world(li);
                if wi.dot(self.ng) * wo.dot(self.ng) <= 0.0 {
                    return None;
                }
                let cos = li.z;
                let corr = self.adjoint_correction(wo, wi, mode);
                Some(BsdfSample {
                    wi,
                    f: r / cos * corr,
                    pdf_w: 1.0,
                    weight: r * corr,
                    delta: true,
                })
            }
            Lobes::Glass { eta, tf_sqrt } => {
                // Entering when wo is on the side the geometric normal points to.
                let entering = ng_side > 0.0;
                let eta_rel = if entering { eta } else { 1.0 / eta };
                let fr = fresnel_dielectric(lo.z, eta_rel);
                if u_lobe < fr {
                    let li = Vec3::new(-lo.x, -lo.y, lo.z);
                    let wi = to_world(li);
                    if wi.dot(self.ng) * wo.dot(self.ng) <= 0.0 {
                        return None;
                    }
                    let corr = self.adjoint_correction(wo, wi, mode);
                    Some(BsdfSample {
                        wi,
                        f: Rgb::splat(fr / li.z * corr),
                        pdf_w: fr,
                        weight: Rgb::splat(corr),
                        delta: true,
                    })
                } else {
                    // Refraction about the local normal (+z), incident direction -lo.
                    let cos_i = lo.z;
                    let sin2_t = (1.0 - cos_i * cos_i) / (eta_rel * eta_rel);
                    if sin2_t >= 1.0 {
                        return None; // fr = 1 here; unreachable in exact arithmetic
                    }
                    let cos_t = safe_sqrt(1.0 - sin2_t);
                    let li =
                        (-lo / eta_rel + Vec3::new(0.0, 0.0, cos_i / eta_rel - cos_t)).normalize();
                    let wi = to_world(li);
                    if wi.dot(self.ng) * wo.dot(self.ng) >= 0.0 {
                        return None;
                    }
                    let radiance_scale = if mode == TransportMode::Radiance {
                        1.0 / (eta_rel * eta_rel)
                    } else {
                        1.0
                    };
                    let corr = self.adjoint_correction(wo, wi, mode);
                    let t = 1.0 - fr;
                    let weight = tf_sqrt * (radiance_scale * corr);
                    Some(BsdfSample {
                        wi,
                        f: tf_sqrt * (t * radiance_scale * corr / li.z.abs()),
                        pdf_w: t,
                        weight,
                        delta: true,
                    })
                }
            }
        }
    }
}
