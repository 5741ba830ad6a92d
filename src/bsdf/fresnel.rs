//! Fresnel reflectance of smooth interfaces, unpolarised: between two dielectrics, at a
//! conductor (complex index of refraction), and averaged over diffuse illumination.
//!
//! The conductor term is the exact unpolarised reflectance of an absorbing medium of relative
//! index `η + i k` (Born & Wolf, "Principles of Optics", §14.2; in the closed form of
//! K. D. Möller, "Optics", 1988, as Mitsuba 3's `fresnel_conductor` also uses). The diffuse
//! reflectance uses the two polynomial fits Mitsuba 3's `fresnel_diffuse_reflectance` picks:
//! Egan & Hilgeman (1973) for η < 1 and d'Eon & Irving (2011) for η >= 1.

use crate::Rgb;
use crate::math::safe_sqrt;

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

/// Fresnel reflectance of a conductor of relative complex index `eta + i k` for unpolarised
/// light arriving from outside at `cos_i` (clamped to [0, 1]); one channel.
pub fn fresnel_conductor_1(cos_i: f32, eta: f32, k: f32) -> f32 {
    let c = cos_i.clamp(0.0, 1.0);
    let c2 = c * c;
    let s2 = 1.0 - c2;
    let s4 = s2 * s2;
    // (a + i b)² = (η + i k)² - sin²θ; a²+b² and a are what the reflectances need.
    let re = eta * eta - k * k - s2;
    let a2_b2 = safe_sqrt(re * re + 4.0 * eta * eta * k * k);
    let a = safe_sqrt(0.5 * (a2_b2 + re));
    let t1 = a2_b2 + c2;
    let t2 = 2.0 * a * c;
    let r_s = (t1 - t2) / (t1 + t2);
    let t3 = a2_b2 * c2 + s4;
    let t4 = t2 * s2;
    let r_p = r_s * (t3 - t4) / (t3 + t4);
    0.5 * (r_s + r_p)
}

/// [`fresnel_conductor_1`] per channel.
pub fn fresnel_conductor(cos_i: f32, eta: Rgb, k: Rgb) -> Rgb {
    Rgb::new(
        fresnel_conductor_1(cos_i, eta.x, k.x),
        fresnel_conductor_1(cos_i, eta.y, k.y),
        fresnel_conductor_1(cos_i, eta.z, k.z),
    )
}

/// Fraction of uniformly diffuse illumination a smooth dielectric interface of relative
/// index `eta` reflects (polynomial fits, see the module doc; Mitsuba 3's choice).
pub fn fresnel_diffuse_reflectance(eta: f32) -> f32 {
    let inv = 1.0 / eta;
    if eta < 1.0 {
        // Egan & Hilgeman (1973).
        0.0636 * inv + eta * (eta * -1.4399 + 0.7099) + 0.6681
    } else {
        // d'Eon & Irving (2011), a polynomial in 1/η.
        let c = [0.919317f32, -3.4793, 6.75335, -7.80989, 4.98554, -1.36881];
        c.iter().rev().fold(0.0, |acc, &ci| acc * inv + ci)
    }
}
