//! The normalised Blinn lobe (its formula: [`crate::bsdf`]) in the local frame, both
//! directions in the upper hemisphere.

use crate::math::{PI, Rgb, safe_sqrt};
use glam::{Vec2, Vec3};

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
pub(super) fn blinn_eval(ks: Rgb, n: f32, wo: Vec3, wi: Vec3) -> Rgb {
    let h = (wo + wi).normalize_or_zero();
    let h_wi = h.dot(wi);
    if h.z <= 0.0 || h_wi <= 0.0 {
        return Rgb::ZERO;
    }
    let d = (n + 1.0) * blinn_cos_pow(h, n);
    ks * (d / (8.0 * PI * h_wi * wo.z.max(wi.z)))
}

#[inline]
pub(super) fn blinn_pdf(n: f32, wo: Vec3, wi: Vec3) -> f32 {
    let h = (wo + wi).normalize_or_zero();
    let h_wo = h.dot(wo);
    if h.z <= 0.0 || h_wo <= 0.0 {
        return 0.0;
    }
    (n + 1.0) * blinn_cos_pow(h, n) / (2.0 * PI * 4.0 * h_wo)
}

#[inline]
pub(super) fn blinn_sample(n: f32, wo: Vec3, u: Vec2) -> Option<Vec3> {
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
